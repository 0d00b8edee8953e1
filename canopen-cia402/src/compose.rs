//! [`Drive`] as one dictionary: the CiA 402 objects serve 6000h–67FFh (the profile area of the first
//! logical device), the application's dictionary every other index, with one comparison per access (as
//! the core's `od::Merged` splits the communication profile from the application). The EDS lists both
//! halves in index order (`od::merge_nth`), so the application may own objects above 67FFh too.

use canopen_core::od::{
    merge_nth, AbortCode, EntryDesc, ObjectDesc, ObjectDictionary, OdDescribe, PdoDir, PdoHandle, SubInfo,
};

use crate::Drive;

/// Whether `index` is one of the drive's (6000h–67FFh).
///
/// ```
/// assert!(canopen_cia402::is_drive_index(0x6041));
/// assert!(!canopen_cia402::is_drive_index(0x2000));
/// ```
pub const fn is_drive_index(index: u16) -> bool {
    index >= 0x6000 && index <= 0x67FF
}

macro_rules! route {
    ($self:ident, $index:expr, $od:ident => $e:expr) => {
        if is_drive_index($index) {
            let $od = &$self.objects;
            $e
        } else {
            let $od = &$self.app;
            $e
        }
    };
    (mut $self:ident, $index:expr, $od:ident => $e:expr) => {
        if is_drive_index($index) {
            let $od = &mut $self.objects;
            $e
        } else {
            let $od = &mut $self.app;
            $e
        }
    };
}

impl<A: ObjectDictionary> ObjectDictionary for Drive<A> {
    const SERVES_PROGRAM: bool = A::SERVES_PROGRAM;
    const STREAMS: bool = A::STREAMS;
    const SEGMENTED_UPLOADS: bool = A::SEGMENTED_UPLOADS;

    fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
        route!(self, index, od => od.info(index, sub))
    }
    fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        route!(self, index, od => od.read(index, sub, offset, buf))
    }
    fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        route!(mut self, index, od => od.write(index, sub, data))
    }
    fn begin_write(&mut self, index: u16, sub: u8, size: Option<usize>) -> Result<(), AbortCode> {
        route!(mut self, index, od => od.begin_write(index, sub, size))
    }
    fn write_chunk(&mut self, index: u16, sub: u8, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        route!(mut self, index, od => od.write_chunk(index, sub, offset, data))
    }
    fn end_write(&mut self, index: u16, sub: u8, total: usize) -> Result<(), AbortCode> {
        route!(mut self, index, od => od.end_write(index, sub, total))
    }
    fn abort_write(&mut self, index: u16, sub: u8) {
        route!(mut self, index, od => od.abort_write(index, sub))
    }
    fn read_expedited(&self, index: u16, sub: u8, buf: &mut [u8; 4]) -> Result<(usize, usize), AbortCode> {
        route!(self, index, od => od.read_expedited(index, sub, buf))
    }
    fn write_expedited(&mut self, index: u16, sub: u8, data: &[u8; 4], len: Option<usize>) -> Result<(), AbortCode> {
        route!(mut self, index, od => od.write_expedited(index, sub, data, len))
    }
    fn slot(&self, index: u16, sub: u8) -> u16 {
        route!(self, index, od => od.slot(index, sub))
    }
    fn read_slot(&self, index: u16, sub: u8, slot: u16, offset: usize, buf: &mut [u8]) -> Result<(), AbortCode> {
        route!(self, index, od => od.read_slot(index, sub, slot, offset, buf))
    }
    fn pdo_resolve(&self, index: u16, sub: u8, dir: PdoDir) -> Result<PdoHandle, AbortCode> {
        route!(self, index, od => od.pdo_resolve(index, sub, dir))
    }
    fn pdo_read(&self, handle: &PdoHandle, buf: &mut [u8]) -> Result<usize, AbortCode> {
        route!(self, handle.index, od => od.pdo_read(handle, buf))
    }
    fn pdo_write(&mut self, handle: &PdoHandle, data: &[u8]) -> Result<(), AbortCode> {
        route!(mut self, handle.index, od => od.pdo_write(handle, data))
    }
    /// Reset Application: both halves back to their defaults.
    fn restore_defaults(&mut self) {
        self.objects.reset();
        self.app.restore_defaults();
    }
    /// The drive's objects are always reported (the application cycles the drive when 6040h, 6060h or a
    /// target is written by SDO); the application's as it says.
    fn write_events(&self) -> bool {
        true
    }
}

impl<A: OdDescribe> Drive<A> {
    fn locate(&self, n: usize) -> Option<(bool, usize)> {
        let (d, a) = (&self.objects, &self.app);
        let (di, ai) = (|i| d.object_index(i).unwrap_or(u16::MAX), |j| a.object_index(j).unwrap_or(u16::MAX));
        merge_nth(n, d.object_count(), di, a.object_count(), ai)
    }
}

impl<A: OdDescribe> OdDescribe for Drive<A> {
    fn object_count(&self) -> usize {
        self.objects.object_count() + self.app.object_count()
    }
    fn object(&self, n: usize) -> Option<ObjectDesc> {
        match self.locate(n)? {
            (true, i) => self.objects.object(i),
            (false, j) => self.app.object(j),
        }
    }
    fn object_index(&self, n: usize) -> Option<u16> {
        match self.locate(n)? {
            (true, i) => self.objects.object_index(i),
            (false, j) => self.app.object_index(j),
        }
    }
    fn entry(&self, index: u16, sub: u8) -> Option<EntryDesc> {
        if is_drive_index(index) {
            self.objects.entry(index, sub)
        } else {
            self.app.entry(index, sub)
        }
    }
}
