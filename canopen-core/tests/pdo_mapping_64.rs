//! PDO mappings of 64 entries (the feature `pdo-mapping-64`; CiA 301 §7.5.2.36/38: sub 01h–40h): 64
//! one-bit objects on a classic frame, configured with the remapping procedure over SDO (PDO-35) and
//! checked against frames written from the packing rule (PDO-32: entry 1 at bit 0 of byte 0, LE, in entry
//! order). Run with `cargo test -p canopen-core --features pdo-mapping-64`.

use canopen_core::node::Node;
use canopen_core::od::{
    AbortCode, Access, DataType, EntryDesc, ObjectDesc, ObjectDictionary, OdDescribe, PdoMapping, SubInfo,
};
use canopen_core::pdo::{mapping::MAX_ENTRIES, PdoDefault};
use canopen_core::profile::eds::{write_eds, EdsInfo};
use canopen_core::profile::{CommProfile, NodeConfig};
use canopen_core::storage::{NoStorage, RamStorage, Storage};
use canopen_core::{CanFrame, Instant, NmtState, NodeId, Sizes};

/// 2000h sub 01h–40h: 64 BOOLEANs (bit `i - 1` of `bits`), 2001h: a UNSIGNED8; mappable both ways.
#[derive(Default)]
struct Flags {
    bits: u64,
    byte: u8,
}

impl ObjectDictionary for Flags {
    fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
        let dt = match (index, sub) {
            (0x2000, 1..=64) => DataType::Boolean,
            (0x2001, 0) => DataType::Unsigned8,
            (0x2000 | 0x2001, _) => return Err(AbortCode::SubIndexDoesNotExist),
            _ => return Err(AbortCode::ObjectDoesNotExist),
        };
        Ok(SubInfo { data_type: dt, access: Access::Rw, pdo: PdoMapping::Both, size: 1 })
    }
    fn read(&self, index: u16, sub: u8, _: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        self.info(index, sub)?;
        let v = if index == 0x2001 { self.byte } else { (self.bits >> (sub - 1)) as u8 & 1 };
        let Some(b) = buf.first_mut() else { return Ok(0) };
        *b = v;
        Ok(1)
    }
    fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        self.info(index, sub)?;
        let &[v] = data else { return Err(AbortCode::LengthMismatch) };
        match index {
            0x2001 => self.byte = v,
            _ if v > 1 => return Err(AbortCode::InvalidValue),
            _ => self.bits = self.bits & !(1 << (sub - 1)) | u64::from(v) << (sub - 1),
        }
        Ok(())
    }
}

/// Nothing to store of the application: the test stores the communication parameters (1010h sub 02h).
impl OdDescribe for Flags {
    fn object_count(&self) -> usize {
        0
    }
    fn object(&self, _: usize) -> Option<ObjectDesc> {
        None
    }
    fn entry(&self, _: u16, _: u8) -> Option<EntryDesc> {
        None
    }
}

/// Two RAM slots of 8 KiB (the communication record with 64-entry mappings is over 4 KiB: every entry
/// of every mapping is stored, 8 bytes each).
type Ram = RamStorage<8192>;

type N<S = NoStorage> = Node<Flags, Sizes, S>;

const CFG: NodeConfig = NodeConfig { rpdo: &[PdoDefault::EVENT], tpdo: &[PdoDefault::EVENT], ..NodeConfig::DEFAULT };

/// Node 5 with RPDO1 and TPDO1 event-driven (FEh), booted, queues drained.
fn booted() -> N {
    boot(Node::new(NodeId::new(5).unwrap(), CFG, Flags::default()))
}

fn boot<S: Storage>(mut node: N<S>) -> N<S> {
    node.handle_timeout(Instant::ZERO);
    drain(&mut node);
    node
}

fn drain<S: Storage>(node: &mut N<S>) -> Vec<CanFrame> {
    while node.poll_event().is_some() {}
    core::iter::from_fn(|| node.poll_transmit()).collect()
}

/// An expedited download to node 5: the SDO response's command byte and its last four bytes (the abort
/// code of an abort, zeros for a confirmation).
fn download<S: Storage>(node: &mut N<S>, index: u16, sub: u8, value: u32, len: usize) -> (u8, u32) {
    let cmd = 0x23 | ((4 - len as u8) << 2);
    let [i0, i1] = index.to_le_bytes();
    let [v0, v1, v2, v3] = value.to_le_bytes();
    node.handle_frame(Instant::from_millis(1), &CanFrame::new(0x605, &[cmd, i0, i1, sub, v0, v1, v2, v3]).unwrap());
    let resp = drain(node);
    let d = resp.last().expect("an SDO response").data();
    assert_eq!(&d[1..4], &[i0, i1, sub]);
    (d[0], u32::from_le_bytes([d[4], d[5], d[6], d[7]]))
}

const OK: (u8, u32) = (0x60, 0);

fn aborted(code: u32) -> (u8, u32) {
    (0x80, code)
}

/// PDO-35 with 64 entries: the PDO made not valid, the mapping disabled, `entries` written to sub 01h–40h,
/// and the count set; returns the answer to the count.
fn remap<S: Storage>(node: &mut N<S>, comm: u16, map: u16, cob_id: u32, entries: &[u32]) -> (u8, u32) {
    assert_eq!(download(node, comm, 1, cob_id | 0x8000_0000, 4), OK);
    assert_eq!(download(node, map, 0, 0, 1), OK);
    for (i, &e) in entries.iter().enumerate() {
        assert_eq!(download(node, map, i as u8 + 1, e, 4), OK, "sub {:02X}h", i + 1);
    }
    download(node, map, 0, entries.len() as u32, 1)
}

/// 2000h:01..40h, one bit each.
fn one_bit_entries() -> Vec<u32> {
    (1..=64).map(|s| 0x2000_0001 | s << 8).collect()
}

/// PDO-30/31/32/35: TPDO1 (185h) mapping 64 one-bit BOOLEANs; objects 1, 2, 9 and 64 true give the frame
/// 03 01 00 00 00 00 00 80 (bit 0 of byte 0 is entry 1, bit 7 of byte 7 entry 64).
#[test]
fn tpdo_of_64_one_bit_entries() {
    assert_eq!(MAX_ENTRIES, 64);
    let mut node = booted();
    assert_eq!(remap(&mut node, 0x1800, 0x1A00, 0x4000_0185, &one_bit_entries()), OK);
    assert_eq!(download(&mut node, 0x1800, 1, 0x4000_0185, 4), OK);
    node.enter_state(NmtState::Operational);
    assert_eq!(drain(&mut node), [CanFrame::new(0x185, &[0; 8]).unwrap()]); // PDO-28: sent on entering
    node.app_mut().bits = 1 | 1 << 1 | 1 << 8 | 1 << 63;
    assert!(node.trigger_tpdo(0));
    assert_eq!(drain(&mut node), [CanFrame::new(0x185, &[0x03, 0x01, 0, 0, 0, 0, 0, 0x80]).unwrap()]);
}

/// PDO-30/32/34/35: RPDO1 (205h) mapping 64 one-bit entries, entry 8 a 1-bit BOOLEAN dummy (0001h, PDO-34):
/// the frame 81 80 00 00 00 00 00 80 sets objects 1, 16 and 64; bit 7 falls on the dummy, object 8 stays 0.
#[test]
fn rpdo_of_64_one_bit_entries_with_a_dummy() {
    let mut node = booted();
    let mut entries = one_bit_entries();
    entries[7] = 0x0001_0001;
    assert_eq!(remap(&mut node, 0x1400, 0x1600, 0x205, &entries), OK);
    assert_eq!(download(&mut node, 0x1400, 1, 0x205, 4), OK);
    node.enter_state(NmtState::Operational);
    drain(&mut node);
    node.handle_frame(Instant::from_millis(2), &CanFrame::new(0x205, &[0x81, 0x80, 0, 0, 0, 0, 0, 0x80]).unwrap());
    assert_eq!(node.app_mut().bits, 1 | 1 << 15 | 1 << 63);
}

/// PDO-30/37 and OD-16 at the 64-entry limit: sub 41h does not exist (0609 0011h), a count of 41h is
/// refused (0604 0042h), so are 64 entries of more than 64 bits (an 8-bit one and 63 one-bit ones: 71 bits);
/// a bad entry at sub 40h gets its PDO-36 code; each refused write leaves the mapping as it was.
#[test]
fn mapping_limits_at_64_entries_pdo_37() {
    let mut node = booted();
    assert_eq!(remap(&mut node, 0x1800, 0x1A00, 0x4000_0185, &one_bit_entries()[..1]), OK);
    assert_eq!(download(&mut node, 0x1A00, 0, 0, 1), OK);
    assert_eq!(download(&mut node, 0x1A00, 0x41, 0x2000_0101, 4), aborted(0x0609_0011));
    let mut entries = one_bit_entries();
    entries[0] = 0x2001_0008;
    assert_eq!(remap(&mut node, 0x1800, 0x1A00, 0x4000_0185, &entries), aborted(0x0604_0042));
    assert_eq!(download(&mut node, 0x1A00, 0, 0x41, 1), aborted(0x0604_0042));
    if cfg!(feature = "mpdo") {
        // MPDO-05: FEh makes the TPDO a SAM-MPDO (feature `mpdo`); back to 0 for the entry checks below.
        assert_eq!(download(&mut node, 0x1A00, 0, 0xFE, 1), OK);
        assert_eq!(download(&mut node, 0x1A00, 0, 0, 1), OK);
    } else {
        assert_eq!(download(&mut node, 0x1A00, 0, 0xFE, 1), aborted(0x0604_0042));
        // no MPDO in this build
    }
    // PDO-34/36 at sub 40h: a missing object, a missing sub-index, 65 bits, a dummy in a TPDO.
    assert_eq!(download(&mut node, 0x1A00, 0x40, 0x5000_0001, 4), aborted(0x0602_0000));
    assert_eq!(download(&mut node, 0x1A00, 0x40, 0x2000_4101, 4), aborted(0x0609_0011));
    assert_eq!(download(&mut node, 0x1A00, 0x40, 0x2000_0141, 4), aborted(0x0604_0041));
    assert_eq!(download(&mut node, 0x1A00, 0x40, 0x0001_0001, 4), aborted(0x0604_0041));
    node.handle_frame(Instant::from_millis(1), &CanFrame::new(0x605, &[0x40, 0x00, 0x1A, 0x40, 0, 0, 0, 0]).unwrap());
    assert_eq!(drain(&mut node).last().unwrap().data(), &[0x43, 0x00, 0x1A, 0x40, 0x01, 0x40, 0x00, 0x20]);
    node.handle_frame(Instant::from_millis(1), &CanFrame::new(0x605, &[0x40, 0x00, 0x1A, 0, 0, 0, 0, 0]).unwrap());
    assert_eq!(drain(&mut node).last().unwrap().data(), &[0x4F, 0x00, 0x1A, 0, 0, 0, 0, 0]); // still 0
    entries[0] = 0x2000_0101;
    assert_eq!(download(&mut node, 0x1A00, 1, entries[0], 4), OK);
    assert_eq!(download(&mut node, 0x1A00, 0, 0x40, 1), OK);
    // PDO-35: entries only while sub 00h = 0, the mapping only while the PDO is not valid (0601 0000h).
    assert_eq!(download(&mut node, 0x1A00, 0x40, 0x2000_4001, 4), aborted(0x0601_0000));
    assert_eq!(download(&mut node, 0x1800, 1, 0x4000_0185, 4), OK);
    assert_eq!(download(&mut node, 0x1A00, 0, 0, 1), aborted(0x0601_0000));
}

/// STORE-04 and PDO-30: a 64-entry RPDO mapping saved with 1010h sub 02h ("save") comes back after a reset
/// communication (NMT 82h), resolved again: the RPDO applies the frame 00 00 00 00 00 00 00 C0 (objects 63
/// and 64).
#[test]
fn a_stored_64_entry_mapping_survives_reset_communication() {
    let ram = Ram::new();
    let mut node = boot(Node::with_storage(NodeId::new(5).unwrap(), CFG, Flags::default(), ram));
    assert_eq!(remap(&mut node, 0x1400, 0x1600, 0x205, &one_bit_entries()), OK);
    assert_eq!(download(&mut node, 0x1400, 1, 0x205, 4), OK);
    assert_eq!(download(&mut node, 0x1010, 2, u32::from_le_bytes(*b"save"), 4), OK);
    node.handle_frame(Instant::from_millis(2), &CanFrame::new(0x000, &[0x82, 0x05]).unwrap());
    drain(&mut node);
    assert_eq!(node.params().rpdo_map[0].active(), one_bit_entries());
    node.enter_state(NmtState::Operational);
    drain(&mut node);
    node.handle_frame(Instant::from_millis(3), &CanFrame::new(0x205, &[0, 0, 0, 0, 0, 0, 0, 0xC0]).unwrap());
    assert_eq!(node.app_mut().bits, 3 << 62);
}

/// PDO-30: the EDS lists the mapping records with sub 00h–40h (SubNumber 41h) and the highest sub-index.
#[test]
fn eds_lists_64_mapping_entries_pdo_30() {
    let od: CommProfile<Sizes> = CommProfile::for_node(NodeConfig::DEFAULT, 5);
    let mut s = String::new();
    write_eds(&mut s, &EdsInfo::DEFAULT, &od).unwrap();
    for index in ["1600", "1A00"] {
        assert!(s.contains(&format!("[{index}]\nParameterName=")), "{index}");
        let at = s.find(&format!("[{index}]\n")).unwrap();
        assert!(s[at..].contains("SubNumber=0x41\n"), "{index}");
        assert!(s.contains(&format!("[{index}sub40]\n")), "{index}");
        assert!(!s.contains(&format!("[{index}sub41]\n")), "{index}");
    }
}
