//! Block download (CiA 301 §7.2.4.3.9–§7.2.4.3.14; SDO-35, SDO-36, SDO-38..SDO-42, SDO-47..SDO-51):
//! initiate (SDO-35, SDO-36), sub-block segments and their acknowledge (SDO-38..SDO-40, go-back-n), end with
//! the CRC check (SDO-41, SDO-48, SDO-49).
//!
//! Each in-order segment is written to the sink when the next one arrives: only the last 7 bytes are held
//! back, because the number of valid bytes in the last segment is only known from the end frame (SDO-41).
//!
//! Loss and duplicates (SDO-40, go-back-n): an out-of-order segment is dropped and the last in-order one is
//! acknowledged when the sub-block ends; a repeat of the segment just accepted or just acknowledged is
//! ignored, as is a repeat of the initiate request before the first segment; a sub-block that stalls for a quarter of the SDO timeout after in-order segments is acknowledged
//! up to them, so a lost last segment costs a quarter of the timeout instead of the whole transfer (see the
//! server's module docs for why once, and why not without in-order segments).

use super::block_upload::UploadPhase;
use super::{Response, SdoEvent, SdoServer, Sink, State};
use crate::od::{AbortCode, ObjectDictionary};
use crate::sdo::block::Crc16;
use crate::wire::sdo::{frame, Multiplexer};

/// The state of a block download (the shared [`State`]'s `BlockDownload`).
#[derive(Debug, Clone, Copy)]
pub(super) struct BlockDownload {
    pub(super) sink: Sink,
    /// Bytes written to the sink so far (everything before the held segment).
    offset: u32,
    size: Option<u32>,
    crc: Crc16,
    crc_on: bool,
    /// Next seqno expected in the current sub-block.
    expected: u8,
    /// The held segment as it came, byte 0 its c ‖ seqno, bytes 1–7 its data; byte 0 is 0 when nothing is
    /// held (a segment has seqno 1..=127). One 8-byte word: a copy and a masked compare, not 7 bytes apart.
    held: [u8; 8],
    /// The segment with c = 1 was accepted: waiting for the end frame.
    pub(super) ending: bool,
    /// Byte 0 of the segment that made the server acknowledge, until the next in-order segment (0 = none):
    /// a CAN-level repeat of it is ignored instead of acknowledged again.
    acked: u8,
}

impl SdoServer {
    #[inline]
    pub(super) fn block_segment<O: ObjectDictionary + ?Sized>(&mut self, b: &[u8; 8], od: &mut O) -> Response {
        let (blksize, mux) = (self.block_size, self.mux);
        let State::BlockDownload(bd) = &mut self.state else { return Response::NONE };
        let last = b[0] & 0x80 != 0;
        let seqno = b[0] & 0x7F;
        if seqno == 0 || seqno > blksize {
            return self.abort(od, AbortCode::InvalidSequenceNumber); // SDO-50
        }
        let in_order = seqno == bd.expected;
        if in_order {
            if bd.held[0] != 0 {
                if let Err(code) = bd.flush_held(mux, 7, od) {
                    return self.abort(od, code);
                }
            }
            bd.held = *b;
            bd.expected = seqno + 1;
            bd.acked = 0;
        } else if b[0] == bd.acked || bd.is_held(b) || bd.is_repeated_initiate(b, mux) {
            // a repeat of the segment just acknowledged or just accepted (a CAN-level duplicate): the server
            // has that sequence number already; a second acknowledge would read as one for the next
            // sub-block and make the client skip segments
            return Response::NONE;
        }
        // Out of order: discarded. The sub-block's end, in order or not, is acknowledged up to the last
        // in-order segment (SDO-39, SDO-40): `expected - 1`, the segment itself when it was in order.
        if last || seqno == blksize {
            let ackseq = bd.expected - 1;
            bd.expected = 1;
            bd.acked = b[0];
            bd.ending = last && in_order; // the last segment taken: the end frame comes next (SDO-41)
            return Response::send(ack(ackseq, blksize));
        }
        Response::NONE
    }

    /// How long after the last frame (`since`) the deadline is in a block transfer, for the SDO time-out
    /// `timeout` (µs, not disabled): a quarter of it while a download sub-block has in-order segments but has
    /// not ended (then [`block_download_stalled`](Self::block_download_stalled) acknowledges them); nothing,
    /// at once, when an upload sub-block was handed out (then [`block_upload_sent`](Self::block_upload_sent)
    /// starts the time-out); `timeout` otherwise. `expected > 1` alone says "in-order segments, not ended":
    /// a sub-block's end (also the one that leaves the server waiting for the end frame) resets `expected`
    /// to 1.
    pub(super) const fn block_delay(&self, timeout: u64) -> u64 {
        match &self.state {
            State::BlockDownload(bd) if bd.expected > 1 => timeout / 4,
            State::BlockUpload(bu) if matches!(bu.phase, UploadPhase::Sent) => 0,
            _ => timeout,
        }
    }

    /// A sub-block stalled: acknowledge the in-order segments received so far (ackseq = last in-order seqno,
    /// go-back-n as SDO-40), so the client resends the rest at once instead of both sides waiting for the SDO
    /// timeout. The SDO timeout still runs from the last frame received. `None` when the stall rule does not
    /// apply (the caller aborts with 0504 0000h).
    pub(super) fn block_download_stalled(&mut self) -> Option<Response> {
        let blksize = self.block_size;
        let State::BlockDownload(bd) = &mut self.state else { return None };
        if bd.expected <= 1 {
            return None; // nothing in order since the last acknowledge, or waiting for the end frame
        }
        let ackseq = bd.expected - 1;
        bd.expected = 1;
        bd.acked = 0;
        Some(Response::send(ack(ackseq, blksize)))
    }

    pub(super) fn block_download_end<O: ObjectDictionary + ?Sized>(
        &mut self,
        unused: u8,
        crc: u16,
        od: &mut O,
    ) -> Response {
        let mux = self.mux;
        let State::BlockDownload(bd) = &mut self.state else {
            return self.invalid(od);
        };
        let r = (|| {
            bd.flush_held(mux, usize::from(7 - unused.min(7)), od)?;
            if bd.crc_on && bd.crc.get() != crc {
                return Err(AbortCode::CrcError); // SDO-50
            }
            // short of the announced size: 0607 0013h (past it, 0607 0012h, was refused in flush_held)
            bd.sink.finish(mux, bd.offset, bd.size, od)
        })();
        if let Err(code) = r {
            return self.abort(od, code);
        }
        self.state = State::Idle;
        Response {
            frame: Some(frame(0xA1, 0, 0)), // scs 5, ss 1 (SDO-41)
            event: Some(SdoEvent::Written { index: mux.index, sub: mux.sub }),
        }
    }
}

/// The sub-block acknowledge (scs 5, ss 2; SDO-39, SDO-40): ackseq in byte 1, the next blksize in byte 2.
fn ack(ackseq: u8, blksize: u8) -> [u8; 8] {
    frame(0xA2, u32::from_le_bytes([ackseq, blksize, 0, 0]), 0)
}

/// Whether `b0`, received while waiting for "end block download" (SDO-41), is a late segment of this transfer.
///
/// Block segments carry no command specifier, so a late or repeated segment (any seqno the sub-blocks can
/// use, last bit or not) would read as a request: 81h–9Fh as an abort with reserved bits, 20h–7Fh as a new
/// initiate. In this state such a frame is a late segment and is ignored (SDO-40); only the end frame (ccs 6,
/// cs 1: C1h + 4·n, bit 1 reserved) and the abort 80h are requests. A client that starts a new transfer here
/// must abort first.
#[inline]
pub(super) const fn is_late_segment(b0: u8, blksize: u8) -> bool {
    let seqno = b0 & 0x7F;
    b0 & 0xE1 != 0xC1 && seqno >= 1 && seqno <= blksize
}

impl BlockDownload {
    /// A block download into `sink` of the announced `size`, with the CRC when `crc_on`, waiting for the
    /// first segment of the first sub-block (`SdoServer::open_download` makes it the state).
    pub(super) const fn new(sink: Sink, size: Option<u32>, crc_on: bool) -> Self {
        BlockDownload {
            sink,
            offset: 0,
            size,
            crc: Crc16::new(),
            crc_on,
            expected: 1,
            held: [0; 8],
            ending: false,
            acked: 0,
        }
    }

    /// Whether `b` is a byte-exact repeat of the initiate request that opened this transfer (a CAN-level
    /// duplicate: C0h–C6h reads as a segment with c = 1 and seqno 64..70), received before any segment.
    /// Taken as a segment, it would be out of order with c = 1 and the server would acknowledge it with
    /// ackseq 0, an acknowledge the client reads as the answer to its first sub-block (SDO-40): it resends
    /// that sub-block, while the server, which acknowledges the real sub-block too, moves on, and from
    /// there the client's data lands at the wrong offset.
    #[inline]
    fn is_repeated_initiate(&self, b: &[u8; 8], mux: Multiplexer) -> bool {
        let size = self.size.unwrap_or(0);
        let b0 = 0xC0 | (u8::from(self.crc_on) << 2) | (u8::from(self.size.is_some()) << 1);
        self.offset == 0 && self.held[0] == 0 && self.acked == 0 && *b == frame(b0, mux.bits(), size)
    }

    /// Whether `b` repeats the held segment: its seqno and data, the c bit aside (SDO-40's duplicate).
    #[inline]
    fn is_held(&self, b: &[u8; 8]) -> bool {
        (u64::from_le_bytes(*b) ^ u64::from_le_bytes(self.held)) & !0x80 == 0
    }

    /// Writes the first `len` bytes of the held segment (in order) to the sink and the CRC.
    // Two callers (an in-order segment, the end frame): one out-of-line copy on a bare-metal target (node
    // -80 B), inlined on the host, where the block_download bench counts it per segment (as node::errors'
    // raise_error).
    #[cfg_attr(target_os = "none", inline(never))]
    #[cfg_attr(not(target_os = "none"), inline)]
    fn flush_held<O: ObjectDictionary + ?Sized>(
        &mut self,
        mux: Multiplexer,
        len: usize,
        od: &mut O,
    ) -> Result<(), AbortCode> {
        let len = len.min(7);
        let [_, data @ ..] = &self.held;
        self.sink.take(mux, &mut self.offset, self.size, data, len, od)?;
        if self.crc_on {
            self.crc.update(&data[..len]);
        }
        self.held[0] = 0;
        Ok(())
    }
}
