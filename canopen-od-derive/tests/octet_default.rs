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
