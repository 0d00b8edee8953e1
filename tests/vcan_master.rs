//! `canopen-master` on real SocketCAN against the example node's dictionary (`examples/common/io_module.rs`,
//! on the tokio runner of `canopen-socketcan`) and a plain core node: ten nodes read at once, a read from a
//! stopped node that times out on time while its heartbeats arrive, 64 KiB block transfers byte-exact and
//! the throughput of 1 MiB each way.
//!
//! `#[ignore]`d with the reason, so a plain `cargo test` lists them as ignored; scripts/test-interop.sh runs
//! them inside the VM with `--include-ignored`, where a missing interface fails them.

#[path = "../examples/common/io_module.rs"]
mod io_module;
#[path = "common/vcan.rs"]
mod vcan;

use std::time::{Duration, Instant};

use canopen_core::node::NoApplication;
use canopen_core::profile::{Identity, NodeConfig};
use canopen_core::{Node, NodeId};
use canopen_master::{Master, Mode, NmtCommand, StateCode, BLOCK};
use canopen_socketcan::{run_tokio, MutexShared, NotifyWake};
use io_module::CONFIG;

use vcan::{require_vcan, IFACE};

/// Runs `node` on vcan0 (the tokio runner) until the task is aborted.
fn spawn_node<N>(node: N) -> tokio::task::JoinHandle<()>
where
    N: canopen_core::node::SansIo + canopen_socketcan::ReceiveFilters + Send + 'static,
{
    tokio::spawn(async move {
        let (shared, wake) = (MutexShared::new(node), NotifyWake::new());
        let r = run_tokio(&shared, IFACE, &wake, &|_| {}).await;
        panic!("node runner stopped: {r:?}");
    })
}

fn example_node(id: u8, heartbeat_ms: u16) -> tokio::task::JoinHandle<()> {
    let identity = Identity { serial: 1000 + u32::from(id), ..CONFIG.identity };
    spawn_node(io_module::new_node(
        NodeId::new(id).unwrap(),
        NodeConfig { heartbeat_time_ms: heartbeat_ms, identity, ..CONFIG },
    ))
}

struct Nodes(Vec<tokio::task::JoinHandle<()>>);

impl Drop for Nodes {
    fn drop(&mut self) {
        self.0.iter().for_each(|t| t.abort());
    }
}

/// Ten example nodes (11..=20) and one plain core node (21) read at once on one socket: each answer is the
/// asked node's own serial number (1018h:04), so no transfer took another's frames.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
#[ignore = "needs SocketCAN (vcan0): scripts/test-interop.sh runs it (scripts/vcan-run.sh)"]
async fn ten_nodes_read_at_once_on_one_socket() {
    require_vcan();
    let mut nodes = Nodes((11..=20).map(|id| example_node(id, 0)).collect());
    let core = NodeConfig { identity: Identity { serial: 1021, ..CONFIG.identity }, ..NodeConfig::DEFAULT };
    nodes.0.push(spawn_node(Node::<NoApplication>::new(NodeId::new(21).unwrap(), core, NoApplication)));
    tokio::time::sleep(Duration::from_millis(300)).await;
    let master = Master::open(IFACE).unwrap();
    for _round in 0..5 {
        let mut set = tokio::task::JoinSet::new();
        for node in 11..=21u8 {
            let m = master.clone();
            set.spawn(async move { (node, m.read::<u32>(node, 0x1018, 4).await) });
        }
        while let Some(r) = set.join_next().await {
            let (node, serial) = r.unwrap();
            assert_eq!(serial.unwrap(), 1000 + u32::from(node), "node {node}");
        }
    }
    assert_eq!(master.read::<String>(21, 0x1008, 0).await.unwrap(), NodeConfig::DEFAULT.device_name);
    assert_eq!(master.scan(Duration::from_millis(300)).await.unwrap(), (11..=21).collect::<Vec<_>>());
}

/// SDO-31: the read from a Stopped node ends with 0504 0000h one time-out (300 ms) after it started, while the
/// node's heartbeats (every 20 ms) keep arriving on the same socket and another node is read meanwhile.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
#[ignore = "needs SocketCAN (vcan0): scripts/test-interop.sh runs it (scripts/vcan-run.sh)"]
async fn a_stopped_nodes_read_times_out_while_its_heartbeats_arrive() {
    require_vcan();
    let _nodes = Nodes(vec![example_node(31, 20), example_node(32, 20)]);
    let master = Master::open(IFACE).unwrap().with_sdo_timeout(Duration::from_millis(300));
    master.wait_for_state(31, StateCode::PreOperational, Duration::from_secs(2)).await.unwrap();
    master.nmt(31, NmtCommand::Stop).await.unwrap();
    master.wait_for_state(31, StateCode::Stopped, Duration::from_secs(1)).await.unwrap();
    let mut heartbeats = master.heartbeats();
    let other = {
        let m = master.clone();
        tokio::spawn(async move {
            let mut n = 0;
            for _ in 0..20 {
                m.read::<u32>(32, 0x1000, 0).await.unwrap();
                n += 1;
                tokio::time::sleep(Duration::from_millis(10)).await;
            }
            n
        })
    };
    let start = Instant::now();
    let e = master.read::<u32>(31, 0x1000, 0).await.unwrap_err();
    let took = start.elapsed();
    assert!(e.is_timeout(), "{e}");
    assert!(took >= Duration::from_millis(300) && took < Duration::from_millis(450), "took {took:?}");
    let mut from_31 = 0;
    while let Ok(hb) = heartbeats.try_recv() {
        from_31 += usize::from(hb.node == 31);
    }
    assert!(from_31 >= 8, "{from_31} heartbeats of node 31 during the 300 ms");
    assert_eq!(other.await.unwrap(), 20);
}

fn pattern(len: usize, seed: u32) -> Vec<u8> {
    (0..len as u32).map(|i| (i.wrapping_mul(2_654_435_761).wrapping_add(seed) >> 13) as u8).collect()
}

/// 64 KiB through the 2005h DOMAIN byte-exact in block mode with CRC and segmented, two nodes at the same
/// time; then 1 MiB each way (16 × 64 KiB, block with CRC) to one node, timed: the figures are printed
/// (`--nocapture`) for the README and scripts/bench-vcan.sh.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
#[ignore = "needs SocketCAN (vcan0): scripts/test-interop.sh runs it (scripts/vcan-run.sh)"]
async fn block_transfers_are_byte_exact_and_timed() {
    require_vcan();
    let _nodes = Nodes(vec![example_node(41, 0), example_node(42, 0)]);
    tokio::time::sleep(Duration::from_millis(300)).await;
    let master = Master::open(IFACE).unwrap();
    let (a, b) = (pattern(65_536, 1), pattern(65_536, 2));
    let (ra, rb) =
        tokio::join!(master.download(41, 0x2005, 0, &a, BLOCK), master.download(42, 0x2005, 0, &b, Mode::Segmented));
    ra.unwrap();
    rb.unwrap();
    let (ua, ub) = tokio::join!(master.upload(41, 0x2005, 0, Mode::Segmented), master.upload(42, 0x2005, 0, BLOCK));
    assert!(ua.unwrap() == a, "node 41's DOMAIN differs");
    assert!(ub.unwrap() == b, "node 42's DOMAIN differs");

    let (mut down, mut up) = (Duration::ZERO, Duration::ZERO);
    for round in 0..16 {
        let data = pattern(65_536, 10 + round);
        let t = Instant::now();
        master.download(41, 0x2005, 0, &data, BLOCK).await.unwrap();
        down += t.elapsed();
        let t = Instant::now();
        let back = master.upload(41, 0x2005, 0, BLOCK).await.unwrap();
        up += t.elapsed();
        assert!(back == data, "round {round} differs");
    }
    let kib_s = |d: Duration| 1024.0 / d.as_secs_f64();
    println!(
        "canopen-master over vcan, 1 MiB block+CRC (16 x 64 KiB): download {:.1} KiB/s, upload {:.1} KiB/s",
        kib_s(down),
        kib_s(up)
    );
}
