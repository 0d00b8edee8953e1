//! The layout of the generated dictionary struct: which of the derive's three ways of serving it the
//! module asks for (`#[derive(ObjectDictionary)]` alone, `#[od(compact)]`, `#[od(compact, zerocopy)]`), and
//! for the last, a field order without padding.
//!
//! `#[od(compact, zerocopy)]` reaches each value by its offset in the struct's bytes, which zerocopy's
//! `IntoBytes`/`FromBytes` give only for a `#[repr(C)]` struct of plain numbers with no padding. So the
//! fields are ordered by alignment, largest first (every offset is then a multiple of its field's
//! alignment), and a `_pad` array fills the tail up to the struct's alignment. A module with a field of any
//! other type (a string, a DOMAIN, a BOOLEAN, a 24-bit integer) cannot have it, and gets `#[od(compact)]`
//! with a comment saying which field stood in the way.

use crate::codegen::{rust_module, Generated};
use crate::eds::Eds;

/// How the generated `Device` struct is served (see the derive's docs, `canopen_od_derive`).
///
/// ```
/// use canopen_eds::{rust_module_as, Eds, StructLayout};
/// let eds = Eds::parse("[2000]\nParameterName=Flag\nDataType=5\nAccessType=rw\n\
///     [2001]\nParameterName=Position\nDataType=4\nAccessType=rw\n").unwrap();
/// let g = rust_module_as(&eds, "dev.eds", StructLayout::Zerocopy);
/// assert!(g.rust.contains("#[od(compact, zerocopy)]") && g.rust.contains("#[repr(C)]"));
/// // The INTEGER32 first, then the UNSIGNED8, then three bytes of padding.
/// let position = g.rust.find("pub position_2001: i32,").unwrap();
/// assert!(position < g.rust.find("pub flag_2000: u8,").unwrap());
/// assert!(g.rust.contains("pub _pad: [u8; 3],"));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum StructLayout {
    /// `#[derive(ObjectDictionary)]`: match arms per entry (the fewest instructions per access, the most
    /// flash per object).
    #[default]
    Code,
    /// `#[od(compact)]`: the dictionary as tables, one accessor arm per field.
    Compact,
    /// `#[od(compact, zerocopy)]`: tables only, each field reached by its offset (the least flash); needs
    /// `zerocopy` with its `derive` feature in the crate that includes the module. Falls back to
    /// [`Compact`](Self::Compact) when a field has no byte view (a string, a DOMAIN, a BOOLEAN, a 24-bit
    /// integer).
    Zerocopy,
}

impl core::str::FromStr for StructLayout {
    type Err = String;

    /// `code`, `compact` or `zerocopy`.
    ///
    /// ```
    /// use canopen_eds::StructLayout;
    /// assert_eq!("zerocopy".parse(), Ok(StructLayout::Zerocopy));
    /// assert!("fast".parse::<StructLayout>().is_err());
    /// ```
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "code" => Ok(Self::Code),
            "compact" => Ok(Self::Compact),
            "zerocopy" => Ok(Self::Zerocopy),
            _ => Err(format!("unknown layout {s:?}: expected code, compact or zerocopy")),
        }
    }
}

/// The body of a `#[od(compact, zerocopy)]` struct from `body` (fields as `rust_module` writes them: each
/// field's comments and `#[od(...)]` lines, then its `    pub name: type,` line): the fields ordered by
/// alignment, largest first, so that none is padded, and a `_pad` field filling the tail up to the
/// struct's alignment. `Err` says which field has no byte view (a string, a DOMAIN, a `bool`, a 24-bit
/// integer). What the generated modules and the flash measurement of the layout (`ci/od-cost`) share.
///
/// ```
/// let body = "    #[od(index = 0x2000)]\n    pub flag: u8,\n    #[od(index = 0x2001, sub = 1..=3)]\n    pub pair: [u16; 3],\n    \
///             #[od(index = 0x2002)]\n    pub speed: u32,";
/// let ordered = canopen_eds::byte_view_fields(body).unwrap();
/// // The UNSIGNED32 first, then the UNSIGNED16s, then the byte (4 + 6 + 1): 1 byte of padding to 4.
/// assert!(ordered.find("pub speed: u32,").unwrap() < ordered.find("pub pair: [u16; 3],").unwrap());
/// assert!(ordered.find("pub pair: [u16; 3],").unwrap() < ordered.find("pub flag: u8,").unwrap());
/// assert!(ordered.ends_with("pub _pad: [u8; 1],"));
/// assert!(canopen_eds::byte_view_fields("    #[od(index = 0x2000)]\n    pub on: bool,").is_err());
/// ```
pub fn byte_view_fields(body: &str) -> Result<String, String> {
    let chunks = fields(body);
    let aligns = chunks.iter().map(|c| alignment(c)).collect::<Result<Vec<usize>, String>>()?;
    let mut order: Vec<(usize, String)> = aligns.into_iter().zip(chunks).collect();
    order.sort_by_key(|(a, _)| core::cmp::Reverse(*a));
    let size: usize = order.iter().map(|(_, c)| byte_size(c)).sum();
    let align = order.iter().filter(|(_, c)| field_type(c).is_some()).map(|(a, _)| *a).max().unwrap_or(1);
    let pad = (align - size % align) % align;
    let mut chunks: Vec<String> = order.into_iter().map(|(_, c)| c).collect();
    if pad > 0 || chunks.is_empty() {
        // A struct without fields would have no bytes to view; one byte keeps the impl the same.
        let n = if chunks.is_empty() { 1 } else { pad };
        chunks.push(format!(
            "    /// Not in the dictionary: the bytes a `repr(C)` struct would pad (zerocopy's byte view has none).\n    pub _pad: [u8; {n}],"
        ));
    }
    Ok(chunks.join("\n"))
}

/// [`rust_module`] with the struct in `layout`.
///
/// ```
/// use canopen_eds::{rust_module_as, Eds, StructLayout};
/// let eds = Eds::parse("[2000]\nParameterName=Name\nDataType=9\nAccessType=rw\nDefaultValue=abc\n").unwrap();
/// let g = rust_module_as(&eds, "dev.eds", StructLayout::Zerocopy);
/// // A VISIBLE_STRING has no byte view: compact, and the reason as a comment.
/// assert!(g.rust.contains("#[od(compact)]") && g.rust.contains("name_2000: VisibleString<32>"));
/// assert!(g.rust.contains("has no byte view"));
/// ```
pub fn rust_module_as(eds: &Eds, source: &str, layout: StructLayout) -> Generated {
    let mut g = rust_module(eds, source);
    if layout == StructLayout::Code {
        return g;
    }
    let Some((head, rest)) = g.rust.split_once(STRUCT_START) else {
        return g;
    };
    let Some((body, tail)) = rest.split_once("\n}\n") else {
        return g;
    };
    let mut derive = String::from("#[derive(ObjectDictionary, Debug, Default)]\n#[od(compact)]\n");
    let mut after = String::new();
    let mut fields_text = body.to_string();
    match (layout, byte_view_fields(body)) {
        (StructLayout::Zerocopy, Ok(ordered)) => {
            fields_text = ordered;
            // `Default` zeroes the struct in one `memset` (a derived one stores each field: 4 B of code per
            // UNSIGNED32 on a Cortex-M); the node gives every entry its default at boot (NMT-04) anyway.
            derive = String::from(
                "#[derive(ObjectDictionary, Debug, zerocopy::IntoBytes, zerocopy::FromBytes, zerocopy::Immutable)]\n\
                 #[repr(C)]\n#[od(compact, zerocopy)]\n",
            );
            after = String::from(
                "\nimpl Default for Device {\n    /// All zero (one `memset`): the node applies the defaults at boot.\n    \
                 fn default() -> Self {\n        <Self as zerocopy::FromZeros>::new_zeroed()\n    }\n}\n",
            );
        }
        (StructLayout::Zerocopy, Err(why)) => {
            derive = format!("// Not `#[od(compact, zerocopy)]`: {why}.\n{derive}");
        }
        _ => {}
    }
    g.rust = format!("{head}{derive}pub struct Device {{\n{fields_text}\n}}\n{after}{tail}");
    g
}

/// How the plain generator starts the struct.
const STRUCT_START: &str = "#[derive(ObjectDictionary, Debug, Default)]\npub struct Device {\n";

/// The struct's body as one text per field: its comments, its `#[od(...)]` and its `pub name: type,` line.
/// A comment after the last field (an object left out at the end) stays a chunk of its own.
fn fields(body: &str) -> Vec<String> {
    let mut chunks = Vec::new();
    let mut current: Vec<&str> = Vec::new();
    for line in body.lines() {
        current.push(line);
        if line.starts_with("    pub ") {
            chunks.push(current.join("\n"));
            current.clear();
        }
    }
    if !current.is_empty() {
        chunks.push(current.join("\n"));
    }
    chunks
}

/// The type of a field's chunk (`u32`, `[i16; 4]`), or `None` for a comment-only chunk.
fn field_type(chunk: &str) -> Option<&str> {
    let line = chunk.lines().last()?.strip_prefix("    pub ")?;
    Some(line.split_once(": ")?.1.trim_end_matches(','))
}

/// The alignment and size of a plain number type in `repr(C)` (on every target the core builds for).
fn plain(ty: &str) -> Option<(usize, usize)> {
    match ty {
        "u8" | "i8" => Some((1, 1)),
        "u16" | "i16" => Some((2, 2)),
        "u32" | "i32" | "f32" => Some((4, 4)),
        "u64" | "i64" | "f64" => Some((8, 8)),
        _ => None,
    }
}

/// The element type and the count of a field type (`[T; N]` or `T`).
fn element(ty: &str) -> (&str, usize) {
    match ty.strip_prefix('[').and_then(|t| t.strip_suffix(']')).and_then(|t| t.split_once("; ")) {
        Some((t, n)) => (t, n.parse().unwrap_or(0)),
        None => (ty, 1),
    }
}

/// The alignment of a chunk's field (a comment-only chunk: 8, so it keeps its place first of none), or why
/// it has no byte view.
fn alignment(chunk: &str) -> Result<usize, String> {
    let Some(ty) = field_type(chunk) else {
        return Ok(8);
    };
    let (t, _) = element(ty);
    plain(t).map(|(align, _)| align).ok_or_else(|| {
        let name = chunk.lines().last().unwrap_or("").trim().trim_start_matches("pub ");
        format!("the field `{}` has no byte view", name.trim_end_matches(','))
    })
}

/// The bytes of a chunk's field (0 for a comment-only chunk).
fn byte_size(chunk: &str) -> usize {
    field_type(chunk).map_or(0, |ty| {
        let (t, n) = element(ty);
        plain(t).map_or(0, |(_, size)| size) * n
    })
}
