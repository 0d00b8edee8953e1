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

/// A capacity given by a constant, not a literal: checked at compile time (tests/ui/not_mappable_const.rs).
const TAG_LEN: usize = 8;

#[derive(ObjectDictionary, Default)]
struct Mapped {
    #[od(index = 0x2009, name = "VISIBLE_STRING", pdo = "both")]
    text: VisibleString<4>,
    #[od(index = 0x200A, name = "Tag", access = "ro", pdo = "tpdo")]
    tag: OctetString<TAG_LEN>,
    #[od(index = 0x200B, name = "UNICODE_STRING", pdo = "rpdo")]
    units: canopen_core::od::UnicodeString<4>,
    #[od(index = 0x200F, name = "DOMAIN", domain, pdo = "both", eds_default = "@ABCD")]
    blob: canopen_core::od::DomainBuf<16>,
    #[od(index = 0x2010, name = "Unmapped")]
    unmapped: VisibleString<4>,
}

/// Strings and a DOMAIN marked PDO-mappable (PDO-33; datatypes.eds 2009h-200Bh, 200Fh): the EDS says
/// `PDOMapping=1`; a string's handle is its whole capacity (4 bytes; 8 for `UnicodeString<4>`), a DOMAIN's
/// its size when resolved (1..=8 bytes); the direction and access still decide (0604 0041h), and so does
/// a string without `pdo` or a DOMAIN that is empty or larger than a PDO. A TPDO reads the current content
/// (the rest of the mapped bytes stays as it was: the core zeroes them), an RPDO writes all mapped bytes.
#[test]
fn strings_and_a_domain_map_to_pdos_with_their_size() {
    use canopen_core::od::{AbortCode, PdoDir, PdoMapping};
    let mut od = Mapped::default();
    assert_eq!(od.entry(0x2009, 0).unwrap().pdo, PdoMapping::Both);
    assert_eq!(od.entry(0x200F, 0).unwrap().pdo, PdoMapping::Both);
    let h = od.pdo_resolve(0x2009, 0, PdoDir::Tpdo).unwrap();
    assert_eq!(h.size, 4);
    let r = od.pdo_resolve(0x2009, 0, PdoDir::Rpdo).unwrap();
    od.pdo_write(&r, b"AB\0\0").unwrap();
    assert_eq!(od.text.as_bytes(), b"AB\0\0");
    assert_eq!(od.pdo_write(&r, &[0x07, 0, 0, 0]), Err(AbortCode::InvalidValue)); // not VISIBLE_CHAR
    od.text = VisibleString::from_str("xy").unwrap();
    let mut b = [0u8; 4];
    assert_eq!(od.pdo_read(&h, &mut b), Ok(2));
    assert_eq!(b, *b"xy\0\0");
    assert_eq!(od.pdo_resolve(0x200A, 0, PdoDir::Tpdo).unwrap().size, 8);
    assert_eq!(od.pdo_resolve(0x200A, 0, PdoDir::Rpdo), Err(AbortCode::NotMappable)); // ro, TPDO only
    assert_eq!(od.pdo_resolve(0x200B, 0, PdoDir::Rpdo).unwrap().size, 8);
    assert_eq!(od.pdo_resolve(0x200B, 0, PdoDir::Tpdo), Err(AbortCode::NotMappable)); // RPDO only
    assert_eq!(od.pdo_resolve(0x2010, 0, PdoDir::Tpdo), Err(AbortCode::NotMappable)); // no `pdo`
                                                                                      // A DOMAIN maps with the size it has: none while empty, 3 bytes after a 3-byte download, none at 9.
    assert_eq!(od.pdo_resolve(0x200F, 0, PdoDir::Tpdo), Err(AbortCode::NotMappable));
    od.write(0x200F, 0, &[1, 2, 3]).unwrap();
    let d = od.pdo_resolve(0x200F, 0, PdoDir::Rpdo).unwrap();
    assert_eq!(d.size, 3);
    od.pdo_write(&d, &[4, 5, 6]).unwrap();
    assert_eq!(od.blob.as_bytes(), &[4, 5, 6]);
    od.write(0x200F, 0, &[0; 9]).unwrap();
    assert_eq!(od.pdo_resolve(0x200F, 0, PdoDir::Tpdo), Err(AbortCode::NotMappable));
}

/// `eds_default` of a DOMAIN (datatypes.eds 200Fh `DefaultValue=@ABCD`, which is no hex pairs): the EDS
/// shows the text as it is; the node does not apply it (restore_defaults leaves a DOMAIN alone).
#[test]
fn a_domains_eds_default_is_the_eds_text_only() {
    use canopen_core::od::Value;
    let mut od = Mapped::default();
    assert_eq!(od.entry(0x200F, 0).unwrap().default, Some(Value::Str("@ABCD")));
    od.restore_defaults();
    assert!(od.blob.as_bytes().is_empty());
    let mut eds = String::new();
    for o in (0..od.object_count()).filter_map(|n| od.object(n)) {
        canopen_core::od::eds::write_object(&mut eds, &od, &o).unwrap();
    }
    assert!(
        eds.contains("[200F]\nParameterName=DOMAIN\nObjectType=0x7\nDataType=0x000F\nAccessType=rw\nDefaultValue=@ABCD\nPDOMapping=1\n"),
        "{eds}"
    );
    assert!(eds.contains("[2009]\nParameterName=VISIBLE_STRING\nObjectType=0x7\nDataType=0x0009\nAccessType=rw\nDefaultValue=\nPDOMapping=1\n"), "{eds}");
}

#[derive(ObjectDictionary, Default)]
struct NoDefault {
    #[od(index = 0x2000, domain)]
    blob: canopen_core::od::DomainBuf<4>,
}

/// A DOMAIN without `eds_default` has no DefaultValue line, as before.
#[test]
fn a_domain_without_eds_default_has_no_default_value() {
    let od = NoDefault::default();
    let mut eds = String::new();
    canopen_core::od::eds::write_object(&mut eds, &od, &od.object(0).unwrap()).unwrap();
    assert_eq!(eds, "[2000]\nParameterName=blob\nObjectType=0x7\nDataType=0x000F\nAccessType=rw\nPDOMapping=0\n\n");
}

#[derive(ObjectDictionary, Default)]
struct FixedOnly {
    #[od(index = 0x2000, access = "rw")]
    setpoint: i16,
    #[od(index = 0x2001, access = "ro")]
    status: u8,
}

/// A dictionary with no string or DOMAIN refuses every streamed write through one shared check, with the
/// codes of OD-16 in the same order as one with streams: unknown index 0602 0000h, unknown sub-index
/// 0609 0011h, read-only 0601 0002h, and a fixed-size entry (written whole, never streamed) 0601 0000h.
#[test]
fn a_dictionary_without_streams_refuses_streamed_writes() {
    use canopen_core::od::AbortCode;
    let mut od = FixedOnly::default();
    for (index, sub, code) in [
        (0x2100, 0, AbortCode::ObjectDoesNotExist),
        (0x2000, 1, AbortCode::SubIndexDoesNotExist),
        (0x2001, 0, AbortCode::WriteOfReadOnly),
        (0x2000, 0, AbortCode::UnsupportedAccess),
    ] {
        assert_eq!(od.begin_write(index, sub, Some(2)), Err(code), "{index:04X}h:{sub}");
        assert_eq!(od.write_chunk(index, sub, 0, &[1, 2]), Err(code), "{index:04X}h:{sub}");
        assert_eq!(od.end_write(index, sub, 2), Err(code), "{index:04X}h:{sub}");
    }
    // The whole write still works, and nothing above changed the values.
    assert_eq!(od.setpoint, 0);
    assert_eq!(od.write(0x2000, 0, &(-5i16).to_le_bytes()), Ok(()));
    assert_eq!(od.setpoint, -5);
}

#[derive(ObjectDictionary, Default)]
struct Extremes {
    #[od(index = 0x2000, access = "rw", min = -9223372036854775808, max = 9223372036854775807)]
    whole_i64: i64,
    #[od(index = 0x2001, access = "rw", max = 18446744073709551614)]
    below_max_u64: u64,
    #[od(index = 0x2002, access = "rw", min = -128, max = -1)]
    negative_i8: i8,
}

/// Integer limits are compared in the field's own type (`od::check_range`): limits at the type's ends are
/// literals of that type (i64::MIN included), a one-sided limit checks its side only, and the codes are
/// 0609 0031h above and 0609 0032h below (OD-16).
#[test]
fn integer_limits_at_the_types_ends() {
    use canopen_core::od::AbortCode;
    let mut od = Extremes::default();
    assert_eq!(od.write(0x2000, 0, &i64::MIN.to_le_bytes()), Ok(()));
    assert_eq!(od.write(0x2000, 0, &i64::MAX.to_le_bytes()), Ok(()));
    assert_eq!(od.write(0x2001, 0, &(u64::MAX - 1).to_le_bytes()), Ok(()));
    assert_eq!(od.write(0x2001, 0, &u64::MAX.to_le_bytes()), Err(AbortCode::ValueTooHigh));
    assert_eq!(od.write(0x2002, 0, &[0x80]), Ok(())); // -128
    assert_eq!(od.write(0x2002, 0, &[0]), Err(AbortCode::ValueTooHigh));
    assert_eq!((od.whole_i64, od.below_max_u64, od.negative_i8), (i64::MAX, u64::MAX - 1, -128));
}

#[derive(ObjectDictionary, Default)]
struct ReadOnlyText {
    #[od(index = 0x2000, access = "ro")]
    name: VisibleString<8>,
    #[od(index = 0x2001)]
    value: u32,
}

#[derive(ObjectDictionary, Default)]
struct WriteOnlyText {
    #[od(index = 0x2000, access = "wo")]
    name: VisibleString<8>,
    #[od(index = 0x2001)]
    value: u32,
}

#[derive(ObjectDictionary, Default)]
struct Wide {
    #[od(index = 0x2000, access = "ro")]
    counter: u64,
}

/// `ObjectDictionary::STREAMS`: a struct with a writable string (`App`, `WriteOnlyText`) takes streamed
/// writes; one whose strings are read-only (`ReadOnlyText`) or that has none (`Counts`, `Wide`) does not, so
/// the SDO server builds no stream path for it.
#[test]
fn streams_is_whether_a_string_or_domain_is_writable() {
    let streams = [App::STREAMS, WriteOnlyText::STREAMS, ReadOnlyText::STREAMS, Counts::STREAMS, Wide::STREAMS];
    assert_eq!(streams, [true, true, false, false, false]);
}

/// `ObjectDictionary::SEGMENTED_UPLOADS`: a readable string (`App`, `ReadOnlyText`) or a 64-bit value
/// (`Wide`) is uploaded segmented; a write-only string (`WriteOnlyText`) is never uploaded, and 1..=4-byte
/// entries (`Counts`) always go expedited, so the SDO server builds no segmented-upload path for those.
#[test]
fn segmented_uploads_is_whether_a_readable_entry_can_exceed_4_bytes() {
    let segmented = [
        App::SEGMENTED_UPLOADS,
        ReadOnlyText::SEGMENTED_UPLOADS,
        Wide::SEGMENTED_UPLOADS,
        WriteOnlyText::SEGMENTED_UPLOADS,
        Counts::SEGMENTED_UPLOADS,
    ];
    assert_eq!(segmented, [true, true, true, false, false]);
}
