//! Attributes eds-to-rust needs to carry real EDS files: a byte string default of an OCTET_STRING, and
//! the access of sub-index 00h of an ARRAY or RECORD.
//!
//! An OCTET_STRING default given as a byte string (`default = b"\xAB\xCD"`, bytes that are no UTF-8, as
//! python canopen's datatypes.eds has `DefaultValue=ABCD` for its 200Ah): the field restores those bytes,
//! SDO reads them, and the EDS writes them as hex pairs (CiA 306), as eds-to-rust's round trip needs.

use canopen_core::od::{ObjectDictionary, OctetString, OdDescribe, VisibleString};
use canopen_od_derive::ObjectDictionary;

#[derive(ObjectDictionary, Default)]
struct App {
    #[od(index = 0x200A, name = "OCTET_STRING", default = b"\xAB\xCD")]
    raw: OctetString<4>,
    #[od(index = 0x200B, name = "Text", default = b"ok")]
    text: VisibleString<4>,
    #[od(index = 0x200C, name = "Octets as text", default = "AB")]
    octets: OctetString<4>,
}

#[test]
fn a_byte_string_default_is_the_octet_strings_bytes() {
    let mut app = App::default();
    app.restore_defaults();
    let mut b = [0u8; 4];
    assert_eq!(app.read(0x200A, 0, 0, &mut b), Ok(2));
    assert_eq!(b[..2], [0xAB, 0xCD]);
    assert_eq!(app.read(0x200B, 0, 0, &mut b), Ok(2));
    assert_eq!(b[..2], *b"ok");
    assert_eq!(app.read(0x200C, 0, 0, &mut b), Ok(2));
    assert_eq!(b[..2], *b"AB");
    let mut eds = String::new();
    for o in (0..app.object_count()).filter_map(|n| app.object(n)) {
        canopen_core::od::eds::write_object(&mut eds, &app, &o).unwrap();
    }
    assert!(eds.contains("[200A]\nParameterName=OCTET_STRING\n"), "{eds}");
    assert!(eds.contains("DefaultValue=ABCD\n"), "{eds}");
    assert!(eds.contains("DefaultValue=ok\n"), "{eds}");
    assert!(eds.contains("DefaultValue=4142\n"), "{eds}");
}

#[derive(ObjectDictionary, Default)]
struct Counts {
    #[od(index = 0x2100, count_access = "ro")]
    gains: [u16; 2],
    #[od(index = 0x2101, sub = 1, record = "Limits", count_access = "ro")]
    low: u8,
    #[od(index = 0x2101, sub = 2)]
    high: u8,
    #[od(index = 0x2102)]
    consts: [u8; 1],
}

/// `count_access = "ro"`: sub-index 00h of an ARRAY or a RECORD is ro as an EDS may say (CiA 306 has ro for
/// a `CompactSubObj` array), const without it; read the same, written by nobody (0601 0002h).
#[test]
fn count_access_sets_sub_index_0s_access() {
    use canopen_core::od::{AbortCode, Access};
    let mut od = Counts::default();
    assert_eq!(od.entry(0x2100, 0).unwrap().access, Access::Ro);
    assert_eq!(od.entry(0x2101, 0).unwrap().access, Access::Ro);
    assert_eq!(od.entry(0x2102, 0).unwrap().access, Access::Const);
    let mut b = [0u8; 1];
    assert_eq!(od.read(0x2101, 0, 0, &mut b), Ok(1));
    assert_eq!(b, [2]);
    assert_eq!(od.write(0x2100, 0, &[1]), Err(AbortCode::WriteOfReadOnly));
}
