//! Expedited and segmented transfer, both directions (CiA 301 §7.2.4.3.3–§7.2.4.3.8): initiate download
//! and upload, expedited (SDO-12..SDO-18) or segmented, download segments and upload segments with the toggle
//! bit (SDO-22..SDO-30).
//!
//! Where downloaded bytes go (`Sink`: an 8-byte scratch written atomically, or a stream into the OD) is
//! shared with block download (`open_sink` here, `Sink::write`/`Sink::finish` beside the state).

use super::{Response, SdoEvent, SdoServer, Sink, State};
use crate::od::{AbortCode, ObjectDictionary};
use crate::wire::sdo::{frame, Multiplexer};

impl SdoServer {
    /// Initiate download (ccs 1, SDO-11..SDO-18): `command` is byte 0 (e, s, n), `data` bytes 4–7. The
    /// response itself, abort included: the expedited one is built where it is returned, not moved out of a
    /// `Result` (12 instructions per download on x86-64).
    #[inline]
    pub(super) fn initiate_download<O: ObjectDictionary + ?Sized>(
        &mut self,
        mux: Multiplexer,
        command: u8,
        data: u32,
        od: &mut O,
    ) -> Response {
        let size_indicated = command & 0x01 != 0;
        if command & 0x02 != 0 {
            // Expedited: info, access, length and the write in one dictionary call (one lookup where it is
            // derived). With s = 1 the bytes past 4 − n are not data and go to the OD as 0 (SDO-12, SDO-13).
            let (data, len) = if size_indicated {
                let len = 4 - u32::from((command >> 2) & 0x03);
                (data & (u32::MAX >> (8 * (4 - len))), Some(len as usize))
            } else {
                (data, None)
            };
            if let Err(code) = od.write_expedited(mux.index, mux.sub, &data.to_le_bytes(), len) {
                return self.abort(od, code);
            }
            return Response {
                frame: Some(frame(0x60, mux.bits(), 0)), // SDO-17
                event: Some(SdoEvent::Written { index: mux.index, sub: mux.sub }),
            };
        }
        let size = size_indicated.then_some(data);
        // With block transfer through the one builder of both download initiates (node -80 B); without,
        // that builder inline here was 40 B larger than the state built after `open_sink` (minimal).
        #[cfg(feature = "sdo-block")]
        return self.open_download(size, None, od);
        #[cfg(not(feature = "sdo-block"))]
        self.initiate_segmented_download(mux, size, od).unwrap_or_else(|code| self.abort(od, code))
    }

    /// Initiate download, segmented (SDO-18: the announced size is checked before any data moves).
    #[cfg(not(feature = "sdo-block"))]
    fn initiate_segmented_download<O: ObjectDictionary + ?Sized>(
        &mut self,
        mux: Multiplexer,
        size: Option<u32>,
        od: &mut O,
    ) -> Result<Response, AbortCode> {
        let sink = self.open_sink(mux, size, od)?;
        self.state = State::Download { toggle: false, offset: 0, size, sink };
        Ok(Response::send(frame(0x60, mux.bits(), 0))) // SDO-17
    }

    /// Opens a segmented download of the server's object with the announced `size` (a block download with
    /// `block`, its CRC flag) and answers it: its sink ([`open_sink`](Self::open_sink)), the server's state
    /// and the response, or the abort that refuses it, built here for both initiates (not moved out of a
    /// `Result` at each).
    #[cfg(feature = "sdo-block")]
    pub(super) fn open_download<O: ObjectDictionary + ?Sized>(
        &mut self,
        size: Option<u32>,
        block: Option<bool>,
        od: &mut O,
    ) -> Response {
        let mux = self.mux; // the frame's (`begin`)
        let sink = match self.open_sink(mux, size, od) {
            Ok(sink) => sink,
            Err(code) => return self.abort(od, code),
        };
        if let Some(crc) = block {
            self.state = State::BlockDownload(super::block_download::BlockDownload::new(sink, size, crc));
            // scs 5, ss 0, sc = cc (INTEROP), blksize in byte 4 (SDO-36)
            return Response::send(frame(0xA0 | (u8::from(crc) << 2), mux.bits(), u32::from(self.block_size)));
        }
        self.state = State::Download { toggle: false, offset: 0, size, sink };
        Response::send(frame(0x60, mux.bits(), 0)) // SDO-17
    }

    /// Where a segmented or block download of `mux` with the announced `size` goes, once the entry was found
    /// writable (0601 0002h otherwise): a fixed-size entry into the scratch, after its size was checked against
    /// the announced one; anything else streamed into the OD (`begin_write`).
    fn open_sink<O: ObjectDictionary + ?Sized>(
        &mut self,
        mux: Multiplexer,
        size: Option<u32>,
        od: &mut O,
    ) -> Result<Sink, AbortCode> {
        let info = od.info(mux.index, mux.sub)?;
        if !info.access.writable() {
            return Err(AbortCode::WriteOfReadOnly);
        }
        match info.data_type.size() {
            // SDO-18: refuse a wrong announced size before any data moves (two comparisons: an `Ordering`
            // matched here cost the node firmware 48 B more).
            Some(n) => match size {
                Some(s) if s as usize > n => Err(AbortCode::LengthTooHigh),
                Some(s) if (s as usize) < n => Err(AbortCode::LengthTooLow),
                _ => Ok(Sink::Scratch([0; 8])),
            },
            None => {
                od.begin_write(mux.index, mux.sub, size.map(|s| s as usize))?;
                if !O::STREAMS {
                    // A dictionary that promised no stream (`ObjectDictionary::STREAMS`) began one: undone
                    // and refused, so that no `Sink::Stream` exists for it.
                    od.abort_write(mux.index, mux.sub);
                    return Err(AbortCode::UnsupportedAccess);
                }
                Ok(Sink::Stream)
            }
        }
    }

    /// Initiate upload (ccs 2, SDO-23..SDO-25): expedited when the object has 1..=4 bytes, else segmented
    /// with the size indicated. The response itself, a refusal's abort included (for the frame's object):
    /// its two callers (ccs 2, a block upload's protocol switch) then move no `Result` (footprint.sh: node
    /// -16 B, minimal -8 B).
    #[inline]
    pub(super) fn initiate_upload<O: ObjectDictionary + ?Sized>(&mut self, od: &mut O) -> Response {
        self.upload_initiated(od).unwrap_or_else(|code| self.abort(od, code))
    }

    /// [`initiate_upload`](Self::initiate_upload)'s answer, or the abort code that refuses it.
    #[inline]
    fn upload_initiated<O: ObjectDictionary + ?Sized>(&mut self, od: &mut O) -> Result<Response, AbortCode> {
        let mux = self.mux; // the frame's (`begin`)
        let mut d = [0u8; 4];
        let (size, n) = od.read_expedited(mux.index, mux.sub, &mut d)?;
        let size = u32::try_from(size).map_err(|_| AbortCode::OutOfMemory)?;
        if (1..=4).contains(&size) {
            // e = 1, s = 1, n = 4 − bytes; the bytes past n stay 0 (SDO-24).
            if !(1..=4).contains(&n) {
                return Err(AbortCode::GeneralError);
            }
            let data = u32::from_le_bytes(d) & (u32::MAX >> (8 * (4 - n as u32)));
            return Ok(Response::send(frame(0x43 | ((4 - n as u8) << 2), mux.bits(), data)));
        }
        if !O::SEGMENTED_UPLOADS {
            // A dictionary that promised 1..=4 bytes for every entry (`ObjectDictionary::SEGMENTED_UPLOADS`)
            // has another size: refused, and no segmented-upload path is built for it.
            return Err(AbortCode::GeneralError);
        }
        let slot = od.slot(mux.index, mux.sub); // one lookup here, none per segment
        self.state = State::Upload { toggle: false, offset: 0, size, slot };
        Ok(Response::send(frame(0x41, mux.bits(), size))) // e = 0, s = 1: the size (SDO-25)
    }

    /// Download segment (ccs 0, SDO-19..SDO-22, SDO-30): 000 ‖ t ‖ n ‖ c, bytes 1–7.
    pub(super) fn download_segment<O: ObjectDictionary + ?Sized>(&mut self, b: &[u8; 8], od: &mut O) -> Response {
        let mux = self.mux;
        let State::Download { toggle, offset, size, sink } = &mut self.state else {
            return self.invalid(od);
        };
        let [command, data @ ..] = b;
        let t = command & 0x10 != 0;
        let last = command & 0x01 != 0;
        if t != *toggle {
            return self.abort(od, AbortCode::ToggleNotAlternated); // SDO-30
        }
        let len = 7 - ((command >> 1) & 0x07);
        let r = (|| {
            sink.take(mux, offset, *size, data, usize::from(len), od)?;
            if last {
                sink.finish(mux, *offset, *size, od)?;
            }
            Ok(())
        })();
        if let Err(code) = r {
            return self.abort(od, code);
        }
        let response = frame(0x20 | (command & 0x10), 0, 0); // SDO-20: t echoed
        if last {
            self.state = State::Idle;
            return Response {
                frame: Some(response),
                event: Some(SdoEvent::Written { index: mux.index, sub: mux.sub }),
            };
        }
        *toggle = !*toggle;
        Response::send(response)
    }

    /// Upload segment request (ccs 3, SDO-26..SDO-28, SDO-30): the next 1..7 bytes, read from the OD straight
    /// into the response frame.
    #[inline]
    pub(super) fn upload_segment<O: ObjectDictionary + ?Sized>(&mut self, t: bool, od: &mut O) -> Response {
        if !O::SEGMENTED_UPLOADS {
            return self.invalid(od); // no upload is ever segmented: the answer of a server without one
        }
        let mux = self.mux;
        let State::Upload { toggle, offset, size, slot } = &mut self.state else {
            return self.invalid(od);
        };
        if t != *toggle {
            return self.abort(od, AbortCode::ToggleNotAlternated); // SDO-28, SDO-30
        }
        // offset <= size (it only grows to size, then the transfer ends): no saturation needed; were it
        // broken, 7 bytes past the end would not be there and read_slot would fail (0607 0010h)
        let want = size.wrapping_sub(*offset).min(7) as usize;
        let mut response = [0u8; 8];
        if let Err(code) = od.read_slot(mux.index, mux.sub, *slot, *offset as usize, &mut response[1..1 + want]) {
            return self.abort(od, code); // 0607 0010h: fewer bytes than the size announced
        }
        let n = want as u8;
        *offset += u32::from(n);
        let last = *offset >= *size;
        *toggle = !*toggle;
        // scs 0 (SDO-27): 000 ‖ t ‖ n ‖ c
        response[0] = (u8::from(t) << 4) | ((7 - n) << 1) | u8::from(last);
        if last {
            self.state = State::Idle;
            return Response {
                frame: Some(response),
                event: Some(SdoEvent::Uploaded { index: mux.index, sub: mux.sub }),
            };
        }
        Response::send(response)
    }
}
