//! SDO frame formats (CiA 301 §7.2.4.3, SDO-02, SDO-03, SDO-08, SDO-11..SDO-28, SDO-32,
//! SDO-35..SDO-47).
//!
//! Every SDO frame is 8 bytes (SDO-02). Byte 0 is the command byte; the command specifier is in bits 7–5
//! (SDO-03, SDO-08). Because client and server specifiers overlap (ccs 3 is "upload segment", scs 3 is
//! "initiate download response"), there are two enums: [`ClientRequest`] (client → server) and
//! [`ServerResponse`] (server → client, parsed by the client). Block sub-block segments carry no command
//! specifier at all (byte 0 = c ‖ seqno, SDO-37), so [`BlockSegment`] is parsed only where the state machine
//! expects one. Every frame other than a segment is built by one function, [`frame`] (command byte,
//! bytes 1–3, bytes 4–7); both enums' `emit` and [`abort_frame`] go through it.
//!
//! Design note: unlike smoltcp there is no zero-copy `Packet<&[u8]>` view: an SDO frame is 8 bytes and a
//! by-value `Repr` is cheaper than a view plus accessors. Parsing is liberal about reserved bits and bytes
//! ("a server should not depend on their content", SDO-02); emitting always writes them as 0. The SDO
//! server is the exception on the hot path: it dispatches on the command byte and reads the few fields each
//! request has straight from the frame, and builds its responses with [`frame`] (an enum parsed and then
//! matched again cost it ~90 instructions per frame; `ClientRequest::parse` is the same decoding, for the
//! tests and tools).
//!
//! ```
//! use canopen_core::wire::sdo::{ClientRequest, Multiplexer, ServerResponse};
//! // Read 6041h:00 → 2 bytes 0240h
//! let req = ClientRequest::parse(&[0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0]).unwrap();
//! assert_eq!(req, ClientRequest::InitiateUpload { mux: Multiplexer::new(0x6041, 0) });
//! let rsp = ServerResponse::expedited_upload(Multiplexer::new(0x6041, 0), &[0x40, 0x02]);
//! assert_eq!(rsp.emit(), [0x4B, 0x41, 0x60, 0x00, 0x40, 0x02, 0x00, 0x00]);
//! ```

/// Length of every SDO frame (SDO-02).
///
/// ```
/// assert_eq!(canopen_core::wire::sdo::FRAME_LEN, 8);
/// ```
pub const FRAME_LEN: usize = 8;

/// Largest block size (SDO-36: blksize 1..127).
///
/// ```
/// assert_eq!(canopen_core::wire::sdo::MAX_BLKSIZE, 0x7F);
/// ```
pub const MAX_BLKSIZE: u8 = 127;

/// Why bytes are not a valid SDO frame.
///
/// ```
/// use canopen_core::wire::sdo::{ClientRequest, ParseError};
/// assert_eq!(ClientRequest::parse(&[0x40, 0, 0]), Err(ParseError::Length));
/// assert_eq!(ClientRequest::parse(&[0xE0, 0, 0, 0, 0, 0, 0, 0]), Err(ParseError::CommandSpecifier));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ParseError {
    /// The frame does not have exactly 8 data bytes (SDO-02).
    Length,
    /// Unknown command specifier or sub-command (SDO-09: abort 0504 0001h).
    CommandSpecifier,
}

/// ```
/// use canopen_core::wire::sdo::ParseError;
/// assert_eq!(ParseError::Length.to_string(), "SDO frame without 8 data bytes");
/// ```
impl core::fmt::Display for ParseError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            ParseError::Length => "SDO frame without 8 data bytes",
            ParseError::CommandSpecifier => "unknown SDO command specifier",
        })
    }
}

impl core::error::Error for ParseError {}

/// The object addressed by an initiate or abort frame: bytes 1–2 index (LE), byte 3 sub-index (SDO-03).
///
/// ```
/// use canopen_core::wire::sdo::Multiplexer;
/// let m = Multiplexer::new(0x1018, 1);
/// assert_eq!(m.index, 0x1018);
/// assert_eq!(m.sub, 1);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Multiplexer {
    /// 16-bit object index.
    pub index: u16,
    /// 8-bit sub-index.
    pub sub: u8,
}

impl Multiplexer {
    /// Builds a multiplexer.
    ///
    /// ```
    /// # use canopen_core::wire::sdo::Multiplexer;
    /// assert_eq!(Multiplexer::new(0x2000, 0).index, 0x2000);
    /// ```
    pub const fn new(index: u16, sub: u8) -> Self {
        Multiplexer { index, sub }
    }

    /// The multiplexer of a frame (bytes 1–3).
    ///
    /// ```
    /// # use canopen_core::wire::sdo::Multiplexer;
    /// assert_eq!(Multiplexer::of_frame(&[0x40, 0x18, 0x10, 0x01, 0, 0, 0, 0]), Multiplexer::new(0x1018, 1));
    /// ```
    pub const fn of_frame(b: &[u8; 8]) -> Self {
        Multiplexer { index: u16::from_le_bytes([b[1], b[2]]), sub: b[3] }
    }

    /// Bytes 1–3 as [`frame`] takes them: index | sub-index << 16.
    ///
    /// ```
    /// # use canopen_core::wire::sdo::Multiplexer;
    /// assert_eq!(Multiplexer::new(0x1018, 1).bits(), 0x01_1018);
    /// ```
    pub const fn bits(self) -> u32 {
        self.index as u32 | (self.sub as u32) << 16
    }
}

/// Builds an 8-byte SDO frame from its three fields: the command byte, bytes 1–3 (`middle`, little-endian: the
/// multiplexer's [`bits`](Multiplexer::bits), or ackseq ‖ blksize, or a CRC) and bytes 4–7 (`data`,
/// UNSIGNED32 LE). Every non-segment frame of both directions is built here (SDO-02: all 8 bytes, reserved
/// ones 0).
///
/// ```
/// use canopen_core::wire::sdo::{frame, Multiplexer};
/// // The confirmation of a write of 607Ah:00: 60h, 607Ah:00
/// assert_eq!(frame(0x60, Multiplexer::new(0x607A, 0).bits(), 0), [0x60, 0x7A, 0x60, 0x00, 0, 0, 0, 0]);
/// ```
#[inline]
pub const fn frame(command: u8, middle: u32, data: u32) -> [u8; 8] {
    (command as u64 | ((middle as u64 & 0xFF_FFFF) << 8) | ((data as u64) << 32)).to_le_bytes()
}

/// Up to four data bytes carried in an expedited initiate frame (SDO-12, SDO-13, SDO-24).
///
/// ```
/// use canopen_core::wire::sdo::Expedited;
/// let e = Expedited::new(&[1, 2]).unwrap();
/// assert_eq!(e.bytes(), &[1, 2]);
/// assert!(e.size_indicated);
/// assert!(Expedited::new(&[]).is_none());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Expedited {
    /// Bytes 4–7 of the frame; only the first `len` are data (the rest is 0 after `parse`).
    pub data: [u8; 4],
    /// Number of data bytes, 1..=4 (4 when the size is not indicated).
    pub len: u8,
    /// `s` bit: whether the size is given (by `n`). When clear, all four bytes are sent and the receiver takes
    /// the length from the object (SDO-13).
    pub size_indicated: bool,
}

impl Expedited {
    /// Expedited data with size indicated; `None` unless `1 <= bytes.len() <= 4`.
    ///
    /// ```
    /// # use canopen_core::wire::sdo::Expedited;
    /// assert_eq!(Expedited::new(&[9; 4]).unwrap().len, 4);
    /// assert!(Expedited::new(&[9; 5]).is_none());
    /// ```
    pub fn new(bytes: &[u8]) -> Option<Self> {
        // By length, not copy_from_slice: a 1-4 byte copy of unknown length is a memcpy call.
        let data = match *bytes {
            [a] => [a, 0, 0, 0],
            [a, b] => [a, b, 0, 0],
            [a, b, c] => [a, b, c, 0],
            [a, b, c, d] => [a, b, c, d],
            _ => return None,
        };
        Some(Expedited { data, len: bytes.len() as u8, size_indicated: true })
    }

    /// The data bytes.
    ///
    /// ```
    /// # use canopen_core::wire::sdo::Expedited;
    /// assert_eq!(Expedited::new(&[7]).unwrap().bytes(), &[7]);
    /// ```
    pub fn bytes(&self) -> &[u8] {
        let n = usize::from(self.len).min(4);
        &self.data[..n]
    }
}

/// What an initiate download request or initiate upload response announces (SDO-11..SDO-16, SDO-24, SDO-25).
///
/// ```
/// use canopen_core::wire::sdo::InitiateData;
/// let d = InitiateData::Segmented { size: Some(23) };
/// assert_ne!(d, InitiateData::Segmented { size: None });
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum InitiateData {
    /// e = 1: the data is in the frame.
    Expedited(Expedited),
    /// e = 0: segments follow; `size` when s = 1.
    Segmented {
        /// Total byte count (bytes 4–7, UNSIGNED32 LE) when indicated.
        size: Option<u32>,
    },
}

impl InitiateData {
    fn parse(b: &[u8; 8]) -> Self {
        let e = b[0] & 0x02 != 0;
        let s = b[0] & 0x01 != 0;
        let mut data = [0u8; 4];
        data.copy_from_slice(&b[4..8]);
        match (e, s) {
            (true, true) => {
                let len = 4 - ((b[0] >> 2) & 0x03);
                for d in data.iter_mut().skip(usize::from(len)) {
                    *d = 0;
                }
                InitiateData::Expedited(Expedited { data, len, size_indicated: true })
            }
            (true, false) => InitiateData::Expedited(Expedited { data, len: 4, size_indicated: false }),
            (false, true) => InitiateData::Segmented { size: Some(u32::from_le_bytes(data)) },
            (false, false) => InitiateData::Segmented { size: None },
        }
    }

    /// The command bits (e, s, n) and bytes 4–7 this announcement adds to an initiate frame.
    fn parts(&self) -> (u8, u32) {
        match *self {
            InitiateData::Expedited(e) if e.size_indicated => {
                let len = e.len.clamp(1, 4);
                // The first `len` bytes, the rest stays 0.
                let keep = u32::MAX >> (8 * (4 - u32::from(len)));
                (((4 - len) << 2) | 0x03, u32::from_le_bytes(e.data) & keep)
            }
            InitiateData::Expedited(e) => (0x02, u32::from_le_bytes(e.data)),
            InitiateData::Segmented { size: Some(size) } => (0x01, size),
            InitiateData::Segmented { size: None } => (0, 0),
        }
    }
}

/// A segment of a segmented transfer: download segment request (ccs 0, SDO-19) and upload segment
/// response (scs 0, SDO-27) share the layout 000b ‖ t ‖ n ‖ c, bytes 1–7 data.
///
/// ```
/// use canopen_core::wire::sdo::Segment;
/// // V §7.3 step 5: t 1, n 5, c 1, "89"
/// let s = Segment::new(true, true, b"89");
/// assert_eq!(s.emit(), [0x1B, 0x38, 0x39, 0, 0, 0, 0, 0]);
/// assert_eq!(Segment::parse(&s.emit()), Ok(s));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Segment {
    /// Toggle bit (SDO-21, SDO-28).
    pub toggle: bool,
    /// c: no more segments (SDO-19, SDO-27).
    pub last: bool,
    /// Number of data bytes, 0..=7 (7 − n).
    pub len: u8,
    /// Bytes 1–7; only the first `len` are data (the rest is 0 after `parse`).
    pub data: [u8; 7],
}

impl Segment {
    /// A segment carrying `bytes` (at most 7 are used).
    ///
    /// ```
    /// # use canopen_core::wire::sdo::Segment;
    /// assert_eq!(Segment::new(false, false, b"1234567").len, 7);
    /// ```
    pub fn new(toggle: bool, last: bool, bytes: &[u8]) -> Self {
        let n = bytes.len().min(7);
        let mut data = [0u8; 7];
        data[..n].copy_from_slice(&bytes[..n]);
        Segment { toggle, last, len: n as u8, data }
    }

    /// The data bytes.
    ///
    /// ```
    /// # use canopen_core::wire::sdo::Segment;
    /// assert_eq!(Segment::new(false, true, b"ab").bytes(), b"ab");
    /// ```
    pub fn bytes(&self) -> &[u8] {
        &self.data[..usize::from(self.len).min(7)]
    }

    /// Parses a segment frame; the command specifier bits are not checked (the caller dispatched on them).
    ///
    /// ```
    /// # use canopen_core::wire::sdo::Segment;
    /// let s = Segment::parse(&[0x00, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37]).unwrap();
    /// assert_eq!((s.toggle, s.last, s.bytes()), (false, false, &b"1234567"[..]));
    /// ```
    pub fn parse(data: &[u8]) -> Result<Self, ParseError> {
        let b = eight(data)?;
        let len = 7 - ((b[0] >> 1) & 0x07);
        let n = usize::from(len);
        let mut d = [0u8; 7];
        d[..n].copy_from_slice(&b[1..1 + n]);
        Ok(Segment { toggle: b[0] & 0x10 != 0, last: b[0] & 0x01 != 0, len, data: d })
    }

    /// Emits the frame (command specifier 000b); unused data bytes are sent as 0.
    ///
    /// ```
    /// # use canopen_core::wire::sdo::Segment;
    /// assert_eq!(Segment::new(false, false, b"1234567").emit()[0], 0x00);
    /// ```
    pub fn emit(&self) -> [u8; 8] {
        let mut b = [0u8; 8];
        let len = self.len.min(7);
        b[0] = (u8::from(self.toggle) << 4) | ((7 - len) << 1) | u8::from(self.last);
        // All 7 data bytes in one fixed-size copy, then the bytes past `len` cleared with a mask: a copy of
        // 0-7 bytes of runtime length would be a memcpy call per segment.
        b[1..8].copy_from_slice(&self.data);
        let keep = u64::MAX.checked_shr(64 - 8 * u32::from(len)).unwrap_or(0); // the low `len` bytes
        let data = (u64::from_le_bytes(b) >> 8) & keep;
        ((data << 8) | u64::from(b[0])).to_le_bytes()
    }
}

/// A block-transfer sub-block segment: byte 0 = c (bit 7) ‖ seqno (bits 6–0), bytes 1–7 data (SDO-37).
///
/// It carries no command specifier, so it is only parsed where the receiver expects a segment.
///
/// ```
/// use canopen_core::wire::sdo::BlockSegment;
/// // V-8.1 step 4: c 1, seqno 2, "89"
/// let s = BlockSegment::parse(&[0x82, 0x38, 0x39, 0, 0, 0, 0, 0]).unwrap();
/// assert_eq!((s.last, s.seqno), (true, 2));
/// assert_eq!(s.emit(), [0x82, 0x38, 0x39, 0, 0, 0, 0, 0]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct BlockSegment {
    /// c: last segment of the whole data set.
    pub last: bool,
    /// Sequence number 1..=127 within the sub-block (0 is invalid, SDO-38).
    pub seqno: u8,
    /// Bytes 1–7 (the number of valid bytes of the last segment comes with the end frame).
    pub data: [u8; 7],
}

impl BlockSegment {
    /// Parses a sub-block segment.
    ///
    /// ```
    /// # use canopen_core::wire::sdo::{BlockSegment, ParseError};
    /// assert_eq!(BlockSegment::parse(&[1]), Err(ParseError::Length));
    /// ```
    pub fn parse(data: &[u8]) -> Result<Self, ParseError> {
        let b = eight(data)?;
        let mut d = [0u8; 7];
        d.copy_from_slice(&b[1..8]);
        Ok(BlockSegment { last: b[0] & 0x80 != 0, seqno: b[0] & 0x7F, data: d })
    }

    /// Emits the frame.
    ///
    /// ```
    /// # use canopen_core::wire::sdo::BlockSegment;
    /// let s = BlockSegment { last: false, seqno: 1, data: *b"1234567" };
    /// assert_eq!(s.emit(), [0x01, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37]);
    /// ```
    pub fn emit(&self) -> [u8; 8] {
        let mut b = [0u8; 8];
        b[0] = (u8::from(self.last) << 7) | (self.seqno & 0x7F);
        b[1..8].copy_from_slice(&self.data);
        b
    }
}

/// A frame from client to server, as the server parses it (ccs = byte 0 bits 7–5, SDO-08).
///
/// ```
/// use canopen_core::wire::sdo::{ClientRequest, Expedited, InitiateData, Multiplexer};
/// // Write 607Ah:00 = 0000 03E8h
/// let bytes = [0x23, 0x7A, 0x60, 0x00, 0xE8, 0x03, 0x00, 0x00];
/// let req = ClientRequest::parse(&bytes).unwrap();
/// assert_eq!(req, ClientRequest::InitiateDownload {
///     mux: Multiplexer::new(0x607A, 0),
///     data: InitiateData::Expedited(Expedited::new(&[0xE8, 0x03, 0, 0]).unwrap()),
/// });
/// assert_eq!(req.emit(), bytes);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ClientRequest {
    /// ccs 1: initiate download (SDO-11..SDO-16).
    InitiateDownload {
        /// The object.
        mux: Multiplexer,
        /// Expedited data or the announced segmented size.
        data: InitiateData,
    },
    /// ccs 0: download segment (SDO-19).
    DownloadSegment(Segment),
    /// ccs 2: initiate upload (SDO-23).
    InitiateUpload {
        /// The object.
        mux: Multiplexer,
    },
    /// ccs 3: upload segment request (SDO-26); bytes 1–7 are reserved and ignored.
    UploadSegment {
        /// Toggle bit.
        toggle: bool,
    },
    /// ccs 4: abort transfer (SDO-32). The code is kept raw: a peer may send codes outside Table 22.
    Abort {
        /// The object.
        mux: Multiplexer,
        /// Abort code (UNSIGNED32 LE in bytes 4–7).
        code: u32,
    },
    /// ccs 6, cs 0: initiate block download (SDO-35).
    BlockDownloadInitiate {
        /// The object.
        mux: Multiplexer,
        /// cc: the client supports CRC.
        crc: bool,
        /// Data set size when s = 1.
        size: Option<u32>,
    },
    /// ccs 6, cs 1: end block download (SDO-41).
    BlockDownloadEnd {
        /// n: bytes of the last segment that carry no data (0..=7).
        unused: u8,
        /// CRC of the whole data set (0 when not used).
        crc: u16,
    },
    /// ccs 5, cs 0: initiate block upload (SDO-42).
    BlockUploadInitiate {
        /// The object.
        mux: Multiplexer,
        /// cc: the client supports CRC.
        crc: bool,
        /// Segments per sub-block (valid 1..=127; not checked here).
        blksize: u8,
        /// Protocol switch threshold (SDO-43).
        pst: u8,
    },
    /// ccs 5, cs 3: start upload (SDO-45).
    BlockUploadStart,
    /// ccs 5, cs 2: sub-block acknowledge (SDO-46).
    BlockUploadAck {
        /// Last segment received in order (0 = none).
        ackseq: u8,
        /// Segments of the next sub-block.
        blksize: u8,
    },
    /// ccs 5, cs 1: end block upload response (SDO-47).
    BlockUploadEnd,
}

fn eight(data: &[u8]) -> Result<&[u8; 8], ParseError> {
    data.try_into().map_err(|_| ParseError::Length)
}

impl ClientRequest {
    /// Parses a client frame. Reserved bits and bytes are ignored (SDO-02); only a frame of exactly 8 bytes is
    /// accepted.
    ///
    /// ```
    /// # use canopen_core::wire::sdo::{ClientRequest, ParseError};
    /// assert_eq!(ClientRequest::parse(&[0xA3, 0, 0, 0, 0, 0, 0, 0]), Ok(ClientRequest::BlockUploadStart));
    /// assert_eq!(ClientRequest::parse(&[0xA3; 7]), Err(ParseError::Length));
    /// ```
    pub fn parse(data: &[u8]) -> Result<Self, ParseError> {
        let b = eight(data)?;
        let mux = Multiplexer::of_frame(b);
        Ok(match b[0] >> 5 {
            0 => ClientRequest::DownloadSegment(Segment::parse(b)?),
            1 => ClientRequest::InitiateDownload { mux, data: InitiateData::parse(b) },
            2 => ClientRequest::InitiateUpload { mux },
            3 => ClientRequest::UploadSegment { toggle: b[0] & 0x10 != 0 },
            4 => ClientRequest::Abort { mux, code: u32::from_le_bytes([b[4], b[5], b[6], b[7]]) },
            5 => match b[0] & 0x03 {
                0 => ClientRequest::BlockUploadInitiate { mux, crc: b[0] & 0x04 != 0, blksize: b[4], pst: b[5] },
                1 => ClientRequest::BlockUploadEnd,
                2 => ClientRequest::BlockUploadAck { ackseq: b[1], blksize: b[2] },
                _ => ClientRequest::BlockUploadStart,
            },
            6 => {
                if b[0] & 0x01 == 0 {
                    let size = (b[0] & 0x02 != 0).then(|| u32::from_le_bytes([b[4], b[5], b[6], b[7]]));
                    ClientRequest::BlockDownloadInitiate { mux, crc: b[0] & 0x04 != 0, size }
                } else {
                    ClientRequest::BlockDownloadEnd {
                        unused: (b[0] >> 2) & 0x07,
                        crc: u16::from_le_bytes([b[1], b[2]]),
                    }
                }
            }
            _ => return Err(ParseError::CommandSpecifier),
        })
    }

    /// Emits the 8-byte frame, reserved bits and bytes 0 (SDO-02).
    ///
    /// ```
    /// # use canopen_core::wire::sdo::{ClientRequest, Multiplexer};
    /// let f = ClientRequest::BlockUploadInitiate { mux: Multiplexer::new(0x2000, 0), crc: true, blksize: 127, pst: 0 };
    /// assert_eq!(f.emit(), [0xA4, 0x00, 0x20, 0x00, 0x7F, 0x00, 0x00, 0x00]);
    /// ```
    pub fn emit(&self) -> [u8; 8] {
        let (command, middle, data) = match *self {
            ClientRequest::InitiateDownload { mux, data } => {
                let (bits, data) = data.parts();
                (0x20 | bits, mux.bits(), data)
            }
            ClientRequest::DownloadSegment(s) => return s.emit(),
            ClientRequest::InitiateUpload { mux } => (0x40, mux.bits(), 0),
            ClientRequest::UploadSegment { toggle } => (0x60 | (u8::from(toggle) << 4), 0, 0),
            ClientRequest::Abort { mux, code } => (0x80, mux.bits(), code),
            ClientRequest::BlockDownloadInitiate { mux, crc, size } => {
                (0xC0 | (u8::from(crc) << 2) | (u8::from(size.is_some()) << 1), mux.bits(), size.unwrap_or(0))
            }
            ClientRequest::BlockDownloadEnd { unused, crc } => (0xC1 | ((unused & 0x07) << 2), u32::from(crc), 0),
            ClientRequest::BlockUploadInitiate { mux, crc, blksize, pst } => {
                (0xA0 | (u8::from(crc) << 2), mux.bits(), u32::from_le_bytes([blksize, pst, 0, 0]))
            }
            ClientRequest::BlockUploadStart => (0xA3, 0, 0),
            ClientRequest::BlockUploadAck { ackseq, blksize } => (0xA2, u32::from_le_bytes([ackseq, blksize, 0, 0]), 0),
            ClientRequest::BlockUploadEnd => (0xA1, 0, 0),
        };
        frame(command, middle, data)
    }
}

/// A frame from server to client, as the client parses it (scs = byte 0 bits 7–5, SDO-08).
///
/// ```
/// use canopen_core::wire::sdo::{Multiplexer, ServerResponse};
/// // V-8.1 step 2: scs 5, sc 1, blksize 127
/// let r = ServerResponse::parse(&[0xA4, 0x00, 0x20, 0x00, 0x7F, 0, 0, 0]).unwrap();
/// assert_eq!(r, ServerResponse::BlockDownloadInitiate { mux: Multiplexer::new(0x2000, 0), crc: true, blksize: 127 });
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ServerResponse {
    /// scs 3: initiate download response (SDO-17).
    InitiateDownload {
        /// The object.
        mux: Multiplexer,
    },
    /// scs 1: download segment response (SDO-20).
    DownloadSegment {
        /// Echo of the request's toggle bit.
        toggle: bool,
    },
    /// scs 2: initiate upload response (SDO-24, SDO-25).
    InitiateUpload {
        /// The object.
        mux: Multiplexer,
        /// Expedited data or the segmented size.
        data: InitiateData,
    },
    /// scs 0: upload segment response (SDO-27).
    UploadSegment(Segment),
    /// scs 4: abort transfer (SDO-32).
    Abort {
        /// The object.
        mux: Multiplexer,
        /// Abort code.
        code: u32,
    },
    /// scs 5, ss 0: initiate block download response (SDO-36).
    BlockDownloadInitiate {
        /// The object.
        mux: Multiplexer,
        /// sc: the server supports CRC.
        crc: bool,
        /// Segments per sub-block.
        blksize: u8,
    },
    /// scs 5, ss 2: sub-block acknowledge (SDO-39, SDO-40).
    BlockDownloadAck {
        /// Last segment received in order (0 = none).
        ackseq: u8,
        /// Segments of the next sub-block.
        blksize: u8,
    },
    /// scs 5, ss 1: end block download response (SDO-41).
    BlockDownloadEnd,
    /// scs 6, ss 0: initiate block upload response (SDO-44).
    BlockUploadInitiate {
        /// The object.
        mux: Multiplexer,
        /// sc: the server uses CRC.
        crc: bool,
        /// Data set size when s = 1.
        size: Option<u32>,
    },
    /// scs 6, ss 1: end block upload request (SDO-47).
    BlockUploadEnd {
        /// n: bytes of the last segment without data.
        unused: u8,
        /// CRC of the data set (0 when not used).
        crc: u16,
    },
}

impl ServerResponse {
    /// An expedited initiate upload response with size indicated (SDO-24); `data` must be 1..=4 bytes
    /// (longer input is cut to 4, empty input sends one zero byte).
    ///
    /// ```
    /// # use canopen_core::wire::sdo::{Multiplexer, ServerResponse};
    /// let r = ServerResponse::expedited_upload(Multiplexer::new(0x1400, 2), &[0xFD]);
    /// assert_eq!(r.emit(), [0x4F, 0x00, 0x14, 0x02, 0xFD, 0, 0, 0]);
    /// ```
    pub fn expedited_upload(mux: Multiplexer, data: &[u8]) -> Self {
        let n = data.len().clamp(1, 4);
        let mut d = [0u8; 4];
        let src = data.get(..n).unwrap_or(&[]);
        d[..src.len()].copy_from_slice(src);
        ServerResponse::InitiateUpload {
            mux,
            data: InitiateData::Expedited(Expedited { data: d, len: n as u8, size_indicated: true }),
        }
    }

    /// Parses a server frame.
    ///
    /// ```
    /// # use canopen_core::wire::sdo::{ParseError, ServerResponse};
    /// assert_eq!(ServerResponse::parse(&[0xA1, 0, 0, 0, 0, 0, 0, 0]), Ok(ServerResponse::BlockDownloadEnd));
    /// assert_eq!(ServerResponse::parse(&[0xA3, 0, 0, 0, 0, 0, 0, 0]), Err(ParseError::CommandSpecifier));
    /// ```
    pub fn parse(data: &[u8]) -> Result<Self, ParseError> {
        let b = eight(data)?;
        let mux = Multiplexer::of_frame(b);
        Ok(match b[0] >> 5 {
            0 => ServerResponse::UploadSegment(Segment::parse(b)?),
            1 => ServerResponse::DownloadSegment { toggle: b[0] & 0x10 != 0 },
            2 => ServerResponse::InitiateUpload { mux, data: InitiateData::parse(b) },
            3 => ServerResponse::InitiateDownload { mux },
            4 => ServerResponse::Abort { mux, code: u32::from_le_bytes([b[4], b[5], b[6], b[7]]) },
            5 => match b[0] & 0x03 {
                0 => ServerResponse::BlockDownloadInitiate { mux, crc: b[0] & 0x04 != 0, blksize: b[4] },
                1 => ServerResponse::BlockDownloadEnd,
                2 => ServerResponse::BlockDownloadAck { ackseq: b[1], blksize: b[2] },
                _ => return Err(ParseError::CommandSpecifier),
            },
            6 => {
                if b[0] & 0x01 == 0 {
                    let size = (b[0] & 0x02 != 0).then(|| u32::from_le_bytes([b[4], b[5], b[6], b[7]]));
                    ServerResponse::BlockUploadInitiate { mux, crc: b[0] & 0x04 != 0, size }
                } else {
                    ServerResponse::BlockUploadEnd { unused: (b[0] >> 2) & 0x07, crc: u16::from_le_bytes([b[1], b[2]]) }
                }
            }
            _ => return Err(ParseError::CommandSpecifier),
        })
    }

    /// Emits the 8-byte frame, reserved bits and bytes 0 (SDO-02).
    ///
    /// ```
    /// # use canopen_core::wire::sdo::ServerResponse;
    /// assert_eq!(ServerResponse::DownloadSegment { toggle: true }.emit(), [0x30, 0, 0, 0, 0, 0, 0, 0]);
    /// ```
    pub fn emit(&self) -> [u8; 8] {
        let (command, middle, data) = match *self {
            ServerResponse::InitiateDownload { mux } => (0x60, mux.bits(), 0),
            ServerResponse::DownloadSegment { toggle } => (0x20 | (u8::from(toggle) << 4), 0, 0),
            ServerResponse::InitiateUpload { mux, data } => {
                let (bits, data) = data.parts();
                (0x40 | bits, mux.bits(), data)
            }
            ServerResponse::UploadSegment(s) => return s.emit(),
            ServerResponse::Abort { mux, code } => (0x80, mux.bits(), code),
            ServerResponse::BlockDownloadInitiate { mux, crc, blksize } => {
                (0xA0 | (u8::from(crc) << 2), mux.bits(), u32::from(blksize))
            }
            ServerResponse::BlockDownloadAck { ackseq, blksize } => {
                (0xA2, u32::from_le_bytes([ackseq, blksize, 0, 0]), 0)
            }
            ServerResponse::BlockDownloadEnd => (0xA1, 0, 0),
            ServerResponse::BlockUploadInitiate { mux, crc, size } => {
                (0xC0 | (u8::from(crc) << 2) | (u8::from(size.is_some()) << 1), mux.bits(), size.unwrap_or(0))
            }
            ServerResponse::BlockUploadEnd { unused, crc } => (0xC1 | ((unused & 0x07) << 2), u32::from(crc), 0),
        };
        frame(command, middle, data)
    }
}

/// The abort frame, identical in both directions: 80h, multiplexer, code LE (SDO-32).
///
/// ```
/// use canopen_core::wire::sdo::{abort_frame, Multiplexer};
/// // Object 5000h does not exist: 0602 0000h on 5000h:00
/// assert_eq!(abort_frame(Multiplexer::new(0x5000, 0), 0x0602_0000), [0x80, 0x00, 0x50, 0x00, 0x00, 0x00, 0x02, 0x06]);
/// ```
pub const fn abort_frame(mux: Multiplexer, code: u32) -> [u8; 8] {
    frame(0x80, mux.bits(), code)
}

#[cfg(test)]
mod tests;
