//! The master against `canopen-core` nodes on the in-memory bus, in simulated time (tokio's paused clock):
//! many nodes at once, time-outs that frames of other nodes never extend, cancellation, NMT and heartbeat,
//! LSS commissioning.

use std::time::Duration;

use canopen_core::node::NoApplication;
use canopen_core::profile::{Identity, NodeConfig};
use canopen_core::{Node, NodeId};
use canopen_master::sim::{SimBus, SimNode};
use canopen_master::{Error, Master, NmtCommand, StateCode};

type Plain = Node<NoApplication>;

fn config(serial: u32, heartbeat_ms: u16) -> NodeConfig {
    NodeConfig {
        heartbeat_time_ms: heartbeat_ms,
        identity: Identity { vendor_id: 0x1234, product_code: 7, revision: 1, serial },
        ..NodeConfig::DEFAULT
    }
}

fn spawn(bus: &SimBus, id: u8, heartbeat_ms: u16) -> SimNode<Plain> {
    bus.spawn_node(Node::new(NodeId::new(id).unwrap(), config(1000 + u32::from(id), heartbeat_ms), NoApplication))
}

/// Ten nodes read at once on one socket: every answer is the asked node's own (1018h:04 = 1000 + node), so
/// no transfer took another's frames, and all of them ran at the same time (the ten reads take one round
/// trip of simulated time, not ten).
#[tokio::test(start_paused = true)]
async fn ten_nodes_read_at_once_each_get_their_own_answer() {
    let bus = SimBus::new();
    let _nodes: Vec<_> = (1..=10).map(|id| spawn(&bus, id, 0)).collect();
    let master = Master::new(bus.port());
    let start = tokio::time::Instant::now();
    let mut set = tokio::task::JoinSet::new();
    for node in 1..=10u8 {
        let m = master.clone();
        set.spawn(async move { (node, m.read::<u32>(node, 0x1018, 4).await) });
    }
    let mut seen = Vec::new();
    while let Some(r) = set.join_next().await {
        let (node, serial) = r.unwrap();
        assert_eq!(serial.unwrap(), 1000 + u32::from(node), "node {node}");
        seen.push(node);
    }
    seen.sort_unstable();
    assert_eq!(seen, (1..=10).collect::<Vec<_>>());
    // The in-memory bus has no latency: all ten were answered without the clock moving.
    assert!(start.elapsed() < Duration::from_millis(1), "{:?}", start.elapsed());
}

/// SDO-31: a read from a Stopped node (no SDO in Stopped, NMT-20) ends with the master's time-out abort
/// 0504 0000h exactly one time-out after it started, although the node's heartbeats (every 10 ms) and the
/// answers of another node arrive on the same socket meanwhile.
#[tokio::test(start_paused = true)]
async fn a_stopped_nodes_read_times_out_on_time_while_its_heartbeats_arrive() {
    let bus = SimBus::new();
    let (_a, _b) = (spawn(&bus, 3, 10), spawn(&bus, 4, 10));
    let master = Master::new(bus.port()).with_sdo_timeout(Duration::from_millis(100));
    master.nmt(3, NmtCommand::Stop).await.unwrap();
    master.wait_for_state(3, StateCode::Stopped, Duration::from_secs(1)).await.unwrap();
    let mut heartbeats = master.heartbeats();
    let start = tokio::time::Instant::now();
    let busy = master.clone();
    let other = tokio::spawn(async move {
        let mut n = 0;
        while start.elapsed() < Duration::from_millis(150) {
            busy.read::<u32>(4, 0x1000, 0).await.unwrap();
            n += 1;
            tokio::time::sleep(Duration::from_millis(5)).await;
        }
        n
    });
    let e = master.read::<u32>(3, 0x1000, 0).await.unwrap_err();
    let took = start.elapsed();
    assert!(e.is_timeout(), "{e}");
    assert_eq!(e.abort_code(), Some(0x0504_0000));
    assert!(took >= Duration::from_millis(100) && took < Duration::from_millis(101), "took {took:?}");
    let mut from_3 = 0;
    while let Ok(hb) = heartbeats.try_recv() {
        if hb.node == 3 {
            assert_eq!(hb.state(), Some(StateCode::Stopped));
            from_3 += 1;
        }
    }
    assert!(from_3 >= 9, "only {from_3} heartbeats of node 3 during the transfer");
    assert!(other.await.unwrap() >= 10);
}

/// A transfer whose future is dropped sends the server an abort, and the next transfer to the same node
/// works (the server is not left waiting in its transfer).
#[tokio::test(start_paused = true)]
async fn a_dropped_transfer_aborts_and_the_next_one_works() {
    let bus = SimBus::new();
    let node = spawn(&bus, 6, 0);
    let watcher = Master::new(bus.port());
    let mut frames = watcher.frames();
    let master = Master::new(bus.port());
    // Stop the node so that the upload hangs, drop it after 10 ms.
    master.nmt(6, NmtCommand::Stop).await.unwrap();
    tokio::time::sleep(Duration::from_millis(1)).await;
    let r = tokio::time::timeout(Duration::from_millis(10), master.upload(6, 0x1008, 0, canopen_master::BLOCK)).await;
    assert!(r.is_err());
    tokio::time::sleep(Duration::from_millis(1)).await;
    let mut abort = None;
    while let Ok(f) = frames.try_recv() {
        if f.cob_id() == 0x606 && f.data()[0] == 0x80 {
            abort = Some(f);
        }
    }
    let abort = abort.expect("no abort frame after the transfer was dropped");
    assert_eq!(abort.data(), &[0x80, 0x08, 0x10, 0x00, 0x00, 0x00, 0x00, 0x08]);
    master.nmt(6, NmtCommand::EnterPreOperational).await.unwrap();
    tokio::time::sleep(Duration::from_millis(1)).await;
    let name: String = master.read(6, 0x1008, 0).await.unwrap();
    assert_eq!(name, NodeConfig::DEFAULT.device_name);
    drop(node);
}

/// Invalid arguments are errors, never panics; a node that is not there is a time-out abort.
#[tokio::test(start_paused = true)]
async fn bad_arguments_are_errors() {
    let bus = SimBus::new();
    let master = Master::new(bus.port()).with_sdo_timeout(Duration::from_millis(20));
    assert!(matches!(master.read::<u8>(0, 0x1000, 0).await, Err(Error::InvalidArgument(_))));
    assert!(matches!(master.read::<u8>(128, 0x1000, 0).await, Err(Error::InvalidArgument(_))));
    assert!(master.read::<u8>(9, 0x1000, 0).await.unwrap_err().is_timeout());
    assert!(master.start_sync(Duration::from_millis(1), 1).is_err());
    assert!(master.start_sync(Duration::ZERO, 0).is_err());
}

/// NMT-07..NMT-13 through the master; the heartbeat stream reports every state (NMT-25, HB-02).
#[tokio::test(start_paused = true)]
async fn nmt_commands_move_the_node_and_the_heartbeats_report_it() {
    let bus = SimBus::new();
    let _n = spawn(&bus, 8, 20);
    let master = Master::new(bus.port());
    let d = Duration::from_secs(1);
    master.wait_for_state(8, StateCode::PreOperational, d).await.unwrap();
    master.nmt(8, NmtCommand::Start).await.unwrap();
    master.wait_for_state(8, StateCode::Operational, d).await.unwrap();
    master.nmt(0, NmtCommand::Stop).await.unwrap();
    master.wait_for_state(8, StateCode::Stopped, d).await.unwrap();
    master.nmt(8, NmtCommand::ResetCommunication).await.unwrap();
    master.wait_for_state(8, StateCode::BootUp, d).await.unwrap();
    assert!(matches!(master.wait_for_state(9, StateCode::BootUp, d).await, Err(Error::Timeout)));
}

/// LSS (CiA 305) through the core's master: two unconfigured slaves get node-IDs 20h and 21h by
/// commissioning (fastscan, configure, back to waiting), then boot with them and answer SDO.
#[tokio::test(start_paused = true)]
async fn lss_commissioning_gives_every_unconfigured_slave_a_node_id() {
    let bus = SimBus::new();
    let unconfigured = |serial| bus.spawn_node(Plain::new_unconfigured(config(serial, 50), NoApplication));
    let (_a, _b) = (unconfigured(0xA5A5_0001), unconfigured(0x0000_0F02));
    let master = Master::new(bus.port());
    let mut heartbeats = master.heartbeats();
    let assigned = {
        let mut lss = master.lss().await.unwrap().with_timeout(Duration::from_millis(10));
        lss.commission(NodeId::new(0x20).unwrap(), false).await.unwrap()
    };
    let mut ids: Vec<_> = assigned.iter().map(|(id, node)| (id.serial, node.get())).collect();
    ids.sort_unstable();
    assert_eq!(ids.len(), 2, "{ids:?}");
    let mut nodes: Vec<_> = ids.iter().map(|&(_, n)| n).collect();
    nodes.sort_unstable();
    assert_eq!(nodes, vec![0x20, 0x21]);
    for (serial, node) in ids {
        assert_eq!(master.read::<u32>(node, 0x1018, 4).await.unwrap(), serial);
    }
    let hb = heartbeats.recv().await.unwrap();
    assert!(hb.node == 0x20 || hb.node == 0x21, "{hb:?}");
    // Nobody is left unconfigured.
    assert_eq!(master.lss().await.unwrap().with_timeout(Duration::from_millis(10)).fastscan().await.unwrap(), None);
}
