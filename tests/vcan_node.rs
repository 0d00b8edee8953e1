//! The example node's dictionary (`examples/common/io_module.rs`) on real SocketCAN, driven by OUR master
//! (`canopen_socketcan::Master` on the core's SDO client), plus a bounded load test. Run inside the VM:
//! `cargo test --test vcan_node -- --ignored` where vcan0 is up (scripts/test-interop.sh does, with
//! `--include-ignored`). They are `#[ignore]`d with the reason, so a plain `cargo test` lists them as ignored.
//!
//! - 64 KiB into and out of the 2005h DOMAIN, segmented and block with CRC (and block without CRC),
//!   byte-exact;
//! - load: 15 block downloads (each followed by a block upload) while another socket floods COB-IDs the
//!   node does not use (11-bit and 29-bit) and the node, Operational, sends 4 TPDOs on 1 ms event timers:
//!   all 15 downloads and the 15 uploads after them complete byte-exact (a failure would have to end with
//!   the same abort code on both sides), the node keeps its heartbeat and its TPDOs keep flowing (issue 21,
//!   item 2);
//! - bystander: frames for other nodes neither wake the node's runner nor reach its socket (kernel
//!   filters, issue 19), and the filters follow a COB-ID written by SDO and an NMT reset communication.

#[path = "../examples/common/io_module.rs"]
mod io_module;
#[path = "common/vcan.rs"]
mod vcan;

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant as StdInstant};

use canopen_core::pdo::PdoDefault;
use canopen_core::sdo::client::Mode;
use canopen_core::{NmtState, NodeId};
use canopen_socketcan::socketcan;
use canopen_socketcan::{run_tokio, BlockingBus, Master, MutexShared, NotifyWake, Observed};
use io_module::{IoNode, CONFIG};

use vcan::{require_vcan, IFACE};

/// A node on its own thread (tokio runner), stopped when dropped.
struct RunningNode {
    shared: Arc<MutexShared<IoNode>>,
    /// Every SDO abort the node reported: (code, sent by the client).
    aborts: Arc<std::sync::Mutex<Vec<(u32, bool)>>>,
    stop: Arc<AtomicBool>,
    /// The blocking runner's wake-up (it sleeps without a deadline otherwise).
    waker: Option<canopen_socketcan::BusWaker>,
    /// Stops the tokio runner without a polling timer (which would wake the node's thread for nothing).
    stop_tokio: Arc<tokio::sync::Notify>,
    /// `/proc/self/task/<tid>` of the node's thread, for its CPU time.
    task: Arc<std::sync::OnceLock<std::path::PathBuf>>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl RunningNode {
    fn start(id: u8) -> Self {
        Self::start_with(id, canopen_core::profile::NodeConfig { heartbeat_time_ms: 100, ..CONFIG })
    }

    fn start_with(id: u8, config: canopen_core::profile::NodeConfig) -> Self {
        let shared = Arc::new(MutexShared::new(io_module::new_node(NodeId::new(id).unwrap(), config)));
        let stop = Arc::new(AtomicBool::new(false));
        let aborts = Arc::new(std::sync::Mutex::new(Vec::new()));
        let (stop_tokio, task) = (Arc::new(tokio::sync::Notify::new()), Arc::new(std::sync::OnceLock::new()));
        let thread = {
            let (shared, stop, aborts) = (shared.clone(), stop_tokio.clone(), aborts.clone());
            let task = task.clone();
            std::thread::spawn(move || {
                let _ = task.set(this_task());
                // I/O only: the runner needs no time driver (its deadlines are a timerfd).
                let rt = tokio::runtime::Builder::new_current_thread().enable_io().build().unwrap();
                rt.block_on(async {
                    let wake = NotifyWake::new();
                    let observe = |o: Observed<'_>| {
                        if let Observed::Adapter(a) = o {
                            eprintln!("node adapter: {a}");
                        }
                        if let Observed::Event(canopen_core::Event::SdoAborted { code, by_client, .. }) = o {
                            aborts.lock().unwrap().push((*code, *by_client));
                        }
                    };
                    tokio::select! {
                        r = run_tokio(&*shared, IFACE, &wake, &observe) => panic!("node runner stopped: {r:?}"),
                        _ = stop.notified() => {}
                    }
                })
            })
        };
        std::thread::sleep(Duration::from_millis(200));
        RunningNode { shared, aborts, stop, waker: None, stop_tokio, task, thread: Some(thread) }
    }

    /// The same node on the blocking runner (`run_blocking`), on its own thread.
    fn start_blocking(id: u8, config: canopen_core::profile::NodeConfig) -> Self {
        let shared = Arc::new(MutexShared::new(io_module::new_node(NodeId::new(id).unwrap(), config)));
        let stop = Arc::new(AtomicBool::new(false));
        let mut bus = BlockingBus::open(IFACE).unwrap();
        let waker = bus.waker().unwrap();
        let task = Arc::new(std::sync::OnceLock::new());
        let thread = {
            let (shared, stop, task) = (shared.clone(), stop.clone(), task.clone());
            std::thread::spawn(move || {
                let _ = task.set(this_task());
                let observe = |o: Observed<'_>| {
                    if let Observed::Adapter(a) = o {
                        eprintln!("node adapter: {a}");
                    }
                };
                canopen_socketcan::run_blocking(&*shared, &mut bus, observe, || !stop.load(Ordering::Relaxed))
                    .expect("blocking runner failed");
            })
        };
        std::thread::sleep(Duration::from_millis(200));
        RunningNode {
            shared,
            aborts: Arc::default(),
            stop,
            waker: Some(waker),
            stop_tokio: Arc::default(),
            task,
            thread: Some(thread),
        }
    }

    /// The node thread's CPU time so far (user + system), in clock ticks (`/proc/self/task/<tid>/stat`).
    fn cpu_ticks(&self) -> u64 {
        let task = self.task.get().expect("the node thread started");
        let stat = std::fs::read_to_string(task.join("stat")).unwrap();
        let fields: Vec<&str> = stat.rsplit_once(')').unwrap().1.split_whitespace().collect();
        fields[11].parse::<u64>().unwrap() + fields[12].parse::<u64>().unwrap()
    }
}

/// `/proc/self/task/<tid>` of the calling thread.
fn this_task() -> std::path::PathBuf {
    let link = std::fs::read_link("/proc/thread-self").unwrap(); // "<pid>/task/<tid>"
    std::path::Path::new("/proc/self/task").join(link.file_name().unwrap())
}

impl Drop for RunningNode {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        self.stop_tokio.notify_one();
        if let Some(w) = &self.waker {
            w.signal();
        }
        if let Some(t) = self.thread.take() {
            let r = t.join();
            if !std::thread::panicking() {
                r.expect("node thread panicked");
            }
        }
    }
}

fn pattern(n: usize, seed: u32) -> Vec<u8> {
    let mut x = seed.wrapping_mul(2_654_435_761) | 1;
    (0..n)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            (x >> 8) as u8
        })
        .collect()
}

/// Stops a helper thread when the test ends, also by a panic.
struct StopOnDrop(Arc<AtomicBool>);

impl Drop for StopOnDrop {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

/// Reads the bus on a thread and a socket of its own until `stop`: every 11-bit frame that passes `filters`
/// ((id, mask) pairs; none: every frame) goes to `seen` as (COB-ID, data).
fn spawn_reader(
    stop: Arc<AtomicBool>,
    filters: &[(u32, u32)],
    mut seen: impl FnMut(u16, &[u8]) + Send + 'static,
) -> std::thread::JoinHandle<()> {
    use socketcan::{CanFilter, EmbeddedFrame, Socket, SocketOptions};
    let filters: Vec<CanFilter> = filters.iter().map(|&(id, mask)| CanFilter::new(id, mask)).collect();
    std::thread::spawn(move || {
        let raw = socketcan::CanSocket::open(IFACE).unwrap();
        if !filters.is_empty() {
            raw.set_filters(&filters).unwrap();
        }
        raw.set_read_timeout(Duration::from_millis(50)).unwrap();
        while !stop.load(Ordering::Relaxed) {
            if let Ok(f) = raw.read_frame() {
                if let socketcan::Id::Standard(id) = f.id() {
                    seen(id.as_raw(), f.data());
                }
            }
        }
    })
}

/// An SDO frame as a monitoring socket saw it: when (since the monitor started), COB-ID, data.
type SdoSeen = (Duration, u16, [u8; 8]);

const BLOCK_CRC: Mode = Mode::Block { crc: true, blksize: 127, pst: 0 };
const BLOCK_NO_CRC: Mode = Mode::Block { crc: false, blksize: 127, pst: 0 };

#[test]
#[ignore = "needs SocketCAN (vcan0): scripts/test-interop.sh runs it (scripts/vcan-run.sh)"]
fn our_client_moves_64k_through_the_domain_segmented_and_block() {
    require_vcan();
    let node = RunningNode::start(31);
    let mut m = Master::new(BlockingBus::open(IFACE).unwrap(), NodeId::new(31).unwrap()).unwrap();
    assert_eq!(m.upload(0x1008, 0, Mode::Auto, 64).unwrap(), b"canopen example node");
    for (i, (down, up)) in
        [(Mode::Segmented, Mode::Auto), (BLOCK_CRC, BLOCK_CRC), (BLOCK_NO_CRC, BLOCK_NO_CRC)].into_iter().enumerate()
    {
        let data = pattern(65_536, i as u32 + 1);
        let t = StdInstant::now();
        m.download(0x2005, 0, &data, down).unwrap();
        let t_down = t.elapsed();
        assert!(node.shared.with(|n| n.app().data_block.as_bytes() == data), "{down:?}: node content");
        let t = StdInstant::now();
        let back = m.upload(0x2005, 0, up, 65_536).unwrap();
        eprintln!("64 KiB {down:?}: down {t_down:.2?}, up {:.2?}", t.elapsed());
        assert!(back == data, "{up:?}: uploaded bytes differ");
    }
    // 65,537 bytes do not fit: refused before any data moves, old content kept.
    let err = m.download(0x2005, 0, &pattern(65_537, 9), BLOCK_CRC).unwrap_err();
    assert_eq!(err.abort_code(), Some(0x0607_0012));
    assert_eq!(m.upload(0x2005, 0, BLOCK_CRC, 65_536).unwrap(), pattern(65_536, 3));
}

#[test]
#[ignore = "needs SocketCAN (vcan0): scripts/test-interop.sh runs it (scripts/vcan-run.sh)"]
fn load_block_transfers_under_a_flood_of_unknown_cob_ids() {
    require_vcan();
    // 4 event-driven TPDOs whose event timers (1 ms) send them whether or not the values change.
    const TPDOS: &[PdoDefault] = &[
        PdoDefault { mapping: &[0x6000_0108, 0x6000_0208], event_timer_ms: 1, ..PdoDefault::EVENT },
        PdoDefault {
            mapping: &[0x6401_0110, 0x6401_0210, 0x6401_0310, 0x6401_0410],
            event_timer_ms: 1,
            ..PdoDefault::EVENT
        },
        PdoDefault { mapping: &[0x2006_0040], event_timer_ms: 1, ..PdoDefault::EVENT },
        PdoDefault { mapping: &[0x6000_0308, 0x6401_0110], event_timer_ms: 1, ..PdoDefault::EVENT },
    ];
    let config = canopen_core::profile::NodeConfig { heartbeat_time_ms: 100, tpdo: TPDOS, ..CONFIG };
    let node = RunningNode::start_with(32, config);
    node.shared.with(|n| n.enter_state(NmtState::Operational)); // PDOs only in Operational (PDO-04)

    // The node's SDO protocol time-out as long as the master's (3 s, below), not the default 1 s. This test
    // saturates the VM's one CPU (four 1 ms TPDOs, the flood, a thread reading every frame), and there the
    // master, reading a sub-block one frame per system call, once acknowledged 127 segments 0.82 s after
    // the last one (as a third socket saw the frames: the SDO frame log below). That upload was aborted
    // with 0504 0000h although no frame was lost: the server's 1 s had started when the runner took the
    // sub-block from the node, 0.33 s before that segment went out (fixed since: the time-out starts at the
    // runner's next pass, tests/sdo_node.rs), and 0.82 s leaves little of 1 s. What is measured here is
    // that the flood loses nothing; a lost frame still fails the transfer, on the master's 3 s time-out.
    node.shared.with(|n| n.set_sdo_timeout(canopen_core::Duration::from_millis(3_000)));
    let stop = Arc::new(AtomicBool::new(false));
    // Counts the node's TPDO frames (180h/280h/380h/480h + 32) from another socket.
    let tpdo_frames = Arc::new([(); 4].map(|_| AtomicU64::new(0)));
    let tpdo_counter = {
        let counts = tpdo_frames.clone();
        spawn_reader(stop.clone(), &[], move |id, data| {
            if id & 0x7F == 32 && (0x180..0x500).contains(&(id & 0x780)) && data.len() <= 8 {
                counts[usize::from((id - 0x180) >> 8)].fetch_add(1, Ordering::Relaxed);
            }
        })
    };
    let flooded = Arc::new(AtomicU64::new(0));
    let flood = {
        let (stop, flooded) = (stop.clone(), flooded.clone());
        std::thread::spawn(move || {
            let raw = socketcan::CanSocket::open(IFACE).unwrap();
            use socketcan::{EmbeddedFrame, ExtendedId, Socket, StandardId};
            let mut x = 0x1234_5678u32;
            while !stop.load(Ordering::Relaxed) {
                x ^= x << 13;
                x ^= x >> 17;
                x ^= x << 5;
                // COB-IDs 080h..7FFh that are not node 32's, not NMT (000h); every 8th frame 29-bit.
                let mut id = 0x080 + (x % 0x780) as u16;
                if id & 0x7F == 32 {
                    id ^= 1;
                }
                let data = x.to_le_bytes();
                let frame = if x % 8 == 0 {
                    socketcan::CanFrame::new(ExtendedId::new(x & 0x1FFF_FFFF).unwrap(), &data)
                } else {
                    socketcan::CanFrame::new(StandardId::new(id).unwrap(), &data)
                }
                .unwrap();
                match raw.write_frame(&frame) {
                    Ok(()) => {
                        flooded.fetch_add(1, Ordering::Relaxed);
                    }
                    Err(_) => std::thread::sleep(Duration::from_micros(200)),
                }
                // About 2000 frames/s (half of a 500 kbit/s bus): 10 frames every 5 ms.
                if flooded.load(Ordering::Relaxed) % 10 == 0 {
                    std::thread::sleep(Duration::from_millis(5));
                }
            }
        })
    };
    // The longest time a thread that sleeps 5 ms was kept from running, µs: how long the VM (or the host)
    // left this test unscheduled. A stall longer than an SDO time-out aborts a transfer (0504 0000h) on a
    // loaded host whatever the node does; it is printed with the figures and with every failure.
    let longest_stall = Arc::new(AtomicU64::new(0));
    let stall_monitor = {
        let (stop, longest) = (stop.clone(), longest_stall.clone());
        std::thread::spawn(move || {
            while !stop.load(Ordering::Relaxed) {
                let t = StdInstant::now();
                std::thread::sleep(Duration::from_millis(5));
                let late = t.elapsed().saturating_sub(Duration::from_millis(5));
                longest.fetch_max(late.as_micros() as u64, Ordering::Relaxed);
            }
        })
    };
    let stall_ms = || longest_stall.load(Ordering::Relaxed) / 1000;
    // The SDO frames of both sides (5A0h, 620h) as a third socket sees them, time-stamped: printed with a
    // failed transfer, they say which side stopped.
    let sdo_log: Arc<std::sync::Mutex<Vec<SdoSeen>>> = Arc::default();
    let sdo_monitor = {
        let (log, t0) = (sdo_log.clone(), StdInstant::now());
        spawn_reader(stop.clone(), &[(0x5A0, 0x7FF), (0x620, 0x7FF)], move |id, data| {
            let mut d = [0u8; 8];
            let n = data.len().min(8);
            d[..n].copy_from_slice(&data[..n]);
            log.lock().unwrap().push((t0.elapsed(), id, d));
        })
    };
    let dump_sdo = |what: &str| {
        let log = sdo_log.lock().unwrap();
        eprintln!("{what}: the last SDO frames on the bus (time, COB-ID, data):");
        for (t, id, d) in log.iter().rev().take(12).rev() {
            eprintln!("  {t:>10.4?} {id:03X} {d:02X?}");
        }
    };
    let _stop_flood = StopOnDrop(stop.clone());
    let mut m = Master::new(BlockingBus::open(IFACE).unwrap(), NodeId::new(32).unwrap()).unwrap();
    m.set_timeout(Duration::from_secs(3));
    let start = StdInstant::now();
    let (mut completed, mut bytes, mut downloads_ok) = (0, 0, 0);
    let mut failures: Vec<String> = Vec::new();
    let mut committed: Vec<u8> = Vec::new();
    const DOWNLOADS: u32 = 15;
    for seed in 100..100 + DOWNLOADS {
        let n = 8192 + (seed as usize * 977) % 8192;
        let data = pattern(n, seed);
        let aborts_before = node.aborts.lock().unwrap().len();
        match m.download(0x2005, 0, &data, BLOCK_CRC) {
            Ok(()) => {
                assert!(
                    node.shared.with(|nd| nd.app().data_block.as_bytes() == data),
                    "download {seed}: completed but the node's 2005h differs"
                );
                completed += 1;
                downloads_ok += 1;
                bytes += n;
                committed = data;
            }
            Err(e) => {
                // Not completed: it must end with a stated abort code on both sides (SDO-17).
                let code = e.abort_code();
                std::thread::sleep(Duration::from_millis(50));
                let node_side = node.aborts.lock().unwrap()[aborts_before..].to_vec();
                dump_sdo(&format!("download {seed} failed: {e}"));
                eprintln!(
                    "download {seed} aborted: {e} (node reported {node_side:X?}; longest stall {} ms)",
                    stall_ms()
                );
                assert!(code.is_some(), "download {seed} failed without an abort code: {e}");
                assert!(
                    node_side.iter().any(|&(c, _)| Some(c) == code),
                    "download {seed}: the node did not report the abort {code:X?}: {node_side:X?}"
                );
                failures.push(format!("download {seed}: {e} (longest stall so far {} ms)", stall_ms()));
            }
        }
        match m.upload(0x2005, 0, BLOCK_CRC, 65_536) {
            Ok(back) => {
                assert!(back == committed, "upload after download {seed}: content differs from the last committed");
                completed += 1;
                bytes += back.len();
            }
            Err(e) => {
                dump_sdo(&format!("upload after download {seed} failed: {e}"));
                assert!(e.abort_code().is_some(), "upload after download {seed} failed without an abort code: {e}");
                failures.push(format!("upload after download {seed}: {e} (longest stall so far {} ms)", stall_ms()));
            }
        }
    }
    // The node still answers and still produces its heartbeat (Operational).
    assert_eq!(m.wait_heartbeat(Duration::from_secs(2)).unwrap(), Some(0x05));
    stop.store(true, Ordering::Relaxed);
    flood.join().unwrap();
    tpdo_counter.join().unwrap();
    stall_monitor.join().unwrap();
    sdo_monitor.join().unwrap();
    eprintln!("load: longest scheduling stall of a 5 ms sleeper: {} ms", stall_ms());
    let tpdos = tpdo_frames.each_ref().map(|c| c.load(Ordering::Relaxed));
    eprintln!("load: TPDO frames seen (TPDO1..4, 1 ms event timers): {tpdos:?} in {:.1?}", start.elapsed());
    assert!(tpdos.iter().all(|&n| n > 100), "every TPDO kept flowing during the transfers: {tpdos:?}");
    let frames = flooded.load(Ordering::Relaxed);
    let stats = canopen_socketcan::runner_stats();
    eprintln!(
        "load: {downloads_ok}/{DOWNLOADS} block downloads byte-exact, {completed} transfers ({bytes} bytes) in {:.1?} while {frames} flood frames were sent; failures: {failures:?}; runner {stats:?}",
        start.elapsed()
    );
    // Issue 21 item 2: the node's kernel filters keep the flood out of its socket (and the master's), so no
    // sub-block is lost to an overflowing receive buffer: every transfer completes. (One failed download
    // was tolerated while the flood reached the node's socket; with the filters, 7 VM runs of this test in
    // a row completed all 30 transfers.)
    assert_eq!(downloads_ok, DOWNLOADS, "block downloads completed: {failures:?}");
    assert!(failures.is_empty(), "every transfer completes under the flood: {failures:?}");
    assert!(frames > 1000, "the flood did not run: {frames} frames");
    // Frames the node had to drop because its transmit queue was full (four 1 ms TPDOs faster than the VM's
    // socket takes them); reported, not asserted.
    eprintln!("load: node transmit-queue drops: {}", node.shared.with(|n| n.tx_dropped()));
    drop(node);
}

/// Issue 19, CAN-02: frames for other nodes cost the node nothing. Idle (Pre-operational, heartbeat off, no
/// deadline) the runner does not wake at all; 4,000 frames for other nodes (their SDO servers, RPDOs,
/// heartbeats, 29-bit frames) are dropped by the kernel filters: no wake-up, no frame received, and the
/// node thread's CPU time stays at its idle level. Then a
/// COB-ID written by SDO (a heartbeat consumer for node 34, 1016h) opens the filter for that node's
/// heartbeat, and an NMT reset communication closes it again.
#[test]
#[ignore = "needs SocketCAN (vcan0): scripts/test-interop.sh runs it (scripts/vcan-run.sh)"]
fn frames_for_other_nodes_do_not_wake_the_tokio_node() {
    require_vcan();
    bystander(RunningNode::start_with(33, canopen_core::profile::NodeConfig { heartbeat_time_ms: 0, ..CONFIG }));
}

/// The same with the blocking runner (with a `BusWaker`, so no `APP_POLL` wake-ups).
#[test]
#[ignore = "needs SocketCAN (vcan0): scripts/test-interop.sh runs it (scripts/vcan-run.sh)"]
fn frames_for_other_nodes_do_not_wake_the_blocking_node() {
    require_vcan();
    bystander(RunningNode::start_blocking(33, canopen_core::profile::NodeConfig { heartbeat_time_ms: 0, ..CONFIG }));
}

fn bystander(node: RunningNode) {
    use socketcan::{EmbeddedFrame, ExtendedId, Socket, StandardId};
    let raw = socketcan::CanSocket::open(IFACE).unwrap();
    let send = |id: u16, n: usize| {
        for i in 0..n {
            let f = if i % 8 == 7 {
                socketcan::CanFrame::new(ExtendedId::new(0x600 + 33).unwrap(), &[0x40, 0, 0x10, 0, 0, 0, 0, 0])
            } else {
                socketcan::CanFrame::new(StandardId::new(id).unwrap(), &[0x40, 0, 0x10, 0, 0, 0, 0, 0])
            }
            .unwrap();
            while raw.write_frame(&f).is_err() {
                std::thread::sleep(Duration::from_micros(200));
            }
        }
    };
    std::thread::sleep(Duration::from_millis(300));
    let (idle0, ticks0) = (canopen_socketcan::runner_stats(), node.cpu_ticks());
    std::thread::sleep(Duration::from_millis(500));
    let (idle1, ticks1) = (canopen_socketcan::runner_stats(), node.cpu_ticks());
    assert_eq!(idle1.wakeups - idle0.wakeups, 0, "idle with heartbeat off: no wake-up ({idle0:?} -> {idle1:?})");
    for id in [0x600 + 34, 0x200 + 34, 0x700 + 34, 0x580 + 33] {
        send(id, 1000);
    }
    std::thread::sleep(Duration::from_millis(300));
    let (flood, ticks2) = (canopen_socketcan::runner_stats(), node.cpu_ticks());
    eprintln!(
        "bystander: 4000 frames for other nodes: {idle1:?} -> {flood:?}; node thread CPU ticks idle {}, flood {}",
        ticks1 - ticks0,
        ticks2 - ticks1
    );
    assert_eq!(flood.wakeups - idle1.wakeups, 0, "woken by frames for other nodes");
    assert_eq!(flood.frames_received - idle1.frames_received, 0, "received frames for other nodes");
    // The node's thread stays at idle level: not one 10 ms tick more than while idle (handling the 4,000
    // frames cost 50-80 ticks before the kernel filters, issue 19).
    assert!(
        ticks2 - ticks1 <= ticks1 - ticks0 + 1,
        "node CPU ticks: idle {}, flood {}",
        ticks1 - ticks0,
        ticks2 - ticks1
    );
    // 1016h:01 = node 34, 500 ms: its heartbeats now reach the node (HB-09), and reset communication
    // restores the power-on filters (NMT-05).
    let mut m = Master::new(BlockingBus::open(IFACE).unwrap(), NodeId::new(33).unwrap()).unwrap();
    m.download(0x1016, 1, &0x0022_01F4u32.to_le_bytes(), Mode::Auto).unwrap();
    std::thread::sleep(Duration::from_millis(100));
    let before = canopen_socketcan::runner_stats();
    send(0x700 + 34, 10);
    std::thread::sleep(Duration::from_millis(200));
    let after = canopen_socketcan::runner_stats();
    assert!(after.frames_received - before.frames_received >= 9, "consumed heartbeats: {before:?} -> {after:?}");
    raw.write_frame(&socketcan::CanFrame::new(StandardId::new(0).unwrap(), &[0x82, 33]).unwrap()).unwrap();
    std::thread::sleep(Duration::from_millis(300));
    let before = canopen_socketcan::runner_stats();
    send(0x700 + 34, 10);
    std::thread::sleep(Duration::from_millis(200));
    let after = canopen_socketcan::runner_stats();
    assert_eq!(after.frames_received - before.frames_received, 0, "after reset communication: {after:?}");
    assert!(
        after.filter_updates - idle0.filter_updates >= 2,
        "filters re-installed after 1016h and after the reset: {idle0:?} -> {after:?}"
    );
    drop(node);
}

/// Issue 22, end to end on vcan (HB-11, HB-13, EEC-01): node 41 consumes the heartbeat of node 40 (1016h:01
/// set by SDO, 300 ms against 40's 100 ms). When node 40 goes silent, node 41 sends EMCY 8130h (heartbeat
/// time-out) with the communication bit of 1001h; when node 40 comes back (boot-up, then heartbeats), node 41
/// clears it: EMCY 0000h with 1001h = 0, and 1001h reads 0 by SDO; silent again, 8130h again.
#[test]
#[ignore = "needs SocketCAN (vcan0): scripts/test-interop.sh runs it (scripts/vcan-run.sh)"]
fn a_lost_heartbeat_raises_8130h_and_its_return_clears_it() {
    use socketcan::{EmbeddedFrame, Frame, Socket};
    require_vcan();
    let config = |ms| canopen_core::profile::NodeConfig { heartbeat_time_ms: ms, ..CONFIG };
    let consumer = RunningNode::start_with(41, config(0));
    let producer = RunningNode::start_with(40, config(100));
    let mut m = Master::new(BlockingBus::open(IFACE).unwrap(), NodeId::new(41).unwrap()).unwrap();
    m.download(0x1016, 1, &0x0028_012Cu32.to_le_bytes(), Mode::Auto).unwrap();
    let raw = socketcan::CanSocket::open(IFACE).unwrap();
    raw.set_read_timeout(Duration::from_millis(50)).unwrap();
    // The first EMCY of node 41 (0A9h) within `limit`, as its 8 data bytes.
    let next_emcy = |limit: Duration| {
        let start = StdInstant::now();
        while start.elapsed() < limit {
            if let Ok(f) = raw.read_frame() {
                if f.raw_id() == 0x080 + 41 {
                    return Some(f.data().to_vec());
                }
            }
        }
        None
    };
    // Monitoring runs (HB-10: it started at 40's first heartbeat after the write): no EMCY while 40 beats.
    assert_eq!(next_emcy(Duration::from_millis(800)), None, "EMCY while the producer is alive");
    drop(producer);
    let lost = next_emcy(Duration::from_secs(2)).expect("no EMCY after the producer went silent");
    assert_eq!(lost[..3], [0x30, 0x81, 0x11], "8130h, 1001h = generic + communication: {lost:02X?}");
    let producer = RunningNode::start_with(40, config(100));
    let back = next_emcy(Duration::from_secs(2)).expect("no EMCY after the producer came back");
    assert_eq!(back[..3], [0x00, 0x00, 0x00], "error reset, 1001h = 0: {back:02X?}");
    assert_eq!(m.upload(0x1001, 0, Mode::Auto, 4).unwrap(), [0x00]);
    // Lost again: raised again (the consumer watches the node it heard back).
    drop(producer);
    let again = next_emcy(Duration::from_secs(2)).expect("no EMCY after the producer went silent again");
    assert_eq!(again[..3], [0x30, 0x81, 0x11], "8130h again: {again:02X?}");
    drop(consumer);
}
