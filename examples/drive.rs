//! A CiA 402 drive on a SocketCAN interface: `canopen-cia402`'s [`Drive`] over a simulated axis
//! ([`SimAxis`]: inertia, top speed, hard stops with a limit switch each at ±200,000 increments).
//!
//! ```text
//! cargo run --example drive                                  # node 6 on vcan0
//! cargo run --example drive -- --iface vcan0 --node-id 6 --quiet
//! cargo run --example drive -- --eds drive.eds               # write the drive's EDS and exit
//! cargo run --example drive -- --store /var/tmp/drive6       # 1010h/1011h in /var/tmp/drive6.a and .b
//! ```
//!
//! The drive cycle runs every 2 ms on its own task, and at once after an RPDO or an SDO write; a SYNC
//! hands the cyclic synchronous modes their set-point. PDOs: `canopen_cia402::pdo`, the standard's default
//! set for a drive (pre-defined COB-IDs, event-driven, with event timers for python canopen's sake):
//!
//! | PDO | mapping |
//! |---|---|
//! | RPDO1 | 6040h controlword |
//! | RPDO2 | 6040h, 6060h modes of operation |
//! | RPDO3 | 6040h, 607Ah target position |
//! | RPDO4 | 6040h, 60FFh target velocity |
//! | TPDO1 | 6041h statusword |
//! | TPDO2 | 6041h, 6061h modes of operation display |
//! | TPDO3 | 6041h, 6064h position actual value |
//! | TPDO4 | 6041h, 606Ch velocity actual value |
//!
//! The application's own object: 2100h simulated fault (UNSIGNED16, rw): a non-zero error code makes the
//! axis report that fault (transition 13, 603Fh, an EMCY), 0 takes it away (a fault reset then works).

// For its `Store` (1010h/1011h in files with --store); the rest of the I/O module is unused here.
#[path = "common/io_module.rs"]
mod io_module;

use std::process::ExitCode;
use std::sync::Arc;
use std::time::{Duration, Instant as StdInstant};

use canopen_cia402::{cycle_node, Drive, SimAxis};
use canopen_core::profile::eds::EdsInfo;
use canopen_core::profile::{Identity, NodeConfig};
use canopen_core::{Event, NodeId, Sizes};
use canopen_od_derive::ObjectDictionary;
use canopen_socketcan::{run_tokio, BlockingBus, Clock, FileStorage, MutexShared, NotifyWake, Observed, TimerFd};
use clap::Parser;
use io_module::Store;

/// A CiA 402 drive (a simulated axis) on SocketCAN: python canopen's BaseNode402, `canopenctl` or any
/// master can enable it, change its mode, home it and move it.
#[derive(Parser, Debug)]
#[command(version, after_help = "Example: cargo run --example drive -- --iface vcan0 --node-id 6 --quiet")]
struct Args {
    /// SocketCAN interface.
    #[arg(long, default_value = "vcan0")]
    iface: String,
    /// Node-ID, 1..=127.
    #[arg(long, default_value_t = 6, value_parser = clap::value_parser!(u8).range(1..=127))]
    node_id: u8,
    /// Producer heartbeat time 1017h in ms (0 = off).
    #[arg(long, default_value_t = 1000)]
    heartbeat: u16,
    /// Stop after this many seconds (default: run until killed).
    #[arg(long)]
    run_for: Option<f64>,
    /// Write the drive's EDS (CiA 306) to FILE and exit.
    #[arg(long, value_name = "FILE")]
    eds: Option<String>,
    /// Parameter storage (1010h/1011h) in FILE.a and FILE.b; also makes `--eds` announce 1010h/1011h.
    #[arg(long, value_name = "FILE")]
    store: Option<String>,
    /// Do not print every frame (events are still printed).
    #[arg(long)]
    quiet: bool,
}

/// The application's own dictionary beside the drive's objects.
#[derive(ObjectDictionary, Debug, Default)]
struct DriveApp {
    #[od(index = 0x2100, name = "Simulated fault", access = "rw", default = 0)]
    simulated_fault: u16,
}

/// The drive's configuration: device type 0002 0192h (CiA 402, servo drive) and the PDOs above.
const CONFIG: NodeConfig = NodeConfig {
    device_type: 0x0002_0192,
    identity: Identity { vendor_id: 0, product_code: 0x0000_0402, revision: 0x0001_0000, serial: 1 },
    device_name: "canopen example drive",
    hardware_version: "simulated axis",
    software_version: "0.1.0",
    heartbeat_time_ms: 1000,
    rpdo: &canopen_cia402::pdo::RPDOS,
    tpdo: &canopen_cia402::pdo::TPDOS,
    ..NodeConfig::DEFAULT
};

const EDS_INFO: EdsInfo = EdsInfo {
    file_name: "drive.eds",
    description: "canopener example drive: CiA 402 on a simulated axis",
    vendor_name: "canopener",
    product_name: "canopen example drive",
    order_code: "DRIVE-1",
    ..EdsInfo::DEFAULT
};

type DriveSizes = Sizes<4, 32, 32, 4, 4>;
type DriveNode = canopen_core::Node<Drive<DriveApp>, DriveSizes, Store>;

/// The drive cycle.
const CYCLE: Duration = Duration::from_millis(2);
/// [`CYCLE`] in microseconds, the longest step the simulated axis is given.
const CYCLE_US: u32 = CYCLE.as_micros() as u32;

fn main() -> ExitCode {
    let args = Args::parse();
    let config = NodeConfig { heartbeat_time_ms: args.heartbeat, ..CONFIG };
    if let Some(path) = &args.eds {
        let mut comm = canopen_core::profile::CommProfile::<DriveSizes>::new(config);
        comm.storage_supported = args.store.is_some();
        let od = canopen_core::od::Merged { comm, app: Drive::new(DriveApp::default()) };
        let mut text = String::new();
        if let Err(e) = canopen_core::profile::eds::write_eds(&mut text, &EDS_INFO, &od) {
            eprintln!("drive: cannot format the EDS: {e}");
            return ExitCode::FAILURE;
        }
        return match std::fs::write(path, text) {
            Ok(()) => {
                println!("drive: EDS written to {path}");
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("drive: cannot write {path}: {e}");
                ExitCode::FAILURE
            }
        };
    }
    let Some(node_id) = NodeId::new(args.node_id) else {
        eprintln!("drive: node-ID must be 1..=127");
        return ExitCode::from(2);
    };
    if let Err(e) = BlockingBus::open(&args.iface) {
        eprintln!("drive: {e}");
        return ExitCode::from(2);
    }
    let store = match &args.store {
        Some(path) => {
            println!("drive: parameters stored in {path}.a / {path}.b (1010h/1011h)");
            Store::File(FileStorage::new(path))
        }
        None => Store::None,
    };
    let node: DriveNode = canopen_core::Node::with_storage(node_id, config, Drive::new(DriveApp::default()), store);
    let shared = Arc::new(MutexShared::new(node));
    println!("drive {} on {} (heartbeat {} ms); Ctrl-C to stop", node_id.get(), args.iface, args.heartbeat);
    match run(&args, shared) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("drive: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The axis and the last state printed, owned by whoever runs a cycle.
struct Axis {
    sim: SimAxis,
    last: Option<(canopen_cia402::State, i8)>,
}

/// One drive cycle on the node: the simulated fault from 2100h, the cycle, the transitions printed.
fn cycle(node: &mut DriveNode, axis: &mut Axis, dt: u32, started: StdInstant) {
    let injected = node.app().app.simulated_fault;
    axis.sim.fault = (injected != 0).then_some(injected);
    let c = cycle_node(node, &mut axis.sim, dt);
    let t = started.elapsed().as_secs_f64();
    for (n, from, to) in c.transitions() {
        println!("({t:10.6}) CiA 402 transition {n}: {} -> {}", from.name(), to.name());
    }
    if let Some(code) = c.raised {
        println!("({t:10.6}) fault {code:04X}h raised (603Fh, EMCY)");
    }
    if let Some(code) = c.cleared {
        println!("({t:10.6}) fault {code:04X}h reset");
    }
    let now = (node.app().state(), node.app().objects.modes_of_operation_display);
    if axis.last.is_some_and(|(_, m)| m != now.1) {
        println!("({t:10.6}) mode of operation {}", now.1);
    }
    axis.last = Some(now);
}

fn run(args: &Args, shared: Arc<MutexShared<DriveNode>>) -> std::io::Result<()> {
    let rt = tokio::runtime::Builder::new_current_thread().enable_io().build()?;
    let started = StdInstant::now();
    let axis = Arc::new(std::sync::Mutex::new(Axis { sim: SimAxis::new(-200_000, 200_000), last: None }));
    let wake = Arc::new(NotifyWake::new());
    let last_cycle = Arc::new(std::sync::Mutex::new(StdInstant::now()));
    // The cycles due since the last run, each of at most CYCLE: a late timer (a loaded host) catches up in
    // steps of the drive's period, as a fixed-rate control loop would, instead of one long step. One long step
    // of the simulated axis's position loop (20 ms and more) leaves the axis off its demand, and a homing then
    // ends tens of increments off its switch's edge (seen in CI as 6064h = -41 after method 17).
    let run_cycle = {
        let (shared, axis, wake, last_cycle) = (shared.clone(), axis.clone(), wake.clone(), last_cycle.clone());
        move || {
            let mut last = last_cycle.lock().unwrap_or_else(|p| p.into_inner());
            let mut due = last.elapsed().as_micros().min(100_000) as u32;
            *last = StdInstant::now();
            let mut axis = axis.lock().unwrap_or_else(|p| p.into_inner());
            loop {
                let dt = due.min(CYCLE_US);
                shared.with(|n| cycle(n, &mut axis, dt, started));
                due -= dt;
                if due == 0 {
                    break;
                }
            }
            wake.signal();
        }
    };
    rt.block_on(async {
        let tick = run_cycle.clone();
        let mut timer = TimerFd::new(Clock::new())?;
        tokio::spawn(async move {
            loop {
                tick();
                if let Err(e) = timer.sleep(CYCLE).await {
                    eprintln!("drive: cycle timer: {e}");
                    return;
                }
            }
        });
        let quiet = args.quiet;
        let iface = args.iface.clone();
        let observe = |o: Observed<'_>| {
            let t = || started.elapsed().as_secs_f64();
            match o {
                Observed::Received(f) if !quiet => println!("({:10.6}) {iface}  rx  {f}", t()),
                Observed::Sent(f) if !quiet => println!("({:10.6}) {iface}  tx  {f}", t()),
                Observed::Event(Event::Sync { .. }) => {
                    shared.with(|n| n.app_mut().sync());
                    run_cycle();
                }
                Observed::Event(Event::RpdoReceived { .. }) => run_cycle(),
                Observed::Event(Event::ObjectWritten { index, sub }) => {
                    println!("({:10.6}) SDO wrote {index:04X}h:{sub:02X}", t());
                    run_cycle();
                }
                Observed::Event(e) => println!("({:10.6}) event {e:?}", t()),
                Observed::Adapter(a) => println!("({:10.6}) adapter {a}", t()),
                _ => {}
            }
        };
        let run = run_tokio(&*shared, &args.iface, &*wake, &observe);
        match args.run_for.map(Duration::from_secs_f64) {
            Some(limit) => {
                let mut timer = TimerFd::new(Clock::new())?;
                tokio::select! {
                    r = run => r.map(|never| match never {}),
                    r = timer.sleep(limit) => r,
                }
            }
            None => run.await.map(|never| match never {}),
        }
    })
}
