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

use canopen_core::od::ObjectDictionary;
use canopen_master::eds::{eval_default, to_rust, Access, Eds, Entry};

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

/// Two values are the same: equal text, or equal numbers however written (`0x0` and `0`).
fn same(a: &Option<String>, b: &Option<String>) -> bool {
    match (a.as_deref(), b.as_deref()) {
        (Some(x), Some(y)) => {
            x == y
                || eval_default(x, 0).is_some_and(|v| eval_default(y, 0) == Some(v))
                || x.parse::<f64>().is_ok_and(|v| y.parse::<f64>() == Ok(v))
        }
        (x, y) => x == y,
    }
}

fn differences(a: &Entry, b: &Entry) -> Vec<&'static str> {
    let mut d = Vec::new();
    if a.data_type != b.data_type {
        d.push("data type");
    }
    // Sub-index 0 of an ARRAY or RECORD (the entry count) is always const in a derived dictionary;
    // CiA 306 has the one CompactSubObj implies be ro. Both are read-only: the same to a master.
    let read_only = |e: &Entry| matches!(e.access, Access::ReadOnly | Access::Const);
    if a.access != b.access && !(a.sub == 0 && read_only(a) && read_only(b)) {
        d.push("access");
    }
    if a.pdo_mapping != b.pdo_mapping {
        d.push("PDO mapping");
    }
    if !same(&a.default, &b.default) {
        d.push("default");
    }
    if !same(&a.low, &b.low) || !same(&a.high, &b.high) {
        d.push("limits");
    }
    d
}

/// Writes the EDS of a generated module's dictionary (its defaults restored) and compares it with the
/// original on every entry it carries; returns how many were compared.
fn round_trip<A: canopen_core::od::OdDescribe + ObjectDictionary>(
    original: &str,
    mut app: A,
    config: canopen_core::profile::NodeConfig,
) -> usize {
    let original = Eds::parse(original).unwrap();
    app.restore_defaults();
    let comm = canopen_core::profile::CommProfile::<canopen_core::Sizes>::new(config);
    let od = canopen_core::od::Merged { comm, app };
    let mut text = String::new();
    canopen_core::profile::eds::write_eds(&mut text, &canopen_core::profile::eds::EdsInfo::DEFAULT, &od).unwrap();
    let back = Eds::parse(&text).unwrap();

    // The application entries the derive can hold (data types up to 001Bh), and the configuration's.
    let carried = |e: &Entry| {
        (e.index >= 0x2000 && e.data_type <= 0x001B)
            || matches!(e.index, 0x1000 | 0x1008 | 0x1009 | 0x100A | 0x1017 | 0x1018)
    };
    let mut compared = 0;
    for e in original.entries().filter(|e| carried(e)) {
        let b =
            back.entry(e.index, e.sub).unwrap_or_else(|| panic!("{:04X}h:{:02X} {} is gone", e.index, e.sub, e.name));
        let d = differences(e, b);
        assert!(d.is_empty(), "{:04X}h:{:02X} {}: {d:?} differ: {e:?} / {b:?}", e.index, e.sub, e.name);
        compared += 1;
    }
    for b in back.entries().filter(|e| e.index >= 0x2000) {
        assert!(original.entry(b.index, b.sub).is_some(), "{:04X}h:{:02X} is new", b.index, b.sub);
    }
    compared
}

#[test]
fn eds_to_rust_to_eds_is_the_same_dictionary() {
    let n = round_trip(EDS, generated::Device::default(), generated::CONFIG);
    assert!(n > 40, "only {n} entries compared");
    let n = round_trip(SHAPES, shapes::Device::default(), shapes::CONFIG);
    assert_eq!(n, 2 + 3 + 4 + 4);
}
