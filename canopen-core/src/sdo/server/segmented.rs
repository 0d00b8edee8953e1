//! Expedited and segmented transfer, both directions (CiA 301 §7.2.4.3.3–§7.2.4.3.8): initiate download
//! and upload, expedited (SDO-12..SDO-18) or segmented, download segments and upload segments with the toggle
//! bit (SDO-22..SDO-30).
//!
//! Where downloaded bytes go (`Sink`: an 8-byte scratch written atomically, or a stream into the OD) is
//! shared with block download (`open_sink` here, `Sink::write`/`Sink::finish` beside the state).

use super::{Response, SdoEvent, SdoServer, Sink, State};
use crate::od::{AbortCode, ObjectDictionary};
use crate::wire::sdo::{Expedited, InitiateData, Multiplexer, Segment, ServerResponse};

impl SdoServer {
    #[inline]
    pub(super) fn initiate_download<O: ObjectDictionary + ?Sized>(
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

    pub(super) fn open_sink<O: ObjectDictionary + ?Sized>(
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

    #[inline]
    pub(super) fn initiate_upload<O: ObjectDictionary + ?Sized>(
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

    pub(super) fn download_segment<O: ObjectDictionary + ?Sized>(&mut self, seg: Segment, od: &mut O) -> Response {
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
            sink.write(mux, *offset, bytes, od)?;
            if seg.last {
                if size.is_some_and(|s| end < s) {
                    return Err(AbortCode::LengthTooLow);
                }
                sink.finish(mux, end, od)?;
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

    pub(super) fn upload_segment<O: ObjectDictionary + ?Sized>(&mut self, t: bool, od: &mut O) -> Response {
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
}
