//! Block-transfer helpers shared by server and client (SDO-37..SDO-51).
//!
//! - [`Crc16`]: the running CRC-16/XMODEM of SDO-49 (poly 1021h, init 0, no reflection, no final XOR). With
//!   the `crc-table` feature (default) a byte at a time from a 256-entry table (512 B of flash, one lookup
//!   per byte; the `crc` crate's digest, used here before, cost about three times as many instructions per
//!   7-byte segment); without it a nibble at a time from a 16-entry table
//!   (32 B, two lookups per byte). Both tables are built at compile time, and the tests check both against
//!   the bit-by-bit definition and the check values "123456789" → 31C3h, "ABCDEFGHIJKLMNOP" → 6080h,
//!   empty → 0. It keeps only the 16-bit register, so a state machine can hold it by value.
//! - [`segment_count`] / [`last_segment_len`]: how a data set of `size` bytes is cut into 7-byte segments
//!   (at least one segment, SDO-51; an empty data set is one segment with n = 7).

/// The CRC register after shifting `bits` zero bits into `n << 8` (poly 1021h, MSB first): the table entry
/// of `n` for a table indexed by the top `bits` bits.
const fn shifted(n: u16, bits: u32) -> u16 {
    let mut r = n << (16 - bits);
    let mut bit = 0;
    while bit < bits {
        r = if r & 0x8000 != 0 { (r << 1) ^ 0x1021 } else { r << 1 };
        bit += 1;
    }
    r
}

/// Byte table: entry `n` is the register after shifting in 8 zero bits from `n << 8`.
#[cfg(any(feature = "crc-table", test))]
static BYTE: [u16; 256] = {
    let mut t = [0u16; 256];
    let mut n = 0;
    while n < 256 {
        t[n] = shifted(n as u16, 8);
        n += 1;
    }
    t
};

/// Nibble table: entry `n` is the register after shifting in 4 zero bits from `n << 12`.
#[cfg(any(not(feature = "crc-table"), test))]
static NIBBLE: [u16; 16] = {
    let mut t = [0u16; 16];
    let mut n = 0;
    while n < 16 {
        t[n] = shifted(n as u16, 4);
        n += 1;
    }
    t
};

/// `crc` updated with `bytes`, a byte per lookup.
#[cfg(any(feature = "crc-table", test))]
fn update_by_byte(mut crc: u16, bytes: &[u8]) -> u16 {
    for &b in bytes {
        crc = (crc << 8) ^ BYTE[usize::from((crc >> 8) as u8 ^ b)];
    }
    crc
}

/// `crc` updated with `bytes`, a nibble per lookup (high nibble first).
#[cfg(any(not(feature = "crc-table"), test))]
fn update_by_nibble(mut crc: u16, bytes: &[u8]) -> u16 {
    for &b in bytes {
        crc = (crc << 4) ^ NIBBLE[usize::from((crc >> 12) as u8 ^ (b >> 4))];
        crc = (crc << 4) ^ NIBBLE[usize::from((crc >> 12) as u8 ^ (b & 0x0F))];
    }
    crc
}

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
    /// assert_eq!(c.get(), 0x6080); // SDO-49: the CRC of "ABCDEFGHIJKLMNOP"
    /// ```
    // Without `#[inline]`, the table choice behind a call kept `update` out of the block segment path: +36
    // instructions per frame in `scripts/bench-node.sh` block_download.
    #[inline]
    pub fn update(&mut self, bytes: &[u8]) {
        #[cfg(feature = "crc-table")]
        {
            self.0 = update_by_byte(self.0, bytes);
        }
        #[cfg(not(feature = "crc-table"))]
        {
            self.0 = update_by_nibble(self.0, bytes);
        }
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
/// assert_eq!(last_segment_len(9), 2); // 9 bytes: the end frame says n = 5 (D5h, SDO-41)
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

    fn bitwise(mut crc: u16, bytes: &[u8]) -> u16 {
        for &b in bytes {
            crc ^= u16::from(b) << 8;
            for _ in 0..8 {
                crc = if crc & 0x8000 != 0 { (crc << 1) ^ 0x1021 } else { crc << 1 };
            }
        }
        crc
    }

    /// The SDO-49 block CRC check values ( "123456789" → 31C3h, "ABCDEFGHIJKLMNOP" → 6080h, empty → 0) from
    /// both tables, whichever one `crc-table` selects for [`Crc16`], and from the bit-by-bit definition.
    #[test]
    fn both_tables_give_the_block_crc_check_values() {
        let vectors: [(&[u8], u16); 3] = [(b"123456789", 0x31C3), (b"ABCDEFGHIJKLMNOP", 0x6080), (b"", 0)];
        for (data, want) in vectors {
            assert_eq!(update_by_byte(0, data), want, "byte table {data:?}");
            assert_eq!(update_by_nibble(0, data), want, "nibble table {data:?}");
            assert_eq!(bitwise(0, data), want, "bitwise {data:?}");
            let mut c = Crc16::new();
            c.update(data);
            assert_eq!(c.get(), want, "Crc16 {data:?}");
        }
        assert_eq!((BYTE.len() * 2, NIBBLE.len() * 2), (512, 32)); // the flash each table costs
    }

    /// Both tables give the bit-by-bit CRC-16/XMODEM for every byte value and running register.
    #[test]
    fn tables_match_bitwise() {
        for start in [0u16, 0x0001, 0x1021, 0x8000, 0xFFFF, 0x31C3] {
            for b in 0..=255u8 {
                assert_eq!(update_by_byte(start, &[b]), bitwise(start, &[b]), "{start:04X} {b:02X}");
                assert_eq!(update_by_nibble(start, &[b]), bitwise(start, &[b]), "{start:04X} {b:02X}");
                let mut c = Crc16(start);
                c.update(&[b]);
                assert_eq!(c.get(), bitwise(start, &[b]), "{start:04X} {b:02X}");
            }
        }
        let data: [u8; 64] = core::array::from_fn(|i| (i * 37 + 11) as u8);
        let mut c = Crc16::new();
        c.update(&data[..13]);
        c.update(&data[13..]);
        assert_eq!(c.get(), bitwise(0, &data));
        assert_eq!(update_by_nibble(update_by_nibble(0, &data[..5]), &data[5..]), bitwise(0, &data));
    }
}
