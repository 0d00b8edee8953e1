//! EDS → Rust: a module that uses only `canopen-core` and `canopen-od-derive` and compiles as it is: the
//! application objects (2000h–FFFFh) as a struct with `#[derive(ObjectDictionary)]`, and a `NodeConfig`
//! with what the EDS says of 1000h–1FFFh that the configuration carries (device type, identity, names,
//! producer heartbeat time).
//!
//! Not carried over, yet: PDO default communication and mapping parameters (1400h–1BFFh; the node's
//! `NodeConfig::DEFAULT` ones apply), per-sub defaults of an array whose subs differ (the field's type
//! default applies), limits on anything but numbers, DOMAIN access other than rw, data types the derive
//! does not know (a comment names each object left out). Sub-index 0 of an ARRAY or RECORD is const in the
//! derived dictionary whatever the EDS says (ro, as CiA 306 has it for `CompactSubObj`).

use std::fmt::Write as _;

use crate::eds::{eval_default, Access, Eds, Entry, Object, ObjectKind};

/// The Rust type of a data type index, and whether it is a number (limits and numeric defaults apply).
fn rust_type(entry: &Entry) -> Option<(String, bool)> {
    let n = |s: &str| Some((s.to_owned(), true));
    match entry.data_type {
        0x0001 => Some(("bool".into(), false)),
        0x0002 => n("i8"),
        0x0003 => n("i16"),
        0x0004 => n("i32"),
        0x0005 => n("u8"),
        0x0006 => n("u16"),
        0x0007 => n("u32"),
        0x0008 => n("f32"),
        0x0011 => n("f64"),
        0x0015 => n("i64"),
        0x001B => n("u64"),
        0x0010 => n("I24"),
        0x0012 => n("I40"),
        0x0013 => n("I48"),
        0x0014 => n("I56"),
        0x0016 => n("U24"),
        0x0018 => n("U40"),
        0x0019 => n("U48"),
        0x001A => n("U56"),
        0x0009 => Some((format!("VisibleString<{}>", text_capacity(entry)), false)),
        0x000A => Some((format!("OctetString<{}>", text_capacity(entry)), false)),
        0x000B => Some((format!("UnicodeString<{}>", text_capacity(entry)), false)),
        0x000C => Some(("TimeOfDay".into(), false)),
        0x000D => Some(("TimeDifference".into(), false)),
        _ => None,
    }
}

/// A string's capacity: its default's length, at least 32.
fn text_capacity(entry: &Entry) -> usize {
    entry.default.as_ref().map_or(0, |d| d.len()).max(32)
}

/// A field name from an object's name: lower-case words joined by `_`, then the index (and sub-index).
fn ident(name: &str, index: u16, sub: Option<u8>) -> String {
    let mut s = String::new();
    for c in name.chars() {
        if c.is_ascii_alphanumeric() {
            s.push(c.to_ascii_lowercase());
        } else if !s.ends_with('_') && !s.is_empty() {
            s.push('_');
        }
    }
    let s = s.trim_end_matches('_');
    let base = if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) { format!("x{s}") } else { s.to_owned() };
    match sub {
        Some(sub) => format!("{base}_{index:04x}_{sub}"),
        None => format!("{base}_{index:04x}"),
    }
}

/// A Rust literal for a numeric EDS value of a type, `None` when it is not one (a `$NODEID` expression).
fn number_literal(text: &str, float: bool) -> Option<String> {
    if float {
        let v: f64 = text.trim().parse().ok()?;
        let s = format!("{v:?}");
        return Some(if s.contains(['.', 'e', 'E']) || s.contains("inf") || s.contains("NaN") {
            s
        } else {
            format!("{s}.0")
        });
    }
    if text.contains('$') {
        return None;
    }
    eval_default(text, 0).map(|v| v.to_string())
}

fn quote(s: &str) -> String {
    format!("{s:?}")
}

/// The `pdo = ...` of an entry mapped to PDOs: the directions its access allows.
fn pdo(entry: &Entry) -> Option<&'static str> {
    if !entry.pdo_mapping {
        return None;
    }
    Some(match entry.access {
        Access::ReadOnly | Access::Const => "tpdo",
        Access::WriteOnly => "rpdo",
        Access::ReadWrite => "both",
    })
}

/// The attributes besides index/sub/name of a value (access, pdo, limits, default).
fn value_attrs(entry: &Entry, numeric: bool, float: bool, default: Option<&str>) -> String {
    let mut a = format!(", access = {}", quote(entry.access.as_str()));
    if let Some(p) = pdo(entry) {
        let _ = write!(a, ", pdo = {}", quote(p));
    }
    if numeric {
        for (key, v) in [("min", &entry.low), ("max", &entry.high)] {
            if let Some(lit) = v.as_deref().and_then(|t| number_literal(t, float)) {
                let _ = write!(a, ", {key} = {lit}");
            }
        }
    }
    match (default, entry.data_type) {
        (Some(d), 0x0001) => {
            if let Some(v) = eval_default(d, 0) {
                let _ = write!(a, ", default = {}", v != 0);
            }
        }
        (Some(d), 0x0009) => {
            let _ = write!(a, ", default = {}", quote(d));
        }
        (Some(d), _) if numeric => {
            if let Some(lit) = number_literal(d, float) {
                let _ = write!(a, ", default = {lit}");
            }
        }
        _ => {}
    }
    a
}

fn is_float(entry: &Entry) -> bool {
    matches!(entry.data_type, 0x0008 | 0x0011)
}

fn var(out: &mut String, o: &Object, e: &Entry) {
    if e.data_type == 0x000F {
        let _ = writeln!(out, "    #[od(index = 0x{:04X}, name = {}, domain)]", o.index, quote(&o.name));
        let _ = writeln!(out, "    pub {}: DomainBuf<4096>,", ident(&o.name, o.index, None));
        return;
    }
    let Some((ty, numeric)) = rust_type(e) else {
        let _ = writeln!(
            out,
            "    // {:04X}h {}: data type {:04X}h is not supported; left out.",
            o.index, o.name, e.data_type
        );
        return;
    };
    let attrs = value_attrs(e, numeric, is_float(e), e.default.as_deref());
    let _ = writeln!(out, "    #[od(index = 0x{:04X}, name = {}{attrs})]", o.index, quote(&o.name));
    let _ = writeln!(out, "    pub {}: {ty},", ident(&o.name, o.index, None));
}

fn array(out: &mut String, o: &Object) {
    let subs: Vec<&Entry> = o.entries.values().filter(|e| e.sub > 0).collect();
    let Some(first) = subs.first() else {
        let _ = writeln!(out, "    // {:04X}h {}: an array without entries; left out.", o.index, o.name);
        return;
    };
    let contiguous = subs.iter().enumerate().all(|(i, e)| usize::from(e.sub) == i + 1);
    let same = subs.iter().all(|e| e.data_type == first.data_type && e.access == first.access);
    let Some((ty, numeric)) = rust_type(first).filter(|_| contiguous && same) else {
        let _ =
            writeln!(out, "    // {:04X}h {}: an array of mixed or unsupported entries; left out.", o.index, o.name);
        return;
    };
    let default = first.default.as_deref().filter(|d| subs.iter().all(|e| e.default.as_deref() == Some(*d)));
    let attrs = value_attrs(first, numeric, is_float(first), default);
    let _ = writeln!(
        out,
        "    #[od(index = 0x{:04X}, sub = 1..={}, name = {}{attrs})]",
        o.index,
        subs.len(),
        quote(&o.name)
    );
    let _ = writeln!(out, "    pub {}: [{ty}; {}],", ident(&o.name, o.index, None), subs.len());
}

fn record(out: &mut String, o: &Object) {
    let mut first = true;
    for e in o.entries.values().filter(|e| e.sub > 0) {
        let Some((ty, numeric)) = rust_type(e) else {
            let _ = writeln!(
                out,
                "    // {:04X}h:{:02X} {}: data type {:04X}h is not supported; left out.",
                o.index, e.sub, e.name, e.data_type
            );
            continue;
        };
        let record = if first { format!(", record = {}", quote(&o.name)) } else { String::new() };
        first = false;
        let attrs = value_attrs(e, numeric, is_float(e), e.default.as_deref());
        let _ = writeln!(
            out,
            "    #[od(index = 0x{:04X}, sub = {}{record}, name = {}{attrs})]",
            o.index,
            e.sub,
            quote(&e.name)
        );
        let _ = writeln!(out, "    pub {}: {ty},", ident(&e.name, o.index, Some(e.sub)));
    }
}

/// The Rust module for `eds`; `source` names the file in its header.
///
/// The application objects (2000h–FFFFh) become a struct with `#[derive(ObjectDictionary)]`, and
/// 1000h–1FFFh a `NodeConfig` (device type, identity, names, producer heartbeat time). Not carried over,
/// yet: PDO default parameters (1400h–1BFFh), per-sub defaults of an array whose subs differ, limits on
/// anything but numbers, DOMAIN access other than rw, data types the derive does not know (a comment names
/// each object left out).
///
/// ```
/// use canopen_master::eds::{to_rust, Eds};
/// let eds = Eds::parse("[1000]\nParameterName=Device type\nDataType=7\nAccessType=ro\nDefaultValue=0x191\n\
///     [2001]\nParameterName=Setpoint\nDataType=3\nAccessType=rw\nLowLimit=-10\nHighLimit=10\nDefaultValue=0\n").unwrap();
/// let rust = to_rust(&eds, "dev.eds");
/// assert!(rust.contains("#[od(index = 0x2001, name = \"Setpoint\", access = \"rw\", min = -10, max = 10, default = 0)]"));
/// assert!(rust.contains("pub setpoint_2001: i16,"));
/// assert!(rust.contains("device_type: 401,"));
/// ```
pub fn to_rust(eds: &Eds, source: &str) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "//! Generated from {source} (CiA 306) by `canopenctl eds-to-rust`: the application objects");
    let _ =
        writeln!(out, "//! (2000h-FFFFh) as a derived object dictionary, and the node configuration from 1000h-1FFFh.");
    let _ = writeln!(out);
    let _ = writeln!(out, "#![allow(unused_imports, clippy::all)]");
    let _ = writeln!(out);
    let _ = writeln!(
        out,
        "use canopen_core::od::{{DomainBuf, OctetString, TimeDifference, TimeOfDay, UnicodeString, VisibleString}};"
    );
    let _ = writeln!(out, "use canopen_core::od::{{I24, I40, I48, I56, U24, U40, U48, U56}};");
    let _ = writeln!(out, "use canopen_core::profile::{{Identity, NodeConfig}};");
    let _ = writeln!(out, "use canopen_od_derive::ObjectDictionary;");
    let _ = writeln!(out);
    let _ = writeln!(out, "/// The application objects of {source}.");
    let _ = writeln!(out, "#[derive(ObjectDictionary, Debug, Default)]");
    let _ = writeln!(out, "pub struct Device {{");
    for o in eds.objects.values().filter(|o| o.index >= 0x2000) {
        match o.kind {
            ObjectKind::Var => {
                if let Some(e) = o.entries.get(&0) {
                    var(&mut out, o, e);
                }
            }
            ObjectKind::Array => array(&mut out, o),
            ObjectKind::Record => record(&mut out, o),
        }
    }
    let _ = writeln!(out, "}}");
    let _ = writeln!(out);
    let u32_of = |index: u16, sub: u8| {
        eds.entry(index, sub)
            .and_then(|e| e.default.as_deref())
            .and_then(|d| eval_default(d, 0))
            .and_then(|v| u32::try_from(v).ok())
    };
    let text_of = |index: u16| eds.entry(index, 0).and_then(|e| e.default.clone());
    let _ = writeln!(out, "/// The node configuration {source} describes.");
    let _ = writeln!(out, "pub const CONFIG: NodeConfig = NodeConfig {{");
    if let Some(v) = u32_of(0x1000, 0) {
        let _ = writeln!(out, "    device_type: {v},");
    }
    let id: Vec<Option<u32>> = (1..=4).map(|s| u32_of(0x1018, s)).collect();
    if id.iter().any(Option::is_some) {
        let f = |v: Option<u32>| v.unwrap_or(0);
        let _ = writeln!(
            out,
            "    identity: Identity {{ vendor_id: {}, product_code: {}, revision: {}, serial: {} }},",
            f(id[0]),
            f(id[1]),
            f(id[2]),
            f(id[3])
        );
    }
    for (index, field) in [(0x1008, "device_name"), (0x1009, "hardware_version"), (0x100A, "software_version")] {
        if let Some(t) = text_of(index) {
            let _ = writeln!(out, "    {field}: {},", quote(&t));
        }
    }
    if let Some(v) = u32_of(0x1017, 0).and_then(|v| u16::try_from(v).ok()) {
        let _ = writeln!(out, "    heartbeat_time_ms: {v},");
    }
    let _ = writeln!(out, "    ..NodeConfig::DEFAULT");
    let _ = writeln!(out, "}};");
    out
}
