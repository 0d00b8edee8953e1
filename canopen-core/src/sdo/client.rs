//! The SDO client: the same protocols from the other side (CiA 301 §7.2.4), sans-IO.
//!
//! Implements the client half of SDO-07..SDO-51: expedited and segmented download/upload (size indicated),
//! block download and block upload with CRC (cc = 1 when asked, CRC used only when the server's sc is 1 too,
//! SDO-48), protocol switch on block upload (SDO-43), go-back-n acknowledgement, time-out (SDO-31) and
//! abort in both directions (never answering an abort, SDO-33). 1280h parameters are a plain struct,
//! [`SdoClientParams`].
//!
//! # Driving it
//!
//! 1. [`SdoClient::start_download`] / [`SdoClient::start_upload`] with a [`Mode`].
//! 2. Loop: send every frame from [`SdoClient::poll_transmit`] (on [`SdoClientParams::tx_cob_id`]); feed
//!    frames received on [`SdoClientParams::rx_cob_id`] to [`SdoClient::handle_response`]; call
//!    [`SdoClient::handle_timeout`] at [`SdoClient::poll_timeout`].
//! 3. A [`ClientEvent`] reports the end: `Done` or `Failed`.
//!
//! The data moves through [`ClientData`] (download: the client reads the bytes to send; upload: it writes the
//! bytes received), so large values stream without a buffer in the client. [`SliceData`] adapts a caller
//! buffer.
//!
//! ```
//! use canopen_core::sdo::client::{ClientData, Mode, SdoClient, SliceData};
//! use canopen_core::sdo::SdoClientParams;
//! use canopen_core::wire::sdo::Multiplexer;
//! use canopen_core::{Instant, NodeId};
//!
//! let mut client = SdoClient::new(SdoClientParams::for_server(NodeId::new(3).unwrap()));
//! let mut value = [0xE8, 0x03, 0x00, 0x00];
//! let mut data = SliceData::download(&mut value);
//! client.start_download(Instant::ZERO, Multiplexer::new(0x607A, 0), data.download_len(), Mode::Auto).unwrap();
//! // Write 607Ah:00 (INTEGER32) = 1000: 23 7A 60 00 E8 03 00 00 -> 60 7A 60 00 ...
//! assert_eq!(client.poll_transmit(Instant::ZERO, &mut data), Some([0x23, 0x7A, 0x60, 0x00, 0xE8, 0x03, 0x00, 0x00]));
//! let ev = client.handle_response(Instant::ZERO, &[0x60, 0x7A, 0x60, 0x00, 0, 0, 0, 0], &mut data);
//! assert_eq!(ev, Some(canopen_core::sdo::client::ClientEvent::Done { len: 4 }));
//! ```

use super::block::{last_segment_len, Crc16};
use crate::abort::AbortCode;
use crate::cob::{CobIdEntry, FunctionCode};
use crate::time::{Duration, Instant};
use crate::wire::sdo::{
    abort_frame, BlockSegment, ClientRequest, Expedited, InitiateData, Multiplexer, Segment, ServerResponse,
    MAX_BLKSIZE,
};
use crate::NodeId;

/// 1280h-style client parameters (SDO-56).
///
/// ```
/// use canopen_core::sdo::SdoClientParams;
/// use canopen_core::NodeId;
/// let p = SdoClientParams::for_server(NodeId::new(3).unwrap());
/// assert_eq!((p.tx_cob_id(), p.rx_cob_id()), (0x603, 0x583));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SdoClientParams {
    /// Sub 01h: COB-ID client → server (the client sends on it).
    pub cob_tx: CobIdEntry,
    /// Sub 02h: COB-ID server → client (the client receives on it).
    pub cob_rx: CobIdEntry,
    /// Sub 03h: node-ID of the server.
    pub server_node: u8,
}

impl SdoClientParams {
    /// The client of `node`'s default server SDO: 600h + node / 580h + node.
    ///
    /// ```
    /// # use canopen_core::sdo::SdoClientParams;
    /// # use canopen_core::NodeId;
    /// assert_eq!(SdoClientParams::for_server(NodeId::new(1).unwrap()).server_node, 1);
    /// ```
    pub const fn for_server(node: NodeId) -> Self {
        SdoClientParams {
            cob_tx: CobIdEntry::new(false, false, FunctionCode::SdoRx.cob_id(node)),
            cob_rx: CobIdEntry::new(false, false, FunctionCode::SdoTx.cob_id(node)),
            server_node: node.get(),
        }
    }

    /// CAN-ID for requests.
    ///
    /// ```
    /// # use canopen_core::sdo::SdoClientParams;
    /// # use canopen_core::NodeId;
    /// assert_eq!(SdoClientParams::for_server(NodeId::new(2).unwrap()).tx_cob_id(), 0x602);
    /// ```
    pub const fn tx_cob_id(&self) -> u16 {
        self.cob_tx.can_id()
    }

    /// CAN-ID of the responses.
    ///
    /// ```
    /// # use canopen_core::sdo::SdoClientParams;
    /// # use canopen_core::NodeId;
    /// assert_eq!(SdoClientParams::for_server(NodeId::new(2).unwrap()).rx_cob_id(), 0x582);
    /// ```
    pub const fn rx_cob_id(&self) -> u16 {
        self.cob_rx.can_id()
    }
}

/// How to transfer.
///
/// ```
/// use canopen_core::sdo::client::Mode;
/// let m = Mode::Block { crc: true, blksize: 127, pst: 0 };
/// assert_ne!(m, Mode::Auto);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Expedited when the data fits in 1..=4 bytes (download) / when the server chooses it (upload),
    /// segmented otherwise.
    Auto,
    /// Always segmented (download); for upload the server decides, as with `Auto`.
    Segmented,
    /// Block transfer.
    Block {
        /// Ask for CRC (cc = 1).
        crc: bool,
        /// Block size the client asks for in block upload (1..=127); ignored for download.
        blksize: u8,
        /// Protocol switch threshold for block upload (SDO-43); ignored for download.
        pst: u8,
    },
}

/// Where the client's data comes from (download) and goes to (upload).
///
/// ```
/// use canopen_core::sdo::client::{ClientData, SliceData};
/// let mut buf = [1u8, 2, 3];
/// let mut d = SliceData::download(&mut buf);
/// let mut out = [0u8; 2];
/// assert_eq!(d.read(1, &mut out), 2);
/// assert_eq!(out, [2, 3]);
/// ```
pub trait ClientData {
    /// Total bytes to download.
    fn download_len(&self) -> usize;
    /// Copies bytes `offset..` of the download data into `buf`; returns how many.
    fn read(&mut self, offset: usize, buf: &mut [u8]) -> usize;
    /// Stores uploaded bytes at `offset` (in increasing, contiguous offsets; a retransmission never rewinds
    /// past data already written).
    fn write(&mut self, offset: usize, data: &[u8]) -> Result<(), AbortCode>;
}

/// [`ClientData`] over a caller buffer.
///
/// ```
/// use canopen_core::sdo::client::{ClientData, SliceData};
/// let mut buf = [0u8; 4];
/// let mut d = SliceData::upload(&mut buf);
/// d.write(0, &[9, 8]).unwrap();
/// assert_eq!(d.len(), 2);
/// assert_eq!(d.as_slice(), &[9, 8]);
/// assert!(d.write(2, &[0; 3]).is_err());
/// ```
#[derive(Debug)]
pub struct SliceData<'a> {
    buf: &'a mut [u8],
    len: usize,
}

impl<'a> SliceData<'a> {
    /// Download all of `buf`.
    ///
    /// ```
    /// # use canopen_core::sdo::client::{ClientData, SliceData};
    /// let mut b = [0u8; 9];
    /// assert_eq!(SliceData::download(&mut b).download_len(), 9);
    /// ```
    pub fn download(buf: &'a mut [u8]) -> Self {
        let len = buf.len();
        SliceData { buf, len }
    }

    /// Upload into `buf` (its length is the capacity; more data aborts with 0504 0005h).
    ///
    /// ```
    /// # use canopen_core::sdo::client::SliceData;
    /// let mut b = [0u8; 9];
    /// assert_eq!(SliceData::upload(&mut b).len(), 0);
    /// ```
    pub fn upload(buf: &'a mut [u8]) -> Self {
        SliceData { buf, len: 0 }
    }

    /// Bytes held (uploaded so far, or the download length).
    ///
    /// ```
    /// # use canopen_core::sdo::client::SliceData;
    /// let mut b = [0u8; 3];
    /// assert_eq!(SliceData::download(&mut b).len(), 3);
    /// ```
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether no bytes are held.
    ///
    /// ```
    /// # use canopen_core::sdo::client::SliceData;
    /// let mut b = [0u8; 3];
    /// assert!(SliceData::upload(&mut b).is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The bytes held.
    ///
    /// ```
    /// # use canopen_core::sdo::client::SliceData;
    /// let mut b = [5u8; 2];
    /// assert_eq!(SliceData::download(&mut b).as_slice(), &[5, 5]);
    /// ```
    pub fn as_slice(&self) -> &[u8] {
        self.buf.get(..self.len).unwrap_or(&[])
    }
}

impl ClientData for SliceData<'_> {
    fn download_len(&self) -> usize {
        self.len
    }

    fn read(&mut self, offset: usize, buf: &mut [u8]) -> usize {
        let src = self.as_slice().get(offset..).unwrap_or(&[]);
        let n = src.len().min(buf.len());
        buf[..n].copy_from_slice(&src[..n]);
        n
    }

    fn write(&mut self, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        let dst = self.buf.get_mut(offset..offset.saturating_add(data.len())).ok_or(AbortCode::OutOfMemory)?;
        dst.copy_from_slice(data);
        self.len = self.len.max(offset + data.len());
        Ok(())
    }
}

/// Why a transfer failed.
///
/// ```
/// use canopen_core::sdo::client::ClientError;
/// use canopen_core::od::AbortCode;
/// assert_eq!(ClientError::Local(AbortCode::SdoTimeout).code(), 0x0504_0000);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ClientError {
    /// The server sent an abort with this code.
    Server(u32),
    /// The client aborted (and sent the abort frame) with this code.
    Local(AbortCode),
}

impl ClientError {
    /// The abort code, whoever sent it.
    ///
    /// ```
    /// # use canopen_core::sdo::client::ClientError;
    /// assert_eq!(ClientError::Server(0x0602_0000).code(), 0x0602_0000);
    /// ```
    pub const fn code(self) -> u32 {
        match self {
            ClientError::Server(c) => c,
            ClientError::Local(c) => c.code(),
        }
    }
}

/// ```
/// use canopen_core::{abort::AbortCode, sdo::client::ClientError};
/// assert_eq!(ClientError::Server(0x0602_0000).to_string(), "the server aborted: 06020000h (ObjectDoesNotExist)");
/// assert_eq!(ClientError::Server(0x1234_5678).to_string(), "the server aborted: 12345678h");
/// assert_eq!(ClientError::Local(AbortCode::SdoTimeout).to_string(), "the client aborted: 05040000h (SdoTimeout)");
/// ```
impl core::fmt::Display for ClientError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            ClientError::Server(c) => match AbortCode::from_code(*c) {
                Some(a) => write!(f, "the server aborted: {a}"),
                None => write!(f, "the server aborted: {c:08X}h"),
            },
            ClientError::Local(a) => write!(f, "the client aborted: {a}"),
        }
    }
}

impl core::error::Error for ClientError {}

/// The end of a transfer.
///
/// ```
/// use canopen_core::sdo::client::ClientEvent;
/// assert_eq!(ClientEvent::Done { len: 3 }, ClientEvent::Done { len: 3 });
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ClientEvent {
    /// Completed; `len` bytes were transferred.
    Done {
        /// Bytes transferred.
        len: usize,
    },
    /// Aborted by either side.
    Failed(ClientError),
}

/// The client is already running a transfer.
///
/// ```
/// use canopen_core::sdo::client::Busy;
/// let _ = Busy;
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Busy;

/// ```
/// assert_eq!(canopen_core::sdo::client::Busy.to_string(), "the SDO client is already running a transfer");
/// ```
impl core::fmt::Display for Busy {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("the SDO client is already running a transfer")
    }
}

impl core::error::Error for Busy {}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    Idle,
    DownloadInit,
    DownloadSegment,
    UploadInit,
    UploadSegment,
    BlockDownloadInit,
    /// Producing sub-block segments (`sent` < blksize and not past the end).
    BlockDownloadSending,
    BlockDownloadAck,
    BlockDownloadEnd,
    BlockUploadInit,
    BlockUploadReceiving,
    BlockUploadEnd,
}

/// One SDO client channel. See the [module docs](self).
///
/// ```
/// use canopen_core::sdo::{SdoClient, SdoClientParams};
/// use canopen_core::NodeId;
/// let c = SdoClient::new(SdoClientParams::for_server(NodeId::new(3).unwrap()));
/// assert!(c.is_idle());
/// ```
#[derive(Debug, Clone)]
pub struct SdoClient {
    params: SdoClientParams,
    timeout: Duration,
    deadline: Option<Instant>,
    phase: Phase,
    mux: Multiplexer,
    pending: Option<[u8; 8]>,
    /// Expedited download: 0 = not expedited, 1 = initiate still to build, 2 = initiate sent.
    expedited: u8,
    toggle: bool,
    /// Download: bytes acknowledged / upload: bytes written to the data.
    offset: u32,
    size: Option<u32>,
    crc_on: bool,
    crc: Crc16,
    crc_len: u32,
    blksize: u8,
    pst: u8,
    sent: u8,
    expected: u8,
    held_seqno: u8,
    held: [u8; 7],
}

impl SdoClient {
    /// An idle client with the [default time-out](super::DEFAULT_TIMEOUT).
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoClient, SdoClientParams};
    /// # use canopen_core::NodeId;
    /// assert!(SdoClient::new(SdoClientParams::for_server(NodeId::new(1).unwrap())).poll_timeout().is_none());
    /// ```
    pub const fn new(params: SdoClientParams) -> Self {
        SdoClient {
            params,
            timeout: super::DEFAULT_TIMEOUT,
            deadline: None,
            phase: Phase::Idle,
            mux: Multiplexer::new(0, 0),
            pending: None,
            expedited: 0,
            toggle: false,
            offset: 0,
            size: None,
            crc_on: false,
            crc: Crc16::new(),
            crc_len: 0,
            blksize: MAX_BLKSIZE,
            pst: 0,
            sent: 0,
            expected: 1,
            held_seqno: 0,
            held: [0; 7],
        }
    }

    /// Sets the time-out (zero disables it).
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoClient, SdoClientParams};
    /// # use canopen_core::{Duration, NodeId};
    /// let c = SdoClient::new(SdoClientParams::for_server(NodeId::new(1).unwrap())).with_timeout(Duration::from_millis(50));
    /// assert!(c.is_idle());
    /// ```
    pub const fn with_timeout(mut self, timeout: Duration) -> Self {
        self.timeout = timeout;
        self
    }

    /// The channel parameters.
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoClient, SdoClientParams};
    /// # use canopen_core::NodeId;
    /// let p = SdoClientParams::for_server(NodeId::new(1).unwrap());
    /// assert_eq!(SdoClient::new(p).params(), &p);
    /// ```
    pub const fn params(&self) -> &SdoClientParams {
        &self.params
    }

    /// Whether no transfer is running (a final frame may still wait in [`poll_transmit`](Self::poll_transmit)).
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoClient, SdoClientParams};
    /// # use canopen_core::NodeId;
    /// assert!(SdoClient::new(SdoClientParams::for_server(NodeId::new(1).unwrap())).is_idle());
    /// ```
    pub const fn is_idle(&self) -> bool {
        matches!(self.phase, Phase::Idle)
    }

    /// The deadline of the running transfer.
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoClient, SdoClientParams};
    /// # use canopen_core::NodeId;
    /// assert_eq!(SdoClient::new(SdoClientParams::for_server(NodeId::new(1).unwrap())).poll_timeout(), None);
    /// ```
    pub const fn poll_timeout(&self) -> Option<Instant> {
        self.deadline
    }

    fn touch(&mut self, now: Instant) {
        self.deadline = if self.timeout.is_zero() || self.is_idle() { None } else { Some(now + self.timeout) };
    }

    fn begin(&mut self, now: Instant, mux: Multiplexer, phase: Phase, frame: [u8; 8]) {
        *self = SdoClient { params: self.params, timeout: self.timeout, ..SdoClient::new(self.params) };
        self.mux = mux;
        self.phase = phase;
        self.pending = Some(frame);
        self.touch(now);
    }

    /// Starts writing `len` bytes (read from the [`ClientData`] as frames go out) to `mux`.
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoClient, SdoClientParams};
    /// # use canopen_core::sdo::client::{Mode, SliceData};
    /// # use canopen_core::wire::sdo::Multiplexer;
    /// # use canopen_core::{Instant, NodeId};
    /// let mut c = SdoClient::new(SdoClientParams::for_server(NodeId::new(3).unwrap()));
    /// let mut b = *b"123456789";
    /// let mut d = SliceData::download(&mut b);
    /// c.start_download(Instant::ZERO, Multiplexer::new(0x2000, 0), 9, Mode::Segmented).unwrap();
    /// assert_eq!(c.poll_transmit(Instant::ZERO, &mut d), Some([0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0]));
    /// ```
    pub fn start_download(&mut self, now: Instant, mux: Multiplexer, len: usize, mode: Mode) -> Result<(), Busy> {
        if !self.is_idle() {
            return Err(Busy);
        }
        let size = u32::try_from(len).map_err(|_| Busy)?;
        match mode {
            Mode::Block { crc, .. } => {
                let f = ClientRequest::BlockDownloadInitiate { mux, crc, size: Some(size) }.emit();
                self.begin(now, mux, Phase::BlockDownloadInit, f);
                self.crc_on = crc;
            }
            Mode::Auto if (1..=4).contains(&len) => {
                // the data goes into the frame in poll_transmit
                let f =
                    ClientRequest::InitiateDownload { mux, data: InitiateData::Segmented { size: Some(size) } }.emit();
                self.begin(now, mux, Phase::DownloadInit, f);
                self.pending = None;
                self.expedited = 1; // the initiate is built from the data in poll_transmit
            }
            _ => {
                let f =
                    ClientRequest::InitiateDownload { mux, data: InitiateData::Segmented { size: Some(size) } }.emit();
                self.begin(now, mux, Phase::DownloadInit, f);
            }
        }
        self.size = Some(size);
        Ok(())
    }

    /// Starts reading `mux`; the bytes go to the [`ClientData`] passed to
    /// [`handle_response`](Self::handle_response).
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoClient, SdoClientParams};
    /// # use canopen_core::sdo::client::{Mode, SliceData};
    /// # use canopen_core::wire::sdo::Multiplexer;
    /// # use canopen_core::{Instant, NodeId};
    /// let mut c = SdoClient::new(SdoClientParams::for_server(NodeId::new(3).unwrap()));
    /// let mut b = [0u8; 32];
    /// let mut d = SliceData::upload(&mut b);
    /// c.start_upload(Instant::ZERO, Multiplexer::new(0x2000, 0), Mode::Block { crc: true, blksize: 127, pst: 0 }).unwrap();
    /// assert_eq!(c.poll_transmit(Instant::ZERO, &mut d), Some([0xA4, 0x00, 0x20, 0x00, 0x7F, 0x00, 0, 0]));
    /// ```
    pub fn start_upload(&mut self, now: Instant, mux: Multiplexer, mode: Mode) -> Result<(), Busy> {
        if !self.is_idle() {
            return Err(Busy);
        }
        match mode {
            Mode::Block { crc, blksize, pst } => {
                let blksize = blksize.clamp(1, MAX_BLKSIZE);
                let f = ClientRequest::BlockUploadInitiate { mux, crc, blksize, pst }.emit();
                self.begin(now, mux, Phase::BlockUploadInit, f);
                self.crc_on = crc;
                self.blksize = blksize;
                self.pst = pst;
            }
            _ => self.begin(now, mux, Phase::UploadInit, ClientRequest::InitiateUpload { mux }.emit()),
        }
        Ok(())
    }

    /// Aborts the running transfer with `code` (the abort frame comes out of
    /// [`poll_transmit`](Self::poll_transmit)).
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoClient, SdoClientParams};
    /// # use canopen_core::od::AbortCode;
    /// # use canopen_core::NodeId;
    /// let mut c = SdoClient::new(SdoClientParams::for_server(NodeId::new(3).unwrap()));
    /// assert_eq!(c.abort(AbortCode::GeneralError), None); // nothing running
    /// ```
    pub fn abort(&mut self, code: AbortCode) -> Option<ClientEvent> {
        if self.is_idle() {
            return None;
        }
        Some(self.fail_local(code))
    }

    fn fail_local(&mut self, code: AbortCode) -> ClientEvent {
        self.pending = Some(abort_frame(self.mux, code.code()));
        self.phase = Phase::Idle;
        self.deadline = None;
        ClientEvent::Failed(ClientError::Local(code))
    }

    fn done(&mut self, len: u32) -> ClientEvent {
        self.phase = Phase::Idle;
        self.deadline = None;
        ClientEvent::Done { len: len as usize }
    }

    /// Aborts with 0504 0000h once the deadline has passed (SDO-31).
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoClient, SdoClientParams};
    /// # use canopen_core::{Instant, NodeId};
    /// let mut c = SdoClient::new(SdoClientParams::for_server(NodeId::new(3).unwrap()));
    /// assert_eq!(c.handle_timeout(Instant::from_millis(10_000)), None);
    /// ```
    pub fn handle_timeout(&mut self, now: Instant) -> Option<ClientEvent> {
        match self.deadline {
            Some(d) if now >= d && !self.is_idle() => Some(self.fail_local(AbortCode::SdoTimeout)),
            _ => None,
        }
    }

    /// The next frame to send, if any.
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoClient, SdoClientParams};
    /// # use canopen_core::sdo::client::SliceData;
    /// # use canopen_core::{Instant, NodeId};
    /// let mut c = SdoClient::new(SdoClientParams::for_server(NodeId::new(3).unwrap()));
    /// assert_eq!(c.poll_transmit(Instant::ZERO, &mut SliceData::upload(&mut [])), None);
    /// ```
    pub fn poll_transmit<D: ClientData + ?Sized>(&mut self, now: Instant, data: &mut D) -> Option<[u8; 8]> {
        if let Some(f) = self.pending.take() {
            return Some(f);
        }
        match self.phase {
            Phase::DownloadInit if self.expedited == 1 => {
                self.expedited = 2;
                let mut d = [0u8; 4];
                let len = (self.size.unwrap_or(0) as usize).min(4);
                let n = data.read(0, &mut d[..len]);
                let e = Expedited::new(d.get(..n).unwrap_or(&[]))?;
                Some(ClientRequest::InitiateDownload { mux: self.mux, data: InitiateData::Expedited(e) }.emit())
            }
            Phase::BlockDownloadSending => {
                let size = self.size.unwrap_or(0);
                let off = self.offset.saturating_add(u32::from(self.sent) * 7);
                let want = size.saturating_sub(off).min(7) as usize;
                let mut seg = BlockSegment { last: false, seqno: self.sent + 1, data: [0; 7] };
                let n = data.read(off as usize, &mut seg.data[..want]) as u32;
                let end = off + n;
                if self.crc_on && end > self.crc_len {
                    let skip = self.crc_len.saturating_sub(off) as usize;
                    self.crc.update(seg.data.get(skip..n as usize).unwrap_or(&[]));
                }
                self.crc_len = self.crc_len.max(end);
                seg.last = end >= size;
                self.sent = seg.seqno;
                if seg.last || self.sent >= self.blksize {
                    self.phase = Phase::BlockDownloadAck;
                }
                self.touch(now);
                Some(seg.emit())
            }
            _ => None,
        }
    }

    /// Handles a frame received on the client's rx COB-ID.
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoClient, SdoClientParams};
    /// # use canopen_core::sdo::client::{ClientError, ClientEvent, Mode, SliceData};
    /// # use canopen_core::wire::sdo::Multiplexer;
    /// # use canopen_core::{Instant, NodeId};
    /// let mut c = SdoClient::new(SdoClientParams::for_server(NodeId::new(3).unwrap()));
    /// let mut b = [0u8; 4];
    /// let mut d = SliceData::upload(&mut b);
    /// c.start_upload(Instant::ZERO, Multiplexer::new(0x5000, 0), Mode::Auto).unwrap();
    /// c.poll_transmit(Instant::ZERO, &mut d);
    /// // Object 5000h does not exist: 80 00 50 00 00 00 02 06 (0602 0000h)
    /// let ev = c.handle_response(Instant::ZERO, &[0x80, 0x00, 0x50, 0x00, 0x00, 0x00, 0x02, 0x06], &mut d);
    /// assert_eq!(ev, Some(ClientEvent::Failed(ClientError::Server(0x0602_0000))));
    /// ```
    pub fn handle_response<D: ClientData + ?Sized>(
        &mut self,
        now: Instant,
        frame: &[u8],
        data: &mut D,
    ) -> Option<ClientEvent> {
        let Ok(b) = <&[u8; 8]>::try_from(frame) else { return None };
        if self.is_idle() {
            return None;
        }
        let ev = self.dispatch(b, data);
        self.touch(now);
        ev
    }

    fn dispatch<D: ClientData + ?Sized>(&mut self, b: &[u8; 8], data: &mut D) -> Option<ClientEvent> {
        if b[0] == 0x80 {
            self.phase = Phase::Idle;
            self.pending = None;
            return Some(ClientEvent::Failed(ClientError::Server(u32::from_le_bytes([b[4], b[5], b[6], b[7]]))));
        }
        if self.phase == Phase::BlockUploadReceiving {
            return self.block_segment(b, data);
        }
        if self.phase == Phase::BlockUploadEnd && b[0] == 0x80 | self.held_seqno && b[1..8] == self.held {
            return None; // CAN duplicate of the last segment
        }
        let Ok(rsp) = ServerResponse::parse(b) else {
            return Some(self.fail_local(AbortCode::InvalidCommandSpecifier));
        };
        let r = match (self.phase, rsp) {
            (_, ServerResponse::Abort { code, .. }) => {
                self.phase = Phase::Idle;
                self.pending = None;
                return Some(ClientEvent::Failed(ClientError::Server(code)));
            }
            (Phase::DownloadInit, ServerResponse::InitiateDownload { mux }) if mux == self.mux => {
                if self.expedited == 2 {
                    return Some(self.done(self.size.unwrap_or(0))); // expedited: confirmed (SDO-17)
                }
                self.phase = Phase::DownloadSegment;
                self.send_download_segment(data);
                Ok(None)
            }
            (Phase::DownloadSegment, ServerResponse::DownloadSegment { toggle }) => {
                if toggle != self.toggle {
                    Err(AbortCode::ToggleNotAlternated)
                } else if self.offset >= self.size.unwrap_or(0) && self.sent == 1 {
                    Ok(Some(self.done(self.offset)))
                } else {
                    self.toggle = !self.toggle;
                    self.send_download_segment(data);
                    Ok(None)
                }
            }
            (Phase::UploadInit | Phase::BlockUploadInit, ServerResponse::InitiateUpload { mux, data: init })
                if mux == self.mux =>
            {
                self.upload_initiated(init, data)
            }
            (Phase::UploadSegment, ServerResponse::UploadSegment(seg)) => self.upload_segment(seg, data),
            (Phase::BlockDownloadInit, ServerResponse::BlockDownloadInitiate { mux, crc, blksize })
                if mux == self.mux =>
            {
                if blksize == 0 || blksize > MAX_BLKSIZE {
                    Err(AbortCode::InvalidBlockSize) // blksize 0 or > 127 from a server: 0504 0002h (SDO-36, SDO-50)
                } else {
                    self.crc_on &= crc;
                    self.blksize = blksize;
                    self.phase = Phase::BlockDownloadSending;
                    Ok(None)
                }
            }
            (
                Phase::BlockDownloadSending | Phase::BlockDownloadAck,
                ServerResponse::BlockDownloadAck { ackseq, blksize },
            ) => self.block_download_ack(ackseq, blksize),
            (Phase::BlockDownloadEnd, ServerResponse::BlockDownloadEnd) => Ok(Some(self.done(self.size.unwrap_or(0)))),
            (Phase::BlockUploadInit, ServerResponse::BlockUploadInitiate { mux, crc, size }) if mux == self.mux => {
                self.crc_on &= crc;
                self.size = size;
                self.phase = Phase::BlockUploadReceiving;
                self.pending = Some(ClientRequest::BlockUploadStart.emit());
                Ok(None)
            }
            (Phase::BlockUploadEnd, ServerResponse::BlockUploadEnd { unused, crc }) => {
                self.block_upload_end(unused, crc, data)
            }
            _ => Err(AbortCode::InvalidCommandSpecifier),
        };
        match r {
            Ok(ev) => ev,
            Err(code) => Some(self.fail_local(code)),
        }
    }

    fn send_download_segment<D: ClientData + ?Sized>(&mut self, data: &mut D) {
        let size = self.size.unwrap_or(0);
        let mut d = [0u8; 7];
        let want = size.saturating_sub(self.offset).min(7) as usize;
        let n = data.read(self.offset as usize, &mut d[..want]);
        self.offset += n as u32;
        let last = self.offset >= size || n < want;
        self.sent = u8::from(last);
        self.pending = Some(ClientRequest::DownloadSegment(Segment::new(self.toggle, last, &d[..n])).emit());
    }

    fn upload_initiated<D: ClientData + ?Sized>(
        &mut self,
        init: InitiateData,
        data: &mut D,
    ) -> Result<Option<ClientEvent>, AbortCode> {
        match init {
            InitiateData::Expedited(e) => {
                data.write(0, e.bytes())?;
                Ok(Some(self.done(u32::from(e.len))))
            }
            InitiateData::Segmented { size } => {
                self.size = size;
                self.phase = Phase::UploadSegment;
                self.pending = Some(ClientRequest::UploadSegment { toggle: false }.emit());
                Ok(None)
            }
        }
    }

    fn upload_segment<D: ClientData + ?Sized>(
        &mut self,
        seg: Segment,
        data: &mut D,
    ) -> Result<Option<ClientEvent>, AbortCode> {
        if seg.toggle != self.toggle {
            return Err(AbortCode::ToggleNotAlternated);
        }
        let end = self.offset.saturating_add(u32::from(seg.len));
        if self.size.is_some_and(|s| end > s) {
            return Err(AbortCode::LengthTooHigh);
        }
        data.write(self.offset as usize, seg.bytes())?;
        self.offset = end;
        if seg.last {
            if self.size.is_some_and(|s| end != s) {
                return Err(AbortCode::LengthTooLow);
            }
            return Ok(Some(self.done(end)));
        }
        self.toggle = !self.toggle;
        self.pending = Some(ClientRequest::UploadSegment { toggle: self.toggle }.emit());
        Ok(None)
    }

    /// The server's acknowledge of a sub-block (SDO-39, SDO-40): go back to the segment after ackseq.
    ///
    /// An ackseq above the segments sent in this sub-block cannot answer it: either it is a stale
    /// acknowledge (a CAN-level duplicate of an earlier one that arrived after the client moved on), or an
    /// earlier stale one was already taken for a newer sub-block and the two sides count sub-blocks
    /// differently. The client cannot tell which, so it aborts with 0504 0003h (SDO-50): ignoring it measured
    /// worse (wrong data committed in 13 of 3,000 lossy-bus seeds instead of 4), because the abort is what
    /// stops a transfer whose sides are out of step. A stale acknowledge whose ackseq fits the current
    /// sub-block is byte-identical to a current one (with blksize 1 every complete sub-block is acknowledged
    /// `A2 01 01 00 00 00 00 00`), so no client can tell those apart: the CRC (SDO-48, SDO-49) is what turns
    /// them into abort 0504 0004h instead of wrong data.
    fn block_download_ack(&mut self, ackseq: u8, blksize: u8) -> Result<Option<ClientEvent>, AbortCode> {
        if ackseq > self.sent {
            return Err(AbortCode::InvalidSequenceNumber);
        }
        if blksize == 0 || blksize > MAX_BLKSIZE {
            return Err(AbortCode::InvalidBlockSize);
        }
        let size = self.size.unwrap_or(0);
        self.offset = self.offset.saturating_add(u32::from(ackseq) * 7);
        self.sent = 0;
        self.blksize = blksize;
        if ackseq >= 1 && self.offset >= size {
            let crc = if self.crc_on { self.crc.get() } else { 0 };
            self.pending = Some(ClientRequest::BlockDownloadEnd { unused: 7 - last_segment_len(size), crc }.emit());
            self.phase = Phase::BlockDownloadEnd;
        } else {
            self.phase = Phase::BlockDownloadSending;
        }
        Ok(None)
    }

    fn flush<D: ClientData + ?Sized>(&mut self, bytes: &[u8], data: &mut D) -> Result<(), AbortCode> {
        let end = self.offset.saturating_add(bytes.len() as u32);
        if self.size.is_some_and(|s| end > s) {
            return Err(AbortCode::LengthTooHigh);
        }
        data.write(self.offset as usize, bytes)?;
        if self.crc_on {
            self.crc.update(bytes);
        }
        self.offset = end;
        self.held_seqno = 0;
        Ok(())
    }

    fn block_segment<D: ClientData + ?Sized>(&mut self, b: &[u8; 8], data: &mut D) -> Option<ClientEvent> {
        let last = b[0] & 0x80 != 0;
        let seqno = b[0] & 0x7F;
        if seqno == 0 || seqno > self.blksize {
            return Some(self.fail_local(AbortCode::InvalidSequenceNumber));
        }
        if seqno != self.expected {
            if self.held_seqno == seqno && b[1..8] == self.held {
                return None;
            }
            if last || seqno == self.blksize {
                let ackseq = self.expected - 1;
                self.expected = 1;
                self.pending = Some(ClientRequest::BlockUploadAck { ackseq, blksize: self.blksize }.emit());
            }
            return None;
        }
        if self.held_seqno != 0 {
            let held = self.held;
            if let Err(code) = self.flush(&held, data) {
                return Some(self.fail_local(code));
            }
        }
        self.held.copy_from_slice(&b[1..8]);
        self.held_seqno = seqno;
        self.expected = seqno + 1;
        if last || seqno == self.blksize {
            self.expected = 1;
            if last {
                self.phase = Phase::BlockUploadEnd;
            }
            self.pending = Some(ClientRequest::BlockUploadAck { ackseq: seqno, blksize: self.blksize }.emit());
        }
        None
    }

    fn block_upload_end<D: ClientData + ?Sized>(
        &mut self,
        unused: u8,
        crc: u16,
        data: &mut D,
    ) -> Result<Option<ClientEvent>, AbortCode> {
        let held = self.held;
        let len = usize::from(7 - unused.min(7));
        self.flush(held.get(..len).unwrap_or(&[]), data)?;
        if self.crc_on && self.crc.get() != crc {
            return Err(AbortCode::CrcError);
        }
        if self.size.is_some_and(|s| s != self.offset) {
            return Err(AbortCode::LengthTooLow);
        }
        self.pending = Some(ClientRequest::BlockUploadEnd.emit());
        Ok(Some(self.done(self.offset)))
    }
}
