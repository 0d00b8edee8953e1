//! The parameter record's own CRC-32 (`storage::Crc32`, bitwise, about 40 bytes of code) is CRC-32/ISO-HDLC:
//! it agrees with the `crc` crate's for any bytes, hashed whole or in any split (the record is hashed in
//! pieces: header fields, then payload chunks).

use canopen_core::storage::Crc32;
use proptest::prelude::*;

const REFERENCE: crc::Crc<u32> = crc::Crc::<u32>::new(&crc::CRC_32_ISO_HDLC);

proptest! {
    #[test]
    fn crc32_agrees_with_the_crc_crate(bytes in proptest::collection::vec(any::<u8>(), 0..300), split in any::<prop::sample::Index>()) {
        prop_assert_eq!(Crc32::checksum(&bytes), REFERENCE.checksum(&bytes));
        let (a, b) = bytes.split_at(split.index(bytes.len() + 1));
        let mut c = Crc32::new();
        c.update(a);
        c.update(b);
        prop_assert_eq!(c.finish(), REFERENCE.checksum(&bytes));
    }
}
