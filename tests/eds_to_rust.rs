//! EDS → Rust → EDS (issue 23 item 3): `canopenctl eds-to-rust` of the example node's EDS
//! (tests/data/eds_to_rust/io_module.eds) is the module tests/data/eds_to_rust/io_module.rs, which compiles
//! here as it is (only canopen-core and canopen-od-derive), and the EDS that module's dictionary writes
//! equals the original on every application object (index, sub-index, data type, access, default, limits,
//! PDO mapping) and on the 1000h–1FFFh values the node configuration carries.

#[path = "../examples/common/io_module.rs"]
mod io_module;

// Exactly as eds-to-rust prints it: rustfmt leaves it alone.
#[rustfmt::skip]
#[path = "data/eds_to_rust/io_module.rs"]
mod generated;

use canopen_core::od::ObjectDictionary;
use canopen_master::eds::{eval_default, to_rust, Eds, Entry};

const EDS: &str = include_str!("data/eds_to_rust/io_module.eds");

/// The fixture is the example node's EDS as it writes it today, and the module is what `eds-to-rust` prints
/// for it (regenerate both: `cargo run --example node -- --eds tests/data/eds_to_rust/io_module.eds`, then
/// `cargo run -p canopenctl -- eds-to-rust tests/data/eds_to_rust/io_module.eds > tests/data/eds_to_rust/io_module.rs`).
#[test]
fn the_module_is_what_eds_to_rust_prints() {
    assert!(EDS == io_module::eds_text(io_module::CONFIG, false), "tests/data/eds_to_rust/io_module.eds is stale");
    let rust = to_rust(&Eds::parse(EDS).unwrap(), "io_module.eds");
    assert!(
        rust == include_str!("data/eds_to_rust/io_module.rs"),
        "tests/data/eds_to_rust/io_module.rs is stale:\n{rust}"
    );
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
    if a.access != b.access {
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

#[test]
fn eds_to_rust_to_eds_is_the_same_dictionary() {
    let original = Eds::parse(EDS).unwrap();
    let mut app = generated::Device::default();
    app.restore_defaults();
    let comm = canopen_core::profile::CommProfile::<canopen_core::Sizes>::new(generated::CONFIG);
    let od = canopen_core::od::Merged { comm, app };
    let mut text = String::new();
    canopen_core::profile::eds::write_eds(&mut text, &canopen_core::profile::eds::EdsInfo::DEFAULT, &od).unwrap();
    let back = Eds::parse(&text).unwrap();

    let carried =
        |e: &Entry| e.index >= 0x2000 || matches!(e.index, 0x1000 | 0x1008 | 0x1009 | 0x100A | 0x1017 | 0x1018);
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
    assert!(compared > 40, "only {compared} entries compared");
}
