//! The string types: OCTET_STRING ([`OctetString`], DT-10), VISIBLE_STRING ([`VisibleString`], DT-11) and
//! UNICODE_STRING ([`UnicodeString`], DT-12), each with a fixed capacity and a tracked current length (no
//! heap), and their exact bus encoding.
//!
//! Decoding checks the length first (0607 0012h too long, 0607 0010h for an odd UNICODE_STRING byte count)
//! and the content second (0609 0030h for a VISIBLE_STRING character outside 00h/20h–7Eh). A streamed write
//! (SDO segmented or block download) collects its bytes in a staging buffer and replaces the value only at
//! its end, so an aborted download leaves the old value.

use super::value::{chunk_end, copy_streamed, fits, OdValue};
use super::{AbortCode, DataType, Value};

macro_rules! byte_string {
    ($(#[$doc:meta])* $name:ident, $dt:ident, $check:expr) => {
        $(#[$doc])*
        #[derive(Clone, Copy)]
        pub struct $name<const N: usize> {
            buf: [u8; N],
            len: usize,
            /// The bytes of a streamed write under way ([`OdValue::stream_chunk`]); they become the value only
            /// at [`OdValue::end_stream`], so an aborted download leaves the old value.
            staged: [u8; N],
        }

        impl<const N: usize> PartialEq for $name<N> {
            fn eq(&self, other: &Self) -> bool {
                self.as_bytes() == other.as_bytes()
            }
        }

        impl<const N: usize> Eq for $name<N> {}

        impl<const N: usize> core::hash::Hash for $name<N> {
            fn hash<H: core::hash::Hasher>(&self, state: &mut H) {
                self.as_bytes().hash(state)
            }
        }

        impl<const N: usize> $name<N> {
            /// The empty value.
            pub const fn new() -> Self {
                $name { buf: [0; N], len: 0, staged: [0; N] }
            }

            /// The value holding `bytes`; `None` if longer than `N` or with invalid content.
            pub const fn from_bytes(bytes: &[u8]) -> Option<Self> {
                if bytes.len() > N {
                    return None;
                }
                let mut buf = [0u8; N];
                let mut i = 0;
                while i < bytes.len() {
                    if !$check(bytes[i]) {
                        return None;
                    }
                    buf[i] = bytes[i];
                    i += 1;
                }
                Some($name { buf, len: bytes.len(), staged: [0; N] })
            }

            /// The current content.
            pub fn as_bytes(&self) -> &[u8] {
                &self.buf[..self.len]
            }

            /// The current length in bytes.
            pub const fn len(&self) -> usize {
                self.len
            }

            /// Whether the value is empty.
            pub const fn is_empty(&self) -> bool {
                self.len == 0
            }

            /// The capacity in bytes.
            pub const fn capacity(&self) -> usize {
                N
            }

            /// Replaces the content; refuses (and changes nothing) if too long or invalid.
            pub fn set(&mut self, bytes: &[u8]) -> Result<(), AbortCode> {
                *self = Self::decode(bytes)?;
                Ok(())
            }
        }

        impl<const N: usize> Default for $name<N> {
            fn default() -> Self {
                Self::new()
            }
        }

        impl<const N: usize> core::fmt::Debug for $name<N> {
            fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                f.debug_tuple(stringify!($name)).field(&self.as_bytes()).finish()
            }
        }

        impl<const N: usize> OdValue for $name<N> {
            const DATA_TYPE: DataType = DataType::$dt;
            const MAX_SIZE: usize = N;
            const MAPPABLE: bool = false;
            fn size(&self) -> usize {
                self.len
            }
            fn read_bytes(&self, offset: usize, buf: &mut [u8]) -> usize {
                copy_streamed(self.as_bytes(), offset, buf)
            }
            fn decode(data: &[u8]) -> Result<Self, AbortCode> {
                if data.len() > N {
                    return Err(AbortCode::LengthTooHigh);
                }
                Self::from_bytes(data).ok_or(AbortCode::InvalidValue)
            }
            fn begin_stream(&mut self, size: Option<usize>) -> Result<(), AbortCode> {
                fits(size, N)
            }
            fn stream_chunk(&mut self, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
                let end = chunk_end(offset, data.len(), N)?;
                if !data.iter().all(|&b| $check(b)) {
                    return Err(AbortCode::InvalidValue);
                }
                self.staged[offset..end].copy_from_slice(data);
                Ok(())
            }
            fn end_stream(&self, total: usize) -> Result<Self, AbortCode> {
                let bytes = self.staged.get(..total).ok_or(AbortCode::LengthTooHigh)?;
                let mut v = *self;
                v.buf[..total].copy_from_slice(bytes);
                v.len = total;
                Ok(v)
            }
        }
    };
}

const fn any_byte(_: u8) -> bool {
    true
}

/// VISIBLE_CHAR (DT-11): 00h or 20h–7Eh.
const fn visible_char(b: u8) -> bool {
    b == 0 || (b >= 0x20 && b <= 0x7E)
}

byte_string!(
    /// VISIBLE_STRING (0009h, DT-11) with capacity `N` bytes and a tracked current length. Only 00h and
    /// 20h–7Eh are accepted (0609 0030h otherwise); no terminating 00h is added.
    ///
    /// ```
    /// use canopen_core::od::{AbortCode, OdValue, VisibleString};
    /// const NAME: VisibleString<16> = VisibleString::literal("node");
    /// assert_eq!(NAME.as_str(), "node");
    /// assert_eq!(VisibleString::<4>::decode(b"toolong"), Err(AbortCode::LengthTooHigh));
    /// assert_eq!(VisibleString::<4>::decode(&[0x07]), Err(AbortCode::InvalidValue));
    /// ```
    VisibleString,
    VisibleString,
    visible_char
);
byte_string!(
    /// OCTET_STRING (000Ah, DT-10) with capacity `N` bytes and a tracked current length.
    ///
    /// ```
    /// use canopen_core::od::{OctetString, OdValue};
    /// let s = OctetString::<8>::from_bytes(&[1, 2, 0xFF]).unwrap();
    /// assert_eq!(s.size(), 3);
    /// ```
    OctetString,
    OctetString,
    any_byte
);

impl<const N: usize> VisibleString<N> {
    /// A value from a string literal, usable in `const` items; panics at compile time if `s` is longer
    /// than `N` or holds a character outside 20h–7Eh.
    pub const fn literal(s: &str) -> Self {
        match Self::from_bytes(s.as_bytes()) {
            Some(v) => v,
            None => panic!("VisibleString::literal: too long or not visible ASCII"),
        }
    }

    /// The content as `&str` (always valid: only ASCII is accepted).
    ///
    /// ```
    /// # use canopen_core::od::VisibleString;
    /// assert_eq!(VisibleString::<8>::from_str("ab").unwrap().as_str(), "ab");
    /// ```
    pub fn as_str(&self) -> &str {
        core::str::from_utf8(self.as_bytes()).unwrap_or("")
    }

    /// A value from `s`; `None` if too long or not visible ASCII.
    #[allow(clippy::should_implement_trait)]
    pub const fn from_str(s: &str) -> Option<Self> {
        Self::from_bytes(s.as_bytes())
    }
}

/// UNICODE_STRING (000Bh, DT-12): up to `N` UNSIGNED16 code units (UTF-16, each LE on the bus) with a
/// tracked current length. An odd byte count is refused with 0607 0010h.
///
/// ```
/// use canopen_core::od::{AbortCode, OdValue, UnicodeString};
/// let s = UnicodeString::<4>::from_str("hé").unwrap();
/// let mut b = [0u8; 8];
/// assert_eq!(s.read_bytes(0, &mut b), 4);
/// assert_eq!(&b[..4], &[0x68, 0x00, 0xE9, 0x00]);
/// assert_eq!(UnicodeString::<4>::decode(&[1, 2, 3]), Err(AbortCode::LengthMismatch));
/// ```
#[derive(Clone, Copy)]
pub struct UnicodeString<const N: usize> {
    units: [u16; N],
    len: usize,
    /// The code units of a streamed write under way; they become the value only at
    /// [`OdValue::end_stream`], so an aborted download leaves the old value.
    staged: [u16; N],
}

impl<const N: usize> PartialEq for UnicodeString<N> {
    fn eq(&self, other: &Self) -> bool {
        self.units() == other.units()
    }
}

impl<const N: usize> Eq for UnicodeString<N> {}

impl<const N: usize> core::hash::Hash for UnicodeString<N> {
    fn hash<H: core::hash::Hasher>(&self, state: &mut H) {
        self.units().hash(state)
    }
}

impl<const N: usize> UnicodeString<N> {
    /// The empty value.
    pub const fn new() -> Self {
        UnicodeString { units: [0; N], len: 0, staged: [0; N] }
    }

    /// A value from `s` encoded as UTF-16; `None` if it needs more than `N` code units.
    #[allow(clippy::should_implement_trait)]
    pub fn from_str(s: &str) -> Option<Self> {
        let mut v = Self::new();
        for u in s.encode_utf16() {
            *v.units.get_mut(v.len)? = u;
            v.len += 1;
        }
        Some(v)
    }

    /// The current code units.
    pub fn units(&self) -> &[u16] {
        &self.units[..self.len]
    }

    /// The current length in code units.
    pub const fn len(&self) -> usize {
        self.len
    }

    /// Whether the value is empty.
    pub const fn is_empty(&self) -> bool {
        self.len == 0
    }
}

impl<const N: usize> Default for UnicodeString<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> core::fmt::Debug for UnicodeString<N> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_tuple("UnicodeString").field(&self.units()).finish()
    }
}

impl<const N: usize> OdValue for UnicodeString<N> {
    fn from_value(value: &Value) -> Option<Self> {
        match *value {
            Value::Str(text) => UnicodeString::from_str(text),
            _ => None,
        }
    }
    const DATA_TYPE: DataType = DataType::UnicodeString;
    const MAX_SIZE: usize = 2 * N;
    const MAPPABLE: bool = false;
    fn size(&self) -> usize {
        2 * self.len
    }
    fn read_bytes(&self, offset: usize, buf: &mut [u8]) -> usize {
        let mut n = 0;
        for (i, out) in buf.iter_mut().enumerate() {
            let pos = offset.saturating_add(i);
            let Some(unit) = self.units().get(pos / 2) else { break };
            *out = unit.to_le_bytes()[pos % 2];
            n += 1;
        }
        n
    }
    fn decode(data: &[u8]) -> Result<Self, AbortCode> {
        if data.len() > 2 * N {
            return Err(AbortCode::LengthTooHigh);
        }
        if data.len() % 2 != 0 {
            return Err(AbortCode::LengthMismatch);
        }
        let mut v = Self::new();
        for (unit, pair) in v.units.iter_mut().zip(data.chunks_exact(2)) {
            *unit = u16::from_le_bytes([pair[0], pair[1]]);
        }
        v.len = data.len() / 2;
        Ok(v)
    }
    fn begin_stream(&mut self, size: Option<usize>) -> Result<(), AbortCode> {
        fits(size, 2 * N)?;
        match size {
            Some(s) if s % 2 != 0 => Err(AbortCode::LengthMismatch),
            _ => Ok(()),
        }
    }
    fn stream_chunk(&mut self, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        chunk_end(offset, data.len(), 2 * N)?;
        for (i, &b) in data.iter().enumerate() {
            let pos = offset + i;
            let Some(unit) = self.staged.get_mut(pos / 2) else { return Err(AbortCode::LengthTooHigh) };
            let mut le = unit.to_le_bytes();
            le[pos % 2] = b;
            *unit = u16::from_le_bytes(le);
        }
        Ok(())
    }
    fn end_stream(&self, total: usize) -> Result<Self, AbortCode> {
        if total % 2 != 0 {
            return Err(AbortCode::LengthMismatch);
        }
        let units = self.staged.get(..total / 2).ok_or(AbortCode::LengthTooHigh)?;
        let mut v = *self;
        v.units[..total / 2].copy_from_slice(units);
        v.len = total / 2;
        Ok(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strings() {
        let s = VisibleString::<8>::decode(b"abc").unwrap();
        assert_eq!(s.as_str(), "abc");
        let mut b = [0u8; 2];
        assert_eq!(s.read_bytes(1, &mut b), 2);
        assert_eq!(&b, b"bc");
        assert_eq!(s.read_bytes(3, &mut b), 0);
        assert_eq!(VisibleString::<2>::decode(b"abc"), Err(AbortCode::LengthTooHigh));
        assert_eq!(VisibleString::<8>::decode(&[0x7F]), Err(AbortCode::InvalidValue));
        let o = OctetString::<4>::decode(&[0, 0xFF]).unwrap();
        assert_eq!(o.as_bytes(), &[0, 0xFF]);
        let u = UnicodeString::<3>::decode(&[0x41, 0, 0x42, 0]).unwrap();
        assert_eq!(u.units(), &[0x41, 0x42]);
        let mut b = [0u8; 4];
        assert_eq!(u.read_bytes(1, &mut b), 3);
        assert_eq!(b[..3], [0, 0x42, 0]);
        assert_eq!(UnicodeString::<1>::decode(&[0; 4]), Err(AbortCode::LengthTooHigh));
        assert!(UnicodeString::<1>::from_str("ab").is_none());
    }

    #[test]
    fn streamed_strings() {
        let mut s = VisibleString::<6>::literal("old");
        assert_eq!(s.begin_stream(Some(7)), Err(AbortCode::LengthTooHigh));
        s.begin_stream(Some(5)).unwrap();
        s.stream_chunk(0, b"hel").unwrap();
        s.stream_chunk(3, b"lo").unwrap();
        assert_eq!(s.stream_chunk(5, b"xx"), Err(AbortCode::LengthTooHigh));
        // until the end the old value stays: an abandoned stream changes nothing
        assert_eq!(s.as_str(), "old");
        assert_eq!(s, VisibleString::<6>::literal("old"));
        s = s.end_stream(5).unwrap();
        assert_eq!(s.as_str(), "hello");
        let mut u = UnicodeString::<2>::from_str("z").unwrap();
        u.begin_stream(None).unwrap();
        u.stream_chunk(0, &[0x41]).unwrap();
        u.stream_chunk(1, &[0x00, 0x42, 0x00]).unwrap();
        assert_eq!(u.units(), &[0x7A]);
        assert_eq!(u.end_stream(3), Err(AbortCode::LengthMismatch));
        assert_eq!(u.end_stream(6), Err(AbortCode::LengthTooHigh));
        u = u.end_stream(4).unwrap();
        assert_eq!(u.units(), &[0x41, 0x42]);
    }
}
