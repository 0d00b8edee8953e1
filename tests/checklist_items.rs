//! Requirements (`docs/CONFORMANCE.md`) that no other test exercised (issue 21, item 4), through whole nodes on the in-memory bus
//! with simulated time: PDO-10 (RPDO side), SYNC-15, OD-07, OD-10, OD-17, OD-19, DT-04, DT-09, DT-16, DT-18,
//! DT-19, NMT-19, NMT-20, SDO-04, SDO-10, SDO-34, ERR-12, DEV-02. Each test names the items it proves.
//!
//! CAN-05 (ISO 11898-2 transceiver, optional galvanic isolation) is hardware below the CAN controller: no
//! software of this crate can meet or break it, so no test here claims it.

mod common;

use canopen::core::{
    node::Node,
    od::{DataType, Merged, ObjectCode, OdDescribe, VisibleString},
    pdo::PdoDefault,
    profile::{
        eds::{write_eds, EdsInfo},
        CommProfile, NodeConfig,
    },
    sync::SyncParams,
    CanFrame, Instant, NmtState, NodeId, Sizes,
};
use canopen::ObjectDictionary;
use common::{frame, Bus};

#[derive(ObjectDictionary, Default, Debug)]
#[od(crate = "canopen::core")]
pub struct App {
    #[od(index = 0x2000, access = "rw", pdo = "both")]
    byte: u8,
    #[od(index = 0x2001, access = "rw", pdo = "both", max = 1000)]
    word: u16,
    #[od(index = 0x2002, access = "rw", pdo = "both")]
    signed: i16,
    #[od(index = 0x2003, access = "rw", pdo = "both")]
    long: u32,
    #[od(index = 0x2004, access = "rw")]
    text: VisibleString<8>,
    #[od(index = 0x2005, access = "ro")]
    fixed: u8,
}

type TestNode = Node<App>;

const RPDO_BYTE: &[PdoDefault] = &[PdoDefault { mapping: &[0x2000_0008], ..PdoDefault::EVENT }];
const TPDO_SYNC: &[PdoDefault] = &[PdoDefault { transmission_type: 1, mapping: &[0x2000_0008], ..PdoDefault::EVENT }];

fn node(id: u8, cfg: NodeConfig) -> TestNode {
    Node::new(NodeId::new(id).unwrap(), cfg, App::default())
}

/// Every SDO server reply (58xh) to `req`.
fn replies(bus: &mut Bus<TestNode>, req: &str) -> Vec<CanFrame> {
    bus.take_master_rx();
    bus.inject(frame(req));
    bus.take_master_rx().into_iter().map(|s| s.frame).filter(|f| f.cob_id() & 0x780 == 0x580).collect()
}

/// The single SDO reply to `req`.
fn sdo(bus: &mut Bus<TestNode>, req: &str) -> CanFrame {
    let r = replies(bus, req);
    assert_eq!(r.len(), 1, "{req}: {r:?}");
    r[0]
}

/// The abort frame the server must answer to `req` with `code`.
fn abort(req: &str, code: u32) -> CanFrame {
    let f = frame(req);
    let d = f.data();
    let c = code.to_le_bytes();
    CanFrame::new(f.cob_id() - 0x80, &[0x80, d[1], d[2], d[3], c[0], c[1], c[2], c[3]]).unwrap()
}

/// Sends writes that must all be confirmed.
fn sdo_ok(bus: &mut Bus<TestNode>, reqs: &[&str]) {
    for r in reqs {
        let f = frame(r);
        let d = f.data();
        let ok = CanFrame::new(f.cob_id() - 0x80, &[0x60, d[1], d[2], d[3], 0, 0, 0, 0]).unwrap();
        assert_eq!(sdo(bus, r), ok, "{r}");
    }
}

fn at_us(bus: &mut Bus<TestNode>, us: u64) {
    bus.run_until(Instant::from_micros(us));
}

/// PDO-10 (RPDO 1400h+k sub 03h inhibit time, 100 µs units): the value is kept and read back, it cannot be
/// changed while the RPDO is valid (0609 0030h, value unchanged), only while it is not; sub 04h and 06h do
/// not exist for an RPDO (0609 0011h). With simulated time: an event-driven RPDO takes effect on reception
/// ("the data is applied immediately"), so frames closer together than the inhibit time are all applied; the
/// inhibit time is the producer's, never a reason for the consumer to drop data.
#[test]
fn rpdo_inhibit_time_pdo_10() {
    let mut bus = Bus::booted(vec![node(5, NodeConfig { rpdo: RPDO_BYTE, ..NodeConfig::DEFAULT })]);
    assert_eq!(sdo(&mut bus, "605 [8] 40 00 14 03 00 00 00 00"), frame("585 [8] 4B 00 14 03 00 00 00 00"));
    let while_valid = "605 [8] 2B 00 14 03 0A 00 00 00";
    assert_eq!(sdo(&mut bus, while_valid), abort(while_valid, 0x0609_0030));
    assert_eq!(sdo(&mut bus, "605 [8] 40 00 14 03 00 00 00 00"), frame("585 [8] 4B 00 14 03 00 00 00 00"));
    for sub in [4u8, 6] {
        let req = format!("605 [8] 40 00 14 {sub:02X} 00 00 00 00");
        assert_eq!(sdo(&mut bus, &req), abort(&req, 0x0609_0011), "{req}");
    }
    // Not valid: the inhibit time (1 ms) may change; valid again: it stays and is refused again.
    sdo_ok(&mut bus, &["605 [8] 23 00 14 01 05 02 00 80", "605 [8] 2B 00 14 03 0A 00 00 00"]);
    assert_eq!(sdo(&mut bus, "605 [8] 40 00 14 03 00 00 00 00"), frame("585 [8] 4B 00 14 03 0A 00 00 00"));
    sdo_ok(&mut bus, &["605 [8] 23 00 14 01 05 02 00 00"]);
    assert_eq!(sdo(&mut bus, "605 [8] 40 00 14 03 00 00 00 00"), frame("585 [8] 4B 00 14 03 0A 00 00 00"));
    let change = "605 [8] 2B 00 14 03 14 00 00 00";
    assert_eq!(sdo(&mut bus, change), abort(change, 0x0609_0030));
    assert_eq!(sdo(&mut bus, "605 [8] 40 00 14 03 00 00 00 00"), frame("585 [8] 4B 00 14 03 0A 00 00 00"));
    assert_eq!(bus.stations[0].params().rpdo_comm[0].inhibit_100us, 10);
    // Reception: three frames 200 µs apart, all inside one inhibit time, each applied at once.
    bus.inject(frame("000 [2] 01 05"));
    let t0 = bus.now.as_micros();
    for (i, v) in [0x11u8, 0x22, 0x33].into_iter().enumerate() {
        at_us(&mut bus, t0 + 200 * i as u64);
        bus.inject(CanFrame::new(0x205, &[v]).unwrap());
        assert_eq!(bus.stations[0].app().byte, v, "RPDO {i} at +{} µs", 200 * i);
    }
}

/// SYNC-15: SYNC is an unconfirmed broadcast with one producer on a high-priority ID, and consumers tolerate
/// jitter. Node 1 produces SYNC every 10 ms (1005h bit 30, 1006h); node 2 consumes it with a synchronous TPDO
/// (type 1). Only node 1 ever sends on 080h, the frames carry no data (no counter), nothing answers a SYNC
/// (the only frames after each are node 2's TPDOs), and 080h is above every other COB-ID on the bus but NMT.
/// Then the master produces SYNCs with ±40 % jitter: node 2 answers every one and raises no EMCY.
#[test]
fn sync_unconfirmed_single_producer_jitter_sync_15() {
    let producer = NodeConfig {
        sync: SyncParams {
            cob_id: canopen::core::cob::CobIdEntry::from_raw(0x4000_0080),
            period_us: 10_000,
            ..SyncParams::DEFAULT
        },
        ..NodeConfig::DEFAULT
    };
    let consumer = NodeConfig { tpdo: TPDO_SYNC, ..NodeConfig::DEFAULT };
    let mut bus = Bus::booted(vec![node(1, producer), node(2, consumer)]);
    bus.inject(frame("000 [2] 01 00"));
    let boot_log = std::mem::take(&mut bus.log);
    bus.run_for_ms(95);
    let syncs: Vec<_> = bus.log.iter().filter(|s| s.frame.cob_id() == 0x080).collect();
    assert!(syncs.len() >= 9, "{} SYNCs in 95 ms", syncs.len());
    assert!(syncs.iter().all(|s| s.from == common::Sender::Station(0) && s.frame.data().is_empty()));
    // Unconfirmed: node 1 sends nothing but SYNC; node 2 only its TPDO, once per SYNC.
    assert!(bus.log.iter().filter(|s| s.from == common::Sender::Station(0)).all(|s| s.frame.cob_id() == 0x080));
    let tpdos = bus.frames_on(0x182);
    assert_eq!(tpdos.len(), syncs.len());
    assert!(bus.log.iter().all(|s| s.frame.cob_id() == 0x080 || s.frame.cob_id() == 0x182));
    // High priority: below every other COB-ID on the bus but NMT's 000h (boot-ups, SDO, TPDOs, EMCY).
    let mut ids: Vec<u16> = boot_log.iter().chain(&bus.log).map(|s| s.frame.cob_id()).collect();
    // Jitter: the master takes over SYNC (node 1 stops producing), period 10 ms ± 4 ms.
    sdo_ok(&mut bus, &["601 [8] 23 05 10 00 80 00 00 00"]);
    ids.extend(bus.log.iter().map(|s| s.frame.cob_id()));
    ids.retain(|&id| id != 0x000 && id != 0x080);
    assert!(ids.contains(&0x701) && ids.contains(&0x581) && ids.contains(&0x182), "{ids:03X?}");
    assert!(ids.iter().all(|&id| id > 0x080), "{ids:03X?}");
    bus.log.clear();
    let start = bus.now.as_micros();
    let offsets_ms = [0u64, 6, 20, 24, 38, 50, 56, 70, 84, 90];
    for off in offsets_ms {
        at_us(&mut bus, start + off * 1000);
        bus.inject(frame("080 [0]"));
    }
    bus.run_for_ms(20);
    assert_eq!(bus.frames_on(0x182).len(), offsets_ms.len());
    assert!(bus.frames_on(0x082).is_empty(), "EMCY on jitter: {:?}", bus.frames_on(0x082));
    assert!(bus.log.iter().filter(|s| s.frame.cob_id() == 0x080).all(|s| s.from == common::Sender::Master));
}

fn merged() -> Merged<CommProfile<Sizes>, App> {
    let cfg = NodeConfig { rpdo: RPDO_BYTE, tpdo: TPDO_SYNC, ..NodeConfig::DEFAULT };
    Merged { comm: CommProfile::for_node(cfg, 5), app: App::default() }
}

/// The `[section]` of an EDS as its `n=0xIIII` index list.
fn eds_list(eds: &str, section: &str) -> Vec<u16> {
    let start = eds.find(&format!("[{section}]\n")).expect(section);
    eds[start..]
        .lines()
        .skip(2)
        .take_while(|l| !l.is_empty() && !l.starts_with('['))
        .map(|l| u16::from_str_radix(l.split("=0x").nth(1).expect(l), 16).expect(l))
        .collect()
}

/// OD-10 (entry categories): the mandatory objects 1000h, 1001h, 1018h are on every node, readable, and the
/// EDS files them under `[MandatoryObjects]` only; the optional ones (1005h, 1017h, the PDOs) under
/// `[OptionalObjects]`; the application's under `[ManufacturerObjects]`; every object is in exactly one list.
/// Conditional: an RPDO's mapping (1600h) exists exactly where its communication parameter (1400h) does.
/// OD-14: every PDO has both records (1400h+k with 1600h+k, 1800h+k with 1A00h+k).
/// OD-12: 1000h, 1001h and 1018h are present (and readable over SDO) on a node configured with nothing.
#[test]
fn entry_categories_od_10() {
    let od = merged();
    let mut eds = String::new();
    write_eds(&mut eds, &EdsInfo::DEFAULT, &od).unwrap();
    let (m, o, a) =
        (eds_list(&eds, "MandatoryObjects"), eds_list(&eds, "OptionalObjects"), eds_list(&eds, "ManufacturerObjects"));
    assert_eq!(m, [0x1000, 0x1001, 0x1018]);
    for i in [0x1005, 0x1017, 0x1400, 0x1600, 0x1800, 0x1A00] {
        assert!(o.contains(&i), "{i:04X} optional: {o:04X?}");
    }
    assert_eq!(a, [0x2000, 0x2001, 0x2002, 0x2003, 0x2004, 0x2005]);
    let all: Vec<u16> = (0..od.object_count()).filter_map(|n| od.object(n)).map(|o| o.index).collect();
    assert_eq!(m.len() + o.len() + a.len(), all.len());
    for i in &all {
        assert_eq!([&m, &o, &a].iter().filter(|l| l.contains(i)).count(), 1, "{i:04X}");
    }
    for k in 0..0x200u16 {
        assert_eq!(all.contains(&(0x1400 + k)), all.contains(&(0x1600 + k)), "RPDO {k}");
        assert_eq!(all.contains(&(0x1800 + k)), all.contains(&(0x1A00 + k)), "TPDO {k}");
    }
    let mut bus = Bus::booted(vec![node(5, NodeConfig::DEFAULT)]);
    for req in ["605 [8] 40 00 10 00 00 00 00 00", "605 [8] 40 01 10 00 00 00 00 00", "605 [8] 40 18 10 01 00 00 00 00"]
    {
        assert_eq!(sdo(&mut bus, req).data()[0] & 0xE0, 0x40, "{req}");
    }
}

/// OD-07 (no nesting: each sub-index is exactly one data field of a basic type) and DT-18 (the predefined
/// record layouts): walking the whole dictionary, every object is a VAR with only sub 00h, or an ARRAY/RECORD
/// whose sub 00h is an UNSIGNED8 count; every sub-entry has one basic data type (below 0020h:
/// no record or array inside). 1400h is PDO_COMMUNICATION_PARAMETER (0020h), 1600h PDO_MAPPING (0021h), 1018h
/// IDENTITY (0023h), sub by sub. PDO-03: each PDO is described by exactly those two records.
#[test]
fn no_nesting_and_predefined_records_od_07_dt_18() {
    let od = merged();
    for n in 0..od.object_count() {
        let o = od.object(n).unwrap();
        let subs: Vec<_> = (0..=255u8).filter_map(|s| od.entry(o.index, s)).collect();
        assert_eq!(subs.len(), usize::from(o.subs), "{:04X}", o.index);
        for e in &subs {
            assert!((e.data_type as u16) < 0x20, "{:04X}:{:02X} is not a basic type", e.index, e.sub);
        }
        match o.code {
            ObjectCode::Var | ObjectCode::Domain => assert_eq!(subs.iter().map(|e| e.sub).collect::<Vec<_>>(), [0]),
            ObjectCode::Array | ObjectCode::Record => {
                assert_eq!((subs[0].sub, subs[0].data_type), (0, DataType::Unsigned8), "{:04X}", o.index);
                // Sub 00h is a count (of sub-indices, or for 1003h/mappings of used entries), never data.
                assert!(subs[1..].iter().all(|e| e.sub > 0), "{:04X}", o.index);
            }
            c => panic!("{:04X}: object code {c:?}", o.index),
        }
    }
    let layout = |index: u16| -> Vec<(u8, DataType)> {
        (0..=255u8).filter_map(|s| od.entry(index, s)).map(|e| (e.sub, e.data_type)).collect()
    };
    use DataType::{Unsigned16 as U16, Unsigned32 as U32, Unsigned8 as U8};
    assert_eq!(layout(0x1400), [(0, U8), (1, U32), (2, U8), (3, U16), (5, U16)]);
    assert_eq!(layout(0x1800), [(0, U8), (1, U32), (2, U8), (3, U16), (5, U16), (6, U8)]);
    let map = layout(0x1600);
    assert_eq!(map[0], (0, U8));
    assert!(map[1..].iter().enumerate().all(|(i, &(s, t))| usize::from(s) == i + 1 && t == U32));
    assert_eq!(layout(0x1018), [(0, U8), (1, U32), (2, U32), (3, U32), (4, U32)]);
}

/// OD-17: the reserved indices of the communication area answer 0602 0000h to reads and writes, on a node
/// with every service configured.
#[test]
fn reserved_indices_od_17() {
    let mut bus = Bus::booted(vec![node(5, NodeConfig { rpdo: RPDO_BYTE, tpdo: TPDO_SYNC, ..NodeConfig::DEFAULT })]);
    for index in [0x1004u16, 0x100B, 0x100E, 0x100F, 0x102A, 0x1100, 0x11FF, 0x1300, 0x13FF] {
        let [lo, hi] = index.to_le_bytes();
        for req in [
            format!("605 [8] 40 {lo:02X} {hi:02X} 00 00 00 00 00"),
            format!("605 [8] 2F {lo:02X} {hi:02X} 00 01 00 00 00"),
        ] {
            assert_eq!(sdo(&mut bus, &req), abort(&req, 0x0602_0000), "{req}");
        }
    }
}

/// OD-19 (Table 74): access and size of the standard communication objects as the spec lists them: 1000h
/// UNSIGNED32 ro, 1001h UNSIGNED8 ro, 1005h UNSIGNED32 rw, 1017h UNSIGNED16 rw, 1018h:00 UNSIGNED8 const and
/// 1018h:01 UNSIGNED32 ro, 1014h UNSIGNED32 rw. A read answers with the type's size (n in the expedited
/// response); a write to a read-only entry is 0601 0002h.
#[test]
fn communication_object_table_od_19() {
    let mut bus = Bus::booted(vec![node(5, NodeConfig::DEFAULT)]);
    // (index, sub, size in bytes, writable)
    for (index, sub, size, rw) in [
        (0x1000u16, 0u8, 4u8, false),
        (0x1001, 0, 1, false),
        (0x1005, 0, 4, true),
        (0x1014, 0, 4, true),
        (0x1017, 0, 2, true),
        (0x1018, 0, 1, false),
        (0x1018, 1, 4, false),
    ] {
        let [lo, hi] = index.to_le_bytes();
        let read = sdo(&mut bus, &format!("605 [8] 40 {lo:02X} {hi:02X} {sub:02X} 00 00 00 00"));
        assert_eq!(read.data()[0], 0x43 | ((4 - size) << 2), "{index:04X}:{sub:02X} read {read:?}");
        let v = read.data()[4..8].to_vec();
        // Write back the value just read, with the type's size.
        let cmd = 0x23 | ((4 - size) << 2);
        let write = format!(
            "605 [8] {cmd:02X} {lo:02X} {hi:02X} {sub:02X} {:02X} {:02X} {:02X} {:02X}",
            v[0], v[1], v[2], v[3]
        );
        let r = sdo(&mut bus, &write);
        if rw {
            assert_eq!(r.data()[0], 0x60, "{write}: {r:?}");
        } else {
            assert_eq!(r, abort(&write, 0x0601_0002), "{write}");
        }
    }
}

/// DT-04 (VOIDn: a field of n bits whose value is undefined): an RPDO mapping 8 bits of 2000h, a 4-bit dummy
/// (0005h, used as VOID4) and 2001h. Whatever the dummy bits hold, the two objects get the same values.
#[test]
fn void_field_in_rpdo_dt_04() {
    const RPDO: &[PdoDefault] =
        &[PdoDefault { mapping: &[0x2000_0008, 0x0005_0004, 0x2001_0010], ..PdoDefault::EVENT }];
    let mut bus = Bus::booted(vec![node(5, NodeConfig { rpdo: RPDO, ..NodeConfig::DEFAULT })]);
    bus.inject(frame("000 [2] 01 05"));
    // bits 0..8 = 2000h, 8..12 = VOID4, 12..28 = 2001h = 0x0123.
    for void in 0..16u32 {
        let raw: u32 = 0x42 | (void << 8) | (0x0123 << 12);
        let b = raw.to_le_bytes();
        bus.stations[0].app_mut().byte = 0;
        bus.stations[0].app_mut().word = 0;
        bus.inject(CanFrame::new(0x205, &b[..4]).unwrap());
        assert_eq!((bus.stations[0].app().byte, bus.stations[0].app().word), (0x42, 0x0123), "VOID4 = {void:X}");
    }
}

/// DT-09 (a compound value is the concatenation of its components' bits in declaration order, then
/// little-endian): the spec's example STRUCT { INTEGER10 x = −423, UNSIGNED5 u = 30 } is 59 7Ah. A TPDO
/// mapping the low 10 bits of 2002h (x) then 5 bits of 2000h (u) is that compound.
#[test]
fn compound_bit_concatenation_dt_09() {
    const TPDO: &[PdoDefault] =
        &[PdoDefault { transmission_type: 1, mapping: &[0x2002_000A, 0x2000_0005], ..PdoDefault::EVENT }];
    let mut bus = Bus::booted(vec![node(5, NodeConfig { tpdo: TPDO, ..NodeConfig::DEFAULT })]);
    bus.stations[0].app_mut().signed = -423;
    bus.stations[0].app_mut().byte = 30;
    bus.inject(frame("000 [2] 01 05"));
    bus.inject(frame("080 [0]"));
    assert_eq!(bus.frames_on(0x185).last().map(|f| f.1.clone()), Some(vec![0x59, 0x7A]));
}

/// DT-16 (NIL is the empty bit sequence): an empty VISIBLE_STRING is written with a segmented download of
/// size 0 and read back as size 0 with no data bytes (one segment with n = 7).
#[test]
fn empty_value_dt_16() {
    let mut bus = Bus::booted(vec![node(5, NodeConfig::DEFAULT)]);
    bus.stations[0].app_mut().text = VisibleString::literal("abc");
    assert_eq!(sdo(&mut bus, "605 [8] 21 04 20 00 00 00 00 00"), frame("585 [8] 60 04 20 00 00 00 00 00"));
    assert_eq!(sdo(&mut bus, "605 [8] 0F 00 00 00 00 00 00 00"), frame("585 [8] 20 00 00 00 00 00 00 00"));
    assert_eq!(bus.stations[0].app().text.as_bytes(), b"");
    // Size indicated, 0 bytes; the one segment holds no data (n = 7) and is the last (c = 1).
    assert_eq!(sdo(&mut bus, "605 [8] 40 04 20 00 00 00 00 00"), frame("585 [8] 41 04 20 00 00 00 00 00"));
    assert_eq!(sdo(&mut bus, "605 [8] 60 00 00 00 00 00 00 00"), frame("585 [8] 0F 00 00 00 00 00 00 00"));
}

/// DT-19 (a device supports only the data types it uses): this dictionary provides no DEFTYPE or DEFSTRUCT
/// entries (0001h–025Fh); reading them is 0602 0000h, and every type the EDS names is one an entry uses.
#[test]
fn only_used_data_types_dt_19() {
    let mut bus = Bus::booted(vec![node(5, NodeConfig::DEFAULT)]);
    for index in [0x0001u16, 0x0005, 0x0007, 0x0009, 0x0020, 0x0023, 0x0040, 0x0060, 0x025F] {
        let [lo, hi] = index.to_le_bytes();
        let req = format!("605 [8] 40 {lo:02X} {hi:02X} 00 00 00 00 00");
        assert_eq!(sdo(&mut bus, &req), abort(&req, 0x0602_0000), "{req}");
    }
    let od = merged();
    let od = &od;
    let used: Vec<u16> = (0..od.object_count())
        .filter_map(|n| od.object(n))
        .flat_map(|o| (0..=255u8).filter_map(move |s| od.entry(o.index, s)))
        .map(|e| e.data_type as u16)
        .collect();
    let mut eds = String::new();
    write_eds(&mut eds, &EdsInfo::DEFAULT, od).unwrap();
    for line in eds.lines().filter_map(|l| l.strip_prefix("DataType=0x")) {
        let t = u16::from_str_radix(line, 16).unwrap();
        assert!(used.contains(&t), "EDS names type {t:04X} that no entry uses");
    }
}

/// NMT-19 (Pre-operational: SDO yes, PDO no) and NMT-20 (Operational: every service, and the application may
/// still refuse particular writes): in Pre-operational an RPDO is not applied and a SYNC makes no TPDO while
/// SDO reads and writes work; in Operational the same RPDO is applied, the SYNC makes the TPDO, SDO still
/// works, and a write above the application's limit (2001h max 1000) is refused with 0609 0031h.
#[test]
fn pre_operational_and_operational_services_nmt_19_nmt_20() {
    let cfg = NodeConfig { rpdo: RPDO_BYTE, tpdo: TPDO_SYNC, ..NodeConfig::DEFAULT };
    let mut bus = Bus::booted(vec![node(5, cfg)]);
    assert_eq!(bus.stations[0].state(), NmtState::PreOperational);
    bus.log.clear();
    bus.inject(frame("205 [1] 77"));
    bus.inject(frame("080 [0]"));
    assert_eq!(bus.stations[0].app().byte, 0);
    assert!(bus.frames_on(0x185).is_empty());
    sdo_ok(&mut bus, &["605 [8] 2F 00 20 00 05 00 00 00", "605 [8] 2B 01 20 00 10 00 00 00"]);
    assert_eq!(sdo(&mut bus, "605 [8] 40 00 20 00 00 00 00 00"), frame("585 [8] 4F 00 20 00 05 00 00 00"));
    bus.inject(frame("000 [2] 01 05"));
    assert_eq!(bus.stations[0].state(), NmtState::Operational);
    bus.inject(frame("205 [1] 77"));
    assert_eq!(bus.stations[0].app().byte, 0x77);
    bus.inject(frame("080 [0]"));
    assert_eq!(bus.frames_on(0x185), [(0, vec![0x77])]);
    sdo_ok(&mut bus, &["605 [8] 2B 01 20 00 E8 03 00 00"]);
    let over = "605 [8] 2B 01 20 00 E9 03 00 00";
    assert_eq!(sdo(&mut bus, over), abort(over, 0x0609_0031));
    assert_eq!(bus.stations[0].app().word, 1000);
}

/// SDO-04 (expedited transfer of up to 4 bytes): downloads of 1, 2 and 4 bytes with the size indicated, and
/// of 4 bytes without (22h), each confirmed and stored; uploads of 1-, 2- and 4-byte objects are expedited
/// responses with the right n.
#[test]
fn expedited_transfers_sdo_04() {
    let mut bus = Bus::booted(vec![node(5, NodeConfig::DEFAULT)]);
    sdo_ok(
        &mut bus,
        &["605 [8] 2F 00 20 00 AB 00 00 00", "605 [8] 2B 01 20 00 CD 01 00 00", "605 [8] 23 03 20 00 01 02 03 04"],
    );
    let a = bus.stations[0].app();
    assert_eq!((a.byte, a.word, a.long), (0xAB, 0x01CD, 0x0403_0201));
    sdo_ok(&mut bus, &["605 [8] 22 03 20 00 0D 0C 0B 0A"]);
    assert_eq!(bus.stations[0].app().long, 0x0A0B_0C0D);
    assert_eq!(sdo(&mut bus, "605 [8] 40 00 20 00 00 00 00 00"), frame("585 [8] 4F 00 20 00 AB 00 00 00"));
    assert_eq!(sdo(&mut bus, "605 [8] 40 01 20 00 00 00 00 00"), frame("585 [8] 4B 01 20 00 CD 01 00 00"));
    assert_eq!(sdo(&mut bus, "605 [8] 40 03 20 00 00 00 00 00"), frame("585 [8] 43 03 20 00 0D 0C 0B 0A"));
}

/// SDO-10 (a response to an initiate request repeats its index and sub-index): expedited and segmented
/// download and upload, block download and block upload initiates, and the abort answering an initiate.
#[test]
fn initiate_responses_repeat_multiplexer_sdo_10() {
    let mut bus = Bus::booted(vec![node(5, NodeConfig::DEFAULT)]);
    for req in [
        "605 [8] 2F 00 20 00 01 00 00 00", // expedited download
        "605 [8] 40 03 20 00 00 00 00 00", // expedited upload
        "605 [8] 21 04 20 00 02 00 00 00", // segmented download
        "605 [8] 40 04 20 00 00 00 00 00", // upload of a string
        "605 [8] C6 04 20 00 02 00 00 00", // block download, CRC, size 2
        "605 [8] A4 03 20 00 10 00 00 00", // block upload, CRC, blksize 16
        "605 [8] 40 05 20 01 00 00 00 00", // sub 01h of a VAR: abort
        "605 [8] 2F 05 20 00 01 00 00 00", // write to ro: abort
    ] {
        let r = sdo(&mut bus, req);
        assert_eq!(r.data()[1..4], frame(req).data()[1..4], "{req}: {r:?}");
        // End whatever the initiate opened before the next one.
        bus.inject(frame("605 [8] 80 00 00 00 00 00 04 05"));
        bus.take_master_rx();
    }
}

/// SDO-34 (the abort code is a mandatory field): every abort the server sends is 8 bytes with a 4-byte code
/// from Table 22, never 0, here one per kind of fault.
#[test]
fn abort_always_carries_a_code_sdo_34() {
    let mut bus = Bus::booted(vec![node(5, NodeConfig::DEFAULT)]);
    for (req, code) in [
        ("605 [8] 40 00 50 00 00 00 00 00", 0x0602_0000u32),
        ("605 [8] 40 00 20 05 00 00 00 00", 0x0609_0011),
        ("605 [8] 2F 05 20 00 01 00 00 00", 0x0601_0002),
        ("605 [8] 2B 01 20 00 E9 03 00 00", 0x0609_0031),
        ("605 [8] 23 00 20 00 01 02 03 04", 0x0607_0012),
        ("605 [8] E0 00 20 00 00 00 00 00", 0x0504_0001),
    ] {
        let r = sdo(&mut bus, req);
        assert_eq!(r, abort(req, code), "{req}");
        assert_eq!(r.data().len(), 8);
        assert_ne!(u32::from_le_bytes(r.data()[4..8].try_into().unwrap()), 0);
    }
    // A toggle error inside a segmented download.
    assert_eq!(sdo(&mut bus, "605 [8] 21 04 20 00 03 00 00 00").data()[0], 0x60);
    let r = sdo(&mut bus, "605 [8] 15 61 62 63 00 00 00 00");
    assert_eq!(r, frame("585 [8] 80 04 20 00 00 00 03 05"));
}

/// ERR-12: with 1029h left at its default (not written), a serious device failure in Operational (here the
/// heartbeat consumer time-out, a communication error) makes the node go to Pre-operational.
#[test]
fn default_error_behaviour_is_pre_operational_err_12() {
    let mut bus = Bus::booted(vec![node(5, NodeConfig::DEFAULT)]);
    assert_eq!(sdo(&mut bus, "605 [8] 40 29 10 01 00 00 00 00"), frame("585 [8] 4F 29 10 01 00 00 00 00"));
    sdo_ok(&mut bus, &["605 [8] 23 16 10 01 64 00 07 00"]);
    bus.inject(frame("000 [2] 01 05"));
    bus.inject(frame("707 [1] 05"));
    bus.run_for_ms(90);
    assert_eq!(bus.stations[0].state(), NmtState::Operational);
    bus.run_for_ms(20);
    assert_eq!(bus.stations[0].state(), NmtState::PreOperational);
}

/// DEV-02 (1000h device type): with no standard profile the node reports 0000h and additional information
/// 0000h (0000 0000h, the default); a device with several logical devices reports FFFFh and the first one's
/// profile (here 0191h, CiA 401). 1000h is read-only.
#[test]
fn device_type_dev_02() {
    let mut bus = Bus::booted(vec![node(5, NodeConfig::DEFAULT)]);
    assert_eq!(sdo(&mut bus, "605 [8] 40 00 10 00 00 00 00 00"), frame("585 [8] 43 00 10 00 00 00 00 00"));
    let mut bus = Bus::booted(vec![node(5, NodeConfig { device_type: 0xFFFF_0191, ..NodeConfig::DEFAULT })]);
    assert_eq!(sdo(&mut bus, "605 [8] 40 00 10 00 00 00 00 00"), frame("585 [8] 43 00 10 00 91 01 FF FF"));
    let w = "605 [8] 23 00 10 00 00 00 00 00";
    assert_eq!(sdo(&mut bus, w), abort(w, 0x0601_0002));
}

/// PDO-39 at every length: an RPDO mapping 7 bytes (2000h, 2001h, 2003h) that arrives with 0 to 6 bytes is
/// not applied and raises EMCY 8210h; with exactly 7 it is applied.
#[test]
fn rpdo_shorter_than_mapping_by_any_amount_pdo_39() {
    const RPDO: &[PdoDefault] =
        &[PdoDefault { mapping: &[0x2000_0008, 0x2001_0010, 0x2003_0020], ..PdoDefault::EVENT }];
    let mut bus = Bus::booted(vec![node(5, NodeConfig { rpdo: RPDO, ..NodeConfig::DEFAULT })]);
    bus.inject(frame("000 [2] 01 05"));
    let data = [0x11, 0x22, 0x01, 0x44, 0x55, 0x66, 0x77];
    for len in 0..data.len() {
        bus.log.clear();
        bus.inject(CanFrame::new(0x205, &data[..len]).unwrap());
        let a = bus.stations[0].app();
        assert_eq!((a.byte, a.word, a.long), (0, 0, 0), "{len} bytes applied");
        assert_eq!(bus.frames_on(0x085).last().map(|f| f.1[..3].to_vec()), Some(vec![0x10, 0x82, 0x11]), "{len}");
        bus.inject(frame("000 [2] 82 05")); // reset communication: the error and its EMCY start afresh
        bus.inject(frame("000 [2] 01 05"));
    }
    bus.log.clear();
    bus.inject(CanFrame::new(0x205, &data).unwrap());
    let a = bus.stations[0].app();
    assert_eq!((a.byte, a.word, a.long), (0x11, 0x0122, 0x7766_5544));
}

/// PDO-38 and PDO-32 for a frame longer than its mapping: only the leading bytes are applied, for a
/// bit-granular mapping (2000h as 4 bits, 2003h as 12 bits: 2 bytes) as for a whole-byte one (2000h: 1 byte),
/// applied at once (FFh) or at the next SYNC (00h), whatever the bytes after the mapping hold.
#[test]
fn rpdo_longer_than_mapping_applies_leading_bytes_pdo_38() {
    for ttype in [255, 0] {
        for (mapping, byte, long) in [(&[0x2000_0004, 0x2003_000C][..], 0x5, 0xC3A), (&[0x2000_0008][..], 0xA5, 0)] {
            let rpdo = [PdoDefault { transmission_type: ttype, mapping, ..PdoDefault::EVENT }];
            let rpdo: &'static [PdoDefault] = Vec::leak(rpdo.to_vec());
            let mut bus = Bus::booted(vec![node(5, NodeConfig { rpdo, ..NodeConfig::DEFAULT })]);
            bus.inject(frame("000 [2] 01 05"));
            bus.inject(frame("205 [8] A5 C3 FF FF FF FF FF FF"));
            if ttype == 0 {
                bus.inject(frame("080 [0]"));
            }
            let a = bus.stations[0].app();
            assert_eq!((a.byte, a.long), (byte, long), "type {ttype:02X}h, mapping {mapping:08X?}");
            assert_eq!(bus.frames_on(0x085).last().map(|f| f.1[..3].to_vec()), Some(vec![0x20, 0x82, 0x11]));
        }
    }
}

/// SYNC-09/PDO-40 at the boundary: with a 1 ms window (1007h), a synchronous RPDO received exactly 1000 µs
/// after the SYNC is inside the window (applied at the next SYNC); one received 1001 µs after is outside
/// (discarded, the next SYNC applies nothing).
#[test]
fn sync_window_boundary_sync_09() {
    const RPDO: &[PdoDefault] = &[PdoDefault { transmission_type: 0, mapping: &[0x2000_0008], ..PdoDefault::EVENT }];
    let mut bus = Bus::booted(vec![node(5, NodeConfig { rpdo: RPDO, ..NodeConfig::DEFAULT })]);
    sdo_ok(&mut bus, &["605 [8] 23 07 10 00 E8 03 00 00"]);
    bus.inject(frame("000 [2] 01 05"));
    for (after_us, value, applied) in [(1000u64, 0x0A, true), (1001, 0x0B, false), (0, 0x0C, true)] {
        bus.run_for_ms(10);
        bus.inject(frame("080 [0]"));
        let t = bus.now.as_micros();
        at_us(&mut bus, t + after_us);
        let before = bus.stations[0].app().byte;
        bus.inject(CanFrame::new(0x205, &[value]).unwrap());
        bus.run_for_ms(5);
        bus.inject(frame("080 [0]"));
        let expect = if applied { value } else { before };
        assert_eq!(bus.stations[0].app().byte, expect, "RPDO {after_us} µs after SYNC");
    }
}

/// PDO-24 at the boundary (TPDO inhibit time = the minimum gap between two transmissions): with 1 ms
/// (1800h:03 = 10), a trigger 999 µs after a transmission is held back and goes out exactly at 1000 µs; a
/// trigger exactly 1000 µs after a transmission goes out at once (`trigger_tpdo` says so).
#[test]
fn tpdo_inhibit_time_boundary_pdo_24() {
    const TPDO: &[PdoDefault] = &[PdoDefault { inhibit_100us: 10, mapping: &[0x2000_0008], ..PdoDefault::EVENT }];
    let mut bus = Bus::booted(vec![node(5, NodeConfig { tpdo: TPDO, ..NodeConfig::DEFAULT })]);
    bus.inject(frame("000 [2] 01 05")); // PDO-28: sent at once, t = 0
    let sent = |bus: &Bus<TestNode>| -> Vec<u64> {
        bus.log.iter().filter(|s| s.frame.cob_id() == 0x185).map(|s| s.at.as_micros()).collect()
    };
    assert_eq!(sent(&bus), [0]);
    // The node learns the time from a frame it ignores (a heartbeat of node 127, no consumer).
    at_us(&mut bus, 999);
    bus.inject(frame("77F [1] 05"));
    assert!(!bus.stations[0].trigger_tpdo(0), "sent 999 µs after the last one");
    at_us(&mut bus, 1000);
    assert_eq!(sent(&bus), [0, 1000]);
    at_us(&mut bus, 2000);
    bus.inject(frame("77F [1] 05"));
    assert!(bus.stations[0].trigger_tpdo(0), "held back exactly one inhibit time after the last one");
    bus.run_for_ms(0);
    assert_eq!(sent(&bus), [0, 1000, 2000]);
}

/// PDO-12 at the boundary (RPDO event timer): with 100 ms (1400h:05), the time-out comes exactly 100 ms after
/// the last RPDO, not a microsecond earlier and not later: the RpdoTimeout event and EMCY 8250h.
#[test]
fn rpdo_event_timer_boundary_pdo_12() {
    const RPDO: &[PdoDefault] = &[PdoDefault { event_timer_ms: 100, mapping: &[0x2000_0008], ..PdoDefault::EVENT }];
    let mut bus = Bus::booted(vec![node(5, NodeConfig { rpdo: RPDO, ..NodeConfig::DEFAULT })]);
    bus.inject(frame("000 [2] 01 05"));
    at_us(&mut bus, 5_000);
    bus.inject(frame("205 [1] 01"));
    let emcy = |bus: &Bus<TestNode>| bus.frames_on(0x085).iter().any(|(_, d)| d[..2] == [0x50, 0x82]);
    at_us(&mut bus, 104_999);
    assert!(!emcy(&bus));
    assert!(!common::events(&mut bus.stations[0]).contains(&canopen::core::Event::RpdoTimeout { pdo: 0 }));
    at_us(&mut bus, 105_000);
    assert!(emcy(&bus), "no EMCY 8250h at 100 ms");
    assert!(common::events(&mut bus.stations[0]).contains(&canopen::core::Event::RpdoTimeout { pdo: 0 }));
}
