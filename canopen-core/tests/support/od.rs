//! Test-support object dictionary for the SDO tests (shared by the unit tests in `src/sdo` through
//! `#[path]` and by the integration tests in `tests/`). No std, no alloc: it must also compile inside the
//! `#![no_std]` library under `cfg(test)`.
//!
//! Entries (node 3 in the vectors):
//! - 1000h:00 U32 ro; 1009h:00 VISIBLE_STRING ro "N10 - WT1209-V1.00-8MB\0" (23 bytes);
//!   100Dh:00 U8 rw; 1017h:00 U16 rw = 100; 1018h:00 U8 const = 4, 1018h:01..04 U32 ro (01 = 2B6h);
//!   1400h:02 U8 rw (refuses FDh with 0609 0030h); 1603h:01 U32 rw = 6012 0208h; 6041h:00 U16 ro = 0240h;
//!   607Ah:00 I32 rw.
//! - 2000h:00 DOMAIN rw, up to 64 KiB, streamed (begin/chunk/end), more → 0504 0005h (out of memory).
//! - 2001h:00 U8 wo; 2002h:00 I16 rw with limits -100..=100 (0609 0031h/0609 0032h);
//!   2003h:00 U32 rw with hooks: 0 → 0609 0030h, 1 → 0800 0000h, 2 → 0800 0020h, 3 → 0800 0022h;
//!   2004h:00 VISIBLE_STRING ro, 64 bytes; 2005h:00 U64 rw; 2006h:00 DOMAIN ro of 200 bytes whose reads
//!   fail from offset 14 on with 0606 0000h; 2007h:00 VISIBLE_STRING rw streamed, up to 16 bytes, whose
//!   `end_write` refuses the text "bad" with 0800 0020h.
#![allow(dead_code)]

use canopen_core::od::{AbortCode, Access, DataType, ObjectDictionary, PdoMapping, SubInfo};

/// Capacity of the 2000h DOMAIN.
pub const DOMAIN_CAP: usize = 65536;

/// The 64-byte string of 2004h.
pub const STRING64: &[u8; 64] = b"CANopen test string of exactly sixty-four bytes for SDO uploads.";

/// 1009h.
pub const SW_VERSION: &[u8; 23] = b"N10 - WT1209-V1.00-8MB\0";

#[derive(Clone, Copy)]
struct Var {
    index: u16,
    sub: u8,
    dt: DataType,
    access: Access,
    value: [u8; 8],
}

const fn var(index: u16, sub: u8, dt: DataType, access: Access, v: u64) -> Var {
    Var { index, sub, dt, access, value: v.to_le_bytes() }
}

const VARS: [Var; 17] = [
    var(0x1000, 0, DataType::Unsigned32, Access::Ro, 0x0000_0191),
    var(0x100D, 0, DataType::Unsigned8, Access::Rw, 3),
    var(0x1017, 0, DataType::Unsigned16, Access::Rw, 100),
    var(0x1018, 0, DataType::Unsigned8, Access::Const, 4),
    var(0x1018, 1, DataType::Unsigned32, Access::Ro, 0x2B6),
    var(0x1018, 2, DataType::Unsigned32, Access::Ro, 0x1234),
    var(0x1018, 3, DataType::Unsigned32, Access::Ro, 0x0001_0002),
    var(0x1018, 4, DataType::Unsigned32, Access::Ro, 0xCAFE),
    var(0x1400, 2, DataType::Unsigned8, Access::Rw, 0xFD),
    var(0x1603, 1, DataType::Unsigned32, Access::Rw, 0x6012_0208),
    var(0x6041, 0, DataType::Unsigned16, Access::Ro, 0x0240),
    var(0x607A, 0, DataType::Integer32, Access::Rw, 0),
    var(0x2001, 0, DataType::Unsigned8, Access::Wo, 0),
    var(0x2002, 0, DataType::Integer16, Access::Rw, 0),
    var(0x2003, 0, DataType::Unsigned32, Access::Rw, 7),
    var(0x2005, 0, DataType::Unsigned64, Access::Rw, 0),
    var(0x2008, 0, DataType::Unsigned8, Access::Ro, 0),
];

/// Streamed-write bookkeeping.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Stream {
    /// Object being written.
    pub index: u16,
    /// Bytes received so far (highest offset written).
    pub written: usize,
}

/// The test dictionary.
pub struct TestOd {
    vars: [Var; 17],
    /// 2000h contents.
    pub domain: [u8; DOMAIN_CAP],
    /// 2000h current length.
    pub domain_len: usize,
    /// 2007h contents.
    pub text: [u8; 16],
    /// 2007h current length.
    pub text_len: usize,
    /// Streamed write in progress.
    pub stream: Option<Stream>,
    /// Count of `abort_write` calls.
    pub aborted_writes: u32,
    /// The object of the last `abort_write` call.
    pub aborted_object: Option<(u16, u8)>,
    /// Count of completed writes (atomic or streamed).
    pub writes: u32,
}

impl Default for TestOd {
    fn default() -> Self {
        Self::new()
    }
}

impl TestOd {
    /// A fresh dictionary; 2000h holds 0 bytes.
    pub fn new() -> Self {
        TestOd {
            vars: VARS,
            domain: [0; DOMAIN_CAP],
            domain_len: 0,
            text: [0; 16],
            text_len: 0,
            stream: None,
            aborted_writes: 0,
            aborted_object: None,
            writes: 0,
        }
    }

    fn var(&self, index: u16, sub: u8) -> Result<usize, AbortCode> {
        if let Some(i) = self.vars.iter().position(|v| v.index == index && v.sub == sub) {
            return Ok(i);
        }
        if self.vars.iter().any(|v| v.index == index) {
            Err(AbortCode::SubIndexDoesNotExist)
        } else {
            Err(AbortCode::ObjectDoesNotExist)
        }
    }

    /// The value of a fixed-size entry as u64 (little-endian, zero-extended).
    pub fn get(&self, index: u16, sub: u8) -> Option<u64> {
        self.var(index, sub).ok().and_then(|i| self.vars.get(i)).map(|v| u64::from_le_bytes(v.value))
    }

    /// Sets 2000h directly.
    pub fn set_domain(&mut self, data: &[u8]) {
        self.domain[..data.len()].copy_from_slice(data);
        self.domain_len = data.len();
    }

    /// 2000h's current contents.
    pub fn domain(&self) -> &[u8] {
        &self.domain[..self.domain_len]
    }
}

fn copy_out(src: &[u8], offset: usize, buf: &mut [u8]) -> usize {
    let src = src.get(offset..).unwrap_or(&[]);
    let n = src.len().min(buf.len());
    buf[..n].copy_from_slice(&src[..n]);
    n
}

fn info(dt: DataType, access: Access, size: usize) -> SubInfo {
    SubInfo { data_type: dt, access, pdo: PdoMapping::No, size }
}

impl ObjectDictionary for TestOd {
    fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
        match (index, sub) {
            (0x1009, 0) => Ok(info(DataType::VisibleString, Access::Ro, SW_VERSION.len())),
            (0x2000, 0) => Ok(info(DataType::Domain, Access::Rw, self.domain_len)),
            (0x2004, 0) => Ok(info(DataType::VisibleString, Access::Ro, STRING64.len())),
            (0x2006, 0) => Ok(info(DataType::Domain, Access::Ro, 200)),
            (0x2007, 0) => Ok(info(DataType::VisibleString, Access::Rw, self.text_len)),
            (0x1009 | 0x2000 | 0x2004 | 0x2006 | 0x2007, _) => Err(AbortCode::SubIndexDoesNotExist),
            _ => {
                let v = self.vars[self.var(index, sub)?];
                Ok(info(v.dt, v.access, v.dt.size().unwrap_or(0)))
            }
        }
    }

    fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        match (index, sub) {
            (0x1009, 0) => Ok(copy_out(SW_VERSION, offset, buf)),
            (0x2000, 0) => Ok(copy_out(self.domain(), offset, buf)),
            (0x2004, 0) => Ok(copy_out(STRING64, offset, buf)),
            (0x2006, 0) if offset >= 14 => Err(AbortCode::HardwareError),
            (0x2006, 0) => Ok(copy_out(&[0x55; 200], offset, buf)),
            (0x2007, 0) => Ok(copy_out(&self.text[..self.text_len], offset, buf)),
            _ => {
                let v = self.vars[self.var(index, sub)?];
                if !v.access.readable() {
                    return Err(AbortCode::ReadOfWriteOnly);
                }
                Ok(copy_out(&v.value[..v.dt.size().unwrap_or(0)], offset, buf))
            }
        }
    }

    fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        let i = self.var(index, sub)?;
        let v = self.vars[i];
        if !v.access.writable() {
            return Err(AbortCode::WriteOfReadOnly);
        }
        let size = v.dt.size().unwrap_or(0);
        if data.len() > size {
            return Err(AbortCode::LengthTooHigh);
        }
        if data.len() < size {
            return Err(AbortCode::LengthTooLow);
        }
        let mut value = [0u8; 8];
        value[..size].copy_from_slice(data);
        let raw = u64::from_le_bytes(value);
        match (index, sub) {
            (0x1400, 2) if raw == 0xFD => return Err(AbortCode::InvalidValue),
            (0x2002, 0) => {
                let x = i16::from_le_bytes([value[0], value[1]]);
                if x > 100 {
                    return Err(AbortCode::ValueTooHigh);
                }
                if x < -100 {
                    return Err(AbortCode::ValueTooLow);
                }
            }
            (0x2003, 0) => match raw {
                0 => return Err(AbortCode::InvalidValue),
                1 => return Err(AbortCode::GeneralError),
                2 => return Err(AbortCode::CannotStore),
                3 => return Err(AbortCode::CannotStoreDeviceState),
                _ => {}
            },
            _ => {}
        }
        self.vars[i].value = value;
        self.writes += 1;
        Ok(())
    }

    fn begin_write(&mut self, index: u16, sub: u8, size: Option<usize>) -> Result<(), AbortCode> {
        let cap = match (index, sub) {
            (0x2000, 0) => DOMAIN_CAP,
            (0x2007, 0) => self.text.len(),
            (0x1009 | 0x2004 | 0x2006, 0) => return Err(AbortCode::WriteOfReadOnly),
            _ => {
                self.info(index, sub)?;
                return Err(AbortCode::UnsupportedAccess);
            }
        };
        if size.is_some_and(|s| s > cap) {
            return Err(if index == 0x2000 { AbortCode::OutOfMemory } else { AbortCode::LengthTooHigh });
        }
        self.stream = Some(Stream { index, written: 0 });
        Ok(())
    }

    fn write_chunk(&mut self, index: u16, _sub: u8, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        let Some(st) = self.stream.as_mut().filter(|s| s.index == index) else { return Err(AbortCode::GeneralError) };
        if offset != st.written {
            return Err(AbortCode::GeneralError); // chunks must come in increasing, contiguous offsets
        }
        let dst = match index {
            0x2000 => self.domain.get_mut(offset..offset + data.len()).ok_or(AbortCode::OutOfMemory)?,
            _ => self.text.get_mut(offset..offset + data.len()).ok_or(AbortCode::LengthTooHigh)?,
        };
        dst.copy_from_slice(data);
        st.written += data.len();
        Ok(())
    }

    fn end_write(&mut self, index: u16, _sub: u8, total: usize) -> Result<(), AbortCode> {
        let Some(st) = self.stream.take().filter(|s| s.index == index) else { return Err(AbortCode::GeneralError) };
        if st.written != total {
            return Err(AbortCode::GeneralError);
        }
        match index {
            0x2000 => self.domain_len = total,
            _ => {
                if &self.text[..total] == b"bad" {
                    return Err(AbortCode::CannotStore);
                }
                self.text_len = total;
            }
        }
        self.writes += 1;
        Ok(())
    }

    fn abort_write(&mut self, index: u16, sub: u8) {
        self.stream = None;
        self.aborted_writes += 1;
        self.aborted_object = Some((index, sub));
    }
}
