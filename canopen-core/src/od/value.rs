//! Rust value types for every CiA 301 basic data type and their exact bus encoding.
//!
//! Covers DT-01 (little-endian), DT-02/DT-05/DT-06 (n-bit integers in ⌈n/8⌉ octets, including the
//! 24/40/48/56-bit widths as [`I24`] … [`U56`]), DT-03 (BOOLEAN as one octet 0/1 on SDO), DT-07/DT-08 (REAL32/64
//! copied as IEEE 754 bytes), DT-13/DT-14 ([`TimeOfDay`], [`TimeDifference`]) and DT-17 (each type names its
//! [`DataType`] index). The strings (DT-10..DT-12: [`OctetString`](super::OctetString),
//! [`VisibleString`](super::VisibleString), [`UnicodeString`](super::UnicodeString)) are the `string`
//! module's, on the helpers for streamed values here; DOMAIN (DT-15) is streamed through
//! [`Domain`](super::Domain).
//!
//! Every decoder checks the length first (0607 0012h too long, 0607 0013h too short) and the content second
//! (0609 0030h for a BOOLEAN other than 0/1), and never panics on hostile input.
//!
//! Floats are never computed with: REAL32/64 values are copied as bytes; the only float operation is the
//! comparison against limits ([`OdValue::cmp_limit`]) of entries whose data type is REAL32/64.

use core::cmp::Ordering;

use super::{AbortCode, DataType, Value};

/// A Rust type that can be an object-dictionary entry: its data type and its exact encoding.
///
/// The derive macro uses it for every field; implement it for your own type to store a value in a custom
/// representation (the macro accepts only the types of this module by name, so a custom type is used
/// through a hand-written [`ObjectDictionary`](super::ObjectDictionary)).
///
/// ```
/// use canopen_core::od::{DataType, OdValue};
/// assert_eq!(<u16 as OdValue>::DATA_TYPE, DataType::Unsigned16);
/// let mut buf = [0u8; 2];
/// assert_eq!(266u16.read_bytes(0, &mut buf), 2);
/// assert_eq!(buf, [0x0A, 0x01]); // UNSIGNED16 266
/// assert_eq!(u16::decode(&[0x0A, 0x01]), Ok(266));
/// ```
pub trait OdValue: Sized {
    /// The CiA 301 data type (DT-17).
    const DATA_TYPE: DataType;
    /// The largest encoded size in bytes (the capacity of a string).
    const MAX_SIZE: usize;
    /// Whether the type may be mapped into a PDO (fixed size of at most 8 bytes).
    const MAPPABLE: bool;

    /// The current encoded size in bytes.
    fn size(&self) -> usize;

    /// Copies bytes `offset..` of the encoding into `buf`; returns how many were copied.
    fn read_bytes(&self, offset: usize, buf: &mut [u8]) -> usize;

    /// Decodes a complete encoding, checking length and content; never panics.
    fn decode(data: &[u8]) -> Result<Self, AbortCode>;

    /// Compares the value with a limit from the entry table; `None` if they cannot be compared (then the
    /// write is refused with 0609 0030h). The default (non-numeric types) always says `Equal`.
    fn cmp_limit(&self, limit: &Value) -> Option<Ordering> {
        let _ = limit;
        Some(Ordering::Equal)
    }

    /// The value a dictionary default (an entry table's `default`) stands for, or `None` when the default
    /// does not fit the type. Used by Reset Application (NMT-04) to restore power-on values.
    ///
    /// ```
    /// use canopen_core::od::{OdValue, Value, I24};
    /// assert_eq!(i16::from_value(&Value::Int(-266)), Some(-266));
    /// assert_eq!(I24::from_value(&Value::Int(-5)), I24::new(-5));
    /// assert_eq!(f32::from_value(&Value::Real32(1.25)), Some(1.25));
    /// assert_eq!(u8::from_value(&Value::Str("x")), None);
    /// ```
    fn from_value(value: &Value) -> Option<Self> {
        let mut buf = [0u8; 8];
        let n = Self::MAX_SIZE.min(8);
        let bytes: &[u8] = match *value {
            Value::Bool(b) => &[b as u8],
            Value::Int(i) => {
                buf = i.to_le_bytes();
                &buf[..n]
            }
            Value::Uint(u) => {
                buf = u.to_le_bytes();
                &buf[..n]
            }
            Value::Real32(f) => {
                buf[..4].copy_from_slice(&f.to_le_bytes());
                &buf[..4]
            }
            Value::Real64(f) => {
                buf = f.to_le_bytes();
                &buf[..8]
            }
            Value::Str(s) => s.as_bytes(),
            Value::Bytes(b) => b,
            Value::NodeIdPlus(_) => return None,
        };
        // Text and bytes are defaults of strings only; numbers of fixed-size types only.
        let text = matches!(value, Value::Str(_) | Value::Bytes(_));
        if text != Self::DATA_TYPE.size().is_none() {
            return None;
        }
        Self::decode(bytes).ok()
    }

    /// Streamed write, step 1: accepts or refuses the announced size before any data moves. Only strings
    /// support streaming; fixed-size values (≤ 8 bytes) are written whole.
    fn begin_stream(&mut self, size: Option<usize>) -> Result<(), AbortCode> {
        let _ = size;
        Err(AbortCode::UnsupportedAccess)
    }

    /// Streamed write, step 2: stores `data` at `offset`.
    fn stream_chunk(&mut self, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        let _ = (offset, data);
        Err(AbortCode::UnsupportedAccess)
    }

    /// Streamed write, step 3: the transfer is complete with `total` bytes; returns the value they make.
    /// The streamed bytes are staged apart from the current value, which stays as it is: the caller checks
    /// the new value and stores it, so a transfer that is aborted, or whose value is refused, changes
    /// nothing (a segmented or block download aborted midway leaves the old string).
    fn end_stream(&self, total: usize) -> Result<Self, AbortCode> {
        let _ = total;
        Err(AbortCode::UnsupportedAccess)
    }
}

/// Copies `src[offset..]` into `buf`; returns the number of bytes copied (0 past the end).
///
/// Out of line: one copy in the firmware for every value type and dictionary entry that reads through it
/// (120 B of the example node's flash when it was inline). The values SDO streams, strings and DOMAINs,
/// first try an inline short path for a buffer filled whole (every segment of an upload but the last).
///
/// ```
/// use canopen_core::od::copy_at;
/// let mut buf = [0u8; 2];
/// assert_eq!(copy_at(&[1, 2, 3], 1, &mut buf), 2);
/// assert_eq!(buf, [2, 3]);
/// assert_eq!(copy_at(&[1, 2, 3], 2, &mut buf), 1); // the tail: one byte
/// assert_eq!(buf, [3, 3]);
/// assert_eq!(copy_at(&[1, 2, 3], 9, &mut buf), 0);
/// assert_eq!(copy_at(&[1, 2, 3], usize::MAX, &mut buf), 0);
/// ```
#[inline(never)]
pub fn copy_at(src: &[u8], offset: usize, buf: &mut [u8]) -> usize {
    let src = src.get(offset..).unwrap_or(&[]);
    let n = src.len().min(buf.len());
    if let (Some(dst), Some(src)) = (buf.get_mut(..n), src.get(..n)) {
        dst.copy_from_slice(src);
    }
    n
}

/// [`copy_at`] for the values SDO streams (strings, DOMAINs): a part that fills `buf` (every segment but
/// the last) is copied inline, where the caller's constant 7 bytes make it two moves; the rest is the call.
#[inline]
pub(crate) fn copy_streamed(src: &[u8], offset: usize, buf: &mut [u8]) -> usize {
    match offset.checked_add(buf.len()).and_then(|end| src.get(offset..end)) {
        Some(whole) => {
            buf.copy_from_slice(whole);
            buf.len()
        }
        None => copy_at(src, offset, buf),
    }
}

/// A streamed write of `size` bytes (when announced) into room for `cap` bytes: 0607 0012h when it cannot fit.
#[inline]
pub(crate) fn fits(size: Option<usize>, cap: usize) -> Result<(), AbortCode> {
    match size {
        Some(s) if s > cap => Err(AbortCode::LengthTooHigh),
        _ => Ok(()),
    }
}

/// The end of a streamed chunk of `len` bytes at `offset`, when it fits in `cap` bytes (else 0607 0012h).
#[inline]
pub(crate) fn chunk_end(offset: usize, len: usize, cap: usize) -> Result<usize, AbortCode> {
    offset.checked_add(len).filter(|&e| e <= cap).ok_or(AbortCode::LengthTooHigh)
}

/// [`copy_at`] for a fixed-size encoding: the whole value at once (PDO packing, expedited SDO) is one
/// load/store of `N` bytes instead of a call to `memcpy`.
#[inline]
fn read_fixed<const N: usize>(b: [u8; N], offset: usize, buf: &mut [u8]) -> usize {
    match buf.get_mut(..N) {
        Some(dst) if offset == 0 => {
            dst.copy_from_slice(&b);
            N
        }
        _ => copy_rare(&b, offset, buf),
    }
}

/// [`copy_at`] for [`read_fixed`]'s rare case (a part of the value, or a short buffer): cold, so that the
/// whole-value path stays the straight line (bench-node.sh sync_4_tpdos: 7 instructions per frame).
#[cold]
fn copy_rare(src: &[u8], offset: usize, buf: &mut [u8]) -> usize {
    copy_at(src, offset, buf)
}

/// Checks that `data` has exactly `size` bytes (0607 0012h / 0607 0013h otherwise).
///
/// ```
/// use canopen_core::od::{check_len, AbortCode};
/// assert_eq!(check_len(&[1, 2], 2), Ok(()));
/// assert_eq!(check_len(&[1, 2, 3], 2), Err(AbortCode::LengthTooHigh));
/// assert_eq!(check_len(&[1], 2), Err(AbortCode::LengthTooLow));
/// ```
#[inline]
pub fn check_len(data: &[u8], size: usize) -> Result<(), AbortCode> {
    // Equality first, as one compare and branch: a `match` on `cmp` built the Ordering (5 instructions on
    // x86-64) before every fixed-size write (expedited download, each RPDO-mapped object).
    if data.len() == size {
        Ok(())
    } else {
        Err(length_error(data.len(), size))
    }
}

/// The abort code of a length that is not the one expected.
#[cold]
#[inline(never)]
fn length_error(len: usize, size: usize) -> AbortCode {
    if len > size {
        AbortCode::LengthTooHigh
    } else {
        AbortCode::LengthTooLow
    }
}

/// Checks a decoded value against optional low/high limits: 0609 0032h below, 0609 0031h above,
/// 0609 0030h when not comparable (e.g. a NaN REAL32).
///
/// ```
/// use canopen_core::od::{check_limits, AbortCode, Value};
/// let (lo, hi) = (Some(Value::Int(-1000)), Some(Value::Int(1000)));
/// assert_eq!(check_limits(&5i16, lo.as_ref(), hi.as_ref()), Ok(()));
/// assert_eq!(check_limits(&1001i16, lo.as_ref(), hi.as_ref()), Err(AbortCode::ValueTooHigh));
/// assert_eq!(check_limits(&-1001i16, lo.as_ref(), hi.as_ref()), Err(AbortCode::ValueTooLow));
/// ```
pub fn check_limits<T: OdValue>(value: &T, low: Option<&Value>, high: Option<&Value>) -> Result<(), AbortCode> {
    if let Some(low) = low {
        match value.cmp_limit(low) {
            Some(Ordering::Less) => return Err(AbortCode::ValueTooLow),
            None => return Err(AbortCode::InvalidValue),
            _ => {}
        }
    }
    if let Some(high) = high {
        match value.cmp_limit(high) {
            Some(Ordering::Greater) => return Err(AbortCode::ValueTooHigh),
            None => return Err(AbortCode::InvalidValue),
            _ => {}
        }
    }
    Ok(())
}

/// Checks a value against low/high limits of its own type: 0609 0032h below, 0609 0031h above. The
/// derive's check for a Rust integer field with integer limits (one compare each, no [`Value`] in between);
/// [`check_limits`] serves every other type.
///
/// ```
/// use canopen_core::od::{check_range, AbortCode};
/// assert_eq!(check_range(5i16, Some(-1000), Some(1000)), Ok(()));
/// assert_eq!(check_range(1001i16, Some(-1000), Some(1000)), Err(AbortCode::ValueTooHigh));
/// assert_eq!(check_range(-1001i16, Some(-1000), None), Err(AbortCode::ValueTooLow));
/// ```
#[inline(never)]
pub fn check_range<T: PartialOrd>(value: T, low: Option<T>, high: Option<T>) -> Result<(), AbortCode> {
    if low.is_some_and(|l| value < l) {
        return Err(AbortCode::ValueTooLow);
    }
    if high.is_some_and(|h| value > h) {
        return Err(AbortCode::ValueTooHigh);
    }
    Ok(())
}

fn cmp_signed(v: i64, limit: &Value) -> Option<Ordering> {
    match *limit {
        Value::Int(l) => Some(v.cmp(&l)),
        Value::Uint(l) => Some(if v < 0 { Ordering::Less } else { (v as u64).cmp(&l) }),
        Value::Bool(b) => Some(v.cmp(&i64::from(b))),
        _ => None,
    }
}

fn cmp_unsigned(v: u64, limit: &Value) -> Option<Ordering> {
    match *limit {
        Value::Uint(l) => Some(v.cmp(&l)),
        Value::Int(l) => Some(if l < 0 { Ordering::Greater } else { v.cmp(&(l as u64)) }),
        Value::Bool(b) => Some(v.cmp(&u64::from(b))),
        _ => None,
    }
}

macro_rules! native_int {
    ($t:ty, $dt:ident, $cmp:ident, $wide:ty) => {
        impl OdValue for $t {
            const DATA_TYPE: DataType = DataType::$dt;
            const MAX_SIZE: usize = core::mem::size_of::<$t>();
            const MAPPABLE: bool = true;
            #[inline]
            fn size(&self) -> usize {
                Self::MAX_SIZE
            }
            #[inline]
            fn read_bytes(&self, offset: usize, buf: &mut [u8]) -> usize {
                read_fixed(self.to_le_bytes(), offset, buf)
            }
            #[inline]
            fn decode(data: &[u8]) -> Result<Self, AbortCode> {
                check_len(data, Self::MAX_SIZE)?;
                let mut b = [0u8; core::mem::size_of::<$t>()];
                b.copy_from_slice(data);
                Ok(<$t>::from_le_bytes(b))
            }
            fn cmp_limit(&self, limit: &Value) -> Option<Ordering> {
                $cmp(*self as $wide, limit)
            }
        }
    };
}

native_int!(i8, Integer8, cmp_signed, i64);
native_int!(i16, Integer16, cmp_signed, i64);
native_int!(i32, Integer32, cmp_signed, i64);
native_int!(i64, Integer64, cmp_signed, i64);
native_int!(u8, Unsigned8, cmp_unsigned, u64);
native_int!(u16, Unsigned16, cmp_unsigned, u64);
native_int!(u32, Unsigned32, cmp_unsigned, u64);
native_int!(u64, Unsigned64, cmp_unsigned, u64);

/// BOOLEAN (DT-03): one octet on SDO, 00h = false, 01h = true; anything else is refused with 0609 0030h.
impl OdValue for bool {
    const DATA_TYPE: DataType = DataType::Boolean;
    const MAX_SIZE: usize = 1;
    const MAPPABLE: bool = true;
    #[inline]
    fn size(&self) -> usize {
        1
    }
    #[inline]
    fn read_bytes(&self, offset: usize, buf: &mut [u8]) -> usize {
        copy_at(&[u8::from(*self)], offset, buf)
    }
    #[inline]
    fn decode(data: &[u8]) -> Result<Self, AbortCode> {
        check_len(data, 1)?;
        match data[0] {
            0 => Ok(false),
            1 => Ok(true),
            _ => Err(AbortCode::InvalidValue),
        }
    }
    fn cmp_limit(&self, limit: &Value) -> Option<Ordering> {
        cmp_unsigned(u64::from(*self), limit)
    }
}

macro_rules! native_real {
    ($t:ty, $dt:ident, $own:ident, $n:expr) => {
        impl OdValue for $t {
            const DATA_TYPE: DataType = DataType::$dt;
            const MAX_SIZE: usize = $n;
            const MAPPABLE: bool = true;
            #[inline]
            fn size(&self) -> usize {
                $n
            }
            #[inline]
            fn read_bytes(&self, offset: usize, buf: &mut [u8]) -> usize {
                read_fixed(self.to_le_bytes(), offset, buf)
            }
            #[inline]
            fn decode(data: &[u8]) -> Result<Self, AbortCode> {
                check_len(data, $n)?;
                let mut b = [0u8; $n];
                b.copy_from_slice(data);
                Ok(<$t>::from_le_bytes(b))
            }
            fn cmp_limit(&self, limit: &Value) -> Option<Ordering> {
                match *limit {
                    Value::$own(l) => self.partial_cmp(&l),
                    Value::Int(l) => (*self as f64).partial_cmp(&(l as f64)),
                    Value::Uint(l) => (*self as f64).partial_cmp(&(l as f64)),
                    _ => None,
                }
            }
        }
    };
}

native_real!(f32, Real32, Real32, 4);
native_real!(f64, Real64, Real64, 8);

macro_rules! wide_int {
    ($(#[$doc:meta])* $name:ident, $inner:ty, $dt:ident, $bits:expr, signed) => {
        wide_int!(@def $(#[$doc])* $name, $inner, $dt, $bits,
            -(1 << ($bits - 1)), (1 << ($bits - 1)) - 1, cmp_signed, i64);
    };
    ($(#[$doc:meta])* $name:ident, $inner:ty, $dt:ident, $bits:expr, unsigned) => {
        wide_int!(@def $(#[$doc])* $name, $inner, $dt, $bits, 0, (1 << $bits) - 1, cmp_unsigned, u64);
    };
    (@def $(#[$doc:meta])* $name:ident, $inner:ty, $dt:ident, $bits:expr, $min:expr, $max:expr, $cmp:ident, $wide:ty) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
        pub struct $name($inner);

        impl $name {
            /// The smallest value.
            pub const MIN: $name = $name($min);
            /// The largest value.
            pub const MAX: $name = $name($max);
            /// The encoded size in bytes.
            pub const SIZE: usize = $bits / 8;

            /// The value if it fits in the type's range.
            #[allow(unused_comparisons, clippy::int_plus_one)]
            pub const fn new(v: $inner) -> Option<Self> {
                if v >= $min && v <= $max {
                    Some($name(v))
                } else {
                    None
                }
            }

            /// The value as the next wider Rust integer.
            pub const fn get(self) -> $inner {
                self.0
            }
        }

        impl OdValue for $name {
            const DATA_TYPE: DataType = DataType::$dt;
            const MAX_SIZE: usize = $bits / 8;
            const MAPPABLE: bool = true;
            fn size(&self) -> usize {
                Self::SIZE
            }
            fn read_bytes(&self, offset: usize, buf: &mut [u8]) -> usize {
                let b = self.0.to_le_bytes();
                copy_at(&b[..Self::SIZE], offset, buf)
            }
            fn decode(data: &[u8]) -> Result<Self, AbortCode> {
                check_len(data, Self::SIZE)?;
                let mut b = [0u8; core::mem::size_of::<$inner>()];
                b[..Self::SIZE].copy_from_slice(data);
                // Sign- or zero-extend from the top bit of the last octet (DT-02: bits above n are ignored).
                let shift = 8 * core::mem::size_of::<$inner>() - $bits;
                Ok($name((<$inner>::from_le_bytes(b) << shift) >> shift))
            }
            fn cmp_limit(&self, limit: &Value) -> Option<Ordering> {
                $cmp(self.0 as $wide, limit)
            }
        }
    };
}

wide_int!(
    /// INTEGER24 (0010h): −2²³ … 2²³−1, 3 octets LE (DT-06).
    ///
    /// ```
    /// use canopen_core::od::{I24, OdValue};
    /// let v = I24::new(-2).unwrap();
    /// let mut b = [0u8; 3];
    /// v.read_bytes(0, &mut b);
    /// assert_eq!(b, [0xFE, 0xFF, 0xFF]);
    /// assert_eq!(I24::decode(&b), Ok(v));
    /// assert!(I24::new(1 << 23).is_none());
    /// ```
    I24, i32, Integer24, 24, signed
);
wide_int!(
    /// INTEGER40 (0012h): 5 octets LE (DT-06).
    ///
    /// ```
    /// use canopen_core::od::{I40, OdValue};
    /// assert_eq!(I40::decode(&[0, 0, 0, 0, 0x80]).unwrap(), I40::MIN);
    /// ```
    I40, i64, Integer40, 40, signed
);
wide_int!(
    /// INTEGER48 (0013h): 6 octets LE (DT-06).
    ///
    /// ```
    /// use canopen_core::od::{I48, OdValue};
    /// assert_eq!(I48::decode(&[0xFF; 6]).unwrap().get(), -1);
    /// ```
    I48, i64, Integer48, 48, signed
);
wide_int!(
    /// INTEGER56 (0014h): 7 octets LE (DT-06).
    ///
    /// ```
    /// use canopen_core::od::{I56, OdValue};
    /// assert_eq!(I56::MAX.get(), (1 << 55) - 1);
    /// ```
    I56, i64, Integer56, 56, signed
);
wide_int!(
    /// UNSIGNED24 (0016h): 0 … 2²⁴−1, 3 octets LE (DT-05).
    ///
    /// ```
    /// use canopen_core::od::{U24, OdValue};
    /// assert_eq!(U24::decode(&[0x56, 0x34, 0x12]).unwrap().get(), 0x12_3456);
    /// ```
    U24, u32, Unsigned24, 24, unsigned
);
wide_int!(
    /// UNSIGNED40 (0018h): 5 octets LE (DT-05).
    ///
    /// ```
    /// use canopen_core::od::U40;
    /// assert!(U40::new(1 << 40).is_none());
    /// ```
    U40, u64, Unsigned40, 40, unsigned
);
wide_int!(
    /// UNSIGNED48 (0019h): 6 octets LE (DT-05).
    ///
    /// ```
    /// use canopen_core::od::U48;
    /// assert_eq!(U48::MAX.get(), 0xFFFF_FFFF_FFFF);
    /// ```
    U48, u64, Unsigned48, 48, unsigned
);
wide_int!(
    /// UNSIGNED56 (001Ah): 7 octets LE (DT-05).
    ///
    /// ```
    /// use canopen_core::od::U56;
    /// assert_eq!(U56::new(5).unwrap().get(), 5);
    /// ```
    U56, u64, Unsigned56, 56, unsigned
);

macro_rules! time_type {
    ($(#[$doc:meta])* $name:ident, $dt:ident) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
        #[cfg_attr(feature = "defmt", derive(defmt::Format))]
        pub struct $name {
            /// Days (since 1984-01-01 for TIME_OF_DAY).
            pub days: u16,
            /// Milliseconds, 0 … 2²⁸−1 (after midnight for TIME_OF_DAY).
            pub ms: u32,
        }

        impl $name {
            /// The largest millisecond value (28 bits).
            pub const MS_MAX: u32 = (1 << 28) - 1;

            /// A value from days and milliseconds; `None` if `ms` does not fit in 28 bits.
            pub const fn new(days: u16, ms: u32) -> Option<Self> {
                if ms > Self::MS_MAX {
                    None
                } else {
                    Some($name { days, ms })
                }
            }

            /// The 6-octet encoding: ms in bits 0–27 of a LE u32 (bits 28–31 reserved, sent as 0), then days LE.
            pub const fn to_bytes(self) -> [u8; 6] {
                let m = (self.ms & Self::MS_MAX).to_le_bytes();
                let d = self.days.to_le_bytes();
                [m[0], m[1], m[2], m[3], d[0], d[1]]
            }

            /// Decodes the 6-octet encoding, ignoring the 4 reserved bits.
            pub const fn from_bytes(b: [u8; 6]) -> Self {
                $name {
                    ms: u32::from_le_bytes([b[0], b[1], b[2], b[3]]) & Self::MS_MAX,
                    days: u16::from_le_bytes([b[4], b[5]]),
                }
            }

            /// The encoding read as one 48-bit little-endian number (`days << 32 | ms`), as EDS tools show it.
            pub const fn raw(self) -> u64 {
                ((self.days as u64) << 32) | (self.ms & Self::MS_MAX) as u64
            }
        }

        impl OdValue for $name {
            const DATA_TYPE: DataType = DataType::$dt;
            const MAX_SIZE: usize = 6;
            const MAPPABLE: bool = true;
            fn size(&self) -> usize {
                6
            }
            fn read_bytes(&self, offset: usize, buf: &mut [u8]) -> usize {
                copy_at(&self.to_bytes(), offset, buf)
            }
            fn decode(data: &[u8]) -> Result<Self, AbortCode> {
                check_len(data, 6)?;
                let mut b = [0u8; 6];
                b.copy_from_slice(data);
                Ok(Self::from_bytes(b))
            }
            fn cmp_limit(&self, limit: &Value) -> Option<Ordering> {
                cmp_unsigned(self.raw(), limit)
            }
        }
    };
}

time_type!(
    /// TIME_OF_DAY (000Ch, DT-13): milliseconds after midnight and days since 1984-01-01.
    ///
    /// ```
    /// use canopen_core::od::TimeOfDay;
    /// // 2011-02-21 12:00:00.000
    /// let t = TimeOfDay::new(9913, 43_200_000).unwrap();
    /// assert_eq!(t.to_bytes(), [0x00, 0x2E, 0x93, 0x02, 0xB9, 0x26]);
    /// ```
    TimeOfDay,
    TimeOfDay
);
time_type!(
    /// TIME_DIFFERENCE (000Dh, DT-14): a duration in days and milliseconds, same layout as TIME_OF_DAY.
    ///
    /// ```
    /// use canopen_core::od::TimeDifference;
    /// let d = TimeDifference::new(1, 500).unwrap();
    /// assert_eq!(d.to_bytes(), [0xF4, 0x01, 0, 0, 1, 0]);
    /// ```
    TimeDifference,
    TimeDifference
);

#[cfg(test)]
mod tests {
    use super::*;

    fn enc<T: OdValue>(v: &T) -> ([u8; 16], usize) {
        let mut b = [0u8; 16];
        let n = v.read_bytes(0, &mut b);
        (b, n)
    }

    fn bytes<T: OdValue>(v: &T) -> heapless::Vec<u8, 16> {
        let (b, n) = enc(v);
        heapless::Vec::from_slice(&b[..n]).unwrap()
    }

    /// Encodings byte for byte (DT-01, DT-05..DT-07): UNSIGNED16 266 = 0A 01, INTEGER16 −266 = F6 FE, REAL32 6.25 =
    /// 00 00 C8 40, UNSIGNED32 0102 0304h = 04 03 02 01, and the DT-xx examples.
    #[test]
    fn encoding_vectors() {
        assert_eq!(bytes(&266u16)[..], [0x0A, 0x01]); // DT-05
        assert_eq!(bytes(&-266i16)[..], [0xF6, 0xFE]); // DT-06
        assert_eq!(bytes(&6.25f32)[..], [0x00, 0x00, 0xC8, 0x40]); // DT-07
        assert_eq!(bytes(&0x0102_0304u32)[..], [0x04, 0x03, 0x02, 0x01]); // DT-01
        let t = TimeOfDay::new(9913, 43_200_000).unwrap(); // 2011-02-21 12:00:00.000
        assert_eq!(bytes(&t)[..], [0x00, 0x2E, 0x93, 0x02, 0xB9, 0x26]);
        assert_eq!(TimeOfDay::decode(&[0x00, 0x2E, 0x93, 0x02, 0xB9, 0x26]), Ok(t));
        assert_eq!(bytes(&TimeOfDay::default())[..], [0; 6]); // 1984-01-01 00:00:00.000
        let t = TimeOfDay::new(5844, 45_296_789).unwrap(); // 2000-01-01 12:34:56.789
        assert_eq!(bytes(&t)[..], [0x95, 0x2C, 0xB3, 0x02, 0xD4, 0x16]);
        assert_eq!(TimeOfDay::decode(&[0x95, 0x2C, 0xB3, 0x02, 0xD4, 0x16]), Ok(t));
        // Reserved bits 28–31 are ignored on decode (DT-13).
        assert_eq!(TimeDifference::decode(&[0x95, 0x2C, 0xB3, 0xF2, 0xD4, 0x16]).unwrap().ms, 45_296_789);
        assert_eq!(bytes(&6.25f64)[..], 6.25f64.to_le_bytes()); // DT-08
        assert_eq!(bytes(&true)[..], [1]); // DT-03
                                           // UNSIGNED10 example of DT-02 lives in a U16 here: 21Ch -> 1C 02.
        assert_eq!(bytes(&0x21Cu16)[..], [0x1C, 0x02]);
    }

    #[test]
    fn wide_integers_round_trip() {
        for v in [I24::MIN, I24::MAX, I24::new(-266).unwrap(), I24::default()] {
            assert_eq!(I24::decode(&bytes(&v)), Ok(v));
        }
        assert_eq!(bytes(&I24::new(-266).unwrap())[..], [0xF6, 0xFE, 0xFF]);
        for v in [I40::MIN, I40::MAX, I40::new(-5).unwrap()] {
            assert_eq!(I40::decode(&bytes(&v)), Ok(v));
        }
        assert_eq!(I48::decode(&bytes(&I48::MIN)), Ok(I48::MIN));
        assert_eq!(I56::decode(&bytes(&I56::MIN)), Ok(I56::MIN));
        assert_eq!(U24::decode(&bytes(&U24::MAX)), Ok(U24::MAX));
        assert_eq!(U40::decode(&bytes(&U40::MAX)), Ok(U40::MAX));
        assert_eq!(bytes(&U48::MAX)[..], [0xFF; 6]);
        assert_eq!(U56::decode(&[1, 0, 0, 0, 0, 0, 0x80]).unwrap().get(), 0x80_0000_0000_0001);
        assert_eq!(U40::decode(&[0; 4]), Err(AbortCode::LengthTooLow));
        assert_eq!(U40::decode(&[0; 6]), Err(AbortCode::LengthTooHigh));
        assert_eq!(<I56 as OdValue>::MAX_SIZE, 7);
    }

    #[test]
    fn booleans_and_limits() {
        assert_eq!(bool::decode(&[2]), Err(AbortCode::InvalidValue));
        assert_eq!(bool::decode(&[]), Err(AbortCode::LengthTooLow));
        let lo = Value::Real32(-1.5);
        let hi = Value::Real32(2.0);
        assert_eq!(check_limits(&1.0f32, Some(&lo), Some(&hi)), Ok(()));
        assert_eq!(check_limits(&2.5f32, Some(&lo), Some(&hi)), Err(AbortCode::ValueTooHigh));
        assert_eq!(check_limits(&f32::NAN, Some(&lo), Some(&hi)), Err(AbortCode::InvalidValue));
        assert_eq!(check_limits(&u64::MAX, Some(&Value::Int(-1)), Some(&Value::Uint(u64::MAX))), Ok(()));
        assert_eq!(check_limits(&-1i64, Some(&Value::Uint(0)), None), Err(AbortCode::ValueTooLow));
        assert_eq!(check_limits(&I24::MAX, None, Some(&Value::Int(10))), Err(AbortCode::ValueTooHigh));
    }
}
