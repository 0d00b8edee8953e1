//! One dictionary from two: the communication profile (1000h–1FFFh) and the application (everything
//! else), dispatched by index range with one comparison, never by scanning. SDO, PDO mapping and the EDS
//! writer all see the [`Merged`] dictionary.

use super::{EntryDesc, ObjectDictionary, OdDescribe};

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

/// The routed methods of an [`ObjectDictionary`] made of two (every method but the constants,
/// `restore_defaults` and `write_events`, which a composition decides itself): each access goes to
/// `self.$first` when `$is_first(index)` holds for its index (a PDO handle's index), else to
/// `self.$second`, with that one comparison and nothing else. Used inside the `impl` block, by
/// [`Merged`] (communication profile | application) and by compositions of other crates (a CiA 402 drive's
/// objects | the application's).
///
/// ```
/// use canopen_core::od::{AbortCode, ObjectDictionary, SubInfo};
/// # struct Half(u16);
/// # impl ObjectDictionary for Half {
/// #     fn info(&self, i: u16, _: u8) -> Result<SubInfo, AbortCode> { Err(AbortCode::ObjectDoesNotExist) }
/// #     fn read(&self, _: u16, _: u8, _: usize, b: &mut [u8]) -> Result<usize, AbortCode> { b[..2].copy_from_slice(&self.0.to_le_bytes()); Ok(2) }
/// #     fn write(&mut self, _: u16, _: u8, d: &[u8]) -> Result<(), AbortCode> { self.0 = u16::from(d[0]); Ok(()) }
/// # }
/// /// 6000h–67FFh to `low`, everything else to `high`.
/// struct Two { low: Half, high: Half }
/// const fn is_low(index: u16) -> bool { index >= 0x6000 && index <= 0x67FF }
/// impl ObjectDictionary for Two {
///     canopen_core::route_by_index!(is_low, low, high);
///     fn restore_defaults(&mut self) {}
/// }
/// let mut two = Two { low: Half(1), high: Half(2) };
/// let mut b = [0u8; 2];
/// assert_eq!(two.read(0x6000, 0, 0, &mut b), Ok(2));
/// assert_eq!(b, [1, 0]);
/// two.write(0x2000, 0, &[9]).unwrap();
/// assert_eq!((two.low.0, two.high.0), (1, 9));
/// ```
#[macro_export]
macro_rules! route_by_index {
    ($is_first:expr, $first:ident, $second:ident) => {
        $crate::route_by_index!(@route $is_first, $first, $second;
            fn info(&self, index: u16, sub: u8) -> Result<$crate::od::SubInfo, $crate::od::AbortCode> => info(index, sub) @ index;
            fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, $crate::od::AbortCode>
                => read(index, sub, offset, buf) @ index;
            fn read_expedited(&self, index: u16, sub: u8, buf: &mut [u8; 4]) -> Result<(usize, usize), $crate::od::AbortCode>
                => read_expedited(index, sub, buf) @ index;
            fn slot(&self, index: u16, sub: u8) -> u16 => slot(index, sub) @ index;
            fn read_slot(&self, index: u16, sub: u8, slot: u16, offset: usize, buf: &mut [u8]) -> Result<(), $crate::od::AbortCode>
                => read_slot(index, sub, slot, offset, buf) @ index;
            fn pdo_resolve(&self, index: u16, sub: u8, dir: $crate::od::PdoDir) -> Result<$crate::od::PdoHandle, $crate::od::AbortCode>
                => pdo_resolve(index, sub, dir) @ index;
        );
        $crate::route_by_index!(@route_mut $is_first, $first, $second;
            fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), $crate::od::AbortCode> => write(index, sub, data) @ index;
            fn begin_write(&mut self, index: u16, sub: u8, size: Option<usize>) -> Result<(), $crate::od::AbortCode>
                => begin_write(index, sub, size) @ index;
            fn write_chunk(&mut self, index: u16, sub: u8, offset: usize, data: &[u8]) -> Result<(), $crate::od::AbortCode>
                => write_chunk(index, sub, offset, data) @ index;
            fn end_write(&mut self, index: u16, sub: u8, total: usize) -> Result<(), $crate::od::AbortCode>
                => end_write(index, sub, total) @ index;
            fn abort_write(&mut self, index: u16, sub: u8) -> () => abort_write(index, sub) @ index;
            fn write_expedited(&mut self, index: u16, sub: u8, data: &[u8; 4], len: Option<usize>) -> Result<(), $crate::od::AbortCode>
                => write_expedited(index, sub, data, len) @ index;
        );
        fn pdo_read(&self, handle: &$crate::od::PdoHandle, buf: &mut [u8]) -> Result<usize, $crate::od::AbortCode> {
            if ($is_first)(handle.index) {
                self.$first.pdo_read(handle, buf)
            } else {
                self.$second.pdo_read(handle, buf)
            }
        }
        fn pdo_write(&mut self, handle: &$crate::od::PdoHandle, data: &[u8]) -> Result<(), $crate::od::AbortCode> {
            if ($is_first)(handle.index) {
                self.$first.pdo_write(handle, data)
            } else {
                self.$second.pdo_write(handle, data)
            }
        }
    };
    (@route $is_first:expr, $first:ident, $second:ident;
        $(fn $m:ident(&self, $($a:ident: $t:ty),*) -> $r:ty => $call:ident($($arg:ident),*) @ $key:ident;)*) => {
        $(fn $m(&self, $($a: $t),*) -> $r {
            if ($is_first)($key) {
                self.$first.$call($($arg),*)
            } else {
                self.$second.$call($($arg),*)
            }
        })*
    };
    (@route_mut $is_first:expr, $first:ident, $second:ident;
        $(fn $m:ident(&mut self, $($a:ident: $t:ty),*) -> $r:ty => $call:ident($($arg:ident),*) @ $key:ident;)*) => {
        $(fn $m(&mut self, $($a: $t),*) -> $r {
            if ($is_first)($key) {
                self.$first.$call($($arg),*)
            } else {
                self.$second.$call($($arg),*)
            }
        })*
    };
}

/// The listing methods of an [`OdDescribe`] made of two (`object_count`, `object`, `object_index`): the
/// objects of `self.$first` and `self.$second` (each listed in increasing index order) merged into one
/// increasing order with [`merge_nth`], no buffer. `entry` routes by index, which the composition writes.
///
/// ```
/// use canopen_core::od::{EntryDesc, ObjectCode, ObjectDesc, OdDescribe};
/// # struct List(&'static [u16]);
/// # impl OdDescribe for List {
/// #     fn object_count(&self) -> usize { self.0.len() }
/// #     fn object(&self, n: usize) -> Option<ObjectDesc> {
/// #         let index = *self.0.get(n)?;
/// #         Some(ObjectDesc { index, name: "x", code: ObjectCode::Var, first: 0, subs: 1 })
/// #     }
/// #     fn entry(&self, _: u16, _: u8) -> Option<EntryDesc> { None }
/// # }
/// struct Two { a: List, b: List }
/// impl OdDescribe for Two {
///     canopen_core::describe_merged!(a, b);
///     fn entry(&self, _: u16, _: u8) -> Option<EntryDesc> { None }
/// }
/// let two = Two { a: List(&[0x1000, 0x6000]), b: List(&[0x2000]) };
/// let order: Vec<u16> = (0..two.object_count()).filter_map(|n| two.object_index(n)).collect();
/// assert_eq!(order, [0x1000, 0x2000, 0x6000]);
/// ```
#[macro_export]
macro_rules! describe_merged {
    ($first:ident, $second:ident) => {
        fn object_count(&self) -> usize {
            self.$first.object_count() + self.$second.object_count()
        }
        fn object(&self, n: usize) -> Option<$crate::od::ObjectDesc> {
            match $crate::od::merged_position(&self.$first, &self.$second, n)? {
                (true, i) => self.$first.object(i),
                (false, j) => self.$second.object(j),
            }
        }
        fn object_index(&self, n: usize) -> Option<u16> {
            match $crate::od::merged_position(&self.$first, &self.$second, n)? {
                (true, i) => self.$first.object_index(i),
                (false, j) => self.$second.object_index(j),
            }
        }
    };
}

impl<C: ObjectDictionary, A: ObjectDictionary> ObjectDictionary for Merged<C, A> {
    const STREAMS: bool = C::STREAMS || A::STREAMS;
    const SEGMENTED_UPLOADS: bool = C::SEGMENTED_UPLOADS || A::SEGMENTED_UPLOADS;

    crate::route_by_index!(is_comm_for::<A>, comm, app);
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

/// Where the `n`-th object of two descriptions merged into one increasing order is: (true, `i`-th of
/// `a`) or (false, `j`-th of `b`); `None` past the end. What [`describe_merged!`](crate::describe_merged)
/// lists by (a listing position whose index is missing sorts last).
///
/// ```
/// use canopen_core::od::{merged_position, EntryDesc, ObjectCode, ObjectDesc, OdDescribe};
/// # struct List(&'static [u16]);
/// # impl OdDescribe for List {
/// #     fn object_count(&self) -> usize { self.0.len() }
/// #     fn object(&self, n: usize) -> Option<ObjectDesc> {
/// #         let index = *self.0.get(n)?;
/// #         Some(ObjectDesc { index, name: "x", code: ObjectCode::Var, first: 0, subs: 1 })
/// #     }
/// #     fn entry(&self, _: u16, _: u8) -> Option<EntryDesc> { None }
/// # }
/// let (a, b) = (List(&[0x1000, 0x6000]), List(&[0x2000]));
/// assert_eq!(merged_position(&a, &b, 1), Some((false, 0)));
/// assert_eq!(merged_position(&a, &b, 3), None);
/// ```
pub fn merged_position<A: OdDescribe + ?Sized, B: OdDescribe + ?Sized>(
    a: &A,
    b: &B,
    n: usize,
) -> Option<(bool, usize)> {
    let (a_index, b_index) = (|i| a.object_index(i).unwrap_or(u16::MAX), |j| b.object_index(j).unwrap_or(u16::MAX));
    merge_nth(n, a.object_count(), a_index, b.object_count(), b_index)
}

impl<C: OdDescribe, A: OdDescribe> OdDescribe for Merged<C, A> {
    crate::describe_merged!(comm, app);
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
