//! EDS → Rust → EDS (issue 23 item 3): `canopenctl eds-to-rust` of the example node's EDS
//! (tests/data/eds_to_rust/io_module.eds) is the module tests/data/eds_to_rust/io_module.rs, which compiles
//! here as it is (only canopen-core and canopen-od-derive), and the EDS that module's dictionary writes
//! equals the original on every application object (index, sub-index, data type, access, default, limits,
//! PDO mapping) and on the 1000h–1FFFh values the node configuration carries.

#[path = "../examples/common/io_module.rs"]
mod io_module;

// Exactly as eds-to-rust prints them: rustfmt leaves them alone.
#[rustfmt::skip]
#[path = "data/eds_to_rust/io_module.rs"]
mod generated;
#[rustfmt::skip]
#[path = "data/eds_to_rust/shapes.rs"]
mod shapes;

#[path = "common/eds_compare.rs"]
mod eds_compare;
#[path = "common/eds_of.rs"]
mod eds_of;

use canopen_core::od::ObjectDictionary;
use canopen_eds::{rust_module, to_rust, Eds};

const EDS: &str = include_str!("data/eds_to_rust/io_module.eds");
/// A hand-written EDS with the shapes the example node lacks: BOOLEAN, a negative hex default, a const
/// string, a RECORD, a CompactSubObj ARRAY of REAL64, and a data type the derive cannot hold (left out).
const SHAPES: &str = include_str!("data/eds_to_rust/shapes.eds");

/// The fixture is the example node's EDS as it writes it today, and the module is what `eds-to-rust` prints
/// for it (regenerate both: `cargo run --example node -- --eds tests/data/eds_to_rust/io_module.eds`, then
/// `cargo run -p canopenctl -- eds-to-rust tests/data/eds_to_rust/io_module.eds > tests/data/eds_to_rust/io_module.rs`).
#[test]
fn the_modules_are_what_eds_to_rust_prints() {
    assert!(EDS == io_module::eds_text(io_module::CONFIG, false), "tests/data/eds_to_rust/io_module.eds is stale");
    let rust = to_rust(&Eds::parse(EDS).unwrap(), "io_module.eds");
    assert!(
        rust == include_str!("data/eds_to_rust/io_module.rs"),
        "tests/data/eds_to_rust/io_module.rs is stale:\n{rust}"
    );
    let rust = to_rust(&Eds::parse(SHAPES).unwrap(), "shapes.eds");
    assert!(rust == include_str!("data/eds_to_rust/shapes.rs"), "tests/data/eds_to_rust/shapes.rs is stale:\n{rust}");
    assert!(rust.contains("// 2040h Complex: data type 0040h is not supported; left out."));
}

/// The EDS of the generated module's dictionary equals the original where the module carries it.
fn round_trip<A: canopen_core::od::OdDescribe + ObjectDictionary>(
    original: &str,
    app: A,
    config: canopen_core::profile::NodeConfig,
) -> usize {
    let original = Eds::parse(original).unwrap();
    let left_out = rust_module(&original, "fixture").left_out;
    let back = Eds::parse(&eds_of::eds_of(app, config)).unwrap();
    eds_compare::compare("fixture", &original, &back, &left_out)
}

#[test]
fn eds_to_rust_to_eds_is_the_same_dictionary() {
    let n = round_trip(EDS, generated::Device::default(), generated::CONFIG);
    assert!(n > 40, "only {n} entries compared");
    let n = round_trip(SHAPES, shapes::Device::default(), shapes::CONFIG);
    assert_eq!(n, 2 + 3 + 4 + 4);
}

/// The EDS writer (canopen-eds) gives back what it read: both fixtures, written and parsed again, are the
/// same description (objects, entries, the sections that describe no object).
#[test]
fn the_fixtures_written_back_parse_the_same() {
    for text in [EDS, SHAPES] {
        let eds = Eds::parse(text).unwrap();
        let written = eds.to_string();
        assert!(Eds::parse(&written).as_ref() == Ok(&eds), "written and parsed again differs:\n{written}");
        assert!(eds.objects.len() > 5);
    }
}

/// The comparison is not vacuous: a default, an access (sub-index 0's too) or a PDO mapping changed in the
/// EDS written back, or an entry gone, fails it; listing the change as left out is what makes it pass.
#[test]
fn the_comparison_catches_a_changed_entry() {
    let original = Eds::parse(SHAPES).unwrap();
    let left_out = rust_module(&original, "shapes.eds").left_out;
    let back = eds_of::eds_of(shapes::Device::default(), shapes::CONFIG);
    assert_eq!(eds_compare::compare("shapes.eds", &original, &Eds::parse(&back).unwrap(), &left_out), 13);
    let section = |s: &str| back.find(s).unwrap_or_else(|| panic!("{s} not in the EDS written back"));
    for (at, from, to) in [
        ("[2020sub1]", "DefaultValue=0.5", "DefaultValue=0.25"),
        ("[2010]", "AccessType=rw", "AccessType=ro"),
        ("[2010]", "PDOMapping=1", "PDOMapping=0"),
        ("[2011]", "LowLimit=-100000", "LowLimit=-99999"),
        ("[2020sub3]", "[2020sub3]", "[2020sub7]"),
        // CompactSubObj's count is ro (count_access): const is a different entry.
        ("[2030sub0]", "AccessType=ro", "AccessType=const"),
    ] {
        let start = section(at);
        let end = start + back[start..].find("\n\n").unwrap_or(back.len() - start);
        assert!(back[start..end].contains(from), "{at} has no {from}");
        let changed = format!("{}{}{}", &back[..start], back[start..end].replacen(from, to, 1), &back[end..]);
        let changed = Eds::parse(&changed).unwrap();
        let r = std::panic::catch_unwind(|| eds_compare::compare("shapes.eds", &original, &changed, &left_out));
        assert!(r.is_err(), "{at}: {from} -> {to} went unnoticed");
    }
}
