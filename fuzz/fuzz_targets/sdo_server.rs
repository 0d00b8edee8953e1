//! cargo-fuzz target on the SDO server's frame entry points.
//!
//! Input: records of 9 bytes, `op` then 8 frame bytes. `op % 12`: 0..=8 → a frame with that DLC (the first
//! `op` bytes), 9 → pull a block-upload frame, 10 → advance time by `bytes[0]` ms and handle the time-out,
//! 11 → an 8-byte frame. Checks: no panic, every reply parses as an SDO server frame (or a sub-block segment
//! when pulled), every abort code is a Table 22 code.
//!
//! Run (from `fuzz/`; new inputs go to the first, gitignored directory):
//! `cargo +nightly fuzz run sdo_server corpus/sdo_server seeds/sdo_server -- -max_total_time=60`
#![no_main]

use canopen_core::od::{AbortCode, Access, DataType, ObjectDictionary, PdoMapping, SubInfo};
use canopen_core::sdo::{Response, SdoServer, SdoServerParams};
use canopen_core::wire::sdo::{BlockSegment, ServerResponse};
use canopen_core::{Duration, Instant, NodeId};
use libfuzzer_sys::fuzz_target;

/// 2000h:00 DOMAIN (streamed, 256 bytes), 2001h:00 U32 rw, 2002h:00 U8 ro, 2003h:00 U16 wo.
struct Od {
    domain: [u8; 256],
    len: usize,
    streaming: bool,
    u32v: u32,
}

impl ObjectDictionary for Od {
    fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
        let (data_type, access, size) = match (index, sub) {
            (0x2000, 0) => (DataType::Domain, Access::Rw, self.len),
            (0x2001, 0) => (DataType::Unsigned32, Access::Rw, 4),
            (0x2002, 0) => (DataType::Unsigned8, Access::Ro, 1),
            (0x2003, 0) => (DataType::Unsigned16, Access::Wo, 2),
            (0x2000..=0x2003, _) => return Err(AbortCode::SubIndexDoesNotExist),
            _ => return Err(AbortCode::ObjectDoesNotExist),
        };
        Ok(SubInfo { data_type, access, pdo: PdoMapping::No, size })
    }
    fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        let v = self.u32v.to_le_bytes();
        let src: &[u8] = match (index, sub) {
            (0x2000, 0) => &self.domain[..self.len],
            (0x2001, 0) => &v,
            (0x2002, 0) => &[7],
            (0x2003, 0) => return Err(AbortCode::ReadOfWriteOnly),
            _ => return Err(AbortCode::ObjectDoesNotExist),
        };
        let src = src.get(offset..).unwrap_or(&[]);
        let n = src.len().min(buf.len());
        buf[..n].copy_from_slice(&src[..n]);
        Ok(n)
    }
    fn write(&mut self, index: u16, _sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        match index {
            0x2001 => {
                self.u32v = u32::from_le_bytes(data.try_into().map_err(|_| AbortCode::LengthMismatch)?);
                Ok(())
            }
            0x2003 if data.len() == 2 => Ok(()),
            0x2003 => Err(AbortCode::LengthMismatch),
            _ => Err(AbortCode::WriteOfReadOnly),
        }
    }
    fn begin_write(&mut self, index: u16, _sub: u8, size: Option<usize>) -> Result<(), AbortCode> {
        if index != 0x2000 {
            return Err(AbortCode::UnsupportedAccess);
        }
        if size.is_some_and(|s| s > self.domain.len()) {
            return Err(AbortCode::OutOfMemory);
        }
        self.streaming = true;
        Ok(())
    }
    fn write_chunk(&mut self, _index: u16, _sub: u8, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        assert!(self.streaming, "write_chunk outside begin/end");
        let dst = self.domain.get_mut(offset..offset + data.len()).ok_or(AbortCode::OutOfMemory)?;
        dst.copy_from_slice(data);
        Ok(())
    }
    fn end_write(&mut self, _index: u16, _sub: u8, total: usize) -> Result<(), AbortCode> {
        assert!(self.streaming, "end_write outside begin/end");
        self.streaming = false;
        self.len = total.min(self.domain.len());
        Ok(())
    }
    fn abort_write(&mut self, _index: u16, _sub: u8) {
        assert!(self.streaming, "abort_write without begin_write");
        self.streaming = false;
    }
}

fn check(r: Response, pulled: bool) {
    if let Some(f) = r.frame {
        if pulled && f[0] != 0x80 {
            BlockSegment::parse(&f).expect("segment");
            return;
        }
        match ServerResponse::parse(&f).expect("well-formed reply") {
            ServerResponse::Abort { code, .. } => assert!(AbortCode::from_code(code).is_some()),
            _ => {}
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let mut od = Od { domain: [0x5A; 256], len: 40, streaming: false, u32v: 0 };
    let mut server = SdoServer::new(SdoServerParams::default_server(NodeId::new(3).unwrap()))
        .with_timeout(Duration::from_millis(100))
        .with_block_size(data.first().map_or(127, |b| b % 127 + 1));
    let mut now = Instant::ZERO;
    for rec in data.get(1..).unwrap_or(&[]).chunks(9) {
        let Some((&op, frame)) = rec.split_first() else { continue };
        match op % 12 {
            n @ 0..=8 => {
                check(server.handle_request(now, frame.get(..usize::from(n)).unwrap_or(frame), &mut od), false)
            }
            9 => check(server.poll_transmit(now, &mut od).unwrap_or(Response::NONE), true),
            10 => {
                now += Duration::from_millis(u64::from(frame.first().copied().unwrap_or(0)));
                check(server.handle_timeout(now, &mut od), false);
            }
            _ => check(server.handle_request(now, frame, &mut od), false),
        }
        now += Duration::from_micros(100);
    }
});
