//! PDO, SYNC, EMCY, TIME, error behaviour and 1F80h through whole nodes on the in-memory bus with simulated
//! time. The master's frames and the expected replies are written out byte for byte (IDs in the test
//! docs); the requirement IDs (`docs/CONFORMANCE.md`) each test covers are named too.

mod common;

use canopen::core::{
    node::Node,
    od::{DomainBuf, OctetString, TimeOfDay, UnicodeString, VisibleString},
    pdo::PdoDefault,
    profile::NodeConfig,
    sync::SyncParams,
    wire::emcy::Emergency,
    CanFrame, Event, NmtState, NodeId, Sizes,
};
use canopen::ObjectDictionary;
use common::{events, frame, ms, Bus};

#[derive(ObjectDictionary, Default, Debug)]
#[od(crate = "canopen::core")]
pub struct App {
    #[od(index = 0x2000, access = "rw", pdo = "both")]
    byte: u8,
    #[od(index = 0x2001, access = "rw", pdo = "both")]
    flag: bool,
    #[od(index = 0x2002, access = "rw", pdo = "both", max = 1000)]
    limited: u16,
    #[od(index = 0x2010, sub = 0x21, record = "Y record", name = "Y", access = "rw", pdo = "both")]
    y: u32,
    #[od(index = 0x6000, sub = 3, record = "Inputs", name = "X", access = "rwr", pdo = "tpdo")]
    x: u16,
    #[od(index = 0x6040, access = "rww", pdo = "rpdo", name = "Controlword")]
    controlword: u16,
    #[od(index = 0x607A, access = "rww", pdo = "rpdo", name = "Target position")]
    target: i32,
    #[od(index = 0x2020, access = "rw", pdo = "both")]
    text: VisibleString<4>,
    #[od(index = 0x2021, access = "rw", pdo = "both")]
    octets: OctetString<2>,
    #[od(index = 0x2022, access = "ro", pdo = "tpdo")]
    units: UnicodeString<2>,
    #[od(index = 0x2023, domain, pdo = "both")]
    blob: DomainBuf<16>,
    #[od(index = 0x2024, access = "rw")]
    long_text: VisibleString<16>,
}

type TestNode = Node<App, Sizes<4, 32, 64>>;

fn node_with(id: u8, cfg: NodeConfig) -> TestNode {
    Node::new(NodeId::new(id).unwrap(), cfg, App::default())
}

/// Sends one SDO request and returns the server's reply.
fn sdo(bus: &mut Bus<TestNode>, req: &str) -> CanFrame {
    bus.take_master_rx();
    bus.inject(frame(req));
    let replies: Vec<CanFrame> =
        bus.take_master_rx().into_iter().map(|s| s.frame).filter(|f| f.cob_id() & 0x780 == 0x580).collect();
    assert_eq!(replies.len(), 1, "{req}: {replies:?}");
    replies[0]
}

fn ok_reply(req: &str) -> CanFrame {
    let f = frame(req);
    let d = f.data();
    CanFrame::new(f.cob_id() - 0x80, &[0x60, d[1], d[2], d[3], 0, 0, 0, 0]).unwrap()
}

/// Sends SDO writes that must all succeed.
fn sdo_ok(bus: &mut Bus<TestNode>, reqs: &[&str]) {
    for r in reqs {
        assert_eq!(sdo(bus, r), ok_reply(r), "{r}");
    }
}

fn on(bus: &Bus<TestNode>, id: u16) -> Vec<(u64, Vec<u8>)> {
    bus.frames_on(id)
}

/// The remapping procedure as frames (PDO-30..PDO-37, PDO-04, PDO-38/39): the master remaps RPDO1 of node 3 in the spec's order,
/// then the RPDO carries the values; negative variants (a missing object, too many
/// bits, absent sub-indices, a reserved type, short and long PDOs, a PDO in Pre-operational). ABORT-13: three
/// 32-bit entries (96 bits) are refused with 0604 0042h.
#[test]
fn rpdo_remapping_procedure_vector() {
    let mut bus = Bus::booted(vec![node_with(3, NodeConfig { rpdo: &[PdoDefault::EVENT], ..NodeConfig::DEFAULT })]);
    // RPDO sub 04h and 06h absent (PDO-11, PDO-13) and RPDO type FCh refused (PDO-09).
    assert_eq!(sdo(&mut bus, "603 [8] 40 00 14 04 00 00 00 00"), frame("583 [8] 80 00 14 04 11 00 09 06"));
    assert_eq!(sdo(&mut bus, "603 [8] 40 00 14 06 00 00 00 00"), frame("583 [8] 80 00 14 06 11 00 09 06"));
    assert_eq!(sdo(&mut bus, "603 [8] 2F 00 14 02 FC 00 00 00"), frame("583 [8] 80 00 14 02 30 00 09 06"));
    // While valid: the COB-ID's CAN-ID and the mapping cannot change (PDO-17, PDO-35).
    assert_eq!(sdo(&mut bus, "603 [8] 23 00 14 01 04 02 00 00"), frame("583 [8] 80 00 14 01 30 00 09 06"));
    assert_eq!(sdo(&mut bus, "603 [8] 2F 00 16 00 00 00 00 00"), frame("583 [8] 80 00 16 00 00 00 01 06"));
    sdo_ok(
        &mut bus,
        &[
            "603 [8] 23 00 14 01 03 02 00 80", // 1: PDO off
            "603 [8] 2F 00 16 00 00 00 00 00", // 2: mapping off
            "603 [8] 23 00 16 01 10 00 40 60", // 3: 6040h:00, 16 bit
            "603 [8] 23 00 16 02 20 00 7A 60", // 3: 607Ah:00, 32 bit
            "603 [8] 2F 00 16 00 02 00 00 00", // 4: two entries
        ],
    );
    // Entries cannot change while sub 00h ≠ 0; mapping a missing object (5000h) is refused.
    assert_eq!(sdo(&mut bus, "603 [8] 23 00 16 03 10 00 40 60"), frame("583 [8] 80 00 16 03 00 00 01 06"));
    sdo_ok(&mut bus, &["603 [8] 2F 00 16 00 00 00 00 00"]);
    assert_eq!(sdo(&mut bus, "603 [8] 23 00 16 01 10 00 00 50"), frame("583 [8] 80 00 16 01 00 00 02 06"));
    // Not RPDO-mappable (6000h:03 is TPDO only): 0604 0041h; more bits than the object: 0604 0041h.
    assert_eq!(sdo(&mut bus, "603 [8] 23 00 16 01 10 03 00 60"), frame("583 [8] 80 00 16 01 41 00 04 06"));
    assert_eq!(sdo(&mut bus, "603 [8] 23 00 16 01 20 00 40 60"), frame("583 [8] 80 00 16 01 41 00 04 06"));
    // The refused writes changed nothing.
    assert_eq!(sdo(&mut bus, "603 [8] 40 00 16 01 00 00 00 00"), frame("583 [8] 43 00 16 01 10 00 40 60"));
    // Three 32-bit entries = 96 bits → 0604 0042h at sub 00h.
    sdo_ok(&mut bus, &["603 [8] 23 00 16 03 20 00 7A 60", "603 [8] 23 00 16 02 20 00 7A 60"]);
    sdo_ok(&mut bus, &["603 [8] 23 00 16 01 20 00 7A 60"]);
    assert_eq!(sdo(&mut bus, "603 [8] 2F 00 16 00 03 00 00 00"), frame("583 [8] 80 00 16 00 42 00 04 06"));
    sdo_ok(
        &mut bus,
        &[
            "603 [8] 23 00 16 01 10 00 40 60",
            "603 [8] 2F 00 16 00 02 00 00 00",
            "603 [8] 23 00 14 01 03 02 00 00", // 5: PDO on
        ],
    );
    // PDO-04: ignored in Pre-operational.
    bus.inject(frame("203 [6] 0F 00 E8 03 00 00"));
    assert_eq!(bus.stations[0].app().controlword, 0);
    bus.inject(frame("000 [2] 01 03"));
    events(&mut bus.stations[0]);
    bus.inject(frame("203 [6] 0F 00 E8 03 00 00"));
    assert_eq!((bus.stations[0].app().controlword, bus.stations[0].app().target), (0x000F, 1000));
    assert!(events(&mut bus.stations[0]).contains(&Event::RpdoReceived { pdo: 0 }));
    // PDO-39: too short → not applied, EMCY 8210h.
    bus.take_master_rx();
    bus.inject(frame("203 [4] 01 00 02 00"));
    assert_eq!(bus.stations[0].app().controlword, 0x000F);
    assert_eq!(on(&bus, 0x083).last().unwrap().1, [0x10, 0x82, 0x11, 0x01, 0, 0, 0, 0]);
    // PDO-38: too long → leading bytes applied, EMCY 8220h.
    bus.inject(frame("203 [8] 07 00 D0 07 00 00 AA BB"));
    assert_eq!((bus.stations[0].app().controlword, bus.stations[0].app().target), (7, 2000));
    assert_eq!(on(&bus, 0x083).last().unwrap().1, [0x20, 0x82, 0x11, 0x01, 0, 0, 0, 0]);
    // The right length again clears both errors: EMCY 0000h, register 0 at the end (EMCY-07).
    bus.inject(frame("203 [6] 0F 00 E8 03 00 00"));
    assert_eq!(on(&bus, 0x083).last().unwrap().1, [0; 8]);
    assert_eq!(bus.stations[0].error_register(), 0);
}

/// Strings and a DOMAIN marked PDO-mappable, remapped through SDO (PDO-31..PDO-37, ABORT-12, ABORT-13;
/// eds-to-rust's datatypes.eds 2009h-200Bh, 200Fh): the core's validation answers as for any entry. More
/// bits than the object (a 4-byte string mapped with 40 bits), more than 64 bits in one entry, an entry
/// not mappable that way (ro in an RPDO, no `pdo`), an empty DOMAIN: 0604 0041h at the entry; 72 bits in
/// all: 0604 0042h at the count. Then an RPDO writes the string (all 4 bytes), the DOMAIN (the 3 bytes it
/// held when mapped) and a byte, and a TPDO carries a UNICODE_STRING and an OCTET_STRING, padded with 00h.
#[test]
fn strings_and_a_domain_in_pdos() {
    let mut bus = Bus::booted(vec![node_with(
        3,
        NodeConfig { rpdo: &[PdoDefault::EVENT], tpdo: &[PdoDefault::EVENT], ..NodeConfig::DEFAULT },
    )]);
    sdo_ok(&mut bus, &["603 [8] 23 00 14 01 03 02 00 80", "603 [8] 2F 00 16 00 00 00 00 00"]);
    let not_mappable = |sub: u8| frame(&format!("583 [8] 80 00 16 {sub:02X} 41 00 04 06"));
    assert_eq!(sdo(&mut bus, "603 [8] 23 00 16 01 28 00 20 20"), not_mappable(1)); // 2020h, 40 of 32 bits
    assert_eq!(sdo(&mut bus, "603 [8] 23 00 16 01 48 00 20 20"), not_mappable(1)); // 72 bits
    assert_eq!(sdo(&mut bus, "603 [8] 23 00 16 01 20 00 22 20"), not_mappable(1)); // 2022h ro: TPDO only
    assert_eq!(sdo(&mut bus, "603 [8] 23 00 16 01 40 00 24 20"), not_mappable(1)); // 2024h: no `pdo`
    assert_eq!(sdo(&mut bus, "603 [8] 23 00 16 02 18 00 23 20"), not_mappable(2)); // 2023h empty
    sdo_ok(
        &mut bus,
        &[
            "603 [8] 27 23 20 00 01 02 03 00", // 2023h := 01 02 03 (expedited, 3 bytes)
            "603 [8] 23 00 16 01 20 00 20 20", // 2020h:00, 32 bit: the whole string
            "603 [8] 23 00 16 02 18 00 23 20", // 2023h:00, 24 bit: the DOMAIN's size now
            "603 [8] 23 00 16 03 08 00 00 20", // 2000h:00, 8 bit
            "603 [8] 23 00 16 04 08 00 01 20", // 2001h:00, 8 bit
        ],
    );
    assert_eq!(sdo(&mut bus, "603 [8] 2F 00 16 00 04 00 00 00"), frame("583 [8] 80 00 16 00 42 00 04 06"));
    sdo_ok(&mut bus, &["603 [8] 2F 00 16 00 03 00 00 00", "603 [8] 23 00 14 01 03 02 00 00"]);
    // TPDO1: 2022h (UNICODE_STRING<2>, 32 bit) and 2021h (OCTET_STRING<2>, 16 bit), sent on every SYNC.
    sdo_ok(
        &mut bus,
        &[
            "603 [8] 23 00 18 01 83 01 00 80",
            "603 [8] 2F 00 18 02 01 00 00 00",
            "603 [8] 2F 00 1A 00 00 00 00 00",
            "603 [8] 23 00 1A 01 20 00 22 20",
            "603 [8] 23 00 1A 02 10 00 21 20",
            "603 [8] 2F 00 1A 00 02 00 00 00",
            "603 [8] 23 00 18 01 83 01 00 00",
        ],
    );
    assert_eq!(sdo(&mut bus, "603 [8] 23 00 1A 01 20 00 20 20"), frame("583 [8] 80 00 1A 01 00 00 01 06"));
    bus.inject(frame("000 [2] 01 03"));
    bus.inject(frame("203 [8] 41 42 00 00 07 08 09 05"));
    {
        let app = bus.stations[0].app();
        assert_eq!((app.text.as_bytes(), app.blob.as_bytes(), app.byte), (&b"AB\0\0"[..], &[7u8, 8, 9][..], 5));
    }
    let app = bus.stations[0].app_mut();
    app.units = UnicodeString::from_str("h\u{e9}").unwrap();
    app.octets = OctetString::from_bytes(&[0xAB]).unwrap();
    bus.inject(frame("080 [0]"));
    assert_eq!(on(&bus, 0x183).last().unwrap().1, [0x68, 0, 0xE9, 0, 0xAB, 0]);
}

/// A TPDO configured by SDO (PDO-15..20): TPDO3 of node 5 moved to 387h, every 3rd SYNC, X = 6000h:03 (16 bit),
/// Y = 2010h:21h (32 bit); and types 1 and 3 (one TPDO per SYNC, one per 3 SYNCs) counted from entering
/// Operational.
#[test]
fn tpdo_configuration_vector_and_cyclic_sync() {
    const TPDOS: &[PdoDefault] = &[PdoDefault::UNUSED, PdoDefault::UNUSED, PdoDefault::EVENT];
    let mut bus = Bus::booted(vec![node_with(5, NodeConfig { tpdo: TPDOS, ..NodeConfig::DEFAULT })]);
    // A COB-ID written with its bytes reversed (38070000h: the frame bit set) is refused (COB-15).
    assert_eq!(sdo(&mut bus, "605 [8] 23 02 18 01 00 00 07 38"), frame("585 [8] 80 02 18 01 30 00 09 06"));
    sdo_ok(
        &mut bus,
        &[
            "605 [8] 23 02 18 01 85 03 00 80",
            "605 [8] 23 02 18 01 87 03 00 80",
            "605 [8] 2F 02 18 02 03 00 00 00",
            "605 [8] 2F 02 1A 00 00 00 00 00",
            "605 [8] 23 02 1A 01 10 03 00 60",
            "605 [8] 23 02 1A 02 20 21 10 20",
            "605 [8] 2F 02 1A 00 02 00 00 00",
            "605 [8] 23 02 18 01 87 03 00 00",
        ],
    );
    // Remapping an 8-bit object and 1010h is refused while the PDO is valid; 1010h is not mappable anyway.
    assert_eq!(sdo(&mut bus, "605 [8] 23 02 1A 01 08 03 00 60"), frame("585 [8] 80 02 1A 01 00 00 01 06"));
    {
        let app = bus.stations[0].app_mut();
        app.x = 0x1234;
        app.y = 0xDEAD_BEEF;
    }
    bus.inject(frame("080 [0]")); // Pre-operational: no TPDO
    bus.inject(frame("000 [2] 01 05"));
    for _ in 0..9 {
        bus.run_for_ms(10);
        bus.inject(frame("080 [0]"));
    }
    let tpdo = on(&bus, 0x387);
    assert_eq!(tpdo.len(), 3, "{tpdo:?}");
    assert!(tpdo.iter().all(|(_, d)| d == &[0x34, 0x12, 0xEF, 0xBE, 0xAD, 0xDE]));
    assert_eq!(tpdo.iter().map(|(t, _)| *t).collect::<Vec<_>>(), [30, 60, 90]); // SYNC #3, #6, #9 (at 10, 20, ... 90 ms)
}

/// PDO-19: type 00h sends once after the SYNC that follows an application event.
/// PDO-26, SYNC-10/11: type 02h with SYNC start value 2 and this node producing SYNC with 1019h = 4.
/// ABORT-29: writing 1019h while 1006h is non-zero is refused for the present device state, 0800 0022h.
#[test]
fn acyclic_and_sync_start_value() {
    const TPDOS: &[PdoDefault] = &[
        PdoDefault { transmission_type: 0, mapping: &[0x2000_0008], ..PdoDefault::EVENT },
        PdoDefault { transmission_type: 2, sync_start: 2, mapping: &[0x2000_0008], ..PdoDefault::EVENT },
    ];
    let sync = SyncParams {
        cob_id: canopen::core::cob::CobIdEntry::from_raw(0x4000_0080),
        period_us: 10_000,
        counter_overflow: 4,
        ..SyncParams::DEFAULT
    };
    let mut bus = Bus::booted(vec![node_with(1, NodeConfig { tpdo: TPDOS, sync, ..NodeConfig::DEFAULT })]);
    bus.stations[0].enter_state(NmtState::Operational);
    bus.run_until(ms(15));
    assert!(!bus.stations[0].trigger_tpdo(0)); // type 0: not now...
    bus.run_until(ms(85));
    // SYNC counters 1,2,3,4,1,2,3,4 at 10..80 ms.
    let counters: Vec<u8> = on(&bus, 0x080).iter().map(|(_, d)| d[0]).collect();
    assert_eq!(counters, [1, 2, 3, 4, 1, 2, 3, 4]);
    assert_eq!(on(&bus, 0x181).iter().map(|(t, _)| *t).collect::<Vec<_>>(), [20]); // ...at the next SYNC only
                                                                                   // Type 2 with start value 2: after counters 2, 4, 2, 4.
    assert_eq!(on(&bus, 0x281).iter().map(|(t, _)| *t).collect::<Vec<_>>(), [20, 40, 60, 80]);
    // SYNC-12: 1019h cannot change while producing.
    assert_eq!(sdo(&mut bus, "601 [8] 2F 19 10 00 03 00 00 00"), frame("581 [8] 80 19 10 00 22 00 00 08"));
    // 1006h = 0 stops the SYNC; then 1019h may change.
    sdo_ok(&mut bus, &["601 [8] 23 06 10 00 00 00 00 00", "601 [8] 2F 19 10 00 00 00 00 00"]);
    let before = on(&bus, 0x080).len();
    bus.run_for_ms(100);
    assert_eq!(on(&bus, 0x080).len(), before);
}

/// PDO-23..25, PDO-28: event-driven TPDOs with inhibit time and event timer, and PDO-21/22/29: RTR-only
/// types.
#[test]
fn event_driven_inhibit_event_timer_and_rtr() {
    const TPDOS: &[PdoDefault] = &[
        PdoDefault { inhibit_100us: 200, mapping: &[0x2002_0010], ..PdoDefault::EVENT },
        PdoDefault { event_timer_ms: 1000, mapping: &[0x2000_0008], ..PdoDefault::EVENT },
        PdoDefault { transmission_type: 252, mapping: &[0x2000_0008], ..PdoDefault::EVENT },
        PdoDefault { transmission_type: 253, mapping: &[0x2000_0008], ..PdoDefault::EVENT },
    ];
    let mut bus = Bus::booted(vec![node_with(4, NodeConfig { tpdo: TPDOS, ..NodeConfig::DEFAULT })]);
    bus.inject(frame("000 [2] 01 04"));
    // Entering Operational: both event-driven TPDOs go out at once; the RTR-only ones do not.
    assert_eq!(on(&bus, 0x184).len(), 1);
    assert_eq!(on(&bus, 0x284).len(), 1);
    assert!(on(&bus, 0x384).is_empty() && on(&bus, 0x484).is_empty());
    // Inhibit 20 ms: the value changes every 5 ms, change-of-value detection → at most one per 20 ms, and the
    // last value is never lost.
    for k in 1..=20u16 {
        bus.run_for_ms(5);
        bus.stations[0].app_mut().limited = k;
        bus.stations[0].trigger_changed_tpdos();
        bus.run_for_ms(0);
    }
    bus.run_for_ms(30);
    let t1 = on(&bus, 0x184);
    let times: Vec<u64> = t1.iter().map(|(t, _)| *t).collect();
    assert!(times.windows(2).all(|w| w[1] - w[0] >= 20), "{times:?}");
    assert_eq!(t1.last().unwrap().1, 20u16.to_le_bytes());
    assert!(t1.len() <= 7, "{times:?}");
    // No data change, event timer 1 s → one TPDO per second.
    bus.run_until(ms(5000));
    let t2: Vec<u64> = on(&bus, 0x284).iter().map(|(t, _)| *t).collect();
    assert_eq!(t2, [0, 1000, 2000, 3000, 4000, 5000]);
    // RTR on the TPDO's COB-ID. FCh answers with what the last SYNC sampled; FDh samples now.
    bus.stations[0].app_mut().byte = 7;
    bus.inject(frame("384 [RTR]"));
    assert!(on(&bus, 0x384).is_empty()); // nothing sampled yet
    bus.inject(frame("080 [0]"));
    bus.stations[0].app_mut().byte = 8;
    bus.inject(frame("384 [RTR]"));
    bus.inject(frame("484 [RTR]"));
    assert_eq!(on(&bus, 0x384), [(5000, vec![7])]);
    assert_eq!(on(&bus, 0x484), [(5000, vec![8])]);
    // RTR not allowed (bit 30 = 1): no answer (PDO-29).
    sdo_ok(&mut bus, &["604 [8] 23 03 18 01 84 04 00 C0", "604 [8] 23 03 18 01 84 04 00 40"]);
    bus.inject(frame("484 [RTR]"));
    assert_eq!(on(&bus, 0x484).len(), 1);
}

/// PDO-12 with PDO-39: a frame too short for an RPDO's mapping is not the reception that ends its time-out.
/// It raises 8210h and leaves 8250h standing; the next frame of the right length ends both, so the last
/// EMCY says no error is left (EMCY-07, ERR-02).
#[test]
fn a_short_frame_after_an_rpdo_time_out_leaves_8250h_to_the_next_good_one() {
    const RPDOS: &[PdoDefault] = &[PdoDefault { event_timer_ms: 100, mapping: &[0x2002_0010], ..PdoDefault::EVENT }];
    let mut bus = Bus::booted(vec![node_with(3, NodeConfig { rpdo: RPDOS, ..NodeConfig::DEFAULT })]);
    bus.inject(frame("000 [2] 01 00"));
    bus.inject(frame("203 [2] 05 00"));
    bus.run_for_ms(150);
    assert_eq!(on(&bus, 0x083).last().unwrap().1, [0x50, 0x82, 0x11, 0x01, 0, 0, 0, 0]);
    bus.inject(frame("203 [1] 06"));
    assert_eq!(on(&bus, 0x083).last().unwrap().1, [0x10, 0x82, 0x11, 0x01, 0, 0, 0, 0]);
    assert_eq!(bus.stations[0].app().limited, 5); // not applied
    bus.inject(frame("203 [2] 06 00"));
    assert_eq!(bus.stations[0].app().limited, 6);
    assert_eq!(on(&bus, 0x083).last().unwrap().1, [0; 8]);
}

/// Synchronous RPDOs (PDO-09): applied at the next SYNC, not before; the event timer (PDO-12) raises EMCY
/// 8250h; the SYNC window (SYNC-09, PDO-40) discards late synchronous data; SYNC-14 (a SYNC with a counter
/// while 1019h = 0).
#[test]
fn synchronous_rpdo_deadline_window_and_sync_length() {
    const RPDOS: &[PdoDefault] = &[
        PdoDefault { transmission_type: 0, mapping: &[0x2000_0008], ..PdoDefault::EVENT },
        PdoDefault { event_timer_ms: 100, mapping: &[0x2002_0010], ..PdoDefault::EVENT },
    ];
    let mut bus = Bus::booted(vec![node_with(3, NodeConfig { rpdo: RPDOS, ..NodeConfig::DEFAULT })]);
    bus.inject(frame("000 [2] 01 00"));
    bus.inject(frame("203 [1] 2A"));
    assert_eq!(bus.stations[0].app().byte, 0);
    bus.inject(frame("080 [0]"));
    assert_eq!(bus.stations[0].app().byte, 42);
    // Event timer: armed by the first frame, expires 100 ms later.
    bus.inject(frame("303 [2] 05 00"));
    assert_eq!(bus.stations[0].app().limited, 5);
    bus.run_for_ms(150);
    assert_eq!(on(&bus, 0x083).last().unwrap().1, [0x50, 0x82, 0x11, 0x02, 0, 0, 0, 0]);
    assert!(events(&mut bus.stations[0]).contains(&Event::RpdoTimeout { pdo: 1 }));
    bus.inject(frame("303 [2] 06 00"));
    assert_eq!(on(&bus, 0x083).last().unwrap().1, [0; 8]); // reception clears 8250h
                                                           // A limit refuses the write, nothing else happens.
    bus.inject(frame("303 [2] FF FF"));
    assert_eq!(bus.stations[0].app().limited, 6);
    // SYNC window 1 ms: a synchronous RPDO 2 ms after the SYNC is discarded.
    sdo_ok(&mut bus, &["603 [8] 23 07 10 00 E8 03 00 00"]);
    bus.inject(frame("080 [0]"));
    bus.run_for_ms(2);
    bus.inject(frame("203 [1] 01"));
    bus.inject(frame("080 [0]"));
    assert_eq!(bus.stations[0].app().byte, 42);
    // A SYNC with a counter while 1019h = 0 → EMCY 8240h.
    bus.inject(frame("080 [1] 05"));
    assert_eq!(on(&bus, 0x083).last().unwrap().1, [0x40, 0x82, 0x11, 0x01, 0, 0, 0, 0]);
}

/// PDO-12, EEC-20, EMCY-07 (issue 22): 8250h is one code for every RPDO, so it is cleared only when no RPDO is
/// timed out any more; the same for the length errors 8210h/8220h.
#[test]
fn rpdo_errors_clear_when_no_rpdo_has_the_cause() {
    const RPDOS: &[PdoDefault] = &[
        PdoDefault { event_timer_ms: 100, mapping: &[0x2000_0008], ..PdoDefault::EVENT },
        PdoDefault { event_timer_ms: 100, mapping: &[0x2002_0010], ..PdoDefault::EVENT },
    ];
    let mut bus = Bus::booted(vec![node_with(3, NodeConfig { rpdo: RPDOS, ..NodeConfig::DEFAULT })]);
    bus.inject(frame("000 [2] 01 00"));
    bus.inject(frame("203 [1] 01"));
    bus.inject(frame("303 [2] 01 00"));
    bus.run_for_ms(150);
    let emcy = |bus: &Bus<_>| on(bus, 0x083).into_iter().map(|(_, d)| d).collect::<Vec<_>>();
    assert_eq!(emcy(&bus), [vec![0x50, 0x82, 0x11, 0x01, 0, 0, 0, 0]], "both timed out: one active code");
    bus.inject(frame("203 [1] 02")); // RPDO 1 back, RPDO 2 still silent: the cause remains
    assert_eq!(emcy(&bus).len(), 1);
    assert_eq!(bus.stations[0].error_register(), 0x11);
    bus.inject(frame("303 [2] 02 00")); // RPDO 2 back: cleared
    assert_eq!(emcy(&bus)[1..], [vec![0; 8]]);
    assert_eq!(bus.stations[0].error_register(), 0);
    // Length errors: RPDO 1 too long (8220h), RPDO 2 too short (8210h).
    bus.inject(frame("203 [2] 01 01"));
    bus.inject(frame("303 [1] 01"));
    assert_eq!(emcy(&bus)[2..], [vec![0x20, 0x82, 0x11, 0x01, 0, 0, 0, 0], vec![0x10, 0x82, 0x11, 0x02, 0, 0, 0, 0]]);
    bus.inject(frame("203 [1] 03")); // RPDO 1 right again; RPDO 2's last frame was still short
    assert_eq!(emcy(&bus).len(), 4);
    bus.inject(frame("303 [2] 03 00")); // both right: both length codes cleared
    assert_eq!(bus.stations[0].error_register(), 0);
    assert_eq!(emcy(&bus).last(), Some(&vec![0; 8]));
}

/// Emergencies (EMCY-04..09, ERR-01..09, NMT-22): the emergency state machine, 1001h and 1003h agree after a
/// sequence of raised and cleared errors. EEC-01/EEC-02: the generic error 1000h goes out as 00 10, and
/// 0000h (error reset) when the errors clear (EMCY-01: the producer supports at least those two). COB-04: the EMCY is on 080h + node-ID (083h). ABORT-31: 1003h:01 with an empty history is 0800 0024h (no data).
#[test]
fn emcy_error_register_and_history_vectors() {
    let mut bus = Bus::booted(vec![node_with(3, NodeConfig::DEFAULT)]);
    // 1003h:01 with an empty history is 0800 0024h; 1001h reads 0 with no error.
    assert_eq!(sdo(&mut bus, "603 [8] 40 03 10 01 00 00 00 00"), frame("583 [8] 80 03 10 01 24 00 00 08"));
    assert_eq!(sdo(&mut bus, "603 [8] 40 01 10 00 00 00 00 00"), frame("583 [8] 4F 01 10 00 00 00 00 00"));
    // Errors 1000h then 8130h raised, then cleared one by one.
    let n = &mut bus.stations[0];
    assert!(n.raise_error(0x1000, [0; 5]));
    assert!(n.raise_error(0x8130, [0; 5]));
    assert!(!n.raise_error(0x8130, [0; 5])); // EMCY-05: nothing repeated
    bus.run_for_ms(0);
    assert_eq!(sdo(&mut bus, "603 [8] 40 03 10 00 00 00 00 00"), frame("583 [8] 4F 03 10 00 02 00 00 00"));
    assert_eq!(sdo(&mut bus, "603 [8] 40 03 10 01 00 00 00 00"), frame("583 [8] 43 03 10 01 30 81 00 00")); // newest first: 8130h
    assert_eq!(sdo(&mut bus, "603 [8] 40 03 10 02 00 00 00 00"), frame("583 [8] 43 03 10 02 00 10 00 00"));
    assert_eq!(sdo(&mut bus, "603 [8] 40 01 10 00 00 00 00 00"), frame("583 [8] 4F 01 10 00 11 00 00 00"));
    bus.stations[0].clear_error(0x1000);
    bus.stations[0].clear_error(0x8130);
    bus.run_for_ms(0);
    let emcy: Vec<Vec<u8>> = on(&bus, 0x083).into_iter().map(|(_, d)| d).collect();
    assert_eq!(
        emcy,
        [
            vec![0x00, 0x10, 0x01, 0, 0, 0, 0, 0],
            vec![0x30, 0x81, 0x11, 0, 0, 0, 0, 0],
            vec![0x00, 0x00, 0x11, 0, 0, 0, 0, 0],
            vec![0x00, 0x00, 0x00, 0, 0, 0, 0, 0],
        ]
    );
    // 1003h:00 accepts only 0 (0609 0030h otherwise), which clears the history.
    assert_eq!(sdo(&mut bus, "603 [8] 2F 03 10 00 01 00 00 00"), frame("583 [8] 80 03 10 00 30 00 09 06"));
    assert_eq!(sdo(&mut bus, "603 [8] 2F 03 10 00 00 00 00 00"), frame("583 [8] 60 03 10 00 00 00 00 00"));
    assert_eq!(sdo(&mut bus, "603 [8] 40 03 10 00 00 00 00 00"), frame("583 [8] 4F 03 10 00 00 00 00 00"));
    // EMCY-06: an RTR on the EMCY ID is not answered.
    bus.take_master_rx();
    bus.inject(frame("083 [RTR]"));
    assert!(bus.take_master_rx().is_empty());
    // NMT-22: raised while Stopped → held; the most recent goes out on leaving Stopped.
    bus.inject(frame("000 [2] 02 03"));
    bus.stations[0].raise_error(0x2310, [0; 5]);
    bus.stations[0].raise_error(0x3120, [0; 5]);
    bus.run_for_ms(10);
    assert_eq!(on(&bus, 0x083).len(), 4);
    bus.inject(frame("000 [2] 80 03"));
    assert_eq!(on(&bus, 0x083).last().unwrap().1, [0x20, 0x31, 0x07, 0, 0, 0, 0, 0]);
    assert_eq!(on(&bus, 0x083).len(), 5);
    // EMCY-09: 1015h = 10 (1 ms); two errors 200 µs apart → the second ≥ 1 ms after the first.
    sdo_ok(&mut bus, &["603 [8] 2B 15 10 00 0A 00 00 00"]);
    let t0 = bus.now;
    bus.stations[0].raise_error(0x4210, [0; 5]);
    bus.run_until(canopen::core::Instant::from_micros(t0.as_micros() + 200));
    bus.stations[0].raise_error(0x5000, [0; 5]);
    bus.run_for_ms(5);
    let seen: Vec<u64> = bus
        .log
        .iter()
        .filter(|s| s.frame.cob_id() == 0x083 && !s.frame.is_rtr())
        .map(|s| s.at.as_micros())
        .skip(5)
        .collect();
    assert_eq!(seen, [t0.as_micros(), t0.as_micros() + 1000]);
    // Another node's EMCY is an event (EMCY-11).
    bus.inject(frame("087 [8] 00 10 01 00 00 00 00 00"));
    let ev = events(&mut bus.stations[0]);
    let e = Emergency { code: 0x1000, register: 1, manufacturer: [0; 5] };
    assert!(ev.contains(&Event::Emergency { node: 7, emcy: e }), "{ev:?}");
}

/// TIME (TIME-01..05): node 1 produces, node 2 consumes; not in Stopped.
#[test]
fn time_round_trip() {
    let producer = NodeConfig { time_cob_id: 0x4000_0100, ..NodeConfig::DEFAULT };
    let mut bus = Bus::booted(vec![node_with(1, producer), node_with(2, NodeConfig::DEFAULT)]);
    let t = TimeOfDay::new(5844, 45_296_789).unwrap(); // 2000-01-01 12:34:56.789
    assert!(bus.stations[0].produce_time(t));
    bus.run_for_ms(0);
    assert_eq!(on(&bus, 0x100), [(0, vec![0x95, 0x2C, 0xB3, 0x02, 0xD4, 0x16])]);
    assert!(events(&mut bus.stations[1]).contains(&Event::Time(t)));
    // 1012h: a consumer-only node cannot produce; the ID cannot change while in use (TIME-03).
    assert!(!bus.stations[1].produce_time(t));
    assert_eq!(sdo(&mut bus, "602 [8] 23 12 10 00 01 01 00 80"), frame("582 [8] 80 12 10 00 30 00 09 06"));
    bus.inject(frame("000 [2] 02 02"));
    bus.inject(frame("100 [6] 00 2E 93 02 B9 26"));
    assert!(!events(&mut bus.stations[1]).iter().any(|e| matches!(e, Event::Time(_))));
    bus.inject(frame("000 [2] 80 02"));
    bus.inject(frame("100 [6] 00 2E 93 02 B9 26")); // 2011-02-21 12:00:00.000
    let want = TimeOfDay::new(9913, 43_200_000).unwrap();
    assert!(events(&mut bus.stations[1]).contains(&Event::Time(want)));
}

/// ERR-10..13, NMT-26: 1029h sub 01h decides what a heartbeat time-out does; 8130h is raised (EEC-12).
/// HB-13: the consumer's heartbeat time-out is that communication error, handled per 1029h sub 01h.
#[test]
fn error_behaviour_1029() {
    for (behaviour, expect) in [(0u8, NmtState::PreOperational), (1, NmtState::Operational), (2, NmtState::Stopped)] {
        let mut bus = Bus::booted(vec![node_with(5, NodeConfig::DEFAULT)]);
        assert_eq!(sdo(&mut bus, "605 [8] 2F 29 10 00 02 00 00 00"), frame("585 [8] 80 29 10 00 02 00 01 06"));
        assert_eq!(sdo(&mut bus, "605 [8] 2F 29 10 01 05 00 00 00"), frame("585 [8] 80 29 10 01 30 00 09 06"));
        let set = format!("605 [8] 2F 29 10 01 {behaviour:02X} 00 00 00");
        sdo_ok(&mut bus, &[&set, "605 [8] 23 16 10 01 64 00 07 00"]);
        bus.inject(frame("000 [2] 01 05"));
        bus.inject(frame("707 [1] 05"));
        bus.run_for_ms(150);
        assert_eq!(bus.stations[0].state(), expect, "1029h = {behaviour}");
        assert_eq!(bus.stations[0].error_register() & 0x11, 0x11);
        let emcy = on(&bus, 0x085);
        assert!(emcy.iter().any(|(_, d)| d[..3] == [0x30, 0x81, 0x11]) || expect == NmtState::Stopped);
    }
}

/// NMT-27 (1F80h bit 2 = 0): the node enters Operational by itself after boot-up, and sends its
/// event-driven TPDOs then (PDO-28).
#[test]
fn nmt_startup_self_start() {
    const TPDOS: &[PdoDefault] = &[PdoDefault { mapping: &[0x2000_0008], ..PdoDefault::EVENT }];
    let mut bus = Bus::new(vec![node_with(6, NodeConfig { nmt_startup: 0, tpdo: TPDOS, ..NodeConfig::DEFAULT })]);
    bus.run_until(ms(0));
    assert_eq!(bus.stations[0].state(), NmtState::Operational);
    assert_eq!(on(&bus, 0x706), [(0, vec![0])]);
    assert_eq!(on(&bus, 0x186), [(0, vec![0])]);
    assert_eq!(
        sdo(&mut Bus::booted(vec![node_with(6, NodeConfig::DEFAULT)]), "606 [8] 40 80 1F 00 00 00 00 00"),
        frame("586 [8] 43 80 1F 00 04 00 00 00")
    );
}

/// PDO-10/14/24/26 (no inhibit time or SYNC start value change while valid), PDO-18 (reserved types), COB-13
/// (a restricted CAN-ID cannot be made valid), ERR-09 (1003h entries are ro), EMCY-03 (1014h ID change while
/// valid), SYNC-01/02 (1005h read), ERR-10 (1029h sub 00h).
#[test]
fn parameter_change_rules() {
    let mut bus = Bus::booted(vec![node_with(5, NodeConfig { tpdo: &[PdoDefault::EVENT], ..NodeConfig::DEFAULT })]);
    let refused = |req: &str| {
        let f = frame(req);
        let d = f.data();
        CanFrame::new(f.cob_id() - 0x80, &[0x80, d[1], d[2], d[3], 0x30, 0x00, 0x09, 0x06]).unwrap()
    };
    for req in [
        "605 [8] 2B 00 18 03 0A 00 00 00", // inhibit while valid
        "605 [8] 2F 00 18 06 02 00 00 00", // start value while valid
        "605 [8] 2F 00 18 02 F1 00 00 00", // reserved type
        "605 [8] 23 14 10 00 86 00 00 00", // 1014h ID change while valid
    ] {
        assert_eq!(sdo(&mut bus, req), refused(req), "{req}");
    }
    assert_eq!(sdo(&mut bus, "605 [8] 40 00 18 00 00 00 00 00"), frame("585 [8] 4F 00 18 00 06 00 00 00"));
    assert_eq!(sdo(&mut bus, "605 [8] 40 04 14 00 00 00 00 00"), frame("585 [8] 80 04 14 00 00 00 02 06")); // no RPDO5
    assert_eq!(sdo(&mut bus, "605 [8] 40 05 10 00 00 00 00 00"), frame("585 [8] 43 05 10 00 80 00 00 00"));
    assert_eq!(sdo(&mut bus, "605 [8] 40 29 10 00 00 00 00 00"), frame("585 [8] 4F 29 10 00 01 00 00 00"));
    assert_eq!(sdo(&mut bus, "605 [8] 23 03 10 01 00 00 00 00"), frame("585 [8] 80 03 10 01 02 00 01 06"));
    sdo_ok(
        &mut bus,
        &[
            "605 [8] 23 00 18 01 85 01 00 80", // off
            "605 [8] 2B 00 18 03 0A 00 00 00", // now the inhibit time may change
            "605 [8] 2F 00 18 06 02 00 00 00",
            "605 [8] 23 00 18 01 01 07 00 80", // 701h while not valid: fine...
        ],
    );
    // ...but not valid with a restricted ID (COB-13).
    assert_eq!(sdo(&mut bus, "605 [8] 23 00 18 01 01 07 00 00"), refused("605 [8] 23 00 18 01 01 07 00 00"));
    // 1014h: invalidate, move, validate (COB-16 sequence); EMCYs go to the new ID.
    sdo_ok(
        &mut bus,
        &["605 [8] 23 14 10 00 85 00 00 80", "605 [8] 23 14 10 00 90 00 00 80", "605 [8] 23 14 10 00 90 00 00 00"],
    );
    bus.stations[0].raise_error(0x1000, [0; 5]);
    bus.run_for_ms(0);
    assert_eq!(on(&bus, 0x090).len(), 1);
}
