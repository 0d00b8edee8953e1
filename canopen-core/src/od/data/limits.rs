//! Limits of a data dictionary's rows (OD-11): a value written below its row's low limit is 0609 0032h,
//! above its high limit 0609 0031h, and a value that does not compare (a NaN) 0609 0030h.
//!
//! Every fixed-size type is compared through one order key, a `u64` whose unsigned order is the type's own
//! order: unsigned numbers as they are, signed ones sign-extended with the sign bit flipped, REAL32/REAL64
//! by the IEEE 754 total-order trick (−0 taken as +0, as IEEE compares them; a NaN has no key), TIME_OF_DAY
//! and TIME_DIFFERENCE as days then milliseconds. So one function, with integer operations only, checks the
//! limits of every type a dictionary has (issue 41: the compare per type was a copy of the same function for
//! each type a dictionary checks, some 100 bytes of flash each, and REAL32 needed the float compare).

use super::{OdData, Shape};
use crate::od::{check_len, AbortCode, DataType};

/// The order key of the `dt` value encoded little-endian in `data` (exactly its size): 0609 0030h for a
/// NaN (it does not compare); the length's abort code for a wrong length (0607 0012h/0607 0013h), and 0609 0030h for a BOOLEAN
/// other than 0 or 1, as decoding the value answers; 0602 0000h for a string or DOMAIN (no limits).
///
/// ```
/// use canopen_core::od::{data::limits::order_key, AbortCode, DataType};
/// let k = |dt, b: &[u8]| order_key(dt, b).unwrap();
/// assert!(k(DataType::Integer16, &(-2i16).to_le_bytes()) < k(DataType::Integer16, &1i16.to_le_bytes()));
/// assert!(k(DataType::Real32, &(-0.5f32).to_le_bytes()) < k(DataType::Real32, &0.25f32.to_le_bytes()));
/// assert_eq!(order_key(DataType::Real32, &f32::NAN.to_le_bytes()), Err(AbortCode::InvalidValue));
/// ```
#[inline(never)]
pub fn order_key(dt: DataType, data: &[u8]) -> Result<u64, AbortCode> {
    key_in(ALL_CLASSES, dt, data)
}

/// [`order_key`] of a dictionary whose limited types are of the [`classes`] in `classes` alone: the arms of
/// the others compile away (a firmware whose only limits are an INTEGER16's links no REAL or TIME key). The
/// class of `dt` must be among them: [`within`] passes only the types of the shapes that have limits.
#[inline(always)]
fn key_in(classes: u8, dt: DataType, data: &[u8]) -> Result<u64, AbortCode> {
    let size = dt.fixed_size();
    if size == 0 {
        return Err(AbortCode::ObjectDoesNotExist);
    }
    check_len(data, size)?;
    let raw = data.iter().rev().fold(0u64, |acc, &b| acc << 8 | u64::from(b));
    // The value moved to the top of the `u64`: its sign bit is bit 63 whatever its size.
    let top = raw << (64 - 8 * size);
    let has = |c: u8| classes & 1 << c != 0;
    Ok(match class(dt) {
        SIGNED if has(SIGNED) => top ^ 1 << 63,
        REAL if has(REAL) => {
            let infinity = if size == 4 { 0x7F80_0000 << 32 } else { 0x7FF0_0000_0000_0000 };
            let magnitude = top & !(1 << 63);
            match (magnitude > infinity, top >> 63 != 0 && magnitude != 0) {
                (true, _) => return Err(AbortCode::InvalidValue), // NaN
                (false, true) => !top, // negative: the larger the magnitude, the smaller the key
                (false, false) => magnitude | 1 << 63, // positive, and -0 as +0
            }
        }
        TIME if has(TIME) => (raw >> 32 & 0xFFFF) << 32 | (raw & 0x0FFF_FFFF),
        BOOLEAN if has(BOOLEAN) && raw > 1 => return Err(AbortCode::InvalidValue),
        _ => raw,
    })
}

/// The class of a fixed-size type: [`SIGNED`], [`REAL`], [`TIME`], [`BOOLEAN`], or 0 (an unsigned number,
/// or a code of no fixed-size type). How [`order_key`] orders a value and how
/// [`OdData::DEFAULTS`](super::OdData::DEFAULTS) holds a default.
pub(super) const fn class(dt: DataType) -> u8 {
    CLASS[dt as usize & 0x1F]
}

/// Every class, for [`order_key`].
const ALL_CLASSES: u8 = 1 << BOOLEAN | 1 << SIGNED | 1 << REAL | 1 << TIME;

/// The classes (bit `c` for `class` `c`) of the first `limited` of `shapes`: the shapes that have limits
/// ([`OdData::LIMITS`]), so the types `within` computes keys of.
///
/// ```
/// use canopen_core::od::{data::{limits::classes, Row, Shape}, Access, DataType, PdoMapping};
/// let var = |dt| Shape::of(Row::var(0, dt, Access::Rw, PdoMapping::No));
/// let shapes = [var(DataType::Integer16), var(DataType::Unsigned8), var(DataType::Real32)];
/// assert_eq!(classes(&shapes, 0), 0);
/// assert_eq!(classes(&shapes, 2), classes(&shapes[..1], 1) | classes(&shapes[1..], 1));
/// assert_ne!(classes(&shapes, 3), classes(&shapes, 2)); // the REAL32 shape's class, once it has limits
/// ```
pub const fn classes(shapes: &[Shape], limited: usize) -> u8 {
    let mut bits = 0;
    let mut i = 0;
    while i < limited && i < shapes.len() {
        bits |= 1 << class(shapes[i].data_type);
        i += 1;
    }
    bits
}

/// [`order_key`] for `D`'s limited types alone ([`key_in`]): one copy per dictionary type, out of line
/// ([`within`] takes three keys).
#[inline(never)]
fn key_of<D: OdData + ?Sized>(dt: DataType, data: &[u8]) -> Result<u64, AbortCode> {
    key_in(const { classes(D::SHAPES, D::LIMITS.len()) }, dt, data)
}

/// [`class`] by type code.
const CLASS: [u8; 32] = {
    let mut t = [0u8; 32];
    t[DataType::Boolean as usize] = BOOLEAN;
    let signed = [
        DataType::Integer8,
        DataType::Integer16,
        DataType::Integer24,
        DataType::Integer32,
        DataType::Integer40,
        DataType::Integer48,
        DataType::Integer56,
        DataType::Integer64,
    ];
    let mut i = 0;
    while i < signed.len() {
        t[signed[i] as usize] = SIGNED;
        i += 1;
    }
    t[DataType::Real32 as usize] = REAL;
    t[DataType::Real64 as usize] = REAL;
    t[DataType::TimeOfDay as usize] = TIME;
    t[DataType::TimeDifference as usize] = TIME;
    t
};
/// [`class`]: BOOLEAN.
const BOOLEAN: u8 = 1;
/// [`class`]: INTEGER8 … INTEGER64.
pub(super) const SIGNED: u8 = 2;
/// [`class`]: REAL32, REAL64.
const REAL: u8 = 3;
/// [`class`]: TIME_OF_DAY, TIME_DIFFERENCE.
const TIME: u8 = 4;

/// The limits of the row at `pos` (its shape's, [`OdData::LIMITS`]) checked against `data`, a value of `dt` (exactly its
/// size), then the application's check ([`OdData::check`]).
///
/// ```
/// use canopen_core::od::{data::limits::check, AbortCode, DataType, ObjectDictionary};
/// use canopen_od_derive::ObjectDictionary;
/// #[derive(ObjectDictionary, Default)]
/// #[od(compact)]
/// struct App { #[od(index = 0x2000, min = -5, max = 5)] x: i16 }
/// let app = App::default();
/// assert_eq!(check(&app, 0, DataType::Integer16, 0, &(-6i16).to_le_bytes()), Err(AbortCode::ValueTooLow));
/// assert_eq!(check(&app, 0, DataType::Integer16, 0, &5i16.to_le_bytes()), Ok(()));
/// ```
#[inline]
pub fn check<D: OdData + ?Sized>(d: &D, pos: u16, dt: DataType, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
    if D::LIMITS.is_empty() {
        // Hooks alone: the value's length first, as with limits (a dictionary without limits links no key).
        check_len(data, dt.fixed_size())?;
    } else {
        within::<D>(pos, dt, data)?;
    }
    d.check(pos, sub, data)
}

/// [`check`]'s limits of the row at `pos`, those of its shape: the low one, then the high one, each compared
/// by its key; a value that has none (a NaN) is 0609 0030h when the row has limits; a limit that has none is
/// no limit.
#[inline(never)]
fn within<D: OdData + ?Sized>(pos: u16, dt: DataType, data: &[u8]) -> Result<(), AbortCode> {
    let size = dt.fixed_size();
    let shape = D::ROWS.get(usize::from(pos)).map_or(usize::MAX, |r| usize::from(r.shape));
    let Some(&at) = D::LIMITS.get(shape) else {
        return check_len(data, size);
    };
    let value = key_of::<D>(dt, data)?;
    let from = usize::from(at);
    // A limit without a key (none stored, a NaN) compares equal: no limit.
    let bound =
        |from: usize| D::LIMIT_VALUES.get(from..from + size).and_then(|b| key_of::<D>(dt, b).ok()).unwrap_or(value);
    if value < bound(from) {
        return Err(AbortCode::ValueTooLow);
    }
    if value > bound(from + size) {
        return Err(AbortCode::ValueTooHigh);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::cmp::Ordering;
    use proptest::prelude::*;

    fn key(dt: DataType, b: &[u8]) -> Option<u64> {
        match order_key(dt, b) {
            Err(AbortCode::InvalidValue) => None,
            k => Some(k.unwrap()),
        }
    }

    /// The key's order against the type's own (`PartialOrd`), for two values.
    fn same_order(dt: DataType, a: &[u8], b: &[u8], own: Option<Ordering>) -> bool {
        match (key(dt, a), key(dt, b)) {
            (Some(x), Some(y)) => Some(x.cmp(&y)) == own,
            _ => own.is_none(),
        }
    }

    proptest! {
        #[test]
        fn integers_keep_their_order(a in any::<i64>(), b in any::<i64>()) {
            prop_assert!(same_order(DataType::Integer64, &a.to_le_bytes(), &b.to_le_bytes(), a.partial_cmp(&b)));
            prop_assert!(same_order(DataType::Unsigned64, &a.to_le_bytes(), &b.to_le_bytes(), (a as u64).partial_cmp(&(b as u64))));
            let (x, y) = (a as i32, b as i32);
            prop_assert!(same_order(DataType::Integer32, &x.to_le_bytes(), &y.to_le_bytes(), x.partial_cmp(&y)));
            prop_assert!(same_order(DataType::Unsigned32, &x.to_le_bytes(), &y.to_le_bytes(), (x as u32).partial_cmp(&(y as u32))));
            let (x, y) = (a as i16, b as i16);
            prop_assert!(same_order(DataType::Integer16, &x.to_le_bytes(), &y.to_le_bytes(), x.partial_cmp(&y)));
            let (x, y) = (a as i8, b as i8);
            prop_assert!(same_order(DataType::Integer8, &x.to_le_bytes(), &y.to_le_bytes(), x.partial_cmp(&y)));
            prop_assert!(same_order(DataType::Unsigned8, &x.to_le_bytes(), &y.to_le_bytes(), (x as u8).partial_cmp(&(y as u8))));
            // 24 bits: the low three bytes, sign-extended.
            let (x, y) = ((a as i32) << 8 >> 8, (b as i32) << 8 >> 8);
            prop_assert!(same_order(DataType::Integer24, &x.to_le_bytes()[..3], &y.to_le_bytes()[..3], x.partial_cmp(&y)));
            // 48 bits.
            let (x, y) = (a << 16 >> 16, b << 16 >> 16);
            prop_assert!(same_order(DataType::Integer48, &x.to_le_bytes()[..6], &y.to_le_bytes()[..6], x.partial_cmp(&y)));
        }

        #[test]
        fn reals_keep_their_order(a in any::<u64>(), b in any::<u64>(), pick in 0u8..4) {
            // Random bit patterns (NaNs, infinities, subnormals, both zeros) and a few fixed values.
            let special = [0.0f64, -0.0, f64::INFINITY, f64::NEG_INFINITY];
            let x = if pick == 0 { special[(a % 4) as usize] } else { f64::from_bits(a) };
            let y = f64::from_bits(b);
            prop_assert!(same_order(DataType::Real64, &x.to_le_bytes(), &y.to_le_bytes(), x.partial_cmp(&y)));
            let (x, y) = (x as f32, f32::from_bits(b as u32));
            prop_assert!(same_order(DataType::Real32, &x.to_le_bytes(), &y.to_le_bytes(), x.partial_cmp(&y)));
        }

        #[test]
        fn time_keeps_its_order(d1 in any::<u16>(), m1 in 0u32..1 << 28, d2 in any::<u16>(), m2 in 0u32..1 << 28) {
            let (x, y) = (crate::od::TimeOfDay { days: d1, ms: m1 }, crate::od::TimeOfDay { days: d2, ms: m2 });
            prop_assert!(same_order(DataType::TimeOfDay, &x.to_bytes(), &y.to_bytes(), x.partial_cmp(&y)));
        }
    }

    #[test]
    fn both_zeros_are_equal_and_wrong_lengths_are_refused() {
        assert_eq!(key(DataType::Real32, &(-0.0f32).to_le_bytes()), key(DataType::Real32, &0.0f32.to_le_bytes()));
        assert_eq!(order_key(DataType::Unsigned16, &[1]), Err(AbortCode::LengthTooLow));
        assert_eq!(order_key(DataType::Unsigned16, &[1, 2, 3]), Err(AbortCode::LengthTooHigh));
        assert_eq!(order_key(DataType::Boolean, &[2]), Err(AbortCode::InvalidValue));
        assert_eq!(order_key(DataType::VisibleString, b"ab"), Err(AbortCode::ObjectDoesNotExist));
    }
}
