//! EDS → Rust: a module that uses only `canopen-core` and `canopen-od-derive` and compiles as it is: the
//! application objects (2000h–FFFFh) as a struct with `#[derive(ObjectDictionary)]`, and a `NodeConfig`
//! with what the EDS says of 1000h–1FFFh that the configuration carries (device type, identity, names,
//! producer heartbeat time, the defaults of RPDO and TPDO 1–4: COB-ID, transmission type, inhibit time,
//! event timer, SYNC start value, mapping).
//!
//! Real EDS files (python canopen's sample.eds, datatypes.eds and e35.eds, in tests/eds_real.rs) showed
//! what is handled here: signed limits and defaults in two's complement hex (`LowLimit=0x80000000` of an
//! INTEGER32 is -2147483648, as python canopen reads it), ARRAYs whose entries differ in access, default or
//! limits (written as a record, one field per entry: every entry is kept, the derived EDS says RECORD),
//! OCTET_STRING defaults in hex pairs, UNICODE_STRING defaults, limits at the type's bounds (none), an
//! ARRAY or RECORD with sub-index 0 only (a VAR), a TPDO COB-ID's bit 30 (`rtr_allowed: false`), a mapping
//! count's limits 0..n, n < 8 (`max_mapped`), OCTET_STRING defaults that are no UTF-8 (a byte string),
//! strings and a DOMAIN marked PDO-mappable (a mapped string gets a capacity a PDO holds, 8 bytes or 4
//! UTF-16 units, since it moves its whole capacity; a DOMAIN maps with its size at the time, 1 to 8
//! bytes), a DOMAIN's default (`eds_default`: the EDS text, shown again in the derived EDS, which the node
//! does not apply: the DOMAIN starts empty).
//!
//! Not carried over, each listed by [`rust_module`] (`Generated::left_out`, which a build script's [`generate`](crate::generate)
//! prints as cargo warnings) and named by a comment in the
//! module where the field would be: data types the derive does not know (0040h and up, the object or entry
//! is left out), an ARRAY without any entry, PDO mapping of a string whose default is longer than a PDO
//! holds, DOMAIN access other than rw, defaults relative to `$NODEID` and limits that are no number of the type, limits on
//! anything but numbers. Of 1000h–1FFFh only what `NodeConfig` holds (device type, identity, names, producer
//! heartbeat time, PDO defaults): SDO parameters, error behaviour and the rest take the node's
//! `NodeConfig::DEFAULT` values; of the PDOs, those beyond the fourth each way, a COB-ID with bits 11–29
//! set (29-bit) or an RPDO's bit 30 (reserved) or relative to `$NODEID` but not the pre-defined connection
//! set, mapping entries beyond sub-index 0's count or under a count they do not fill (a count without
//! DefaultValue keeps the entries, none mapped: `count: Some(0)`), and limits on PDO parameters
//! (but a mapping count's 0..n and those at the type's bounds, which limit nothing). Sub-index 0 of an
//! ARRAY or RECORD is ro (`count_access = "ro"`) or const as the EDS says; a writable one is left out.

use std::fmt::{self, Write as _};

use crate::eds::{eval_default, eval_typed, no_limit, Access, Eds, Entry, Object, ObjectKind};

/// What the generated module does not carry of an EDS, so that a round trip knows what to skip and a
/// reader of the module sees it: each one is also a comment in the module, where the field would be.
///
/// ```
/// use canopen_eds::{rust_module, Dropped, Eds};
/// let eds = Eds::parse("[2001]\nParameterName=Blob\nDataType=0xF\nAccessType=ro\n").unwrap();
/// let g = rust_module(&eds, "dev.eds");
/// assert_eq!((g.left_out[0].index, g.left_out[0].sub, g.left_out[0].dropped), (0x2001, None, Dropped::Access));
/// assert!(g.rust.contains("// 2001h Blob: access ro not carried (a derived DOMAIN is rw)."));
/// assert_eq!(g.left_out[0].to_string(), "2001h Blob: access ro not carried (a derived DOMAIN is rw).");
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LeftOut {
    /// Object index.
    pub index: u16,
    /// The sub-index, `None` for the whole object (or a VAR).
    pub sub: Option<u8>,
    /// What of it is not carried.
    pub dropped: Dropped,
    /// Why, in words.
    pub why: String,
    /// The whole sentence: the module's comment, a build script's cargo warning, and the `Display` text.
    pub note: String,
}

impl fmt::Display for LeftOut {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.note)
    }
}

/// What a [`LeftOut`] leaves out.
///
/// ```
/// let eds = canopen_eds::Eds::parse("[2001]\nParameterName=Gain\nDataType=3\nDefaultValue=$NODEID\n").unwrap();
/// let g = canopen_eds::rust_module(&eds, "dev.eds");
/// assert_eq!(g.left_out[0].dropped, canopen_eds::Dropped::Default); // the field is kept, its default is not
/// assert!(g.rust.contains("pub gain_2001: i16,"));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dropped {
    /// The object or entry itself: no field holds it.
    Entry,
    /// Its `DefaultValue` (the field's type default applies).
    Default,
    /// Its `LowLimit`/`HighLimit`.
    Limits,
    /// Its `AccessType` (a DOMAIN is always rw).
    Access,
    /// Its `PDOMapping=1`: a string whose default is longer than a PDO's 8 bytes (a mapped string moves its
    /// whole capacity, which a PDO must hold).
    PdoMapping,
}

/// The generated module and what it leaves out.
///
/// ```
/// let eds = canopen_eds::Eds::parse("[2001]\nParameterName=Gain\nDataType=3\n[2002]\nParameterName=X\nDataType=0x40\n").unwrap();
/// let g = canopen_eds::rust_module(&eds, "dev.eds");
/// assert!(g.rust.contains("pub struct Device {") && g.rust.contains("pub const CONFIG: NodeConfig"));
/// assert_eq!(g.left_out.iter().map(|l| l.index).collect::<Vec<_>>(), [0x2002]);
/// ```
#[derive(Debug, Clone, Default)]
pub struct Generated {
    /// The Rust module's text.
    pub rust: String,
    /// Everything of the EDS's application objects (2000h–FFFFh) the module does not carry.
    pub left_out: Vec<LeftOut>,
}

impl Generated {
    fn leave_out_object(&mut self, o: &Object, why: &str) {
        let note = format!("{:04X}h {}: {why}; left out.", o.index, o.name);
        let _ = writeln!(self.rust, "    // {note}");
        self.left_out.push(LeftOut { index: o.index, sub: None, dropped: Dropped::Entry, why: why.into(), note });
    }

    fn leave_out(&mut self, e: &Entry, object: Option<&Object>, dropped: Dropped, why: String) {
        let (sub, name, at) = match object {
            Some(o) => (None, &o.name, format!("{:04X}h", o.index)),
            None => (Some(e.sub), &e.name, format!("{:04X}h:{:02X}", e.index, e.sub)),
        };
        let note = match dropped {
            Dropped::Entry => format!("{at} {name}: {why}; left out."),
            Dropped::Default => format!("{at} {name}: default {} not carried ({why}).", show(&e.default)),
            Dropped::Limits => format!("{at} {name}: limits {}..{} not carried ({why}).", show(&e.low), show(&e.high)),
            Dropped::Access => format!("{at} {name}: access {} not carried ({why}).", e.access.as_str()),
            Dropped::PdoMapping => format!("{at} {name}: PDO mapping not carried ({why})."),
        };
        let _ = writeln!(self.rust, "    // {note}");
        self.left_out.push(LeftOut { index: e.index, sub, dropped, why, note });
    }
}

fn show(v: &Option<String>) -> &str {
    v.as_deref().unwrap_or("")
}

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

/// The length of a string's default in the capacity's unit (bytes; UTF-16 units for a UNICODE_STRING; an
/// OCTET_STRING's hex pairs), 0 without one.
fn text_len(entry: &Entry) -> usize {
    let Some(d) = entry.default.as_deref() else { return 0 };
    match entry.data_type {
        0x000A => octets(d).map_or(d.len(), |_| d.split_whitespace().map(str::len).sum::<usize>() / 2),
        0x000B => d.encode_utf16().count(),
        _ => d.len(),
    }
}

/// The capacity of a string mapped to PDOs that fits a PDO's 8 bytes (a mapped string moves its whole
/// capacity): 8 bytes, 4 UTF-16 units.
fn pdo_text_capacity(entry: &Entry) -> usize {
    if entry.data_type == 0x000B {
        4
    } else {
        8
    }
}

/// Whether a string marked PDO-mappable gets a capacity that fits a PDO: its default fits one.
fn text_maps(entry: &Entry) -> bool {
    entry.pdo_mapping && text_len(entry) <= pdo_text_capacity(entry)
}

/// A string's capacity: a PDO's worth when it maps ([`text_maps`]), else its default's length, at least 32.
fn text_capacity(entry: &Entry) -> usize {
    if text_maps(entry) {
        pdo_text_capacity(entry)
    } else {
        text_len(entry).max(32)
    }
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

/// A Rust literal for a numeric EDS value of `entry`'s type, `None` when it is not one (a `$NODEID`
/// expression, text). Signed integers written in hex are two's complement ([`eval_typed`]).
fn number_literal(text: &str, entry: &Entry) -> Option<String> {
    if is_float(entry) {
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
    eval_typed(text, entry.data_type, 0).map(|v| v.to_string())
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

/// An OCTET_STRING default (hex pairs, CiA 306) as the derive's `default` literal: the text whose bytes
/// they are when UTF-8 (`"ABCD"` for 41424344), else a byte string (`b"\xab\xcd"` for ABCD).
fn octets(hex: &str) -> Result<String, &'static str> {
    let hex: String = hex.split_whitespace().collect();
    if hex.len() % 2 != 0 {
        return Err("not hex pairs");
    }
    let bytes = (0..hex.len())
        .step_by(2)
        .map(|i| hex.get(i..i + 2).and_then(|b| u8::from_str_radix(b, 16).ok()))
        .collect::<Option<Vec<u8>>>()
        .ok_or("not hex pairs")?;
    Ok(match String::from_utf8(bytes) {
        Ok(text) => quote(&text),
        Err(e) => format!("b\"{}\"", e.as_bytes().escape_ascii()),
    })
}

/// The attributes besides index/sub/name of a value (access, pdo, limits, default); what cannot be
/// written as an attribute is left out through `g` (`object` names the whole object for a VAR/array).
fn value_attrs(g: &mut Generated, e: &Entry, object: Option<&Object>, numeric: bool, default: Option<&str>) -> String {
    let mut a = format!(", access = {}", quote(e.access.as_str()));
    if let Some(p) = pdo(e) {
        if matches!(e.data_type, 0x0009..=0x000B) && !text_maps(e) {
            let why = "its default is longer than a PDO holds, and a mapped string moves its whole capacity";
            g.leave_out(e, object, Dropped::PdoMapping, why.into());
        } else {
            let _ = write!(a, ", pdo = {}", quote(p));
        }
    }
    if numeric {
        let mut missed = false;
        for (key, v) in [("min", &e.low), ("max", &e.high)] {
            match v.as_deref().map(|t| number_literal(t, e)) {
                Some(Some(lit)) => {
                    let _ = write!(a, ", {key} = {lit}");
                }
                Some(None) => missed = true,
                None => {}
            }
        }
        if missed {
            g.leave_out(e, object, Dropped::Limits, "not a number of the type".into());
        }
    } else if e.low.is_some() || e.high.is_some() {
        g.leave_out(e, object, Dropped::Limits, "limits apply to numbers only".into());
    }
    let Some(d) = default else { return a };
    let literal = match e.data_type {
        0x0001 => eval_default(d, 0).map(|v| (v != 0).to_string()).ok_or("not 0 or 1"),
        0x0009 | 0x000B => Ok(quote(d)),
        0x000A => octets(d),
        _ if numeric => number_literal(d, e).ok_or("not a number of the type, or relative to $NODEID"),
        _ => Err("a default of this type is not supported"),
    };
    match literal {
        Ok(lit) => {
            let _ = write!(a, ", default = {lit}");
        }
        Err(why) => g.leave_out(e, object, Dropped::Default, why.into()),
    }
    a
}

fn is_float(entry: &Entry) -> bool {
    matches!(entry.data_type, 0x0008 | 0x0011)
}

fn var(g: &mut Generated, o: &Object, e: &Entry) {
    if e.data_type == 0x000F {
        if e.access != Access::ReadWrite {
            g.leave_out(e, Some(o), Dropped::Access, "a derived DOMAIN is rw".into());
        }
        let mut attrs = String::new();
        if let Some(p) = pdo(e) {
            let _ = write!(attrs, ", pdo = {}", quote(p));
        }
        if let Some(d) = &e.default {
            // The EDS's text, shown again in the derived EDS; the node does not apply it (a DOMAIN's content
            // is its `Domain` implementation's), and nothing here reads it as hex pairs (`@ABCD` is none).
            let _ = writeln!(
                g.rust,
                "    // {:04X}h {}: the default is the EDS text only; the DOMAIN starts empty.",
                o.index, o.name
            );
            let _ = write!(attrs, ", eds_default = {}", quote(d));
        }
        let _ = writeln!(g.rust, "    #[od(index = 0x{:04X}, name = {}, domain{attrs})]", o.index, quote(&o.name));
        let _ = writeln!(g.rust, "    pub {}: DomainBuf<4096>,", ident(&o.name, o.index, None));
        return;
    }
    let Some((ty, numeric)) = rust_type(e) else {
        return g.leave_out_object(o, &format!("data type {:04X}h is not supported", e.data_type));
    };
    let attrs = value_attrs(g, e, Some(o), numeric, e.default.as_deref());
    let _ = writeln!(g.rust, "    #[od(index = 0x{:04X}, name = {}{attrs})]", o.index, quote(&o.name));
    let _ = writeln!(g.rust, "    pub {}: {ty},", ident(&o.name, o.index, None));
}

/// An ARRAY whose entries are alike (sub-indices 1..=n, one data type, access, PDO mapping, limits and
/// default) is an array field; any other is written as a record, one field per entry, which keeps every
/// entry as it is (the derived EDS then says RECORD for it).
fn array(g: &mut Generated, o: &Object) {
    let subs: Vec<&Entry> = o.entries.values().filter(|e| e.sub > 0).collect();
    let Some(first) = subs.first() else {
        return only_sub_zero(g, o);
    };
    let contiguous = subs.iter().enumerate().all(|(i, e)| usize::from(e.sub) == i + 1);
    let alike = subs.iter().all(|e| {
        (e.data_type, e.access, e.pdo_mapping, &e.low, &e.high, &e.default)
            == (first.data_type, first.access, first.pdo_mapping, &first.low, &first.high, &first.default)
    });
    let Some((ty, numeric)) = rust_type(first).filter(|_| contiguous && alike) else {
        return record(g, o);
    };
    let attrs = value_attrs(g, first, Some(o), numeric, first.default.as_deref()) + &count_access(g, o);
    let _ = writeln!(
        g.rust,
        "    #[od(index = 0x{:04X}, sub = 1..={}, name = {}{attrs})]",
        o.index,
        subs.len(),
        quote(&o.name)
    );
    let _ = writeln!(g.rust, "    pub {}: [{ty}; {}],", ident(&o.name, o.index, None), subs.len());
}

fn record(g: &mut Generated, o: &Object) {
    let mut first = true;
    for e in o.entries.values().filter(|e| e.sub > 0) {
        let Some((ty, numeric)) = rust_type(e) else {
            g.leave_out(e, None, Dropped::Entry, format!("data type {:04X}h is not supported", e.data_type));
            continue;
        };
        let record = if first { format!(", record = {}", quote(&o.name)) + &count_access(g, o) } else { String::new() };
        first = false;
        let attrs = value_attrs(g, e, None, numeric, e.default.as_deref());
        let _ = writeln!(
            g.rust,
            "    #[od(index = 0x{:04X}, sub = {}{record}, name = {}{attrs})]",
            o.index,
            e.sub,
            quote(&e.name)
        );
        let _ = writeln!(g.rust, "    pub {}: {ty},", ident(&e.name, o.index, Some(e.sub)));
    }
    if first {
        only_sub_zero(g, o);
    }
}

/// The `count_access` of an ARRAY or RECORD: `ro` when its sub-index 0 says so (CiA 306 has ro for a
/// `CompactSubObj` array), nothing for `const` (the derive's default); a writable count is left out (the
/// derived count is the fixed number of entries).
fn count_access(g: &mut Generated, o: &Object) -> String {
    match o.entries.get(&0).map(|e| (e, e.access)) {
        Some((_, Access::ReadOnly)) => ", count_access = \"ro\"".into(),
        Some((e, Access::ReadWrite | Access::WriteOnly)) => {
            g.leave_out(e, None, Dropped::Access, "a derived count is the fixed number of entries: ro or const".into());
            String::new()
        }
        _ => String::new(),
    }
}

/// An ARRAY or RECORD with no entry beyond sub-index 0 (sample.eds's 3010h ReadRawValue, a REAL32 at
/// sub-index 0): its one entry is written as a VAR, which holds the same entry at the same index and
/// sub-index (the derived EDS says VAR). One without any entry (sample.eds's 3003h: no `CompactSubObj`, no
/// sub sections) has nothing a dictionary could hold, not even the entry count CiA 301 gives every ARRAY.
fn only_sub_zero(g: &mut Generated, o: &Object) {
    match o.entries.get(&0) {
        Some(e) => {
            let kind = if o.kind == ObjectKind::Array { "ARRAY" } else { "RECORD" };
            let _ =
                writeln!(g.rust, "    // {:04X}h {}: a {kind} with sub-index 0 only, held as a VAR.", o.index, o.name);
            var(g, o, e);
        }
        None => g.leave_out_object(o, "no entries, not even sub-index 0: nothing to hold"),
    }
}

/// The Rust module for `eds`; `source` names the file in its header.
///
/// The application objects (2000h–FFFFh) become a struct with `#[derive(ObjectDictionary)]`, and
/// 1000h–1FFFh a `NodeConfig` (device type, identity, names, producer heartbeat time, PDO defaults). What is not carried
/// over is listed in the module docs, and by [`rust_module`] for a given file.
///
/// ```
/// use canopen_eds::{to_rust, Eds};
/// let eds = Eds::parse("[1000]\nParameterName=Device type\nDataType=7\nAccessType=ro\nDefaultValue=0x191\n\
///     [2001]\nParameterName=Setpoint\nDataType=3\nAccessType=rw\nLowLimit=-10\nHighLimit=10\nDefaultValue=0\n").unwrap();
/// let rust = to_rust(&eds, "dev.eds");
/// assert!(rust.contains("#[od(index = 0x2001, name = \"Setpoint\", access = \"rw\", min = -10, max = 10, default = 0)]"));
/// assert!(rust.contains("pub setpoint_2001: i16,"));
/// assert!(rust.contains("device_type: 401,"));
/// ```
pub fn to_rust(eds: &Eds, source: &str) -> String {
    rust_module(eds, source).rust
}

/// [`to_rust`], with the list of what the module leaves out of the application objects (each also a
/// comment in the module): what a round trip EDS → Rust → EDS may not find again.
///
/// ```
/// use canopen_eds::{rust_module, Dropped, Eds};
/// let eds = Eds::parse("[2001]\nParameterName=Complex\nDataType=0x40\n[2002]\nParameterName=Id\nDataType=7\nDefaultValue=$NODEID+1\n").unwrap();
/// let g = rust_module(&eds, "dev.eds");
/// let what: Vec<_> = g.left_out.iter().map(|l| (l.index, l.dropped)).collect();
/// assert_eq!(what, [(0x2001, Dropped::Entry), (0x2002, Dropped::Default)]);
/// ```
pub fn rust_module(eds: &Eds, source: &str) -> Generated {
    let mut g = Generated::default();
    let out = &mut g.rust;
    let _ = writeln!(
        out,
        "//! Generated from {source} (CiA 306) by canopen-eds (`canopenctl eds-to-rust` or a build script's"
    );
    let _ = writeln!(
        out,
        "//! `canopen_eds::generate`): the application objects (2000h-FFFFh) as a derived object dictionary,"
    );
    let _ = writeln!(out, "//! and the node configuration from 1000h-1FFFh.");
    let _ = writeln!(out);
    let _ = writeln!(out, "#![allow(unused_imports, clippy::all)]");
    let _ = writeln!(out);
    let _ = writeln!(
        out,
        "use canopen_core::od::{{DomainBuf, OctetString, TimeDifference, TimeOfDay, UnicodeString, VisibleString}};"
    );
    let _ = writeln!(out, "use canopen_core::od::{{I24, I40, I48, I56, U24, U40, U48, U56}};");
    let _ = writeln!(out, "use canopen_core::pdo::PdoDefault;");
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
                    var(&mut g, o, e);
                }
            }
            ObjectKind::Array => array(&mut g, o),
            ObjectKind::Record => record(&mut g, o),
        }
    }
    let out = &mut g.rust;
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
    for (field, comm, map) in [("rpdo", 0x1400, 0x1600), ("tpdo", 0x1800, 0x1A00)] {
        pdo_defaults(&mut g, eds, field, comm, map);
    }
    let out = &mut g.rust;
    let _ = writeln!(out, "    ..NodeConfig::DEFAULT");
    let _ = writeln!(out, "}};");
    g
}

/// PDOs a node configuration carries the defaults of, each way (`canopen_core::Sizes`: RPDO 1-4, TPDO 1-4).
const CARRIED_PDOS: u16 = 4;

/// The mapping entries a derived node takes per PDO: canopen-core's `pdo::mapping::MAX_ENTRIES` without its
/// feature `pdo-mapping-64` (this crate does not depend on the core, so that a build script needs nothing but
/// std; a count limit 0..n with n below it is `max_mapped`, one at it limits nothing).
const MAX_MAPPED: usize = 8;

/// The CAN-ID of the pre-defined connection set for PDO `k` (0-based, 0..4; COB-05/06): 180h/200h + 100h·k.
fn predefined_pdo_id(tpdo: bool, k: u16) -> u32 {
    (if tpdo { 0x180u32 } else { 0x200 }) + 0x100 * u32::from(k)
}

/// The `rpdo`/`tpdo` field of the node configuration: a `PdoDefault` per PDO the EDS describes among the
/// first [`CARRIED_PDOS`] (communication parameter `comm` + k: COB-ID, transmission type, inhibit time,
/// event timer, SYNC start value; mapping parameter `map` + k: the entries up to sub-index 0's count). A
/// COB-ID relative to `$NODEID` is the pre-defined connection set only (anything else relative is left
/// out); mapping entries beyond the count with a value are left out (a default mapping is its entries).
fn pdo_defaults(g: &mut Generated, eds: &Eds, field: &str, comm: u16, map: u16) {
    let tpdo = field == "tpdo";
    let last = (0..CARRIED_PDOS).rev().find(|&k| eds.objects.contains_key(&(comm + k)));
    let Some(last) = last else { return };
    let value =
        |index: u16, sub: u8| eds.entry(index, sub).and_then(|e| Some((e, eval_default(e.default.as_deref()?, 0)?)));
    let mut items = Vec::new();
    for k in 0..=last {
        if !eds.objects.contains_key(&(comm + k)) {
            items.push("PdoDefault::UNUSED".to_owned());
            continue;
        }
        let mut fields = Vec::new();
        let mut max_mapped = None;
        let max = MAX_MAPPED;
        let count = value(map + k, 0).and_then(|(_, c)| usize::try_from(c).ok()).filter(|&c| c <= max);
        let subs = [(comm + k, [1u8, 2, 3, 5, 6].as_slice()), (map + k, [0u8, 1, 2, 3, 4, 5, 6, 7, 8].as_slice())];
        for (index, subs) in subs {
            // Limits at the type's bounds (sample.eds's transmission types 0..255) limit nothing.
            let limited = |e: &&Entry| {
                !no_limit(e.low.as_deref(), e.data_type, true) || !no_limit(e.high.as_deref(), e.data_type, false)
            };
            for e in subs.iter().filter_map(|&sub| eds.entry(index, sub)).filter(limited) {
                // The mapping count's 0..n (sample.eds: 0..4) is `max_mapped` when n is below MAX_ENTRIES
                // (what every derived node takes, for which the core's EDS states no limit) and the count.
                let high = e.high.as_deref().and_then(|h| eval_default(h, 0)).and_then(|h| usize::try_from(h).ok());
                let count_limits = index == map + k && e.sub == 0 && no_limit(e.low.as_deref(), e.data_type, true);
                match high.filter(|_| count_limits) {
                    Some(h) if h < max && count.unwrap_or(0) <= h => max_mapped = Some(h),
                    _ => g.leave_out(
                        e,
                        None,
                        Dropped::Limits,
                        "of the communication profile's parameters, only a mapping count's 0..n (n < 8, n >= the \
                         count) is carried"
                            .into(),
                    ),
                }
            }
        }
        if let Some((e, v)) = value(comm + k, 1) {
            let raw = u32::try_from(v).unwrap_or(0);
            let relative = e.default.as_deref().is_some_and(|d| d.to_ascii_uppercase().contains("$NODEID"));
            let id = raw & 0x7FF;
            let can_id = match (relative, k < 4 && id == predefined_pdo_id(tpdo, k)) {
                _ if raw & 0x3FFF_F800 != 0 => Err("bits 11-29 of the COB-ID (29-bit frame) set"),
                _ if !tpdo && raw & 0x4000_0000 != 0 => Err("bit 30 of an RPDO's COB-ID is reserved (PDO-07)"),
                (true, true) => Ok("None".to_owned()),
                (true, false) => Err("a node-ID-relative COB-ID other than the pre-defined connection set"),
                (false, _) => Ok(format!("Some(0x{id:03X})")),
            };
            match can_id {
                Ok(c) => {
                    fields.push(format!("valid: {}, can_id: {c}", raw & 0x8000_0000 == 0));
                    if raw & 0x4000_0000 != 0 {
                        fields.push("rtr_allowed: false".into()); // PDO-15: no remote request
                    }
                }
                Err(why) => g.leave_out(e, None, Dropped::Default, why.into()),
            }
        }
        for (sub, name, max) in [
            (2, "transmission_type", 0xFF),
            (3, "inhibit_100us", 0xFFFF),
            (5, "event_timer_ms", 0xFFFF),
            (6, "sync_start", 0xFF),
        ] {
            if let Some((_, v)) = value(comm + k, sub).filter(|&(_, v)| (0..=max).contains(&v)) {
                fields.push(format!("{name}: {v}"));
            }
        }
        let listed: Vec<(u8, &Entry, i128)> =
            (1..=max as u8).filter_map(|sub| value(map + k, sub).map(|(e, v)| (sub, e, v))).collect();
        let usable = count.filter(|&c| (1..=c).all(|sub| listed.iter().any(|&(s, _, _)| usize::from(s) == sub)));
        match usable {
            Some(count) => {
                let mapping: Vec<String> = listed
                    .iter()
                    .filter(|&&(sub, _, _)| usize::from(sub) <= count)
                    .map(|&(_, _, v)| format!("0x{:08X}", u32::try_from(v).unwrap_or(0)))
                    .collect();
                for &(_, e, _) in listed.iter().filter(|&&(sub, _, v)| usize::from(sub) > count && v != 0) {
                    g.leave_out(e, None, Dropped::Default, "beyond the mapping's entry count".into());
                }
                fields.push(format!("mapping: &[{}]", mapping.join(", ")));
            }
            // No DefaultValue for the count (its type's zero, as for any entry) but entries 1..=n with
            // values (e35.eds's 1600h, whose count has only a ParameterValue): the entries, none mapped.
            None if eds.entry(map + k, 0).is_some_and(|e| e.default.is_none())
                && !listed.is_empty()
                && listed.iter().enumerate().all(|(i, &(sub, _, _))| usize::from(sub) == i + 1) =>
            {
                let last = listed.iter().rposition(|&(_, _, v)| v != 0).map_or(0, |i| i + 1);
                let mapping: Vec<String> = listed[..last]
                    .iter()
                    .map(|&(_, _, v)| format!("0x{:08X}", u32::try_from(v).unwrap_or(0)))
                    .collect();
                fields.push(format!("mapping: &[{}], count: Some(0)", mapping.join(", ")));
            }
            None => {
                // A count the listed entries do not fill, or entries with gaps: no default mapping.
                let why = "the mapping's entry count (sub-index 0) has no usable DefaultValue";
                if let Some(e) = eds.entry(map + k, 0).filter(|e| e.default.is_some()) {
                    g.leave_out(e, None, Dropped::Default, why.into());
                }
                for &(_, e, _) in listed.iter().filter(|&&(_, _, v)| v != 0) {
                    g.leave_out(e, None, Dropped::Default, why.into());
                }
            }
        }
        fields.extend(max_mapped.map(|h| format!("max_mapped: {h}")));
        items.push(if fields.is_empty() {
            "PdoDefault::EVENT".to_owned()
        } else {
            format!("PdoDefault {{ {}, ..PdoDefault::EVENT }}", fields.join(", "))
        });
    }
    let out = &mut g.rust;
    let _ = writeln!(out, "    {field}: &[");
    for i in items {
        let _ = writeln!(out, "        {i},");
    }
    let _ = writeln!(out, "    ],");
}

#[cfg(test)]
mod tests {
    use super::*;

    /// PDO defaults (1400h-1BFFh) into the node configuration: a pre-defined COB-ID as `None`, a fixed one
    /// as itself, an invalid one as `valid: false`, a TPDO's bit 30 as `rtr_allowed: false`, the mapping up
    /// to its count, a count's limits 0..4 as `max_mapped`; what a `PdoDefault` cannot hold (bit 30 of an
    /// RPDO, an entry beyond the count, other limits) is left out and listed. The round trip
    /// of these through the core's EDS writer runs in tests/eds_to_rust.rs and tests/eds_real.rs.
    #[test]
    fn pdo_defaults_go_into_the_node_configuration() {
        let eds = Eds::parse(
            "[1400]\nObjectType=0x9\n[1400sub1]\nDataType=7\nDefaultValue=$NODEID+0x200\n\
             [1400sub2]\nDataType=5\nDefaultValue=1\nLowLimit=0\nHighLimit=240\n\
             [1401]\nObjectType=0x9\n[1401sub1]\nDataType=7\nDefaultValue=0x80000321\n\
             [1401sub2]\nDataType=5\nDefaultValue=254\nLowLimit=0x0\nHighLimit=255\n\
             [1402]\nObjectType=0x9\n[1402sub1]\nDataType=7\nDefaultValue=$NODEID+0x40000400\n\
             [1600]\nObjectType=0x9\n[1600sub0]\nDataType=5\nDefaultValue=1\nLowLimit=0\nHighLimit=4\n\
             [1600sub1]\nDataType=7\nDefaultValue=0x20000108\n[1600sub2]\nDataType=7\nDefaultValue=0x20010108\n\
             [1601]\nObjectType=0x9\n[1601sub0]\nDataType=5\nDefaultValue=0\nLowLimit=0\nHighLimit=8\n\
             [1602]\nObjectType=0x9\n[1602sub0]\nDataType=5\nParameterValue=2\n\
             [1602sub1]\nDataType=7\nDefaultValue=0x60FF0020\n[1602sub2]\nDataType=7\nDefaultValue=0\n\
             [1800]\nObjectType=0x9\n[1800sub1]\nDataType=7\nDefaultValue=$NODEID+0x40000180\n\
             [1800sub5]\nDataType=6\nDefaultValue=100\n",
        )
        .unwrap();
        let g = rust_module(&eds, "pdo.eds");
        assert!(g.rust.contains("use canopen_core::pdo::PdoDefault;"));
        assert!(
            g.rust.contains(
                "PdoDefault { valid: true, can_id: None, transmission_type: 1, mapping: &[0x20000108], max_mapped: 4, \
             ..PdoDefault::EVENT },"
            ),
            "{}",
            g.rust
        );
        assert!(
            g.rust.contains(
                "PdoDefault { valid: false, can_id: Some(0x321), transmission_type: 254, mapping: &[], ..PdoDefault::EVENT },"
            ),
            "{}",
            g.rust
        );
        // e35.eds's shape: a count without DefaultValue (zero), entries with values: kept, none mapped.
        assert!(
            g.rust.contains("PdoDefault { mapping: &[0x60FF0020], count: Some(0), ..PdoDefault::EVENT },"),
            "{}",
            g.rust
        );
        assert!(
            g.rust.contains(
                "tpdo: &[\n        PdoDefault { valid: true, can_id: None, rtr_allowed: false, event_timer_ms: 100, \
                 ..PdoDefault::EVENT },"
            ),
            "{}",
            g.rust
        );
        let left: Vec<_> = g.left_out.iter().map(|l| (l.index, l.sub, l.dropped)).collect();
        assert_eq!(
            left,
            [
                (0x1400, Some(2), Dropped::Limits), // 0..240; 1401h:02's 0..255 is UNSIGNED8's range: none
                (0x1600, Some(2), Dropped::Default), // beyond the count of 1
                (0x1601, Some(0), Dropped::Limits), // 0..8: every derived node's, stated nowhere
                (0x1402, Some(1), Dropped::Default), // bit 30 of an RPDO: reserved
            ]
        );
    }

    /// What python canopen's real files (tests/eds_real.rs) showed: signed limits in two's complement hex,
    /// an ARRAY whose entries differ in access and default, strings and a DOMAIN marked PDO-mappable (one
    /// string's default too long for a PDO), a DOMAIN default that is no hex pairs, an OCTET_STRING
    /// default in hex pairs, a UNICODE_STRING default, a RECORD with nothing beyond sub-index 0 (a VAR) and
    /// an ARRAY without entries (left out).
    const REAL: &str = "\
[3030]
ParameterName=Negative
DataType=0x04
AccessType=rw
HighLimit=0xFFFFFFFF
LowLimit=0x80000000

[3040]
ParameterName=Range
DataType=0x15
AccessType=rw
HighLimit=0x000000000000000A
LowLimit=0xFFFFFFFFFFFFFFF6

[20C2]
ParameterName=Driver temperature
ObjectType=0x8

[20C2sub0]
DataType=0x0005
AccessType=const
DefaultValue=0x2

[20C2sub1]
ParameterName=Actual
DataType=0x0004
AccessType=ro
PDOMapping=0x1

[20C2sub2]
ParameterName=Max
DataType=0x0004
AccessType=rw
DefaultValue=85000

[2009]
ParameterName=Text
DataType=0x0009
AccessType=rw
DefaultValue=ABCD
PDOMapping=1

[200A]
ParameterName=Octets
DataType=0x000A
AccessType=rw
DefaultValue=41424344
PDOMapping=1

[200D]
ParameterName=Long text
DataType=0x0009
AccessType=ro
DefaultValue=more than a PDO
PDOMapping=1

[200F]
ParameterName=Blob
DataType=0x000F
AccessType=rw
DefaultValue=@ABCD
PDOMapping=1

[200C]
ParameterName=Raw octets
DataType=0x000A
AccessType=rw
DefaultValue=ABCD

[200B]
ParameterName=Unicode
DataType=0x000B
AccessType=rw
DefaultValue=abc\u{2713}
PDOMapping=1

[3010]
ParameterName=ReadRawValue
ObjectType=0x9

[3010Sub0]
ParameterName=Temperature
DataType=0x0008
AccessType=ro

[3011]
ParameterName=Valve % open
ObjectType=0x8
DataType=0x0008
AccessType=rw

[3050]
ParameterName=Compact
ObjectType=0x8
CompactSubObj=2
DataType=0x0006
AccessType=ro

[3060]
ParameterName=Writable count
ObjectType=0x9

[3060sub0]
DataType=0x0005
AccessType=rw
DefaultValue=1

[3060sub1]
ParameterName=Only
DataType=0x0005
AccessType=rw
";

    #[test]
    fn real_world_shapes_generate() {
        let g = rust_module(&Eds::parse(REAL).unwrap(), "real.eds");
        let has = |s: &str| assert!(g.rust.contains(s), "no `{s}` in:\n{}", g.rust);
        has("name = \"Negative\", access = \"rw\", min = -2147483648, max = -1)]");
        has("name = \"Range\", access = \"rw\", min = -10, max = 10)]");
        has("#[od(index = 0x20C2, sub = 1, record = \"Driver temperature\", name = \"Actual\", access = \"ro\", pdo = \"tpdo\")]");
        has("#[od(index = 0x20C2, sub = 2, name = \"Max\", access = \"rw\", default = 85000)]");
        // Mapped strings: a capacity a PDO holds (8 bytes, 4 UTF-16 units); unmapped ones at least 32.
        has("name = \"Text\", access = \"rw\", pdo = \"both\", default = \"ABCD\")]\n    pub text_2009: VisibleString<8>,");
        has("name = \"Octets\", access = \"rw\", pdo = \"both\", default = \"ABCD\")]\n    pub octets_200a: OctetString<8>,");
        has("name = \"Raw octets\", access = \"rw\", default = b\"\\xab\\xcd\")]\n    pub raw_octets_200c: OctetString<32>,");
        has("name = \"Unicode\", access = \"rw\", pdo = \"both\", default = \"abc\u{2713}\")]\n    pub unicode_200b: UnicodeString<4>,");
        has("// 200Dh Long text: PDO mapping not carried (its default is longer than a PDO holds");
        has("name = \"Long text\", access = \"ro\", default = \"more than a PDO\")]\n    pub long_text_200d: VisibleString<32>,");
        // A DOMAIN: mapped, and its default as the EDS text (no hex pairs: nothing else could hold it).
        has("// 200Fh Blob: the default is the EDS text only; the DOMAIN starts empty.\n    \
             #[od(index = 0x200F, name = \"Blob\", domain, pdo = \"both\", eds_default = \"@ABCD\")]");
        let left: Vec<_> = g.left_out.iter().map(|l| (l.index, l.sub, l.dropped)).collect();
        assert_eq!(
            left,
            [(0x200D, None, Dropped::PdoMapping), (0x3011, None, Dropped::Entry), (0x3060, Some(0), Dropped::Access)]
        );
        has("// 3010h ReadRawValue: a RECORD with sub-index 0 only, held as a VAR.\n    \
             #[od(index = 0x3010, name = \"ReadRawValue\", access = \"ro\")]\n    pub readrawvalue_3010: f32,");
        has("// 3011h Valve % open: no entries, not even sub-index 0: nothing to hold; left out.");
        // Sub-index 0's access: ro as CompactSubObj implies (count_access), const as the derive's default
        // (20C2h), a writable count left out.
        has("#[od(index = 0x3050, sub = 1..=2, name = \"Compact\", access = \"ro\", count_access = \"ro\")]");
        has("#[od(index = 0x20C2, sub = 1, record = \"Driver temperature\", name = \"Actual\", access = \"ro\", pdo = \"tpdo\")]");
        has("// 3060h:00 : access rw not carried (a derived count is the fixed number of entries: ro or const).");
    }
}
