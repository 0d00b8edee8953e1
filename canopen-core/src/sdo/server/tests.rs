//! Unit tests of the SDO server: the segmented and block exchanges of node 3 byte for byte (SDO-14..SDO-51)
//! and the choices in the module docs.

use super::test_od::{TestOd, STRING64};
use super::*;
#[cfg(feature = "sdo-block")]
use crate::sdo::block::Crc16;
use crate::wire::sdo::Segment;
#[cfg(feature = "sdo-block")]
use crate::Duration;

const T0: Instant = Instant::ZERO;

fn server() -> SdoServer {
    SdoServer::new(SdoServerParams::default_server(NodeId::new(3).unwrap()))
}

/// A server (node 3) and the test dictionary.
struct Bench {
    s: SdoServer,
    od: TestOd,
}

impl Bench {
    fn new() -> Self {
        Bench { s: server(), od: TestOd::new() }
    }

    #[cfg(feature = "sdo-block")]
    fn with_block_size(blksize: u8) -> Self {
        Bench { s: server().with_block_size(blksize), od: TestOd::new() }
    }

    /// Sends `req` at [`T0`], expects exactly `want` as the reply frame.
    fn ex(&mut self, req: [u8; 8], want: Option<[u8; 8]>) -> Response {
        let r = self.s.handle_request(T0, &req, &mut self.od);
        assert_eq!(r.frame, want, "request {req:02X?} → {:02X?}", r.frame);
        r
    }
}

fn abort_of(index: u16, sub: u8, code: AbortCode) -> Option<[u8; 8]> {
    Some(abort_frame(Multiplexer::new(index, sub), code.code()))
}

/// SDO-54, SDO-55: the node's per-frame test `receives` is `Some(id) == rx_cob_id()` for valid, invalid
/// (bit 31) and 29-bit (bit 29) COB-IDs in either direction, bit 30 (dyn) set or not, and every 11-bit ID.
#[test]
fn receives_is_the_rx_cob_id() {
    use crate::cob::CobIdEntry;
    for rx in [0x605, 0x605 | CobIdEntry::BIT30, 0x605 | CobIdEntry::BIT31, 0x605 | CobIdEntry::FRAME, 0x7FF] {
        for tx in [0x585, 0x585 | CobIdEntry::BIT30, 0x585 | CobIdEntry::BIT31, 0x585 | CobIdEntry::FRAME] {
            let params = SdoServerParams {
                cob_rx: CobIdEntry::from_raw(rx),
                cob_tx: CobIdEntry::from_raw(tx),
                client_node: None,
            };
            let s = SdoServer::new(params);
            for id in 0..=0x7FFu16 {
                assert_eq!(s.receives(id), Some(id) == s.rx_cob_id(), "{rx:X} {tx:X} {id:X}");
            }
        }
    }
}

#[test]
fn ram_bound() {
    let server = core::mem::size_of::<SdoServer>();
    std::eprintln!("size_of SdoServer = {server} B");
    assert!(server <= SdoServer::RAM_BYTES, "{server}");
    #[cfg(feature = "sdo-client")]
    {
        let client = core::mem::size_of::<crate::sdo::SdoClient>();
        std::eprintln!("size_of SdoClient = {client} B");
        assert!(client <= 96, "{client}");
    }
}

#[test]
fn expedited_requests_answered_positively() {
    let mut t = Bench::new();
    // Write 607Ah:00 (INTEGER32) = 0000 03E8h (1000): 23 7A 60 00 E8 03 00 00 -> 60 7A 60 00 ...
    let r = t.ex([0x23, 0x7A, 0x60, 0x00, 0xE8, 0x03, 0x00, 0x00], Some([0x60, 0x7A, 0x60, 0, 0, 0, 0, 0]));
    assert_eq!(r.event, Some(SdoEvent::Written { index: 0x607A, sub: 0 }));
    assert_eq!(t.od.get(0x607A, 0), Some(1000));
    // Read 6041h:00 -> 2 bytes 0240h: 40 41 60 00 ... -> 4B 41 60 00 40 02 00 00
    t.ex([0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0], Some([0x4B, 0x41, 0x60, 0x00, 0x40, 0x02, 0, 0]));
    // RPDO1 transmission type 1400h:02 = FDh is reserved for RPDOs: 0609 0030h; then a positive write of FEh
    t.ex([0x2F, 0x00, 0x14, 0x02, 0xFD, 0, 0, 0], abort_of(0x1400, 2, AbortCode::InvalidValue));
    t.ex([0x2F, 0x00, 0x14, 0x02, 0xFE, 0, 0, 0], Some([0x60, 0x00, 0x14, 0x02, 0, 0, 0, 0]));
    // Write 1603h:01 = 6012 0208h (map 6012h:02, 8 bits) and read it back
    t.ex([0x23, 0x03, 0x16, 0x01, 0x08, 0x02, 0x12, 0x60], Some([0x60, 0x03, 0x16, 0x01, 0, 0, 0, 0]));
    t.ex([0x40, 0x03, 0x16, 0x01, 0, 0, 0, 0], Some([0x43, 0x03, 0x16, 0x01, 0x08, 0x02, 0x12, 0x60]));
    // Read 1400h:02 -> 1 byte (FEh after the write above)
    t.ex([0x40, 0x00, 0x14, 0x02, 0, 0, 0, 0], Some([0x4F, 0x00, 0x14, 0x02, 0xFE, 0, 0, 0]));
    // Our 1018h: vendor-ID 2B6h at 1018h:01, 4 entries at 1018h:00; device type 1000h read while served
    t.ex([0x40, 0x18, 0x10, 0x01, 0, 0, 0, 0], Some([0x43, 0x18, 0x10, 0x01, 0xB6, 0x02, 0, 0]));
    t.ex([0x40, 0x18, 0x10, 0x00, 0, 0, 0, 0], Some([0x4F, 0x18, 0x10, 0x00, 0x04, 0, 0, 0]));
    t.ex([0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0], Some([0x43, 0x00, 0x10, 0x00, 0x91, 0x01, 0, 0]));
    // SDO-13: 22h without size into a U16 takes 2 bytes
    t.ex([0x22, 0x17, 0x10, 0x00, 0xE8, 0x03, 0xAA, 0xBB], Some([0x60, 0x17, 0x10, 0, 0, 0, 0, 0]));
    assert_eq!(t.od.get(0x1017, 0), Some(1000));
    assert!(t.s.is_idle());
    assert_eq!(t.s.poll_timeout(), None);
}

#[test]
fn expedited_negative_cases_and_od_abort_codes() {
    let mut t = Bench::new();
    let cases: &[([u8; 8], u16, u8, AbortCode)] = &[
        ([0x40, 0x00, 0x50, 0x00, 0, 0, 0, 0], 0x5000, 0, AbortCode::ObjectDoesNotExist), // 5000h absent
        ([0x40, 0x18, 0x10, 0x07, 0, 0, 0, 0], 0x1018, 7, AbortCode::SubIndexDoesNotExist), // 1018h:07 absent
        ([0x23, 0x00, 0x10, 0x00, 0, 0, 0, 0], 0x1000, 0, AbortCode::WriteOfReadOnly),    // write of ro 1000h
        ([0x2F, 0x17, 0x10, 0x00, 0x64, 0, 0, 0], 0x1017, 0, AbortCode::LengthTooLow),    // 1 byte into U16 1017h
        ([0x23, 0x0D, 0x10, 0x00, 0x03, 0, 0, 0], 0x100D, 0, AbortCode::LengthTooHigh),   // 4 bytes into U8 100Dh
        ([0xE0, 0x00, 0x10, 0x00, 0, 0, 0, 0], 0x1000, 0, AbortCode::InvalidCommandSpecifier), // ccs 7
        ([0x40, 0x01, 0x20, 0x00, 0, 0, 0, 0], 0x2001, 0, AbortCode::ReadOfWriteOnly),
        ([0x2B, 0x02, 0x20, 0x00, 0x65, 0x00, 0, 0], 0x2002, 0, AbortCode::ValueTooHigh),
        ([0x2B, 0x02, 0x20, 0x00, 0x9B, 0xFF, 0, 0], 0x2002, 0, AbortCode::ValueTooLow),
        ([0x23, 0x03, 0x20, 0x00, 0, 0, 0, 0], 0x2003, 0, AbortCode::InvalidValue),
        ([0x23, 0x03, 0x20, 0x00, 1, 0, 0, 0], 0x2003, 0, AbortCode::GeneralError),
        ([0x23, 0x03, 0x20, 0x00, 2, 0, 0, 0], 0x2003, 0, AbortCode::CannotStore),
        ([0x23, 0x03, 0x20, 0x00, 3, 0, 0, 0], 0x2003, 0, AbortCode::CannotStoreDeviceState),
        ([0x21, 0x17, 0x10, 0x00, 3, 0, 0, 0], 0x1017, 0, AbortCode::LengthTooHigh), // SDO-18 at initiate
        ([0x21, 0x05, 0x20, 0x00, 4, 0, 0, 0], 0x2005, 0, AbortCode::LengthTooLow),
        #[cfg(feature = "sdo-block")]
        ([0xC6, 0x00, 0x20, 0x00, 0x01, 0x00, 0x01, 0x00], 0x2000, 0, AbortCode::OutOfMemory), // 65537 bytes
    ];
    for &(req, index, sub, code) in cases {
        let r = t.ex(req, abort_of(index, sub, code));
        assert_eq!(r.event, Some(SdoEvent::Aborted { index, sub, code }));
        assert!(t.s.is_idle());
    }
    // a refused write changed nothing
    assert_eq!(t.od.get(0x2003, 0), Some(7));
    // streamed write to a fixed-size object the OD cannot stream: unsupported access (0601 0000h) does
    // not arise; a streamed end_write refusal does (0800 0020h)
    t.ex([0x21, 0x07, 0x20, 0x00, 3, 0, 0, 0], Some([0x60, 0x07, 0x20, 0, 0, 0, 0, 0]));
    t.ex([0x09, b'b', b'a', b'd', 0, 0, 0, 0], abort_of(0x2007, 0, AbortCode::CannotStore));
    assert_eq!(t.od.aborted_writes, 1);
}

/// A dictionary of one object at every index: `info` says `data_type`, `access` and `size`; `read` delivers
/// only `readable` bytes (`x`); writes succeed and are dropped. Streaming is the trait's default: refused.
struct OneObject {
    data_type: crate::od::DataType,
    access: crate::od::Access,
    size: usize,
    readable: usize,
}

impl ObjectDictionary for OneObject {
    fn info(&self, _: u16, _: u8) -> Result<crate::od::SubInfo, AbortCode> {
        let (data_type, access, size) = (self.data_type, self.access, self.size);
        Ok(crate::od::SubInfo { data_type, access, pdo: crate::od::PdoMapping::No, size })
    }
    fn read(&self, _: u16, _: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        let n = self.readable.saturating_sub(offset).min(buf.len());
        buf[..n].fill(b'x');
        Ok(n)
    }
    fn write(&mut self, _: u16, _: u8, _: &[u8]) -> Result<(), AbortCode> {
        Ok(())
    }
}

#[test]
fn unsupported_access_from_od() {
    // An OD that cannot stream a DOMAIN: the trait's default begin_write refuses with 0601 0000h.
    let mut od =
        OneObject { data_type: crate::od::DataType::Domain, access: crate::od::Access::Rw, size: 0, readable: 0 };
    let mut s = server();
    let r = s.handle_request(T0, &[0x21, 0x00, 0x30, 0x00, 3, 0, 0, 0], &mut od);
    assert_eq!(r.frame, abort_of(0x3000, 0, AbortCode::UnsupportedAccess));
    // an empty DOMAIN uploads as a segmented transfer of 0 bytes: one segment with n = 7, c = 1
    let r = s.handle_request(T0, &[0x40, 0x00, 0x30, 0x00, 0, 0, 0, 0], &mut od);
    assert_eq!(r.frame, Some([0x41, 0x00, 0x30, 0x00, 0, 0, 0, 0]));
    let r = s.handle_request(T0, &[0x60, 0, 0, 0, 0, 0, 0, 0], &mut od);
    assert_eq!(r.frame, Some([0x0F, 0, 0, 0, 0, 0, 0, 0]));
    assert!(s.is_idle());
}

#[test]
fn value_shorter_than_announced_is_length_mismatch() {
    // info says 10 bytes, read delivers only 3: the upload cannot keep its announced size (0607 0010h)
    let mut od = OneObject {
        data_type: crate::od::DataType::VisibleString,
        access: crate::od::Access::Ro,
        size: 10,
        readable: 3,
    };
    let mut s = server();
    let r = s.handle_request(T0, &[0x40, 0x00, 0x30, 0x00, 0, 0, 0, 0], &mut od);
    assert_eq!(r.frame, Some([0x41, 0x00, 0x30, 0x00, 10, 0, 0, 0]));
    let r = s.handle_request(T0, &[0x60, 0, 0, 0, 0, 0, 0, 0], &mut od);
    assert_eq!(r.frame, abort_of(0x3000, 0, AbortCode::LengthMismatch));
    #[cfg(feature = "sdo-block")]
    {
        let r = s.handle_request(T0, &[0xA4, 0x00, 0x30, 0x00, 0x7F, 0, 0, 0], &mut od);
        assert_eq!(r.frame, Some([0xC6, 0x00, 0x30, 0x00, 10, 0, 0, 0]));
        s.handle_request(T0, &[0xA3, 0, 0, 0, 0, 0, 0, 0], &mut od);
        assert_eq!(s.poll_transmit(T0, &mut od).unwrap().frame, abort_of(0x3000, 0, AbortCode::LengthMismatch));
    }
    assert!(s.is_idle());
}

/// Without the `sdo-block` feature the server has no block transfer: an initiate (block download C6h, block
/// upload A4h) is refused with 0504 0001h for its object, every other block request with 0504 0001h as out
/// of state (SDO-09), and the server stays idle.
#[test]
#[cfg(not(feature = "sdo-block"))]
fn block_transfer_compiled_out() {
    let mut t = Bench::new();
    let invalid = AbortCode::InvalidCommandSpecifier;
    t.ex([0xC6, 0x00, 0x20, 0x00, 9, 0, 0, 0], abort_of(0x2000, 0, invalid)); // a block initiate (C6h, size 9)
    assert!(t.s.is_idle());
    t.ex([0xA4, 0x04, 0x20, 0x00, 0x7F, 0, 0, 0], abort_of(0x2004, 0, invalid)); // block upload initiate
    assert!(t.s.is_idle());
    for req in [[0xA3, 0, 0, 0, 0, 0, 0, 0], [0xA1, 0, 0, 0, 0, 0, 0, 0], [0xC1, 0, 0, 0, 0, 0, 0, 0]] {
        t.ex(req, abort_of(0, 0, invalid));
    }
    // A segmented transfer under way is aborted by a block request, as by any out-of-state frame.
    t.ex([0x40, 0x04, 0x20, 0x00, 0, 0, 0, 0], Some([0x41, 0x04, 0x20, 0x00, 64, 0, 0, 0]));
    t.ex([0xA2, 1, 0x7F, 0, 0, 0, 0, 0], abort_of(0x2004, 0, invalid));
    assert!(t.s.is_idle());
}

/// SDO-09: a segment of the other direction is out of state: an upload segment request (60h) during a
/// segmented download and a download segment (00h) during a segmented upload are each aborted with
/// 0504 0001h for the transfer's object, which ends; the toggle of either does not matter.
#[test]
fn segment_of_the_other_direction_is_out_of_state() {
    let invalid = AbortCode::InvalidCommandSpecifier;
    for t_bit in [0x00, 0x10] {
        let mut t = Bench::new();
        t.ex([0x21, 0x00, 0x20, 0x00, 9, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
        t.ex([0x60 | t_bit, 0, 0, 0, 0, 0, 0, 0], abort_of(0x2000, 0, invalid));
        assert!(t.s.is_idle());
        assert_eq!(t.od.aborted_writes, 1); // the streamed write is abandoned
        t.ex([0x40, 0x04, 0x20, 0x00, 0, 0, 0, 0], Some([0x41, 0x04, 0x20, 0x00, 64, 0, 0, 0]));
        t.ex([t_bit, 1, 2, 3, 4, 5, 6, 7], abort_of(0x2004, 0, invalid));
        assert!(t.s.is_idle());
    }
}

/// The segmented upload of 1009h "N10 - WT1209-V1.00-8MB\0" (23 bytes, SDO-25..SDO-28), then the same upload with
/// the second segment request repeating t = 0 (60h instead of 70h): abort 0503 0000h (SDO-30).
#[test]
fn segmented_upload_of_1009h_and_toggle_error() {
    let mut t = Bench::new();
    let steps: [([u8; 8], Option<[u8; 8]>); 8] = [
        ([0x40, 0x09, 0x10, 0x00, 0, 0, 0, 0], Some([0x41, 0x09, 0x10, 0x00, 0x17, 0, 0, 0])),
        ([0x60, 0, 0, 0, 0, 0, 0, 0], Some([0x00, 0x4E, 0x31, 0x30, 0x20, 0x2D, 0x20, 0x57])),
        ([0x70, 0, 0, 0, 0, 0, 0, 0], Some([0x10, 0x54, 0x31, 0x32, 0x30, 0x39, 0x2D, 0x56])),
        // 002's client puts the multiplexer in the reserved bytes: accepted (SDO-02)
        ([0x60, 0x09, 0x10, 0x00, 0, 0, 0, 0], Some([0x00, 0x31, 0x2E, 0x30, 0x30, 0x2D, 0x38, 0x4D])),
        ([0x70, 0, 0, 0, 0, 0, 0, 0], Some([0x1B, 0x42, 0x00, 0, 0, 0, 0, 0])),
        // a second upload: its first segment request has t = 0 again (every transfer starts with toggle 0)
        ([0x40, 0x09, 0x10, 0x00, 0, 0, 0, 0], Some([0x41, 0x09, 0x10, 0x00, 0x17, 0, 0, 0])),
        ([0x60, 0x09, 0x10, 0x00, 0, 0, 0, 0], Some([0x00, 0x4E, 0x31, 0x30, 0x20, 0x2D, 0x20, 0x57])),
        ([0x60, 0x09, 0x10, 0x00, 0, 0, 0, 0], abort_of(0x1009, 0, AbortCode::ToggleNotAlternated)),
    ];
    for (i, (req, rsp)) in steps.iter().enumerate() {
        let r = t.ex(*req, *rsp);
        if i == 4 {
            assert_eq!(r.event, Some(SdoEvent::Uploaded { index: 0x1009, sub: 0 }));
        }
        assert_eq!(t.s.is_idle(), i == 4 || i == 7, "step {i}");
    }
}

#[test]
fn segmented_download_of_9_bytes_and_variants() {
    let mut t = Bench::new();
    t.ex([0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
    t.ex([0x00, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37], Some([0x20, 0, 0, 0, 0, 0, 0, 0]));
    let r = t.ex([0x1B, 0x38, 0x39, 0, 0, 0, 0, 0], Some([0x30, 0, 0, 0, 0, 0, 0, 0]));
    assert_eq!(r.event, Some(SdoEvent::Written { index: 0x2000, sub: 0 }));
    assert_eq!(t.od.domain(), b"123456789");

    // toggle-error variant
    t.ex([0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
    t.ex([0x00, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37], Some([0x20, 0, 0, 0, 0, 0, 0, 0]));
    t.ex([0x0B, 0x38, 0x39, 0, 0, 0, 0, 0], Some([0x80, 0x00, 0x20, 0x00, 0x00, 0x00, 0x03, 0x05]));
    assert_eq!(t.od.aborted_writes, 1);

    // time-out variant (SDO-31)
    let t1 = Instant::from_millis(10);
    let r = t.s.handle_request(t1, &[0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], &mut t.od);
    assert!(r.frame.is_some());
    let deadline = t.s.poll_timeout().unwrap();
    assert_eq!(deadline, t1 + super::super::DEFAULT_TIMEOUT);
    assert_eq!(t.s.handle_timeout(Instant::from_micros(deadline.as_micros() - 1), &mut t.od), Response::NONE);
    let r = t.s.handle_timeout(deadline, &mut t.od);
    assert_eq!(r.frame, Some([0x80, 0x00, 0x20, 0x00, 0x00, 0x00, 0x04, 0x05]));
    assert_eq!(r.event, Some(SdoEvent::Aborted { index: 0x2000, sub: 0, code: AbortCode::SdoTimeout }));
    assert!(t.s.is_idle() && t.s.poll_timeout().is_none());
    assert_eq!(t.od.aborted_writes, 2);

    // new-initiate variant (SDO-29)
    t.ex([0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
    t.ex([0x00, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37], Some([0x20, 0, 0, 0, 0, 0, 0, 0]));
    t.ex([0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0], Some([0x43, 0x00, 0x10, 0x00, 0x91, 0x01, 0, 0]));
    assert_eq!(t.od.aborted_writes, 3);
    assert!(t.s.is_idle());
    assert_eq!(t.od.domain(), b"123456789"); // the abandoned write left the old value visible
}

/// SDO-31: a zero time-out disables it: a transfer under way has no deadline and is never aborted for time,
/// and setting a time-out again gives the next frame its deadline.
#[test]
fn zero_timeout_disables_the_protocol_timeout() {
    let mut t = Bench { s: server().with_timeout(Duration::ZERO), od: TestOd::new() };
    t.ex([0x21, 0x00, 0x20, 0x00, 21, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
    assert!(!t.s.is_idle());
    assert_eq!(t.s.poll_timeout(), None);
    assert_eq!(t.s.handle_timeout(Instant::from_micros(u64::MAX - 1), &mut t.od), Response::NONE);
    assert!(!t.s.is_idle());
    t.s.set_timeout(Duration::from_millis(20));
    let t1 = Instant::from_millis(5);
    let r = t.s.handle_request(t1, &[0x00, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37], &mut t.od);
    assert_eq!(r.frame, Some([0x20, 0, 0, 0, 0, 0, 0, 0]));
    assert_eq!(t.s.poll_timeout(), Some(Instant::from_millis(25)));
    t.s.set_timeout(Duration::ZERO);
    let r = t.s.handle_request(t1, &[0x10, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37], &mut t.od);
    assert_eq!(r.frame, Some([0x30, 0, 0, 0, 0, 0, 0, 0]));
    assert!(!t.s.is_idle());
    assert_eq!(t.s.poll_timeout(), None);
    t.ex([0x01, 0x38, 0x39, 0x30, 0x31, 0x32, 0x33, 0x34], Some([0x20, 0, 0, 0, 0, 0, 0, 0]));
    assert_eq!(t.od.domain(), b"123456712345678901234");
}

/// SDO-31: a time-out changed during a transfer leaves the deadline it has; the next frame gets the new one.
/// Disabling it removes the deadline at once (the server keeps the instant of the last frame, not the deadline).
#[test]
fn changed_timeout_applies_from_the_next_frame() {
    let mut t = Bench::new();
    let t1 = Instant::from_millis(100);
    let r = t.s.handle_request(t1, &[0x21, 0x00, 0x20, 0x00, 21, 0, 0, 0], &mut t.od);
    assert_eq!(r.frame, Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
    assert_eq!(t.s.poll_timeout(), Some(t1 + super::super::DEFAULT_TIMEOUT));
    t.s.set_timeout(Duration::from_millis(30));
    assert_eq!(t.s.poll_timeout(), Some(t1 + super::super::DEFAULT_TIMEOUT));
    let t2 = Instant::from_millis(200);
    let r = t.s.handle_request(t2, &[0x00, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37], &mut t.od);
    assert_eq!(r.frame, Some([0x20, 0, 0, 0, 0, 0, 0, 0]));
    assert_eq!(t.s.poll_timeout(), Some(Instant::from_millis(230)));
    t.s.set_timeout(Duration::from_millis(100));
    assert_eq!(t.s.poll_timeout(), Some(Instant::from_millis(230)));
    // a time-out longer than the deadline is after the origin: the deadline is the new time-out after it
    t.s.set_timeout(Duration::from_millis(2_000));
    assert_eq!(t.s.poll_timeout(), Some(Instant::from_millis(2_000)));
    t.s.set_timeout(Duration::ZERO);
    assert_eq!(t.s.poll_timeout(), None);
    assert_eq!(t.s.handle_timeout(Instant::from_micros(u64::MAX - 1), &mut t.od), Response::NONE);
    assert!(!t.s.is_idle());
}

#[test]
fn segmented_length_checks() {
    let mut t = Bench::new();
    // announced 9, sends 14 → too high at the second segment
    t.ex([0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
    t.ex([0x00, 1, 2, 3, 4, 5, 6, 7], Some([0x20, 0, 0, 0, 0, 0, 0, 0]));
    t.ex([0x11, 1, 2, 3, 4, 5, 6, 7], abort_of(0x2000, 0, AbortCode::LengthTooHigh));
    // announced 9, sends 7 → too low at the last segment
    t.ex([0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
    t.ex([0x01, 1, 2, 3, 4, 5, 6, 7], abort_of(0x2000, 0, AbortCode::LengthTooLow));
    // segmented U64 without size via the scratch: 8 bytes are written, 9 do not fit the 8-byte scratch
    let last_segments = [
        ([0x1D, 8, 0, 0, 0, 0, 0, 0], Some([0x30, 0, 0, 0, 0, 0, 0, 0])),
        ([0x1B, 8, 9, 0, 0, 0, 0, 0], abort_of(0x2005, 0, AbortCode::LengthTooHigh)),
    ];
    for (last, want) in last_segments {
        t.ex([0x20, 0x05, 0x20, 0x00, 0, 0, 0, 0], Some([0x60, 0x05, 0x20, 0x00, 0, 0, 0, 0]));
        t.ex([0x00, 1, 2, 3, 4, 5, 6, 7], Some([0x20, 0, 0, 0, 0, 0, 0, 0]));
        t.ex(last, want);
        assert_eq!(t.od.get(0x2005, 0), Some(0x0807_0605_0403_0201)); // the refused 9 bytes changed nothing
    }
}

#[test]
fn segmented_upload_64_byte_string_and_read_error() {
    let mut t = Bench::new();
    t.ex([0x40, 0x04, 0x20, 0x00, 0, 0, 0, 0], Some([0x41, 0x04, 0x20, 0x00, 64, 0, 0, 0]));
    let mut got = [0u8; 64];
    let mut n = 0;
    for i in 0..10u8 {
        let toggle = i % 2 == 1;
        let r = t.s.handle_request(T0, &[0x60 | (u8::from(toggle) << 4), 0, 0, 0, 0, 0, 0, 0], &mut t.od);
        let seg = Segment::parse(&r.frame.unwrap()).unwrap();
        assert_eq!(seg.toggle, toggle);
        got[n..n + seg.bytes().len()].copy_from_slice(seg.bytes());
        n += seg.bytes().len();
        assert_eq!(seg.last, i == 9);
    }
    assert_eq!(&got, STRING64);
    // 2006h fails reading at offset 14: the third segment aborts with the OD's code (0606 0000h)
    t.ex([0x40, 0x06, 0x20, 0x00, 0, 0, 0, 0], Some([0x41, 0x06, 0x20, 0x00, 200, 0, 0, 0]));
    t.ex([0x60, 0, 0, 0, 0, 0, 0, 0], Some([0x00, 0x55, 0x55, 0x55, 0x55, 0x55, 0x55, 0x55]));
    t.ex([0x70, 0, 0, 0, 0, 0, 0, 0], Some([0x10, 0x55, 0x55, 0x55, 0x55, 0x55, 0x55, 0x55]));
    t.ex([0x60, 0, 0, 0, 0, 0, 0, 0], abort_of(0x2006, 0, AbortCode::HardwareError));
}

#[test]
#[cfg(feature = "sdo-block")]
fn block_download_of_9_bytes_and_variants() {
    let mut t = Bench::new();
    t.ex([0xC6, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0xA4, 0x00, 0x20, 0x00, 0x7F, 0, 0, 0]));
    t.ex([0x01, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37], None);
    t.ex([0x82, 0x38, 0x39, 0, 0, 0, 0, 0], Some([0xA2, 0x02, 0x7F, 0, 0, 0, 0, 0]));
    assert_eq!(t.s.state(), ServerState::BlockDownloadEnd);
    let r = t.ex([0xD5, 0xC3, 0x31, 0, 0, 0, 0, 0], Some([0xA1, 0, 0, 0, 0, 0, 0, 0]));
    assert_eq!(r.event, Some(SdoEvent::Written { index: 0x2000, sub: 0 }));
    assert_eq!(t.od.domain(), b"123456789");

    // CRC error variant
    t.ex([0xC6, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0xA4, 0x00, 0x20, 0x00, 0x7F, 0, 0, 0]));
    t.ex([0x01, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37], None);
    t.ex([0x82, 0x38, 0x39, 0, 0, 0, 0, 0], Some([0xA2, 0x02, 0x7F, 0, 0, 0, 0, 0]));
    t.ex([0xD5, 0, 0, 0, 0, 0, 0, 0], Some([0x80, 0x00, 0x20, 0x00, 0x04, 0x00, 0x04, 0x05]));
    assert_eq!(t.od.aborted_writes, 1);

    // no-CRC variant: sc = cc = 0, CRC bytes not checked
    t.ex([0xC2, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0xA0, 0x00, 0x20, 0x00, 0x7F, 0, 0, 0]));
    t.ex([0x01, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37], None);
    t.ex([0x82, 0x38, 0x39, 0, 0, 0, 0, 0], Some([0xA2, 0x02, 0x7F, 0, 0, 0, 0, 0]));
    // a CAN-level duplicate of the last segment is not taken for an end frame
    t.ex([0x82, 0x38, 0x39, 0, 0, 0, 0, 0], None);
    t.ex([0xD5, 0x12, 0x34, 0, 0, 0, 0, 0], Some([0xA1, 0, 0, 0, 0, 0, 0, 0]));

    // block download of a U32 via the scratch
    t.ex([0xC6, 0x7A, 0x60, 0x00, 4, 0, 0, 0], Some([0xA4, 0x7A, 0x60, 0x00, 0x7F, 0, 0, 0]));
    t.ex([0x81, 0x10, 0x27, 0, 0, 0, 0, 0], Some([0xA2, 0x01, 0x7F, 0, 0, 0, 0, 0]));
    let mut crc = Crc16::new();
    crc.update(&[0x10, 0x27, 0, 0]);
    let [c0, c1] = crc.get().to_le_bytes();
    t.ex([0xCD, c0, c1, 0, 0, 0, 0, 0], Some([0xA1, 0, 0, 0, 0, 0, 0, 0]));
    assert_eq!(t.od.get(0x607A, 0), Some(10_000));
}

/// Block download of "ABCDEFGHIJKLMNOP" with blksize 3 (segment 2 lost, 83h closes the sub-block: acknowledge 1,
/// go back, CRC 6080h), with SDO-40's duplicates:
/// a CAN-level repeat of the segment that made the server acknowledge is ignored, not acknowledged again (a
/// second acknowledge would read as the next sub-block's and make the client skip segments).
#[test]
#[cfg(feature = "sdo-block")]
fn block_download_go_back_n_after_a_lost_segment() {
    let mut t = Bench::with_block_size(3);
    t.ex([0xC6, 0x00, 0x20, 0x00, 0x10, 0, 0, 0], Some([0xA4, 0x00, 0x20, 0x00, 0x03, 0, 0, 0]));
    t.ex([0x01, 0x41, 0x42, 0x43, 0x44, 0x45, 0x46, 0x47], None);
    t.ex([0x83, 0x4F, 0x50, 0, 0, 0, 0, 0], Some([0xA2, 0x01, 0x03, 0, 0, 0, 0, 0]));
    t.ex([0x83, 0x4F, 0x50, 0, 0, 0, 0, 0], None);
    t.ex([0x01, 0x48, 0x49, 0x4A, 0x4B, 0x4C, 0x4D, 0x4E], None);
    t.ex([0x82, 0x4F, 0x50, 0, 0, 0, 0, 0], Some([0xA2, 0x02, 0x03, 0, 0, 0, 0, 0]));
    t.ex([0xD5, 0x80, 0x60, 0, 0, 0, 0, 0], Some([0xA1, 0, 0, 0, 0, 0, 0, 0]));
    assert_eq!(t.od.domain(), b"ABCDEFGHIJKLMNOP");
    // the same after an in-order acknowledge (03h = blksize): its repeat is ignored, the next sub-block goes on
    t.ex([0xC6, 0x00, 0x20, 0x00, 0x16, 0, 0, 0], Some([0xA4, 0x00, 0x20, 0x00, 0x03, 0, 0, 0]));
    for seg in [[0x01, 1, 2, 3, 4, 5, 6, 7], [0x02, 8, 9, 10, 11, 12, 13, 14]] {
        t.ex(seg, None);
    }
    t.ex([0x03, 15, 16, 17, 18, 19, 20, 21], Some([0xA2, 0x03, 0x03, 0, 0, 0, 0, 0]));
    t.ex([0x03, 15, 16, 17, 18, 19, 20, 21], None);
    t.ex([0x81, 22, 0, 0, 0, 0, 0, 0], Some([0xA2, 0x01, 0x03, 0, 0, 0, 0, 0]));
    assert_eq!(t.s.state(), ServerState::BlockDownloadEnd);
}

/// SDO-29: a block download initiate during a streamed segmented download drops that transfer first
/// (`abort_write` for its object, 2000h:00), then answers for its own object (1000h:00): 0601 0002h with
/// block transfer (1000h is read-only), 0504 0001h without (SDO-35 not built).
#[test]
fn block_initiate_during_a_stream_drops_it_for_its_own_object() {
    let mut t = Bench::new();
    t.ex([0x21, 0x00, 0x20, 0x00, 9, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
    t.ex([0x00, 1, 2, 3, 4, 5, 6, 7], Some([0x20, 0, 0, 0, 0, 0, 0, 0]));
    #[cfg(feature = "sdo-block")]
    let code = AbortCode::WriteOfReadOnly;
    #[cfg(not(feature = "sdo-block"))]
    let code = AbortCode::InvalidCommandSpecifier;
    t.ex([0xC6, 0x00, 0x10, 0x00, 4, 0, 0, 0], abort_of(0x1000, 0, code));
    assert_eq!((t.od.aborted_writes, t.od.aborted_object), (1, Some((0x2000, 0))));
    assert!(t.s.is_idle());
}

/// SDO-40: a CAN-level repeat of the segment the server holds (taken in order, not acknowledged yet) is
/// ignored, also with the c bit set (01h again as 81h): the server has that sequence number. The same
/// sequence number with other data is no repeat: with c = 1 it is an out-of-order last segment, and the
/// sub-block is acknowledged up to the held one without ending the transfer.
#[test]
#[cfg(feature = "sdo-block")]
fn repeat_of_the_held_segment_is_ignored_c_bit_aside() {
    let mut t = Bench::with_block_size(8);
    t.ex([0xC6, 0x00, 0x20, 0x00, 0x10, 0, 0, 0], Some([0xA4, 0x00, 0x20, 0x00, 8, 0, 0, 0]));
    let first = [0x01, 0x41, 0x42, 0x43, 0x44, 0x45, 0x46, 0x47];
    t.ex(first, None);
    t.ex(first, None);
    t.ex([0x81, 0x41, 0x42, 0x43, 0x44, 0x45, 0x46, 0x47], None);
    assert_eq!(t.s.state(), ServerState::BlockDownloadSubBlock);
    let second = [0x02, 0x48, 0x49, 0x4A, 0x4B, 0x4C, 0x4D, 0x4E];
    t.ex(second, None);
    t.ex(second, None);
    t.ex([0x83, 0x4F, 0x50, 0, 0, 0, 0, 0], Some([0xA2, 0x03, 0x08, 0, 0, 0, 0, 0]));
    let mut crc = Crc16::new();
    crc.update(b"ABCDEFGHIJKLMNOP");
    let [c0, c1] = crc.get().to_le_bytes();
    t.ex([0xD5, c0, c1, 0, 0, 0, 0, 0], Some([0xA1, 0, 0, 0, 0, 0, 0, 0]));
    assert_eq!(t.od.domain(), b"ABCDEFGHIJKLMNOP");
    // the held sequence number with other data and c = 1: acknowledged up to 1, not the end
    t.ex([0xC6, 0x00, 0x20, 0x00, 0x10, 0, 0, 0], Some([0xA4, 0x00, 0x20, 0x00, 8, 0, 0, 0]));
    t.ex(first, None);
    t.ex([0x81, 0x41, 0x42, 0x43, 0x44, 0x45, 0x46, 0x00], Some([0xA2, 0x01, 0x08, 0, 0, 0, 0, 0]));
    assert_eq!(t.s.state(), ServerState::BlockDownloadSubBlock);
}

/// SDO-40/SDO-41: while waiting for "end block download", a late segment (here the last segment again as
/// number 1 of a repeated sub-block, 81h) is ignored, not read as an abort with reserved bits; the end
/// frame still completes the transfer.
#[test]
#[cfg(feature = "sdo-block")]
fn late_segment_before_block_end_is_ignored() {
    let mut t = Bench::with_block_size(8);
    t.ex([0xC6, 0x00, 0x20, 0x00, 0x10, 0, 0, 0], Some([0xA4, 0x00, 0x20, 0x00, 8, 0, 0, 0]));
    t.ex([0x01, 0x41, 0x42, 0x43, 0x44, 0x45, 0x46, 0x47], None);
    t.ex([0x02, 0x48, 0x49, 0x4A, 0x4B, 0x4C, 0x4D, 0x4E], None);
    t.ex([0x83, 0x4F, 0x50, 0, 0, 0, 0, 0], Some([0xA2, 0x03, 0x08, 0, 0, 0, 0, 0]));
    assert_eq!(t.s.state(), ServerState::BlockDownloadEnd);
    // late copies under other sequence numbers, last bit or not: silence, still waiting for the end
    for late in [[0x81, 0x4F, 0x50, 0, 0, 0, 0, 0], [0x82, 0x2E, 0x4D, 0x6C, 0x8B, 0xAA, 0xC9, 0], [0x02; 8]] {
        let r = t.ex(late, None);
        assert_eq!(r.event, None, "{late:02X?}");
        assert_eq!(t.s.state(), ServerState::BlockDownloadEnd, "{late:02X?}");
    }
    let mut crc = Crc16::new();
    crc.update(b"ABCDEFGHIJKLMNOP");
    let [c0, c1] = crc.get().to_le_bytes();
    let r = t.ex([0xD5, c0, c1, 0, 0, 0, 0, 0], Some([0xA1, 0, 0, 0, 0, 0, 0, 0]));
    assert_eq!(r.event, Some(SdoEvent::Written { index: 0x2000, sub: 0 }));
    assert_eq!(t.od.domain(), b"ABCDEFGHIJKLMNOP");
    // a seqno beyond the block size cannot be a segment: 89h is an abort (reserved bits set, SDO-02)
    t.ex([0xC6, 0x00, 0x20, 0x00, 0x01, 0, 0, 0], Some([0xA4, 0x00, 0x20, 0x00, 8, 0, 0, 0]));
    t.ex([0x81, 0x41, 0, 0, 0, 0, 0, 0], Some([0xA2, 0x01, 0x08, 0, 0, 0, 0, 0]));
    let r = t.ex([0x89, 0x00, 0x20, 0x00, 0x00, 0x00, 0x04, 0x05], None);
    assert!(matches!(r.event, Some(SdoEvent::AbortReceived { code: 0x0504_0000, .. })), "{:?}", r.event);
    assert!(t.s.is_idle());
}

#[test]
#[cfg(feature = "sdo-block")]
fn block_download_sequence_and_size_errors() {
    let mut t = Bench::with_block_size(3);
    // seqno 0 and seqno > blksize → 0504 0003h
    for bad in [0x00u8, 0x04, 0x80 | 0x05] {
        t.ex([0xC4, 0x00, 0x20, 0x00, 0, 0, 0, 0], Some([0xA4, 0x00, 0x20, 0x00, 0x03, 0, 0, 0]));
        t.ex([bad, 1, 2, 3, 4, 5, 6, 7], abort_of(0x2000, 0, AbortCode::InvalidSequenceNumber));
    }
    // an abort frame during a sub-block is an abort, not a segment (SDO-33: not answered)
    t.ex([0xC4, 0x00, 0x20, 0x00, 0, 0, 0, 0], Some([0xA4, 0x00, 0x20, 0x00, 0x03, 0, 0, 0]));
    let r = t.ex([0x80, 0x00, 0x20, 0x00, 0x00, 0x00, 0x00, 0x08], None);
    assert_eq!(r.event, Some(SdoEvent::AbortReceived { index: 0x2000, sub: 0, code: 0x0800_0000 }));
    assert!(t.s.is_idle());
    // more data than announced → 0607 0012h; less → 0607 0013h
    t.ex([0xC6, 0x00, 0x20, 0x00, 0x03, 0, 0, 0], Some([0xA4, 0x00, 0x20, 0x00, 0x03, 0, 0, 0]));
    t.ex([0x01, 1, 2, 3, 4, 5, 6, 7], None);
    t.ex([0x02, 1, 2, 3, 4, 5, 6, 7], abort_of(0x2000, 0, AbortCode::LengthTooHigh));
    t.ex([0xC2, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0xA0, 0x00, 0x20, 0x00, 0x03, 0, 0, 0]));
    t.ex([0x81, 1, 2, 3, 4, 5, 6, 7], Some([0xA2, 0x01, 0x03, 0, 0, 0, 0, 0]));
    t.ex([0xC1, 0, 0, 0, 0, 0, 0, 0], abort_of(0x2000, 0, AbortCode::LengthTooLow));
    // a block end frame while idle, an upload segment request while downloading → 0504 0001h
    t.ex([0xC1, 0, 0, 0, 0, 0, 0, 0], abort_of(0, 0, AbortCode::InvalidCommandSpecifier));
    t.ex([0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
    t.ex([0x60, 0, 0, 0, 0, 0, 0, 0], abort_of(0x2000, 0, AbortCode::InvalidCommandSpecifier));
}

#[test]
#[cfg(feature = "sdo-block")]
fn block_upload_of_9_bytes() {
    let mut t = Bench::new();
    t.od.set_domain(b"123456789");
    t.ex([0xA4, 0x00, 0x20, 0x00, 0x7F, 0x00, 0, 0], Some([0xC6, 0x00, 0x20, 0x00, 0x09, 0, 0, 0]));
    assert!(!t.s.wants_transmit());
    t.ex([0xA3, 0, 0, 0, 0, 0, 0, 0], None);
    assert!(t.s.wants_transmit());
    assert_eq!(t.s.poll_transmit(T0, &mut t.od).unwrap().frame, Some([0x01, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37]));
    assert_eq!(t.s.poll_transmit(T0, &mut t.od).unwrap().frame, Some([0x82, 0x38, 0x39, 0, 0, 0, 0, 0]));
    assert!(t.s.poll_transmit(T0, &mut t.od).is_none());
    t.ex([0xA2, 0x02, 0x7F, 0, 0, 0, 0, 0], Some([0xD5, 0xC3, 0x31, 0, 0, 0, 0, 0]));
    let r = t.ex([0xA1, 0, 0, 0, 0, 0, 0, 0], None);
    assert_eq!(r.event, Some(SdoEvent::Uploaded { index: 0x2000, sub: 0 }));
    assert!(t.s.is_idle());
    // INTEROP: cc = 0 → sc = 0 and CRC 0
    t.ex([0xA0, 0x00, 0x20, 0x00, 0x7F, 0x00, 0, 0], Some([0xC2, 0x00, 0x20, 0x00, 0x09, 0, 0, 0]));
    t.ex([0xA3, 0, 0, 0, 0, 0, 0, 0], None);
    while t.s.poll_transmit(T0, &mut t.od).is_some() {}
    t.ex([0xA2, 0x02, 0x7F, 0, 0, 0, 0, 0], Some([0xD5, 0, 0, 0, 0, 0, 0, 0]));
    t.ex([0xA1, 0, 0, 0, 0, 0, 0, 0], None);
}

#[test]
#[cfg(feature = "sdo-block")]
fn block_upload_retransmission_and_errors() {
    let mut t = Bench::new();
    t.od.set_domain(b"ABCDEFGHIJKLMNOP");
    t.ex([0xA4, 0x00, 0x20, 0x00, 0x02, 0x00, 0, 0], Some([0xC6, 0x00, 0x20, 0x00, 0x10, 0, 0, 0]));
    t.ex([0xA3, 0, 0, 0, 0, 0, 0, 0], None);
    assert_eq!(t.s.poll_transmit(T0, &mut t.od).unwrap().frame.unwrap()[0], 0x01);
    assert_eq!(t.s.poll_transmit(T0, &mut t.od).unwrap().frame.unwrap()[0], 0x02);
    assert!(t.s.poll_transmit(T0, &mut t.od).is_none());
    // client got only seq 1: go back to "HIJKLMN" as seqno 1, new blksize 3
    t.ex([0xA2, 0x01, 0x03, 0, 0, 0, 0, 0], None);
    assert_eq!(t.s.poll_transmit(T0, &mut t.od).unwrap().frame, Some([0x01, 0x48, 0x49, 0x4A, 0x4B, 0x4C, 0x4D, 0x4E]));
    assert_eq!(t.s.poll_transmit(T0, &mut t.od).unwrap().frame, Some([0x82, 0x4F, 0x50, 0, 0, 0, 0, 0]));
    assert!(t.s.poll_transmit(T0, &mut t.od).is_none());
    t.ex([0xA2, 0x02, 0x03, 0, 0, 0, 0, 0], Some([0xD5, 0x80, 0x60, 0, 0, 0, 0, 0]));
    t.ex([0xA1, 0, 0, 0, 0, 0, 0, 0], None);
    // invalid blksize at initiate and in the ack; ackseq beyond what was sent
    t.ex([0xA4, 0x00, 0x20, 0x00, 0x00, 0x00, 0, 0], abort_of(0x2000, 0, AbortCode::InvalidBlockSize));
    t.ex([0xA4, 0x00, 0x20, 0x00, 0x80, 0x00, 0, 0], abort_of(0x2000, 0, AbortCode::InvalidBlockSize));
    t.ex([0xA4, 0x00, 0x20, 0x00, 0x02, 0x00, 0, 0], Some([0xC6, 0x00, 0x20, 0x00, 0x10, 0, 0, 0]));
    t.ex([0xA3, 0, 0, 0, 0, 0, 0, 0], None);
    while t.s.poll_transmit(T0, &mut t.od).is_some() {}
    t.ex([0xA2, 0x02, 0x00, 0, 0, 0, 0, 0], abort_of(0x2000, 0, AbortCode::InvalidBlockSize));
    t.ex([0xA4, 0x00, 0x20, 0x00, 0x02, 0x00, 0, 0], Some([0xC6, 0x00, 0x20, 0x00, 0x10, 0, 0, 0]));
    t.ex([0xA3, 0, 0, 0, 0, 0, 0, 0], None);
    while t.s.poll_transmit(T0, &mut t.od).is_some() {}
    t.ex([0xA2, 0x03, 0x02, 0, 0, 0, 0, 0], abort_of(0x2000, 0, AbortCode::InvalidSequenceNumber));
    // read error during a sub-block
    t.ex([0xA4, 0x06, 0x20, 0x00, 0x7F, 0x00, 0, 0], Some([0xC6, 0x06, 0x20, 0x00, 200, 0, 0, 0]));
    t.ex([0xA3, 0, 0, 0, 0, 0, 0, 0], None);
    assert!(t.s.poll_transmit(T0, &mut t.od).unwrap().event.is_none());
    assert!(t.s.poll_transmit(T0, &mut t.od).unwrap().event.is_none());
    let r = t.s.poll_transmit(T0, &mut t.od).unwrap();
    assert_eq!(r.frame, abort_of(0x2006, 0, AbortCode::HardwareError));
    assert!(t.s.is_idle());
}

#[test]
#[cfg(feature = "sdo-block")]
fn block_upload_protocol_switch_to_segmented() {
    let mut t = Bench::new();
    t.od.set_domain(b"123456789");
    t.ex([0xA4, 0x00, 0x20, 0x00, 0x7F, 0x15, 0, 0], Some([0x41, 0x00, 0x20, 0x00, 0x09, 0, 0, 0]));
    t.ex([0x60, 0, 0, 0, 0, 0, 0, 0], Some([0x00, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37]));
    t.ex([0x70, 0, 0, 0, 0, 0, 0, 0], Some([0x1B, 0x38, 0x39, 0, 0, 0, 0, 0]));
    t.ex([0xA4, 0x17, 0x10, 0x00, 0x7F, 0x15, 0, 0], Some([0x4B, 0x17, 0x10, 0x00, 0x64, 0, 0, 0]));
    assert!(t.s.is_idle());
}

#[test]
fn abort_handling_and_ignored_frames() {
    let mut t = Bench::new();
    // abort while idle: silence (SDO-33)
    t.ex([0x80, 0, 0x20, 0, 0, 0, 0x04, 0x05], None);
    // abort during a segmented download: silence, OD told, idle
    t.ex([0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
    let r = t.ex([0x80, 0x00, 0x20, 0x00, 0x00, 0x00, 0x04, 0x05], None);
    assert_eq!(r.event, Some(SdoEvent::AbortReceived { index: 0x2000, sub: 0, code: 0x0504_0000 }));
    assert_eq!(t.od.aborted_writes, 1);
    assert!(t.s.is_idle() && t.s.poll_timeout().is_none());
    // DLC < 8 (CAN-07 choice: ignored), also mid-transfer; the transfer goes on
    for n in 0..8 {
        assert_eq!(t.s.handle_request(T0, &[0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0][..n], &mut t.od), Response::NONE);
    }
    t.ex([0x40, 0x09, 0x10, 0x00, 0, 0, 0, 0], Some([0x41, 0x09, 0x10, 0x00, 0x17, 0, 0, 0]));
    assert_eq!(t.s.handle_request(T0, &[0x60], &mut t.od), Response::NONE);
    assert_eq!(t.s.state(), ServerState::Uploading);
    // unknown ccs mid-transfer: abort with the transfer's multiplexer
    t.ex([0xE0, 0, 0, 0, 0, 0, 0, 0], abort_of(0x1009, 0, AbortCode::InvalidCommandSpecifier));
    // a download segment while idle
    t.ex([0x00, 1, 2, 3, 4, 5, 6, 7], abort_of(0, 0, AbortCode::InvalidCommandSpecifier));
    // block upload start / ack / end while idle
    for b0 in [0xA3u8, 0xA2, 0xA1] {
        t.ex([b0, 1, 1, 0, 0, 0, 0, 0], abort_of(0, 0, AbortCode::InvalidCommandSpecifier));
    }
}

#[test]
fn servers_table() {
    let node = NodeId::new(0x7F).unwrap();
    let servers = SdoServers::<4>::new(node);
    assert_eq!(servers.len(), 4);
    assert_eq!(servers.find(0x67F), Some(0));
    assert_eq!(servers.iter().filter(|s| s.rx_cob_id().is_some()).count(), 1);
    let p = SdoServerParams {
        cob_rx: CobIdEntry::from_raw(0x2000_0600),
        cob_tx: CobIdEntry::from_raw(0x580),
        client_node: None,
    };
    assert!(!p.is_valid(), "29-bit frames are not supported");
}

/// Issue 21 item 2 (server side), SDO-40 go-back-n on simulated time: a sub-block whose last segment is lost
/// stalls; after a quarter of the SDO timeout the server acknowledges the in-order segments it has, the client
/// resends the rest, and the SDO timeout still counts from the last frame received.
#[test]
#[cfg(feature = "sdo-block")]
fn stalled_sub_block_is_acknowledged_after_a_quarter_of_the_timeout() {
    let mut s = server().with_block_size(4).with_timeout(Duration::from_millis(100));
    let mut od = TestOd::new();
    let t = |ms| Instant::from_millis(ms);
    assert!(s.handle_request(t(0), &[0xC6, 0x00, 0x20, 0x00, 0x10, 0, 0, 0], &mut od).frame.is_some());
    // waiting for the first segment: the SDO timeout, no early acknowledge (nothing to acknowledge yet)
    assert_eq!(s.poll_timeout(), Some(t(100)));
    s.handle_request(t(1), &[0x01, 0x41, 0x42, 0x43, 0x44, 0x45, 0x46, 0x47], &mut od);
    s.handle_request(t(2), &[0x02, 0x48, 0x49, 0x4A, 0x4B, 0x4C, 0x4D, 0x4E], &mut od);
    // segment 3 (the last, 83h) is lost
    assert_eq!(s.poll_timeout(), Some(t(27)));
    assert_eq!(s.handle_timeout(t(26), &mut od), Response::NONE);
    let r = s.handle_timeout(t(27), &mut od);
    assert_eq!(r.frame, Some([0xA2, 0x02, 0x04, 0, 0, 0, 0, 0]), "ackseq 2, blksize 4");
    assert_eq!(r.event, None);
    assert_eq!(s.state(), ServerState::BlockDownloadSubBlock);
    // one acknowledge per stall: then the SDO timeout from the last frame received (2 ms)
    assert_eq!(s.poll_timeout(), Some(t(102)));
    // the client resends "OP" as segment 1 of the next sub-block, last
    let r = s.handle_request(t(30), &[0x81, 0x4F, 0x50, 0, 0, 0, 0, 0], &mut od);
    assert_eq!(r.frame, Some([0xA2, 0x01, 0x04, 0, 0, 0, 0, 0]));
    // waiting for the end frame (SDO-41): no early acknowledge, the SDO timeout from that segment
    assert_eq!(s.state(), ServerState::BlockDownloadEnd);
    assert_eq!(s.poll_timeout(), Some(t(130)));
    assert_eq!(s.handle_timeout(t(129), &mut od), Response::NONE);
    let r = s.handle_request(t(31), &[0xD5, 0x80, 0x60, 0, 0, 0, 0, 0], &mut od);
    assert_eq!(r.frame, Some([0xA1, 0, 0, 0, 0, 0, 0, 0]));
    assert_eq!(od.domain(), b"ABCDEFGHIJKLMNOP");
    // a stall with no in-order segment of the sub-block ends by the SDO timeout (0504 0000h)
    s.handle_request(t(200), &[0xC6, 0x00, 0x20, 0x00, 0x10, 0, 0, 0], &mut od);
    s.handle_request(t(201), &[0x02, 0x48, 0x49, 0x4A, 0x4B, 0x4C, 0x4D, 0x4E], &mut od);
    assert_eq!(s.poll_timeout(), Some(t(301)));
    assert_eq!(s.handle_timeout(t(301), &mut od).frame, abort_of(0x2000, 0, AbortCode::SdoTimeout));
}

/// A dictionary that says it takes no streamed write (`STREAMS = false`) but whose `begin_write` succeeds:
/// the server, which builds no stream path for it, refuses the download with 0601 0000h and undoes the
/// begun write, for a segmented and (feature `sdo-block`) a block download.
struct NoStreams {
    begun: u32,
    aborted: u32,
}

impl ObjectDictionary for NoStreams {
    const STREAMS: bool = false;
    fn info(&self, _: u16, _: u8) -> Result<crate::od::SubInfo, AbortCode> {
        let (data_type, access) = (crate::od::DataType::Domain, crate::od::Access::Rw);
        Ok(crate::od::SubInfo { data_type, access, pdo: crate::od::PdoMapping::No, size: 0 })
    }
    fn read(&self, _: u16, _: u8, _: usize, _: &mut [u8]) -> Result<usize, AbortCode> {
        Ok(0)
    }
    fn write(&mut self, _: u16, _: u8, _: &[u8]) -> Result<(), AbortCode> {
        Ok(())
    }
    fn begin_write(&mut self, _: u16, _: u8, _: Option<usize>) -> Result<(), AbortCode> {
        self.begun += 1;
        Ok(())
    }
    fn abort_write(&mut self, _: u16, _: u8) {
        self.aborted += 1;
    }
}

#[test]
fn no_stream_for_a_dictionary_without_streams() {
    let mut od = NoStreams { begun: 0, aborted: 0 };
    let mut s = server();
    // Segmented download initiate of 3000h:00, 3 bytes indicated.
    let r = s.handle_request(T0, &[0x21, 0x00, 0x30, 0x00, 3, 0, 0, 0], &mut od);
    assert_eq!(r.frame, abort_of(0x3000, 0, AbortCode::UnsupportedAccess));
    assert_eq!((od.begun, od.aborted), (1, 1));
    assert!(s.is_idle());
    #[cfg(feature = "sdo-block")]
    {
        // Block download initiate, size indicated (cs = 6, s = 1).
        let r = s.handle_request(T0, &[0xC2, 0x00, 0x30, 0x00, 3, 0, 0, 0], &mut od);
        assert_eq!(r.frame, abort_of(0x3000, 0, AbortCode::UnsupportedAccess));
        assert_eq!((od.begun, od.aborted), (2, 2));
        assert!(s.is_idle());
    }
}

/// SDO-33, SDO-02: an abort frame with reserved bits set (ccs 4, 81h–9Fh) ends the transfer under way
/// without an answer and names the transfer's object, not the frame's bytes 1–3; while idle it is ignored.
#[test]
fn abort_with_reserved_bits_names_the_transfer() {
    let mut t = Bench::new();
    let r = t.ex([0x84, 0x34, 0x12, 0x05, 0x00, 0x00, 0x04, 0x05], None);
    assert_eq!(r.event, None);
    t.ex([0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
    let r = t.ex([0x84, 0x34, 0x12, 0x05, 0x00, 0x00, 0x04, 0x05], None);
    assert_eq!(r.event, Some(SdoEvent::AbortReceived { index: 0x2000, sub: 0, code: 0x0504_0000 }));
    assert_eq!(t.od.aborted_writes, 1);
    assert!(t.s.is_idle());
}

/// SDO-35, SDO-18: a block download initiate is checked as a segmented one before anything is answered: an
/// entry that does not exist (0602 0000h), a read-only one (0601 0002h), and for a fixed-size entry an
/// announced size above (0607 0012h) or below (0607 0013h) its own; without a size it is taken.
#[test]
#[cfg(feature = "sdo-block")]
fn block_download_initiate_refusals() {
    let mut t = Bench::new();
    t.ex([0xC6, 0x00, 0x50, 0x00, 4, 0, 0, 0], abort_of(0x5000, 0, AbortCode::ObjectDoesNotExist));
    t.ex([0xC6, 0x00, 0x10, 0x00, 4, 0, 0, 0], abort_of(0x1000, 0, AbortCode::WriteOfReadOnly));
    t.ex([0xC6, 0x7A, 0x60, 0x00, 5, 0, 0, 0], abort_of(0x607A, 0, AbortCode::LengthTooHigh));
    t.ex([0xC6, 0x7A, 0x60, 0x00, 3, 0, 0, 0], abort_of(0x607A, 0, AbortCode::LengthTooLow));
    assert!(t.s.is_idle());
    t.ex([0xC4, 0x7A, 0x60, 0x00, 0, 0, 0, 0], Some([0xA4, 0x7A, 0x60, 0x00, 0x7F, 0, 0, 0]));
    assert_eq!(t.s.state(), ServerState::BlockDownloadSubBlock);
}

/// SDO-31 with the time-out disabled (zero): no deadline in the block states that otherwise have an early
/// one, a download sub-block with in-order segments (the stall acknowledge, SDO-40) and an upload sub-block
/// handed out (due at once), and the time-out's own.
#[test]
#[cfg(feature = "sdo-block")]
fn zero_timeout_gives_no_deadline_in_block_transfers() {
    let mut t = Bench { s: server().with_timeout(Duration::ZERO).with_block_size(4), od: TestOd::new() };
    t.ex([0xC6, 0x00, 0x20, 0x00, 0x10, 0, 0, 0], Some([0xA4, 0x00, 0x20, 0x00, 0x04, 0, 0, 0]));
    t.ex([0x01, 0x41, 0x42, 0x43, 0x44, 0x45, 0x46, 0x47], None);
    assert_eq!(t.s.poll_timeout(), None);
    assert_eq!(t.s.handle_timeout(Instant::from_micros(u64::MAX - 1), &mut t.od), Response::NONE);
    assert_eq!(t.s.state(), ServerState::BlockDownloadSubBlock);
    t.s.cancel(&mut t.od);
    t.od.set_domain(b"123456789");
    t.ex([0xA4, 0x00, 0x20, 0x00, 0x7F, 0x00, 0, 0], Some([0xC6, 0x00, 0x20, 0x00, 0x09, 0, 0, 0]));
    t.ex([0xA3, 0, 0, 0, 0, 0, 0, 0], None);
    while t.s.poll_transmit(T0, &mut t.od).is_some() {}
    assert_eq!(t.s.state(), ServerState::BlockUploadAck);
    assert_eq!(t.s.poll_timeout(), None);
    assert_eq!(t.s.handle_timeout(Instant::from_micros(u64::MAX - 1), &mut t.od), Response::NONE);
    // with a time-out, the same sub-block handed out is due at once (the time-out then starts)
    t.s.set_timeout(Duration::from_millis(10));
    t.ex([0xA2, 0x00, 0x7F, 0, 0, 0, 0, 0], None); // go back to the start: the sub-block again
    while t.s.poll_transmit(Instant::from_millis(3), &mut t.od).is_some() {}
    assert_eq!(t.s.poll_timeout(), Some(Instant::from_millis(3)));
}

/// The unused bytes of the last segment (the end frame's n) and the CRC of a block upload of every size from
/// 0 to 16 bytes, with and without CRC, in sub-blocks whose size the client changes after each
/// acknowledge (2, then 3, then 1, ...): n = 7 × segments − size, 7 for an empty data set, which is one
/// segment (SDO-37, SDO-40, SDO-46, SDO-47, SDO-48, SDO-49, SDO-51).
#[test]
#[cfg(feature = "sdo-block")]
fn block_upload_end_frame_n_and_crc_for_every_size() {
    let data: [u8; 16] = core::array::from_fn(|i| 0x30 + i as u8);
    for crc_on in [false, true] {
        for size in 0..=16usize {
            let mut t = Bench::new();
            t.od.set_domain(&data[..size]);
            let cc = u8::from(crc_on) << 2;
            t.ex(
                [0xA0 | cc, 0x00, 0x20, 0x00, 0x02, 0x00, 0, 0],
                Some([0xC2 | cc, 0x00, 0x20, 0x00, size as u8, 0, 0, 0]),
            );
            t.ex([0xA3, 0, 0, 0, 0, 0, 0, 0], None);
            let mut got = std::vec::Vec::new();
            let mut blksizes = [3u8, 1, 2].into_iter().cycle();
            let end = loop {
                let mut sent = 0u8;
                let mut last = false;
                while let Some(r) = t.s.poll_transmit(T0, &mut t.od) {
                    let f = r.frame.unwrap();
                    sent += 1;
                    assert_eq!(f[0] & 0x7F, sent, "size {size}: seqno");
                    assert!(!last, "size {size}: a segment after c = 1");
                    last = f[0] & 0x80 != 0;
                    got.extend_from_slice(&f[1..]);
                }
                assert!(sent >= 1, "size {size}: an empty sub-block (SDO-51)");
                let r = t.s.handle_request(T0, &[0xA2, sent, blksizes.next().unwrap(), 0, 0, 0, 0, 0], &mut t.od);
                if last {
                    break r.frame.unwrap();
                }
                assert_eq!(r.frame, None, "size {size}");
            };
            let segments = size.div_ceil(7).max(1);
            let n = 7 * segments - size;
            let mut crc = Crc16::new();
            if crc_on {
                crc.update(&data[..size]);
            }
            let [c0, c1] = crc.get().to_le_bytes();
            assert_eq!(end, [0xC1 | ((n as u8) << 2), c0, c1, 0, 0, 0, 0, 0], "size {size}, crc {crc_on}");
            assert_eq!(&got[..size], &data[..size], "size {size}");
            assert_eq!(got.len(), 7 * segments, "size {size}");
            let r = t.ex([0xA1, 0, 0, 0, 0, 0, 0, 0], None);
            assert_eq!(r.event, Some(SdoEvent::Uploaded { index: 0x2000, sub: 0 }));
        }
    }
}

/// Block download of 0, 7 and 14 bytes: the end frame's n covers a last segment with no data at all (an
/// empty data set is one segment, n = 7) or with all 7 bytes (n = 0), with and without CRC (SDO-37, SDO-41,
/// SDO-48, SDO-49, SDO-51).
#[test]
#[cfg(feature = "sdo-block")]
fn block_download_last_segment_n_edges() {
    let data: [u8; 14] = core::array::from_fn(|i| 0x61 + i as u8);
    for crc_on in [false, true] {
        for size in [0usize, 7, 14] {
            let mut t = Bench::with_block_size(4);
            t.od.set_domain(b"old");
            let cc = u8::from(crc_on) << 2;
            t.ex([0xC2 | cc, 0x00, 0x20, 0x00, size as u8, 0, 0, 0], Some([0xA0 | cc, 0x00, 0x20, 0x00, 4, 0, 0, 0]));
            let segments = size.div_ceil(7).max(1);
            for i in 0..segments {
                let mut seg = [0xEEu8; 8];
                seg[0] = (i as u8 + 1) | if i + 1 == segments { 0x80 } else { 0 };
                let part = &data[(7 * i).min(size)..(7 * i + 7).min(size)];
                seg[1..1 + part.len()].copy_from_slice(part);
                let want = (i + 1 == segments).then_some([0xA2, segments as u8, 4, 0, 0, 0, 0, 0]);
                t.ex(seg, want);
            }
            let n = (7 * segments - size) as u8;
            let mut crc = Crc16::new();
            crc.update(&data[..size]);
            let [c0, c1] = if crc_on { crc.get().to_le_bytes() } else { [0x5A, 0xA5] };
            let r = t.ex([0xC1 | (n << 2), c0, c1, 0, 0, 0, 0, 0], Some([0xA1, 0, 0, 0, 0, 0, 0, 0]));
            assert_eq!(r.event, Some(SdoEvent::Written { index: 0x2000, sub: 0 }));
            assert_eq!(t.od.domain(), &data[..size], "size {size}, crc {crc_on}");
        }
    }
}

/// An abort from the client in the middle of an upload sub-block (SDO-33, SDO-46): not answered, the rest of
/// the sub-block is not sent, the server is idle and has no deadline.
#[test]
#[cfg(feature = "sdo-block")]
fn client_abort_in_the_middle_of_an_upload_sub_block() {
    let mut t = Bench::new();
    t.od.set_domain(b"ABCDEFGHIJKLMNOPQRSTU");
    t.ex([0xA4, 0x00, 0x20, 0x00, 0x7F, 0x00, 0, 0], Some([0xC6, 0x00, 0x20, 0x00, 21, 0, 0, 0]));
    t.ex([0xA3, 0, 0, 0, 0, 0, 0, 0], None);
    assert_eq!(t.s.poll_transmit(T0, &mut t.od).unwrap().frame.unwrap()[0], 0x01);
    let r = t.ex([0x80, 0x00, 0x20, 0x00, 0x00, 0x00, 0x04, 0x05], None);
    assert_eq!(r.event, Some(SdoEvent::AbortReceived { index: 0x2000, sub: 0, code: 0x0504_0000 }));
    assert!(t.s.is_idle() && !t.s.wants_transmit() && t.s.poll_timeout().is_none());
    assert!(t.s.poll_transmit(T0, &mut t.od).is_none());
}

/// SDO-09 in a block upload: start (A3h) is valid only before the first sub-block, an acknowledge (A2h) only
/// once a sub-block is going out or was sent, the end response (A1h) only after the end frame; any other of
/// the three is 0504 0001h for the transfer's object, and the server is idle after it.
#[test]
#[cfg(feature = "sdo-block")]
fn block_upload_requests_out_of_phase() {
    // (requests to reach the phase, then the requests that are out of place there)
    let to_start: &[[u8; 8]] = &[];
    let to_sending: &[[u8; 8]] = &[[0xA3, 0, 0, 0, 0, 0, 0, 0]];
    type Case<'a> = (&'a [[u8; 8]], bool, &'a [u8]);
    let cases: [Case; 4] = [
        (to_start, false, &[0xA2, 0xA1]),
        (to_sending, false, &[0xA3, 0xA1]),
        (to_sending, true, &[0xA3, 0xA1]), // the sub-block handed out (Sent), and its time-out started
        (&[[0xA3, 0, 0, 0, 0, 0, 0, 0], [0xA2, 0x02, 0x7F, 0, 0, 0, 0, 0]], false, &[0xA3, 0xA2]),
    ];
    for (to_phase, drain, bad) in cases {
        for &b0 in bad {
            let mut t = Bench::new();
            t.od.set_domain(b"123456789");
            t.ex([0xA4, 0x00, 0x20, 0x00, 0x7F, 0x00, 0, 0], Some([0xC6, 0x00, 0x20, 0x00, 0x09, 0, 0, 0]));
            for &req in to_phase {
                if req[0] == 0xA2 {
                    while t.s.poll_transmit(T0, &mut t.od).is_some() {}
                }
                t.s.handle_request(T0, &req, &mut t.od);
            }
            if drain {
                while t.s.poll_transmit(T0, &mut t.od).is_some() {}
                assert_eq!(t.s.handle_timeout(T0, &mut t.od), Response::NONE);
                assert_eq!(t.s.state(), ServerState::BlockUploadAck);
            }
            let r = t.ex([b0, 0x01, 0x7F, 0, 0, 0, 0, 0], abort_of(0x2000, 0, AbortCode::InvalidCommandSpecifier));
            assert!(matches!(r.event, Some(SdoEvent::Aborted { .. })), "{b0:02X}");
            assert!(t.s.is_idle(), "{b0:02X}");
        }
    }
}
