//! One dictionary from two: the communication profile (1000h–1FFFh) and the application (everything
//! else), dispatched by index range with one comparison, never by scanning. SDO, PDO mapping and the EDS
//! writer all see the [`Merged`] dictionary.

use super::{AbortCode, EntryDesc, ObjectDesc, ObjectDictionary, OdDescribe, PdoDir, PdoHandle, SubInfo};

/// The communication profile `comm` (1000h–1FFFh) merged with the application dictionary `app`.
///
/// Objects are listed in increasing index order, the two halves' (each in increasing order) merged
/// ([`merge_nth`]): the application half may list objects inside the communication range (1F50h–1F57h of a
/// `program::ProgramDownload`), which come before the profile's 1F80h.
///
/// ```
/// # use canopen_core::Sizes;
/// use canopen_core::profile::NodeConfig;
/// use canopen_core::{od::{Merged, ObjectDictionary, AbortCode}, profile::CommProfile};
/// # use canopen_core::od::{Access, DataType, PdoMapping, SubInfo};
/// # struct Empty;
/// # impl ObjectDictionary for Empty {
/// #     fn info(&self, _: u16, _: u8) -> Result<SubInfo, AbortCode> { Err(AbortCode::ObjectDoesNotExist) }
/// #     fn read(&self, _: u16, _: u8, _: usize, _: &mut [u8]) -> Result<usize, AbortCode> { Err(AbortCode::ObjectDoesNotExist) }
/// #     fn write(&mut self, _: u16, _: u8, _: &[u8]) -> Result<(), AbortCode> { Err(AbortCode::ObjectDoesNotExist) }
/// # }
/// let od = Merged { comm: CommProfile::<Sizes<1, 16, 16, 0, 0>>::new(NodeConfig::DEFAULT), app: Empty };
/// assert!(od.info(0x1000, 0).is_ok());
/// assert_eq!(od.info(0x2000, 0), Err(AbortCode::ObjectDoesNotExist));
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Merged<C, A> {
    /// The communication profile, serving 1000h–1FFFh.
    pub comm: C,
    /// The application dictionary, serving every other index.
    pub app: A,
}

/// Whether `index` belongs to the communication profile area (OD-02).
pub(crate) const fn is_comm(index: u16) -> bool {
    index >= 0x1000 && index <= 0x1FFF
}

/// Whether `index` is in the program download area 1F50h–1F57h (CiA 302-3).
pub(crate) const fn is_program(index: u16) -> bool {
    index & 0xFFF8 == 0x1F50
}

/// Whether `index` goes to the communication profile when `A` is the application dictionary: as
/// [`is_comm`], except 1F50h–1F57h when `A` serves them ([`ObjectDictionary::SERVES_PROGRAM`], a constant,
/// so the extra test is compiled only for such an `A`).
#[inline(always)]
pub(crate) const fn is_comm_for<A: ObjectDictionary + ?Sized>(index: u16) -> bool {
    is_comm(index) && !(A::SERVES_PROGRAM && is_program(index))
}

macro_rules! route {
    ($self:ident, $index:expr, $od:ident => $e:expr) => {
        if is_comm_for::<A>($index) {
            let $od = &$self.comm;
            $e
        } else {
            let $od = &$self.app;
            $e
        }
    };
    (mut $self:ident, $index:expr, $od:ident => $e:expr) => {
        if is_comm_for::<A>($index) {
            let $od = &mut $self.comm;
            $e
        } else {
            let $od = &mut $self.app;
            $e
        }
    };
}

impl<C: ObjectDictionary, A: ObjectDictionary> ObjectDictionary for Merged<C, A> {
    const STREAMS: bool = C::STREAMS || A::STREAMS;
    const SEGMENTED_UPLOADS: bool = C::SEGMENTED_UPLOADS || A::SEGMENTED_UPLOADS;

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
    /// Reset Application restores the application's values only (NMT-04: 2000h–9FFFh); the communication
    /// profile is restored by Reset Communication.
    fn restore_defaults(&mut self) {
        self.app.restore_defaults()
    }
    fn write_events(&self) -> bool {
        self.app.write_events()
    }
}

/// Where the `n`-th object of two increasing lists merged into one increasing list is: `(true, i)` for the
/// `i`-th of list `a` (`a_len` objects, index of the `i`-th `a(i)`), `(false, j)` for the `j`-th of `b`;
/// `None` past the end. A binary search over the split (how many of the first `n` come from `a`), so
/// listing every object costs `O(n log n)` index look-ups, with no buffer.
///
/// ```
/// # use canopen_core::od::merge_nth;
/// let (a, b) = ([0x1000u16, 0x1018, 0x1F80], [0x1F50u16, 0x2000]);
/// let merged: Vec<u16> = (0..6)
///     .map_while(|n| merge_nth(n, a.len(), |i| a[i], b.len(), |j| b[j]))
///     .map(|(in_a, i)| if in_a { a[i] } else { b[i] })
///     .collect();
/// assert_eq!(merged, [0x1000, 0x1018, 0x1F50, 0x1F80, 0x2000]);
/// ```
pub fn merge_nth(
    n: usize,
    a_len: usize,
    a: impl Fn(usize) -> u16,
    b_len: usize,
    b: impl Fn(usize) -> u16,
) -> Option<(bool, usize)> {
    if n >= a_len + b_len {
        return None;
    }
    // The smallest split i (objects of `a` among the first n) at which a(i) is not below b(n - i - 1).
    let (mut lo, mut hi) = (n.saturating_sub(b_len), n.min(a_len));
    while lo < hi {
        let i = lo + (hi - lo) / 2;
        if a(i) < b(n - i - 1) {
            lo = i + 1;
        } else {
            hi = i;
        }
    }
    let j = n - lo;
    Some(if lo < a_len && (j >= b_len || a(lo) < b(j)) { (true, lo) } else { (false, j) })
}

/// The index of an object a description lists at `n` (`u16::MAX` for a hole, so it sorts last).
fn index_of<D: OdDescribe + ?Sized>(od: &D, n: usize) -> u16 {
    od.object_index(n).unwrap_or(u16::MAX)
}

impl<C: OdDescribe, A: OdDescribe> Merged<C, A> {
    /// Where the `n`-th object of the merged order is: (true, `comm`'s `i`) or (false, `app`'s `j`).
    fn locate(&self, n: usize) -> Option<(bool, usize)> {
        let (c, a) = (&self.comm, &self.app);
        merge_nth(n, c.object_count(), |i| index_of(c, i), a.object_count(), |j| index_of(a, j))
    }
}

impl<C: OdDescribe, A: OdDescribe> OdDescribe for Merged<C, A> {
    fn object_count(&self) -> usize {
        self.comm.object_count() + self.app.object_count()
    }
    fn object(&self, n: usize) -> Option<ObjectDesc> {
        match self.locate(n)? {
            (true, i) => self.comm.object(i),
            (false, j) => self.app.object(j),
        }
    }
    fn object_index(&self, n: usize) -> Option<u16> {
        match self.locate(n)? {
            (true, i) => self.comm.object_index(i),
            (false, j) => self.app.object_index(j),
        }
    }
    /// 1F50h–1F57h: the communication profile's entry, else the application's (which serves them when it
    /// is a `program::ProgramDownload`).
    fn entry(&self, index: u16, sub: u8) -> Option<EntryDesc> {
        if is_program(index) {
            return self.comm.entry(index, sub).or_else(|| self.app.entry(index, sub));
        }
        if is_comm(index) {
            self.comm.entry(index, sub)
        } else {
            self.app.entry(index, sub)
        }
    }
}
