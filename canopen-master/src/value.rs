//! Typed SDO values: how a Rust type is encoded in an object (little-endian, CiA 301 §7.1).

use crate::Error;

/// A type [`Master::read`](crate::Master::read) and [`Master::write`](crate::Master::write) move: the
/// CiA 301 basic types (BOOLEAN, INTEGER8..64, UNSIGNED8..64, REAL32/64, VISIBLE_STRING as [`String`],
/// OCTET_STRING/DOMAIN as `Vec<u8>`).
///
/// ```
/// use canopen_master::SdoValue;
/// assert_eq!((-2i16).encode(), vec![0xFE, 0xFF]);
/// assert_eq!(u32::decode(&[0x91, 0x01, 0x0F, 0x00]).unwrap(), 0x000F_0191);
/// assert!(u32::decode(&[1, 2]).is_err()); // a 2-byte object is no UNSIGNED32
/// assert_eq!(String::decode(b"io module").unwrap(), "io module");
/// ```
pub trait SdoValue: Sized {
    /// The encoded size in bytes, `None` for a variable size (strings, byte vectors).
    const SIZE: Option<usize>;
    /// Decodes the bytes an upload returned.
    fn decode(bytes: &[u8]) -> Result<Self, Error>;
    /// The bytes a download sends.
    fn encode(&self) -> Vec<u8>;
}

macro_rules! numeric {
    ($($t:ty),*) => {$(
        impl SdoValue for $t {
            const SIZE: Option<usize> = Some(core::mem::size_of::<$t>());
            fn decode(bytes: &[u8]) -> Result<Self, Error> {
                let arr = bytes.try_into().map_err(|_| Error::TypeMismatch {
                    expected: core::mem::size_of::<$t>(),
                    got: bytes.len(),
                })?;
                Ok(<$t>::from_le_bytes(arr))
            }
            fn encode(&self) -> Vec<u8> {
                self.to_le_bytes().to_vec()
            }
        }
    )*};
}

numeric!(u8, u16, u32, u64, i8, i16, i32, i64, f32, f64);

/// BOOLEAN: one byte, 0 = false, anything else true.
///
/// ```
/// use canopen_master::SdoValue;
/// assert_eq!(true.encode(), vec![1]);
/// assert!(bool::decode(&[2]).unwrap());
/// ```
impl SdoValue for bool {
    const SIZE: Option<usize> = Some(1);
    fn decode(bytes: &[u8]) -> Result<Self, Error> {
        u8::decode(bytes).map(|b| b != 0)
    }
    fn encode(&self) -> Vec<u8> {
        vec![u8::from(*self)]
    }
}

/// VISIBLE_STRING (or UNICODE_STRING's UTF-8 reading): any length; invalid UTF-8 is replaced (U+FFFD),
/// trailing NULs a server pads with are dropped.
///
/// ```
/// use canopen_master::SdoValue;
/// assert_eq!(String::decode(b"abc\0\0").unwrap(), "abc");
/// assert_eq!("abc".to_string().encode(), b"abc".to_vec());
/// ```
impl SdoValue for String {
    const SIZE: Option<usize> = None;
    fn decode(bytes: &[u8]) -> Result<Self, Error> {
        let end = bytes.iter().rposition(|&b| b != 0).map_or(0, |i| i + 1);
        Ok(String::from_utf8_lossy(&bytes[..end]).into_owned())
    }
    fn encode(&self) -> Vec<u8> {
        self.as_bytes().to_vec()
    }
}

/// OCTET_STRING or DOMAIN: the bytes as they are, any length.
///
/// ```
/// use canopen_master::SdoValue;
/// assert_eq!(Vec::<u8>::decode(&[0, 1]).unwrap(), vec![0, 1]);
/// ```
impl SdoValue for Vec<u8> {
    const SIZE: Option<usize> = None;
    fn decode(bytes: &[u8]) -> Result<Self, Error> {
        Ok(bytes.to_vec())
    }
    fn encode(&self) -> Vec<u8> {
        self.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_round_trip_little_endian() {
        assert_eq!(i64::decode(&(-5i64).encode()).unwrap(), -5);
        assert_eq!(f32::decode(&1.5f32.encode()).unwrap(), 1.5);
        assert_eq!(0x1234u16.encode(), vec![0x34, 0x12]);
        assert!(matches!(u16::decode(&[1, 2, 3]), Err(Error::TypeMismatch { expected: 2, got: 3 })));
    }
}
