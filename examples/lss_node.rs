//! A node on SocketCAN whose node-ID comes from an LSS master (CiA 305) and is persisted to a file.
//!
//! ```text
//! cargo run --example lss_node -- --iface vcan0 --store /tmp/lss-node.txt
//! ```
//!
//! At start it reads the node-ID the last LSS store configuration wrote to `--store`; with no file (or FFh
//! in it) it starts without a node-ID and serves only LSS until a master (for example python `canopen`'s
//! `network.lss`: fastscan, `configure_node_id`, `store_configuration`, switch to waiting) gives it one;
//! then it boots (boot-up frame, Pre-operational) and serves SDO. Restarted, it boots with the stored ID.
//!
//! The store request is answered after the file is written: the runner returns from `run_blocking` when
//! the node reports `LssEvent::StoreRequested`, stores through [`LssStore`], and runs on.

use std::cell::{Cell, RefCell};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant as StdInstant};

use canopen::core::{
    lss::{LssEvent, LssStore, StoreError},
    node::{NoApplication, Node},
    profile::{Identity, NodeConfig},
    wire::lss::BitRate,
    Event,
};
use canopen_socketcan::{run_blocking, BlockingBus, Observed};
use clap::Parser;

/// A CANopen node configured by LSS, on SocketCAN.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// SocketCAN interface.
    #[arg(long, default_value = "vcan0")]
    iface: String,
    /// File that keeps the LSS-stored node-ID and bit rate.
    #[arg(long)]
    store: PathBuf,
    /// Serial number (1018h:04, the last part of the LSS address).
    #[arg(long, default_value_t = 0x8000_0001, value_parser = parse_u32)]
    serial: u32,
    /// Producer heartbeat time 1017h in ms (0 = off).
    #[arg(long, default_value_t = 0)]
    heartbeat: u16,
    /// Stop after this many seconds (default: run until killed).
    #[arg(long)]
    run_for: Option<f64>,
}

fn parse_u32(s: &str) -> Result<u32, String> {
    let r = match s.strip_prefix("0x") {
        Some(hex) => u32::from_str_radix(hex, 16),
        None => s.parse(),
    };
    r.map_err(|e| e.to_string())
}

/// The LSS address is 1018h: vendor-ID 0 (none assigned), product code 1, revision 1.0.
const CONFIG: NodeConfig = NodeConfig {
    device_type: 0,
    identity: Identity { vendor_id: 0, product_code: 0x0000_0001, revision: 0x0001_0000, serial: 0 },
    device_name: "canopen LSS example node",
    hardware_version: "vcan",
    software_version: env!("CARGO_PKG_VERSION"),
    ..NodeConfig::DEFAULT
};

/// The LSS configuration in a small text file: `node_id=<dec>` and `bit_rate=<table index>`.
struct FileStore(PathBuf);

impl FileStore {
    /// The stored node-ID, FFh (unconfigured) if there is none.
    fn node_id(&self) -> u8 {
        let Ok(text) = std::fs::read_to_string(&self.0) else {
            return 0xFF;
        };
        text.lines().find_map(|l| l.strip_prefix("node_id=")).and_then(|v| v.trim().parse().ok()).unwrap_or(0xFF)
    }
}

impl LssStore for FileStore {
    fn store(&mut self, node_id: u8, bit_rate: BitRate) -> Result<(), StoreError> {
        write_atomically(&self.0, &format!("node_id={node_id}\nbit_rate={}\n", bit_rate.index())).map_err(|e| {
            eprintln!("lss_node: storing to {}: {e}", self.0.display());
            StoreError::MediaAccess
        })
    }
}

fn write_atomically(path: &Path, text: &str) -> std::io::Result<()> {
    let tmp = path.with_extension("tmp");
    std::fs::write(&tmp, text)?;
    std::fs::rename(&tmp, path)
}

fn main() -> ExitCode {
    let args = Args::parse();
    let mut bus = match BlockingBus::open(&args.iface) {
        Ok(bus) => bus,
        Err(e) => {
            eprintln!("lss_node: {e}");
            return ExitCode::from(2);
        }
    };
    let mut store = FileStore(args.store.clone());
    let config = NodeConfig {
        identity: Identity { serial: args.serial, ..CONFIG.identity },
        heartbeat_time_ms: args.heartbeat,
        ..CONFIG
    };
    let stored = store.node_id();
    // A corrupt stored value (0, 80h..FEh) counts as "no node-ID".
    let mut node: Node<NoApplication> = Node::from_raw_node_id(stored, config, NoApplication)
        .unwrap_or_else(|| Node::new_unconfigured(config, NoApplication));
    node.lss_mut().set_store_supported(true);
    match node.lss_node_id() {
        Some(id) => println!("lss_node: node-ID {} from {} on {}", id.get(), args.store.display(), bus.iface()),
        None => println!("lss_node: no node-ID, waiting for an LSS master on {}", bus.iface()),
    }

    let started = StdInstant::now();
    let limit = args.run_for.map(Duration::from_secs_f64);
    let iface = bus.iface().to_owned();
    let node = RefCell::new(node);
    loop {
        let store_requested = Cell::new(false);
        let result = run_blocking(
            &node,
            &mut bus,
            |o| {
                let t = started.elapsed().as_secs_f64();
                match o {
                    Observed::Received(f) => println!("({t:10.6}) {iface}  rx  {f}"),
                    Observed::Sent(f) => println!("({t:10.6}) {iface}  tx  {f}"),
                    Observed::Adapter(a) => println!("({t:10.6}) {iface}  {a:?}"),
                    Observed::Event(e) => {
                        println!("({t:10.6}) event {e:?}");
                        if matches!(e, Event::Lss(LssEvent::StoreRequested { .. })) {
                            store_requested.set(true);
                        }
                    }
                }
            },
            || !store_requested.get() && limit.is_none_or(|l| started.elapsed() < l),
        );
        if let Err(e) = result {
            eprintln!("lss_node: {e}");
            return ExitCode::FAILURE;
        }
        if !store_requested.get() {
            return ExitCode::SUCCESS;
        }
        // The 17h answer goes out on the next pass of run_blocking.
        node.borrow_mut().complete_lss_store(&mut store);
    }
}
