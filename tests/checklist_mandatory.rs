//! Mandatory requirements (`docs/CONFORMANCE.md`) that no test cited (issue 21, item 6 follow-up), frame by frame through whole
//! nodes on the in-memory bus with the byte values of the CiA 301 requirements (`docs/CONFORMANCE.md`) and their test vectors: the pre-defined
//! connection set (COB-*), the SDO frame layout and command specifiers (SDO-*, ABORT-03), the identity and
//! device type objects (DEV-01, DEV-03), object addressing (OD-01, OD-03), COB-ID entries (COB-14, DT-22)
//! and PDO content (PDO-01). Each test names the items it proves.

mod common;

use canopen::core::{
    node::Node,
    pdo::PdoDefault,
    profile::{Identity, NodeConfig},
    CanFrame, NmtState, NodeId,
};
use canopen::ObjectDictionary;
use common::{frame, Bus, Sender, Station};

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

/// The master sends `req` ("COB-ID [DLC] bytes"); every frame the nodes send in return.
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
fn upload<S: Station>(bus: &mut Bus<S>, id: u8, index: u16, sub: u8) -> Result<u32, u32> {
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
/// 400h/500h + ID, 1800h–1803h 180h/280h/380h/480h + ID). NodeId refuses 0 and 128. The same reads prove
/// COB-04 (EMCY 080h + ID), COB-06 (RPDO1-4 200h/300h/400h/500h + ID) and COB-12 (the generic pre-defined
/// set of 1400h-1403h and 1800h-1803h).
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

/// Sends each request and checks the node's only answer against the expected frame ("COB-ID [DLC] bytes").
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
/// written when it comes), SDO-23 (initiate upload 40h with the multiplexer). Node 3
/// (on 2003h instead of 2000h) and §8.1/8.3.
///
/// The same frames prove the segmented and block layouts: SDO-05 (a 9-byte object goes segmented), SDO-14
/// (21h with the size in bytes 4–7), SDO-19 (download segments 00h and 1Bh: t, n = 5 unused bytes, c on the
/// last; exactly "123456789" is written), SDO-20 (answers 20h/30h, zeros), SDO-21 (t starts at 0, alternates,
/// is echoed), SDO-22 (the write completes with the answer to the c = 1 segment, 9 bytes as announced),
/// SDO-25 (41h with the size), SDO-26 (60h/70h), SDO-27 (00h then 1Bh: t, n, c), SDO-35 (C6h: cc, s, size),
/// SDO-36 (A4h, multiplexer, blksize 1..127, zeros), SDO-39 (A2h, ackseq 2, blksize after the c = 1
/// segment), SDO-42 (A4h, blksize 7Fh, pst 0), SDO-44 (C6h with the size), SDO-45 (nothing until A3h, then
/// the sub-block), SDO-46 (segments, the client's A2h acknowledgement, then the end). SDO-06: block transfer,
/// optional, is offered both ways.
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
    // ccs 1 segmented (21h, size 9) → scs 3; ccs 0 segments → scs 1 with the toggle.
    dialogue(
        &mut bus,
        &[
            ("603 [8] 21 03 20 00 09 00 00 00", "583 [8] 60 03 20 00 00 00 00 00"),
            ("603 [8] 00 31 32 33 34 35 36 37", "583 [8] 20 00 00 00 00 00 00 00"),
            ("603 [8] 1B 38 39 00 00 00 00 00", "583 [8] 30 00 00 00 00 00 00 00"),
        ],
    );
    assert_eq!(bus.stations[0].app().text.as_str(), "123456789");
    // ccs 2 on 9 bytes → scs 2 segmented (41h, size 9); ccs 3 → scs 0.
    dialogue(
        &mut bus,
        &[
            ("603 [8] 40 03 20 00 00 00 00 00", "583 [8] 41 03 20 00 09 00 00 00"),
            ("603 [8] 60 00 00 00 00 00 00 00", "583 [8] 00 31 32 33 34 35 36 37"),
            ("603 [8] 70 00 00 00 00 00 00 00", "583 [8] 1B 38 39 00 00 00 00 00"),
        ],
    );
    // ccs 6 (block download) → scs 5 ("ABCDEFGHI").
    let r = one(&mut bus, "603 [8] C6 03 20 00 09 00 00 00");
    let d = r.data();
    assert_eq!((r.cob_id(), d[0], &d[1..4]), (0x583, 0xA4, &[0x03, 0x20, 0x00][..]), "{r:?}");
    assert!((2..=127).contains(&d[4]), "blksize {}", d[4]);
    assert_eq!(&d[5..], &[0, 0, 0]);
    bus.inject(frame("603 [8] 01 41 42 43 44 45 46 47"));
    let blk = d[4];
    let ack = one(&mut bus, "603 [8] 82 48 49 00 00 00 00 00");
    assert_eq!(ack, CanFrame::new(0x583, &[0xA2, 0x02, blk, 0, 0, 0, 0, 0]).unwrap());
    let crc = crc16_xmodem(b"ABCDEFGHI").to_le_bytes();
    let end = format!("603 [8] D5 {:02X} {:02X} 00 00 00 00 00", crc[0], crc[1]);
    dialogue(&mut bus, &[(&end, "583 [8] A1 00 00 00 00 00 00 00")]);
    assert_eq!(bus.stations[0].app().text.as_str(), "ABCDEFGHI");
    // ccs 5 (block upload) → scs 6.
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
/// 80h, the request's multiplexer, the code as a little-endian UNSIGNED32): ccs 7 = E0h, ccs 7
/// with other low bits, and a ccs 7 arriving in the middle of a segmented download, which aborts it (the
/// write does not happen). 5000h absent shows the layout with another code (80 00 50 00 00 00 02 06).
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
/// (0503 0000h: the last segment sent with t = 0 again, ABORT-01), after which a new transfer starts normally.
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

/// An SDO expedited download of a 4-byte value to node `id`: Ok, or the abort code.
fn download(bus: &mut Bus<TestNode>, id: u8, index: u16, sub: u8, value: u32) -> Result<(), u32> {
    download_n(bus, id, index, sub, value, 4)
}

/// An SDO expedited download of the `len` low bytes of `value` (n = 4 - len).
fn download_n(bus: &mut Bus<TestNode>, id: u8, index: u16, sub: u8, value: u32, len: u8) -> Result<(), u32> {
    let [lo, hi] = index.to_le_bytes();
    let v = value.to_le_bytes();
    let cmd = 0x23 | (4 - len) << 2;
    let req = CanFrame::new(0x600 + u16::from(id), &[cmd, lo, hi, sub, v[0], v[1], v[2], v[3]]).unwrap();
    bus.take_master_rx();
    bus.inject(req);
    let r: Vec<CanFrame> = bus.take_master_rx().into_iter().map(|s| s.frame).collect();
    assert_eq!(r.len(), 1, "{index:04X}:{sub}: {r:?}");
    let d = r[0].data();
    assert_eq!(&d[1..4], &[lo, hi, sub]);
    match d[0] {
        0x60 => Ok(()),
        0x80 => Err(u32::from_le_bytes([d[4], d[5], d[6], d[7]])),
        c => panic!("{index:04X}:{sub}: unexpected command byte {c:02X}"),
    }
}

/// DEV-01 (1000h device type: UNSIGNED32, read-only, not mappable; the profile number in bits 15–0 and the
/// additional information in bits 31–16) and DEV-03 (1018h identity: sub 00h const 4, then vendor-ID,
/// product code, revision and serial number, all read-only UNSIGNED32): the values of the configuration come
/// back byte for byte (43 18 10 01 v0 v1 v2 v3), every write is refused with 0601 0002h, 1018h:05 does not exist,
/// and mapping 1000h into a TPDO is refused with 0604 0041h (ABORT-12).
#[test]
fn device_type_and_identity_dev_01_dev_03() {
    let cfg = NodeConfig {
        device_type: 0x0002_0191,
        identity: Identity { vendor_id: 0x0000_02B6, product_code: 0x0000_1234, revision: 0x0001_0002, serial: 42 },
        tpdo: FOUR_TPDOS,
        ..NodeConfig::DEFAULT
    };
    let mut bus = Bus::booted(vec![node(1, cfg)]);
    dialogue(
        &mut bus,
        &[
            ("601 [8] 40 00 10 00 00 00 00 00", "581 [8] 43 00 10 00 91 01 02 00"),
            ("601 [8] 40 18 10 00 00 00 00 00", "581 [8] 4F 18 10 00 04 00 00 00"),
            ("601 [8] 40 18 10 01 00 00 00 00", "581 [8] 43 18 10 01 B6 02 00 00"),
            ("601 [8] 40 18 10 02 00 00 00 00", "581 [8] 43 18 10 02 34 12 00 00"),
            ("601 [8] 40 18 10 03 00 00 00 00", "581 [8] 43 18 10 03 02 00 01 00"),
            ("601 [8] 40 18 10 04 00 00 00 00", "581 [8] 43 18 10 04 2A 00 00 00"),
            ("601 [8] 40 18 10 05 00 00 00 00", "581 [8] 80 18 10 05 11 00 09 06"),
            ("601 [8] 2F 18 10 00 04 00 00 00", "581 [8] 80 18 10 00 02 00 01 06"),
        ],
    );
    for (index, sub) in [(0x1000u16, 0u8), (0x1018, 1), (0x1018, 2), (0x1018, 3), (0x1018, 4)] {
        assert_eq!(download(&mut bus, 1, index, sub, 7), Err(0x0601_0002), "{index:04X}:{sub}");
    }
    assert_eq!(upload(&mut bus, 1, 0x1018, 4), Ok(42));
    // Not mappable: TPDO1 made invalid, its mapping emptied, then 1000h offered as an entry.
    let cob = upload(&mut bus, 1, 0x1800, 1).unwrap();
    assert_eq!(download(&mut bus, 1, 0x1800, 1, cob | 0x8000_0000), Ok(()));
    assert_eq!(download_n(&mut bus, 1, 0x1A00, 0, 0, 1), Ok(()));
    assert_eq!(download(&mut bus, 1, 0x1A00, 1, 0x1000_0020), Err(0x0604_0041));
    assert_eq!(download(&mut bus, 1, 0x1A00, 1, 0x2002_0020), Ok(()));
}

/// OD-01 (an entry is addressed by a 16-bit index and an 8-bit sub-index) and OD-03 (a VAR is at sub-index
/// 00h only): 1018h:01 and 1018h:04 are different entries; 1810h (the index bytes swapped) does not exist; the VARs 1017h and 2000h answer at 00h and refuse 01h and FFh with 0609 0011h; a write to 2000h:00
/// changes only 2000h.
#[test]
fn object_addressing_od_01_od_03() {
    let cfg = NodeConfig {
        heartbeat_time_ms: 0x64,
        identity: Identity { vendor_id: 1, product_code: 2, revision: 3, serial: 4 },
        ..NodeConfig::DEFAULT
    };
    let mut bus = Bus::booted(vec![node(2, cfg)]);
    assert_eq!(upload(&mut bus, 2, 0x1018, 1), Ok(1));
    assert_eq!(upload(&mut bus, 2, 0x1018, 4), Ok(4));
    assert_eq!(upload(&mut bus, 2, 0x1810, 1), Err(0x0602_0000));
    assert_eq!(upload(&mut bus, 2, 0x1017, 0), Ok(0x64));
    for sub in [1u8, 0xFF] {
        assert_eq!(upload(&mut bus, 2, 0x1017, sub), Err(0x0609_0011), "1017h:{sub}");
        assert_eq!(upload(&mut bus, 2, 0x2000, sub), Err(0x0609_0011), "2000h:{sub}");
    }
    dialogue(&mut bus, &[("602 [8] 2F 00 20 00 5A 00 00 00", "582 [8] 60 00 20 00 00 00 00 00")]);
    let app = bus.stations[0].app();
    assert_eq!((app.byte, app.word, app.long), (0x5A, 0, 0));
}

/// COB-14 (every COB-ID entry has the same layout: bit 31 and 30 object-specific, bit 29 the frame type,
/// bits 10–0 the 11-bit CAN-ID with bits 28–11 zero) and DT-22 (such structured UNSIGNED32 entries travel
/// as one little-endian UNSIGNED32): on 1005h, 1014h, 1400h and 1800h, bit 29 and any of bits 28–11 are
/// refused with 0609 0030h; bit 31 makes TPDO1 invalid (a trigger sends nothing) and clearing it valid
/// again; the new CAN-ID written as the bytes A3 01 00 80 is 0x8000_01A3 and TPDO1 goes out on 1A3h; the
/// mapping written as 10 00 01 20 (2001h:00, 16 bits) reads back as those bytes and makes a 2-byte TPDO.
/// PDO-05 (variable mapping: the PDO configuration is changed over SDO).
#[test]
fn cob_id_entry_layout_cob_14_dt_22() {
    let cfg = NodeConfig { tpdo: FOUR_TPDOS, rpdo: FOUR_RPDOS, ..NodeConfig::DEFAULT };
    let mut bus = Bus::booted(vec![node(3, cfg)]);
    for (index, sub) in [(0x1005u16, 0u8), (0x1014, 0), (0x1400, 1), (0x1800, 1)] {
        let cur = upload(&mut bus, 3, index, sub).unwrap();
        let off = if index == 0x1005 { cur } else { cur | 0x8000_0000 };
        assert_eq!(download(&mut bus, 3, index, sub, off), Ok(()), "{index:04X}");
        for bad in [off | 0x2000_0000, off | 0x0000_0800, off | 0x1000_0000, off | 0x0004_0000] {
            assert_eq!(download(&mut bus, 3, index, sub, bad), Err(0x0609_0030), "{index:04X} {bad:08X}");
        }
        assert_eq!(upload(&mut bus, 3, index, sub), Ok(off), "{index:04X} unchanged");
    }
    bus.inject(frame("000 [2] 01 03"));
    bus.stations[0].app_mut().word = 0xBEEF;
    assert!(!bus.stations[0].trigger_tpdo(0), "TPDO1 is invalid");
    bus.take_master_rx();
    dialogue(
        &mut bus,
        &[
            ("603 [8] 23 00 18 01 A3 01 00 80", "583 [8] 60 00 18 01 00 00 00 00"),
            ("603 [8] 2F 00 1A 00 00 00 00 00", "583 [8] 60 00 1A 00 00 00 00 00"),
            ("603 [8] 23 00 1A 01 10 00 01 20", "583 [8] 60 00 1A 01 00 00 00 00"),
            ("603 [8] 2F 00 1A 00 01 00 00 00", "583 [8] 60 00 1A 00 00 00 00 00"),
            ("603 [8] 40 00 1A 01 00 00 00 00", "583 [8] 43 00 1A 01 10 00 01 20"),
            ("603 [8] 40 00 18 01 00 00 00 00", "583 [8] 43 00 18 01 A3 01 00 80"),
        ],
    );
    assert!(!bus.stations[0].trigger_tpdo(0), "still invalid");
    dialogue(&mut bus, &[("603 [8] 23 00 18 01 A3 01 00 00", "583 [8] 60 00 18 01 00 00 00 00")]);
    assert!(bus.stations[0].trigger_tpdo(0));
    bus.run_for_ms(1);
    assert_eq!(bus.frames_on(0x1A3), vec![(bus.now.as_micros() / 1000 - 1, vec![0xEF, 0xBE])]);
    assert!(bus.frames_on(0x183).is_empty());
}

/// COB-10 (the pre-defined IDs apply whenever Pre-operational is entered after initialisation): TPDO1
/// moved to 1A3h and the EMCY to 0A3h over SDO are back at 183h and 083h after NMT reset communication (82h),
/// and TPDO1 goes out on 183h again; the same after reset node (81h).
#[test]
fn default_ids_after_reset_cob_10() {
    let cfg = NodeConfig { tpdo: FOUR_TPDOS, ..NodeConfig::DEFAULT };
    let mut bus = Bus::booted(vec![node(3, cfg)]);
    let tpdo = upload(&mut bus, 3, 0x1800, 1).unwrap();
    assert_eq!((tpdo & 0x7FF, upload(&mut bus, 3, 0x1014, 0)), (0x183, Ok(0x83)));
    for reset in ["000 [2] 82 03", "000 [2] 81 03"] {
        assert_eq!(download(&mut bus, 3, 0x1800, 1, 0x8000_01A3), Ok(()));
        assert_eq!(download(&mut bus, 3, 0x1800, 1, 0x0000_01A3), Ok(()));
        assert_eq!(download(&mut bus, 3, 0x1014, 0, 0x8000_0083), Ok(()));
        assert_eq!(download(&mut bus, 3, 0x1014, 0, 0x0000_00A3), Ok(()));
        assert_eq!(upload(&mut bus, 3, 0x1800, 1), Ok(0x0000_01A3));
        let boot = exchange(&mut bus, reset);
        assert_eq!(boot, vec![frame("703 [1] 00")], "{reset}");
        assert_eq!(bus.stations[0].state(), NmtState::PreOperational);
        assert_eq!(upload(&mut bus, 3, 0x1800, 1), Ok(tpdo), "{reset}");
        assert_eq!(upload(&mut bus, 3, 0x1014, 0), Ok(0x83), "{reset}");
        bus.log.clear();
        bus.inject(frame("000 [2] 01 03"));
        assert!(bus.stations[0].trigger_tpdo(0));
        bus.run_for_ms(1);
        assert!(bus.frames_on(0x1A3).is_empty());
        assert!(!bus.frames_on(0x183).is_empty(), "{reset}");
    }
}

/// PDO-01 (a PDO carries only the mapped data, 0 to 8 bytes, with no protocol bytes, and is not confirmed):
/// TPDO1 maps one byte and goes out with DLC 1 holding just that byte, TPDO4 maps a byte and a word and goes
/// out with DLC 3; TPDO2 with its mapping emptied (1A01h:00 = 0) goes out with DLC 0; RPDO1 received from the
/// master is applied and nothing answers it.
#[test]
fn pdo_carries_only_mapped_data_pdo_01() {
    let cfg = NodeConfig { tpdo: FOUR_TPDOS, rpdo: FOUR_RPDOS, ..NodeConfig::DEFAULT };
    let mut bus = Bus::booted(vec![node(4, cfg)]);
    let cob = upload(&mut bus, 4, 0x1801, 1).unwrap();
    assert_eq!(download(&mut bus, 4, 0x1801, 1, cob | 0x8000_0000), Ok(()));
    assert_eq!(download_n(&mut bus, 4, 0x1A01, 0, 0, 1), Ok(()));
    assert_eq!(download(&mut bus, 4, 0x1801, 1, cob), Ok(()));
    bus.inject(frame("000 [2] 01 04"));
    bus.run_for_ms(1);
    bus.log.clear(); // entering Operational sent each event-driven TPDO once (PDO-28)
    {
        let app = bus.stations[0].app_mut();
        app.byte = 0x11;
        app.word = 0x3322;
    }
    for k in [0, 1, 3] {
        assert!(bus.stations[0].trigger_tpdo(k), "TPDO{}", k + 1);
    }
    bus.run_for_ms(1);
    assert_eq!(bus.frames_on(0x184), vec![(1, vec![0x11])]);
    assert_eq!(bus.frames_on(0x284), vec![(1, vec![])]);
    assert_eq!(bus.frames_on(0x484), vec![(1, vec![0x11, 0x22, 0x33])]);
    assert!(exchange(&mut bus, "204 [1] 55").is_empty());
    assert_eq!(bus.stations[0].app().byte, 0x55);
}

/// COB-09 (the pre-defined set allocates identifiers only to the objects the device has): a node built with
/// no PDOs has no 1400h/1600h/1800h/1A00h at all; a node with four PDO slots of which none is configured
/// has all of them invalid (bit 31); neither sends a PDO in a second of Operational, while the node whose
/// four TPDOs are configured does; none has a second SDO server (1201h).
#[test]
fn identifiers_only_for_existing_objects_cob_09() {
    let mut none: Bus<Node<App, canopen::core::Sizes<4, 16, 16, 0, 0>>> =
        Bus::booted(vec![Node::new(NodeId::new(6).unwrap(), NodeConfig::DEFAULT, App::default())]);
    for index in [0x1400u16, 0x1600, 0x1800, 0x1A00, 0x1201] {
        assert_eq!(upload(&mut none, 6, index, 1), Err(0x0602_0000), "{index:04X}");
    }
    assert_eq!(upload(&mut none, 6, 0x1014, 0), Ok(0x86));
    let mut unused = Bus::booted(vec![
        node(6, NodeConfig::DEFAULT),
        node(7, NodeConfig { tpdo: FOUR_TPDOS, ..NodeConfig::DEFAULT }),
    ]);
    for k in 0..4u16 {
        for index in [0x1400 + k, 0x1800 + k] {
            assert_eq!(upload(&mut unused, 6, index, 1).map(|v| v >> 31), Ok(1), "{index:04X} invalid");
            assert_eq!(upload(&mut unused, 7, index, 1).map(|v| v >> 31), Ok(u32::from(index < 0x1800)));
        }
    }
    for bus_frames in [
        {
            none.inject(frame("000 [2] 01 00"));
            none.stations[0].app_mut().byte = 1;
            none.run_for_ms(1000);
            none.log.iter().map(|s| s.frame.cob_id()).collect::<Vec<_>>()
        },
        {
            unused.inject(frame("000 [2] 01 00"));
            unused.stations[0].app_mut().byte = 1;
            unused.run_for_ms(1000);
            unused.log.iter().filter(|s| s.from == Sender::Station(0)).map(|s| s.frame.cob_id()).collect()
        },
    ] {
        assert!(bus_frames.iter().all(|id| !(0x180..0x580).contains(id)), "{bus_frames:03X?}");
    }
    let configured: Vec<u16> =
        unused.log.iter().filter(|s| s.from == Sender::Station(1)).map(|s| s.frame.cob_id()).collect();
    for id in [0x187, 0x287, 0x387, 0x487] {
        assert!(configured.contains(&id), "{id:03X}: {configured:03X?}");
    }
}

/// The block upload of `text` from 2003h on node 3 with the client's `blksize` and CRC (A4h/A0h, start A3h, acknowledge A2h, end A1h):
/// every frame the server sends after the start (A3h) and after each acknowledgement, sub-block by sub-block.
fn block_upload_sub_blocks(bus: &mut Bus<TestNode>, blksize: u8, sub_blocks: &[&[&str]], end: &str) {
    let init = format!("603 [8] A4 03 20 00 {blksize:02X} 00 00 00");
    let r = one(bus, &init);
    assert_eq!(r.data()[0], 0xC6, "{r:?}");
    let mut trigger = "603 [8] A3 00 00 00 00 00 00 00".to_string();
    for blk in sub_blocks {
        let got = exchange(bus, &trigger);
        let want: Vec<CanFrame> = blk.iter().map(|f| frame(f)).collect();
        assert_eq!(got, want, "after {trigger}");
        trigger = format!("603 [8] A2 {:02X} {blksize:02X} 00 00 00 00 00", blk.len());
    }
    dialogue(bus, &[(&trigger, end)]);
    assert!(exchange(bus, "603 [8] A1 00 00 00 00 00 00 00").is_empty());
}

/// SDO-15 (20h: segmented download without a size), SDO-38 (seqno restarts at 1 in every sub-block, up to
/// blksize), SDO-51 (a block transfer has at least one sub-block: 16 bytes in blocks of 2 segments make two
/// sub-blocks), SDO-43 (protocol switch: pst 21 ≥ 9 bytes → a segmented upload 41h; a 2-byte object →
/// expedited), SDO-48 and SDO-50/ABORT-06 (the CRC counts only when cc and sc were both 1:
/// with C2h (cc 0) a CRC of 0000h is accepted; with C6h a wrong CRC is 0504 0004h),
/// ABORT-04 (a client blksize of 0 or 80h is 0504 0002h) and ABORT-05 (a block-download segment with seqno
/// 0 is 0504 0003h).
#[test]
fn segmented_and_block_variants_sdo_15_38_43_48_50_51_abort_04_05_06() {
    let mut bus = Bus::booted(vec![node(3, NodeConfig { heartbeat_time_ms: 100, ..NodeConfig::DEFAULT })]);
    // SDO-15.
    dialogue(
        &mut bus,
        &[
            ("603 [8] 20 03 20 00 00 00 00 00", "583 [8] 60 03 20 00 00 00 00 00"),
            ("603 [8] 00 41 42 43 44 45 46 47", "583 [8] 20 00 00 00 00 00 00 00"),
            ("603 [8] 10 48 49 4A 4B 4C 4D 4E", "583 [8] 30 00 00 00 00 00 00 00"),
            ("603 [8] 0B 4F 50 00 00 00 00 00", "583 [8] 20 00 00 00 00 00 00 00"),
        ],
    );
    assert_eq!(bus.stations[0].app().text.as_str(), "ABCDEFGHIJKLMNOP");
    // SDO-38, SDO-51: blksize 2, 16 bytes = 3 segments = two sub-blocks, the second restarting at seqno 1.
    let crc = crc16_xmodem(b"ABCDEFGHIJKLMNOP").to_le_bytes();
    block_upload_sub_blocks(
        &mut bus,
        2,
        &[
            &["583 [8] 01 41 42 43 44 45 46 47", "583 [8] 02 48 49 4A 4B 4C 4D 4E"],
            &["583 [8] 81 4F 50 00 00 00 00 00"],
        ],
        &format!("583 [8] D5 {:02X} {:02X} 00 00 00 00 00", crc[0], crc[1]),
    );
    // SDO-43.
    dialogue(
        &mut bus,
        &[
            ("603 [8] A4 03 20 00 7F 15 00 00", "583 [8] 41 03 20 00 10 00 00 00"),
            ("603 [8] 60 00 00 00 00 00 00 00", "583 [8] 00 41 42 43 44 45 46 47"),
            ("603 [8] 70 00 00 00 00 00 00 00", "583 [8] 10 48 49 4A 4B 4C 4D 4E"),
            ("603 [8] 60 00 00 00 00 00 00 00", "583 [8] 0B 4F 50 00 00 00 00 00"),
            ("603 [8] A4 17 10 00 7F 15 00 00", "583 [8] 4B 17 10 00 64 00 00 00"),
        ],
    );
    // SDO-48: no CRC asked (C2h), so a CRC of 0000h is not checked.
    let r = one(&mut bus, "603 [8] C2 03 20 00 03 00 00 00");
    assert_eq!(r.data()[0] & 0xFB, 0xA0, "{r:?}");
    bus.inject(frame("603 [8] 81 78 79 7A 00 00 00 00"));
    bus.take_master_rx();
    dialogue(&mut bus, &[("603 [8] D1 00 00 00 00 00 00 00", "583 [8] A1 00 00 00 00 00 00 00")]);
    assert_eq!(bus.stations[0].app().text.as_str(), "xyz");
    // SDO-50, ABORT-06: CRC asked and wrong.
    let r = one(&mut bus, "603 [8] C6 03 20 00 03 00 00 00");
    assert_eq!(r.data()[0], 0xA4, "{r:?}");
    bus.inject(frame("603 [8] 81 31 32 33 00 00 00 00"));
    bus.take_master_rx();
    dialogue(&mut bus, &[("603 [8] D1 00 00 00 00 00 00 00", "583 [8] 80 03 20 00 04 00 04 05")]);
    // What the object holds after this abort: `aborted_downloads_leave_the_old_value`.
    // ABORT-04: blksize 0 and 80h at a block upload initiate.
    for b in ["00", "80"] {
        let req = format!("603 [8] A4 03 20 00 {b} 00 00 00");
        dialogue(&mut bus, &[(&req, "583 [8] 80 03 20 00 02 00 04 05")]);
    }
    // ABORT-05: seqno 0 in a block download.
    let r = one(&mut bus, "603 [8] C6 03 20 00 03 00 00 00");
    assert_eq!(r.data()[0], 0xA4, "{r:?}");
    let r = exchange(&mut bus, "603 [8] 80 31 32 33 00 00 00 00");
    assert!(r.is_empty(), "80h here is the client's abort, not a segment: {r:?}");
    let r = one(&mut bus, "603 [8] C6 03 20 00 03 00 00 00");
    assert_eq!(r.data()[0], 0xA4, "{r:?}");
    dialogue(&mut bus, &[("603 [8] 00 31 32 33 00 00 00 00", "583 [8] 80 03 20 00 03 00 04 05")]);
}

/// An aborted download must not change the object: the value read afterwards is the old one, whether the
/// client aborted a segmented download (SDO-33) or the server aborted a block download for a wrong CRC
/// (SDO-50). The string types (VISIBLE/OCTET/UNICODE_STRING) stage the streamed bytes apart from their value
/// and the derived dictionary stores the new value only when the transfer ends (`OdValue::end_stream`).
#[test]
fn aborted_downloads_leave_the_old_value() {
    let mut bus = Bus::booted(vec![node(3, NodeConfig::DEFAULT)]);
    let set_xyz = |bus: &mut Bus<TestNode>| {
        dialogue(bus, &[("603 [8] 27 03 20 00 78 79 7A 00", "583 [8] 60 03 20 00 00 00 00 00")]);
        assert_eq!(bus.stations[0].app().text.as_str(), "xyz");
    };
    set_xyz(&mut bus);
    dialogue(
        &mut bus,
        &[
            ("603 [8] 21 03 20 00 09 00 00 00", "583 [8] 60 03 20 00 00 00 00 00"),
            ("603 [8] 00 31 32 33 34 35 36 37", "583 [8] 20 00 00 00 00 00 00 00"),
        ],
    );
    assert!(exchange(&mut bus, "603 [8] 80 03 20 00 00 00 04 05").is_empty());
    assert_eq!(bus.stations[0].app().text.as_str(), "xyz", "after a client abort");
    set_xyz(&mut bus);
    assert_eq!(one(&mut bus, "603 [8] C6 03 20 00 03 00 00 00").data()[0], 0xA4);
    bus.inject(frame("603 [8] 81 31 32 33 00 00 00 00"));
    bus.take_master_rx();
    dialogue(&mut bus, &[("603 [8] D1 00 00 00 00 00 00 00", "583 [8] 80 03 20 00 04 00 04 05")]);
    assert_eq!(bus.stations[0].app().text.as_str(), "xyz", "after a CRC error");
}

/// OD-13 (the node supports node guarding, so 100Ch and 100Dh exist; 1017h exists too), HB-01 (1017h:
/// UNSIGNED16 ms, rw, default 0 = off, not mappable), GUARD-02 (100Ch: UNSIGNED16 ms, rw, default 0) and
/// GUARD-03 (100Dh: UNSIGNED8 factor, rw, default 0): sizes and defaults as read, writes of the right size
/// accepted and read back, of the wrong size refused (1 byte into 1017h: 0607 0013h; 4 bytes into 100Dh:
/// 0607 0012h); 1017h = 50 makes a heartbeat every 50 ms and 0 stops it; mapping 1017h into a TPDO is 0604 0041h.
#[test]
fn error_control_objects_od_13_hb_01_guard_02_guard_03() {
    let mut bus = Bus::booted(vec![node(3, NodeConfig { tpdo: FOUR_TPDOS, ..NodeConfig::DEFAULT })]);
    dialogue(
        &mut bus,
        &[
            ("603 [8] 40 17 10 00 00 00 00 00", "583 [8] 4B 17 10 00 00 00 00 00"),
            ("603 [8] 40 0C 10 00 00 00 00 00", "583 [8] 4B 0C 10 00 00 00 00 00"),
            ("603 [8] 40 0D 10 00 00 00 00 00", "583 [8] 4F 0D 10 00 00 00 00 00"),
            ("603 [8] 2F 17 10 00 64 00 00 00", "583 [8] 80 17 10 00 13 00 07 06"),
            ("603 [8] 23 0D 10 00 03 00 00 00", "583 [8] 80 0D 10 00 12 00 07 06"),
            ("603 [8] 2B 0C 10 00 64 00 00 00", "583 [8] 60 0C 10 00 00 00 00 00"),
            ("603 [8] 2F 0D 10 00 03 00 00 00", "583 [8] 60 0D 10 00 00 00 00 00"),
            ("603 [8] 40 0C 10 00 00 00 00 00", "583 [8] 4B 0C 10 00 64 00 00 00"),
            ("603 [8] 40 0D 10 00 00 00 00 00", "583 [8] 4F 0D 10 00 03 00 00 00"),
            ("603 [8] 2B 0C 10 00 00 00 00 00", "583 [8] 60 0C 10 00 00 00 00 00"),
        ],
    );
    bus.run_for_ms(1000);
    assert!(bus.frames_on(0x703).len() == 1, "only the boot-up with 1017h = 0");
    let t0 = bus.now.as_micros() / 1000;
    dialogue(&mut bus, &[("603 [8] 2B 17 10 00 32 00 00 00", "583 [8] 60 17 10 00 00 00 00 00")]);
    bus.run_for_ms(120);
    let hb: Vec<u64> = bus.frames_on(0x703).iter().skip(1).map(|(t, _)| t - t0).collect();
    assert_eq!(hb, [50, 100]);
    dialogue(&mut bus, &[("603 [8] 2B 17 10 00 00 00 00 00", "583 [8] 60 17 10 00 00 00 00 00")]);
    bus.run_for_ms(500);
    assert_eq!(bus.frames_on(0x703).len(), 3);
    let cob = upload(&mut bus, 3, 0x1800, 1).unwrap();
    assert_eq!(download(&mut bus, 3, 0x1800, 1, cob | 0x8000_0000), Ok(()));
    assert_eq!(download_n(&mut bus, 3, 0x1A00, 0, 0, 1), Ok(()));
    assert_eq!(download(&mut bus, 3, 0x1A00, 1, 0x1017_0010), Err(0x0604_0041));
}

/// SYNC-06 (1006h communication cycle period: UNSIGNED32 µs, rw, default 0 = no SYNC): a node that may
/// produce SYNC (1005h bit 30) reads 1006h as 0 and sends nothing; 1006h = 10 000 µs makes a SYNC every
/// 10 ms; 0 stops it again. EMCY-02 (1014h: UNSIGNED32, rw, default 080h + node-ID, frame bit 0): read as
/// 4 bytes 83 00 00 00, written and read back. SYNC-08 (1007h window length: UNSIGNED32, rw, default 0;
/// the unit, µs, is `sync_window_boundary_sync_09`'s): read as 4 zero bytes, written and read back.
#[test]
fn sync_period_sync_06_and_emcy_cob_id_emcy_02() {
    let cfg = NodeConfig {
        sync: canopen::core::sync::SyncParams {
            cob_id: canopen::core::cob::CobIdEntry::from_raw(0x4000_0080),
            ..canopen::core::sync::SyncParams::DEFAULT
        },
        ..NodeConfig::DEFAULT
    };
    let mut bus = Bus::booted(vec![node(3, cfg)]);
    dialogue(&mut bus, &[("603 [8] 40 06 10 00 00 00 00 00", "583 [8] 43 06 10 00 00 00 00 00")]);
    bus.run_for_ms(100);
    assert!(bus.frames_on(0x080).is_empty());
    dialogue(&mut bus, &[("603 [8] 23 06 10 00 10 27 00 00", "583 [8] 60 06 10 00 00 00 00 00")]);
    let t0 = bus.now.as_micros() / 1000;
    bus.run_for_ms(100);
    let sync: Vec<u64> = bus.frames_on(0x080).iter().map(|(t, _)| t - t0).collect();
    assert_eq!(sync, (1..=10).map(|k| 10 * k).collect::<Vec<u64>>());
    dialogue(&mut bus, &[("603 [8] 23 06 10 00 00 00 00 00", "583 [8] 60 06 10 00 00 00 00 00")]);
    bus.run_for_ms(100);
    assert_eq!(bus.frames_on(0x080).len(), 10);
    dialogue(
        &mut bus,
        &[
            ("603 [8] 40 07 10 00 00 00 00 00", "583 [8] 43 07 10 00 00 00 00 00"),
            ("603 [8] 23 07 10 00 E8 03 00 00", "583 [8] 60 07 10 00 00 00 00 00"),
            ("603 [8] 40 07 10 00 00 00 00 00", "583 [8] 43 07 10 00 E8 03 00 00"),
            ("603 [8] 40 14 10 00 00 00 00 00", "583 [8] 43 14 10 00 83 00 00 00"),
            ("603 [8] 23 14 10 00 83 00 00 80", "583 [8] 60 14 10 00 00 00 00 00"),
            ("603 [8] 23 14 10 00 A3 00 00 80", "583 [8] 60 14 10 00 00 00 00 00"),
            ("603 [8] 40 14 10 00 00 00 00 00", "583 [8] 43 14 10 00 A3 00 00 80"),
        ],
    );
}

/// SYNC-05 (a SYNC consumer handles SYNC in Pre-operational and Operational; the PDO action only in
/// Operational): in Pre-operational a SYNC with a counter the node does not expect (1019h = 0) raises EMCY
/// 8240h, so it was handled, yet the synchronous TPDO stays silent; in Operational the TPDO follows each
/// SYNC; in Stopped the SYNC is not handled (no EMCY, no TPDO).
#[test]
fn sync_in_pre_operational_and_operational_sync_05() {
    const TPDO_SYNC: &[PdoDefault] =
        &[PdoDefault { transmission_type: 1, mapping: &[0x2000_0008], ..PdoDefault::EVENT }];
    let mut bus = Bus::booted(vec![node(3, NodeConfig { tpdo: TPDO_SYNC, ..NodeConfig::DEFAULT })]);
    bus.inject(frame("080 [0]"));
    assert!(bus.frames_on(0x183).is_empty());
    bus.inject(frame("080 [1] 05"));
    assert_eq!(bus.frames_on(0x083).len(), 1);
    assert_eq!(&bus.frames_on(0x083)[0].1[..2], &[0x40, 0x82]);
    assert!(bus.frames_on(0x183).is_empty());
    bus.inject(frame("000 [2] 01 03"));
    for _ in 0..3 {
        bus.inject(frame("080 [0]"));
    }
    assert_eq!(bus.frames_on(0x183).len(), 3);
    bus.inject(frame("000 [2] 02 03"));
    let emcy = bus.frames_on(0x083).len();
    bus.inject(frame("080 [1] 05"));
    bus.inject(frame("080 [0]"));
    assert_eq!((bus.frames_on(0x083).len(), bus.frames_on(0x183).len()), (emcy, 3));
}

/// PDO-06 (1400h+k sub 00h: const, the highest sub-index, between 02h and 06h: 05h here, with the inhibit
/// time 03h and the event timer 05h) and PDO-07 (1400h+k sub 01h bit 31: only valid RPDOs are used in
/// Operational): RPDO1 and RPDO2 both map 2000h; RPDO2 invalid ignores its frames on 304h while RPDO1's on
/// 204h are applied; once RPDO2's bit 31 is cleared, its frames are applied too, and once RPDO1's is set,
/// RPDO1's are not.
#[test]
fn rpdo_parameter_count_and_valid_bit_pdo_06_pdo_07() {
    const TWO: &[PdoDefault] = &[
        PdoDefault { mapping: &[0x2000_0008], ..PdoDefault::EVENT },
        PdoDefault { mapping: &[0x2000_0008], ..PdoDefault::EVENT },
    ];
    let mut bus = Bus::booted(vec![node(4, NodeConfig { rpdo: TWO, ..NodeConfig::DEFAULT })]);
    dialogue(
        &mut bus,
        &[
            ("604 [8] 40 00 14 00 00 00 00 00", "584 [8] 4F 00 14 00 05 00 00 00"),
            ("604 [8] 2F 00 14 00 02 00 00 00", "584 [8] 80 00 14 00 02 00 01 06"),
            ("604 [8] 40 00 14 04 00 00 00 00", "584 [8] 80 00 14 04 11 00 09 06"),
        ],
    );
    let rpdo2 = upload(&mut bus, 4, 0x1401, 1).unwrap();
    assert_eq!(download(&mut bus, 4, 0x1401, 1, rpdo2 | 0x8000_0000), Ok(()));
    bus.inject(frame("000 [2] 01 04"));
    let byte = |bus: &Bus<TestNode>| bus.stations[0].app().byte;
    bus.inject(frame("204 [1] 11"));
    assert_eq!(byte(&bus), 0x11);
    bus.inject(frame("304 [1] 22"));
    assert_eq!(byte(&bus), 0x11, "RPDO2 is invalid");
    assert_eq!(download(&mut bus, 4, 0x1401, 1, rpdo2 & 0x7FFF_FFFF), Ok(()));
    bus.inject(frame("304 [1] 22"));
    assert_eq!(byte(&bus), 0x22);
    let rpdo1 = upload(&mut bus, 4, 0x1400, 1).unwrap();
    assert_eq!(download(&mut bus, 4, 0x1400, 1, rpdo1 | 0x8000_0000), Ok(()));
    bus.inject(frame("204 [1] 33"));
    assert_eq!(byte(&bus), 0x22, "RPDO1 is invalid");
}

/// PDO-27 (a TPDO with a SYNC start value, whose start the counter has already passed when the node enters
/// Operational, waits for the next cycle in which the counter equals the start value): node 3 consumes SYNC
/// with a counter to 10 (1019h); TPDO1 is type 1 with start value 3. Operational is entered after the SYNC
/// with counter 5: counters 6 to 10 and 1, 2 send nothing, 3 sends the first TPDO, and 4 and 5 the next.
#[test]
fn sync_start_value_already_passed_pdo_27() {
    const TPDO: &[PdoDefault] =
        &[PdoDefault { transmission_type: 1, sync_start: 3, mapping: &[0x2000_0008], ..PdoDefault::EVENT }];
    let mut bus = Bus::booted(vec![node(3, NodeConfig { tpdo: TPDO, ..NodeConfig::DEFAULT })]);
    dialogue(&mut bus, &[("603 [8] 2F 19 10 00 0A 00 00 00", "583 [8] 60 19 10 00 00 00 00 00")]);
    let sync = |bus: &mut Bus<TestNode>, c: u8| {
        let before = bus.frames_on(0x183).len();
        bus.inject(CanFrame::new(0x080, &[c]).unwrap());
        bus.frames_on(0x183).len() > before
    };
    for c in 1..=5 {
        assert!(!sync(&mut bus, c), "Pre-operational, counter {c}");
    }
    bus.inject(frame("000 [2] 01 03"));
    bus.log.clear();
    let sent: Vec<bool> = [6u8, 7, 8, 9, 10, 1, 2, 3, 4, 5].into_iter().map(|c| sync(&mut bus, c)).collect();
    assert_eq!(sent, [false, false, false, false, false, false, false, true, true, true]);
    assert!(bus.frames_on(0x083).is_empty(), "no EMCY: the counter is expected");
}

/// EMCY-12 (the manufacturer-specific field and additional error codes come from the manufacturer): an
/// application error code (FF01h, device specific) and its five bytes go out unchanged in the EMCY frame,
/// after the error register (bit 0 and the manufacturer bit 7 set).
#[test]
fn manufacturer_error_code_and_field_emcy_12() {
    let mut bus = Bus::booted(vec![node(3, NodeConfig::DEFAULT)]);
    assert!(bus.stations[0].raise_error(0xFF01, [1, 2, 3, 4, 5]));
    bus.run_for_ms(1);
    assert_eq!(bus.frames_on(0x083), vec![(0, vec![0x01, 0xFF, 0x81, 1, 2, 3, 4, 5])]);
}
