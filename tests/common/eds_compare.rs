//! EDS → Rust → EDS comparison, shared by tests/eds_to_rust.rs (our fixtures) and tests/eds_real.rs
//! (python canopen's files): the EDS a generated module's dictionary writes equals the original on every
//! entry the module carries (index, sub-index, data type, access, default, limits, PDO mapping; of
//! 1000h-1FFFh what a node configuration holds, PDO defaults included), and what it does not carry is
//! exactly what `rust_module` listed as left out.
#![allow(dead_code)]

use canopen_eds::{eval_typed, no_limit, Access, Dropped, Eds, Entry, LeftOut};

/// Two values of a data type are the same: equal text, or equal numbers however written (`0x0` and `0`,
/// `0xFFFFFFFF` and `-1` for an INTEGER32).
fn same(a: &Option<String>, b: &Option<String>, data_type: u16) -> bool {
    match (a.as_deref(), b.as_deref()) {
        (Some(x), Some(y)) => {
            x == y
                || eval_typed(x, data_type, 0).is_some_and(|v| eval_typed(y, data_type, 0) == Some(v))
                || x.parse::<f64>().is_ok_and(|v| y.parse::<f64>() == Ok(v))
        }
        (x, y) => x == y,
    }
}

fn differences(a: &Entry, b: &Entry) -> Vec<Dropped> {
    let mut d = Vec::new();
    if a.data_type != b.data_type {
        d.push(Dropped::Entry);
    }
    if a.pdo_mapping != b.pdo_mapping {
        d.push(Dropped::PdoMapping);
    }
    // Sub-index 0 of the communication profile's records (1018h, the PDO parameters) is as the core
    // describes it (const), not a NodeConfig field: ro there is the same to a master, and listed as not
    // carried in canopen-master's README. Application objects' counts are compared exactly (count_access).
    let read_only = |e: &Entry| matches!(e.access, Access::ReadOnly | Access::Const);
    let profile_count = a.index < 0x2000 && a.sub == 0 && read_only(a) && read_only(b);
    if a.access != b.access && !profile_count {
        d.push(Dropped::Access);
    }
    if !same(&a.default, &b.default, a.data_type) {
        d.push(Dropped::Default);
    }
    // A limit at its type's bound limits nothing: the same as none (sample.eds's transmission types 0..255).
    let limit = |e: &Entry, low: bool| {
        let v = if low { &e.low } else { &e.high };
        if no_limit(v.as_deref(), e.data_type, low) {
            None
        } else {
            v.clone()
        }
    };
    if !same(&limit(a, true), &limit(b, true), a.data_type) || !same(&limit(a, false), &limit(b, false), a.data_type) {
        d.push(Dropped::Limits);
    }
    d
}

/// Compares `back` (the EDS written by the module generated from `original`) with `original` on every
/// application entry and the 1000h–1FFFh values a node configuration carries; an entry or attribute may
/// differ only when `left_out` says so. Returns how many entries were compared.
pub fn compare(file: &str, original: &Eds, back: &Eds, left_out: &[LeftOut]) -> usize {
    let dropped = |e: &Entry, what: Dropped| {
        left_out.iter().any(|l| l.index == e.index && l.sub.is_none_or(|s| s == e.sub) && l.dropped == what)
    };
    // The PDO defaults a node configuration carries (RPDO/TPDO 1-4): the communication parameters'
    // COB-ID, transmission type, inhibit time, event timer, SYNC start value, and the mapping entries.
    let pdo = |e: &Entry| match e.index {
        0x1400..=0x1403 | 0x1800..=0x1803 => matches!(e.sub, 1 | 2 | 3 | 5 | 6),
        0x1600..=0x1603 | 0x1A00..=0x1A03 => e.sub <= 8,
        _ => false,
    };
    let config = |e: &Entry| matches!(e.index, 0x1000 | 0x1008 | 0x1009 | 0x100A | 0x1017 | 0x1018) || pdo(e);
    let mut compared = 0;
    for e in original.entries().filter(|e| e.index >= 0x2000 || config(e)) {
        if dropped(e, Dropped::Entry) {
            continue;
        }
        let at = format!("{file}: {:04X}h:{:02X} {}", e.index, e.sub, e.name);
        let b = back.entry(e.index, e.sub).unwrap_or_else(|| panic!("{at} is gone"));
        // An entry the EDS gives no default holds its type's zero (the derive's `restore_defaults`, a node
        // configuration's fields), which the core's EDS writes as `DefaultValue=0` (empty for a string).
        let zero = matches!(b.default.as_deref(), None | Some("")) || same(&Some("0".into()), &b.default, b.data_type);
        let absent_is_zero = |w: Dropped| w == Dropped::Default && e.default.is_none() && zero;
        let d: Vec<Dropped> = differences(e, b).into_iter().filter(|&w| !dropped(e, w) && !absent_is_zero(w)).collect();
        assert!(d.is_empty(), "{at}: {d:?} differ: {e:?} / {b:?}");
        compared += 1;
    }
    for b in back.entries().filter(|e| e.index >= 0x2000) {
        assert!(original.entry(b.index, b.sub).is_some(), "{file}: {:04X}h:{:02X} is new", b.index, b.sub);
    }
    compared
}
