//! A CANopen node on a SocketCAN interface.
//!
//! ```text
//! cargo run --example node                         # node 5 on vcan0
//! cargo run --example node -- --iface vcan0 --node-id 5 --heartbeat 1000
//! ```
//!
//! It prints what happens on the bus, candump-like, and the node's events. Where there is no SocketCAN
//! interface it says so in one line, with the commands that create a virtual one.

use std::process::ExitCode;
use std::time::{Duration, Instant as StdInstant};

use canopen::core::{
    comm::{Identity, NodeConfig},
    node::{NoApplication, Node},
    NodeId,
};
use canopen_socketcan::{run_blocking, BlockingBus, Observed};
use clap::Parser;

/// A CiA 301 CANopen node on SocketCAN.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// SocketCAN interface.
    #[arg(long, default_value = "vcan0")]
    iface: String,
    /// Node-ID, 1..=127.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u8).range(1..=127))]
    node_id: u8,
    /// Producer heartbeat time 1017h in ms (0 = off).
    #[arg(long, default_value_t = 1000)]
    heartbeat: u16,
    /// Stop after this many seconds (default: run until killed).
    #[arg(long)]
    run_for: Option<f64>,
}

const CONFIG: NodeConfig = NodeConfig {
    device_type: 0x000F_0191,
    identity: Identity { vendor_id: 0, product_code: 0x0000_0001, revision: 0x0001_0000, serial: 1 },
    device_name: "canopen example node",
    hardware_version: "vcan",
    software_version: env!("CARGO_PKG_VERSION"),
    heartbeat_time_ms: 1000,
    guard_time_ms: 0,
    life_time_factor: 0,
    ..NodeConfig::DEFAULT
};

fn main() -> ExitCode {
    let args = Args::parse();
    let bus = match BlockingBus::open(&args.iface) {
        Ok(bus) => bus,
        Err(e) => {
            eprintln!("node: {e}");
            return ExitCode::from(2);
        }
    };
    let Some(node_id) = NodeId::new(args.node_id) else {
        eprintln!("node: node-ID must be 1..=127");
        return ExitCode::from(2);
    };
    let config = NodeConfig { heartbeat_time_ms: args.heartbeat, ..CONFIG };
    let mut node: Node<NoApplication> = Node::new(node_id, config, NoApplication);
    println!("node {} on {} (heartbeat {} ms); Ctrl-C to stop", node_id.get(), bus.iface(), args.heartbeat);

    let started = StdInstant::now();
    let limit = args.run_for.map(Duration::from_secs_f64);
    let result = run_blocking(
        &mut node,
        &bus,
        |o| {
            let t = started.elapsed().as_secs_f64();
            match o {
                Observed::Received(f) => println!("({t:10.6}) {}  rx  {f}", bus.iface()),
                Observed::Sent(f) => println!("({t:10.6}) {}  tx  {f}", bus.iface()),
                Observed::Event(e) => println!("({t:10.6}) event {e:?}"),
            }
        },
        || limit.is_none_or(|l| started.elapsed() < l),
    );
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("node: {e}");
            ExitCode::FAILURE
        }
    }
}
