//! Multiplexed PDOs on whole nodes (the feature `mpdo`, on by default): frames typed from CiA 301 fig. 19
//! (byte 0: f bit 7, node-ID bits 6–0; bytes 1–2 index LE; byte 3 sub-index; bytes 4–7 data), never built
//! by the code under test. MPDO-01 (frame), MPDO-02 (DAM consumer, EMCY 8230h / EEC-18), MPDO-03 (SAM
//! producer with the scanner list 1FA0h, consumer with the dispatching list 1FD0h), MPDO-04 (event-driven
//! only, inhibit time), MPDO-05 / PDO-30 (mapping sub 00h FEh/FFh).
//!
//! Run: `cargo test -p canopen-core --test mpdo`.

use canopen_core::event::Event;
use canopen_core::node::Node;
use canopen_core::od::{AbortCode, Access, DataType, ObjectDictionary, PdoMapping, SubInfo};
use canopen_core::pdo::mpdo::MpdoRefused;
use canopen_core::pdo::PdoDefault;
use canopen_core::profile::NodeConfig;
use canopen_core::{CanFrame, Instant, NmtState, NodeId};

/// The application objects: (index, sub, type, access, PDO mapping, value).
/// - 2000h:01 U32 rw, 2000h:02 U16 rw (both ways mappable);
/// - 2001h:00 U8 ro (TPDO only: a DAM write to it is dropped);
/// - 2002h:00 U64 rw (8 bytes: no MPDO carries it);
/// - 2003h:00 U8 rw, not PDO-mappable;
/// - 2100h:0Bh..12h U8 rw (a dispatching block's targets; 13h is missing on purpose).
struct App {
    vars: Vec<(u16, u8, DataType, Access, PdoMapping, u64)>,
}

impl App {
    fn new() -> Self {
        use Access::*;
        use DataType::*;
        let mut vars = vec![
            (0x2000, 1, Unsigned32, Rw, PdoMapping::Both, 0),
            (0x2000, 2, Unsigned16, Rw, PdoMapping::Both, 0),
            (0x2001, 0, Unsigned8, Ro, PdoMapping::Tpdo, 0x5A),
            (0x2002, 0, Unsigned64, Rw, PdoMapping::Both, 0),
            (0x2003, 0, Unsigned8, Rw, PdoMapping::No, 0),
        ];
        vars.extend((0x0B..=0x12).map(|s| (0x2100, s, Unsigned8, Rw, PdoMapping::Both, 0)));
        App { vars }
    }

    fn find(&self, index: u16, sub: u8) -> Result<usize, AbortCode> {
        match self.vars.iter().position(|v| (v.0, v.1) == (index, sub)) {
            Some(i) => Ok(i),
            None if self.vars.iter().any(|v| v.0 == index) => Err(AbortCode::SubIndexDoesNotExist),
            None => Err(AbortCode::ObjectDoesNotExist),
        }
    }

    fn get(&self, index: u16, sub: u8) -> u64 {
        self.vars[self.find(index, sub).unwrap()].5
    }
}

impl ObjectDictionary for App {
    fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
        let v = self.vars[self.find(index, sub)?];
        let size = match v.2 {
            DataType::Unsigned8 => 1,
            DataType::Unsigned16 => 2,
            DataType::Unsigned32 => 4,
            _ => 8,
        };
        Ok(SubInfo { data_type: v.2, access: v.3, pdo: v.4, size })
    }
    fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        let size = self.info(index, sub)?.size;
        let bytes = self.vars[self.find(index, sub)?].5.to_le_bytes();
        let src = &bytes[offset.min(size)..size];
        let n = src.len().min(buf.len());
        buf[..n].copy_from_slice(&src[..n]);
        Ok(n)
    }
    fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        let info = self.info(index, sub)?;
        if !info.access.writable() {
            return Err(AbortCode::WriteOfReadOnly);
        }
        if data.len() != info.size {
            return Err(AbortCode::LengthMismatch);
        }
        let i = self.find(index, sub)?;
        self.vars[i].5 = data.iter().rev().fold(0, |v, &b| v << 8 | u64::from(b));
        Ok(())
    }
}

type TestNode = Node<App>;

const DAM: PdoDefault = PdoDefault { count: Some(0xFF), ..PdoDefault::EVENT };
const SAM: PdoDefault = PdoDefault { count: Some(0xFE), ..PdoDefault::EVENT };

fn ms(t: u64) -> Instant {
    Instant::from_millis(t)
}

/// Node `id` booted into Operational, its boot-up frames and events drained.
fn operational(id: u8, config: NodeConfig) -> TestNode {
    let mut node = Node::new(NodeId::new(id).unwrap(), config, App::new());
    node.handle_timeout(Instant::ZERO);
    node.enter_state(NmtState::Operational);
    drain(&mut node);
    node
}

fn drain(node: &mut TestNode) -> (Vec<CanFrame>, Vec<Event>) {
    (core::iter::from_fn(|| node.poll_transmit()).collect(), core::iter::from_fn(|| node.poll_event()).collect())
}

fn rx(node: &mut TestNode, t: Instant, cob: u16, data: &[u8]) -> (Vec<CanFrame>, Vec<Event>) {
    node.handle_frame(t, &CanFrame::new(cob, data).unwrap());
    drain(node)
}

fn written(pdo: u16, index: u16, sub: u8) -> Event {
    Event::MpdoWritten { pdo, index, sub }
}

/// MPDO-02, MPDO-01: a DAM-MPDO writes the object it names when it is addressed to this node or to all.
#[test]
fn dam_consumer_writes_the_addressed_object_mpdo_02() {
    let mut node = operational(5, NodeConfig { rpdo: &[DAM], ..NodeConfig::DEFAULT });
    // To node 5: 2000h:01 = 1234 5678h.
    let (tx, ev) = rx(&mut node, ms(1), 0x205, &[0x85, 0x00, 0x20, 0x01, 0x78, 0x56, 0x34, 0x12]);
    assert_eq!((tx, ev), (vec![], vec![written(0, 0x2000, 1)]));
    assert_eq!(node.app().get(0x2000, 1), 0x1234_5678);
    // To every DAM consumer (addr 0): 2000h:02 = BEEFh (2 data bytes of 4; the rest is not written).
    let (_, ev) = rx(&mut node, ms(2), 0x205, &[0x80, 0x00, 0x20, 0x02, 0xEF, 0xBE, 0xAA, 0xAA]);
    assert_eq!(ev, vec![written(0, 0x2000, 2)]);
    assert_eq!(node.app().get(0x2000, 2), 0xBEEF);
    // To node 6: not for us.
    let none = (vec![], vec![]);
    assert_eq!(rx(&mut node, ms(3), 0x205, &[0x86, 0x00, 0x20, 0x01, 0, 0, 0, 0]), none);
    // A SAM frame (f = 0) on a DAM consumer, a frame of 7 bytes: not processed (CAN-07).
    assert_eq!(rx(&mut node, ms(4), 0x205, &[0x05, 0x00, 0x20, 0x01, 0, 0, 0, 0]), none);
    assert_eq!(rx(&mut node, ms(5), 0x205, &[0x85, 0x00, 0x20, 0x01, 0, 0, 0]), none);
    assert_eq!(node.app().get(0x2000, 1), 0x1234_5678);
    // Pre-operational: no PDO (PDO-04).
    node.enter_state(NmtState::PreOperational);
    drain(&mut node);
    assert_eq!(rx(&mut node, ms(6), 0x205, &[0x85, 0x00, 0x20, 0x01, 0, 0, 0, 0]), none);
    assert_eq!(node.app().get(0x2000, 1), 0x1234_5678);
}

/// MPDO-02, EEC-18: a missing destination object raises EMCY 8230h (manufacturer bytes: RPDO 1, index,
/// sub-index), the next DAM write clears it; a read-only, unmappable or 8-byte object is dropped silently.
#[test]
fn dam_consumer_missing_object_emcy_8230_eec_18() {
    let mut node = operational(5, NodeConfig { rpdo: &[DAM], ..NodeConfig::DEFAULT });
    let (tx, ev) = rx(&mut node, ms(1), 0x205, &[0x85, 0x00, 0x30, 0x00, 1, 0, 0, 0]); // 3000h:00
    assert_eq!(
        tx.iter().map(|f| (f.cob_id(), f.padded())).collect::<Vec<_>>(),
        [(0x85, [0x30, 0x82, 0x11, 0x01, 0x00, 0x30, 0x00, 0x00])]
    );
    assert_eq!(ev, vec![]);
    let (tx, _) = rx(&mut node, ms(2), 0x205, &[0x85, 0x00, 0x20, 0x09, 1, 0, 0, 0]); // 2000h:09: no sub
    assert_eq!(tx, vec![], "8230h is already active");
    let dropped = [
        [0x85, 0x01, 0x20, 0x00, 0x11, 0, 0, 0], // 2001h ro
        [0x85, 0x03, 0x20, 0x00, 0x11, 0, 0, 0], // 2003h not mappable
        [0x85, 0x02, 0x20, 0x00, 0x11, 0, 0, 0], // 2002h 8 bytes
    ];
    for f in dropped {
        assert_eq!(rx(&mut node, ms(3), 0x205, &f), (vec![], vec![]), "{f:02X?}");
    }
    assert_eq!((node.app().get(0x2001, 0), node.app().get(0x2003, 0), node.app().get(0x2002, 0)), (0x5A, 0, 0));
    // A DAM write that succeeds: the cause is gone, EMCY 0000h with error register 00h.
    let (tx, ev) = rx(&mut node, ms(4), 0x205, &[0x80, 0x00, 0x20, 0x01, 7, 0, 0, 0]);
    assert_eq!(tx.iter().map(|f| (f.cob_id(), f.padded())).collect::<Vec<_>>(), [(0x85, [0; 8])]);
    assert_eq!(ev, vec![written(0, 0x2000, 1)]);
}

/// MPDO-03: the SAM consumer writes what its dispatching list maps; §7.5.2.40's example entry (producer
/// sub 1..9 → local 11..19, block 9), here from node 0Ah's 6000h to local 2100h.
#[test]
fn sam_consumer_dispatches_mpdo_03() {
    const CONSUMER: PdoDefault = PdoDefault { can_id: Some(0x18A), ..SAM }; // node 0Ah's TPDO 1
    let mut node = operational(5, NodeConfig { rpdo: &[CONSUMER], ..NodeConfig::DEFAULT });
    let none = (vec![], vec![]);
    // Unconfigured list (every entry 0): nothing is written.
    assert_eq!(rx(&mut node, ms(1), 0x18A, &[0x0A, 0x00, 0x60, 0x05, 0x42, 0, 0, 0]), none);
    node.dictionary().write(0x1FD0, 1, &[0x0A, 0x01, 0x00, 0x60, 0x0B, 0x00, 0x21, 0x09]).unwrap();
    // Node 0Ah's 6000h:05 → 2100h:0Fh (11 + 4).
    let (tx, ev) = rx(&mut node, ms(2), 0x18A, &[0x0A, 0x00, 0x60, 0x05, 0x42, 0, 0, 0]);
    assert_eq!((tx, ev), (vec![], vec![written(0, 0x2100, 0x0F)]));
    assert_eq!(node.app().get(0x2100, 0x0F), 0x42);
    // 6000h:01 → 2100h:0Bh, the block's first.
    assert_eq!(rx(&mut node, ms(3), 0x18A, &[0x0A, 0x00, 0x60, 0x01, 0x01, 0, 0, 0]).1, vec![written(0, 0x2100, 0x0B)]);
    // Outside the block (sub 0Ah), another producer (0Bh), another index (6001h), a DAM frame: ignored.
    for f in [
        [0x0A, 0x00, 0x60, 0x0A, 0x01, 0, 0, 0],
        [0x0B, 0x00, 0x60, 0x01, 0x01, 0, 0, 0],
        [0x0A, 0x01, 0x60, 0x01, 0x01, 0, 0, 0],
        [0x85, 0x00, 0x21, 0x0B, 0x01, 0, 0, 0],
        [0x00, 0x00, 0x60, 0x01, 0x01, 0, 0, 0], // SAM from node 0: reserved
    ] {
        assert_eq!(rx(&mut node, ms(4), 0x18A, &f), none, "{f:02X?}");
    }
    // 6000h:09 → 2100h:13h, which does not exist: dropped, and no 8230h (that is DAM's, MPDO-02).
    assert_eq!(rx(&mut node, ms(5), 0x18A, &[0x0A, 0x00, 0x60, 0x09, 0x01, 0, 0, 0]), none);
    // The list is read back as written (UNSIGNED64, LE).
    let mut b = [0u8; 8];
    assert_eq!(node.dictionary().read(0x1FD0, 1, 0, &mut b), Ok(8));
    assert_eq!(u64::from_le_bytes(b), 0x0921_000B_6000_010A);
}

/// MPDO-01, MPDO-04: the DAM producer's frames; the inhibit time refuses a second MPDO until it passed.
#[test]
fn dam_producer_frames_and_inhibit_time_mpdo_04() {
    const TPDO: PdoDefault = PdoDefault { inhibit_100us: 10, ..DAM }; // 1 ms
    const PLAIN: PdoDefault = PdoDefault { mapping: &[0x2001_0008], ..PdoDefault::EVENT };
    let cfg = NodeConfig { tpdo: &[TPDO, PLAIN], ..NodeConfig::DEFAULT };
    let mut node = Node::new(NodeId::new(5).unwrap(), cfg, App::new());
    node.handle_timeout(Instant::ZERO);
    drain(&mut node);
    assert_eq!(node.send_dam_mpdo(0, 0, 0x2000, 1, &[1]), Err(MpdoRefused::NotOperational));
    node.enter_state(NmtState::Operational);
    // Entering Operational sends the plain event-driven TPDO 2 (PDO-28), not the MPDO (MPDO-04).
    let (tx, _) = drain(&mut node);
    assert_eq!(tx.iter().map(CanFrame::cob_id).collect::<Vec<_>>(), [0x285]);

    node.send_dam_mpdo(0, 0, 0x2000, 1, &[1, 2, 3, 4]).unwrap();
    let (tx, _) = drain(&mut node);
    assert_eq!(
        tx.iter().map(|f| (f.cob_id(), f.dlc(), f.padded())).collect::<Vec<_>>(),
        [(0x185, 8, [0x80, 0x00, 0x20, 0x01, 0x01, 0x02, 0x03, 0x04])]
    );
    assert_eq!(node.send_dam_mpdo(0, 0x7F, 0x6000, 2, &[9]), Err(MpdoRefused::Inhibited));
    node.handle_timeout(Instant::from_micros(999));
    assert_eq!(node.send_dam_mpdo(0, 0x7F, 0x6000, 2, &[9]), Err(MpdoRefused::Inhibited));
    node.handle_timeout(ms(1));
    node.send_dam_mpdo(0, 0x7F, 0x6000, 2, &[9]).unwrap();
    assert_eq!(drain(&mut node).0[0].padded(), [0xFF, 0x00, 0x60, 0x02, 0x09, 0x00, 0x00, 0x00]);

    node.handle_timeout(ms(10));
    assert_eq!(node.send_dam_mpdo(0, 128, 0x2000, 1, &[1]), Err(MpdoRefused::InvalidNode));
    assert_eq!(node.send_dam_mpdo(0, 1, 0x2000, 1, &[1, 2, 3, 4, 5]), Err(MpdoRefused::TooLong));
    assert_eq!(node.send_dam_mpdo(1, 1, 0x2000, 1, &[1]), Err(MpdoRefused::NotMpdo)); // a plain TPDO
    assert_eq!(node.send_dam_mpdo(7, 1, 0x2000, 1, &[1]), Err(MpdoRefused::NotMpdo)); // no TPDO 8
    assert_eq!(node.send_sam_mpdo(0, 0x2000, 1), Err(MpdoRefused::NotMpdo)); // a DAM TPDO
                                                                             // No application trigger, no SYNC: an MPDO is sent by its producer call only (MPDO-04).
    assert!(!node.trigger_tpdo(0));
    assert_eq!(node.trigger_changed_tpdos(), 0);
    assert_eq!(rx(&mut node, ms(11), 0x080, &[]).0, vec![]);
}

/// MPDO-03: the SAM producer sends what its scanner list covers, with its own node-ID.
#[test]
fn sam_producer_uses_the_scanner_list_mpdo_03() {
    let mut node = operational(5, NodeConfig { tpdo: &[SAM], ..NodeConfig::DEFAULT });
    node.app_mut().vars[1].5 = 0xBEEF; // 2000h:02
    assert_eq!(node.send_sam_mpdo(0, 0x2000, 2), Err(MpdoRefused::NotScanned));
    // 1FA0h:01 = 0220 0001h: 2000h sub 01h..02h; 1FA0h:02 = 0020 0200h: 2002h:00; :03 = 2003h:00;
    // :04 = 3000h:00.
    for (sub, v) in [(1u8, 0x0220_0001u32), (2, 0x0020_0200), (3, 0x0020_0300), (4, 0x0030_0000)] {
        node.dictionary().write(0x1FA0, sub, &v.to_le_bytes()).unwrap();
    }
    node.send_sam_mpdo(0, 0x2000, 2).unwrap();
    let (tx, _) = drain(&mut node);
    assert_eq!(
        tx.iter().map(|f| (f.cob_id(), f.padded())).collect::<Vec<_>>(),
        [(0x185, [0x05, 0x00, 0x20, 0x02, 0xEF, 0xBE, 0x00, 0x00])]
    );
    assert_eq!(node.send_sam_mpdo(0, 0x2000, 3), Err(MpdoRefused::NotScanned));
    assert_eq!(node.send_sam_mpdo(0, 0x2002, 0), Err(MpdoRefused::TooLong));
    assert_eq!(node.send_sam_mpdo(0, 0x2003, 0), Err(MpdoRefused::Object(AbortCode::NotMappable)));
    assert_eq!(node.send_sam_mpdo(0, 0x3000, 0), Err(MpdoRefused::Object(AbortCode::ObjectDoesNotExist)));
    assert_eq!(node.send_dam_mpdo(0, 1, 0x2000, 1, &[1]), Err(MpdoRefused::NotMpdo)); // a SAM TPDO
    assert_eq!(drain(&mut node).0, vec![]);
}

/// One SDO expedited request to node `id`; the reply's bytes.
fn sdo(node: &mut TestNode, id: u16, req: [u8; 8]) -> [u8; 8] {
    node.handle_frame(ms(1), &CanFrame::new(0x600 + id, &req).unwrap());
    core::iter::from_fn(|| node.poll_transmit()).find(|f| f.cob_id() == 0x580 + id).expect("an SDO reply").padded()
}

/// MPDO-05, PDO-30: mapping sub 00h FFh/FEh written by SDO with the remapping procedure (invalid PDO
/// first); then a DAM-MPDO from one node reaches another (producer and consumer over the same frames).
#[test]
fn mpdo_mapping_by_sdo_and_end_to_end_mpdo_05() {
    // Valid plain PDOs to start with: TPDO 1 of node 1 on 181h, RPDO 1 of node 2 on 181h, no mapping.
    const RPDO: PdoDefault = PdoDefault { can_id: Some(0x181), ..PdoDefault::EVENT };
    let mut producer = operational(1, NodeConfig { tpdo: &[PdoDefault::EVENT], ..NodeConfig::DEFAULT });
    let mut consumer = operational(2, NodeConfig { rpdo: &[RPDO], ..NodeConfig::DEFAULT });
    // While the PDO is valid its mapping does not change (PDO-35: 0601 0000h).
    let r = sdo(&mut producer, 1, [0x2F, 0x00, 0x1A, 0x00, 0xFF, 0, 0, 0]);
    assert_eq!(r, [0x80, 0x00, 0x1A, 0x00, 0x00, 0x00, 0x01, 0x06]);
    // TPDO 1 of node 1: invalid (1800h:01 = 8000 0181h), 1A00h:00 = FFh, valid again.
    assert_eq!(sdo(&mut producer, 1, [0x23, 0x00, 0x18, 0x01, 0x81, 0x01, 0x00, 0x80])[0], 0x60);
    assert_eq!(sdo(&mut producer, 1, [0x2F, 0x00, 0x1A, 0x00, 0xFF, 0, 0, 0])[0], 0x60);
    assert_eq!(sdo(&mut producer, 1, [0x23, 0x00, 0x18, 0x01, 0x81, 0x01, 0x00, 0x00])[0], 0x60);
    assert_eq!(sdo(&mut producer, 1, [0x40, 0x00, 0x1A, 0x00, 0, 0, 0, 0]), [0x4F, 0x00, 0x1A, 0x00, 0xFF, 0, 0, 0]);
    // A reserved count (41h, PDO-30) stays refused (PDO-37: 0604 0042h).
    assert_eq!(sdo(&mut consumer, 2, [0x23, 0x00, 0x14, 0x01, 0x81, 0x01, 0x00, 0x80])[0], 0x60);
    let r = sdo(&mut consumer, 2, [0x2F, 0x00, 0x16, 0x00, 0x41, 0, 0, 0]);
    assert_eq!(r, [0x80, 0x00, 0x16, 0x00, 0x42, 0x00, 0x04, 0x06]);
    // RPDO 1 of node 2 on 181h, a DAM consumer.
    assert_eq!(sdo(&mut consumer, 2, [0x2F, 0x00, 0x16, 0x00, 0xFF, 0, 0, 0])[0], 0x60);
    assert_eq!(sdo(&mut consumer, 2, [0x23, 0x00, 0x14, 0x01, 0x81, 0x01, 0x00, 0x00])[0], 0x60);
    drain(&mut producer);
    drain(&mut consumer);

    producer.send_dam_mpdo(0, 2, 0x2000, 2, &[0x34, 0x12]).unwrap();
    let frame = producer.poll_transmit().unwrap();
    assert_eq!((frame.cob_id(), frame.padded()), (0x181, [0x82, 0x00, 0x20, 0x02, 0x34, 0x12, 0x00, 0x00]));
    consumer.handle_frame(ms(2), &frame);
    assert_eq!(drain(&mut consumer).1, vec![written(0, 0x2000, 2)]);
    assert_eq!(consumer.app().get(0x2000, 2), 0x1234);
}

/// Two RAM slots of 8 KiB, as the storage contract asks (with `pdo-mapping-64` the communication record is
/// over 4 KiB).
struct Ram(Vec<Vec<u8>>);

impl canopen_core::storage::Storage for Ram {
    fn capacity(&self) -> usize {
        8192
    }
    fn erase(&mut self, slot: u8) -> Result<(), canopen_core::storage::StorageError> {
        self.0[usize::from(slot)].fill(0xFF);
        Ok(())
    }
    fn write(&mut self, slot: u8, offset: usize, data: &[u8]) -> Result<(), canopen_core::storage::StorageError> {
        self.0[usize::from(slot)][offset..offset + data.len()].copy_from_slice(data);
        Ok(())
    }
    fn read(&mut self, slot: u8, offset: usize, buf: &mut [u8]) -> Result<(), canopen_core::storage::StorageError> {
        buf.copy_from_slice(&self.0[usize::from(slot)][offset..offset + buf.len()]);
        Ok(())
    }
}

/// MPDO-03, MPDO-05: 1FA0h / 1FD0h over SDO (sub 00h const 10h; a 1FD0h entry is UNSIGNED64, so a
/// segmented download, SDO-13..16) and a mapping count FFh, stored with the communication parameters
/// (1010h sub 02h); the lists back to 0 after a restore and a reset communication.
#[test]
fn lists_over_sdo_and_storage_mpdo_03() {
    use canopen_core::node::NoApplication;
    let mut node: Node<NoApplication, canopen_core::Sizes, Ram> =
        Node::with_storage(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication, Ram(vec![vec![0xFF; 8192]; 2]));
    node.handle_timeout(Instant::ZERO);
    let mut sdo = |req: [u8; 8]| {
        node.handle_frame(ms(1), &CanFrame::new(0x605, &req).unwrap());
        core::iter::from_fn(|| node.poll_transmit()).find(|f| f.cob_id() == 0x585).unwrap().padded()
    };
    assert_eq!(sdo([0x40, 0xA0, 0x1F, 0x00, 0, 0, 0, 0]), [0x4F, 0xA0, 0x1F, 0x00, 0x10, 0, 0, 0]);
    assert_eq!(sdo([0x2F, 0xA0, 0x1F, 0x00, 0x01, 0, 0, 0]), [0x80, 0xA0, 0x1F, 0x00, 0x02, 0x00, 0x01, 0x06]);
    assert_eq!(sdo([0x40, 0xA0, 0x1F, 0x11, 0, 0, 0, 0]), [0x80, 0xA0, 0x1F, 0x11, 0x11, 0x00, 0x09, 0x06]);
    // 1FA0h:01 = 0220 0001h, expedited.
    assert_eq!(sdo([0x23, 0xA0, 0x1F, 0x01, 0x01, 0x00, 0x20, 0x02])[0], 0x60);
    // 1FD0h:01 = 0921 000B 6000 010Ah: initiate (size 8), 7 bytes, last segment of 1 byte (n = 6).
    assert_eq!(sdo([0x21, 0xD0, 0x1F, 0x01, 0x08, 0, 0, 0]), [0x60, 0xD0, 0x1F, 0x01, 0, 0, 0, 0]);
    assert_eq!(sdo([0x00, 0x0A, 0x01, 0x00, 0x60, 0x0B, 0x00, 0x21]), [0x20, 0, 0, 0, 0, 0, 0, 0]);
    assert_eq!(sdo([0x1D, 0x09, 0, 0, 0, 0, 0, 0]), [0x30, 0, 0, 0, 0, 0, 0, 0]);
    // RPDO 1 (not valid by default) made a DAM consumer: 1600h:00 = FFh (MPDO-05).
    assert_eq!(sdo([0x2F, 0x00, 0x16, 0x00, 0xFF, 0, 0, 0])[0], 0x60);
    // Save the communication parameters ("save"), reset communication: both lists and 1600h:00 come back.
    assert_eq!(sdo([0x23, 0x10, 0x10, 0x02, 0x73, 0x61, 0x76, 0x65])[0], 0x60);
    node.handle_frame(ms(2), &CanFrame::new(0x000, &[0x82, 0x05]).unwrap());
    let mut b = [0u8; 8];
    assert_eq!(node.dictionary().read(0x1FD0, 1, 0, &mut b), Ok(8));
    assert_eq!(u64::from_le_bytes(b), 0x0921_000B_6000_010A);
    assert_eq!(node.dictionary().read(0x1FA0, 1, 0, &mut b), Ok(4));
    assert_eq!(b[..4], [0x01, 0x00, 0x20, 0x02]);
    assert_eq!(node.comm_profile().params.rpdo_map[0].count, 0xFF);
    // Restore the communication defaults (1011h sub 02h "load"), reset communication: 0 again.
    node.handle_frame(ms(3), &CanFrame::new(0x605, &[0x23, 0x11, 0x10, 0x02, 0x6C, 0x6F, 0x61, 0x64]).unwrap());
    node.handle_frame(ms(4), &CanFrame::new(0x000, &[0x82, 0x05]).unwrap());
    assert_eq!(node.dictionary().read(0x1FD0, 1, 0, &mut b), Ok(8));
    assert_eq!(b, [0; 8]);
}

/// MPDO-03: one SAM producer per device: FEh on a second TPDO's mapping is refused (0604 0043h) and the
/// mapping stays as it was; FFh (DAM) on it is fine.
#[test]
fn one_sam_producer_per_device_mpdo_03() {
    let mut node = operational(5, NodeConfig { tpdo: &[SAM], ..NodeConfig::DEFAULT });
    // TPDO 2 is not valid by default: its mapping may change.
    let r = sdo(&mut node, 5, [0x2F, 0x01, 0x1A, 0x00, 0xFE, 0, 0, 0]);
    assert_eq!(r, [0x80, 0x01, 0x1A, 0x00, 0x43, 0x00, 0x04, 0x06]);
    assert_eq!(sdo(&mut node, 5, [0x40, 0x01, 0x1A, 0x00, 0, 0, 0, 0]), [0x4F, 0x01, 0x1A, 0x00, 0, 0, 0, 0]);
    assert_eq!(sdo(&mut node, 5, [0x2F, 0x01, 0x1A, 0x00, 0xFF, 0, 0, 0])[0], 0x60);
    // TPDO 1 itself may be written FEh again (no conflict with itself).
    assert_eq!(sdo(&mut node, 5, [0x23, 0x00, 0x18, 0x01, 0x85, 0x01, 0x00, 0x80])[0], 0x60);
    assert_eq!(sdo(&mut node, 5, [0x2F, 0x00, 0x1A, 0x00, 0x00, 0, 0, 0])[0], 0x60);
    assert_eq!(sdo(&mut node, 5, [0x2F, 0x00, 0x1A, 0x00, 0xFE, 0, 0, 0])[0], 0x60);
}

/// Payloads of 0–8 bytes: mostly MPDO-shaped (byte 0 for this node, all, another node or a SAM producer;
/// an index of the test dictionary or a missing one; a low sub-index), some entirely random.
fn frames() -> impl proptest::strategy::Strategy<Value = Vec<u8>> {
    use proptest::prelude::*;
    let shaped = (
        prop::sample::select(vec![0x85u8, 0x80, 0x86, 0x05, 0x0A, 0x00, 0x8A, 0x7F]),
        prop::sample::select(vec![0x2000u16, 0x2001, 0x2002, 0x2003, 0x2100, 0x3000]),
        0u8..=0x14,
        any::<[u8; 4]>(),
        0usize..=12,
    )
        .prop_map(|(f, index, sub, d, len)| {
            let [lo, hi] = index.to_le_bytes();
            let mut v = vec![f, lo, hi, sub, d[0], d[1], d[2], d[3]];
            v.truncate(len.min(8));
            v
        });
    prop_oneof![4 => shaped, 1 => proptest::collection::vec(any::<u8>(), 0..=8)]
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 512, ..Default::default() })]

    /// MPDO-02/03, CAN-07: any payload of 0–8 bytes on a DAM and a SAM consumer never panics; every write
    /// it makes is reported, names an object of the dictionary that is RPDO-mappable and at most 4 bytes,
    /// and holds the frame's leading data bytes; a frame that is not 8 bytes writes nothing.
    #[test]
    fn any_frame_on_the_consumers(data in frames(), sam in proptest::prelude::any::<bool>()) {
        const CONSUMERS: [PdoDefault; 2] = [DAM, PdoDefault { can_id: Some(0x18A), ..SAM }];
        let mut node = operational(5, NodeConfig { rpdo: &CONSUMERS, ..NodeConfig::DEFAULT });
        // Every producer's 2000h..2003h / 2100h sub 00h..FFh (block FFh) dispatched to the same local object.
        for (i, idx) in [0x2000u64, 0x2001, 0x2002, 0x2003, 0x2100].iter().enumerate() {
            let raw = 0xFF00_0000_0000_0000 | idx << 40 | idx << 16 | u64::from(data.first().copied().unwrap_or(0) & 0x7F);
            node.dictionary().write(0x1FD0, i as u8 + 1, &raw.to_le_bytes()).unwrap();
        }
        let (cob, pdo) = if sam { (0x18A, 1) } else { (0x205, 0) };
        let before = node.app().vars.clone();
        let (_, events) = rx(&mut node, ms(1), cob, &data);
        let writes: Vec<_> = events.iter().filter(|e| matches!(e, Event::MpdoWritten { .. })).collect();
        proptest::prop_assert!(writes.len() <= 1);
        if data.len() != 8 {
            proptest::prop_assert!(writes.is_empty());
        }
        for e in writes {
            let Event::MpdoWritten { pdo: p, index, sub } = *e else { unreachable!() };
            proptest::prop_assert_eq!(p, pdo);
            let info = node.app().info(index, sub).unwrap();
            proptest::prop_assert!(info.pdo.rpdo() && info.size <= 4);
            let mut v = [0u8; 8];
            v[..info.size].copy_from_slice(&data[4..4 + info.size]);
            proptest::prop_assert_eq!(node.app().get(index, sub), u64::from_le_bytes(v));
        }
        // Nothing else changed.
        let changed = before.iter().zip(&node.app().vars).filter(|(a, b)| a != b).count();
        proptest::prop_assert!(changed <= 1);
    }
}
