//! Instruction-count workload for the SDO server alone (no Node, a minimal hand-written dictionary): the
//! protocol machine's share of the whole-node figures of `scripts/bench-node.sh`.
//!
//! `sdo_instructions <scenario> <iterations>` runs one scenario `iterations` times and prints the number of
//! frames the server handled. `scripts/bench-instructions.sh` runs it under callgrind twice (N and 0
//! iterations) and divides the difference in instructions by the number of frames.
//!
//! Scenarios: `expedited_upload` (U32 1000h), `expedited_download` (U32), `segmented_upload` (64-byte
//! string), `block_download` (889·k bytes with CRC, k = 8; 889 = one full sub-block of 127 segments).

use std::hint::black_box;

use canopen_core::od::{AbortCode, Access, DataType, ObjectDictionary, PdoMapping, SubInfo};
use canopen_core::sdo::block::Crc16;
use canopen_core::sdo::{SdoServer, SdoServerParams};
use canopen_core::{Instant, NodeId};

const STRING64: &[u8; 64] = b"CANopen test string of exactly sixty-four bytes for SDO uploads.";
const K: usize = 8;
const BLOCK_LEN: usize = 889 * K;

/// A small dictionary: 1000h:00 U32 ro, 2001h:00 U32 rw, 2004h:00 64-byte string, 2000h:00 DOMAIN.
struct Od {
    device_type: u32,
    value: u32,
    domain: Vec<u8>,
    len: usize,
}

fn copy_out(src: &[u8], offset: usize, buf: &mut [u8]) -> usize {
    let src = src.get(offset..).unwrap_or(&[]);
    let n = src.len().min(buf.len());
    buf[..n].copy_from_slice(&src[..n]);
    n
}

impl ObjectDictionary for Od {
    fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
        let (data_type, access, size) = match (index, sub) {
            (0x1000, 0) => (DataType::Unsigned32, Access::Ro, 4),
            (0x2001, 0) => (DataType::Unsigned32, Access::Rw, 4),
            (0x2004, 0) => (DataType::VisibleString, Access::Ro, 64),
            (0x2000, 0) => (DataType::Domain, Access::Rw, self.len),
            _ => return Err(AbortCode::ObjectDoesNotExist),
        };
        Ok(SubInfo { data_type, access, pdo: PdoMapping::No, size })
    }
    fn read(&self, index: u16, _sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        Ok(match index {
            0x1000 => copy_out(&self.device_type.to_le_bytes(), offset, buf),
            0x2001 => copy_out(&self.value.to_le_bytes(), offset, buf),
            0x2004 => copy_out(STRING64, offset, buf),
            _ => copy_out(&self.domain[..self.len], offset, buf),
        })
    }
    fn write(&mut self, _index: u16, _sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        self.value = u32::from_le_bytes(data.try_into().map_err(|_| AbortCode::LengthMismatch)?);
        Ok(())
    }
    fn begin_write(&mut self, _index: u16, _sub: u8, _size: Option<usize>) -> Result<(), AbortCode> {
        Ok(())
    }
    fn write_chunk(&mut self, _index: u16, _sub: u8, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        self.domain.get_mut(offset..offset + data.len()).ok_or(AbortCode::OutOfMemory)?.copy_from_slice(data);
        Ok(())
    }
    fn end_write(&mut self, _index: u16, _sub: u8, total: usize) -> Result<(), AbortCode> {
        self.len = total;
        Ok(())
    }
}

/// The client frames of one block download of BLOCK_LEN bytes with CRC.
fn block_download_frames() -> Vec<[u8; 8]> {
    let data: Vec<u8> = (0..BLOCK_LEN).map(|i| (i * 7) as u8).collect();
    let mut crc = Crc16::new();
    crc.update(&data);
    let size = (BLOCK_LEN as u32).to_le_bytes();
    let mut frames = vec![[0xC6, 0x00, 0x20, 0x00, size[0], size[1], size[2], size[3]]];
    for (i, chunk) in data.chunks(7).enumerate() {
        let seqno = (i % 127) as u8 + 1;
        let last = (i + 1) * 7 >= BLOCK_LEN;
        let mut f = [0u8; 8];
        f[0] = seqno | if last { 0x80 } else { 0 };
        f[1..1 + chunk.len()].copy_from_slice(chunk);
        frames.push(f);
    }
    let [c0, c1] = crc.get().to_le_bytes();
    frames.push([0xC1, c0, c1, 0, 0, 0, 0, 0]); // 889·k is a multiple of 7: n = 0
    frames
}

fn main() {
    let mut args = std::env::args().skip(1);
    let scenario = args.next().unwrap_or_else(|| "expedited_upload".into());
    let iterations: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(1000);
    let mut od = Od { device_type: 0x0001_0191, value: 0, domain: vec![0; BLOCK_LEN], len: 0 };
    let mut server = SdoServer::new(SdoServerParams::default_server(NodeId::new(3).unwrap()));
    let now = Instant::from_millis(1);
    let mut frames = 0usize;
    let mut replies = 0usize;
    let script: Vec<[u8; 8]> = match scenario.as_str() {
        "expedited_upload" => vec![[0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0]],
        "expedited_download" => vec![[0x23, 0x01, 0x20, 0x00, 0xE8, 0x03, 0x00, 0x00]],
        "segmented_upload" => {
            let mut v = vec![[0x40, 0x04, 0x20, 0x00, 0, 0, 0, 0]];
            for i in 0..10 {
                v.push([if i % 2 == 0 { 0x60 } else { 0x70 }, 0, 0, 0, 0, 0, 0, 0]);
            }
            v
        }
        "block_download" => block_download_frames(),
        other => panic!("unknown scenario {other}"),
    };
    let script = black_box(script);
    for _ in 0..iterations {
        for f in &script {
            let r = server.handle_request(now, black_box(f), black_box(&mut od));
            frames += 1;
            replies += usize::from(black_box(r).frame.is_some());
        }
    }
    assert!(server.is_idle());
    if scenario == "block_download" && iterations > 0 {
        assert_eq!(od.len, BLOCK_LEN);
    }
    println!("{scenario}: {frames} frames, {replies} replies");
}
