//! Random EDS/DCF text and random concise DCF bytes: parsing never panics (a bad file is an error), and what
//! parses is written back and parsed again to the same thing. The text is built from the sections, keys and
//! values real files use, mixed with junk, so that most cases get past the first line.

use canopen_eds::{ConciseDcf, Eds};
use proptest::prelude::*;

/// A section: its header, mostly a valid DataType (which an entry needs), then keys real files use, or junk.
fn section() -> impl Strategy<Value = String> {
    let name = prop::sample::select(vec![
        "FileInfo",
        "DeviceInfo",
        "1000",
        "1018",
        "1018sub0",
        "1018sub1",
        "1018Sub2",
        "2000",
        "2000sub1",
        "2000Name",
        "2000Value",
        "6000",
        "a00",
        "DeviceComissioning",
        "MandatoryObjects",
        "Comments",
        "",
        "1sub",
        "zz",
    ]);
    let data_type = prop::sample::select(vec!["DataType=0x0007", "DataType=5", "DataType=0x0009", "DataType=x", ""]);
    let key = prop::sample::select(vec![
        "ParameterName",
        "ObjectType",
        "AccessType",
        "DefaultValue",
        "LowLimit",
        "HighLimit",
        "PDOMapping",
        "ParameterValue",
        "CompactSubObj",
        "SubNumber",
        "NodeID",
        "NodeName",
        "Baudrate",
        "LSS_SerialNumber",
        "CANopenManager",
        "1",
        "2",
        "objecttype",
        "",
    ]);
    let value = prop::sample::select(vec![
        "0x7",
        "7",
        "8",
        "9",
        "ro",
        "rw",
        "RWW",
        "const",
        "wo",
        "x",
        "",
        "1",
        "2",
        "300",
        "-5",
        "0x80000000",
        "$NODEID+0x180",
        "5.2",
        "a b",
        "=",
        "[",
        "0xZZ",
        "127",
        "128",
        "0",
    ]);
    let line = prop_oneof![
        8 => (key, value).prop_map(|(k, v)| format!("{k}={v}")),
        1 => "[ -~]{0,12}",
        1 => Just("; comment".to_owned()),
    ];
    (name, data_type, prop::collection::vec(line, 0..8))
        .prop_map(|(n, t, lines)| format!("[{n}]\n{t}\n{}\n", lines.join("\n")))
}

proptest! {
    #[test]
    fn random_text_parses_or_errs_and_round_trips(sections in prop::collection::vec(section(), 0..12)) {
        let text = sections.concat();
        match Eds::parse(&text) {
            Ok(eds) => {
                let written = eds.to_string();
                prop_assert_eq!(Eds::parse(&written), Ok(eds), "written:\n{}", written);
            }
            Err(e) => prop_assert!(e.line >= 1 && e.line <= text.lines().count(), "{e} in:\n{text}"),
        }
    }

    #[test]
    fn random_bytes_parse_or_err_and_round_trip(bytes in prop::collection::vec(any::<u8>(), 0..64)) {
        if let Ok(c) = ConciseDcf::parse(&bytes) {
            prop_assert_eq!(c.to_bytes(), bytes);
        }
    }

    #[test]
    fn concise_dcf_round_trips(entries in prop::collection::vec((any::<u16>(), any::<u8>(), prop::collection::vec(any::<u8>(), 0..12)), 0..8)) {
        let c = ConciseDcf { entries: entries.into_iter().map(|(i, s, d)| canopen_eds::Configured::new(i, s, d)).collect() };
        prop_assert_eq!(ConciseDcf::parse(&c.to_bytes()), Ok(c));
    }
}
