//! PDO mapping entry (PDO-31, PDO-34): an UNSIGNED32 in 1600h–17FFh / 1A00h–1BFFh sub 01h–40h,
//! bits 31–16 index, bits 15–8 sub-index, bits 7–0 length in bits; on the bus (SDO) little-endian.

use super::WireError;

/// One mapping entry.
///
/// ```
/// use canopen_core::wire::pdo_mapping::MappingEntry;
/// // 6040 0010h: 6040h:00, 16 bit.
/// let e = MappingEntry::from_raw(0x6040_0010);
/// assert_eq!((e.index, e.sub, e.bits), (0x6040, 0, 16));
/// assert_eq!(e.emit(), [0x10, 0x00, 0x40, 0x60]);
/// assert_eq!(MappingEntry::parse(&[0x10, 0x00, 0x40, 0x60]), Ok(e));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct MappingEntry {
    /// Index of the mapped object (or a data-type index 0001h–001Bh for a dummy entry).
    pub index: u16,
    /// Sub-index of the mapped object.
    pub sub: u8,
    /// Length in bits.
    pub bits: u8,
}

impl MappingEntry {
    /// Decodes the UNSIGNED32 value.
    pub const fn from_raw(raw: u32) -> Self {
        MappingEntry { index: (raw >> 16) as u16, sub: (raw >> 8) as u8, bits: raw as u8 }
    }

    /// Encodes as the UNSIGNED32 value.
    ///
    /// ```
    /// # use canopen_core::wire::pdo_mapping::MappingEntry;
    /// assert_eq!(MappingEntry { index: 0x2003, sub: 3, bits: 16 }.raw(), 0x2003_0310); // on the bus 10 03 03 20
    /// ```
    pub const fn raw(self) -> u32 {
        ((self.index as u32) << 16) | ((self.sub as u32) << 8) | self.bits as u32
    }

    /// Parses the 4 bytes of an SDO download (exactly 4, CAN-07).
    pub fn parse(data: &[u8]) -> Result<Self, WireError> {
        let b: [u8; 4] = data.try_into().map_err(|_| WireError::Length)?;
        Ok(Self::from_raw(u32::from_le_bytes(b)))
    }

    /// The 4 bytes on the bus.
    pub const fn emit(self) -> [u8; 4] {
        self.raw().to_le_bytes()
    }

    /// Whether the entry is a dummy entry (PDO-34): a data-type index 0001h–0007h, 0010h, 0012h–0016h or
    /// 0018h–001Bh with sub-index 0, usable in RPDOs to skip received bits.
    ///
    /// ```
    /// # use canopen_core::wire::pdo_mapping::MappingEntry;
    /// assert!(MappingEntry::from_raw(0x0005_0008).is_dummy());
    /// assert!(!MappingEntry::from_raw(0x0008_0020).is_dummy()); // REAL32 is not a dummy type
    /// ```
    pub const fn is_dummy(self) -> bool {
        self.dummy_bits().is_some()
    }

    /// The size in bits of the dummy data type (`None` if not a dummy entry).
    ///
    /// ```
    /// # use canopen_core::wire::pdo_mapping::MappingEntry;
    /// assert_eq!(MappingEntry::from_raw(0x0007_0020).dummy_bits(), Some(32));
    /// assert_eq!(MappingEntry::from_raw(0x0001_0001).dummy_bits(), Some(1));
    /// ```
    pub const fn dummy_bits(self) -> Option<u8> {
        let i = self.index as usize;
        if self.sub != 0 || i >= DUMMY_BITS.len() {
            return None;
        }
        match DUMMY_BITS[i] {
            0 => None,
            bits => Some(bits),
        }
    }
}

/// The size in bits of each static data type 0000h–001Bh that a dummy entry may name (PDO-34; CiA 301
/// table 44), 0 for the others (0000h, the REAL, string, DOMAIN and TIME types, 0011h REAL64, 0017h): one
/// table where a match per type was twice the code.
const DUMMY_BITS: [u8; 0x1C] = [
    0, 1, 8, 16, 32, 8, 16, 32, // 00h; 01h BOOLEAN (one bit in a PDO); INTEGER8/16/32; UNSIGNED8/16/32
    0, 0, 0, 0, 0, 0, 0, 0, // 08h-0Fh: REAL32, strings, DOMAIN, TIME types: not dummies
    24, 0, 40, 48, 56, 64, 24, 0, // 10h INTEGER24, 11h REAL64, INTEGER40/48/56/64, 16h UNSIGNED24, 17h
    40, 48, 56, 64, // 18h-1Bh UNSIGNED40/48/56/64
];

#[cfg(test)]
mod tests {
    use super::*;

    /// Mapping entries 6040 0010h, 607A 0020h, 6041 0010h, 6064 0020h, 2000 0108h, 2003 0310h, 2003 0108h
    /// (a drive's and a tutorial's PDO configurations).
    #[test]
    fn mapping_entry_vectors() {
        let cases: [(u32, [u8; 4]); 7] = [
            (0x6040_0010, [0x10, 0x00, 0x40, 0x60]),
            (0x607A_0020, [0x20, 0x00, 0x7A, 0x60]),
            (0x6041_0010, [0x10, 0x00, 0x41, 0x60]),
            (0x6064_0020, [0x20, 0x00, 0x64, 0x60]),
            (0x2000_0108, [0x08, 0x01, 0x00, 0x20]),
            (0x2003_0310, [0x10, 0x03, 0x03, 0x20]),
            (0x2003_0108, [0x08, 0x01, 0x03, 0x20]),
        ];
        for (raw, bytes) in cases {
            assert_eq!(MappingEntry::from_raw(raw).emit(), bytes);
            assert_eq!(MappingEntry::parse(&bytes).map(MappingEntry::raw), Ok(raw));
        }
        assert_eq!(MappingEntry::parse(&[1, 2, 3]), Err(WireError::Length));
        assert!(!MappingEntry::from_raw(0x0005_0108).is_dummy());
        assert_eq!(MappingEntry::from_raw(0x0008_0020).dummy_bits(), None);
    }

    /// PDO-34: the dummy data types and their sizes, type by type as CiA 301 lists them, against the table;
    /// sub-index 0 only.
    #[test]
    fn dummy_types() {
        for index in 0u16..=0x40 {
            let expect = match index {
                0x0001 => Some(1),
                0x0002 | 0x0005 => Some(8),
                0x0003 | 0x0006 => Some(16),
                0x0010 | 0x0016 => Some(24),
                0x0004 | 0x0007 => Some(32),
                0x0012 | 0x0018 => Some(40),
                0x0013 | 0x0019 => Some(48),
                0x0014 | 0x001A => Some(56),
                0x0015 | 0x001B => Some(64),
                _ => None,
            };
            let e = MappingEntry { index, sub: 0, bits: 8 };
            assert_eq!((e.dummy_bits(), e.is_dummy()), (expect, expect.is_some()), "{index:04X}h");
            assert_eq!(MappingEntry { sub: 1, ..e }.dummy_bits(), None, "{index:04X}h sub 1");
        }
        assert_eq!(MappingEntry { index: 0x1005, sub: 0, bits: 8 }.dummy_bits(), None);
    }
}
