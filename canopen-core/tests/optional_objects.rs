//! The optional communication objects of `profile::optional` on a whole node, with frames written from
//! CiA 301 (SDO expedited requests on 605h, TIME on 100h, EMCY on 080h + node) and simulated time:
//! 1002h (ERR-03), 1013h (TIME-06), 1020h (STORE-12), 1028h (EMCY-10, COB-14/15/16).
//!
//! Run: `cargo test -p canopen-core --test optional_objects` (needs the four features, the default).

use canopen_core::event::Event;
use canopen_core::node::{NoApplication, Node};
use canopen_core::od::{AbortCode, Access, OdDescribe, PdoMapping};
use canopen_core::pdo::PdoDefault;
use canopen_core::profile::NodeConfig;
use canopen_core::storage::{RamStorage, Storage};
use canopen_core::{CanFrame, Instant, NodeId, Sizes};

type TestNode<S = canopen_core::storage::NoStorage> = Node<NoApplication, Sizes, S>;

fn ms(t: u64) -> Instant {
    Instant::from_millis(t)
}

fn booted<S: Storage>(mut node: TestNode<S>) -> TestNode<S> {
    node.handle_timeout(Instant::ZERO);
    while node.poll_transmit().is_some() {}
    while node.poll_event().is_some() {}
    node
}

fn node(config: NodeConfig) -> TestNode {
    booted(Node::new(NodeId::new(5).unwrap(), config, NoApplication))
}

/// One SDO request to node 5 (605h) at `t`; the server's reply on 585h.
fn sdo<S: Storage>(node: &mut TestNode<S>, t: Instant, req: [u8; 8]) -> [u8; 8] {
    node.handle_frame(t, &CanFrame::new(0x605, &req).unwrap());
    let reply = core::iter::from_fn(|| node.poll_transmit()).find(|f| f.cob_id() == 0x585).expect("an SDO reply");
    reply.padded()
}

/// Expedited upload of `index`:`sub`: the 4 value bytes, or the abort code.
fn upload<S: Storage>(node: &mut TestNode<S>, t: Instant, index: u16, sub: u8) -> Result<u32, u32> {
    let [lo, hi] = index.to_le_bytes();
    let r = sdo(node, t, [0x40, lo, hi, sub, 0, 0, 0, 0]);
    let v = u32::from_le_bytes([r[4], r[5], r[6], r[7]]);
    if r[0] == 0x80 {
        Err(v)
    } else {
        assert_eq!(&r[1..4], &[lo, hi, sub], "reply multiplexer");
        Ok(v)
    }
}

/// Expedited download of a 4-byte `value` (`23h`, size indicated): Ok, or the abort code.
fn download<S: Storage>(node: &mut TestNode<S>, t: Instant, index: u16, sub: u8, value: u32) -> Result<(), u32> {
    let [lo, hi] = index.to_le_bytes();
    let v = value.to_le_bytes();
    let r = sdo(node, t, [0x23, lo, hi, sub, v[0], v[1], v[2], v[3]]);
    match r[0] {
        0x60 => Ok(()),
        0x80 => Err(u32::from_le_bytes([r[4], r[5], r[6], r[7]])),
        c => panic!("unexpected reply {c:02X}h"),
    }
}

/// ERR-03: 1002h is a VAR UNSIGNED32, ro, TPDO-mappable, set by the application only.
#[test]
fn manufacturer_status_err03() {
    let mut node = node(NodeConfig::DEFAULT);
    assert_eq!(upload(&mut node, ms(1), 0x1002, 0), Ok(0));
    node.set_manufacturer_status(0xCAFE_0001);
    // 40 02 10 00 → 43 02 10 00 01 00 FE CA
    assert_eq!(sdo(&mut node, ms(2), [0x40, 0x02, 0x10, 0, 0, 0, 0, 0]), [0x43, 0x02, 0x10, 0, 0x01, 0, 0xFE, 0xCA]);
    assert_eq!(download(&mut node, ms(3), 0x1002, 0, 5), Err(AbortCode::WriteOfReadOnly.code()));
    assert_eq!(upload(&mut node, ms(4), 0x1002, 1), Err(AbortCode::SubIndexDoesNotExist.code()));
    assert_eq!(node.manufacturer_status(), 0xCAFE_0001);
    let e = node.dictionary().entry(0x1002, 0).unwrap();
    assert_eq!((e.access, e.pdo), (Access::Ro, PdoMapping::Tpdo));
}

/// ERR-03: 1002h mapped into TPDO1 (1A00h:01 = 1002 0020h) goes out with the status register's value.
#[test]
fn manufacturer_status_in_a_tpdo_err03() {
    static TPDO: [PdoDefault; 1] = [PdoDefault { mapping: &[0x1002_0020], ..PdoDefault::EVENT }];
    let mut node = node(NodeConfig { tpdo: &TPDO, ..NodeConfig::DEFAULT });
    node.enter_state(canopen_core::NmtState::Operational);
    while node.poll_transmit().is_some() {} // TPDO1 as Operational starts, with 1002h = 0
    node.set_manufacturer_status(0x0403_0201);
    node.trigger_tpdo(0);
    let f = core::iter::from_fn(|| node.poll_transmit()).find(|f| f.cob_id() == 0x185).expect("TPDO1");
    assert_eq!(f.data(), &[0x01, 0x02, 0x03, 0x04]);
}

/// TIME-06: 1013h is a VAR UNSIGNED32 in µs, rw, default 0, mappable both ways; it runs on the node's clock
/// from its last set value, and TIME received (1012h bit 31) or produced (bit 30) sets it to the time of
/// day's ms × 1000 (TIME-02: consume bit 31, produce bit 30; TIME-04: the 6-byte TIME_OF_DAY frame on 100h).
#[test]
fn high_resolution_time_stamp_time06() {
    let mut node = node(NodeConfig::DEFAULT);
    let e = node.dictionary().entry(0x1013, 0).unwrap();
    assert_eq!((e.access, e.pdo, e.default), (Access::Rw, PdoMapping::Both, Some(canopen_core::od::Value::Uint(0))));
    // Default 0 at power-on (t = 0), then it runs: 7 ms later it reads 7000 µs.
    assert_eq!(upload(&mut node, ms(7), 0x1013, 0), Ok(7_000));
    // 23 13 10 00 E8 03 00 00: 1013h = 1000 µs at 10 ms; 250 µs later 1250.
    assert_eq!(download(&mut node, ms(10), 0x1013, 0, 1_000), Ok(()));
    assert_eq!(upload(&mut node, Instant::from_micros(10_250), 0x1013, 0), Ok(1_250));
    // TIME (consumed by default, 100h, DLC 6): 12:00:00.000 = 43,200,000 ms → 1013h = 43,200,000,000 mod 2³².
    let noon = (43_200_000u64 * 1000 % (1 << 32)) as u32;
    node.handle_frame(ms(20), &CanFrame::new(0x100, &[0x00, 0x2E, 0x93, 0x02, 0xB9, 0x26]).unwrap());
    assert!(core::iter::from_fn(|| node.poll_event()).any(|e| matches!(e, Event::Time(_))));
    assert_eq!(upload(&mut node, ms(21), 0x1013, 0), Ok(noon.wrapping_add(1_000)));
    // Not consumed (1012h bit 31 = 0): a TIME frame changes nothing.
    assert_eq!(download(&mut node, ms(22), 0x1012, 0, 0x0000_0100), Ok(()));
    node.handle_frame(ms(23), &CanFrame::new(0x100, &[0x10, 0x27, 0, 0, 0, 0]).unwrap());
    assert_eq!(upload(&mut node, ms(24), 0x1013, 0), Ok(noon.wrapping_add(4_000)));
    // Produced (bit 30): 10,000 ms after midnight → 1013h = 10,000,000 µs at the production.
    assert_eq!(download(&mut node, ms(25), 0x1012, 0, 0x4000_0100), Ok(()));
    assert!(node.produce_time(canopen_core::od::TimeOfDay::new(1, 10_000).unwrap()));
    assert_eq!(node.high_res_time(), 10_000_000);
    assert_eq!(upload(&mut node, ms(26), 0x1013, 0), Ok(10_001_000));
    // A wrong length is refused like any UNSIGNED32 (2B: 2 bytes).
    let r = sdo(&mut node, ms(27), [0x2B, 0x13, 0x10, 0, 1, 0, 0, 0]);
    assert_eq!(r, [0x80, 0x13, 0x10, 0, 0x13, 0x00, 0x07, 0x06]); // 0607 0013h
}

/// TIME-06: 1013h consumed through an RPDO (1600h:01 = 1013 0020h) and produced in a TPDO (1A00h:01).
#[test]
fn high_resolution_time_stamp_in_pdos_time06() {
    static RPDO: [PdoDefault; 1] = [PdoDefault { mapping: &[0x1013_0020], ..PdoDefault::EVENT }];
    static TPDO: [PdoDefault; 1] = [PdoDefault { mapping: &[0x1013_0020], ..PdoDefault::EVENT }];
    let mut node = node(NodeConfig { rpdo: &RPDO, tpdo: &TPDO, ..NodeConfig::DEFAULT });
    node.enter_state(canopen_core::NmtState::Operational);
    while node.poll_transmit().is_some() {}
    // RPDO1 on 205h carries 0x00010000 µs.
    node.handle_frame(ms(30), &CanFrame::new(0x205, &[0x00, 0x00, 0x01, 0x00]).unwrap());
    assert_eq!(node.high_res_time(), 0x0001_0000);
    node.handle_timeout(Instant::from_micros(30_500));
    node.trigger_tpdo(0);
    let f = core::iter::from_fn(|| node.poll_transmit()).find(|f| f.cob_id() == 0x185).expect("TPDO1");
    assert_eq!(f.data(), &(0x0001_0000u32 + 500).to_le_bytes());
}

/// Two 8 KiB slots: with the feature pdo-mapping-64 the communication record is over 4 KiB.
type Ram = RamStorage<8192>;

const SAVE: u32 = 0x6576_6173;
const LOAD: u32 = 0x6461_6F6C;

/// STORE-12: 1020h (sub 00h const 02h, date and time rw, default 0) is saved and loaded with the
/// configuration, and set to 0 by the device when a 1011h restore changes the boot-up configuration — live
/// at once, and in the stored record, while the rest of the stored configuration stays.
#[test]
fn verify_configuration_store12() {
    let mut node: TestNode<Ram> =
        booted(Node::with_storage(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication, Ram::new()));
    assert_eq!(upload(&mut node, ms(1), 0x1020, 0), Ok(2));
    assert_eq!(download(&mut node, ms(1), 0x1020, 0, 3), Err(AbortCode::WriteOfReadOnly.code()));
    assert_eq!(upload(&mut node, ms(1), 0x1020, 3), Err(AbortCode::SubIndexDoesNotExist.code()));
    assert_eq!((upload(&mut node, ms(1), 0x1020, 1), upload(&mut node, ms(1), 0x1020, 2)), (Ok(0), Ok(0)));
    // The configuration tool: a parameter, then 1020h (day 15,000 after 1984-01-01, 12:00), then "save".
    assert_eq!(download(&mut node, ms(2), 0x1006, 0, 10_000), Ok(()));
    assert_eq!(download(&mut node, ms(2), 0x1020, 1, 15_000), Ok(()));
    assert_eq!(download(&mut node, ms(2), 0x1020, 2, 43_200_000), Ok(()));
    assert_eq!(download(&mut node, ms(3), 0x1010, 1, SAVE), Ok(()));
    // Reset node: the stored configuration and its 1020h come back.
    node.handle_frame(ms(4), &CanFrame::new(0x000, &[0x81, 0x05]).unwrap());
    assert_eq!(upload(&mut node, ms(5), 0x1006, 0), Ok(10_000));
    assert_eq!(upload(&mut node, ms(5), 0x1020, 1), Ok(15_000));
    assert_eq!(upload(&mut node, ms(5), 0x1020, 2), Ok(43_200_000));
    // 1011h sub 03h (application defaults): the boot-up configuration changed, 1020h reads 0 at once...
    assert_eq!(download(&mut node, ms(6), 0x1011, 3, LOAD), Ok(()));
    assert_eq!((upload(&mut node, ms(6), 0x1020, 1), upload(&mut node, ms(6), 0x1020, 2)), (Ok(0), Ok(0)));
    // ...and after the next reset, while the stored communication parameters still load.
    node.handle_frame(ms(7), &CanFrame::new(0x000, &[0x81, 0x05]).unwrap());
    assert_eq!(upload(&mut node, ms(8), 0x1006, 0), Ok(10_000));
    assert_eq!((upload(&mut node, ms(8), 0x1020, 1), upload(&mut node, ms(8), 0x1020, 2)), (Ok(0), Ok(0)));
}

/// The EMCY events the node reported, as (node, error code).
fn emcy_events<S: Storage>(node: &mut TestNode<S>) -> Vec<(u8, u16)> {
    core::iter::from_fn(|| node.poll_event())
        .filter_map(|e| match e {
            Event::Emergency { node, emcy } => Some((node, emcy.code)),
            _ => None,
        })
        .collect()
}

/// An EMCY 8130h (heartbeat) with error register 11h on `can_id`.
fn emcy_frame(can_id: u16) -> CanFrame {
    CanFrame::new(can_id, &[0x30, 0x81, 0x11, 0, 0, 0, 0, 0]).unwrap()
}

/// EMCY-10, COB-14/15/16: 1028h sub 00h const 7Fh, sub n the COB-ID of node n's EMCY; only EMCYs on a
/// valid entry's CAN-ID reach the application (as node n); bit 29 and bit 30 and bits 28–11 are refused
/// with 0609 0030h, the CAN-ID does not change while valid; reset communication brings the defaults back.
#[test]
fn emergency_consumer_emcy10() {
    let mut node = node(NodeConfig::DEFAULT);
    assert_eq!(upload(&mut node, ms(1), 0x1028, 0), Ok(0x7F));
    assert_eq!(download(&mut node, ms(1), 0x1028, 0, 1), Err(AbortCode::WriteOfReadOnly.code()));
    assert_eq!(upload(&mut node, ms(1), 0x1028, 0x80), Err(AbortCode::SubIndexDoesNotExist.code()));
    // Default: entry n valid on 80h + n.
    assert_eq!(upload(&mut node, ms(1), 0x1028, 3), Ok(0x83));
    assert_eq!(upload(&mut node, ms(1), 0x1028, 127), Ok(0xFF));
    node.handle_frame(ms(2), &emcy_frame(0x083));
    assert_eq!(emcy_events(&mut node), [(3, 0x8130)]);
    // COB-16: the CAN-ID of a valid entry does not change; COB-15: no 29-bit frame; bit 30 reserved.
    assert_eq!(download(&mut node, ms(3), 0x1028, 3, 0x0000_0093), Err(AbortCode::InvalidValue.code()));
    assert_eq!(download(&mut node, ms(3), 0x1028, 3, 0x2000_0083), Err(AbortCode::InvalidValue.code()));
    assert_eq!(download(&mut node, ms(3), 0x1028, 3, 0x4000_0083), Err(AbortCode::InvalidValue.code()));
    assert_eq!(download(&mut node, ms(3), 0x1028, 3, 0x0000_0883), Err(AbortCode::InvalidValue.code()));
    assert_eq!(upload(&mut node, ms(3), 0x1028, 3), Ok(0x83));
    // Invalidate entry 3: node 3's EMCY is no longer reported; node 4's still is.
    assert_eq!(download(&mut node, ms(4), 0x1028, 3, 0x8000_0083), Ok(()));
    assert_eq!(upload(&mut node, ms(4), 0x1028, 3), Ok(0x8000_0083));
    node.handle_frame(ms(5), &emcy_frame(0x083));
    node.handle_frame(ms(5), &emcy_frame(0x084));
    assert_eq!(emcy_events(&mut node), [(4, 0x8130)]);
    // Invalidate, change, validate (COB-16): entry 3 on 2A3h, outside the EMCY range.
    assert_eq!(download(&mut node, ms(6), 0x1028, 3, 0x8000_02A3), Ok(()));
    assert_eq!(download(&mut node, ms(6), 0x1028, 3, 0x0000_02A3), Ok(()));
    let f = node.rx_filters();
    assert!(f.iter().any(|x| 0x2A3 & x.mask == x.id & x.mask), "the filters let 2A3h through: {f:?}");
    node.handle_frame(ms(7), &emcy_frame(0x2A3));
    node.handle_frame(ms(7), &emcy_frame(0x083));
    assert_eq!(emcy_events(&mut node), [(3, 0x8130)]);
    // An RTR on a listed CAN-ID and a short frame are not EMCYs (EMCY-06, CAN-07).
    node.handle_frame(ms(8), &CanFrame::new_rtr(0x084, 8).unwrap());
    node.handle_frame(ms(8), &CanFrame::new(0x084, &[0x30, 0x81]).unwrap());
    assert_eq!(emcy_events(&mut node), []);
    // Reset communication: 1028h back to its defaults.
    node.handle_frame(ms(9), &CanFrame::new(0x000, &[0x82, 0x05]).unwrap());
    assert_eq!(upload(&mut node, ms(10), 0x1028, 3), Ok(0x83));
    while node.poll_event().is_some() {}
    node.handle_frame(ms(11), &emcy_frame(0x083));
    node.handle_frame(ms(11), &emcy_frame(0x2A3));
    assert_eq!(emcy_events(&mut node), [(3, 0x8130)]);
}

/// EMCY-10: two entries on one CAN-ID report the first; a listed CAN-ID that another service owns first
/// (SYNC 080h) stays that service's.
#[test]
fn emergency_consumer_lookup_emcy10() {
    let mut node = node(NodeConfig::DEFAULT);
    for sub in [9, 10] {
        assert_eq!(download(&mut node, ms(1), 0x1028, sub, 0x8000_0000 | 0x300), Ok(()));
        assert_eq!(download(&mut node, ms(1), 0x1028, sub, 0x300), Ok(()));
    }
    node.handle_frame(ms(2), &emcy_frame(0x300));
    assert_eq!(emcy_events(&mut node), [(9, 0x8130)]);
    assert_eq!(download(&mut node, ms(3), 0x1028, 11, 0x8000_008B), Ok(()));
    assert_eq!(download(&mut node, ms(3), 0x1028, 11, 0x80), Ok(()));
    node.handle_frame(ms(4), &CanFrame::new(0x080, &[]).unwrap());
    let events: Vec<Event> = core::iter::from_fn(|| node.poll_event()).collect();
    assert!(events.iter().any(|e| matches!(e, Event::Sync { .. })), "{events:?}");
    assert!(!events.iter().any(|e| matches!(e, Event::Emergency { .. })), "{events:?}");
}

/// The EDS lists the optional objects in index order with their entries (OD-12 order, EMCY-10 defaults).
#[test]
fn optional_objects_in_the_eds() {
    let mut comm = canopen_core::profile::CommProfile::<Sizes>::for_node(NodeConfig::DEFAULT, 5);
    comm.storage_supported = false;
    let od = canopen_core::od::Merged { comm, app: NoApplication };
    let all: Vec<u16> = (0..od.object_count()).map(|n| od.object(n).unwrap().index).collect();
    assert!(all.windows(2).all(|w| w[0] < w[1]), "{all:X?}");
    let mut text = String::new();
    canopen_core::profile::eds::write_eds(&mut text, &Default::default(), &od).unwrap();
    assert_eq!(text.contains("[1028sub7F]\nParameterName=Emergency consumer 127\n"), cfg!(feature = "emcy-consumer"));
    assert_eq!(text.contains("[1020sub2]\nParameterName=Configuration time\n"), cfg!(feature = "verify-config"));
    assert_eq!(text.contains("[1013]\nParameterName=High resolution time stamp\n"), cfg!(feature = "high-res-time"));
    assert_eq!(
        text.contains("[1002]\nParameterName=Manufacturer status register\n"),
        cfg!(feature = "manufacturer-status")
    );
}

/// EMCY-10, STORE-03: 1028h is stored with the communication parameters; only the entries that differ from
/// their default go into the record (a default one loads as the default anyway), so the record stays small.
#[test]
fn emergency_consumer_is_stored_emcy10() {
    let mut node: TestNode<Ram> =
        booted(Node::with_storage(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication, Ram::new()));
    let used = |node: &TestNode<Ram>, slot: u8| node.storage().slot(slot).iter().rposition(|&b| b != 0xFF);
    assert_eq!(download(&mut node, ms(1), 0x1010, 2, SAVE), Ok(())); // slot 0: every 1028h entry default
    assert_eq!(download(&mut node, ms(1), 0x1028, 3, 0x8000_0083), Ok(()));
    assert_eq!(download(&mut node, ms(1), 0x1010, 2, SAVE), Ok(())); // slot 1: entry 3 changed
    let (all_default, one_changed) = (used(&node, 0).unwrap(), used(&node, 1).unwrap());
    assert_eq!(one_changed - all_default, 8, "one item (index, sub, length, 4 bytes) more, not 127");
    node.handle_frame(ms(2), &CanFrame::new(0x000, &[0x82, 0x05]).unwrap()); // reset communication
    assert_eq!(upload(&mut node, ms(3), 0x1028, 3), Ok(0x8000_0083));
    assert_eq!(upload(&mut node, ms(3), 0x1028, 4), Ok(0x84));
    while node.poll_event().is_some() {}
    node.handle_frame(ms(4), &emcy_frame(0x083));
    node.handle_frame(ms(4), &emcy_frame(0x084));
    assert_eq!(emcy_events(&mut node), [(4, 0x8130)]);
}
