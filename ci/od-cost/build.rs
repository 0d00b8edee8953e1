//! Writes `$OUT_DIR/dict.rs`: the struct `Dict` of the dictionary OD_COST names.
//!
//! - `base`: the reference dictionary (one UNSIGNED32 VAR with a default, one ARRAY of 4 × UNSIGNED16, one
//!   RECORD of UNSIGNED8/UNSIGNED16/UNSIGNED32, one VISIBLE_STRING), so that every kind's generic code is
//!   already in the image;
//! - `var:N`, `array:N`, `record:N`, `string:N`: the base plus N more objects of that kind (at 3000h..);
//! - `one`: a dictionary of one UNSIGNED8 VAR (the floor a generated module is measured against);
//! - with OD_COST_COMPACT=1 the struct is `#[od(compact)]` (the dictionary as data); with 2 it is
//!   `#[od(compact, zerocopy)]` (reached by offset): `repr(C)`, zerocopy's derives, the fields ordered by
//!   alignment and the tail padded, and no string in the base (a string has no byte view; `string:N`
//!   is refused);
//! - `file:PATH`: `canopenctl eds-to-rust` output (its `Device` struct becomes `Dict`; the node
//!   configuration it also holds is not used, so only the application dictionary differs).
use std::fmt::Write;

fn main() {
    println!("cargo:rerun-if-env-changed=OD_COST");
    println!("cargo:rerun-if-env-changed=OD_COST_COMPACT");
    let spec = std::env::var("OD_COST").unwrap_or_else(|_| "base".into());
    let out = std::path::PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    let layout = std::env::var("OD_COST_COMPACT").unwrap_or_default();
    let mut src = generate(&spec, layout == "2").unwrap_or_else(|e| panic!("OD_COST={spec}: {e}"));
    // OD_COST_COMPACT=1: the struct asks for the dictionary as data (`#[od(compact)]`); 2: reached by
    // offset (generate wrote the zerocopy attributes, or the file came from `eds-to-rust --layout zerocopy`).
    if layout == "1" {
        src = src.replacen("pub struct Dict", "#[od(compact)]\npub struct Dict", 1);
    }
    std::fs::write(out.join("dict.rs"), src).expect("OUT_DIR is writable");
}

fn generate(spec: &str, zerocopy: bool) -> Result<String, String> {
    if let Some(path) = spec.strip_prefix("file:") {
        println!("cargo:rerun-if-changed={path}");
        let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
        // Inner attributes cannot stand in an included file; the struct is renamed.
        let body: String = text
            .lines()
            .filter(|l| !l.starts_with("#![") && !l.starts_with("//!"))
            .map(|l| l.replace("pub struct Device", "pub struct Dict").replace("impl Default for Device", "impl Default for Dict") + "\n")
            .collect();
        return Ok(body);
    }
    let mut s = String::new();
    if spec == "one" {
        s += "    #[od(index = 0x2000, access = \"rw\", default = 1)]\n    pub one: u8,\n";
        return Ok(wrap(&s, zerocopy));
    }
    s += "    #[od(index = 0x2000, access = \"rw\", pdo = \"both\", default = 7)]\n    pub var: u32,\n";
    s += "    #[od(index = 0x2001, sub = 1..=4, access = \"rw\", pdo = \"both\", default = 3)]\n    pub array: [u16; 4],\n";
    s += "    #[od(index = 0x2002, sub = 1, record = \"R\", access = \"rw\", default = 1)]\n    pub r1: u8,\n";
    s += "    #[od(index = 0x2002, sub = 2, access = \"rw\", default = 2)]\n    pub r2: u16,\n";
    s += "    #[od(index = 0x2002, sub = 3, access = \"rw\", default = 3)]\n    pub r3: u32,\n";
    if !zerocopy {
        s += "    #[od(index = 0x2003, access = \"rw\", default = \"abc\")]\n    pub text: VisibleString<16>,\n";
    }
    let (kind, n) = match spec.split_once(':') {
        Some((k, n)) => (k, n.parse::<u32>().map_err(|e| e.to_string())?),
        None if spec == "base" => ("base", 0),
        None => return Err("expected base, one, var:N, array:N, record:N, string:N or file:PATH".into()),
    };
    for i in 0..n {
        let index = 0x3000 + i;
        match kind {
            "var" => writeln!(s, "    #[od(index = {index:#06x}, access = \"rw\", pdo = \"both\", default = {})]\n    pub v{i}: u32,", i + 1),
            "array" => writeln!(s, "    #[od(index = {index:#06x}, sub = 1..=4, access = \"rw\", pdo = \"both\", default = {})]\n    pub a{i}: [u16; 4],", i + 1),
            "record" => writeln!(
                s,
                "    #[od(index = {index:#06x}, sub = 1, record = \"R{i}\", access = \"rw\", default = 1)]\n    pub r{i}a: u8,\n    \
                 #[od(index = {index:#06x}, sub = 2, access = \"rw\", default = 2)]\n    pub r{i}b: u16,\n    \
                 #[od(index = {index:#06x}, sub = 3, access = \"rw\", default = 3)]\n    pub r{i}c: u32,"
            ),
            "string" if zerocopy => return Err("a string has no byte view (OD_COST_COMPACT=2)".into()),
            "string" => writeln!(s, "    #[od(index = {index:#06x}, access = \"rw\", default = \"s{i}\")]\n    pub s{i}: VisibleString<16>,"),
            _ => return Err(format!("unknown kind {kind}")),
        }
        .map_err(|e| e.to_string())?;
    }
    Ok(wrap(&s, zerocopy))
}

/// The struct `Dict` around `fields` (pairs of an `#[od]` line and a `pub name: type,` line); with
/// `zerocopy`, `#[od(compact, zerocopy)]` with the fields ordered by alignment and the tail padded.
fn wrap(fields: &str, zerocopy: bool) -> String {
    let mut s = String::from("use canopen_core::od::VisibleString;\nuse canopen_od_derive::ObjectDictionary;\n");
    if !zerocopy {
        return s + "#[derive(ObjectDictionary, Default)]\npub struct Dict {\n" + fields + "}\n";
    }
    // Ordered by alignment with the tail padded, as `eds-to-rust --layout zerocopy` writes it.
    let body = canopen_eds::byte_view_fields(fields.trim_end()).unwrap_or_else(|why| panic!("no byte view: {why}"));
    // Zeroed in one `memset` rather than a store per field (the derived Default): the node gives every
    // entry its default at boot anyway (Reset Application, NMT-04), so this is what such a firmware writes.
    s += "impl Default for Dict {\n    fn default() -> Self {\n        <Self as zerocopy::FromZeros>::new_zeroed()\n    }\n}\n";
    s += "#[derive(ObjectDictionary, zerocopy::IntoBytes, zerocopy::FromBytes, zerocopy::Immutable)]\n";
    s += "#[repr(C)]\n#[od(compact, zerocopy)]\npub struct Dict {\n";
    s + &body + "\n}\n"
}
