//! Unit tests of the SDO frame formats: every command specifier both ways (SDO-08), and the frames of the
//! expedited, segmented and block exchanges byte for byte.

use super::*;
use ClientRequest as Req;
use ServerResponse as Rsp;

/// Bytes past `len` are never sent, whatever the segment holds there.
#[test]
fn segment_emit_sends_len_bytes_only() {
    for len in 0..=7u8 {
        let seg = Segment { toggle: true, last: false, len, data: [1, 2, 3, 4, 5, 6, 7] };
        let b = seg.emit();
        let mut want = [0u8; 8];
        want[0] = 0x10 | ((7 - len) << 1);
        want[1..1 + usize::from(len)].copy_from_slice(&seg.data[..usize::from(len)]);
        assert_eq!(b, want, "len {len}");
    }
    let e = Expedited { data: [9, 8, 7, 6], len: 2, size_indicated: true };
    let b = Rsp::InitiateUpload { mux: Multiplexer::new(0x1000, 0), data: InitiateData::Expedited(e) }.emit();
    assert_eq!(b[4..], [9, 8, 0, 0]);
}

fn req(b: [u8; 8]) -> ClientRequest {
    Req::parse(&b).unwrap()
}

fn rsp(b: [u8; 8]) -> ServerResponse {
    ServerResponse::parse(&b).unwrap()
}

fn mux(index: u16, sub: u8) -> Multiplexer {
    Multiplexer::new(index, sub)
}

fn exp(bytes: &[u8]) -> InitiateData {
    InitiateData::Expedited(Expedited::new(bytes).unwrap())
}

/// Requests that must round-trip byte-exactly (the vectors' client frames with reserved bytes 0).
fn check_req(b: [u8; 8], want: ClientRequest) {
    assert_eq!(req(b), want, "{b:02X?}");
    assert_eq!(want.emit(), b, "{want:?}");
}

fn check_rsp(b: [u8; 8], want: ServerResponse) {
    assert_eq!(rsp(b), want, "{b:02X?}");
    assert_eq!(want.emit(), b, "{want:?}");
}

#[test]
fn expedited_frames_round_trip() {
    // Write 607Ah:00 (INTEGER32) = 0000 03E8h and its confirmation
    check_req(
        [0x23, 0x7A, 0x60, 0x00, 0xE8, 0x03, 0x00, 0x00],
        Req::InitiateDownload { mux: mux(0x607A, 0), data: exp(&[0xE8, 0x03, 0, 0]) },
    );
    check_rsp([0x60, 0x7A, 0x60, 0x00, 0, 0, 0, 0], Rsp::InitiateDownload { mux: mux(0x607A, 0) });
    // Read 6041h:00 -> 2 bytes 0240h
    check_req([0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0], Req::InitiateUpload { mux: mux(0x6041, 0) });
    check_rsp([0x4B, 0x41, 0x60, 0x00, 0x40, 0x02, 0, 0], Rsp::expedited_upload(mux(0x6041, 0), &[0x40, 2]));
    // 1400h:02 = FDh (reserved for RPDOs) and its conformant abort answer 0609 0030h
    check_req(
        [0x2F, 0x00, 0x14, 0x02, 0xFD, 0, 0, 0],
        Req::InitiateDownload { mux: mux(0x1400, 2), data: exp(&[0xFD]) },
    );
    check_rsp([0x80, 0x00, 0x14, 0x02, 0x30, 0x00, 0x09, 0x06], Rsp::Abort { mux: mux(0x1400, 2), code: 0x0609_0030 });
    // Write 1603h:01 = 6012 0208h (map 6012h:02, 8 bits)
    check_req(
        [0x23, 0x03, 0x16, 0x01, 0x08, 0x02, 0x12, 0x60],
        Req::InitiateDownload { mux: mux(0x1603, 1), data: exp(&[0x08, 0x02, 0x12, 0x60]) },
    );
    check_rsp([0x60, 0x03, 0x16, 0x01, 0, 0, 0, 0], Rsp::InitiateDownload { mux: mux(0x1603, 1) });
    // Read 1400h:02 -> 1 byte FDh; read 1603h:01 -> 4 bytes 6012 0208h
    check_rsp([0x4F, 0x00, 0x14, 0x02, 0xFD, 0, 0, 0], Rsp::expedited_upload(mux(0x1400, 2), &[0xFD]));
    check_rsp(
        [0x43, 0x03, 0x16, 0x01, 0x08, 0x02, 0x12, 0x60],
        Rsp::expedited_upload(mux(0x1603, 1), &[0x08, 0x02, 0x12, 0x60]),
    );
    // Read 1018h:01 -> vendor-ID 2B6h; read 1018h:00 -> 4
    check_rsp([0x43, 0x18, 0x10, 0x01, 0xB6, 0x02, 0, 0], Rsp::expedited_upload(mux(0x1018, 1), &[0xB6, 2, 0, 0]));
    check_rsp([0x4F, 0x18, 0x10, 0x00, 0x04, 0, 0, 0], Rsp::expedited_upload(mux(0x1018, 0), &[4]));
    // Abort frames: 5000h absent, 1018h:07 absent, ro 1000h, too short, too long, ccs 7, invalid 1014h
    for (b, m, code) in [
        ([0x80, 0x00, 0x50, 0x00, 0x00, 0x00, 0x02, 0x06], mux(0x5000, 0), 0x0602_0000),
        ([0x80, 0x18, 0x10, 0x07, 0x11, 0x00, 0x09, 0x06], mux(0x1018, 7), 0x0609_0011),
        ([0x80, 0x00, 0x10, 0x00, 0x02, 0x00, 0x01, 0x06], mux(0x1000, 0), 0x0601_0002),
        ([0x80, 0x17, 0x10, 0x00, 0x13, 0x00, 0x07, 0x06], mux(0x1017, 0), 0x0607_0013),
        ([0x80, 0x0D, 0x10, 0x00, 0x12, 0x00, 0x07, 0x06], mux(0x100D, 0), 0x0607_0012),
        ([0x80, 0x00, 0x10, 0x00, 0x01, 0x00, 0x04, 0x05], mux(0x1000, 0), 0x0504_0001),
        ([0x80, 0x14, 0x10, 0x00, 0x30, 0x00, 0x09, 0x06], mux(0x1014, 0), 0x0609_0030),
    ] {
        check_rsp(b, Rsp::Abort { mux: m, code });
        check_req(b, Req::Abort { mux: m, code });
    }
    // ccs 7 (E0h) is not a command
    assert_eq!(Req::parse(&[0xE0, 0x00, 0x10, 0, 0, 0, 0, 0]), Err(ParseError::CommandSpecifier));
    assert_eq!(ServerResponse::parse(&[0xE0, 0x00, 0x10, 0, 0, 0, 0, 0]), Err(ParseError::CommandSpecifier));
}

#[test]
fn expedited_command_bytes_sdo_12_24() {
    for (len, dl, ul) in [(1usize, 0x2F, 0x4F), (2, 0x2B, 0x4B), (3, 0x27, 0x47), (4, 0x23, 0x43)] {
        let data = &[1, 2, 3, 4][..len];
        let d = Req::InitiateDownload { mux: mux(1, 2), data: exp(data) }.emit();
        assert_eq!(d[0], dl);
        let u = Rsp::InitiateUpload { mux: mux(1, 2), data: exp(data) }.emit();
        assert_eq!(u[0], ul);
        match req(d) {
            Req::InitiateDownload { data: InitiateData::Expedited(e), .. } => assert_eq!(e.bytes(), data),
            other => panic!("{other:?}"),
        }
    }
    // SDO-13: 22h expedited without size → 4 bytes, size not indicated
    let r = req([0x22, 0x00, 0x20, 0x00, 1, 2, 3, 4]);
    let e = Expedited { data: [1, 2, 3, 4], len: 4, size_indicated: false };
    assert_eq!(r, Req::InitiateDownload { mux: mux(0x2000, 0), data: InitiateData::Expedited(e) });
    assert_eq!(r.emit()[0], 0x22);
    // 42h expedited upload without size
    assert_eq!(
        rsp([0x42, 0, 0x20, 0, 1, 2, 3, 4]),
        Rsp::InitiateUpload { mux: mux(0x2000, 0), data: InitiateData::Expedited(e) }
    );
    // SDO-16: n is ignored unless e = 1 and s = 1
    assert_eq!(
        req([0x2C, 0, 0x20, 0, 0, 0, 0, 0]),
        Req::InitiateDownload { mux: mux(0x2000, 0), data: InitiateData::Segmented { size: None } }
    );
}

#[test]
fn segmented_upload_frames_of_1009h() {
    let m = mux(0x1009, 0);
    check_req([0x40, 0x09, 0x10, 0x00, 0, 0, 0, 0], Req::InitiateUpload { mux: m });
    check_rsp(
        [0x41, 0x09, 0x10, 0x00, 0x17, 0, 0, 0],
        Rsp::InitiateUpload { mux: m, data: InitiateData::Segmented { size: Some(23) } },
    );
    check_req([0x60, 0, 0, 0, 0, 0, 0, 0], Req::UploadSegment { toggle: false });
    check_req([0x70, 0, 0, 0, 0, 0, 0, 0], Req::UploadSegment { toggle: true });
    // 002's client sends the multiplexer in the reserved bytes: still an upload segment request (SDO-02)
    assert_eq!(req([0x60, 0x09, 0x10, 0x00, 0, 0, 0, 0]), Req::UploadSegment { toggle: false });
    let segs: [([u8; 8], bool, bool, &[u8]); 4] = [
        ([0x00, 0x4E, 0x31, 0x30, 0x20, 0x2D, 0x20, 0x57], false, false, b"N10 - W"),
        ([0x10, 0x54, 0x31, 0x32, 0x30, 0x39, 0x2D, 0x56], true, false, b"T1209-V"),
        ([0x00, 0x31, 0x2E, 0x30, 0x30, 0x2D, 0x38, 0x4D], false, false, b"1.00-8M"),
        ([0x1B, 0x42, 0x00, 0, 0, 0, 0, 0], true, true, b"B\0"),
    ];
    for (b, t, c, data) in segs {
        check_rsp(b, Rsp::UploadSegment(Segment::new(t, c, data)));
    }
    // 7.1 seed step 10 as printed: 0Bh = t 0, n 5, c 1
    assert_eq!(rsp([0x0B, 0x42, 0, 0, 0, 0, 0, 0]), Rsp::UploadSegment(Segment::new(false, true, b"B\0")));
}

#[test]
fn segmented_download_frames_of_9_bytes() {
    let m = mux(0x2000, 0);
    check_req(
        [0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0],
        Req::InitiateDownload { mux: m, data: InitiateData::Segmented { size: Some(9) } },
    );
    check_req(
        [0x20, 0x00, 0x20, 0x00, 0, 0, 0, 0],
        Req::InitiateDownload { mux: m, data: InitiateData::Segmented { size: None } },
    );
    check_rsp([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0], Rsp::InitiateDownload { mux: m });
    check_req(
        [0x00, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37],
        Req::DownloadSegment(Segment::new(false, false, b"1234567")),
    );
    check_rsp([0x20, 0, 0, 0, 0, 0, 0, 0], Rsp::DownloadSegment { toggle: false });
    check_req([0x1B, 0x38, 0x39, 0, 0, 0, 0, 0], Req::DownloadSegment(Segment::new(true, true, b"89")));
    check_rsp([0x30, 0, 0, 0, 0, 0, 0, 0], Rsp::DownloadSegment { toggle: true });
    // toggle-error variant, abort 0503 0000h and timeout abort 0504 0000h
    assert_eq!(req([0x0B, 0x38, 0x39, 0, 0, 0, 0, 0]), Req::DownloadSegment(Segment::new(false, true, b"89")));
    check_rsp([0x80, 0x00, 0x20, 0x00, 0x00, 0x00, 0x03, 0x05], Rsp::Abort { mux: m, code: 0x0503_0000 });
    check_rsp([0x80, 0x00, 0x20, 0x00, 0x00, 0x00, 0x04, 0x05], Rsp::Abort { mux: m, code: 0x0504_0000 });
    // n = 7: a segment with no data
    assert_eq!(req([0x0F, 0, 0, 0, 0, 0, 0, 0]), Req::DownloadSegment(Segment::new(false, true, b"")));
}

#[test]
fn block_download_frames_with_and_without_loss() {
    let m = mux(0x2000, 0);
    check_req([0xC6, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Req::BlockDownloadInitiate { mux: m, crc: true, size: Some(9) });
    check_req(
        [0xC2, 0x00, 0x20, 0x00, 0x09, 0, 0, 0],
        Req::BlockDownloadInitiate { mux: m, crc: false, size: Some(9) },
    );
    check_req([0xC4, 0x00, 0x20, 0x00, 0, 0, 0, 0], Req::BlockDownloadInitiate { mux: m, crc: true, size: None });
    check_rsp([0xA4, 0x00, 0x20, 0x00, 0x7F, 0, 0, 0], Rsp::BlockDownloadInitiate { mux: m, crc: true, blksize: 127 });
    check_rsp([0xA0, 0x00, 0x20, 0x00, 0x03, 0, 0, 0], Rsp::BlockDownloadInitiate { mux: m, crc: false, blksize: 3 });
    let s1 = BlockSegment::parse(&[0x01, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37]).unwrap();
    assert_eq!(s1, BlockSegment { last: false, seqno: 1, data: *b"1234567" });
    let s2 = BlockSegment::parse(&[0x83, 0x4F, 0x50, 0, 0, 0, 0, 0]).unwrap();
    assert_eq!((s2.last, s2.seqno, &s2.data[..2]), (true, 3, &b"OP"[..]));
    check_rsp([0xA2, 0x02, 0x7F, 0, 0, 0, 0, 0], Rsp::BlockDownloadAck { ackseq: 2, blksize: 127 });
    check_rsp([0xA2, 0x01, 0x03, 0, 0, 0, 0, 0], Rsp::BlockDownloadAck { ackseq: 1, blksize: 3 });
    check_req([0xD5, 0xC3, 0x31, 0, 0, 0, 0, 0], Req::BlockDownloadEnd { unused: 5, crc: 0x31C3 });
    check_req([0xD5, 0x80, 0x60, 0, 0, 0, 0, 0], Req::BlockDownloadEnd { unused: 5, crc: 0x6080 });
    check_req([0xC1, 0, 0, 0, 0, 0, 0, 0], Req::BlockDownloadEnd { unused: 0, crc: 0 });
    check_rsp([0xA1, 0, 0, 0, 0, 0, 0, 0], Rsp::BlockDownloadEnd);
    check_rsp([0x80, 0x00, 0x20, 0x00, 0x04, 0x00, 0x04, 0x05], Rsp::Abort { mux: m, code: 0x0504_0004 });
}

#[test]
fn block_upload_frames_and_protocol_switch() {
    let m = mux(0x2000, 0);
    check_req(
        [0xA4, 0x00, 0x20, 0x00, 0x7F, 0x00, 0, 0],
        Req::BlockUploadInitiate { mux: m, crc: true, blksize: 127, pst: 0 },
    );
    check_req(
        [0xA4, 0x00, 0x20, 0x00, 0x7F, 0x15, 0, 0],
        Req::BlockUploadInitiate { mux: m, crc: true, blksize: 127, pst: 21 },
    );
    check_rsp([0xC6, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Rsp::BlockUploadInitiate { mux: m, crc: true, size: Some(9) });
    check_rsp([0xC0, 0x00, 0x20, 0x00, 0, 0, 0, 0], Rsp::BlockUploadInitiate { mux: m, crc: false, size: None });
    check_req([0xA3, 0, 0, 0, 0, 0, 0, 0], Req::BlockUploadStart);
    let seg = BlockSegment { last: true, seqno: 2, data: [0x38, 0x39, 0, 0, 0, 0, 0] };
    assert_eq!(seg.emit(), [0x82, 0x38, 0x39, 0, 0, 0, 0, 0]);
    check_req([0xA2, 0x02, 0x7F, 0, 0, 0, 0, 0], Req::BlockUploadAck { ackseq: 2, blksize: 127 });
    check_rsp([0xD5, 0xC3, 0x31, 0, 0, 0, 0, 0], Rsp::BlockUploadEnd { unused: 5, crc: 0x31C3 });
    check_req([0xA1, 0, 0, 0, 0, 0, 0, 0], Req::BlockUploadEnd);
    // 8.4: protocol switch answers
    check_rsp(
        [0x41, 0x00, 0x20, 0x00, 0x09, 0, 0, 0],
        Rsp::InitiateUpload { mux: m, data: InitiateData::Segmented { size: Some(9) } },
    );
    check_rsp([0x4B, 0x17, 0x10, 0x00, 0x64, 0, 0, 0], Rsp::expedited_upload(mux(0x1017, 0), &[0x64, 0]));
}

#[test]
fn short_and_long_frames_are_length_errors() {
    for n in 0..16usize {
        let buf = [0u8; 16];
        let want = if n == 8 { Ok(()) } else { Err(ParseError::Length) };
        assert_eq!(Req::parse(&buf[..n]).map(|_| ()), want);
        assert_eq!(ServerResponse::parse(&buf[..n]).map(|_| ()), want);
        assert_eq!(BlockSegment::parse(&buf[..n]).map(|_| ()), want);
        assert_eq!(Segment::parse(&buf[..n]).map(|_| ()), want);
    }
}

#[test]
fn every_command_byte_parses_or_errors_and_reemits_stably() {
    for b0 in 0..=255u8 {
        let b = [b0, 0x34, 0x12, 0x05, 0xAA, 0xBB, 0xCC, 0xDD];
        if let Ok(r) = Req::parse(&b) {
            // emit → parse is a fixed point (reserved bits are dropped once)
            assert_eq!(Req::parse(&r.emit()), Ok(r), "{b0:02X}");
            assert_eq!(r.emit()[0] >> 5, b0 >> 5);
        } else {
            assert_eq!(b0 >> 5, 7);
        }
        if let Ok(r) = ServerResponse::parse(&b) {
            assert_eq!(ServerResponse::parse(&r.emit()), Ok(r), "{b0:02X}");
        } else {
            assert!(b0 >> 5 == 7 || (b0 >> 5 == 5 && b0 & 3 == 3), "{b0:02X}");
        }
    }
}
