//! The dictionary reached by offset (`#[od(compact, zerocopy)]`, [`OdData::BY_OFFSET`]): a fixed-size value
//! is its row's byte offset in the struct's bytes, which zerocopy's traits prove sound (no `unsafe` here),
//! moved in the little-endian encoding (ENC-01); PDO handles carry the offset and the size itself
//! (PDO-11/PDO-12), so a mapped object is one dispatch and one copy with no row at all. Limits and hooks
//! (OD-11) still go through the row.

use super::{limits, OdData, Row, Shape};
use crate::od::{AbortCode, PdoHandle};

/// [`OdData::bytes`] of a `#[od(compact, zerocopy)]` dictionary: the struct's bytes, which zerocopy's
/// `IntoBytes` proves are all initialised (no padding) and `Immutable` proves are not behind a cell.
///
/// ```
/// use zerocopy::{Immutable, IntoBytes};
/// #[derive(IntoBytes, Immutable)]
/// #[repr(C)]
/// struct App { speed: u32, mode: u16, level: u16 }
/// let app = App { speed: 1, mode: 2, level: 3 };
/// assert_eq!(canopen_core::od::data::as_bytes(&app).len(), 8);
/// ```
#[inline(always)]
pub fn as_bytes<T: zerocopy::IntoBytes + zerocopy::Immutable>(t: &T) -> &[u8] {
    t.as_bytes()
}

/// [`OdData::bytes_mut`] of a `#[od(compact, zerocopy)]` dictionary: the struct's bytes to write, which
/// zerocopy's `FromBytes` proves any value of is a valid struct.
///
/// ```
/// use zerocopy::{FromBytes, IntoBytes};
/// #[derive(IntoBytes, FromBytes)]
/// #[repr(C)]
/// struct App { speed: u32 }
/// let mut app = App { speed: 1 };
/// canopen_core::od::data::as_bytes_mut(&mut app).copy_from_slice(&7u32.to_ne_bytes());
/// assert_eq!(app.speed, 7);
/// ```
#[inline(always)]
pub fn as_bytes_mut<T: zerocopy::IntoBytes + zerocopy::FromBytes>(t: &mut T) -> &mut [u8] {
    t.as_mut_bytes()
}

/// Copies an `N`-byte value between native byte order (in [`OdData::bytes`]) and the little-endian
/// encoding: one load and one store on a little-endian target.
#[inline(always)]
fn copy_order<const N: usize>(src: &[u8; N], dst: &mut [u8; N]) {
    *dst = *src;
    if cfg!(target_endian = "big") {
        dst.reverse();
    }
}

/// Bytes `offset..` of the fixed-size value of `row`/`elem`, reached by offset ([`OdData::BY_OFFSET`]);
/// `None` for a string or DOMAIN. One arm per size, each a fixed-size copy (a copy of the run-time size
/// was a call to `memcpy` per value).
#[inline(always)]
pub(super) fn read_at<D: OdData + ?Sized>(
    d: &D,
    row: &Row,
    elem: u8,
    offset: usize,
    buf: &mut [u8],
) -> Option<Result<usize, AbortCode>> {
    let bytes = d.bytes();
    Some(Ok(match row.data_type.fixed_size() {
        0 => return None,
        1 => read_n::<1>(bytes, row, elem, offset, buf),
        2 => read_n::<2>(bytes, row, elem, offset, buf),
        4 => read_n::<4>(bytes, row, elem, offset, buf),
        8 if const { has_size(D::SHAPES, 8) } => read_n::<8>(bytes, row, elem, offset, buf),
        // A struct with a byte view holds plain numbers only: 1, 2, 4 or 8 bytes (and 8 only when a shape
        // has 8: a row's size is its shape's).
        _ => return Some(Err(AbortCode::ObjectDoesNotExist)),
    }))
}

/// [`read_at`] of an `N`-byte value: the whole of it into a buffer that holds it, else from `offset`.
#[inline(always)]
fn read_n<const N: usize>(bytes: &[u8], row: &Row, elem: u8, offset: usize, buf: &mut [u8]) -> usize {
    let Some(src) = value::<N>(bytes, at(row, elem, N)) else {
        return 0;
    };
    match buf.get_mut(..N).and_then(|b| <&mut [u8; N]>::try_from(b).ok()) {
        Some(dst) if offset == 0 => {
            copy_order(src, dst);
            N
        }
        _ => read_part(src, offset, buf),
    }
}

/// [`read_n`]'s rare case: a part of the value, or a buffer shorter than it (SDO segments of a 64-bit
/// value). One copy for every size (`src` is 1 to 8 bytes in native order).
#[cold]
#[inline(never)]
fn read_part(src: &[u8], offset: usize, buf: &mut [u8]) -> usize {
    let mut le = [0u8; 8];
    let Some(le) = le.get_mut(..src.len()) else {
        return 0;
    };
    le.copy_from_slice(src);
    if cfg!(target_endian = "big") {
        le.reverse();
    }
    crate::od::copy_at(le, offset, buf)
}

/// Whether one of `shapes` is of a type of `n` bytes: a dictionary without 64-bit values links no 8-byte
/// arm in [`read_at`] and [`store`] (a row's size is its shape's, so the arm could never be taken).
const fn has_size(shapes: &[Shape], n: usize) -> bool {
    let mut i = 0;
    while i < shapes.len() {
        if shapes[i].data_type.fixed_size() == n {
            return true;
        }
        i += 1;
    }
    false
}

/// Where the value of `row`/`elem` starts in [`OdData::bytes`]: the row's offset and the element's.
#[inline(always)]
fn at(row: &Row, elem: u8, size: usize) -> usize {
    usize::from(row.field) + usize::from(elem) * size
}

/// The `N` bytes of the value at `at`, or `None` past the end of `bytes`.
#[inline(always)]
fn value<const N: usize>(bytes: &[u8], at: usize) -> Option<&[u8; N]> {
    bytes.get(at..at + N).and_then(|s| <&[u8; N]>::try_from(s).ok())
}

/// Stores `data` (little-endian, `size` bytes: 1, 2, 4 or 8) at `at` in native byte order, one arm per size
/// ([`copy_in`]): a write by row and a write through an offset PDO handle alike.
#[inline(always)]
fn store<D: OdData + ?Sized>(bytes: &mut [u8], at: usize, size: usize, data: &[u8]) -> Result<(), AbortCode> {
    match size {
        1 => copy_in::<1>(bytes, at, data),
        2 => copy_in::<2>(bytes, at, data),
        4 => copy_in::<4>(bytes, at, data),
        8 if const { has_size(D::SHAPES, 8) } => copy_in::<8>(bytes, at, data),
        // A struct with a byte view holds plain numbers only (8 bytes only when a shape has them, see
        // [`read_at`]).
        _ => Err(AbortCode::ObjectDoesNotExist),
    }
}

/// Stores a fixed-size value of `row`/`elem` by offset ([`OdData::BY_OFFSET`]), after its limits and the
/// application's check with `hooks`; `None` for a string or DOMAIN.
#[inline(always)]
pub(super) fn write_at<D: OdData + ?Sized>(
    d: &mut D,
    pos: u16,
    row: &Row,
    elem: u8,
    sub: u8,
    data: &[u8],
    hooks: bool,
) -> Option<Result<(), AbortCode>> {
    let size = row.data_type.fixed_size();
    if size == 0 {
        return None;
    }
    Some((|| {
        if hooks {
            limits::check(d, pos, row.data_type, sub, data)?;
        }
        store::<D>(d.bytes_mut(), at(row, elem, size), size, data)?;
        if hooks {
            d.on_write(pos, sub);
        }
        Ok(())
    })())
}

/// A PDO handle's slot in [`OdData::BY_OFFSET`] mode is either the value's byte offset in
/// [`OdData::bytes`] (bits 0..11) with its size class (bits 12..13: `log2` of 1, 2, 4 or 8 bytes) and
/// [`SLOT_RO`], or, with this bit, a row position (a value with limits or hooks, or past 4 KiB).
/// [`pdo_read`](super::pdo_read)/[`pdo_write`](super::pdo_write) dispatch once on the slot's top four
/// bits: each size, a read-only entry and a row slot are arms of one jump table, and an offset slot moves
/// its value with no row at all.
const ROW_SLOT: u16 = 0x8000;
/// In an offset slot: the entry is not writable ([`pdo_write`](super::pdo_write) answers 0601 0002h).
const SLOT_RO: u16 = 0x4000;
/// In an offset slot: where the size class is.
const SIZE_SHIFT: u16 = 12;
/// In an offset slot: the offset's bits.
const OFFSET_MASK: u16 = (1 << SIZE_SHIFT) - 1;

/// The offset slot of `row`/`elem` (see [`ROW_SLOT`]) in [`OdData::BY_OFFSET`] mode, `None` when the row
/// needs its checks, SDO may not read it, or the offset does not fit.
pub(super) fn offset_slot<D: OdData + ?Sized>(row: &Row, elem: u8) -> Option<u16> {
    let size = row.data_type.fixed_size();
    let at = at(row, elem, size);
    let class = match size {
        1 => 0,
        2 => 1,
        4 => 2,
        8 => 3,
        _ => return None,
    };
    let ro = if row.writable() { 0 } else { SLOT_RO };
    (D::BY_OFFSET && !row.checks() && row.readable() && at <= usize::from(OFFSET_MASK))
        .then_some(ro | class << SIZE_SHIFT | at as u16)
}

/// The PDO slot of the row at `pos` when it has no offset slot: marked with [`ROW_SLOT`] in
/// [`OdData::BY_OFFSET`] mode.
pub(super) fn row_slot<D: OdData + ?Sized>(pos: u16) -> u16 {
    if D::BY_OFFSET {
        pos | ROW_SLOT
    } else {
        pos
    }
}

/// The row position of a PDO handle's row slot ([`row_slot`]).
#[inline(always)]
pub(super) fn slot_row<D: OdData + ?Sized>(slot: u16) -> u16 {
    if D::BY_OFFSET {
        slot & !ROW_SLOT
    } else {
        slot
    }
}

/// [`pdo_read`](super::pdo_read) of an offset slot: the value's bytes from its offset; `None` for a row slot.
/// One dispatch on the slot's top four bits ([`ROW_SLOT`], [`SLOT_RO`], the size class), so that telling
/// an offset slot from a row slot costs no test of its own.
#[inline(always)]
pub(super) fn read_offset_slot<D: OdData + ?Sized>(
    d: &D,
    handle: &PdoHandle,
    buf: &mut [u8],
) -> Option<Result<usize, AbortCode>> {
    let (bytes, at) = (d.bytes(), usize::from(handle.slot & OFFSET_MASK));
    const _: () = assert!(ROW_SLOT >> SIZE_SHIFT == 8 && SLOT_RO >> SIZE_SHIFT == 4);
    let n = match handle.slot >> SIZE_SHIFT {
        0 | 4 => copy_out::<1>(bytes, at, buf),
        1 | 5 => copy_out::<2>(bytes, at, buf),
        2 | 6 => copy_out::<4>(bytes, at, buf),
        3 | 7 => copy_out::<8>(bytes, at, buf),
        _ => return None,
    };
    Some(n.ok_or(AbortCode::ObjectDoesNotExist))
}

/// The `N` bytes at `at` into the front of `buf`, little-endian.
#[inline(always)]
fn copy_out<const N: usize>(bytes: &[u8], at: usize, buf: &mut [u8]) -> Option<usize> {
    let src = value::<N>(bytes, at)?;
    let dst = buf.get_mut(..N).and_then(|b| <&mut [u8; N]>::try_from(b).ok())?;
    copy_order(src, dst);
    Some(N)
}

/// [`pdo_write`](super::pdo_write) of an offset slot: `data` (the value's size) stored at its offset;
/// `None` for a row slot. As [`read_offset_slot`], one dispatch: a read-only entry ([`SLOT_RO`]) is one
/// more arm, 0601 0002h.
#[inline(always)]
pub(super) fn write_offset_slot<D: OdData + ?Sized>(
    d: &mut D,
    handle: &PdoHandle,
    data: &[u8],
) -> Option<Result<(), AbortCode>> {
    let (bytes, at) = (d.bytes_mut(), usize::from(handle.slot & OFFSET_MASK));
    Some(match handle.slot >> SIZE_SHIFT {
        0 => copy_in::<1>(bytes, at, data),
        1 => copy_in::<2>(bytes, at, data),
        2 => copy_in::<4>(bytes, at, data),
        3 => copy_in::<8>(bytes, at, data),
        4..=7 => Err(AbortCode::WriteOfReadOnly),
        _ => return None,
    })
}

/// `data` (exactly `N` little-endian bytes) stored at `at` in native byte order.
#[inline(always)]
fn copy_in<const N: usize>(bytes: &mut [u8], at: usize, data: &[u8]) -> Result<(), AbortCode> {
    crate::od::check_len(data, N)?;
    let src = <&[u8; N]>::try_from(data).map_err(|_| AbortCode::GeneralError)?; // the same check: folded
    let dst = bytes.get_mut(at..at + N).and_then(|s| <&mut [u8; N]>::try_from(s).ok());
    copy_order(src, dst.ok_or(AbortCode::ObjectDoesNotExist)?);
    Ok(())
}
