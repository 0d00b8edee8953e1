//! The SDO server: a sans-IO state machine serving an [`ObjectDictionary`] (CiA 301 §7.2.4).
//!
//! Implements CHECKLIST SDO-01..SDO-51 (SDO-52 partly: out of memory is passed through from the OD, no
//! 060A 0023h because each server has its own channel), SDO-53/54/55 as [`SdoServerParams`] (the lead wires
//! them into 1200h–127Fh), ABORT-01..ABORT-11, ABORT-16..ABORT-31 as far as the OD reports them.
//! Not yet: SDO in NMT Stopped is the node's business (NMT-18: the node must not feed frames then).
//!
//! # Driving it
//!
//! - [`SdoServer::handle_request`] for every frame received on the server's rx COB-ID; the [`Response`] says
//!   which frame to send (on the tx COB-ID), if any, and what happened ([`SdoEvent`]).
//! - [`SdoServer::poll_transmit`] while [`SdoServer::wants_transmit`]: during a block upload the server
//!   produces a whole sub-block, one frame per call, so the node pulls frames only when its bounded TX queue
//!   has room.
//! - [`SdoServer::poll_timeout`] / [`SdoServer::handle_timeout`]: the protocol time-out (SDO-31, 0504 0000h).
//!
//! # Data path, RAM
//!
//! Data moves straight between frames and the OD: fixed-size values (≤ 8 bytes) are collected in an 8-byte
//! scratch and written atomically with [`ObjectDictionary::write`]; everything else is streamed with
//! `begin_write`/`write_chunk`/`end_write` (and `abort_write` when a transfer is abandoned); uploads read
//! 1..7 bytes at a time with [`ObjectDictionary::read`] at an offset. Block download writes each in-order
//! segment to the OD as soon as the next one arrives: only the last 7 bytes are held back, because the number
//! of valid bytes in the last segment is only known from the end frame (SDO-41). The whole server is
//! [`SdoServer::RAM_BYTES`] = 80 bytes or less (`size_of::<SdoServer>()` is 80 on x86-64, asserted in a unit
//! test; the client is 88). No other RAM: no buffer of the object's size, no sub-block buffer.
//!
//! # Choices where the spec leaves room
//!
//! - **DLC ≠ 8** (CAN-07, SDO-02): the frame is ignored, no abort (as CANopenNode does). A master that sends
//!   short SDO frames is not conformant and an abort would tear down a transfer for a frame we cannot
//!   interpret anyway.
//! - **Toggle error** (SDO-30): abort 0503 0000h rather than silently ignoring the repeated segment, so a
//!   client that lost sync learns it at once instead of at its time-out.
//! - **A frame that is not valid in the current state** (e.g. a download segment while idle): abort
//!   0504 0001h (SDO-09). An abort received is never answered (SDO-33), also when idle.
//! - **New initiate during a transfer** (SDO-29): the old transfer is abandoned (`abort_write`) without an
//!   abort frame and the new one is served. During a block download sub-block every frame other than the
//!   abort frame `80h` is a segment (byte 0 is c ‖ seqno there), so an initiate cannot be recognised then.
//! - **Block sequence numbers** (SDO-50): seqno 0 or > blksize → 0504 0003h. An out-of-order segment is
//!   discarded; the server acknowledges the last in-order one when the segment with seqno = blksize or c = 1
//!   arrives (go-back-n, VECTORS 8.2). An exact repeat of the last accepted segment (a CAN-level duplicate)
//!   is ignored without an acknowledgement.
//! - **CRC** (SDO-48, INTEROP): the server answers `sc = cc` in both directions.
//! - **Block upload acknowledgement** with ackseq > segments sent → 0504 0003h; blksize outside 1..127 →
//!   0504 0002h.
//! - **Expedited download without size** (22h, SDO-13): the length is the object's fixed size when that is
//!   ≤ 4, otherwise 4.
//!
//! ```
//! use canopen_core::sdo::{SdoServer, SdoServerParams, SdoEvent};
//! use canopen_core::od::{AbortCode, Access, DataType, ObjectDictionary, PdoMapping, SubInfo};
//! use canopen_core::{Instant, NodeId};
//!
//! struct Od(u32);
//! impl ObjectDictionary for Od {
//!     fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
//!         match (index, sub) {
//!             (0x607A, 0) => Ok(SubInfo { data_type: DataType::Integer32, access: Access::Rw, pdo: PdoMapping::No, size: 4 }),
//!             _ => Err(AbortCode::ObjectDoesNotExist),
//!         }
//!     }
//!     fn read(&self, _: u16, _: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
//!         let v = self.0.to_le_bytes();
//!         let src = v.get(offset..).unwrap_or(&[]);
//!         let n = src.len().min(buf.len());
//!         buf[..n].copy_from_slice(&src[..n]);
//!         Ok(n)
//!     }
//!     fn write(&mut self, _: u16, _: u8, data: &[u8]) -> Result<(), AbortCode> {
//!         self.0 = u32::from_le_bytes(data.try_into().map_err(|_| AbortCode::LengthMismatch)?);
//!         Ok(())
//!     }
//! }
//!
//! let mut od = Od(0);
//! let mut server = SdoServer::new(SdoServerParams::default_server(NodeId::new(3).unwrap()));
//! // V-SDO-01: write 607Ah:00 = 1000
//! let r = server.handle_request(Instant::ZERO, &[0x23, 0x7A, 0x60, 0x00, 0xE8, 0x03, 0x00, 0x00], &mut od);
//! assert_eq!(r.frame, Some([0x60, 0x7A, 0x60, 0x00, 0, 0, 0, 0]));
//! assert_eq!(r.event, Some(SdoEvent::Written { index: 0x607A, sub: 0 }));
//! assert_eq!(od.0, 1000);
//! ```

use super::block::{last_segment_len, Crc16};
use crate::cob::{CobIdEntry, FunctionCode};
use crate::od::{AbortCode, ObjectDictionary};
use crate::time::{Duration, Instant};
use crate::wire::sdo::{
    abort_frame, BlockSegment, ClientRequest, Expedited, InitiateData, Multiplexer, Segment, ServerResponse,
    MAX_BLKSIZE,
};
use crate::NodeId;

/// 1200h–127Fh-style parameters of one server SDO (SDO-53..SDO-55).
///
/// ```
/// use canopen_core::sdo::SdoServerParams;
/// use canopen_core::NodeId;
/// let p = SdoServerParams::default_server(NodeId::new(5).unwrap());
/// assert_eq!(p.cob_rx.raw(), 0x605);
/// assert_eq!(p.cob_tx.raw(), 0x585);
/// assert!(SdoServerParams::DISABLED.rx_cob_id().is_none());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SdoServerParams {
    /// Sub 01h: COB-ID client → server (the server receives on it).
    pub cob_rx: CobIdEntry,
    /// Sub 02h: COB-ID server → client (the server sends on it).
    pub cob_tx: CobIdEntry,
    /// Sub 03h: node-ID of the client (optional, additional servers only).
    pub client_node: Option<NodeId>,
}

impl SdoServerParams {
    /// An additional server (1201h–127Fh) before configuration: both COB-IDs invalid (bit 31 = 1, SDO-54).
    ///
    /// ```
    /// # use canopen_core::sdo::SdoServerParams;
    /// assert!(SdoServerParams::DISABLED.cob_rx.bit31());
    /// ```
    pub const DISABLED: SdoServerParams = SdoServerParams {
        cob_rx: CobIdEntry::from_raw(CobIdEntry::BIT31),
        cob_tx: CobIdEntry::from_raw(CobIdEntry::BIT31),
        client_node: None,
    };

    /// 1200h: requests on 600h + node, responses on 580h + node (SDO-01, SDO-53).
    ///
    /// ```
    /// # use canopen_core::sdo::SdoServerParams;
    /// # use canopen_core::NodeId;
    /// assert_eq!(SdoServerParams::default_server(NodeId::new(3).unwrap()).rx_cob_id(), Some(0x603));
    /// ```
    pub const fn default_server(node: NodeId) -> Self {
        SdoServerParams {
            cob_rx: CobIdEntry::new(false, false, FunctionCode::SdoRx.cob_id(node)),
            cob_tx: CobIdEntry::new(false, false, FunctionCode::SdoTx.cob_id(node)),
            client_node: None,
        }
    }

    /// Whether the SDO exists: bit 31 clear in both COB-IDs (SDO-55). 29-bit frames are not supported.
    ///
    /// ```
    /// # use canopen_core::sdo::SdoServerParams;
    /// assert!(!SdoServerParams::DISABLED.is_valid());
    /// ```
    pub const fn is_valid(&self) -> bool {
        !self.cob_rx.bit31() && !self.cob_tx.bit31() && !self.cob_rx.is_extended() && !self.cob_tx.is_extended()
    }

    /// The CAN-ID the server receives on, if valid.
    ///
    /// ```
    /// # use canopen_core::sdo::SdoServerParams;
    /// # use canopen_core::NodeId;
    /// assert_eq!(SdoServerParams::default_server(NodeId::new(1).unwrap()).rx_cob_id(), Some(0x601));
    /// ```
    pub const fn rx_cob_id(&self) -> Option<u16> {
        if self.is_valid() {
            Some(self.cob_rx.can_id())
        } else {
            None
        }
    }

    /// The CAN-ID the server sends on, if valid.
    ///
    /// ```
    /// # use canopen_core::sdo::SdoServerParams;
    /// # use canopen_core::NodeId;
    /// assert_eq!(SdoServerParams::default_server(NodeId::new(1).unwrap()).tx_cob_id(), Some(0x581));
    /// ```
    pub const fn tx_cob_id(&self) -> Option<u16> {
        if self.is_valid() {
            Some(self.cob_tx.can_id())
        } else {
            None
        }
    }
}

/// What happened while handling a frame, for the node to turn into an application event.
///
/// ```
/// use canopen_core::sdo::SdoEvent;
/// let e = SdoEvent::Written { index: 0x2000, sub: 0 };
/// assert_ne!(e, SdoEvent::Written { index: 0x2000, sub: 1 });
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SdoEvent {
    /// A download completed: the object now holds the new value (apply side effects).
    Written {
        /// Index.
        index: u16,
        /// Sub-index.
        sub: u8,
    },
    /// An upload completed (the last segment or the block end was confirmed).
    Uploaded {
        /// Index.
        index: u16,
        /// Sub-index.
        sub: u8,
    },
    /// The server aborted the transfer with `code` (the abort frame is in the same [`Response`]).
    Aborted {
        /// Index of the abort frame.
        index: u16,
        /// Sub-index of the abort frame.
        sub: u8,
        /// The reason.
        code: AbortCode,
    },
    /// The client aborted the transfer (SDO-33: not answered).
    AbortReceived {
        /// Index from the abort frame.
        index: u16,
        /// Sub-index from the abort frame.
        sub: u8,
        /// The raw code (a peer may send codes outside Table 22).
        code: u32,
    },
}

/// The outcome of one call: a frame to send on the tx COB-ID (8 bytes, SDO-02) and/or an event.
///
/// ```
/// use canopen_core::sdo::Response;
/// assert_eq!(Response::NONE.frame, None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Response {
    /// The frame to send, if any.
    pub frame: Option<[u8; 8]>,
    /// What happened, if anything the application may care about.
    pub event: Option<SdoEvent>,
}

impl Response {
    /// Nothing to send, nothing happened (ignored frame, abort received while idle, ...).
    ///
    /// ```
    /// # use canopen_core::sdo::Response;
    /// assert!(Response::NONE.event.is_none());
    /// ```
    pub const NONE: Response = Response { frame: None, event: None };

    const fn send(frame: [u8; 8]) -> Response {
        Response { frame: Some(frame), event: None }
    }
}

/// The server's state as seen from outside (for tests, models and diagnostics).
///
/// ```
/// use canopen_core::sdo::{SdoServer, SdoServerParams, ServerState};
/// let s = SdoServer::new(SdoServerParams::DISABLED);
/// assert_eq!(s.state(), ServerState::Idle);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ServerState {
    /// No transfer.
    Idle,
    /// Segmented download: waiting for a download segment.
    Downloading,
    /// Segmented upload: waiting for an upload segment request.
    Uploading,
    /// Block download: receiving sub-block segments.
    BlockDownloadSubBlock,
    /// Block download: the last segment was acknowledged, waiting for the end frame.
    BlockDownloadEnd,
    /// Block upload: initiate answered, waiting for "start upload" (A3h).
    BlockUploadStart,
    /// Block upload: sub-block frames are waiting in [`SdoServer::poll_transmit`].
    BlockUploadSending,
    /// Block upload: sub-block sent, waiting for the acknowledge.
    BlockUploadAck,
    /// Block upload: end frame sent, waiting for A1h.
    BlockUploadEnd,
}

/// Where downloaded bytes go.
#[derive(Debug, Clone, Copy)]
enum Sink {
    /// A fixed-size value of at most 8 bytes, written atomically at the end.
    Scratch([u8; 8]),
    /// Streamed into the OD (`begin_write` was called).
    Stream,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum UploadPhase {
    Start,
    Sending,
    WaitAck,
    WaitEnd,
}

#[derive(Debug, Clone, Copy)]
enum State {
    Idle,
    Download { mux: Multiplexer, toggle: bool, offset: u32, size: Option<u32>, sink: Sink },
    Upload { mux: Multiplexer, toggle: bool, offset: u32, size: u32 },
    BlockDownload(BlockDownload),
    BlockUpload(BlockUpload),
}

#[derive(Debug, Clone, Copy)]
struct BlockDownload {
    mux: Multiplexer,
    sink: Sink,
    /// Bytes written to the sink so far (everything before the held segment).
    offset: u32,
    size: Option<u32>,
    crc: Crc16,
    crc_on: bool,
    /// Next seqno expected in the current sub-block.
    expected: u8,
    /// Seqno of the held segment (0 = nothing held).
    held_seqno: u8,
    held: [u8; 7],
    /// The segment with c = 1 was accepted: waiting for the end frame.
    ending: bool,
}

#[derive(Debug, Clone, Copy)]
struct BlockUpload {
    mux: Multiplexer,
    size: u32,
    /// Offset of the first byte of the current sub-block.
    base: u32,
    /// Bytes covered by the CRC so far (always a prefix of the data, go-back-n never skips ahead).
    crc_len: u32,
    crc: Crc16,
    crc_on: bool,
    blksize: u8,
    /// Segments of the current sub-block produced so far.
    sent: u8,
    phase: UploadPhase,
}

/// One SDO server channel (SDO-01..SDO-51). See the [module docs](self) for the driving calls and choices.
///
/// ```
/// use canopen_core::sdo::{SdoServer, SdoServerParams};
/// use canopen_core::{Duration, NodeId};
/// let s = SdoServer::new(SdoServerParams::default_server(NodeId::new(3).unwrap()))
///     .with_timeout(Duration::from_millis(500))
///     .with_block_size(16);
/// assert!(s.is_idle());
/// assert!(core::mem::size_of::<SdoServer>() <= SdoServer::RAM_BYTES);
/// ```
#[derive(Debug, Clone)]
pub struct SdoServer {
    params: SdoServerParams,
    timeout: Duration,
    block_size: u8,
    deadline: Option<Instant>,
    state: State,
}

impl SdoServer {
    /// Upper bound of `size_of::<SdoServer>()` (asserted in a unit test; x86-64 and thumbv6m alike).
    ///
    /// ```
    /// # use canopen_core::sdo::SdoServer;
    /// assert!(core::mem::size_of::<SdoServer>() <= SdoServer::RAM_BYTES);
    /// ```
    pub const RAM_BYTES: usize = 80;

    /// A server with the [default time-out](super::DEFAULT_TIMEOUT) and block size 127.
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams};
    /// assert!(SdoServer::new(SdoServerParams::DISABLED).is_idle());
    /// ```
    pub const fn new(params: SdoServerParams) -> Self {
        SdoServer {
            params,
            timeout: super::DEFAULT_TIMEOUT,
            block_size: MAX_BLKSIZE,
            deadline: None,
            state: State::Idle,
        }
    }

    /// Sets the protocol time-out (SDO-31); zero disables it.
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams};
    /// # use canopen_core::Duration;
    /// let s = SdoServer::new(SdoServerParams::DISABLED).with_timeout(Duration::from_millis(100));
    /// assert!(s.poll_timeout().is_none());
    /// ```
    pub const fn with_timeout(mut self, timeout: Duration) -> Self {
        self.timeout = timeout;
        self
    }

    /// Changes the protocol time-out (SDO-31) of a server in use; zero disables it. A transfer under way keeps
    /// the deadline it has and uses the new time-out from its next frame on.
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams};
    /// # use canopen_core::Duration;
    /// let mut s = SdoServer::new(SdoServerParams::DISABLED);
    /// s.set_timeout(Duration::from_millis(250));
    /// assert!(s.is_idle());
    /// ```
    pub fn set_timeout(&mut self, timeout: Duration) {
        self.timeout = timeout;
    }

    /// Sets the block size the server asks for in block download (clamped to 1..=127, SDO-36).
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams};
    /// let s = SdoServer::new(SdoServerParams::DISABLED).with_block_size(0);
    /// assert!(s.is_idle());
    /// ```
    pub const fn with_block_size(mut self, blksize: u8) -> Self {
        self.block_size = if blksize == 0 {
            1
        } else if blksize > MAX_BLKSIZE {
            MAX_BLKSIZE
        } else {
            blksize
        };
        self
    }

    /// The channel parameters.
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams};
    /// assert_eq!(SdoServer::new(SdoServerParams::DISABLED).params(), &SdoServerParams::DISABLED);
    /// ```
    pub const fn params(&self) -> &SdoServerParams {
        &self.params
    }

    /// Replaces the channel parameters (1200h–127Fh written); a running transfer is dropped.
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams};
    /// # use canopen_core::NodeId;
    /// let mut s = SdoServer::new(SdoServerParams::DISABLED);
    /// s.set_params(SdoServerParams::default_server(NodeId::new(2).unwrap()));
    /// assert_eq!(s.rx_cob_id(), Some(0x602));
    /// ```
    pub fn set_params(&mut self, params: SdoServerParams) {
        self.params = params;
        self.state = State::Idle;
        self.deadline = None;
    }

    /// Drops the current transfer without a frame: the node left the states that serve SDO (NMT-18, a node
    /// in Stopped sends no SDO frame, not even a time-out abort later). A streamed write is abandoned
    /// ([`ObjectDictionary::abort_write`]).
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams};
    /// # use canopen_core::od::{AbortCode, ObjectDictionary, SubInfo};
    /// # struct Empty;
    /// # impl ObjectDictionary for Empty {
    /// #     fn info(&self, _: u16, _: u8) -> Result<SubInfo, AbortCode> { Err(AbortCode::ObjectDoesNotExist) }
    /// #     fn read(&self, _: u16, _: u8, _: usize, _: &mut [u8]) -> Result<usize, AbortCode> { Err(AbortCode::ObjectDoesNotExist) }
    /// #     fn write(&mut self, _: u16, _: u8, _: &[u8]) -> Result<(), AbortCode> { Err(AbortCode::ObjectDoesNotExist) }
    /// # }
    /// let mut s = SdoServer::new(SdoServerParams::DISABLED);
    /// s.cancel(&mut Empty);
    /// assert!(s.is_idle() && s.poll_timeout().is_none());
    /// ```
    pub fn cancel<O: ObjectDictionary + ?Sized>(&mut self, od: &mut O) {
        self.reset(od);
    }

    /// The CAN-ID to receive requests on, if the channel is valid.
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams};
    /// assert_eq!(SdoServer::new(SdoServerParams::DISABLED).rx_cob_id(), None);
    /// ```
    pub const fn rx_cob_id(&self) -> Option<u16> {
        self.params.rx_cob_id()
    }

    /// The CAN-ID to send responses on, if the channel is valid.
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams};
    /// assert_eq!(SdoServer::new(SdoServerParams::DISABLED).tx_cob_id(), None);
    /// ```
    pub const fn tx_cob_id(&self) -> Option<u16> {
        self.params.tx_cob_id()
    }

    /// Whether no transfer is in progress.
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams};
    /// assert!(SdoServer::new(SdoServerParams::DISABLED).is_idle());
    /// ```
    pub const fn is_idle(&self) -> bool {
        matches!(self.state, State::Idle)
    }

    /// The current protocol state.
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams, ServerState};
    /// assert_eq!(SdoServer::new(SdoServerParams::DISABLED).state(), ServerState::Idle);
    /// ```
    pub const fn state(&self) -> ServerState {
        match &self.state {
            State::Idle => ServerState::Idle,
            State::Download { .. } => ServerState::Downloading,
            State::Upload { .. } => ServerState::Uploading,
            State::BlockDownload(b) if b.ending => ServerState::BlockDownloadEnd,
            State::BlockDownload(_) => ServerState::BlockDownloadSubBlock,
            State::BlockUpload(b) => match b.phase {
                UploadPhase::Start => ServerState::BlockUploadStart,
                UploadPhase::Sending => ServerState::BlockUploadSending,
                UploadPhase::WaitAck => ServerState::BlockUploadAck,
                UploadPhase::WaitEnd => ServerState::BlockUploadEnd,
            },
        }
    }

    /// The next protocol deadline, if a transfer is in progress and a time-out is set.
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams};
    /// assert_eq!(SdoServer::new(SdoServerParams::DISABLED).poll_timeout(), None);
    /// ```
    pub const fn poll_timeout(&self) -> Option<Instant> {
        self.deadline
    }

    /// Aborts a transfer whose deadline has passed with 0504 0000h (SDO-31, ABORT-02).
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams, Response};
    /// # use canopen_core::od::{AbortCode, ObjectDictionary, SubInfo};
    /// # struct Empty;
    /// # impl ObjectDictionary for Empty {
    /// #     fn info(&self, _: u16, _: u8) -> Result<SubInfo, AbortCode> { Err(AbortCode::ObjectDoesNotExist) }
    /// #     fn read(&self, _: u16, _: u8, _: usize, _: &mut [u8]) -> Result<usize, AbortCode> { Err(AbortCode::ObjectDoesNotExist) }
    /// #     fn write(&mut self, _: u16, _: u8, _: &[u8]) -> Result<(), AbortCode> { Err(AbortCode::ObjectDoesNotExist) }
    /// # }
    /// let mut s = SdoServer::new(SdoServerParams::DISABLED);
    /// assert_eq!(s.handle_timeout(canopen_core::Instant::from_millis(5), &mut Empty), Response::NONE);
    /// ```
    pub fn handle_timeout<O: ObjectDictionary + ?Sized>(&mut self, now: Instant, od: &mut O) -> Response {
        match self.deadline {
            Some(d) if now >= d && !self.is_idle() => {
                let mux = self.mux().unwrap_or_default();
                self.abort(od, mux, AbortCode::SdoTimeout)
            }
            _ => Response::NONE,
        }
    }

    /// Whether [`poll_transmit`](Self::poll_transmit) has a frame (block upload sub-block in progress).
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams};
    /// assert!(!SdoServer::new(SdoServerParams::DISABLED).wants_transmit());
    /// ```
    pub const fn wants_transmit(&self) -> bool {
        matches!(self.state, State::BlockUpload(BlockUpload { phase: UploadPhase::Sending, .. }))
    }

    /// The next frame of a block-upload sub-block (SDO-37, SDO-46), one per call, `None` when there is
    /// nothing to send. Call it when the TX queue has room. A read error aborts the transfer (the abort frame
    /// is returned in the response).
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams};
    /// # use canopen_core::od::{AbortCode, ObjectDictionary, SubInfo};
    /// # struct Empty;
    /// # impl ObjectDictionary for Empty {
    /// #     fn info(&self, _: u16, _: u8) -> Result<SubInfo, AbortCode> { Err(AbortCode::ObjectDoesNotExist) }
    /// #     fn read(&self, _: u16, _: u8, _: usize, _: &mut [u8]) -> Result<usize, AbortCode> { Err(AbortCode::ObjectDoesNotExist) }
    /// #     fn write(&mut self, _: u16, _: u8, _: &[u8]) -> Result<(), AbortCode> { Err(AbortCode::ObjectDoesNotExist) }
    /// # }
    /// let mut s = SdoServer::new(SdoServerParams::DISABLED);
    /// assert!(s.poll_transmit(canopen_core::Instant::ZERO, &mut Empty).is_none());
    /// ```
    pub fn poll_transmit<O: ObjectDictionary + ?Sized>(&mut self, now: Instant, od: &mut O) -> Option<Response> {
        let State::BlockUpload(b) = &mut self.state else { return None };
        if b.phase != UploadPhase::Sending {
            return None;
        }
        let off = b.base.saturating_add(u32::from(b.sent).saturating_mul(7));
        let want = b.size.saturating_sub(off).min(7) as usize;
        let mut seg = BlockSegment { last: false, seqno: b.sent.saturating_add(1), data: [0; 7] };
        let mux = b.mux;
        let n = match od.read(mux.index, mux.sub, off as usize, &mut seg.data[..want]) {
            Ok(n) if n == want => n as u32,
            Ok(_) => return Some(self.abort(od, mux, AbortCode::LengthMismatch)),
            Err(code) => return Some(self.abort(od, mux, code)),
        };
        let end = off + n;
        if end > b.crc_len && b.crc_on {
            let skip = b.crc_len.saturating_sub(off) as usize;
            b.crc.update(seg.data.get(skip..n as usize).unwrap_or(&[]));
        }
        b.crc_len = b.crc_len.max(end);
        seg.last = end >= b.size;
        b.sent = seg.seqno;
        if seg.last || b.sent >= b.blksize {
            b.phase = UploadPhase::WaitAck;
        }
        self.touch(now);
        Some(Response::send(seg.emit()))
    }

    /// Handles one frame received on the server's rx COB-ID. `data` is the frame's data field (its length is
    /// the DLC).
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams, SdoEvent};
    /// # use canopen_core::od::{AbortCode, ObjectDictionary, SubInfo};
    /// # use canopen_core::Instant;
    /// # struct Empty;
    /// # impl ObjectDictionary for Empty {
    /// #     fn info(&self, _: u16, _: u8) -> Result<SubInfo, AbortCode> { Err(AbortCode::ObjectDoesNotExist) }
    /// #     fn read(&self, _: u16, _: u8, _: usize, _: &mut [u8]) -> Result<usize, AbortCode> { Err(AbortCode::ObjectDoesNotExist) }
    /// #     fn write(&mut self, _: u16, _: u8, _: &[u8]) -> Result<(), AbortCode> { Err(AbortCode::ObjectDoesNotExist) }
    /// # }
    /// let mut s = SdoServer::new(SdoServerParams::DISABLED);
    /// // V-SDO-10: object 5000h does not exist
    /// let r = s.handle_request(Instant::ZERO, &[0x40, 0x00, 0x50, 0x00, 0, 0, 0, 0], &mut Empty);
    /// assert_eq!(r.frame, Some([0x80, 0x00, 0x50, 0x00, 0x00, 0x00, 0x02, 0x06]));
    /// // short frames are ignored (CAN-07)
    /// assert_eq!(s.handle_request(Instant::ZERO, &[0x40, 0x00, 0x50], &mut Empty).frame, None);
    /// ```
    pub fn handle_request<O: ObjectDictionary + ?Sized>(&mut self, now: Instant, data: &[u8], od: &mut O) -> Response {
        let Ok(b) = <&[u8; 8]>::try_from(data) else { return Response::NONE };
        let r = self.dispatch(b, od);
        if self.is_idle() {
            self.deadline = None;
        } else {
            self.touch(now);
        }
        r
    }

    fn touch(&mut self, now: Instant) {
        self.deadline = if self.timeout.is_zero() { None } else { Some(now + self.timeout) };
    }

    fn mux(&self) -> Option<Multiplexer> {
        match &self.state {
            State::Idle => None,
            State::Download { mux, .. } | State::Upload { mux, .. } => Some(*mux),
            State::BlockDownload(b) => Some(b.mux),
            State::BlockUpload(b) => Some(b.mux),
        }
    }

    /// Drops the current transfer; tells the OD when a streamed write is abandoned.
    fn reset<O: ObjectDictionary + ?Sized>(&mut self, od: &mut O) {
        match self.state {
            State::Download { mux, sink: Sink::Stream, .. }
            | State::BlockDownload(BlockDownload { mux, sink: Sink::Stream, .. }) => od.abort_write(mux.index, mux.sub),
            _ => {}
        }
        self.state = State::Idle;
        self.deadline = None;
    }

    fn abort<O: ObjectDictionary + ?Sized>(&mut self, od: &mut O, mux: Multiplexer, code: AbortCode) -> Response {
        self.reset(od);
        Response {
            frame: Some(abort_frame(mux, code.code())),
            event: Some(SdoEvent::Aborted { index: mux.index, sub: mux.sub, code }),
        }
    }

    fn dispatch<O: ObjectDictionary + ?Sized>(&mut self, b: &[u8; 8], od: &mut O) -> Response {
        // SDO-32/SDO-33: the abort frame is 80h in every state, and is never answered.
        if b[0] == 0x80 {
            if self.is_idle() {
                return Response::NONE;
            }
            self.reset(od);
            let code = u32::from_le_bytes([b[4], b[5], b[6], b[7]]);
            return Response {
                frame: None,
                event: Some(SdoEvent::AbortReceived { index: u16::from_le_bytes([b[1], b[2]]), sub: b[3], code }),
            };
        }
        if let State::BlockDownload(bd) = &mut self.state {
            if !bd.ending {
                return self.block_segment(b, od);
            }
            // Waiting for "end block download" (SDO-41). Block segments carry no command specifier, so a late
            // or repeated segment of this transfer (any seqno the sub-blocks can use, last bit or not) would
            // read as a request: 81h–9Fh as an abort with reserved bits, 20h–7Fh as a new initiate. In this
            // state such a frame is a late segment and is ignored (SDO-40); only the end frame and the abort
            // 80h (handled above) are requests. A client that starts a new transfer here must abort first.
            if !is_block_download_end(b[0]) && (1..=self.block_size).contains(&(b[0] & 0x7F)) {
                return Response::NONE;
            }
        }
        let req = match ClientRequest::parse(b) {
            Ok(r) => r,
            Err(_) => {
                let mux = self.mux().unwrap_or(Multiplexer::new(u16::from_le_bytes([b[1], b[2]]), b[3]));
                return self.abort(od, mux, AbortCode::InvalidCommandSpecifier);
            }
        };
        match req {
            ClientRequest::Abort { .. } => {
                // ccs 4 with non-zero reserved bits: still an abort (SDO-02), never answered.
                if self.is_idle() {
                    return Response::NONE;
                }
                let mux = self.mux().unwrap_or_default();
                self.reset(od);
                let code = u32::from_le_bytes([b[4], b[5], b[6], b[7]]);
                Response { frame: None, event: Some(SdoEvent::AbortReceived { index: mux.index, sub: mux.sub, code }) }
            }
            ClientRequest::InitiateDownload { mux, data } => {
                self.reset(od); // SDO-29
                self.initiate_download(mux, data, od).unwrap_or_else(|code| self.abort(od, mux, code))
            }
            ClientRequest::InitiateUpload { mux } => {
                self.reset(od);
                self.initiate_upload(mux, od).unwrap_or_else(|code| self.abort(od, mux, code))
            }
            ClientRequest::BlockDownloadInitiate { mux, crc, size } => {
                self.reset(od);
                self.block_download_initiate(mux, crc, size, od).unwrap_or_else(|code| self.abort(od, mux, code))
            }
            ClientRequest::BlockUploadInitiate { mux, crc, blksize, pst } => {
                self.reset(od);
                self.block_upload_initiate(mux, crc, blksize, pst, od).unwrap_or_else(|code| self.abort(od, mux, code))
            }
            ClientRequest::DownloadSegment(seg) => self.download_segment(seg, od),
            ClientRequest::UploadSegment { toggle } => self.upload_segment(toggle, od),
            ClientRequest::BlockDownloadEnd { unused, crc } => self.block_download_end(unused, crc, od),
            ClientRequest::BlockUploadStart => match &mut self.state {
                State::BlockUpload(bu) if bu.phase == UploadPhase::Start => {
                    bu.phase = UploadPhase::Sending;
                    Response::NONE
                }
                _ => self.invalid(od),
            },
            ClientRequest::BlockUploadAck { ackseq, blksize } => self.block_upload_ack(ackseq, blksize, od),
            ClientRequest::BlockUploadEnd => match self.state {
                State::BlockUpload(bu) if bu.phase == UploadPhase::WaitEnd => {
                    self.state = State::Idle;
                    Response { frame: None, event: Some(SdoEvent::Uploaded { index: bu.mux.index, sub: bu.mux.sub }) }
                }
                _ => self.invalid(od),
            },
        }
    }

    /// A well-formed frame that is not valid in the current state: 0504 0001h (SDO-09).
    fn invalid<O: ObjectDictionary + ?Sized>(&mut self, od: &mut O) -> Response {
        // frames in the wrong state: the transfer's multiplexer, or 0000h:00 when idle
        let mux = self.mux().unwrap_or_default();
        self.abort(od, mux, AbortCode::InvalidCommandSpecifier)
    }

    fn initiate_download<O: ObjectDictionary + ?Sized>(
        &mut self,
        mux: Multiplexer,
        data: InitiateData,
        od: &mut O,
    ) -> Result<Response, AbortCode> {
        match data {
            InitiateData::Expedited(e) => {
                // info, access, length and the write in one dictionary call (one lookup where it is derived).
                let len = e.size_indicated.then_some(usize::from(e.len));
                od.write_expedited(mux.index, mux.sub, &e.data, len)?;
                Ok(Response {
                    frame: Some(ServerResponse::InitiateDownload { mux }.emit()),
                    event: Some(SdoEvent::Written { index: mux.index, sub: mux.sub }),
                })
            }
            InitiateData::Segmented { size } => {
                let info = od.info(mux.index, mux.sub)?;
                if !info.access.writable() {
                    return Err(AbortCode::WriteOfReadOnly);
                }
                let sink = self.open_sink(mux, info.data_type.size(), size, od)?;
                self.state = State::Download { mux, toggle: false, offset: 0, size, sink };
                Ok(Response::send(ServerResponse::InitiateDownload { mux }.emit()))
            }
        }
    }

    fn open_sink<O: ObjectDictionary + ?Sized>(
        &mut self,
        mux: Multiplexer,
        fixed: Option<usize>,
        size: Option<u32>,
        od: &mut O,
    ) -> Result<Sink, AbortCode> {
        match fixed {
            Some(n) => {
                // SDO-18: refuse a wrong announced size before any data moves.
                match size.map(|s| (s as usize).cmp(&n)) {
                    Some(core::cmp::Ordering::Greater) => Err(AbortCode::LengthTooHigh),
                    Some(core::cmp::Ordering::Less) => Err(AbortCode::LengthTooLow),
                    _ => Ok(Sink::Scratch([0; 8])),
                }
            }
            None => {
                od.begin_write(mux.index, mux.sub, size.map(|s| s as usize))?;
                Ok(Sink::Stream)
            }
        }
    }

    fn initiate_upload<O: ObjectDictionary + ?Sized>(
        &mut self,
        mux: Multiplexer,
        od: &mut O,
    ) -> Result<Response, AbortCode> {
        let mut d = [0u8; 4];
        let (size, n) = od.read_expedited(mux.index, mux.sub, &mut d)?;
        let size = u32::try_from(size).map_err(|_| AbortCode::OutOfMemory)?;
        if (1..=4).contains(&size) {
            let e = Expedited::new(d.get(..n).unwrap_or(&[])).ok_or(AbortCode::GeneralError)?;
            return Ok(Response::send(ServerResponse::InitiateUpload { mux, data: InitiateData::Expedited(e) }.emit()));
        }
        self.state = State::Upload { mux, toggle: false, offset: 0, size };
        Ok(Response::send(
            ServerResponse::InitiateUpload { mux, data: InitiateData::Segmented { size: Some(size) } }.emit(),
        ))
    }

    fn download_segment<O: ObjectDictionary + ?Sized>(&mut self, seg: Segment, od: &mut O) -> Response {
        let State::Download { mux, toggle, offset, size, sink } = &mut self.state else {
            return self.invalid(od);
        };
        let mux = *mux;
        if seg.toggle != *toggle {
            return self.abort(od, mux, AbortCode::ToggleNotAlternated); // SDO-30
        }
        let bytes = seg.bytes();
        let end = offset.saturating_add(u32::from(seg.len));
        let r = (|| {
            if size.is_some_and(|s| end > s) || end == u32::MAX {
                return Err(AbortCode::LengthTooHigh);
            }
            sink_write(sink, mux, *offset, bytes, od)?;
            if seg.last {
                if size.is_some_and(|s| end < s) {
                    return Err(AbortCode::LengthTooLow);
                }
                sink_finish(sink, mux, end, od)?;
            }
            Ok(())
        })();
        if let Err(code) = r {
            return self.abort(od, mux, code);
        }
        let frame = ServerResponse::DownloadSegment { toggle: seg.toggle }.emit();
        if seg.last {
            self.state = State::Idle;
            return Response { frame: Some(frame), event: Some(SdoEvent::Written { index: mux.index, sub: mux.sub }) };
        }
        *offset = end;
        *toggle = !*toggle;
        Response::send(frame)
    }

    fn upload_segment<O: ObjectDictionary + ?Sized>(&mut self, t: bool, od: &mut O) -> Response {
        let State::Upload { mux, toggle, offset, size } = &mut self.state else {
            return self.invalid(od);
        };
        let mux = *mux;
        if t != *toggle {
            return self.abort(od, mux, AbortCode::ToggleNotAlternated); // SDO-28, SDO-30
        }
        let want = size.saturating_sub(*offset).min(7) as usize;
        let mut seg = Segment { toggle: t, last: false, len: 0, data: [0; 7] };
        let n = match od.read(mux.index, mux.sub, *offset as usize, &mut seg.data[..want]) {
            Ok(n) if n == want => n,
            Ok(_) => return self.abort(od, mux, AbortCode::LengthMismatch),
            Err(code) => return self.abort(od, mux, code),
        };
        seg.len = n as u8;
        *offset += n as u32;
        seg.last = *offset >= *size;
        *toggle = !*toggle;
        if seg.last {
            self.state = State::Idle;
            return Response {
                frame: Some(seg.emit()),
                event: Some(SdoEvent::Uploaded { index: mux.index, sub: mux.sub }),
            };
        }
        Response::send(seg.emit())
    }

    fn block_download_initiate<O: ObjectDictionary + ?Sized>(
        &mut self,
        mux: Multiplexer,
        crc: bool,
        size: Option<u32>,
        od: &mut O,
    ) -> Result<Response, AbortCode> {
        let info = od.info(mux.index, mux.sub)?;
        if !info.access.writable() {
            return Err(AbortCode::WriteOfReadOnly);
        }
        let sink = self.open_sink(mux, info.data_type.size(), size, od)?;
        self.state = State::BlockDownload(BlockDownload {
            mux,
            sink,
            offset: 0,
            size,
            crc: Crc16::new(),
            crc_on: crc,
            expected: 1,
            held_seqno: 0,
            held: [0; 7],
            ending: false,
        });
        // INTEROP: sc = cc
        Ok(Response::send(ServerResponse::BlockDownloadInitiate { mux, crc, blksize: self.block_size }.emit()))
    }

    fn block_segment<O: ObjectDictionary + ?Sized>(&mut self, b: &[u8; 8], od: &mut O) -> Response {
        let blksize = self.block_size;
        let State::BlockDownload(bd) = &mut self.state else { return Response::NONE };
        let mux = bd.mux;
        let last = b[0] & 0x80 != 0;
        let seqno = b[0] & 0x7F;
        if seqno == 0 || seqno > blksize {
            return self.abort(od, mux, AbortCode::InvalidSequenceNumber); // SDO-50
        }
        if seqno != bd.expected {
            if bd.held_seqno == seqno && b[1..8] == bd.held {
                return Response::NONE; // exact repeat of the last accepted segment
            }
            // out of order: discard; acknowledge the last in-order segment at the sub-block's end (SDO-40)
            if last || seqno == blksize {
                let ackseq = bd.expected - 1;
                bd.expected = 1;
                return Response::send(ServerResponse::BlockDownloadAck { ackseq, blksize }.emit());
            }
            return Response::NONE;
        }
        if bd.held_seqno != 0 {
            let held = bd.held;
            if let Err(code) = block_flush(bd, &held, od) {
                return self.abort(od, mux, code);
            }
        }
        bd.held.copy_from_slice(&b[1..8]);
        bd.held_seqno = seqno;
        bd.expected = seqno + 1;
        if last || seqno == blksize {
            bd.expected = 1;
            bd.ending = last;
            return Response::send(ServerResponse::BlockDownloadAck { ackseq: seqno, blksize }.emit());
        }
        Response::NONE
    }

    fn block_download_end<O: ObjectDictionary + ?Sized>(&mut self, unused: u8, crc: u16, od: &mut O) -> Response {
        let State::BlockDownload(bd) = &mut self.state else {
            return self.invalid(od);
        };
        let mux = bd.mux;
        let held = bd.held;
        let len = usize::from(7 - unused.min(7));
        let r = (|| {
            block_flush(bd, held.get(..len).unwrap_or(&[]), od)?;
            if bd.crc_on && bd.crc.get() != crc {
                return Err(AbortCode::CrcError); // SDO-50
            }
            match bd.size {
                Some(s) if bd.offset > s => return Err(AbortCode::LengthTooHigh),
                Some(s) if bd.offset < s => return Err(AbortCode::LengthTooLow),
                _ => {}
            }
            sink_finish(&bd.sink, mux, bd.offset, od)
        })();
        if let Err(code) = r {
            return self.abort(od, mux, code);
        }
        self.state = State::Idle;
        Response {
            frame: Some(ServerResponse::BlockDownloadEnd.emit()),
            event: Some(SdoEvent::Written { index: mux.index, sub: mux.sub }),
        }
    }

    fn block_upload_initiate<O: ObjectDictionary + ?Sized>(
        &mut self,
        mux: Multiplexer,
        crc: bool,
        blksize: u8,
        pst: u8,
        od: &mut O,
    ) -> Result<Response, AbortCode> {
        if blksize == 0 || blksize > MAX_BLKSIZE {
            return Err(AbortCode::InvalidBlockSize);
        }
        let size = readable_size(mux, od)?;
        if pst > 0 && size <= u32::from(pst) {
            return self.initiate_upload(mux, od); // SDO-43: protocol switch
        }
        self.state = State::BlockUpload(BlockUpload {
            mux,
            size,
            base: 0,
            crc_len: 0,
            crc: Crc16::new(),
            crc_on: crc,
            blksize,
            sent: 0,
            phase: UploadPhase::Start,
        });
        Ok(Response::send(ServerResponse::BlockUploadInitiate { mux, crc, size: Some(size) }.emit()))
    }

    fn block_upload_ack<O: ObjectDictionary + ?Sized>(&mut self, ackseq: u8, blksize: u8, od: &mut O) -> Response {
        let State::BlockUpload(bu) = &mut self.state else { return self.invalid(od) };
        if !matches!(bu.phase, UploadPhase::Sending | UploadPhase::WaitAck) {
            return self.invalid(od);
        }
        let mux = bu.mux;
        if ackseq > bu.sent {
            return self.abort(od, mux, AbortCode::InvalidSequenceNumber);
        }
        if blksize == 0 || blksize > MAX_BLKSIZE {
            return self.abort(od, mux, AbortCode::InvalidBlockSize);
        }
        bu.base = bu.base.saturating_add(u32::from(ackseq) * 7);
        bu.sent = 0;
        bu.blksize = blksize;
        if ackseq >= 1 && bu.base >= bu.size {
            bu.phase = UploadPhase::WaitEnd;
            let crc = if bu.crc_on { bu.crc.get() } else { 0 };
            let unused = 7 - last_segment_len(bu.size);
            return Response::send(ServerResponse::BlockUploadEnd { unused, crc }.emit());
        }
        bu.phase = UploadPhase::Sending;
        Response::NONE
    }
}

/// True for the client's "end block download" command byte: ccs 6, cs 1 (C1h + 4·n, bit 1 reserved; SDO-41).
const fn is_block_download_end(b0: u8) -> bool {
    b0 & 0xE1 == 0xC1
}

/// Size of a readable object (SDO upload preconditions).
fn readable_size<O: ObjectDictionary + ?Sized>(mux: Multiplexer, od: &O) -> Result<u32, AbortCode> {
    let info = od.info(mux.index, mux.sub)?;
    if !info.access.readable() {
        return Err(AbortCode::ReadOfWriteOnly);
    }
    u32::try_from(info.size).map_err(|_| AbortCode::OutOfMemory)
}

fn sink_write<O: ObjectDictionary + ?Sized>(
    sink: &mut Sink,
    mux: Multiplexer,
    offset: u32,
    bytes: &[u8],
    od: &mut O,
) -> Result<(), AbortCode> {
    match sink {
        Sink::Scratch(buf) => {
            let start = offset as usize;
            let dst = buf.get_mut(start..start + bytes.len()).ok_or(AbortCode::LengthTooHigh)?;
            dst.copy_from_slice(bytes);
            Ok(())
        }
        Sink::Stream => od.write_chunk(mux.index, mux.sub, offset as usize, bytes),
    }
}

fn sink_finish<O: ObjectDictionary + ?Sized>(
    sink: &Sink,
    mux: Multiplexer,
    total: u32,
    od: &mut O,
) -> Result<(), AbortCode> {
    match sink {
        Sink::Scratch(buf) => od.write(mux.index, mux.sub, buf.get(..total as usize).ok_or(AbortCode::LengthTooHigh)?),
        Sink::Stream => od.end_write(mux.index, mux.sub, total as usize),
    }
}

/// Writes in-order block data to the sink and the CRC.
fn block_flush<O: ObjectDictionary + ?Sized>(
    bd: &mut BlockDownload,
    bytes: &[u8],
    od: &mut O,
) -> Result<(), AbortCode> {
    let end = bd.offset.saturating_add(bytes.len() as u32);
    if bd.size.is_some_and(|s| end > s) || end == u32::MAX {
        return Err(AbortCode::LengthTooHigh);
    }
    sink_write(&mut bd.sink, bd.mux, bd.offset, bytes, od)?;
    if bd.crc_on {
        bd.crc.update(bytes);
    }
    bd.offset = end;
    bd.held_seqno = 0;
    Ok(())
}

/// The default server plus `N - 1` additional servers (1201h–127Fh), a compile-time count (SDO-57).
///
/// Dispatch by COB-ID is a scan over these `N` channels only (N is small; the node's own dispatch picks the
/// SDO table by function code first).
///
/// ```
/// use canopen_core::sdo::{SdoServerParams, SdoServers};
/// use canopen_core::NodeId;
/// let mut servers = SdoServers::<2>::new(NodeId::new(4).unwrap());
/// assert_eq!(servers.find(0x604), Some(0));
/// assert_eq!(servers.find(0x640), None); // server 2 is disabled until configured
/// let mut p = SdoServerParams::DISABLED;
/// p.cob_rx = canopen_core::cob::CobIdEntry::from_raw(0x640);
/// p.cob_tx = canopen_core::cob::CobIdEntry::from_raw(0x5C0);
/// servers.get_mut(1).unwrap().set_params(p);
/// assert_eq!(servers.find(0x640), Some(1));
/// ```
#[derive(Debug, Clone)]
pub struct SdoServers<const N: usize> {
    servers: [SdoServer; N],
}

impl<const N: usize> SdoServers<N> {
    /// Server 0 is the default server of `node` (1200h); the others start disabled.
    ///
    /// ```
    /// # use canopen_core::sdo::SdoServers;
    /// # use canopen_core::NodeId;
    /// assert_eq!(SdoServers::<1>::new(NodeId::new(1).unwrap()).len(), 1);
    /// ```
    pub fn new(node: NodeId) -> Self {
        let mut servers = core::array::from_fn(|_| SdoServer::new(SdoServerParams::DISABLED));
        if let Some(first) = servers.first_mut() {
            *first = SdoServer::new(SdoServerParams::default_server(node));
        }
        SdoServers { servers }
    }

    /// Number of channels.
    ///
    /// ```
    /// # use canopen_core::sdo::SdoServers;
    /// # use canopen_core::NodeId;
    /// assert_eq!(SdoServers::<3>::new(NodeId::new(1).unwrap()).len(), 3);
    /// ```
    pub const fn len(&self) -> usize {
        N
    }

    /// Whether there are no channels (`N == 0`).
    ///
    /// ```
    /// # use canopen_core::sdo::SdoServers;
    /// # use canopen_core::NodeId;
    /// assert!(!SdoServers::<1>::new(NodeId::new(1).unwrap()).is_empty());
    /// ```
    pub const fn is_empty(&self) -> bool {
        N == 0
    }

    /// The channel that receives on `cob_id`.
    ///
    /// ```
    /// # use canopen_core::sdo::SdoServers;
    /// # use canopen_core::NodeId;
    /// assert_eq!(SdoServers::<1>::new(NodeId::new(1).unwrap()).find(0x601), Some(0));
    /// ```
    pub fn find(&self, cob_id: u16) -> Option<usize> {
        self.servers.iter().position(|s| s.rx_cob_id() == Some(cob_id))
    }

    /// A channel by number (0 = 1200h).
    ///
    /// ```
    /// # use canopen_core::sdo::SdoServers;
    /// # use canopen_core::NodeId;
    /// assert!(SdoServers::<1>::new(NodeId::new(1).unwrap()).get_mut(1).is_none());
    /// ```
    pub fn get_mut(&mut self, i: usize) -> Option<&mut SdoServer> {
        self.servers.get_mut(i)
    }

    /// All channels.
    ///
    /// ```
    /// # use canopen_core::sdo::SdoServers;
    /// # use canopen_core::NodeId;
    /// assert_eq!(SdoServers::<2>::new(NodeId::new(1).unwrap()).iter().count(), 2);
    /// ```
    pub fn iter(&self) -> impl Iterator<Item = &SdoServer> {
        self.servers.iter()
    }
}

#[cfg(test)]
#[path = "../../tests/support/od.rs"]
mod test_od;

#[cfg(test)]
extern crate std;

#[cfg(test)]
mod tests {
    use super::test_od::{TestOd, STRING64};
    use super::*;

    const T0: Instant = Instant::ZERO;

    fn server() -> SdoServer {
        SdoServer::new(SdoServerParams::default_server(NodeId::new(3).unwrap()))
    }

    /// Sends `req`, expects exactly `want` as the reply frame.
    fn exchange(s: &mut SdoServer, od: &mut TestOd, req: [u8; 8], want: Option<[u8; 8]>) -> Response {
        let r = s.handle_request(T0, &req, od);
        assert_eq!(r.frame, want, "request {req:02X?} → {:02X?}", r.frame);
        r
    }

    fn abort_of(index: u16, sub: u8, code: AbortCode) -> Option<[u8; 8]> {
        Some(abort_frame(Multiplexer::new(index, sub), code.code()))
    }

    #[test]
    fn ram_bound() {
        let (server, client) = (core::mem::size_of::<SdoServer>(), core::mem::size_of::<crate::sdo::SdoClient>());
        std::eprintln!("size_of SdoServer = {server} B, SdoClient = {client} B");
        assert!(server <= SdoServer::RAM_BYTES, "{server}");
        assert!(client <= 96, "{client}");
    }

    #[test]
    fn v_sdo_expedited_positive() {
        let (mut s, mut od) = (server(), TestOd::new());
        // V-SDO-01
        let r = exchange(
            &mut s,
            &mut od,
            [0x23, 0x7A, 0x60, 0x00, 0xE8, 0x03, 0x00, 0x00],
            Some([0x60, 0x7A, 0x60, 0, 0, 0, 0, 0]),
        );
        assert_eq!(r.event, Some(SdoEvent::Written { index: 0x607A, sub: 0 }));
        assert_eq!(od.get(0x607A, 0), Some(1000));
        // V-SDO-02
        exchange(
            &mut s,
            &mut od,
            [0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0],
            Some([0x4B, 0x41, 0x60, 0x00, 0x40, 0x02, 0, 0]),
        );
        // V-SDO-03 (conformant answer) and a positive 1400h:02 write of FEh
        exchange(
            &mut s,
            &mut od,
            [0x2F, 0x00, 0x14, 0x02, 0xFD, 0, 0, 0],
            abort_of(0x1400, 2, AbortCode::InvalidValue),
        );
        exchange(&mut s, &mut od, [0x2F, 0x00, 0x14, 0x02, 0xFE, 0, 0, 0], Some([0x60, 0x00, 0x14, 0x02, 0, 0, 0, 0]));
        // V-SDO-04, V-SDO-06
        exchange(
            &mut s,
            &mut od,
            [0x23, 0x03, 0x16, 0x01, 0x08, 0x02, 0x12, 0x60],
            Some([0x60, 0x03, 0x16, 0x01, 0, 0, 0, 0]),
        );
        exchange(
            &mut s,
            &mut od,
            [0x40, 0x03, 0x16, 0x01, 0, 0, 0, 0],
            Some([0x43, 0x03, 0x16, 0x01, 0x08, 0x02, 0x12, 0x60]),
        );
        // V-SDO-05 (value FEh after the write above)
        exchange(&mut s, &mut od, [0x40, 0x00, 0x14, 0x02, 0, 0, 0, 0], Some([0x4F, 0x00, 0x14, 0x02, 0xFE, 0, 0, 0]));
        // V-SDO-08, V-SDO-09 (our 1018h), V-SDO-17
        exchange(
            &mut s,
            &mut od,
            [0x40, 0x18, 0x10, 0x01, 0, 0, 0, 0],
            Some([0x43, 0x18, 0x10, 0x01, 0xB6, 0x02, 0, 0]),
        );
        exchange(&mut s, &mut od, [0x40, 0x18, 0x10, 0x00, 0, 0, 0, 0], Some([0x4F, 0x18, 0x10, 0x00, 0x04, 0, 0, 0]));
        exchange(
            &mut s,
            &mut od,
            [0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0],
            Some([0x43, 0x00, 0x10, 0x00, 0x91, 0x01, 0, 0]),
        );
        // SDO-13: 22h without size into a U16 takes 2 bytes
        exchange(
            &mut s,
            &mut od,
            [0x22, 0x17, 0x10, 0x00, 0xE8, 0x03, 0xAA, 0xBB],
            Some([0x60, 0x17, 0x10, 0, 0, 0, 0, 0]),
        );
        assert_eq!(od.get(0x1017, 0), Some(1000));
        assert!(s.is_idle());
        assert_eq!(s.poll_timeout(), None);
    }

    #[test]
    fn v_sdo_expedited_negative_and_od_abort_codes() {
        let (mut s, mut od) = (server(), TestOd::new());
        let cases: [([u8; 8], u16, u8, AbortCode); 16] = [
            ([0x40, 0x00, 0x50, 0x00, 0, 0, 0, 0], 0x5000, 0, AbortCode::ObjectDoesNotExist), // V-SDO-10
            ([0x40, 0x18, 0x10, 0x07, 0, 0, 0, 0], 0x1018, 7, AbortCode::SubIndexDoesNotExist), // V-SDO-11
            ([0x23, 0x00, 0x10, 0x00, 0, 0, 0, 0], 0x1000, 0, AbortCode::WriteOfReadOnly),    // V-SDO-12
            ([0x2F, 0x17, 0x10, 0x00, 0x64, 0, 0, 0], 0x1017, 0, AbortCode::LengthTooLow),    // V-SDO-13
            ([0x23, 0x0D, 0x10, 0x00, 0x03, 0, 0, 0], 0x100D, 0, AbortCode::LengthTooHigh),   // V-SDO-14
            ([0xE0, 0x00, 0x10, 0x00, 0, 0, 0, 0], 0x1000, 0, AbortCode::InvalidCommandSpecifier), // V-SDO-15
            ([0x40, 0x01, 0x20, 0x00, 0, 0, 0, 0], 0x2001, 0, AbortCode::ReadOfWriteOnly),
            ([0x2B, 0x02, 0x20, 0x00, 0x65, 0x00, 0, 0], 0x2002, 0, AbortCode::ValueTooHigh),
            ([0x2B, 0x02, 0x20, 0x00, 0x9B, 0xFF, 0, 0], 0x2002, 0, AbortCode::ValueTooLow),
            ([0x23, 0x03, 0x20, 0x00, 0, 0, 0, 0], 0x2003, 0, AbortCode::InvalidValue),
            ([0x23, 0x03, 0x20, 0x00, 1, 0, 0, 0], 0x2003, 0, AbortCode::GeneralError),
            ([0x23, 0x03, 0x20, 0x00, 2, 0, 0, 0], 0x2003, 0, AbortCode::CannotStore),
            ([0x23, 0x03, 0x20, 0x00, 3, 0, 0, 0], 0x2003, 0, AbortCode::CannotStoreDeviceState),
            ([0x21, 0x17, 0x10, 0x00, 3, 0, 0, 0], 0x1017, 0, AbortCode::LengthTooHigh), // SDO-18 at initiate
            ([0x21, 0x05, 0x20, 0x00, 4, 0, 0, 0], 0x2005, 0, AbortCode::LengthTooLow),
            ([0xC6, 0x00, 0x20, 0x00, 0x01, 0x00, 0x01, 0x00], 0x2000, 0, AbortCode::OutOfMemory), // 65537 bytes
        ];
        for (req, index, sub, code) in cases {
            let r = exchange(&mut s, &mut od, req, abort_of(index, sub, code));
            assert_eq!(r.event, Some(SdoEvent::Aborted { index, sub, code }));
            assert!(s.is_idle());
        }
        // a refused write changed nothing
        assert_eq!(od.get(0x2003, 0), Some(7));
        // streamed write to a fixed-size object the OD cannot stream: unsupported access (0601 0000h) does
        // not arise; a streamed end_write refusal does (0800 0020h)
        exchange(&mut s, &mut od, [0x21, 0x07, 0x20, 0x00, 3, 0, 0, 0], Some([0x60, 0x07, 0x20, 0, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0x09, b'b', b'a', b'd', 0, 0, 0, 0], abort_of(0x2007, 0, AbortCode::CannotStore));
        assert_eq!(od.aborted_writes, 1);
    }

    #[test]
    fn unsupported_access_from_od() {
        // An OD that cannot stream a DOMAIN: the trait's default begin_write refuses with 0601 0000h.
        struct NoStream;
        impl ObjectDictionary for NoStream {
            fn info(&self, _: u16, _: u8) -> Result<crate::od::SubInfo, AbortCode> {
                Ok(crate::od::SubInfo {
                    data_type: crate::od::DataType::Domain,
                    access: crate::od::Access::Rw,
                    pdo: crate::od::PdoMapping::No,
                    size: 0,
                })
            }
            fn read(&self, _: u16, _: u8, _: usize, _: &mut [u8]) -> Result<usize, AbortCode> {
                Ok(0)
            }
            fn write(&mut self, _: u16, _: u8, _: &[u8]) -> Result<(), AbortCode> {
                Ok(())
            }
        }
        let mut s = server();
        let r = s.handle_request(T0, &[0x21, 0x00, 0x30, 0x00, 3, 0, 0, 0], &mut NoStream);
        assert_eq!(r.frame, abort_of(0x3000, 0, AbortCode::UnsupportedAccess));
        // an empty DOMAIN uploads as a segmented transfer of 0 bytes: one segment with n = 7, c = 1
        let r = s.handle_request(T0, &[0x40, 0x00, 0x30, 0x00, 0, 0, 0, 0], &mut NoStream);
        assert_eq!(r.frame, Some([0x41, 0x00, 0x30, 0x00, 0, 0, 0, 0]));
        let r = s.handle_request(T0, &[0x60, 0, 0, 0, 0, 0, 0, 0], &mut NoStream);
        assert_eq!(r.frame, Some([0x0F, 0, 0, 0, 0, 0, 0, 0]));
        assert!(s.is_idle());
    }

    #[test]
    fn value_shorter_than_announced_is_length_mismatch() {
        // info says 10 bytes, read delivers only 3: the upload cannot keep its announced size (0607 0010h)
        struct Shrunk;
        impl ObjectDictionary for Shrunk {
            fn info(&self, _: u16, _: u8) -> Result<crate::od::SubInfo, AbortCode> {
                Ok(crate::od::SubInfo {
                    data_type: crate::od::DataType::VisibleString,
                    access: crate::od::Access::Ro,
                    pdo: crate::od::PdoMapping::No,
                    size: 10,
                })
            }
            fn read(&self, _: u16, _: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
                let n = 3usize.saturating_sub(offset).min(buf.len());
                buf[..n].fill(b'x');
                Ok(n)
            }
            fn write(&mut self, _: u16, _: u8, _: &[u8]) -> Result<(), AbortCode> {
                Err(AbortCode::WriteOfReadOnly)
            }
        }
        let mut s = server();
        let r = s.handle_request(T0, &[0x40, 0x00, 0x30, 0x00, 0, 0, 0, 0], &mut Shrunk);
        assert_eq!(r.frame, Some([0x41, 0x00, 0x30, 0x00, 10, 0, 0, 0]));
        let r = s.handle_request(T0, &[0x60, 0, 0, 0, 0, 0, 0, 0], &mut Shrunk);
        assert_eq!(r.frame, abort_of(0x3000, 0, AbortCode::LengthMismatch));
        let r = s.handle_request(T0, &[0xA4, 0x00, 0x30, 0x00, 0x7F, 0, 0, 0], &mut Shrunk);
        assert_eq!(r.frame, Some([0xC6, 0x00, 0x30, 0x00, 10, 0, 0, 0]));
        s.handle_request(T0, &[0xA3, 0, 0, 0, 0, 0, 0, 0], &mut Shrunk);
        assert_eq!(s.poll_transmit(T0, &mut Shrunk).unwrap().frame, abort_of(0x3000, 0, AbortCode::LengthMismatch));
        assert!(s.is_idle());
    }

    #[test]
    fn v_sdo_segmented_upload_7_2() {
        let (mut s, mut od) = (server(), TestOd::new());
        let steps: [([u8; 8], [u8; 8]); 5] = [
            ([0x40, 0x09, 0x10, 0x00, 0, 0, 0, 0], [0x41, 0x09, 0x10, 0x00, 0x17, 0, 0, 0]),
            ([0x60, 0, 0, 0, 0, 0, 0, 0], [0x00, 0x4E, 0x31, 0x30, 0x20, 0x2D, 0x20, 0x57]),
            ([0x70, 0, 0, 0, 0, 0, 0, 0], [0x10, 0x54, 0x31, 0x32, 0x30, 0x39, 0x2D, 0x56]),
            // 002's client puts the multiplexer in the reserved bytes: accepted (SDO-02)
            ([0x60, 0x09, 0x10, 0x00, 0, 0, 0, 0], [0x00, 0x31, 0x2E, 0x30, 0x30, 0x2D, 0x38, 0x4D]),
            ([0x70, 0, 0, 0, 0, 0, 0, 0], [0x1B, 0x42, 0x00, 0, 0, 0, 0, 0]),
        ];
        for (i, (req, rsp)) in steps.iter().enumerate() {
            let r = exchange(&mut s, &mut od, *req, Some(*rsp));
            if i == 4 {
                assert_eq!(r.event, Some(SdoEvent::Uploaded { index: 0x1009, sub: 0 }));
            }
        }
        assert!(s.is_idle());
    }

    #[test]
    fn v_sdo_seed_7_1_toggle_error() {
        // The seed's step 5 repeats t = 0: abort 0503 0000h (SDO-30)
        let (mut s, mut od) = (server(), TestOd::new());
        exchange(&mut s, &mut od, [0x40, 0x09, 0x10, 0x00, 0, 0, 0, 0], Some([0x41, 0x09, 0x10, 0x00, 0x17, 0, 0, 0]));
        exchange(
            &mut s,
            &mut od,
            [0x60, 0x09, 0x10, 0x00, 0, 0, 0, 0],
            Some([0x00, 0x4E, 0x31, 0x30, 0x20, 0x2D, 0x20, 0x57]),
        );
        exchange(
            &mut s,
            &mut od,
            [0x60, 0x09, 0x10, 0x00, 0, 0, 0, 0],
            abort_of(0x1009, 0, AbortCode::ToggleNotAlternated),
        );
        assert!(s.is_idle());
    }

    #[test]
    fn v_sdo_segmented_download_7_3_and_variants() {
        let (mut s, mut od) = (server(), TestOd::new());
        exchange(&mut s, &mut od, [0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0x00, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37], Some([0x20, 0, 0, 0, 0, 0, 0, 0]));
        let r = exchange(&mut s, &mut od, [0x1B, 0x38, 0x39, 0, 0, 0, 0, 0], Some([0x30, 0, 0, 0, 0, 0, 0, 0]));
        assert_eq!(r.event, Some(SdoEvent::Written { index: 0x2000, sub: 0 }));
        assert_eq!(od.domain(), b"123456789");

        // toggle-error variant
        exchange(&mut s, &mut od, [0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0x00, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37], Some([0x20, 0, 0, 0, 0, 0, 0, 0]));
        exchange(
            &mut s,
            &mut od,
            [0x0B, 0x38, 0x39, 0, 0, 0, 0, 0],
            Some([0x80, 0x00, 0x20, 0x00, 0x00, 0x00, 0x03, 0x05]),
        );
        assert_eq!(od.aborted_writes, 1);

        // time-out variant (SDO-31)
        let t1 = Instant::from_millis(10);
        let r = s.handle_request(t1, &[0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], &mut od);
        assert!(r.frame.is_some());
        let deadline = s.poll_timeout().unwrap();
        assert_eq!(deadline, t1 + super::super::DEFAULT_TIMEOUT);
        assert_eq!(s.handle_timeout(Instant::from_micros(deadline.as_micros() - 1), &mut od), Response::NONE);
        let r = s.handle_timeout(deadline, &mut od);
        assert_eq!(r.frame, Some([0x80, 0x00, 0x20, 0x00, 0x00, 0x00, 0x04, 0x05]));
        assert_eq!(r.event, Some(SdoEvent::Aborted { index: 0x2000, sub: 0, code: AbortCode::SdoTimeout }));
        assert!(s.is_idle() && s.poll_timeout().is_none());
        assert_eq!(od.aborted_writes, 2);

        // new-initiate variant (SDO-29)
        exchange(&mut s, &mut od, [0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0x00, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37], Some([0x20, 0, 0, 0, 0, 0, 0, 0]));
        exchange(
            &mut s,
            &mut od,
            [0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0],
            Some([0x43, 0x00, 0x10, 0x00, 0x91, 0x01, 0, 0]),
        );
        assert_eq!(od.aborted_writes, 3);
        assert!(s.is_idle());
        assert_eq!(od.domain(), b"123456789"); // the abandoned write left the old value visible
    }

    #[test]
    fn segmented_length_checks() {
        let (mut s, mut od) = (server(), TestOd::new());
        // announced 9, sends 14 → too high at the second segment
        exchange(&mut s, &mut od, [0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0x00, 1, 2, 3, 4, 5, 6, 7], Some([0x20, 0, 0, 0, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0x11, 1, 2, 3, 4, 5, 6, 7], abort_of(0x2000, 0, AbortCode::LengthTooHigh));
        // announced 9, sends 7 → too low at the last segment
        exchange(&mut s, &mut od, [0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0x01, 1, 2, 3, 4, 5, 6, 7], abort_of(0x2000, 0, AbortCode::LengthTooLow));
        // segmented U64 without size via the scratch
        exchange(&mut s, &mut od, [0x20, 0x05, 0x20, 0x00, 0, 0, 0, 0], Some([0x60, 0x05, 0x20, 0x00, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0x00, 1, 2, 3, 4, 5, 6, 7], Some([0x20, 0, 0, 0, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0x1D, 8, 0, 0, 0, 0, 0, 0], Some([0x30, 0, 0, 0, 0, 0, 0, 0]));
        assert_eq!(od.get(0x2005, 0), Some(0x0807_0605_0403_0201));
        // 9 bytes into the 8-byte scratch without size
        exchange(&mut s, &mut od, [0x20, 0x05, 0x20, 0x00, 0, 0, 0, 0], Some([0x60, 0x05, 0x20, 0x00, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0x00, 1, 2, 3, 4, 5, 6, 7], Some([0x20, 0, 0, 0, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0x1B, 8, 9, 0, 0, 0, 0, 0], abort_of(0x2005, 0, AbortCode::LengthTooHigh));
    }

    #[test]
    fn segmented_upload_64_byte_string_and_read_error() {
        let (mut s, mut od) = (server(), TestOd::new());
        exchange(&mut s, &mut od, [0x40, 0x04, 0x20, 0x00, 0, 0, 0, 0], Some([0x41, 0x04, 0x20, 0x00, 64, 0, 0, 0]));
        let mut got = [0u8; 64];
        let mut n = 0;
        for i in 0..10u8 {
            let t = i % 2 == 1;
            let r = s.handle_request(T0, &[0x60 | (u8::from(t) << 4), 0, 0, 0, 0, 0, 0, 0], &mut od);
            let seg = Segment::parse(&r.frame.unwrap()).unwrap();
            assert_eq!(seg.toggle, t);
            got[n..n + seg.bytes().len()].copy_from_slice(seg.bytes());
            n += seg.bytes().len();
            assert_eq!(seg.last, i == 9);
        }
        assert_eq!(&got, STRING64);
        // 2006h fails reading at offset 14: the third segment aborts with the OD's code (0606 0000h)
        exchange(&mut s, &mut od, [0x40, 0x06, 0x20, 0x00, 0, 0, 0, 0], Some([0x41, 0x06, 0x20, 0x00, 200, 0, 0, 0]));
        exchange(&mut s, &mut od, [0x60, 0, 0, 0, 0, 0, 0, 0], Some([0x00, 0x55, 0x55, 0x55, 0x55, 0x55, 0x55, 0x55]));
        exchange(&mut s, &mut od, [0x70, 0, 0, 0, 0, 0, 0, 0], Some([0x10, 0x55, 0x55, 0x55, 0x55, 0x55, 0x55, 0x55]));
        exchange(&mut s, &mut od, [0x60, 0, 0, 0, 0, 0, 0, 0], abort_of(0x2006, 0, AbortCode::HardwareError));
    }

    #[test]
    fn v_sdo_block_download_8_1_and_variants() {
        let (mut s, mut od) = (server(), TestOd::new());
        exchange(
            &mut s,
            &mut od,
            [0xC6, 0x00, 0x20, 0x00, 0x09, 0, 0, 0],
            Some([0xA4, 0x00, 0x20, 0x00, 0x7F, 0, 0, 0]),
        );
        exchange(&mut s, &mut od, [0x01, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37], None);
        exchange(&mut s, &mut od, [0x82, 0x38, 0x39, 0, 0, 0, 0, 0], Some([0xA2, 0x02, 0x7F, 0, 0, 0, 0, 0]));
        assert_eq!(s.state(), ServerState::BlockDownloadEnd);
        let r = exchange(&mut s, &mut od, [0xD5, 0xC3, 0x31, 0, 0, 0, 0, 0], Some([0xA1, 0, 0, 0, 0, 0, 0, 0]));
        assert_eq!(r.event, Some(SdoEvent::Written { index: 0x2000, sub: 0 }));
        assert_eq!(od.domain(), b"123456789");

        // CRC error variant
        exchange(
            &mut s,
            &mut od,
            [0xC6, 0x00, 0x20, 0x00, 0x09, 0, 0, 0],
            Some([0xA4, 0x00, 0x20, 0x00, 0x7F, 0, 0, 0]),
        );
        exchange(&mut s, &mut od, [0x01, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37], None);
        exchange(&mut s, &mut od, [0x82, 0x38, 0x39, 0, 0, 0, 0, 0], Some([0xA2, 0x02, 0x7F, 0, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0xD5, 0, 0, 0, 0, 0, 0, 0], Some([0x80, 0x00, 0x20, 0x00, 0x04, 0x00, 0x04, 0x05]));
        assert_eq!(od.aborted_writes, 1);

        // no-CRC variant: sc = cc = 0, CRC bytes not checked
        exchange(
            &mut s,
            &mut od,
            [0xC2, 0x00, 0x20, 0x00, 0x09, 0, 0, 0],
            Some([0xA0, 0x00, 0x20, 0x00, 0x7F, 0, 0, 0]),
        );
        exchange(&mut s, &mut od, [0x01, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37], None);
        exchange(&mut s, &mut od, [0x82, 0x38, 0x39, 0, 0, 0, 0, 0], Some([0xA2, 0x02, 0x7F, 0, 0, 0, 0, 0]));
        // a CAN-level duplicate of the last segment is not taken for an end frame
        exchange(&mut s, &mut od, [0x82, 0x38, 0x39, 0, 0, 0, 0, 0], None);
        exchange(&mut s, &mut od, [0xD5, 0x12, 0x34, 0, 0, 0, 0, 0], Some([0xA1, 0, 0, 0, 0, 0, 0, 0]));

        // block download of a U32 via the scratch
        exchange(&mut s, &mut od, [0xC6, 0x7A, 0x60, 0x00, 4, 0, 0, 0], Some([0xA4, 0x7A, 0x60, 0x00, 0x7F, 0, 0, 0]));
        exchange(&mut s, &mut od, [0x81, 0x10, 0x27, 0, 0, 0, 0, 0], Some([0xA2, 0x01, 0x7F, 0, 0, 0, 0, 0]));
        let mut crc = Crc16::new();
        crc.update(&[0x10, 0x27, 0, 0]);
        let [c0, c1] = crc.get().to_le_bytes();
        exchange(&mut s, &mut od, [0xCD, c0, c1, 0, 0, 0, 0, 0], Some([0xA1, 0, 0, 0, 0, 0, 0, 0]));
        assert_eq!(od.get(0x607A, 0), Some(10_000));
    }

    #[test]
    fn v_sdo_block_download_8_2_go_back_n() {
        let mut s = server().with_block_size(3);
        let mut od = TestOd::new();
        exchange(
            &mut s,
            &mut od,
            [0xC6, 0x00, 0x20, 0x00, 0x10, 0, 0, 0],
            Some([0xA4, 0x00, 0x20, 0x00, 0x03, 0, 0, 0]),
        );
        exchange(&mut s, &mut od, [0x01, 0x41, 0x42, 0x43, 0x44, 0x45, 0x46, 0x47], None);
        exchange(&mut s, &mut od, [0x83, 0x4F, 0x50, 0, 0, 0, 0, 0], Some([0xA2, 0x01, 0x03, 0, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0x01, 0x48, 0x49, 0x4A, 0x4B, 0x4C, 0x4D, 0x4E], None);
        exchange(&mut s, &mut od, [0x82, 0x4F, 0x50, 0, 0, 0, 0, 0], Some([0xA2, 0x02, 0x03, 0, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0xD5, 0x80, 0x60, 0, 0, 0, 0, 0], Some([0xA1, 0, 0, 0, 0, 0, 0, 0]));
        assert_eq!(od.domain(), b"ABCDEFGHIJKLMNOP");
    }

    /// SDO-40/SDO-41: while waiting for "end block download", a late segment (here the last segment again as
    /// number 1 of a repeated sub-block, 81h) is ignored, not read as an abort with reserved bits; the end
    /// frame still completes the transfer.
    #[test]
    fn late_segment_before_block_end_is_ignored() {
        let mut s = server().with_block_size(8);
        let mut od = TestOd::new();
        exchange(&mut s, &mut od, [0xC6, 0x00, 0x20, 0x00, 0x10, 0, 0, 0], Some([0xA4, 0x00, 0x20, 0x00, 8, 0, 0, 0]));
        exchange(&mut s, &mut od, [0x01, 0x41, 0x42, 0x43, 0x44, 0x45, 0x46, 0x47], None);
        exchange(&mut s, &mut od, [0x02, 0x48, 0x49, 0x4A, 0x4B, 0x4C, 0x4D, 0x4E], None);
        exchange(&mut s, &mut od, [0x83, 0x4F, 0x50, 0, 0, 0, 0, 0], Some([0xA2, 0x03, 0x08, 0, 0, 0, 0, 0]));
        assert_eq!(s.state(), ServerState::BlockDownloadEnd);
        // late copies under other sequence numbers, last bit or not: silence, still waiting for the end
        for late in [[0x81, 0x4F, 0x50, 0, 0, 0, 0, 0], [0x82, 0x2E, 0x4D, 0x6C, 0x8B, 0xAA, 0xC9, 0], [0x02; 8]] {
            let r = exchange(&mut s, &mut od, late, None);
            assert_eq!(r.event, None, "{late:02X?}");
            assert_eq!(s.state(), ServerState::BlockDownloadEnd, "{late:02X?}");
        }
        let mut crc = Crc16::new();
        crc.update(b"ABCDEFGHIJKLMNOP");
        let [c0, c1] = crc.get().to_le_bytes();
        let r = exchange(&mut s, &mut od, [0xD5, c0, c1, 0, 0, 0, 0, 0], Some([0xA1, 0, 0, 0, 0, 0, 0, 0]));
        assert_eq!(r.event, Some(SdoEvent::Written { index: 0x2000, sub: 0 }));
        assert_eq!(od.domain(), b"ABCDEFGHIJKLMNOP");
        // a seqno beyond the block size cannot be a segment: 89h is an abort (reserved bits set, SDO-02)
        exchange(&mut s, &mut od, [0xC6, 0x00, 0x20, 0x00, 0x01, 0, 0, 0], Some([0xA4, 0x00, 0x20, 0x00, 8, 0, 0, 0]));
        exchange(&mut s, &mut od, [0x81, 0x41, 0, 0, 0, 0, 0, 0], Some([0xA2, 0x01, 0x08, 0, 0, 0, 0, 0]));
        let r = exchange(&mut s, &mut od, [0x89, 0x00, 0x20, 0x00, 0x00, 0x00, 0x04, 0x05], None);
        assert!(matches!(r.event, Some(SdoEvent::AbortReceived { code: 0x0504_0000, .. })), "{:?}", r.event);
        assert!(s.is_idle());
    }

    #[test]
    fn block_download_sequence_and_size_errors() {
        let mut s = server().with_block_size(3);
        let mut od = TestOd::new();
        // seqno 0 and seqno > blksize → 0504 0003h
        for bad in [0x00u8, 0x04, 0x80 | 0x05] {
            exchange(
                &mut s,
                &mut od,
                [0xC4, 0x00, 0x20, 0x00, 0, 0, 0, 0],
                Some([0xA4, 0x00, 0x20, 0x00, 0x03, 0, 0, 0]),
            );
            exchange(
                &mut s,
                &mut od,
                [bad, 1, 2, 3, 4, 5, 6, 7],
                abort_of(0x2000, 0, AbortCode::InvalidSequenceNumber),
            );
        }
        // an abort frame during a sub-block is an abort, not a segment (SDO-33: not answered)
        exchange(&mut s, &mut od, [0xC4, 0x00, 0x20, 0x00, 0, 0, 0, 0], Some([0xA4, 0x00, 0x20, 0x00, 0x03, 0, 0, 0]));
        let r = exchange(&mut s, &mut od, [0x80, 0x00, 0x20, 0x00, 0x00, 0x00, 0x00, 0x08], None);
        assert_eq!(r.event, Some(SdoEvent::AbortReceived { index: 0x2000, sub: 0, code: 0x0800_0000 }));
        assert!(s.is_idle());
        // more data than announced → 0607 0012h; less → 0607 0013h
        exchange(
            &mut s,
            &mut od,
            [0xC6, 0x00, 0x20, 0x00, 0x03, 0, 0, 0],
            Some([0xA4, 0x00, 0x20, 0x00, 0x03, 0, 0, 0]),
        );
        exchange(&mut s, &mut od, [0x01, 1, 2, 3, 4, 5, 6, 7], None);
        exchange(&mut s, &mut od, [0x02, 1, 2, 3, 4, 5, 6, 7], abort_of(0x2000, 0, AbortCode::LengthTooHigh));
        exchange(
            &mut s,
            &mut od,
            [0xC2, 0x00, 0x20, 0x00, 0x09, 0, 0, 0],
            Some([0xA0, 0x00, 0x20, 0x00, 0x03, 0, 0, 0]),
        );
        exchange(&mut s, &mut od, [0x81, 1, 2, 3, 4, 5, 6, 7], Some([0xA2, 0x01, 0x03, 0, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0xC1, 0, 0, 0, 0, 0, 0, 0], abort_of(0x2000, 0, AbortCode::LengthTooLow));
        // a block end frame while idle, an upload segment request while downloading → 0504 0001h
        exchange(&mut s, &mut od, [0xC1, 0, 0, 0, 0, 0, 0, 0], abort_of(0, 0, AbortCode::InvalidCommandSpecifier));
        exchange(&mut s, &mut od, [0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0x60, 0, 0, 0, 0, 0, 0, 0], abort_of(0x2000, 0, AbortCode::InvalidCommandSpecifier));
    }

    #[test]
    fn v_sdo_block_upload_8_3() {
        let (mut s, mut od) = (server(), TestOd::new());
        od.set_domain(b"123456789");
        exchange(
            &mut s,
            &mut od,
            [0xA4, 0x00, 0x20, 0x00, 0x7F, 0x00, 0, 0],
            Some([0xC6, 0x00, 0x20, 0x00, 0x09, 0, 0, 0]),
        );
        assert!(!s.wants_transmit());
        exchange(&mut s, &mut od, [0xA3, 0, 0, 0, 0, 0, 0, 0], None);
        assert!(s.wants_transmit());
        assert_eq!(s.poll_transmit(T0, &mut od).unwrap().frame, Some([0x01, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37]));
        assert_eq!(s.poll_transmit(T0, &mut od).unwrap().frame, Some([0x82, 0x38, 0x39, 0, 0, 0, 0, 0]));
        assert!(s.poll_transmit(T0, &mut od).is_none());
        exchange(&mut s, &mut od, [0xA2, 0x02, 0x7F, 0, 0, 0, 0, 0], Some([0xD5, 0xC3, 0x31, 0, 0, 0, 0, 0]));
        let r = exchange(&mut s, &mut od, [0xA1, 0, 0, 0, 0, 0, 0, 0], None);
        assert_eq!(r.event, Some(SdoEvent::Uploaded { index: 0x2000, sub: 0 }));
        assert!(s.is_idle());
        // INTEROP: cc = 0 → sc = 0 and CRC 0
        exchange(
            &mut s,
            &mut od,
            [0xA0, 0x00, 0x20, 0x00, 0x7F, 0x00, 0, 0],
            Some([0xC2, 0x00, 0x20, 0x00, 0x09, 0, 0, 0]),
        );
        exchange(&mut s, &mut od, [0xA3, 0, 0, 0, 0, 0, 0, 0], None);
        while s.poll_transmit(T0, &mut od).is_some() {}
        exchange(&mut s, &mut od, [0xA2, 0x02, 0x7F, 0, 0, 0, 0, 0], Some([0xD5, 0, 0, 0, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0xA1, 0, 0, 0, 0, 0, 0, 0], None);
    }

    #[test]
    fn block_upload_retransmission_and_errors() {
        let (mut s, mut od) = (server(), TestOd::new());
        od.set_domain(b"ABCDEFGHIJKLMNOP");
        exchange(
            &mut s,
            &mut od,
            [0xA4, 0x00, 0x20, 0x00, 0x02, 0x00, 0, 0],
            Some([0xC6, 0x00, 0x20, 0x00, 0x10, 0, 0, 0]),
        );
        exchange(&mut s, &mut od, [0xA3, 0, 0, 0, 0, 0, 0, 0], None);
        assert_eq!(s.poll_transmit(T0, &mut od).unwrap().frame.unwrap()[0], 0x01);
        assert_eq!(s.poll_transmit(T0, &mut od).unwrap().frame.unwrap()[0], 0x02);
        assert!(s.poll_transmit(T0, &mut od).is_none());
        // client got only seq 1: go back to "HIJKLMN" as seqno 1, new blksize 3
        exchange(&mut s, &mut od, [0xA2, 0x01, 0x03, 0, 0, 0, 0, 0], None);
        assert_eq!(s.poll_transmit(T0, &mut od).unwrap().frame, Some([0x01, 0x48, 0x49, 0x4A, 0x4B, 0x4C, 0x4D, 0x4E]));
        assert_eq!(s.poll_transmit(T0, &mut od).unwrap().frame, Some([0x82, 0x4F, 0x50, 0, 0, 0, 0, 0]));
        assert!(s.poll_transmit(T0, &mut od).is_none());
        exchange(&mut s, &mut od, [0xA2, 0x02, 0x03, 0, 0, 0, 0, 0], Some([0xD5, 0x80, 0x60, 0, 0, 0, 0, 0]));
        exchange(&mut s, &mut od, [0xA1, 0, 0, 0, 0, 0, 0, 0], None);
        // invalid blksize at initiate and in the ack; ackseq beyond what was sent
        exchange(
            &mut s,
            &mut od,
            [0xA4, 0x00, 0x20, 0x00, 0x00, 0x00, 0, 0],
            abort_of(0x2000, 0, AbortCode::InvalidBlockSize),
        );
        exchange(
            &mut s,
            &mut od,
            [0xA4, 0x00, 0x20, 0x00, 0x80, 0x00, 0, 0],
            abort_of(0x2000, 0, AbortCode::InvalidBlockSize),
        );
        exchange(
            &mut s,
            &mut od,
            [0xA4, 0x00, 0x20, 0x00, 0x02, 0x00, 0, 0],
            Some([0xC6, 0x00, 0x20, 0x00, 0x10, 0, 0, 0]),
        );
        exchange(&mut s, &mut od, [0xA3, 0, 0, 0, 0, 0, 0, 0], None);
        while s.poll_transmit(T0, &mut od).is_some() {}
        exchange(&mut s, &mut od, [0xA2, 0x02, 0x00, 0, 0, 0, 0, 0], abort_of(0x2000, 0, AbortCode::InvalidBlockSize));
        exchange(
            &mut s,
            &mut od,
            [0xA4, 0x00, 0x20, 0x00, 0x02, 0x00, 0, 0],
            Some([0xC6, 0x00, 0x20, 0x00, 0x10, 0, 0, 0]),
        );
        exchange(&mut s, &mut od, [0xA3, 0, 0, 0, 0, 0, 0, 0], None);
        while s.poll_transmit(T0, &mut od).is_some() {}
        exchange(
            &mut s,
            &mut od,
            [0xA2, 0x03, 0x02, 0, 0, 0, 0, 0],
            abort_of(0x2000, 0, AbortCode::InvalidSequenceNumber),
        );
        // read error during a sub-block
        exchange(
            &mut s,
            &mut od,
            [0xA4, 0x06, 0x20, 0x00, 0x7F, 0x00, 0, 0],
            Some([0xC6, 0x06, 0x20, 0x00, 200, 0, 0, 0]),
        );
        exchange(&mut s, &mut od, [0xA3, 0, 0, 0, 0, 0, 0, 0], None);
        assert!(s.poll_transmit(T0, &mut od).unwrap().event.is_none());
        assert!(s.poll_transmit(T0, &mut od).unwrap().event.is_none());
        let r = s.poll_transmit(T0, &mut od).unwrap();
        assert_eq!(r.frame, abort_of(0x2006, 0, AbortCode::HardwareError));
        assert!(s.is_idle());
    }

    #[test]
    fn v_sdo_block_upload_8_4_protocol_switch() {
        let (mut s, mut od) = (server(), TestOd::new());
        od.set_domain(b"123456789");
        exchange(
            &mut s,
            &mut od,
            [0xA4, 0x00, 0x20, 0x00, 0x7F, 0x15, 0, 0],
            Some([0x41, 0x00, 0x20, 0x00, 0x09, 0, 0, 0]),
        );
        exchange(&mut s, &mut od, [0x60, 0, 0, 0, 0, 0, 0, 0], Some([0x00, 0x31, 0x32, 0x33, 0x34, 0x35, 0x36, 0x37]));
        exchange(&mut s, &mut od, [0x70, 0, 0, 0, 0, 0, 0, 0], Some([0x1B, 0x38, 0x39, 0, 0, 0, 0, 0]));
        exchange(
            &mut s,
            &mut od,
            [0xA4, 0x17, 0x10, 0x00, 0x7F, 0x15, 0, 0],
            Some([0x4B, 0x17, 0x10, 0x00, 0x64, 0, 0, 0]),
        );
        assert!(s.is_idle());
    }

    #[test]
    fn abort_handling_and_ignored_frames() {
        let (mut s, mut od) = (server(), TestOd::new());
        // abort while idle: silence (SDO-33)
        exchange(&mut s, &mut od, [0x80, 0, 0x20, 0, 0, 0, 0x04, 0x05], None);
        // abort during a segmented download: silence, OD told, idle
        exchange(&mut s, &mut od, [0x21, 0x00, 0x20, 0x00, 0x09, 0, 0, 0], Some([0x60, 0x00, 0x20, 0x00, 0, 0, 0, 0]));
        let r = exchange(&mut s, &mut od, [0x80, 0x00, 0x20, 0x00, 0x00, 0x00, 0x04, 0x05], None);
        assert_eq!(r.event, Some(SdoEvent::AbortReceived { index: 0x2000, sub: 0, code: 0x0504_0000 }));
        assert_eq!(od.aborted_writes, 1);
        assert!(s.is_idle() && s.poll_timeout().is_none());
        // DLC < 8 (CAN-07 choice: ignored), also mid-transfer; the transfer goes on
        for n in 0..8 {
            assert_eq!(s.handle_request(T0, &[0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0][..n], &mut od), Response::NONE);
        }
        exchange(&mut s, &mut od, [0x40, 0x09, 0x10, 0x00, 0, 0, 0, 0], Some([0x41, 0x09, 0x10, 0x00, 0x17, 0, 0, 0]));
        assert_eq!(s.handle_request(T0, &[0x60], &mut od), Response::NONE);
        assert_eq!(s.state(), ServerState::Uploading);
        // unknown ccs mid-transfer: abort with the transfer's multiplexer
        exchange(&mut s, &mut od, [0xE0, 0, 0, 0, 0, 0, 0, 0], abort_of(0x1009, 0, AbortCode::InvalidCommandSpecifier));
        // a download segment while idle
        exchange(&mut s, &mut od, [0x00, 1, 2, 3, 4, 5, 6, 7], abort_of(0, 0, AbortCode::InvalidCommandSpecifier));
        // block upload start / ack / end while idle
        for b0 in [0xA3u8, 0xA2, 0xA1] {
            exchange(&mut s, &mut od, [b0, 1, 1, 0, 0, 0, 0, 0], abort_of(0, 0, AbortCode::InvalidCommandSpecifier));
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
}
