//! A CANopen node on a SocketCAN interface: a CiA 401-style I/O module (`examples/common/io_module.rs`).
//!
//! ```text
//! cargo run --example node                                   # node 5 on vcan0, tokio runner
//! cargo run --example node -- --iface vcan0 --node-id 5 --heartbeat 1000
//! cargo run --example node -- --blocking                     # the blocking runner instead of tokio
//! cargo run --example node -- --eds io_module.eds            # write the node's EDS and exit
//! cargo run --example node -- --store /var/tmp/node5         # 1010h/1011h in /var/tmp/node5.a and .b
//! cargo run --example node -- --node-id 255 --store /tmp/n   # wait for an LSS master, keep what it stores
//! cargo run --example node -- --program /tmp/image.bin       # 1F50h downloads go to /tmp/image.bin
//! cargo run --example node --features pdo-mapping-64         # PDO mappings of up to 64 entries, not 8
//! cargo run --example node -- --help
//! ```
//!
//! It prints what happens, candump-like: every frame received and sent (unless `--quiet`), NMT state
//! changes, SDO writes with the new value, aborts, and what the adapter saw (error frames, bus-off, the
//! interface going down and coming back). Where there is no SocketCAN interface it says so in one line, with
//! the commands that create a virtual one.
//!
//! The inputs 2006h (uptime in ms), 6000h (a walking bit, once a second) and 6401h (analogue waves) are
//! sampled when someone needs them, never on a tick: before the node serves an SDO upload of one of them,
//! and, while
//! the node is Operational, by another task (tokio) or thread (`--blocking`) that sleeps until the walking
//! bit changes. The node lives in a `MutexShared` cell; the task changes it under the lock, calls
//! `trigger_changed_tpdos` (the event-driven TPDO1 and TPDO2 go out when their inputs changed, spaced by
//! their inhibit time) and signals the runner (`NotifyWake`, `BusWaker`) so it sends them at once. Idle in
//! Pre-operational with the heartbeat off, the process makes no system call at all. RPDO1/RPDO2 write the
//! outputs 6200h/6411h.
//!
//! **NMT reset node on Linux**: the node resets *in-process*. The core sends the boot-up frame, sets the
//! application values back to their `default =` values and the communication parameters to their power-on
//! values, then loads what 1010h stored. The process, its socket and 2006h uptime continue (the uptime
//! reads 0 until the inputs are sampled again). A master sees the boot-up either way; restarting the process would
//! lose the socket and make a supervisor part of the protocol for no gain.
//!
//! **Store/restore**: with `--store FILE` the parameters go to `FILE.a`/`FILE.b`
//! (`canopen_socketcan::FileStorage`): 1010h:01..03 = "save" writes them, they are loaded at start-up and
//! at every reset; 1011h:01..03 = "load" brings the defaults back at the next reset (or restart). Without
//! `--store`, 1010h/1011h answer 0606 0000h.
//!
//! **LSS (CiA 305)**: the node answers an LSS master (fastscan, configure node-ID, ...). With `--store FILE`,
//! "store configuration" keeps the node-ID and bit rate in `FILE.lss.a` (the same [`FileStorage`] scheme),
//! and at power-on a stored node-ID wins over `--node-id`, which is only the factory default.
//!
//! **The store is checked at start** (`examples/common/store_file.rs`): a path that cannot be created or
//! written ends the program before the node starts (the path and the OS error, exit code 2); a file that
//! fails its format or CRC check is reported, moved aside to `<file>.bad`, and the node starts on defaults.
//!
//! **Program download (CiA 302-3)**: with `--program FILE` a download of 1F50h:01 (segmented or block) is
//! written to `FILE.part` as it arrives and renamed to `FILE` when it completes; the node then prints the
//! image's length and CRC-32 (the `zlib.crc32` of the file), which 1F56h:01 also reads. 1F51h:01 is the
//! program control (00h stop, 01h start, 02h reset, 03h clear; the node only records the state), 1F57h:01
//! the flash status. Without `--program` a download is refused with 0800 0020h.
//!
//! **Error injection**: writing a non-zero code to 2100h raises it (1001h, 1003h and an EMCY frame); writing
//! another code clears the old one first, 0 clears it.

#[path = "common/io_module.rs"]
mod io_module;
#[path = "common/store_file.rs"]
mod store_file;

use std::process::ExitCode;
use std::sync::Arc;
use std::time::{Duration, Instant as StdInstant};

use canopen_core::lss::LssEvent;
use canopen_core::od::ObjectDictionary;
use canopen_core::{Event, NmtState, NodeId};
use canopen_socketcan::{
    run_blocking, run_tokio, BlockingBus, Clock, FileStorage, MutexShared, NotifyWake, Observed, TimerFd,
};
use clap::Parser;
use io_module::{IoNode, Store, CONFIG};

/// A CiA 301 CANopen node (a CiA 401-style I/O module) on SocketCAN: serves SDO, PDO, SYNC, EMCY,
/// heartbeat and LSS to any master on the bus, e.g. python canopen or `cargo run -p canopenctl -- read 5 0x1008 0`.
#[derive(Parser, Debug)]
#[command(
    version,
    after_help = "Example: cargo run --example node -- --iface vcan0 --node-id 5 --store state.bin\n\
                  (create vcan0 first: sudo modprobe vcan && sudo ip link add dev vcan0 type vcan && sudo ip link set up vcan0)"
)]
struct Args {
    /// SocketCAN interface.
    #[arg(long, default_value = "vcan0")]
    iface: String,
    /// Node-ID, 1..=127, or 255 to start without one and wait for an LSS master (CiA 305). This is the
    /// factory default: a node-ID an LSS master stored in `--store` wins at power-on (CiA 305).
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u8).range(1..=255))]
    node_id: u8,
    /// Serial number (1018h:04, the last part of the LSS address), decimal or 0x-hex.
    #[arg(long, default_value = "1", value_parser = parse_u32)]
    serial: u32,
    /// Producer heartbeat time 1017h in ms (0 = off).
    #[arg(long, default_value_t = 1000)]
    heartbeat: u16,
    /// SDO server time-out in ms (SDO-31): a transfer whose client is silent this long is aborted with
    /// 0504 0000h.
    #[arg(long, default_value_t = 1000)]
    sdo_timeout: u64,
    /// Stop after this many seconds (default: run until killed).
    #[arg(long)]
    run_for: Option<f64>,
    /// Write the node's EDS (CiA 306) to FILE and exit.
    #[arg(long, value_name = "FILE")]
    eds: Option<String>,
    /// Parameter storage (1010h/1011h) in FILE.a and FILE.b, the LSS configuration (node-ID, bit rate) in
    /// FILE.lss.a; also makes `--eds` announce 1010h/1011h. Checked at start: an unwritable path ends the
    /// program, a damaged file is reported and kept as FILE.x.bad, the node then starts on defaults.
    #[arg(long, value_name = "FILE")]
    store: Option<String>,
    /// Program download (CiA 302-3): an image written to 1F50h:01 goes to FILE (through FILE.part while it
    /// arrives); the node prints its length and CRC-32 when the download ends.
    #[arg(long, value_name = "FILE")]
    program: Option<std::path::PathBuf>,
    /// Use the blocking runner instead of tokio.
    #[arg(long)]
    blocking: bool,
    /// Do not print every frame (events and adapter reports are still printed).
    #[arg(long)]
    quiet: bool,
}

type SharedNode = MutexShared<IoNode>;

fn parse_u32(s: &str) -> Result<u32, String> {
    let r = match s.strip_prefix("0x") {
        Some(hex) => u32::from_str_radix(hex, 16),
        None => s.parse(),
    };
    r.map_err(|e| e.to_string())
}

fn main() -> ExitCode {
    let args = Args::parse();
    let config = canopen_core::profile::NodeConfig {
        heartbeat_time_ms: args.heartbeat,
        identity: canopen_core::profile::Identity { serial: args.serial, ..CONFIG.identity },
        ..CONFIG
    };
    if let Some(path) = &args.eds {
        return match std::fs::write(path, io_module::eds_text(config, args.store.is_some())) {
            Ok(()) => {
                println!("node: EDS written to {path}");
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("node: cannot write {path}: {e}");
                ExitCode::FAILURE
            }
        };
    }
    // The store first: an unusable one ends the program before anything starts.
    let checked = match &args.store {
        Some(path) => match store_file::check(path) {
            Ok(c) => Some(c),
            Err(e) => {
                eprintln!("node: {e}");
                return ExitCode::from(2);
            }
        },
        None => None,
    };
    if let Some(c) = &checked {
        for r in &c.reports {
            eprintln!("node: {r}");
        }
        if !c.reports.is_empty() && !c.params_valid {
            eprintln!("node: starting on defaults");
        }
    }
    // CiA 305: a node-ID stored by LSS "store configuration" wins over the factory default --node-id.
    let raw_id = match checked.as_ref().and_then(|c| c.lss) {
        Some((stored, bit_rate)) => {
            println!(
                "node: node-ID {} from the LSS store (bit rate table index {bit_rate}), not --node-id {}",
                if stored == 255 { "none (FFh)".to_owned() } else { stored.to_string() },
                args.node_id
            );
            stored
        }
        None => args.node_id,
    };
    // 255 (FFh): no node-ID; the node serves only LSS until a master configures one (CiA 305).
    let unconfigured = raw_id == 255;
    let Some(node_id) = NodeId::new(if unconfigured { 1 } else { raw_id }) else {
        eprintln!("node: node-ID must be 1..=127, or 255 to start without one (LSS)");
        return ExitCode::from(2);
    };
    // Fail with one clear line when the interface is missing, before starting anything.
    if let Err(e) = BlockingBus::open(&args.iface) {
        eprintln!("node: {e}");
        return ExitCode::from(2);
    }
    let (store, lss) = match &args.store {
        Some(path) => {
            println!("node: parameters stored in {path}.a / {path}.b (1010h/1011h), LSS in {path}.lss.a");
            (Store::File(FileStorage::new(path)), Some(std::sync::Mutex::new(store_file::LssFile::new(path))))
        }
        None => (Store::None, None),
    };
    if let Some(path) = &args.program {
        println!("node: program downloads (1F50h:01) go to {}", path.display());
    }
    let mut node = io_module::new_node_with_program(node_id, config, store, args.program.clone());
    if unconfigured {
        node = node.without_node_id();
    }
    node.lss_mut().set_store_supported(lss.is_some());
    node.set_sdo_timeout(canopen_core::Duration::from_millis(args.sdo_timeout));
    let shared = Arc::new(MutexShared::new(node));
    println!(
        "node {} on {} (heartbeat {} ms, {} runner); Ctrl-C to stop",
        if unconfigured { "without node-ID (LSS only)".to_owned() } else { node_id.get().to_string() },
        args.iface,
        args.heartbeat,
        if args.blocking { "blocking" } else { "tokio" }
    );
    let started = StdInstant::now();
    let limit = args.run_for.map(Duration::from_secs_f64);
    let wake = Arc::new(NotifyWake::new());
    let printer = Printer {
        shared: shared.clone(),
        started,
        iface: args.iface.clone(),
        quiet: args.quiet,
        wake: wake.clone(),
        app: Arc::default(),
        lss,
    };
    let result = if args.blocking {
        run_on_threads(&args, &shared, &printer, limit)
    } else {
        run_on_tokio(&args, &shared, &printer, limit)
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("node: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run_on_tokio(
    args: &Args,
    shared: &Arc<SharedNode>,
    printer: &Printer,
    limit: Option<Duration>,
) -> std::io::Result<()> {
    // One thread, I/O only: every sleep is a timerfd (`TimerFd`), so the runtime has no time driver, which
    // would read the clock at every wake-up.
    let rt = tokio::runtime::Builder::new_current_thread().enable_io().build()?;
    rt.block_on(async {
        let wake = printer.wake.clone();
        // The application task: wakes when its inputs change (the walking bit, once a second) while the
        // node is Operational (the TPDOs go out only then), and when the NMT state changes; never on a tick.
        let (s, w, t0, app) = (shared.clone(), wake.clone(), printer.started, printer.app.clone());
        let mut timer = TimerFd::new(Clock::new())?;
        tokio::spawn(async move {
            loop {
                match next_input_change(&s, t0) {
                    Some(wait) => {
                        w.signal();
                        tokio::select! {
                            r = timer.sleep(wait) => {
                                if let Err(e) = r {
                                    eprintln!("node: application timer: {e}");
                                    return;
                                }
                            }
                            _ = app.notify.notified() => {}
                        }
                    }
                    None => app.notify.notified().await,
                }
            }
        });
        let observe = |o: Observed<'_>| printer.print(o);
        let run = run_tokio(&**shared, &args.iface, &*wake, &observe);
        match limit {
            Some(l) => {
                let mut timer = TimerFd::new(Clock::new())?;
                tokio::select! {
                    r = run => r.map(|never| match never {}),
                    r = timer.sleep(l) => r,
                }
            }
            None => run.await.map(|never| match never {}),
        }
    })
}

fn run_on_threads(
    args: &Args,
    shared: &Arc<SharedNode>,
    printer: &Printer,
    limit: Option<Duration>,
) -> std::io::Result<()> {
    let mut bus = BlockingBus::open(&args.iface)?;
    let (s, t0, app, waker) = (shared.clone(), printer.started, printer.app.clone(), bus.waker()?);
    // The application thread, as the tokio task: on input changes while Operational, and on state changes.
    std::thread::spawn(move || loop {
        let wait = next_input_change(&s, t0);
        if wait.is_some() {
            waker.signal();
        }
        app.wait_thread(wait);
    });
    run_blocking(&**shared, &mut bus, |o| printer.print(o), || limit.is_none_or(|l| printer.started.elapsed() < l))
}

/// The application's inputs, sampled now: while Operational the application then sleeps until the next
/// change (returned; the caller wakes the runner so the TPDOs go out); in other states only a state change
/// or an SDO request (see [`Printer::print`]) samples them again (`None`).
fn next_input_change(shared: &SharedNode, started: StdInstant) -> Option<Duration> {
    shared.with(|n| {
        update_process_values(n, started);
        (n.state() == NmtState::Operational).then(|| {
            let ms = started.elapsed().as_millis() as u64;
            Duration::from_millis(1000 - ms % 1000)
        })
    })
}

/// Whether `f` is an SDO upload request (initiate, CCS 2, or block upload initiate, CCS 5) of an input (2006h uptime, 6000h, 6401h) to any
/// server (600h–67Fh): the application samples its inputs right before the node serves it, so a read is
/// always current without sampling while nobody looks.
fn reads_an_input(f: &canopen_core::CanFrame) -> bool {
    let d = f.data();
    (0x600..0x680).contains(&f.cob_id())
        && d.len() >= 3
        && matches!(d[0] >> 5, 2 | 5)
        && matches!(u16::from_le_bytes([d[1], d[2]]), 0x2006 | 0x6000 | 0x6401)
}

/// A wake-up for the application task (tokio) or thread (`--blocking`): a state change.
#[derive(Default)]
struct AppWake {
    notify: tokio::sync::Notify,
    pending: std::sync::Mutex<bool>,
    cv: std::sync::Condvar,
}

impl AppWake {
    fn signal(&self) {
        self.notify.notify_one();
        *self.pending.lock().unwrap_or_else(|p| p.into_inner()) = true;
        self.cv.notify_all();
    }

    /// Blocks the application thread until a signal or `timeout` (forever if `None`).
    fn wait_thread(&self, timeout: Option<Duration>) {
        let guard = self.pending.lock().unwrap_or_else(|p| p.into_inner());
        let mut guard = match timeout {
            Some(t) => self.cv.wait_timeout_while(guard, t, |p| !*p).unwrap_or_else(|p| p.into_inner()).0,
            None => self.cv.wait_while(guard, |p| !*p).unwrap_or_else(|p| p.into_inner()),
        };
        *guard = false;
    }
}

/// New input values (uptime, the walking bit, the analogue wave), then the event-driven TPDOs whose
/// inputs changed.
fn update_process_values(node: &mut IoNode, started: StdInstant) {
    let ms = started.elapsed().as_millis() as u64;
    let app = node.app_mut();
    app.uptime_ms = ms;
    let second = (ms / 1000) as usize;
    for (i, input) in app.digital_inputs.iter_mut().enumerate() {
        *input = u8::from(i == second % 8);
    }
    for (i, input) in app.analog_inputs.iter_mut().enumerate() {
        // A slow triangle wave per channel.
        let phase = ((ms / 10) as i64 + 250 * i as i64) % 2000;
        *input = (if phase < 1000 { phase } else { 2000 - phase } - 500) as i16;
    }
    node.trigger_changed_tpdos();
}

/// Prints frames and events, candump-like.
struct Printer {
    shared: Arc<SharedNode>,
    started: StdInstant,
    iface: String,
    quiet: bool,
    /// Wakes the tokio driver when an event handler queued frames (an EMCY of 2100h), so they go out now
    /// rather than at the next deadline (the blocking runner drains the node after every event anyway).
    wake: Arc<NotifyWake>,
    /// Wakes the application task on an NMT state change.
    app: Arc<AppWake>,
    /// Where LSS "store configuration" goes (`--store`); without it the node answers "not supported".
    lss: Option<std::sync::Mutex<store_file::LssFile>>,
}

impl Printer {
    fn print(&self, o: Observed<'_>) {
        // The clock is read only for what is printed (`--quiet` prints no frames).
        let t = || self.started.elapsed().as_secs_f64();
        match o {
            Observed::Received(f) => {
                if reads_an_input(f) {
                    self.shared.with(|n| update_process_values(n, self.started));
                }
                if !self.quiet {
                    println!("({:10.6}) {}  rx  {f}", t(), self.iface)
                }
            }
            Observed::Sent(f) if !self.quiet => println!("({:10.6}) {}  tx  {f}", t(), self.iface),
            Observed::Sent(_) => {}
            Observed::Event(e) => self.event(t(), e),
            Observed::Adapter(a) => match a.bus_state() {
                // The runner feeds the state to the node (8120h, 8140h, 1029h:01 on bus-off); this prints it.
                Some(state) => println!("({:10.6}) CAN bus state: {state} ({a})", t()),
                None => println!("({:10.6}) adapter {a}", t()),
            },
        }
    }

    fn event(&self, t: f64, e: &Event) {
        match e {
            Event::StateChanged { from, to } => {
                println!("({t:10.6}) NMT {from:?} -> {to:?}");
                self.app.signal();
            }
            Event::ResetApplication => {
                println!("({t:10.6}) NMT reset application: application values back to their defaults (or stored)")
            }
            Event::ResetCommunication => {
                println!("({t:10.6}) NMT reset communication");
                let (_, raised) = self.shared.with(io_module::error_injection_after_reset);
                if raised != 0 {
                    println!("({t:10.6}) error injection: code {raised:04X}h raised again (2100h)");
                    self.wake.signal();
                }
            }
            Event::ObjectWritten { index: 0x1F50, sub: 1 } => {
                let (last, path) =
                    self.shared.with(|n| (n.app().sink.last, n.app().sink.path().map(|p| p.display().to_string())));
                if let (Some((len, crc)), Some(path)) = (last, path) {
                    println!("({t:10.6}) program download complete: {len} bytes, CRC-32 {crc:08X}, in {path}");
                }
            }
            Event::ObjectWritten { index, sub } => {
                let value = self.shared.with(|n| {
                    let mut buf = [0u8; 32];
                    n.dictionary().read(*index, *sub, 0, &mut buf).map(|len| buf[..len].to_vec())
                });
                match value {
                    Ok(v) if *index == 0x2005 => {
                        let len = self.shared.with(|n| n.app().data_block.as_bytes().len());
                        println!("({t:10.6}) SDO wrote {index:04X}h:{sub:02X} ({len} bytes, starts {})", hex(&v))
                    }
                    Ok(v) => println!("({t:10.6}) SDO wrote {index:04X}h:{sub:02X} = {}", hex(&v)),
                    Err(code) => println!("({t:10.6}) SDO wrote {index:04X}h:{sub:02X} (unreadable: {code:?})"),
                }
                if *index == 0x2100 {
                    let (cleared, raised) = self.shared.with(io_module::apply_error_injection);
                    if cleared != 0 {
                        println!("({t:10.6}) error injection: code {cleared:04X}h cleared");
                    }
                    if raised != 0 {
                        println!("({t:10.6}) error injection: code {raised:04X}h raised");
                    }
                    self.wake.signal();
                }
            }
            Event::Lss(LssEvent::StoreRequested { .. }) => {
                println!("({t:10.6}) event {e:?}");
                if let Some(lss) = &self.lss {
                    let mut lss = lss.lock().unwrap_or_else(|p| p.into_inner());
                    self.shared.with(|n| n.complete_lss_store(&mut *lss));
                    self.wake.signal();
                }
            }
            Event::SdoAborted { index, sub, code, by_client } => println!(
                "({t:10.6}) SDO {index:04X}h:{sub:02X} aborted by the {} with {code:08X}h",
                if *by_client { "client" } else { "node" }
            ),
            other => println!("({t:10.6}) event {other:?}"),
        }
    }
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02X}")).collect::<Vec<_>>().join(" ")
}
