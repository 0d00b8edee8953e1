//! `canopen-master` on real SocketCAN against the example node's dictionary (`examples/common/io_module.rs`,
//! on the tokio runner of `canopen-socketcan`) and a plain core node: ten nodes read at once, a read from a
//! stopped node that times out on time while its heartbeats arrive, 64 KiB block transfers byte-exact,
//! the throughput of 1 MiB each way, and the master surviving its interface going down and up (on vcan1,
//! so that the tests on vcan0 are not disturbed; `ip link` needs root, as inside the VM).
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
use canopen_master::{Error, Master, Mode, NmtCommand, SocketCan, StateCode, BLOCK};
use canopen_socketcan::AdapterEvent;
use canopen_socketcan::{run_tokio, MutexShared, NotifyWake};
use io_module::CONFIG;

use vcan::{require_vcan, IFACE};

/// Runs `node` on vcan0 (the tokio runner) until the task is aborted.
fn spawn_node<N>(node: N) -> tokio::task::JoinHandle<()>
where
    N: canopen_core::node::SansIo + canopen_socketcan::ReceiveFilters + Send + 'static,
{
    spawn_node_on(IFACE, node)
}

/// Runs `node` on `iface` (the tokio runner, which waits out the interface going down) until aborted.
fn spawn_node_on<N>(iface: &'static str, node: N) -> tokio::task::JoinHandle<()>
where
    N: canopen_core::node::SansIo + canopen_socketcan::ReceiveFilters + Send + 'static,
{
    tokio::spawn(async move {
        let (shared, wake) = (MutexShared::new(node), NotifyWake::new());
        let r = run_tokio(&shared, iface, &wake, &|_| {}).await;
        panic!("node runner stopped: {r:?}");
    })
}

fn example_node(id: u8, heartbeat_ms: u16) -> tokio::task::JoinHandle<()> {
    example_node_on(IFACE, id, heartbeat_ms)
}

fn example_node_on(iface: &'static str, id: u8, heartbeat_ms: u16) -> tokio::task::JoinHandle<()> {
    let identity = Identity { serial: 1000 + u32::from(id), ..CONFIG.identity };
    spawn_node_on(
        iface,
        io_module::new_node(
            NodeId::new(id).unwrap(),
            NodeConfig { heartbeat_time_ms: heartbeat_ms, identity, ..CONFIG },
        ),
    )
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

fn ip(args: &str) -> bool {
    std::process::Command::new("ip").args(args.split(' ')).status().is_ok_and(|s| s.success())
}

/// Whether `e` is the interface being down, as the master reports it: a transfer waiting for frames is cut
/// off by the receive side ([`Error::Interrupted`]), one that was sending gets the send's `ENETDOWN`.
fn is_down_error(e: &Error) -> bool {
    match e {
        Error::Interrupted(why) => why.contains("vcan1") && why.contains("down"),
        Error::Io(io) => io.raw_os_error() == Some(libc::ENETDOWN),
        _ => false,
    }
}

/// The interface goes down under the master (`ip link set vcan1 down`) and comes back: a read waiting for a
/// node that never answers and a block upload in flight both fail at once with the interface's error (not
/// after their 5 s SDO time-out), a transfer started while it is down fails at once too, the adapter events
/// say `InterfaceDown` then `Reopened`, and the same master (no new one) reads and moves 64 KiB byte-exact
/// again afterwards.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
#[ignore = "needs SocketCAN (vcan1) and root for ip link: scripts/test-interop.sh runs it (scripts/vcan-run.sh)"]
async fn the_master_survives_its_interface_going_down_and_up() {
    const IFC: &str = "vcan1";
    assert!(std::path::Path::new("/sys/class/net/vcan1").exists(), "no vcan1: run scripts/test-interop.sh");
    let _nodes = Nodes(vec![example_node_on(IFC, 51, 0)]);
    tokio::time::sleep(Duration::from_millis(300)).await;
    let io = SocketCan::open(IFC).unwrap();
    let mut events = io.adapter_events();
    let master = Master::new(io).with_sdo_timeout(Duration::from_secs(5));
    assert_eq!(master.read::<u32>(51, 0x1018, 4).await.unwrap(), 1051);
    let data = pattern(65_536, 7);
    master.download(51, 0x2005, 0, &data, BLOCK).await.unwrap();

    // Node 99 does not exist: this read waits for an answer until the interface goes down.
    let waiting = tokio::spawn({
        let m = master.clone();
        async move { m.read::<u32>(99, 0x1000, 0).await }
    });
    let busy = tokio::spawn({
        let m = master.clone();
        async move {
            loop {
                if let Err(e) = m.upload(51, 0x2005, 0, BLOCK).await {
                    return e;
                }
            }
        }
    });
    tokio::time::sleep(Duration::from_millis(200)).await;
    assert!(ip(&format!("link set {IFC} down")), "ip link set down failed (needs root, as inside the VM)");
    let t = Instant::now();
    let e = waiting.await.unwrap().unwrap_err();
    assert!(
        matches!(&e, Error::Interrupted(why) if why.contains("vcan1") && why.contains("down")),
        "{e:?} after {:?}",
        t.elapsed()
    );
    let e = busy.await.unwrap();
    assert!(is_down_error(&e), "{e:?}");
    assert!(t.elapsed() < Duration::from_secs(1), "the transfers failed only after {:?}", t.elapsed());
    let e = master.read::<u32>(51, 0x1018, 4).await.unwrap_err();
    assert!(is_down_error(&e), "a transfer while the interface is down: {e:?}");
    assert!(t.elapsed() < Duration::from_secs(2), "{:?}", t.elapsed());

    assert!(ip(&format!("link set {IFC} up")));
    let mut seen = Vec::new();
    tokio::time::timeout(Duration::from_secs(3), async {
        while !seen.iter().any(|e| matches!(e, AdapterEvent::Reopened { .. })) {
            seen.push(events.recv().await.unwrap());
        }
    })
    .await
    .unwrap_or_else(|_| panic!("no Reopened event within 3 s: {seen:?}"));
    let down = seen.iter().position(|e| matches!(e, AdapterEvent::InterfaceDown { iface, .. } if iface == IFC));
    assert!(down.is_some_and(|d| d < seen.len() - 1), "InterfaceDown before Reopened: {seen:?}");
    // The node's runner polls for the interface too (every 100 ms): give it time to reopen.
    tokio::time::sleep(Duration::from_millis(300)).await;
    assert_eq!(master.read::<u32>(51, 0x1018, 4).await.unwrap(), 1051);
    let again = pattern(65_536, 8);
    master.download(51, 0x2005, 0, &again, BLOCK).await.unwrap();
    assert!(master.upload(51, 0x2005, 0, BLOCK).await.unwrap() == again, "the DOMAIN differs after the reopen");
}
