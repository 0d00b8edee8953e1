//! A node built without an optional service (canopen-core's Cargo features, `lib.rs`): the service is
//! silent on the bus and its objects do not exist (SDO abort 0602 0000h, OD-16; not in the EDS). Each test
//! runs only in a build without its feature (`cargo test -p canopen-core --no-default-features`, or a
//! feature left out); in the default build every service is in and these tests are compiled out.
#![allow(dead_code, unused_imports)]

use canopen_core::node::{NoApplication, Node};
use canopen_core::profile::eds::{write_eds, EdsInfo};
use canopen_core::profile::{CommProfile, NodeConfig};
use canopen_core::{CanFrame, Event, Instant, NodeId, Sizes};

type N = Node<NoApplication>;

/// Node 5, booted, guarding and TIME consumption configured in its defaults, queues drained.
fn booted() -> N {
    booted_with(NodeConfig { guard_time_ms: 100, life_time_factor: 3, ..NodeConfig::DEFAULT })
}

/// Node 5 with `cfg`, booted, queues drained.
fn booted_with(cfg: NodeConfig) -> N {
    let mut node: N = Node::new(NodeId::new(5).unwrap(), cfg, NoApplication);
    node.handle_timeout(Instant::ZERO);
    drain(&mut node);
    node
}

fn drain(node: &mut N) -> (Vec<CanFrame>, Vec<Event>) {
    (core::iter::from_fn(|| node.poll_transmit()).collect(), core::iter::from_fn(|| node.poll_event()).collect())
}

/// The node's answer to one SDO request on 605h.
fn sdo(node: &mut N, req: [u8; 8]) -> Vec<CanFrame> {
    node.handle_frame(Instant::from_millis(1), &CanFrame::new(0x605, &req).unwrap());
    drain(node).0
}

fn abort(index: u16, code: u32) -> CanFrame {
    let [i0, i1] = index.to_le_bytes();
    let [c0, c1, c2, c3] = code.to_le_bytes();
    CanFrame::new(0x585, &[0x80, i0, i1, 0, c0, c1, c2, c3]).unwrap()
}

fn eds() -> String {
    let od: CommProfile<Sizes> = CommProfile::for_node(NodeConfig::DEFAULT, 5);
    let mut s = String::new();
    write_eds(&mut s, &EdsInfo::DEFAULT, &od).unwrap();
    s
}

/// GUARD-05 without `guarding`: a guarding RTR on 705h gets no reply, 100Ch/100Dh do not exist (OD-16)
/// and are not in the EDS.
#[test]
#[cfg(not(feature = "guarding"))]
fn without_guarding() {
    let mut node = booted();
    node.handle_frame(Instant::from_millis(1), &CanFrame::new_rtr(0x705, 1).unwrap());
    assert_eq!(drain(&mut node), (vec![], vec![]));
    for index in [0x100C, 0x100D] {
        let [i0, i1] = u16::to_le_bytes(index);
        assert_eq!(sdo(&mut node, [0x40, i0, i1, 0, 0, 0, 0, 0]), [abort(index, 0x0602_0000)]);
        assert_eq!(sdo(&mut node, [0x2F, i0, i1, 0, 1, 0, 0, 0]), [abort(index, 0x0602_0000)]);
    }
    // No life-guarding time-out either, however long the master stays away.
    node.handle_timeout(Instant::from_millis(10_000));
    assert!(drain(&mut node).1.is_empty());
    let eds = eds();
    assert!(!eds.contains("[100C]") && !eds.contains("[100D]") && !eds.contains("=0x100C"), "{eds}");
}

/// TIME-04 without `time`: a TIME frame on 100h is no event, 1012h does not exist and is not in the EDS.
#[test]
#[cfg(not(feature = "time"))]
fn without_time() {
    let mut node = booted();
    node.enter_state(canopen_core::NmtState::Operational);
    drain(&mut node);
    node.handle_frame(Instant::from_millis(1), &CanFrame::new(0x100, &[0x00, 0x2E, 0x93, 0x02, 0xB9, 0x26]).unwrap());
    assert_eq!(drain(&mut node), (vec![], vec![]));
    assert_eq!(sdo(&mut node, [0x40, 0x12, 0x10, 0, 0, 0, 0, 0]), [abort(0x1012, 0x0602_0000)]);
    assert_eq!(sdo(&mut node, [0x23, 0x12, 0x10, 0, 0, 1, 0, 0x80]), [abort(0x1012, 0x0602_0000)]);
    let eds = eds();
    assert!(!eds.contains("[1012]") && !eds.contains("=0x1012"), "{eds}");
}

/// CiA 305 without `lss`: requests on 7E5h get no answer, the node keeps its node-ID.
#[test]
#[cfg(not(feature = "lss"))]
fn without_lss() {
    let mut node = booted();
    for req in [[0x04, 1, 0, 0, 0, 0, 0, 0], [0x11, 0x22, 0, 0, 0, 0, 0, 0], [0x5E, 0, 0, 0, 0, 0, 0, 0]] {
        node.handle_frame(Instant::from_millis(1), &CanFrame::new(0x7E5, &req).unwrap());
    }
    assert_eq!(drain(&mut node), (vec![], vec![]));
    assert_eq!(node.node_id().get(), 5);
    assert!(!node.rx_filters().iter().any(|f| f.id == 0x7E5));
}

/// SDO-09 without `sdo-block`: block download and upload initiate are refused with 0504 0001h for their
/// object, and the server serves the next request.
#[test]
#[cfg(not(feature = "sdo-block"))]
fn without_block_transfer() {
    let mut node = booted();
    assert_eq!(sdo(&mut node, [0xC6, 0x17, 0x10, 0, 2, 0, 0, 0]), [abort(0x1017, 0x0504_0001)]);
    assert_eq!(sdo(&mut node, [0xA4, 0x00, 0x10, 0, 0x7F, 0, 0, 0]), [abort(0x1000, 0x0504_0001)]);
    let reply = sdo(&mut node, [0x40, 0x17, 0x10, 0, 0, 0, 0, 0]);
    assert_eq!(reply, [CanFrame::new(0x585, &[0x4B, 0x17, 0x10, 0, 0, 0, 0, 0]).unwrap()]);
}

/// SYNC-03 without `sync-producer`: a node configured to produce SYNC (1005h bit 30, 1006h = 1 ms) is a
/// consumer only: no SYNC goes out, 1005h reads without the gen bit, and writing the gen bit is refused
/// with 0609 0030h; a consumer's COB-ID is still accepted.
#[test]
#[cfg(not(feature = "sync-producer"))]
fn without_sync_producer() {
    use canopen_core::{cob::CobIdEntry, sync::SyncParams};
    let sync = SyncParams { cob_id: CobIdEntry::from_raw(0x4000_0080), period_us: 1000, ..SyncParams::DEFAULT };
    let mut node = booted_with(NodeConfig { sync, ..NodeConfig::DEFAULT });
    for t in 1..=10 {
        node.handle_timeout(Instant::from_millis(t));
    }
    assert!(drain(&mut node).0.is_empty());
    let upload = sdo(&mut node, [0x40, 0x05, 0x10, 0, 0, 0, 0, 0]);
    assert_eq!(upload, [CanFrame::new(0x585, &[0x43, 0x05, 0x10, 0, 0x80, 0, 0, 0]).unwrap()]);
    let generate = sdo(&mut node, [0x23, 0x05, 0x10, 0, 0x80, 0, 0, 0x40]);
    assert_eq!(generate, [abort(0x1005, 0x0609_0030)]);
    let consumer = sdo(&mut node, [0x23, 0x05, 0x10, 0, 0x81, 0, 0, 0]);
    assert_eq!(consumer, [CanFrame::new(0x585, &[0x60, 0x05, 0x10, 0, 0, 0, 0, 0]).unwrap()]);
}

/// PDO-36 without `pdo-bit-mapping`: a mapping entry that is not a whole object of whole bytes (4 bits of
/// 1001h) does not resolve, the whole object (8 bits) does. A configured mapping of such an entry leaves
/// its TPDO silent on entering Operational (PDO-28: an event-driven TPDO goes out at once when it is
/// valid); with `pdo-dynamic-mapping` an SDO write of the entry is refused with 0604 0041h.
#[test]
#[cfg(not(feature = "pdo-bit-mapping"))]
fn without_pdo_bit_mapping() {
    use canopen_core::{pdo::PdoDefault, NmtState};
    const PART: [PdoDefault; 1] = [PdoDefault { mapping: &[0x1001_0004], ..PdoDefault::EVENT }];
    const WHOLE: [PdoDefault; 1] = [PdoDefault { mapping: &[0x1001_0008], ..PdoDefault::EVENT }];
    for (tpdo, sent) in [(&PART, vec![]), (&WHOLE, vec![CanFrame::new(0x185, &[0]).unwrap()])] {
        let mut node = booted_with(NodeConfig { tpdo, ..NodeConfig::DEFAULT });
        node.enter_state(NmtState::Operational);
        assert_eq!(drain(&mut node).0, sent);
    }
    if cfg!(feature = "pdo-dynamic-mapping") {
        let mut node = booted();
        let part = sdo(&mut node, [0x23, 0x00, 0x1A, 0x01, 0x04, 0x00, 0x01, 0x10]);
        assert_eq!(part, [CanFrame::new(0x585, &[0x80, 0x00, 0x1A, 0x01, 0x41, 0x00, 0x04, 0x06]).unwrap()]);
        let whole = sdo(&mut node, [0x23, 0x00, 0x1A, 0x01, 0x08, 0x00, 0x01, 0x10]);
        assert_eq!(whole, [CanFrame::new(0x585, &[0x60, 0x00, 0x1A, 0x01, 0, 0, 0, 0]).unwrap()]);
    }
}

/// PDO-29 without `pdo-rtr` (the PDO read service is optional): TPDO 1's default COB-ID has bit 30 set (no
/// RTR allowed), a remote frame on its CAN-ID gets no reply in Operational, clearing bit 30 and the RTR-only
/// types FCh/FDh are refused with 0609 0030h (PDO-15, PDO-18).
#[test]
#[cfg(not(feature = "pdo-rtr"))]
fn without_pdo_rtr() {
    use canopen_core::{pdo::PdoDefault, NmtState};
    const TPDO: [PdoDefault; 1] = [PdoDefault { mapping: &[0x1001_0008], ..PdoDefault::EVENT }];
    let mut node: N =
        Node::new(NodeId::new(5).unwrap(), NodeConfig { tpdo: &TPDO, ..NodeConfig::DEFAULT }, NoApplication);
    node.handle_timeout(Instant::ZERO);
    node.enter_state(NmtState::Operational);
    drain(&mut node);
    node.handle_frame(Instant::from_millis(1), &CanFrame::new_rtr(0x185, 1).unwrap());
    assert_eq!(drain(&mut node), (vec![], vec![]));
    let cob = sdo(&mut node, [0x40, 0x00, 0x18, 0x01, 0, 0, 0, 0]);
    assert_eq!(cob, [CanFrame::new(0x585, &[0x43, 0x00, 0x18, 0x01, 0x85, 0x01, 0x00, 0x40]).unwrap()]);
    let refused = |sub: u8| CanFrame::new(0x585, &[0x80, 0x00, 0x18, sub, 0x30, 0x00, 0x09, 0x06]).unwrap();
    assert_eq!(sdo(&mut node, [0x23, 0x00, 0x18, 0x01, 0x85, 0x01, 0x00, 0x80]), [refused(1)]);
    for ttype in [0xFC, 0xFD] {
        assert_eq!(sdo(&mut node, [0x2F, 0x00, 0x18, 0x02, ttype, 0, 0, 0]), [refused(2)]);
    }
}

/// An optional object this build leaves out: SDO upload and download get 0602 0000h (OD-16) and the EDS
/// does not list it.
fn absent(node: &mut N, index: u16) {
    let [i0, i1] = u16::to_le_bytes(index);
    assert_eq!(sdo(node, [0x40, i0, i1, 0, 0, 0, 0, 0]), [abort(index, 0x0602_0000)], "{index:04X}h");
    assert_eq!(sdo(node, [0x2F, i0, i1, 0, 0, 0, 0, 0]), [abort(index, 0x0602_0000)], "{index:04X}h");
    let eds = eds();
    let section = format!("[{index:04X}]");
    let listed = format!("=0x{index:04X}\n");
    assert!(!eds.contains(&section) && !eds.contains(&listed), "{index:04X}h in {eds}");
}

/// ERR-04 without `error-history` (1003h is optional): no 1003h; an error still gives its EMCY (EMCY-07)
/// and sets 1001h (ERR-02).
#[test]
#[cfg(not(feature = "error-history"))]
fn without_error_history() {
    let mut node = booted();
    absent(&mut node, 0x1003);
    assert!(node.raise_error(0x5000, [0; 5]));
    let (frames, _) = drain(&mut node);
    assert_eq!(frames, [CanFrame::new(0x85, &[0x00, 0x50, 0x01, 0, 0, 0, 0, 0]).unwrap()]); // generic error
    let register = sdo(&mut node, [0x40, 0x01, 0x10, 0, 0, 0, 0, 0]);
    assert_eq!(register, [CanFrame::new(0x585, &[0x4F, 0x01, 0x10, 0, 0x01, 0, 0, 0]).unwrap()]);
}

/// DEV-04 without `manufacturer-strings` (1008h–100Ah are optional): the objects do not exist, whatever
/// the configuration names.
#[test]
#[cfg(not(feature = "manufacturer-strings"))]
fn without_manufacturer_strings() {
    let cfg = NodeConfig { device_name: "dev", hardware_version: "hw", software_version: "sw", ..NodeConfig::DEFAULT };
    let mut node = booted_with(cfg);
    for index in [0x1008, 0x1009, 0x100A] {
        absent(&mut node, index);
    }
}

/// EMCY-09 without `emcy-inhibit` (1015h is optional): the configured inhibit time is not applied, so two
/// errors raised together give two EMCYs at once.
#[test]
#[cfg(not(feature = "emcy-inhibit"))]
fn without_emcy_inhibit() {
    let cfg = NodeConfig { emcy_inhibit_100us: 100, ..NodeConfig::DEFAULT };
    let mut node = booted_with(cfg);
    absent(&mut node, 0x1015);
    assert_eq!(node.comm_profile().params.emcy_inhibit_100us, 0);
    node.raise_error(0x5000, [0; 5]);
    node.raise_error(0x6000, [0; 5]);
    node.handle_timeout(Instant::from_millis(1));
    let (frames, _) = drain(&mut node);
    assert_eq!(frames.iter().map(|f| f.cob_id()).collect::<Vec<_>>(), [0x85, 0x85]);
}

/// SYNC-10 without `sync-counter` (1019h is conditional on a counter): a configured overflow value is not
/// applied, a SYNC of DLC 0 is a SYNC and one carrying a counter is the wrong length (SYNC-14, EMCY 8240h).
#[test]
#[cfg(not(feature = "sync-counter"))]
fn without_sync_counter() {
    use canopen_core::sync::SyncParams;
    let sync = SyncParams { counter_overflow: 5, ..SyncParams::DEFAULT };
    let mut node = booted_with(NodeConfig { sync, ..NodeConfig::DEFAULT });
    absent(&mut node, 0x1019);
    node.handle_frame(Instant::from_millis(2), &CanFrame::new(0x80, &[]).unwrap());
    assert_eq!(drain(&mut node), (vec![], vec![Event::Sync { counter: None }]));
    node.handle_frame(Instant::from_millis(3), &CanFrame::new(0x80, &[1]).unwrap());
    let (frames, _) = drain(&mut node);
    // 8240h, register generic + communication, the received DLC (1) in the manufacturer field.
    assert_eq!(frames, [CanFrame::new(0x85, &[0x40, 0x82, 0x11, 1, 0, 0, 0, 0]).unwrap()]);
}

/// SYNC-08 without `sync-window` (1007h is optional): no 1007h, and a configured window is not applied.
#[test]
#[cfg(not(feature = "sync-window"))]
fn without_sync_window() {
    use canopen_core::sync::SyncParams;
    let sync = SyncParams { window_us: 100, ..SyncParams::DEFAULT };
    let mut node = booted_with(NodeConfig { sync, ..NodeConfig::DEFAULT });
    absent(&mut node, 0x1007);
    let window = node.comm_profile().params.sync.window_us;
    assert_eq!(window, 0);
}

/// ERR-10/NMT-26 without `error-behaviour` (1029h is optional): a communication error (bus-off) in
/// Operational leads to Pre-operational, 1029h's default, whatever the configuration asked (2, Stopped).
#[test]
#[cfg(not(feature = "error-behaviour"))]
fn without_error_behaviour() {
    use canopen_core::{bus::BusState, NmtState};
    let cfg = NodeConfig { error_behaviour: 2, ..NodeConfig::DEFAULT };
    let mut node: N = Node::new(NodeId::new(5).unwrap(), cfg, NoApplication);
    node.handle_timeout(Instant::ZERO);
    node.enter_state(NmtState::Operational);
    drain(&mut node);
    absent(&mut node, 0x1029);
    assert_eq!(node.comm_profile().params.error_behaviour, 0);
    node.set_bus_state(Instant::from_millis(1), BusState::BusOff);
    assert_eq!(node.state(), NmtState::PreOperational);
}

/// PDO-30 without `pdo-dynamic-mapping` (the mapping is fixed): the mapping records are const. Writing the
/// count or an entry is refused with 0601 0002h whatever the PDO's state, the configured mapping stays and
/// its TPDO still works, and the EDS says AccessType=const.
#[test]
#[cfg(not(feature = "pdo-dynamic-mapping"))]
fn without_pdo_dynamic_mapping() {
    use canopen_core::{pdo::PdoDefault, NmtState};
    const TPDO: [PdoDefault; 1] = [PdoDefault { mapping: &[0x1001_0008], ..PdoDefault::EVENT }];
    let mut node = booted_with(NodeConfig { tpdo: &TPDO, ..NodeConfig::DEFAULT });
    let read_only = |sub: u8| CanFrame::new(0x585, &[0x80, 0x00, 0x1A, sub, 0x02, 0x00, 0x01, 0x06]).unwrap();
    let disable = sdo(&mut node, [0x23, 0x00, 0x18, 0x01, 0x85, 0x01, 0x00, 0xC0]); // PDO-35 step 1
    assert_eq!(disable, [CanFrame::new(0x585, &[0x60, 0x00, 0x18, 0x01, 0, 0, 0, 0]).unwrap()]);
    assert_eq!(sdo(&mut node, [0x2F, 0x00, 0x1A, 0x00, 0, 0, 0, 0]), [read_only(0)]);
    assert_eq!(sdo(&mut node, [0x23, 0x00, 0x1A, 0x01, 0x10, 0x00, 0x17, 0x10]), [read_only(1)]);
    let entry = sdo(&mut node, [0x40, 0x00, 0x1A, 0x01, 0, 0, 0, 0]);
    assert_eq!(entry, [CanFrame::new(0x585, &[0x43, 0x00, 0x1A, 0x01, 0x08, 0x00, 0x01, 0x10]).unwrap()]);
    let enable = sdo(&mut node, [0x23, 0x00, 0x18, 0x01, 0x85, 0x01, 0x00, 0x40]);
    assert_eq!(enable, [CanFrame::new(0x585, &[0x60, 0x00, 0x18, 0x01, 0, 0, 0, 0]).unwrap()]);
    node.enter_state(NmtState::Operational);
    assert_eq!(drain(&mut node).0, [CanFrame::new(0x185, &[0]).unwrap()]); // PDO-28: 1001h, the mapping kept
    let eds = eds();
    for sub in ["[1A00sub0]", "[1A00sub1]", "[1600sub0]", "[1600sub8]"] {
        let section = &eds[eds.find(sub).unwrap_or_else(|| panic!("{sub} in {eds}"))..];
        let section = &section[..section.find("\n\n").unwrap_or(section.len())];
        assert!(section.contains("AccessType=const"), "{section}");
    }
}

/// STORE-01 without `store-restore` (1010h and 1011h are optional): neither object exists, so "save" and
/// "load" are refused with 0602 0000h and the EDS does not list them.
#[test]
#[cfg(not(feature = "store-restore"))]
fn without_store_restore() {
    let mut node = booted();
    for index in [0x1010, 0x1011] {
        absent(&mut node, index);
        let [i0, i1] = u16::to_le_bytes(index);
        let command = sdo(&mut node, [0x23, i0, i1, 0x01, b's', b'a', b'v', b'e']);
        let refused = CanFrame::new(0x585, &[0x80, i0, i1, 0x01, 0x00, 0x00, 0x02, 0x06]).unwrap();
        assert_eq!(command, [refused], "{index:04X}h");
    }
}
