//! Block-transfer helpers shared by server and client (CHECKLIST SDO-37..SDO-51).
//!
//! - [`Crc16`]: the running CRC-16/XMODEM of SDO-49 (poly 1021h, init 0, no reflection, no final XOR), via the
//!   `crc` crate. It keeps only the 16-bit register, so a state machine can hold it by value.
//! - [`segment_count`] / [`last_segment_len`]: how a data set of `size` bytes is cut into 7-byte segments
//!   (at least one segment, SDO-51; an empty data set is one segment with n = 7).

use crc::{Crc, CRC_16_XMODEM};

static CRC16: Crc<u16> = Crc::<u16>::new(&CRC_16_XMODEM);

/// A running CRC-16/XMODEM (SDO-49).
///
/// ```
/// use canopen_core::sdo::block::Crc16;
/// let mut crc = Crc16::new();
/// crc.update(b"1234");
/// crc.update(b"56789");
/// assert_eq!(crc.get(), 0x31C3);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Crc16(u16);

impl Crc16 {
    /// The initial value 0000h.
    ///
    /// ```
    /// # use canopen_core::sdo::block::Crc16;
    /// assert_eq!(Crc16::new().get(), 0);
    /// ```
    pub const fn new() -> Self {
        Crc16(0)
    }

    /// Feeds bytes.
    ///
    /// ```
    /// # use canopen_core::sdo::block::Crc16;
    /// let mut c = Crc16::new();
    /// c.update(b"ABCDEFGHIJKLMNOP");
    /// assert_eq!(c.get(), 0x6080); // VECTORS 8.2
    /// ```
    pub fn update(&mut self, bytes: &[u8]) {
        if bytes.is_empty() {
            return;
        }
        let mut d = CRC16.digest_with_initial(self.0);
        d.update(bytes);
        self.0 = d.finalize();
    }

    /// The CRC of everything fed so far.
    ///
    /// ```
    /// # use canopen_core::sdo::block::Crc16;
    /// assert_eq!(Crc16::new().get(), 0);
    /// ```
    pub const fn get(self) -> u16 {
        self.0
    }
}

/// Number of 7-byte segments for `size` bytes (at least 1, SDO-51).
///
/// ```
/// use canopen_core::sdo::block::segment_count;
/// assert_eq!(segment_count(0), 1);
/// assert_eq!(segment_count(7), 1);
/// assert_eq!(segment_count(8), 2);
/// ```
pub const fn segment_count(size: u32) -> u32 {
    if size == 0 {
        1
    } else {
        size.div_ceil(7)
    }
}

/// Data bytes in the last segment of `size` bytes (0..=7); the end frame carries `7 − this` as n.
///
/// ```
/// use canopen_core::sdo::block::last_segment_len;
/// assert_eq!(last_segment_len(9), 2); // VECTORS 8.1: n = 5
/// assert_eq!(last_segment_len(14), 7);
/// assert_eq!(last_segment_len(0), 0);
/// ```
pub const fn last_segment_len(size: u32) -> u8 {
    if size == 0 {
        0
    } else {
        ((size - 1) % 7 + 1) as u8
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc_check_value_sdo_49() {
        let mut c = Crc16::new();
        c.update(b"123456789");
        assert_eq!(c.get(), 0x31C3);
        let mut c = Crc16::new();
        for b in b"123456789" {
            c.update(core::slice::from_ref(b));
        }
        assert_eq!(c.get(), 0x31C3);
    }

    #[test]
    fn segments() {
        for size in 0..100u32 {
            let n = segment_count(size);
            let last = u32::from(last_segment_len(size));
            assert_eq!((n - 1) * 7 + last, size);
        }
    }
}
