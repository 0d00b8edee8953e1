//! The dictionary reached by offset (`#[od(compact, zerocopy)]`, issue 41): PDO handles that carry the value's
//! byte offset (PDO-11/PDO-12: a mapped object moves its bytes each PDO; OD-08/OD-09: a read-only object is
//! not written, 0601 0002h), limits and hooks still applied through the row (OD-11), defaults restored from
//! the tables, zero defaults included (NMT-04), and every value in the little-endian encoding (ENC-01).

use canopen_core::od::{AbortCode, ObjectDictionary, PdoDir};
use canopen_od_derive::ObjectDictionary;

#[derive(ObjectDictionary, zerocopy::IntoBytes, zerocopy::FromBytes, zerocopy::Immutable)]
#[od(compact, zerocopy)]
#[repr(C)]
struct Drive {
    #[od(index = 0x607A, access = "rww", pdo = "both", default = -5)]
    target: i32,
    #[od(index = 0x6064, access = "ro", pdo = "tpdo", default = 0x0102_0304)]
    actual: i32,
    #[od(index = 0x6081, access = "rww", pdo = "both", max = 1000)]
    speed: u32,
    #[od(index = 0x2000, sub = 1..=2, access = "rww", pdo = "both", default = 0x1122)]
    pair: [u16; 2],
    #[od(index = 0x6040, access = "rww", pdo = "rpdo", on_write = "controlword_written")]
    controlword: u16,
    #[od(index = 0x6060, access = "rww", pdo = "both")]
    mode: i8,
    #[od(index = 0x2001, access = "rw")]
    writes: u8,
}

impl Drive {
    fn controlword_written(&mut self, _sub: u8) {
        self.writes += 1;
    }
}

fn drive() -> Drive {
    let mut d = <Drive as zerocopy::FromZeros>::new_zeroed();
    d.restore_defaults();
    d
}

#[test]
fn defaults_come_from_the_tables_zero_ones_included() {
    let mut d = drive();
    assert_eq!((d.target, d.actual, d.speed, d.pair, d.controlword, d.mode), (-5, 0x0102_0304, 0, [0x1122; 2], 0, 0));
    d.speed = 9;
    d.mode = 3;
    d.restore_defaults();
    assert_eq!((d.speed, d.mode), (0, 0), "a zero default has no bytes in DEFAULTS but is restored");
}

#[test]
fn a_pdo_handle_moves_the_value_little_endian() {
    let mut d = drive();
    let h = d.pdo_resolve(0x607A, 0, PdoDir::Rpdo).unwrap();
    assert_eq!(h.size, 4);
    d.pdo_write(&h, &[0x78, 0x56, 0x34, 0x12]).unwrap();
    assert_eq!(d.target, 0x1234_5678);
    let t = d.pdo_resolve(0x607A, 0, PdoDir::Tpdo).unwrap();
    let mut buf = [0u8; 4];
    assert_eq!(d.pdo_read(&t, &mut buf), Ok(4));
    assert_eq!(buf, [0x78, 0x56, 0x34, 0x12]);
    // An ARRAY element: its own offset.
    let e = d.pdo_resolve(0x2000, 2, PdoDir::Rpdo).unwrap();
    d.pdo_write(&e, &[0xCD, 0xAB]).unwrap();
    assert_eq!(d.pair, [0x1122, 0xABCD]);
    let m = d.pdo_resolve(0x6060, 0, PdoDir::Rpdo).unwrap();
    d.pdo_write(&m, &[0xFE]).unwrap();
    assert_eq!(d.mode, -2);
    // A wrong length is the SDO length answer, and changes nothing.
    assert_eq!(d.pdo_write(&h, &[1, 2]), Err(AbortCode::LengthTooLow));
    assert_eq!(d.target, 0x1234_5678);
}

#[test]
fn a_read_only_entry_is_not_written_through_its_handle() {
    let mut d = drive();
    let h = d.pdo_resolve(0x6064, 0, PdoDir::Tpdo).unwrap();
    assert_eq!(d.pdo_write(&h, &[0, 0, 0, 0]), Err(AbortCode::WriteOfReadOnly));
    assert_eq!(d.actual, 0x0102_0304);
    let mut buf = [0u8; 4];
    assert_eq!(d.pdo_read(&h, &mut buf), Ok(4));
    assert_eq!(buf, [4, 3, 2, 1]);
    assert_eq!(d.pdo_resolve(0x6064, 0, PdoDir::Rpdo).err(), Some(AbortCode::NotMappable));
}

#[test]
fn limits_and_hooks_still_apply_to_mapped_entries() {
    let mut d = drive();
    let s = d.pdo_resolve(0x6081, 0, PdoDir::Rpdo).unwrap();
    assert_eq!(d.pdo_write(&s, &1001u32.to_le_bytes()), Err(AbortCode::ValueTooHigh));
    assert_eq!(d.speed, 0);
    d.pdo_write(&s, &1000u32.to_le_bytes()).unwrap();
    assert_eq!(d.speed, 1000);
    let c = d.pdo_resolve(0x6040, 0, PdoDir::Rpdo).unwrap();
    d.pdo_write(&c, &[0x0F, 0x00]).unwrap();
    assert_eq!((d.controlword, d.writes), (0x000F, 1), "on_write ran");
    // And over SDO the same.
    assert_eq!(d.write(0x6081, 0, &2000u32.to_le_bytes()), Err(AbortCode::ValueTooHigh));
    d.write(0x6040, 0, &[6, 0]).unwrap();
    assert_eq!((d.controlword, d.writes), (6, 2));
}

#[test]
fn sdo_reads_of_every_size_and_a_part_of_one() {
    let mut d = drive();
    d.mode = -1;
    let mut buf = [0u8; 8];
    assert_eq!(d.read(0x6060, 0, 0, &mut buf), Ok(1));
    assert_eq!(buf[0], 0xFF);
    assert_eq!(d.read(0x2000, 1, 0, &mut buf), Ok(2));
    assert_eq!(&buf[..2], &[0x22, 0x11]);
    assert_eq!(d.read(0x6064, 0, 0, &mut buf), Ok(4));
    assert_eq!(&buf[..4], &[4, 3, 2, 1]);
    // From an offset into the value (a segment), and into a short buffer.
    assert_eq!(d.read(0x6064, 0, 1, &mut buf), Ok(3));
    assert_eq!(&buf[..3], &[3, 2, 1]);
    let mut short = [0u8; 2];
    assert_eq!(d.read(0x6064, 0, 0, &mut short), Ok(2));
    assert_eq!(short, [4, 3]);
}

/// Limits of every width and sign through the one order key of `od::data::limits` (OD-11): 0609 0032h
/// below, 0609 0031h above, the limits themselves accepted, a NaN 0609 0030h where there are limits and
/// stored where there are none (a hook alone), −0.0 equal to a low limit of 0.0.
#[derive(ObjectDictionary, zerocopy::IntoBytes, zerocopy::FromBytes, zerocopy::Immutable)]
#[od(compact, zerocopy)]
#[repr(C)]
struct Limited {
    #[od(index = 0x2000, min = -9000000000, max = 5)]
    wide: i64,
    #[od(index = 0x2001, min = 0.0, max = 2.5)]
    real: f64,
    #[od(index = 0x2002, min = 10, max = 4000000000)]
    count: u32,
    #[od(index = 0x2003, min = -1.5, max = -0.25)]
    small: f32,
    #[od(index = 0x2004, check = "any_real")]
    hooked: f32,
    #[od(index = 0x2005, min = -100, max = -2)]
    offset: i16,
    #[od(index = 0x2006, min = -128)]
    tiny: i8,
    #[od(index = 0x2007, max = 254)]
    byte: u8,
}

impl Limited {
    fn any_real(&self, _sub: u8, _value: &f32) -> Result<(), AbortCode> {
        Ok(())
    }
}

#[test]
fn limits_compare_in_each_type() {
    let mut d = <Limited as zerocopy::FromZeros>::new_zeroed();
    let w = |d: &mut Limited, index: u16, bytes: &[u8]| d.write(index, 0, bytes);
    assert_eq!(w(&mut d, 0x2000, &(-9_000_000_001i64).to_le_bytes()), Err(AbortCode::ValueTooLow));
    assert_eq!(w(&mut d, 0x2000, &(-9_000_000_000i64).to_le_bytes()), Ok(()));
    assert_eq!(w(&mut d, 0x2000, &6i64.to_le_bytes()), Err(AbortCode::ValueTooHigh));
    assert_eq!(d.wide, -9_000_000_000);
    assert_eq!(w(&mut d, 0x2001, &(-0.0f64).to_le_bytes()), Ok(()));
    assert_eq!(w(&mut d, 0x2001, &(-1e-300f64).to_le_bytes()), Err(AbortCode::ValueTooLow));
    assert_eq!(w(&mut d, 0x2001, &2.5000001f64.to_le_bytes()), Err(AbortCode::ValueTooHigh));
    assert_eq!(w(&mut d, 0x2001, &f64::NAN.to_le_bytes()), Err(AbortCode::InvalidValue));
    assert_eq!(w(&mut d, 0x2001, &f64::INFINITY.to_le_bytes()), Err(AbortCode::ValueTooHigh));
    assert_eq!(w(&mut d, 0x2002, &9u32.to_le_bytes()), Err(AbortCode::ValueTooLow));
    assert_eq!(w(&mut d, 0x2002, &4_000_000_001u32.to_le_bytes()), Err(AbortCode::ValueTooHigh));
    assert_eq!(w(&mut d, 0x2002, &4_000_000_000u32.to_le_bytes()), Ok(()));
    assert_eq!(w(&mut d, 0x2003, &(-2.0f32).to_le_bytes()), Err(AbortCode::ValueTooLow));
    assert_eq!(w(&mut d, 0x2003, &(-0.1f32).to_le_bytes()), Err(AbortCode::ValueTooHigh));
    assert_eq!(w(&mut d, 0x2003, &(-0.25f32).to_le_bytes()), Ok(()));
    assert_eq!(w(&mut d, 0x2003, &f32::NEG_INFINITY.to_le_bytes()), Err(AbortCode::ValueTooLow));
    assert_eq!(w(&mut d, 0x2004, &f32::NAN.to_le_bytes()), Ok(()));
    assert!(d.hooked.is_nan());
    assert_eq!(w(&mut d, 0x2004, &[0, 0]), Err(AbortCode::LengthTooLow));
    assert_eq!(w(&mut d, 0x2005, &(-101i16).to_le_bytes()), Err(AbortCode::ValueTooLow));
    assert_eq!(w(&mut d, 0x2005, &(-1i16).to_le_bytes()), Err(AbortCode::ValueTooHigh));
    assert_eq!(w(&mut d, 0x2005, &(-2i16).to_le_bytes()), Ok(()));
    assert_eq!(w(&mut d, 0x2006, &[0x80]), Ok(()));
    assert_eq!(w(&mut d, 0x2007, &[255]), Err(AbortCode::ValueTooHigh));
    assert_eq!(w(&mut d, 0x2007, &[254, 0]), Err(AbortCode::LengthTooHigh));
    assert_eq!(
        (d.real.to_bits(), d.count, d.small, d.offset, d.tiny),
        ((-0.0f64).to_bits(), 4_000_000_000, -0.25, -2, -128)
    );
}

/// Every size class of an offset PDO handle (1, 2, 4, 8 bytes), and values beyond the 4 KiB an offset
/// slot reaches, which keep a row slot and move the same (PDO-11/PDO-12).
#[derive(ObjectDictionary, zerocopy::IntoBytes, zerocopy::FromBytes, zerocopy::Immutable)]
#[od(compact, zerocopy)]
#[repr(C)]
struct Wide {
    #[od(index = 0x2000, pdo = "both")]
    big: u64,
    #[od(index = 0x2001, pdo = "both")]
    word: u32,
    #[od(index = 0x2002, pdo = "both")]
    half: i16,
    #[od(index = 0x2003, pdo = "both")]
    byte: u8,
    pad: u8,
    #[od(index = 0x2004, sub = 1..=254, access = "ro")]
    bulk: [u64; 254],
    #[od(index = 0x2008, sub = 1..=254, access = "ro")]
    more: [u64; 254],
    #[od(index = 0x2009, sub = 1..=4, access = "ro")]
    last: [u64; 4],
    #[od(index = 0x2005, pdo = "both")]
    far: u64,
    #[od(index = 0x2006, access = "ro", pdo = "tpdo", default = 0x0A0B)]
    far_ro: u16,
    #[od(index = 0x2007, pdo = "both")]
    far_byte: u8,
    tail: [u8; 5],
}

#[test]
fn every_size_and_offsets_past_4_kib_move_through_handles() {
    let mut d = <Wide as zerocopy::FromZeros>::new_zeroed();
    d.restore_defaults();
    let cases: [(u16, &[u8]); 6] = [
        (0x2000, &[1, 2, 3, 4, 5, 6, 7, 8]),
        (0x2001, &[9, 10, 11, 12]),
        (0x2002, &[0xFE, 0xFF]),
        (0x2003, &[0x7F]),
        (0x2005, &[8, 7, 6, 5, 4, 3, 2, 1]),
        (0x2007, &[0x33]),
    ];
    for (index, bytes) in cases {
        let rx = d.pdo_resolve(index, 0, PdoDir::Rpdo).unwrap();
        assert_eq!(usize::from(rx.size), bytes.len());
        assert_eq!(d.pdo_write(&rx, bytes), Ok(()), "{index:04X}h");
        let tx = d.pdo_resolve(index, 0, PdoDir::Tpdo).unwrap();
        let mut buf = [0u8; 8];
        assert_eq!(d.pdo_read(&tx, &mut buf), Ok(bytes.len()), "{index:04X}h");
        assert_eq!(&buf[..bytes.len()], bytes, "{index:04X}h");
        // One byte short: the length's answer, nothing stored.
        assert_eq!(d.pdo_write(&rx, &bytes[1..]), Err(AbortCode::LengthTooLow), "{index:04X}h");
    }
    assert_eq!((d.big, d.word, d.half, d.byte), (0x0807_0605_0403_0201, 0x0C0B_0A09, -2, 0x7F));
    assert_eq!((d.far, d.far_byte), (0x0102_0304_0506_0708, 0x33));
    assert!(core::mem::offset_of!(Wide, far) > 4096, "far lies beyond what an offset slot reaches");
    // A read-only value past 4 KiB: read through its handle, refused for a write.
    let ro = d.pdo_resolve(0x2006, 0, PdoDir::Tpdo).unwrap();
    let mut buf = [0u8; 2];
    assert_eq!(d.pdo_read(&ro, &mut buf), Ok(2));
    assert_eq!(buf, [0x0B, 0x0A]);
    assert_eq!(d.pdo_write(&ro, &[0, 0]), Err(AbortCode::WriteOfReadOnly));
    // A buffer too short for the value reads nothing past it.
    let big = d.pdo_resolve(0x2000, 0, PdoDir::Tpdo).unwrap();
    assert!(d.pdo_read(&big, &mut [0u8; 4]).is_err());
}
