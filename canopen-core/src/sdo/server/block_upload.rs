//! Block upload (CiA 301 §7.2.4.3.15–§7.2.4.3.20; SDO-37, SDO-43..SDO-51): initiate with the
//! protocol switch (SDO-43, SDO-44), start, sub-blocks pulled one frame at a time through
//! [`SdoServer::poll_transmit`] (SDO-37, SDO-46), the client's acknowledge with go-back-n and a new block
//! size (SDO-45), end with the CRC (SDO-47..SDO-49).

use super::{Micros, Response, SdoEvent, SdoServer, State};
use crate::od::{AbortCode, ObjectDictionary};
use crate::sdo::block::Crc16;
use crate::time::Instant;
use crate::wire::sdo::{frame, Multiplexer, MAX_BLKSIZE};

/// Where a block upload is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub(super) enum UploadPhase {
    Start,
    Sending,
    /// The sub-block's last segment was handed out, and may not be on the bus yet: a runner that takes a
    /// whole sub-block at once needs as long as the bus does to send it. The time-out (SDO-31: from the
    /// last frame sent) starts at the next [`SdoServer::handle_timeout`], the first time the runner tells
    /// the time after that.
    Sent,
    WaitAck,
    WaitEnd,
}

/// The state of a block upload (the shared [`State`]'s `BlockUpload`).
#[derive(Debug, Clone, Copy)]
pub(super) struct BlockUpload {
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
    pub(super) phase: UploadPhase,
}

impl SdoServer {
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
        if !self.wants_transmit() {
            return None;
        }
        Some(self.next_segment(now, od))
    }

    /// The next frame of a sub-block ([`poll_transmit`](Self::poll_transmit)) once
    /// [`wants_transmit`](Self::wants_transmit) said there is one: for the node's pump, which asks that first,
    /// without a second test and an `Option` around the response. `Response::NONE` in any other state.
    #[inline]
    pub(crate) fn next_segment<O: ObjectDictionary + ?Sized>(&mut self, now: Instant, od: &mut O) -> Response {
        let mux = self.mux;
        let State::BlockUpload(b) = &mut self.state else { return Response::NONE };
        // sent <= 127: no overflow in the product
        let off = b.base.saturating_add(u32::from(b.sent) * 7);
        // off <= size while Sending (a sub-block stops at the last segment, the acknowledge of it ends the
        // upload), as in `upload_segment`: no saturation needed
        let want = b.size.wrapping_sub(off).min(7) as usize;
        // while Sending, sent < blksize <= 127: a 7-bit seqno, no overflow
        let seqno = b.sent + 1;
        // The segment (SDO-37): c ‖ seqno, then the data read from the OD straight into the frame.
        let mut segment = [0u8; 8];
        let n = match od.read(mux.index, mux.sub, off as usize, &mut segment[1..1 + want]) {
            Ok(n) if n == want => n as u32,
            Ok(_) => return self.abort(od, AbortCode::LengthMismatch),
            Err(code) => return self.abort(od, code),
        };
        let end = off + n;
        // Every segment starts at a multiple of 7 (`base` moves by whole segments) and ends 7 bytes later or
        // at `size`, and so does `crc_len`, the end of the furthest one sent: a segment past it starts there,
        // so it is fed whole, and one not past it (sent again after go-back-n) was fed before.
        if end > b.crc_len {
            if b.crc_on {
                b.crc.update(&segment[1..1 + n as usize]);
            }
            b.crc_len = end;
        }
        let last = end >= b.size;
        b.sent = seqno;
        segment[0] = (u8::from(last) << 7) | seqno;
        if last || b.sent >= b.blksize {
            b.phase = UploadPhase::Sent; // the deadline is due at once (block_delay)
        }
        self.since = Micros(now.as_micros()); // SDO-31: the time-out runs from the last frame sent
        Response::send(segment)
    }

    pub(super) fn block_upload_initiate<O: ObjectDictionary + ?Sized>(
        &mut self,
        crc: bool,
        blksize: u8,
        pst: u8,
        od: &mut O,
    ) -> Result<Response, AbortCode> {
        let mux = self.mux; // the frame's (`begin`)
        if blksize == 0 || blksize > MAX_BLKSIZE {
            return Err(AbortCode::InvalidBlockSize);
        }
        let size = readable_size(mux, od)?;
        if pst > 0 && size <= u32::from(pst) {
            return Ok(self.initiate_upload(od)); // SDO-43: protocol switch
        }
        self.state = State::BlockUpload(BlockUpload {
            size,
            base: 0,
            crc_len: 0,
            crc: Crc16::new(),
            crc_on: crc,
            blksize,
            sent: 0,
            phase: UploadPhase::Start,
        });
        // scs 6, ss 0, sc = cc, s = 1: the size in bytes 4–7 (SDO-44)
        Ok(Response::send(frame(0xC2 | (u8::from(crc) << 2), mux.bits(), size)))
    }

    /// At the first time-out check after a sub-block was handed out ([`UploadPhase::Sent`]): its last
    /// segment has gone out by now, so the time-out starts from `now` (SDO-31). Whether it was that case.
    pub(super) fn block_upload_sent(&mut self, now: Instant) -> bool {
        match &mut self.state {
            State::BlockUpload(bu) if bu.phase == UploadPhase::Sent => {
                bu.phase = UploadPhase::WaitAck;
                self.since = Micros(now.as_micros());
                true
            }
            _ => false,
        }
    }

    /// The client's requests of a block upload, ccs 5 with cs = 1..3 (`b` is the frame): end (A1h, SDO-47:
    /// the transfer is complete), acknowledge (A2h, SDO-46: ackseq in byte 1, the next blksize in byte 2,
    /// go-back-n as SDO-40) and start (A3h, SDO-45: the first sub-block may go out). One test of the state and
    /// phase for the three ([`VALID_IN`]), one exit for a request out of state (0504 0001h).
    pub(super) fn block_upload_request<O: ObjectDictionary + ?Sized>(&mut self, b: &[u8; 8], od: &mut O) -> Response {
        let (mux, cs) = (self.mux, b[0] & 0x03);
        let State::BlockUpload(bu) = &mut self.state else { return self.invalid(od) };
        if VALID_IN[usize::from(cs)] >> (bu.phase as u8) & 1 == 0 {
            return self.invalid(od);
        }
        if cs == 1 {
            self.state = State::Idle;
            return Response { frame: None, event: Some(SdoEvent::Uploaded { index: mux.index, sub: mux.sub }) };
        }
        if cs == 2 {
            let (ackseq, blksize) = (b[1], b[2]);
            if ackseq > bu.sent {
                return self.abort(od, AbortCode::InvalidSequenceNumber);
            }
            if blksize == 0 || blksize > MAX_BLKSIZE {
                return self.abort(od, AbortCode::InvalidBlockSize);
            }
            bu.base = bu.base.saturating_add(u32::from(ackseq) * 7);
            bu.sent = 0;
            bu.blksize = blksize;
            if ackseq >= 1 && bu.base >= bu.size {
                bu.phase = UploadPhase::WaitEnd;
                // 0 without CRC (sc = 0): nothing was fed, it is still Crc16::new()
                let crc = bu.crc.get();
                // `base` moved by whole segments to the end of the last one, 7 × segments (at least one,
                // SDO-51): past `size` by the last segment's unused bytes, 7 for an empty data set. No
                // division by 7.
                let unused = (bu.base - bu.size) as u8;
                // scs 6, ss 1: n unused bytes of the last segment, the CRC in bytes 1–2 (SDO-47)
                return Response::send(frame(0xC1 | (unused << 2), u32::from(crc), 0));
            }
        }
        // start, or an acknowledge with more to send: the (next) sub-block goes out
        bu.phase = UploadPhase::Sending;
        Response::NONE
    }
}

/// The phases each client request of a block upload is valid in, by cs (1 end, 2 acknowledge, 3 start): a
/// bit per [`UploadPhase`] (`1 << phase`).
const VALID_IN: [u8; 4] = [
    0,
    1 << UploadPhase::WaitEnd as u8,
    (1 << UploadPhase::Sending as u8) | (1 << UploadPhase::Sent as u8) | (1 << UploadPhase::WaitAck as u8),
    1 << UploadPhase::Start as u8,
];

/// Size of a readable object (SDO upload preconditions).
fn readable_size<O: ObjectDictionary + ?Sized>(mux: Multiplexer, od: &O) -> Result<u32, AbortCode> {
    let info = od.info(mux.index, mux.sub)?;
    if !info.access.readable() {
        return Err(AbortCode::ReadOfWriteOnly);
    }
    u32::try_from(info.size).map_err(|_| AbortCode::OutOfMemory)
}
