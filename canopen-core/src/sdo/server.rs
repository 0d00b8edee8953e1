//! The SDO server: a sans-IO state machine serving an [`ObjectDictionary`] (CiA 301 §7.2.4).
//!
//! Implements SDO-01..SDO-51 (SDO-52 partly: out of memory is passed through from the OD, no
//! 060A 0023h because each server has its own channel), SDO-53/54/55 as [`SdoServerParams`] (the lead wires
//! them into 1200h–127Fh), ABORT-01..ABORT-11, ABORT-16..ABORT-31 as far as the OD reports them.
//! Not yet: SDO in NMT Stopped is the node's business (NMT-18: the node must not feed frames then).
//!
//! # Files
//!
//! One transfer state (`State`) and one dispatcher here, one file per protocol beside it:
//!
//! - `server.rs` (this file): parameters (SDO-53..SDO-55), the frame dispatch (on the command byte, SDO-08:
//!   no request enum in between; responses are built with [`crate::wire::sdo::frame`]), aborts sent and
//!   received (SDO-09, SDO-29, SDO-32, SDO-33, ABORT-01..ABORT-11), the time-out (SDO-31), [`SdoServers`]
//!   (SDO-57).
//! - `server/segmented.rs`: expedited and segmented download and upload (SDO-10..SDO-30).
//! - `server/block_download.rs`: block download (SDO-35, SDO-36, SDO-38..SDO-42, SDO-47..SDO-51).
//! - `server/block_upload.rs`: block upload with the protocol switch (SDO-37, SDO-43..SDO-51).
//! - `server/tests.rs`: the unit tests (segmented and block exchanges byte for byte).
//!
//! The per-frame paths cross these files, so [`SdoServer::handle_request`], `dispatch` and the helpers they
//! reach on every segment (`Sink::write`, the block download segment and flush, the initiate handlers) are
//! `#[inline]`: without it, a generic function is compiled in its own module's codegen unit, where the
//! caller's cannot inline it (the split then cost up to 47 instructions per block segment; `dispatch` out of
//! line cost 14 to 23 instructions per frame on the expedited and block paths).
//!
//! # Driving it
//!
//! - [`SdoServer::handle_request`] for every frame received on the server's rx COB-ID; the [`Response`] says
//!   which frame to send (on the tx COB-ID), if any, and what happened ([`SdoEvent`]).
//! - [`SdoServer::poll_transmit`] while [`SdoServer::wants_transmit`]: during a block upload the server
//!   produces a whole sub-block, one frame per call, so the node pulls frames only when its bounded TX queue
//!   has room.
//! - [`SdoServer::poll_timeout`] / [`SdoServer::handle_timeout`]: the protocol time-out (SDO-31, 0504 0000h),
//!   from the last frame received or sent. Once a block-upload sub-block has been handed out, `poll_timeout`
//!   is due at once and the next `handle_timeout` starts the time-out: a runner that takes a whole sub-block
//!   and then needs long to send it (a slow or busy bus) tells the time next when it went out, so the
//!   client gets its full time to acknowledge.
//!
//! # Per-frame cost
//!
//! `dispatch` switches on the command byte (SDO-08) and each handler reads its few fields from the frame; every
//! response is one [`frame`](crate::wire::sdo::frame) call (command byte, bytes 1–3, bytes 4–7), and upload
//! segments are read from the OD straight into the response. The error paths (`abort`, `invalid`,
//! `abort_received`) are out of line. `scripts/bench-node.sh` (whole node, x86-64): expedited upload ~294
//! instructions per frame, of which ~60 are the dictionary's lookup and read of 1000h; expedited download ~297
//! (~45 in the dictionary; ~268 when the application takes no write events, [`ObjectDictionary::write_events`]);
//! segmented upload ~259 per frame (the segments read at the slot found once, inlined, no search); block
//! download ~256 per segment (~55, the streamed write). About 80 to 100 of each are the driver loop (events,
//! peek and transmitted). The time-out costs a frame one store (the instant it came): the deadline
//! is computed when the node asks for it, not per frame.
//!
//! # Data path, RAM
//!
//! Data moves straight between frames and the OD: fixed-size values (≤ 8 bytes) are collected in an 8-byte
//! scratch and written atomically with [`ObjectDictionary::write`]; everything else is streamed with
//! `begin_write`/`write_chunk`/`end_write` (and `abort_write` when a transfer is abandoned); uploads read
//! 1..7 bytes at a time at an offset with [`ObjectDictionary::read_slot`], the entry's position looked up once
//! at the initiate ([`ObjectDictionary::slot`]: no search per segment in a derived dictionary). Block download writes each in-order
//! segment to the OD as soon as the next one arrives: only the last 7 bytes are held back, because the number
//! of valid bytes in the last segment is only known from the end frame (SDO-41). The streaming and the
//! segmented-upload paths are built only for a dictionary that can use them ([`ObjectDictionary::STREAMS`],
//! [`ObjectDictionary::SEGMENTED_UPLOADS`]: a device whose entries are all numbers of 1..=4 bytes has
//! neither). The whole server is
//! [`SdoServer::RAM_BYTES`] = 72 bytes or less (`size_of::<SdoServer>()` is 72 on x86-64, asserted in a unit
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
//!   arrives (go-back-n: with segment 2 of 3 lost, 83h closes the sub-block and is answered A2 01). A repeat of the last accepted segment or of the one that made the
//!   server acknowledge (a CAN-level duplicate) is ignored without an acknowledgement: the server has that
//!   sequence number already, and a second acknowledge would read as the next sub-block's.
//! - **Stalled sub-block** (SDO-40, as CANopenNode does at 70 % of its timeout): when a sub-block has
//!   in-order segments but no frame arrives for a quarter of the SDO timeout (its last segment was lost, so
//!   the client waits for the acknowledge and the server for segments), the server acknowledges the last
//!   in-order segment once; the client goes back to the next one (our client, and python-canopen's
//!   `BlockDownloadStream`, whose 0.3 s response timeout is longer than 250 ms at the default 1 s). The SDO
//!   timeout still runs from the last frame received. With no in-order segment since the last acknowledge
//!   the server does not guess (the client may not have that acknowledge yet) and waits for the timeout.
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
//! // Write 607Ah:00 = 1000: 23 7A 60 00 E8 03 00 00 -> 60 7A 60 00 ...
//! let r = server.handle_request(Instant::ZERO, &[0x23, 0x7A, 0x60, 0x00, 0xE8, 0x03, 0x00, 0x00], &mut od);
//! assert_eq!(r.frame, Some([0x60, 0x7A, 0x60, 0x00, 0, 0, 0, 0]));
//! assert_eq!(r.event, Some(SdoEvent::Written { index: 0x607A, sub: 0 }));
//! assert_eq!(od.0, 1000);
//! ```

use crate::cob::{CobIdEntry, FunctionCode};
use crate::od::{AbortCode, ObjectDictionary};
use crate::time::{Deadline, Duration, Instant};
#[cfg(feature = "sdo-block")]
use crate::wire::sdo::MAX_BLKSIZE;
use crate::wire::sdo::{abort_frame, Multiplexer};
use crate::NodeId;

// Block transfer (feature `sdo-block`): without it, block initiate requests are answered 0504 0001h.
#[cfg(feature = "sdo-block")]
mod block_download;
#[cfg(feature = "sdo-block")]
mod block_upload;
mod segmented;

#[cfg(feature = "sdo-block")]
use block_download::{is_late_segment, BlockDownload};
#[cfg(feature = "sdo-block")]
use block_upload::{BlockUpload, UploadPhase};

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
        // One test for all four bits: it runs for every frame received and every response sent.
        (self.cob_rx.raw() | self.cob_tx.raw()) & (CobIdEntry::BIT31 | CobIdEntry::FRAME) == 0
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

/// A time in µs kept at 4-byte alignment, so that the node (and the SDO server in it) is 4-aligned on a
/// 32-bit target: copying or clearing it then takes `__aeabi_memcpy4`/`memclr4`, which the firmware links
/// anyway, and not also their 8-byte variants (330 B of flash on Cortex-M). See [`crate::time`].
#[derive(Debug, Clone, Copy)]
#[repr(C, packed(4))]
struct Micros(u64);

/// The time-out as [`SdoServer`] keeps it, µs: zero (disabled) becomes `u64::MAX`, so that a deadline
/// `since + timeout` saturates to `u64::MAX`, which is [`Deadline::NONE`].
const fn stored_timeout(timeout: Duration) -> u64 {
    if timeout.is_zero() {
        u64::MAX
    } else {
        timeout.as_micros()
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

    /// [`NONE`](Self::NONE) built in place: a struct constant is copied from flash whole (its 20 bytes by
    /// `ldm`/`stm` on Cortex-M), this is two stores of the `None` tags. Used where it measured smaller
    /// (`scripts/footprint.sh`): at some other exits LLVM shares one copy of the constant, and there the
    /// stores cost more.
    #[inline]
    const fn none() -> Response {
        Response { frame: None, event: None }
    }

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

impl Sink {
    /// Writes the first `len` (≤ 7) of a segment's data bytes at `offset`: into the scratch (0607 0012h past
    /// its 8 bytes) or as a chunk to the OD.
    #[inline]
    fn write<O: ObjectDictionary + ?Sized>(
        &mut self,
        mux: Multiplexer,
        offset: u32,
        data: &[u8; 7],
        len: usize,
        od: &mut O,
    ) -> Result<(), AbortCode> {
        let len = len.min(7);
        match self {
            Sink::Scratch(buf) => {
                // At most two segments reach the scratch: a plain copy (64-bit shifts cost 300 B on Cortex-M).
                let start = offset as usize;
                let dst = buf.get_mut(start..start + len).ok_or(AbortCode::LengthTooHigh)?;
                dst.copy_from_slice(&data[..len]);
                Ok(())
            }
            Sink::Stream if O::STREAMS => od.write_chunk(mux.index, mux.sub, offset as usize, &data[..len]),
            // Never built for such a dictionary (`open_sink`); the arm keeps its streaming path out of the build.
            Sink::Stream => Err(AbortCode::GeneralError),
        }
    }

    /// [`write`](Self::write) at `*offset`, which then moves past the bytes: 0607 0012h when they would pass
    /// the announced `size` (SDO-18) or the 32-bit offset. The one copy for the segmented download's segments
    /// and the block download's held segment (out of line on a bare-metal target).
    #[inline]
    fn take<O: ObjectDictionary + ?Sized>(
        &mut self,
        mux: Multiplexer,
        offset: &mut u32,
        size: Option<u32>,
        data: &[u8; 7],
        len: usize,
        od: &mut O,
    ) -> Result<(), AbortCode> {
        let end = offset.saturating_add(len as u32);
        if size.is_some_and(|s| end > s) || end == u32::MAX {
            return Err(AbortCode::LengthTooHigh);
        }
        self.write(mux, *offset, data, len, od)?;
        *offset = end;
        Ok(())
    }

    /// Commits `total` bytes: 0607 0013h when short of the announced `size` (SDO-18; past it was refused by
    /// [`take`](Self::take)), else the scratch with one atomic [`ObjectDictionary::write`], a stream with
    /// `end_write`. `total` is what `write` took, so at most the scratch's 8 bytes (`write` refused more).
    #[inline]
    fn finish<O: ObjectDictionary + ?Sized>(
        &self,
        mux: Multiplexer,
        total: u32,
        size: Option<u32>,
        od: &mut O,
    ) -> Result<(), AbortCode> {
        if size.is_some_and(|s| total < s) {
            return Err(AbortCode::LengthTooLow);
        }
        match self {
            Sink::Scratch(buf) => od.write(mux.index, mux.sub, &buf[..(total as usize).min(buf.len())]),
            Sink::Stream if O::STREAMS => od.end_write(mux.index, mux.sub, total as usize),
            Sink::Stream => Err(AbortCode::GeneralError), // never built, as in `write`
        }
    }
}

/// The one transfer state of a server: which protocol runs, and its progress. Each protocol's file handles
/// its own variant; the shared part (abort, reset, time-out, the multiplexer) is here.
#[derive(Debug, Clone, Copy)]
enum State {
    Idle,
    /// Segmented download (`segmented.rs`).
    Download {
        toggle: bool,
        offset: u32,
        size: Option<u32>,
        sink: Sink,
    },
    /// Segmented upload (`segmented.rs`). `slot`: the object's [`ObjectDictionary::slot`], for each segment's
    /// read.
    Upload {
        toggle: bool,
        offset: u32,
        size: u32,
        slot: u16,
    },
    #[cfg(feature = "sdo-block")]
    BlockDownload(BlockDownload),
    #[cfg(feature = "sdo-block")]
    BlockUpload(BlockUpload),
}

/// One SDO server channel (SDO-01..SDO-51). See the [module docs](self) for the driving calls and choices.
///
/// ```
/// use canopen_core::sdo::{SdoServer, SdoServerParams};
/// use canopen_core::{Duration, NodeId};
/// let s = SdoServer::new(SdoServerParams::default_server(NodeId::new(3).unwrap()))
///     .with_timeout(Duration::from_millis(500));
/// #[cfg(feature = "sdo-block")] // block transfer is a Cargo feature (default on)
/// let s = s.with_block_size(16);
/// assert!(s.is_idle());
/// assert!(core::mem::size_of::<SdoServer>() <= SdoServer::RAM_BYTES);
/// ```
#[derive(Debug, Clone)]
pub struct SdoServer {
    params: SdoServerParams,
    /// The protocol time-out (SDO-31), µs; a disabled (zero) one is kept as `u64::MAX`, so that the deadline
    /// `since + timeout` saturates to none, no flag.
    timeout: Micros,
    #[cfg(feature = "sdo-block")]
    block_size: u8,
    /// When the transfer under way last received (block upload: sent) a frame, µs: its time-out deadline
    /// (SDO-31) is `since + timeout`, computed when asked ([`deadline`](Self::deadline)), so that a frame
    /// costs one store, not the deadline's arithmetic and a test for idle. `u64::MAX`: no deadline until the
    /// next frame (the time-out was disabled when the last one came). Meaningless while `state` is idle.
    since: Micros,
    /// The object of the transfer under way (meaningless while `state` is idle).
    mux: Multiplexer,
    state: State,
}

impl SdoServer {
    /// Upper bound of `size_of::<SdoServer>()` (asserted in a unit test; x86-64 and thumbv6m alike).
    ///
    /// ```
    /// # use canopen_core::sdo::SdoServer;
    /// assert!(core::mem::size_of::<SdoServer>() <= SdoServer::RAM_BYTES);
    /// ```
    pub const RAM_BYTES: usize = 72;

    /// A server with the [default time-out](super::DEFAULT_TIMEOUT) and block size 127.
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams};
    /// assert!(SdoServer::new(SdoServerParams::DISABLED).is_idle());
    /// ```
    pub const fn new(params: SdoServerParams) -> Self {
        SdoServer {
            params,
            timeout: Micros(stored_timeout(super::DEFAULT_TIMEOUT)),
            #[cfg(feature = "sdo-block")]
            block_size: MAX_BLKSIZE,
            since: Micros(0),
            mux: Multiplexer::new(0, 0),
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
        self.timeout = Micros(stored_timeout(timeout));
        self
    }

    /// Changes the protocol time-out (SDO-31) of a server in use; zero disables it. A transfer under way keeps
    /// the deadline it has (none while the time-out was disabled; disabling it removes the deadline at once;
    /// a deadline earlier than the new time-out after the origin becomes that) and uses the new time-out from
    /// its next frame on.
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams};
    /// # use canopen_core::Duration;
    /// let mut s = SdoServer::new(SdoServerParams::DISABLED);
    /// s.set_timeout(Duration::from_millis(250));
    /// assert!(s.is_idle());
    /// ```
    pub fn set_timeout(&mut self, timeout: Duration) {
        let new = stored_timeout(timeout);
        // `since` moves so that `since + new` is the deadline the transfer has; none stays none.
        let at = self.since.0.saturating_add(self.timeout.0);
        self.since = Micros(if at == u64::MAX { u64::MAX } else { at.saturating_sub(new) });
        self.timeout = Micros(new);
    }

    /// Sets the block size the server asks for in block download (clamped to 1..=127, SDO-36).
    ///
    /// ```
    /// # use canopen_core::sdo::{SdoServer, SdoServerParams};
    /// let s = SdoServer::new(SdoServerParams::DISABLED).with_block_size(0);
    /// assert!(s.is_idle());
    /// ```
    #[cfg(feature = "sdo-block")]
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

    /// `Some(id) ==` [`rx_cob_id`](Self::rx_cob_id), as the node tests every frame: the receive COB-ID's
    /// validity bits and CAN-ID in one masked compare, then the transmit COB-ID's validity.
    #[inline]
    pub(crate) const fn receives(&self, id: u16) -> bool {
        const INVALID: u32 = CobIdEntry::BIT31 | CobIdEntry::FRAME;
        self.params.cob_rx.raw() & (INVALID | 0x7FF) == id as u32 && self.params.cob_tx.raw() & INVALID == 0
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
            #[cfg(feature = "sdo-block")]
            State::BlockDownload(b) if b.ending => ServerState::BlockDownloadEnd,
            #[cfg(feature = "sdo-block")]
            State::BlockDownload(_) => ServerState::BlockDownloadSubBlock,
            #[cfg(feature = "sdo-block")]
            State::BlockUpload(b) => match b.phase {
                UploadPhase::Start => ServerState::BlockUploadStart,
                UploadPhase::Sending => ServerState::BlockUploadSending,
                UploadPhase::Sent | UploadPhase::WaitAck => ServerState::BlockUploadAck,
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
        self.deadline().get()
    }

    /// [`poll_timeout`](Self::poll_timeout) as a [`Deadline`], for the node's minimum over its services.
    #[inline(never)] // 64-bit arithmetic for the block download stall (~130 B on Cortex-M), used in 3 places
    pub(crate) const fn deadline(&self) -> Deadline {
        if self.is_idle() {
            return Deadline::NONE;
        }
        let after = self.timeout.0; // u64::MAX when disabled: the sum saturates to none
        #[cfg(feature = "sdo-block")]
        let after = if after == u64::MAX { after } else { self.block_delay(after) };
        // u64::MAX (none) when the time-out is disabled, or was when this transfer's last frame came (`since`)
        Deadline::new(Some(Instant::from_micros(self.since.0.saturating_add(after))))
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
        if !self.deadline().passed(now) {
            return Response::NONE; // none while idle
        }
        #[cfg(feature = "sdo-block")]
        if let Some(ack) = self.block_download_stalled() {
            return ack;
        }
        #[cfg(feature = "sdo-block")]
        if self.block_upload_sent(now) {
            return Response::NONE;
        }
        // a passed deadline means a transfer is under way: its multiplexer
        self.abort(od, AbortCode::SdoTimeout)
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
    /// // Object 5000h does not exist: abort 0602 0000h
    /// let r = s.handle_request(Instant::ZERO, &[0x40, 0x00, 0x50, 0x00, 0, 0, 0, 0], &mut Empty);
    /// assert_eq!(r.frame, Some([0x80, 0x00, 0x50, 0x00, 0x00, 0x00, 0x02, 0x06]));
    /// // short frames are ignored (CAN-07)
    /// assert_eq!(s.handle_request(Instant::ZERO, &[0x40, 0x00, 0x50], &mut Empty).frame, None);
    /// ```
    #[inline]
    pub fn handle_request<O: ObjectDictionary + ?Sized>(&mut self, now: Instant, data: &[u8], od: &mut O) -> Response {
        let Ok(b) = <&[u8; 8]>::try_from(data) else { return Response::none() };
        let r = self.dispatch(b, od);
        self.since = Micros(now.as_micros()); // the time-out runs from here (SDO-31), unless the server is idle now
        r
    }

    /// Drops the current transfer; tells the OD when a streamed write is abandoned.
    fn reset<O: ObjectDictionary + ?Sized>(&mut self, od: &mut O) {
        match self.state {
            // No stream without `O::STREAMS` (`open_sink`): then nothing to tell the dictionary.
            State::Download { sink: Sink::Stream, .. } if O::STREAMS => od.abort_write(self.mux.index, self.mux.sub),
            #[cfg(feature = "sdo-block")]
            State::BlockDownload(BlockDownload { sink: Sink::Stream, .. }) if O::STREAMS => {
                od.abort_write(self.mux.index, self.mux.sub)
            }
            _ => {}
        }
        self.state = State::Idle;
    }

    /// Ends the transfer with an abort frame (SDO-32) and [`SdoEvent::Aborted`], for the object in `mux`
    /// (a refused initiate and a frame out of state while idle store theirs there first). Out of line: it is
    /// reached from a dozen error paths, none of them hot, and none passes the multiplexer.
    #[inline(never)]
    fn abort<O: ObjectDictionary + ?Sized>(&mut self, od: &mut O, code: AbortCode) -> Response {
        let mux = self.mux;
        self.reset(od);
        Response {
            frame: Some(abort_frame(mux, code.code())),
            event: Some(SdoEvent::Aborted { index: mux.index, sub: mux.sub, code }),
        }
    }

    /// One frame, dispatched on its command byte straight to the handler (no request enum in between: the
    /// handlers read the fields they need from the frame).
    #[inline]
    fn dispatch<O: ObjectDictionary + ?Sized>(&mut self, b: &[u8; 8], od: &mut O) -> Response {
        let command = b[0];
        // SDO-32/SDO-33: the abort frame is 80h in every state, and is never answered.
        if command == 0x80 {
            return self.abort_received(Multiplexer::of_frame(b), b, od);
        }
        #[cfg(feature = "sdo-block")]
        if let State::BlockDownload(bd) = &self.state {
            if !bd.ending {
                return self.block_segment(b, od);
            }
            if is_late_segment(command, self.block_size) {
                return Response::NONE;
            }
        }
        // The multiplexer and data bytes are read in the arms that use them: read before the match, they
        // cost every segment frame 12 instructions (x86-64) for nothing.
        let mux = || Multiplexer::of_frame(b);
        let data = || u32::from_le_bytes([b[4], b[5], b[6], b[7]]);
        // ccs = bits 7–5 (SDO-08); for ccs 5 and 6 the sub-command is in the low bits.
        let initiated = match command >> 5 {
            0 => return self.download_segment(b, od),
            1 => {
                // `begin` written out: its call cost the expedited download 11 Cortex-M4 instructions
                // (test-qemu.sh)
                self.reset(od);
                self.mux = mux();
                return self.initiate_download(mux(), command, data(), od);
            }
            2 => {
                self.begin(b, od);
                return self.initiate_upload(od);
            }
            3 => return self.upload_segment(command & 0x10 != 0, od),
            4 => {
                // ccs 4 with non-zero reserved bits: still an abort (SDO-02), never answered; it names the
                // transfer's object (ignored while idle).
                return self.abort_received(self.mux, b, od);
            }
            #[cfg(feature = "sdo-block")]
            5 => match command & 0x03 {
                0 => {
                    self.begin(b, od);
                    self.block_upload_initiate(command & 0x04 != 0, b[4], b[5], od)
                }
                _ => return self.block_upload_request(b, od), // end, acknowledge, start
            },
            #[cfg(feature = "sdo-block")]
            6 if command & 0x01 == 0 => {
                self.begin(b, od);
                let size = (command & 0x02 != 0).then(data);
                return self.open_download(size, Some(command & 0x04 != 0), od);
            }
            #[cfg(feature = "sdo-block")]
            6 => return self.block_download_end((command >> 2) & 0x07, u16::from_le_bytes([b[1], b[2]]), od),
            // Without block transfer: an initiate is refused for its own object, the rest is out of state.
            #[cfg(not(feature = "sdo-block"))]
            5 if command & 0x03 == 0 => {
                self.begin(b, od);
                Err(AbortCode::InvalidCommandSpecifier)
            }
            #[cfg(not(feature = "sdo-block"))]
            6 if command & 0x01 == 0 => {
                self.begin(b, od);
                Err(AbortCode::InvalidCommandSpecifier)
            }
            #[cfg(not(feature = "sdo-block"))]
            5 | 6 => return self.invalid(od),
            _ => {
                if self.is_idle() {
                    self.mux = mux(); // idle: the frame's object, else the transfer's
                }
                return self.abort(od, AbortCode::InvalidCommandSpecifier);
            }
        };
        // a refused initiate: its own object (`begin` stored it once the transfer under way was dropped)
        initiated.unwrap_or_else(|code| self.abort(od, code))
    }

    /// The start of every initiate: the transfer under way is dropped (SDO-29: abandoned without an abort
    /// frame, `abort_write` for its object), then the frame's object is the server's, for the new transfer
    /// or for the abort that refuses it: no initiate keeps the multiplexer in registers across its call for
    /// its error path, and a refusal is `abort` alone. Out of line on a bare-metal target (one copy for the
    /// upload and block initiates; inline there, node -92 B instead of -152 B, minimal +12 B instead of
    /// +4 B), inline on the host, where `scripts/bench-node.sh` counts it per initiate. The expedited
    /// download's arm does the same two steps inline (the call cost it 11 Cortex-M4 instructions).
    #[cfg_attr(target_os = "none", inline(never))]
    #[cfg_attr(not(target_os = "none"), inline)]
    fn begin<O: ObjectDictionary + ?Sized>(&mut self, b: &[u8; 8], od: &mut O) {
        self.reset(od);
        self.mux = Multiplexer::of_frame(b);
    }

    /// An abort from the client (SDO-33): the transfer ends, nothing is sent; ignored when idle. Out of line:
    /// two arms of `dispatch` reach it, neither hot.
    #[inline(never)]
    fn abort_received<O: ObjectDictionary + ?Sized>(&mut self, mux: Multiplexer, b: &[u8; 8], od: &mut O) -> Response {
        if self.is_idle() {
            return Response::none();
        }
        self.reset(od);
        let code = u32::from_le_bytes([b[4], b[5], b[6], b[7]]);
        Response { frame: None, event: Some(SdoEvent::AbortReceived { index: mux.index, sub: mux.sub, code }) }
    }

    /// A well-formed frame that is not valid in the current state: 0504 0001h (SDO-09). Out of line, as
    /// [`abort`](Self::abort).
    #[inline(never)]
    fn invalid<O: ObjectDictionary + ?Sized>(&mut self, od: &mut O) -> Response {
        // frames in the wrong state: the transfer's multiplexer, or 0000h:00 when idle
        if self.is_idle() {
            self.mux = Multiplexer::default();
        }
        self.abort(od, AbortCode::InvalidCommandSpecifier)
    }
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
mod tests;
