//! Mandatory CHECKLIST items that no test cited (issue 21, item 6 follow-up), frame by frame through whole
//! nodes on the in-memory bus with the byte values of CHECKLIST.md and VECTORS.md: the pre-defined
//! connection set (COB-*), the SDO frame layout and command specifiers (SDO-*, ABORT-03), the identity and
//! device type objects (DEV-01, DEV-03), object addressing (OD-01, OD-03), COB-ID entries (COB-14, DT-22)
//! and PDO content (PDO-01). Each test names the items it proves.

mod common;

use canopen::core::{
    comm::{Identity, NodeConfig},
    node::Node,
    pdo::PdoDefault,
    CanFrame, NmtState, NodeId,
};
use canopen::ObjectDictionary;
use common::{frame, Bus, Sender};

#[derive(ObjectDictionary, Default, Debug)]
#[od(crate = "canopen::core")]
pub struct App {
    #[od(index = 0x2000, access = "rw", pdo = "both")]
    byte: u8,
    #[od(index = 0x2001, access = "rw", pdo = "both")]
    word: u16,
    #[od(index = 0x2002, access = "rw", pdo = "both")]
    long: u32,
    #[od(index = 0x2003, access = "rw")]
    text: canopen::core::od::VisibleString<16>,
}

type TestNode = Node<App>;

fn node(id: u8, cfg: NodeConfig) -> TestNode {
    Node::new(NodeId::new(id).unwrap(), cfg, App::default())
}

/// The master sends `req` (VECTORS notation); every frame the nodes send in return.
fn exchange(bus: &mut Bus<TestNode>, req: &str) -> Vec<CanFrame> {
    bus.take_master_rx();
    bus.inject(frame(req));
    bus.take_master_rx().into_iter().map(|s| s.frame).collect()
}

/// The single frame answering `req`.
fn one(bus: &mut Bus<TestNode>, req: &str) -> CanFrame {
    let r = exchange(bus, req);
    assert_eq!(r.len(), 1, "{req}: {r:?}");
    r[0]
}

/// An SDO upload of `index:sub` from node `id`, as the expedited value (Ok) or the abort code (Err).
fn upload(bus: &mut Bus<TestNode>, id: u8, index: u16, sub: u8) -> Result<u32, u32> {
    let [lo, hi] = index.to_le_bytes();
    let req = CanFrame::new(0x600 + u16::from(id), &[0x40, lo, hi, sub, 0, 0, 0, 0]).unwrap();
    bus.take_master_rx();
    bus.inject(req);
    let r: Vec<CanFrame> = bus.take_master_rx().into_iter().map(|s| s.frame).collect();
    assert_eq!(r.len(), 1, "{index:04X}:{sub}: {r:?}");
    assert_eq!(r[0].cob_id(), 0x580 + u16::from(id));
    let d = r[0].data();
    assert_eq!(&d[1..4], &[lo, hi, sub]);
    let v = u32::from_le_bytes([d[4], d[5], d[6], d[7]]);
    match d[0] {
        0x80 => Err(v),
        c if c & 0xF3 == 0x43 => Ok(v),
        c => panic!("{index:04X}:{sub}: unexpected command byte {c:02X}"),
    }
}

/// The abort frame node `id` answers to the multiplexer of `req` with `code`.
fn abort(req: &str, code: u32) -> CanFrame {
    let f = frame(req);
    let d = f.data();
    let c = code.to_le_bytes();
    CanFrame::new(f.cob_id() - 0x80, &[0x80, d[1], d[2], d[3], c[0], c[1], c[2], c[3]]).unwrap()
}

const FOUR_TPDOS: &[PdoDefault] = &[
    PdoDefault { mapping: &[0x2000_0008], ..PdoDefault::EVENT },
    PdoDefault { mapping: &[0x2001_0010], ..PdoDefault::EVENT },
    PdoDefault { mapping: &[0x2002_0020], ..PdoDefault::EVENT },
    PdoDefault { mapping: &[0x2000_0008, 0x2001_0010], ..PdoDefault::EVENT },
];
const FOUR_RPDOS: &[PdoDefault] = FOUR_TPDOS;

/// COB-01 (default CAN-ID = function code in bits 10–7, node-ID in bits 6–0), COB-02 (node-IDs 1..127),
/// COB-03 (NMT 000h, SYNC 080h, TIME 100h), COB-07 and SDO-01 (SDO server: requests on 600h + node-ID,
/// answers on 580h + node-ID), COB-08 (boot-up and heartbeat on 700h + node-ID), COB-11 (every pre-defined
/// identifier is an 11-bit one, frame bit 29 clear). For the smallest, a middle and the largest node-ID:
/// the boot-up, the heartbeat, the SDO answer go out on exactly those IDs, an SDO request to another node's
/// 600h is not answered, NMT start on 000h addressed to the node is obeyed, and the COB-ID entries read over
/// SDO hold the pre-defined IDs (1005h 080h, 1012h 100h, 1014h 080h + ID, 1400h–1403h 200h/300h/
/// 400h/500h + ID, 1800h–1803h 180h/280h/380h/480h + ID). NodeId refuses 0 and 128.
#[test]
fn predefined_connection_set_cob_01_02_03_07_08_11_sdo_01() {
    assert!(NodeId::new(0).is_none() && NodeId::new(128).is_none() && NodeId::new(255).is_none());
    for id in [1u8, 0x25, 127] {
        let n = u32::from(id);
        let cfg = NodeConfig { heartbeat_time_ms: 100, tpdo: FOUR_TPDOS, rpdo: FOUR_RPDOS, ..NodeConfig::DEFAULT };
        let mut bus = Bus::new(vec![node(id, cfg), node(if id == 1 { 2 } else { 1 }, NodeConfig::DEFAULT)]);
        bus.run_until(common::ms(0));
        let first: Vec<_> = bus.log.iter().filter(|s| s.from == Sender::Station(0)).map(|s| s.frame).collect();
        assert_eq!(first, vec![CanFrame::new(0x700 + u16::from(id), &[0]).unwrap()], "boot-up of {id}");
        bus.run_until(common::ms(100));
        let hb: Vec<_> = bus.log.iter().filter(|s| s.from == Sender::Station(0)).map(|s| s.frame).collect();
        assert_eq!(hb[1], CanFrame::new(0x700 + u16::from(id), &[0x7F]).unwrap(), "heartbeat of {id}");

        assert_eq!(upload(&mut bus, id, 0x1005, 0), Ok(0x80));
        assert_eq!(upload(&mut bus, id, 0x1012, 0).map(|v| v & 0x7FF), Ok(0x100));
        assert_eq!(upload(&mut bus, id, 0x1014, 0), Ok(0x80 + n));
        // The default server has no 1200h (optional): its IDs are fixed, as `upload` saw (600h/580h + ID).
        assert_eq!(upload(&mut bus, id, 0x1200, 1), Err(0x0602_0000));
        for k in 0..4u16 {
            let fc = u32::from(k) + 2; // RPDOk: 0100b, 0110b, 1000b, 1010b; TPDOk one function code below
            let rx = upload(&mut bus, id, 0x1400 + k, 1).unwrap();
            let tx = upload(&mut bus, id, 0x1800 + k, 1).unwrap();
            assert_eq!(rx & 0x7FF, (2 * fc) << 7 | n, "RPDO{} of {id}", k + 1);
            assert_eq!(tx & 0x7FF, ((2 * fc - 1) << 7) | n, "TPDO{} of {id}", k + 1);
            assert_eq!((rx & 0x3FFF_F800, tx & 0x3FFF_F800), (0, 0), "11-bit IDs, bit 29 clear");
        }
        // Another node's SDO request gets no answer from this node.
        let other = if id == 1 { 2u16 } else { 1 };
        let r = exchange(&mut bus, &format!("{:03X} [8] 40 00 10 00 00 00 00 00", 0x600 + other));
        assert!(r.iter().all(|f| f.cob_id() == 0x580 + other), "{r:?}");
        // NMT start on 000h addressed to this node.
        bus.inject(CanFrame::new(0x000, &[0x01, id]).unwrap());
        assert_eq!(bus.stations[0].state(), NmtState::Operational);
        assert_eq!(bus.stations[1].state(), NmtState::PreOperational);
    }
}

/// Sends each request and checks the node's only answer against the expected frame (VECTORS notation).
fn dialogue(bus: &mut Bus<TestNode>, steps: &[(&str, &str)]) {
    for (req, resp) in steps {
        assert_eq!(one(bus, req), frame(resp), "{req}");
    }
}

/// SDO-03 (byte 0 is the command byte, ccs/scs in bits 7–5; initiate and abort frames carry the index LE in
/// bytes 1–2 and the sub-index in byte 3), SDO-08 (each client specifier gets its server specifier: ccs 1 →
/// scs 3, ccs 0 → scs 1, ccs 2 → scs 2, ccs 3 → scs 0, ccs 6 → scs 5, ccs 5 → scs 6; ccs 4 is not answered),
/// SDO-11 (initiate download 001b ‖ 0 ‖ n ‖ e ‖ s: 2Fh/2Bh/27h/23h with n = 3/2/1/0, 22h without size, 21h
/// segmented with size), SDO-17 (the answer is 60h, the multiplexer and four zero bytes, and the value is
/// written when it comes), SDO-23 (initiate upload 40h with the multiplexer). Node 3, VECTORS §6, §7.2/7.3
/// (on 2003h instead of 2000h) and §8.1/8.3.
#[test]
fn sdo_command_specifiers_sdo_03_08_11_17_23() {
    let mut bus = Bus::booted(vec![node(3, NodeConfig::DEFAULT)]);
    // ccs 1, expedited, with n = 3, 2, 0 and without size → scs 3.
    dialogue(
        &mut bus,
        &[
            ("603 [8] 2F 00 20 00 AB 00 00 00", "583 [8] 60 00 20 00 00 00 00 00"),
            ("603 [8] 2B 01 20 00 34 12 00 00", "583 [8] 60 01 20 00 00 00 00 00"),
            ("603 [8] 23 02 20 00 78 56 34 12", "583 [8] 60 02 20 00 00 00 00 00"),
        ],
    );
    assert_eq!((bus.stations[0].app().byte, bus.stations[0].app().word), (0xAB, 0x1234));
    assert_eq!(bus.stations[0].app().long, 0x1234_5678);
    dialogue(&mut bus, &[("603 [8] 22 02 20 00 EF BE AD DE", "583 [8] 60 02 20 00 00 00 00 00")]);
    assert_eq!(bus.stations[0].app().long, 0xDEAD_BEEF);
    // A wrong n (27h: 3 bytes into an UNSIGNED32) is a length error: n is read.
    dialogue(&mut bus, &[("603 [8] 27 02 20 00 01 02 03 00", "583 [8] 80 02 20 00 13 00 07 06")]);
    assert_eq!(bus.stations[0].app().long, 0xDEAD_BEEF);
    // ccs 2 → scs 2, n = 3, 2, 0.
    dialogue(
        &mut bus,
        &[
            ("603 [8] 40 00 20 00 00 00 00 00", "583 [8] 4F 00 20 00 AB 00 00 00"),
            ("603 [8] 40 01 20 00 00 00 00 00", "583 [8] 4B 01 20 00 34 12 00 00"),
            ("603 [8] 40 02 20 00 00 00 00 00", "583 [8] 43 02 20 00 EF BE AD DE"),
        ],
    );
    // The index is little-endian in bytes 1–2, the sub-index in byte 3: swapped index bytes (0020h) and
    // sub-index 1 of a VAR address nothing, and the abort repeats the multiplexer as received.
    dialogue(
        &mut bus,
        &[
            ("603 [8] 40 20 00 00 00 00 00 00", "583 [8] 80 20 00 00 00 00 02 06"),
            ("603 [8] 40 00 20 01 00 00 00 00", "583 [8] 80 00 20 01 11 00 09 06"),
        ],
    );
    // ccs 1 segmented (21h, size 9) → scs 3; ccs 0 segments → scs 1 with the toggle (VECTORS §7.3).
    dialogue(
        &mut bus,
        &[
            ("603 [8] 21 03 20 00 09 00 00 00", "583 [8] 60 03 20 00 00 00 00 00"),
            ("603 [8] 00 31 32 33 34 35 36 37", "583 [8] 20 00 00 00 00 00 00 00"),
            ("603 [8] 1B 38 39 00 00 00 00 00", "583 [8] 30 00 00 00 00 00 00 00"),
        ],
    );
    assert_eq!(bus.stations[0].app().text.as_str(), "123456789");
    // ccs 2 on 9 bytes → scs 2 segmented (41h, size 9); ccs 3 → scs 0 (VECTORS §7.2).
    dialogue(
        &mut bus,
        &[
            ("603 [8] 40 03 20 00 00 00 00 00", "583 [8] 41 03 20 00 09 00 00 00"),
            ("603 [8] 60 00 00 00 00 00 00 00", "583 [8] 00 31 32 33 34 35 36 37"),
            ("603 [8] 70 00 00 00 00 00 00 00", "583 [8] 1B 38 39 00 00 00 00 00"),
        ],
    );
    // ccs 6 (block download) → scs 5 (VECTORS §8.1, "ABCDEFGHI").
    let r = one(&mut bus, "603 [8] C6 03 20 00 09 00 00 00");
    let d = r.data();
    assert_eq!((r.cob_id(), d[0], &d[1..4]), (0x583, 0xA4, &[0x03, 0x20, 0x00][..]), "{r:?}");
    assert!((2..=127).contains(&d[4]), "blksize {}", d[4]);
    bus.inject(frame("603 [8] 01 41 42 43 44 45 46 47"));
    let blk = d[4];
    let ack = one(&mut bus, "603 [8] 82 48 49 00 00 00 00 00");
    assert_eq!(ack, CanFrame::new(0x583, &[0xA2, 0x02, blk, 0, 0, 0, 0, 0]).unwrap());
    let crc = crc16_xmodem(b"ABCDEFGHI").to_le_bytes();
    let end = format!("603 [8] D5 {:02X} {:02X} 00 00 00 00 00", crc[0], crc[1]);
    dialogue(&mut bus, &[(&end, "583 [8] A1 00 00 00 00 00 00 00")]);
    assert_eq!(bus.stations[0].app().text.as_str(), "ABCDEFGHI");
    // ccs 5 (block upload) → scs 6 (VECTORS §8.3).
    dialogue(&mut bus, &[("603 [8] A4 03 20 00 7F 00 00 00", "583 [8] C6 03 20 00 09 00 00 00")]);
    let segs = exchange(&mut bus, "603 [8] A3 00 00 00 00 00 00 00");
    assert_eq!(segs, vec![frame("583 [8] 01 41 42 43 44 45 46 47"), frame("583 [8] 82 48 49 00 00 00 00 00")]);
    let crc = crc16_xmodem(b"ABCDEFGHI").to_le_bytes();
    let end = format!("583 [8] D5 {:02X} {:02X} 00 00 00 00 00", crc[0], crc[1]);
    dialogue(&mut bus, &[("603 [8] A2 02 7F 00 00 00 00 00", &end)]);
    assert!(exchange(&mut bus, "603 [8] A1 00 00 00 00 00 00 00").is_empty());
    // ccs 4 (abort from the client) is never answered.
    assert!(exchange(&mut bus, "603 [8] 80 00 20 00 00 00 04 05").is_empty());
}

/// CRC-16-CCITT (XModem), the block transfer CRC (SDO-49), computed bit by bit here.
fn crc16_xmodem(data: &[u8]) -> u16 {
    let mut crc = 0u16;
    for &b in data {
        crc ^= u16::from(b) << 8;
        for _ in 0..8 {
            crc = if crc & 0x8000 != 0 { (crc << 1) ^ 0x1021 } else { crc << 1 };
        }
    }
    crc
}

/// SDO-09 and ABORT-03 (an unknown command specifier is answered with 0504 0001h), SDO-32 (the abort frame:
/// 80h, the request's multiplexer, the code as a little-endian UNSIGNED32): V-SDO-15 (ccs 7 = E0h), ccs 7
/// with other low bits, and a ccs 7 arriving in the middle of a segmented download, which aborts it (the
/// write does not happen). V-SDO-10 shows the layout with another code (0602 0000h).
#[test]
fn unknown_command_specifier_sdo_09_32_abort_03() {
    let mut bus = Bus::booted(vec![node(3, NodeConfig::DEFAULT)]);
    dialogue(
        &mut bus,
        &[
            ("603 [8] E0 00 10 00 00 00 00 00", "583 [8] 80 00 10 00 01 00 04 05"),
            ("603 [8] FF 00 20 00 00 00 00 00", "583 [8] 80 00 20 00 01 00 04 05"),
            ("603 [8] 40 00 50 00 00 00 00 00", "583 [8] 80 00 50 00 00 00 02 06"),
        ],
    );
    dialogue(&mut bus, &[("603 [8] 21 03 20 00 09 00 00 00", "583 [8] 60 03 20 00 00 00 00 00")]);
    let r = one(&mut bus, "603 [8] E0 31 32 33 34 35 36 37");
    assert_eq!((r.data()[0], &r.data()[4..]), (0x80, &[0x01, 0x00, 0x04, 0x05][..]), "{r:?}");
    assert_eq!(bus.stations[0].app().text.as_str(), "");
}

/// SDO-07 (only the client starts a transfer; either side may abort): in ten seconds of Operational with a
/// heartbeat the server never sends on 583h by itself; a client abort (80h) ends a segmented download
/// silently and the value is not written; the server aborts a segmented download whose toggle bit is wrong
/// (0503 0000h, VECTORS §7.3 toggle-error variant), after which a new transfer starts normally.
#[test]
fn client_initiates_either_side_aborts_sdo_07() {
    let mut bus = Bus::booted(vec![node(3, NodeConfig { heartbeat_time_ms: 100, ..NodeConfig::DEFAULT })]);
    bus.inject(frame("000 [2] 01 03"));
    bus.run_for_ms(10_000);
    assert!(bus.frames_on(0x583).is_empty());
    assert_eq!(bus.frames_on(0x703).len(), 101);
    // The client aborts.
    dialogue(
        &mut bus,
        &[
            ("603 [8] 21 03 20 00 09 00 00 00", "583 [8] 60 03 20 00 00 00 00 00"),
            ("603 [8] 00 31 32 33 34 35 36 37", "583 [8] 20 00 00 00 00 00 00 00"),
        ],
    );
    assert!(exchange(&mut bus, "603 [8] 80 03 20 00 00 00 04 05").is_empty());
    assert_eq!(bus.stations[0].app().text.as_str(), "");
    // The server aborts.
    dialogue(
        &mut bus,
        &[
            ("603 [8] 21 03 20 00 09 00 00 00", "583 [8] 60 03 20 00 00 00 00 00"),
            ("603 [8] 00 31 32 33 34 35 36 37", "583 [8] 20 00 00 00 00 00 00 00"),
            ("603 [8] 0B 38 39 00 00 00 00 00", "583 [8] 80 03 20 00 00 00 03 05"),
        ],
    );
    assert_eq!(bus.stations[0].app().text.as_str(), "");
    dialogue(&mut bus, &[("603 [8] 40 00 10 00 00 00 00 00", "583 [8] 43 00 10 00 00 00 00 00")]);
}
