//! `#[derive(ObjectDictionary)]`: a Rust struct becomes a CANopen object dictionary (and its EDS).
//!
//! ```
//! use canopen_core::od::{AbortCode, DomainBuf, ObjectDictionary};
//! use canopen_od_derive::ObjectDictionary;
//!
//! #[derive(ObjectDictionary, Default)]
//! struct App {
//!     /// ARRAY 6000h, subs 1..=8, sub 0 = 8 (const).
//!     #[od(index = 0x6000, sub = 1..=8, access = "ro", pdo = "tpdo", name = "Digital inputs")]
//!     inputs: [u8; 8],
//!     /// VAR 2001h with limits and a validation hook.
//!     #[od(index = 0x2001, access = "rw", pdo = "rpdo", min = -1000, max = 1000, default = 0,
//!          check = "check_setpoint")]
//!     setpoint: i16,
//!     /// RECORD 2100h: fields sharing an index with different sub-indices.
//!     #[od(index = 0x2100, sub = 1, record = "PID", name = "Kp")]
//!     kp: f32,
//!     #[od(index = 0x2100, sub = 2, name = "Ki")]
//!     ki: f32,
//!     /// A streamed DOMAIN (any type implementing `canopen_core::od::Domain`).
//!     #[od(index = 0x2200, domain)]
//!     firmware: DomainBuf<256>,
//!     /// A field without `#[od]` is not in the dictionary.
//!     scratch: u32,
//! }
//!
//! impl App {
//!     fn check_setpoint(&self, _sub: u8, v: &i16) -> Result<(), AbortCode> {
//!         if *v == 13 { Err(AbortCode::InvalidValue) } else { Ok(()) }
//!     }
//! }
//!
//! let mut app = App::default();
//! app.write(0x2001, 0, &500i16.to_le_bytes()).unwrap();
//! assert_eq!(app.setpoint, 500);
//! assert_eq!(app.write(0x2001, 0, &2000i16.to_le_bytes()), Err(AbortCode::ValueTooHigh));
//! assert_eq!(app.write(0x2001, 0, &13i16.to_le_bytes()), Err(AbortCode::InvalidValue));
//! assert_eq!(app.write(0x6000, 1, &[1]), Err(AbortCode::WriteOfReadOnly));
//! let mut b = [0u8; 1];
//! assert_eq!(app.read(0x6000, 0, 0, &mut b), Ok(1));
//! assert_eq!(b, [8]);
//! assert_eq!(App::OD_ENTRIES.len(), 9 + 1 + 3 + 1);
//! ```
//!
//! Field attribute keys (`#[od(...)]`):
//! - `index = 0x2000..` (required; 2000h–FFFFh: 0000h–1FFFh is refused, the core provides 1000h–1FFFh);
//! - `sub = n` (record member), `sub = a..=b` (array; must match the array length; default `1..=N`);
//! - `name = "..."` (ParameterName; default: the field name), `record = "..."` (the record's name);
//! - `access = "ro" | "wo" | "rw" | "rwr" | "rww" | "const"` (default `rw`; OD-08, OD-09);
//! - `pdo = "no" | "tpdo" | "rpdo" | "both"` (default `no`; PDO-33): a fixed-size type maps with its size;
//!   a string with its whole capacity, which must fit a PDO's 8 bytes (a compile error otherwise; a TPDO
//!   pads the current content with 00h, an RPDO writes all mapped bytes); a DOMAIN with the size its
//!   `Domain::size` gives when the mapping is checked, mappable only when that is 1 to 8 bytes (0604 0041h
//!   otherwise). The core checks the mapped length against that size and the PDO's 64 bits as for any
//!   entry (0604 0041h / 0604 0042h);
//! - `min = …`, `max = …`, `default = …` (literals; checked against each other and the type's range; an
//!   `OctetString<N>` default is a string literal, its UTF-8 bytes, or a byte string `b"\xAB\xCD"`);
//! - `domain` (the field implements `Domain` and is streamed);
//! - `eds_default = "..."` (a DOMAIN only): the text its EDS shows as `DefaultValue`, as it is (an
//!   imported EDS's may be no hex pairs, like python canopen's datatypes.eds `@ABCD`, which python canopen
//!   also keeps as raw text). The node does not apply it: a DOMAIN's content is its `Domain`
//!   implementation's, which `restore_defaults` leaves alone;
//! - `count_access = "ro" | "const"` (an array field or a record member: the access of the object's
//!   sub-index 00h, its fixed number of entries; default `const`);
//! - `check = "method"`: `fn(&self, sub: u8, new: &T) -> Result<(), AbortCode>` runs after the length and
//!   limit checks and before anything changes: return an abort code to refuse the value;
//! - `on_write = "method"`: `fn(&mut self, sub: u8)` runs after an accepted write (side effects).
//!
//! Struct attributes: `#[od(crate = "canopen::core")]` when `canopen_core` is reached through another
//! path (default `::canopen_core`); `#[od(write_events = false)]` when the application needs no
//! `Event::ObjectWritten` for SDO downloads of its entries (`ObjectDictionary::write_events`: it reads its
//! values, or reacts in `on_write`), which spares each download an event queued and polled;
//! `#[od(compact)]` for the dictionary as data (below).
//!
//! `#[od(compact)]` (issue 41, opt-in for now): instead of match arms per entry, the derive emits
//! `impl canopen_core::od::data::OdData`: a sorted `u16` index per row (or per object, and where its rows
//! start, when RECORDs are large), a 3-byte row per VAR, per ARRAY and per RECORD member that names one of
//! the dictionary's shapes (data type, access, PDO mapping, count, limits; the sub-index follows from the
//! row's place when the numbering is regular), the defaults and limit values as bytes, and one arm per field in the accessor of its
//! type (`&self` and `&mut self`); `ObjectDictionary` forwards to the core's one generic path
//! (`canopen_core::od::data`). Same answers on every SDO path (`canopen-core/tests/derived_access.rs`,
//! `tests/od_all_types.rs` with the test feature `od-compact-tests`). Flash per object
//! (`scripts/od-cost.sh`, thumbv7em, opt "s", LTO): UNSIGNED32 VAR with a default 11.0 B instead of 45.7 B,
//! ARRAY of 4 x UNSIGNED16 26.8 B instead of 201.6 B, RECORD of three 41.5 B instead of 149.9 B, python
//! canopen's e35.eds application 19,868 B instead of 39,258 B. The price: two jump tables per access
//! instead of one, so more instructions per frame (x86-64 callgrind, `scripts/bench-node.sh` with the
//! bench built with the test feature `od-compact-tests`, which makes its dictionaries compact: expedited
//! download 332 instead of 292, segmented upload 350.3 instead of 245.3, RPDO to 4 objects 648.5 instead
//! of 354.5, SYNC to 4 TPDOs 508.5 instead of 209.3 per bus frame; the compact figures measured before the
//! fourth flash diet), which is why it is not the default.
//!
//! `#[od(compact, zerocopy)]` (issue 41): the same tables, and no per-field code at all: each row holds its
//! field's `offset_of!`, and the core reaches every value through the struct's bytes, which zerocopy proves
//! sound (the core has no `unsafe`). The struct must be `#[repr(C)]`, free of padding, of plain numbers
//! (`i8`..`u64`, `f32`, `f64` and arrays of them: no `bool`, string or DOMAIN) and derive zerocopy's
//! `IntoBytes`, `FromBytes` and `Immutable` (the crate needs `zerocopy` with its `derive` feature); zerocopy's
//! derive says what stands in the way. `eds-to-rust --layout zerocopy` writes such a struct (fields ordered
//! by alignment, the tail padded). Construct it with `zerocopy::FromZeros::new_zeroed()` (one `memset`): the
//! node applies the defaults at boot (NMT-04). Flash per further object (`scripts/od-cost.sh`, the node a
//! static as in a firmware): UNSIGNED32 VAR 6.8 B (match arms 45.7, `compact` 11.0), ARRAY of 4 x UNSIGNED16
//! 9.1 B (201.6, 26.8), RECORD of three 17.6 B (149.9, 41.5), RAM the values alone; python canopen's e35.eds
//! application 6,668 B (39,258, 19,868; CANopenNode's layout ~11,400 B). Instructions per frame (`scripts/bench-node.sh`, x86-64):
//! expedited download 284 (default layout 292), RPDO to 4 objects 337.5 (353.5), SYNC to 4 TPDOs 212.5 per
//! bus frame (209.3): PDO handles hold the value's offset and size class, one jump table per value.
//!
//! Field types are recognised by name: `bool`, `i8`, `i16`, `i32`, `i64`, `u8`, `u16`, `u32`, `u64`,
//! `f32`, `f64`, `I24`, `I40`, `I48`, `I56`, `U24`, `U40`, `U48`, `U56`, `TimeOfDay`, `TimeDifference`,
//! `VisibleString<N>`, `OctetString<N>`, `UnicodeString<N>`, and `[T; N]` of those (ARRAY). Anything else
//! must be a `domain`. A type alias is not seen through; the generated code also asserts at compile time
//! that the type's `OdValue::DATA_TYPE` is the one the name implies.
//!
//! Generated (no heap, no `unsafe`, nothing in `.data`/`.bss`):
//! - `App::OD_ENTRIES: &[EntryDesc]` sorted by (index, sub) and `App::OD_OBJECTS: &[ObjectDesc]`
//!   (const, in `.rodata`), `App::OD_MAX_VALUE_SIZE` (largest non-DOMAIN value, to size an SDO buffer);
//! - `impl ObjectDictionary for App`: a binary search of the 4-byte keys `OD_KEYS` gives a position (on bare
//!   metal, a dictionary of 2 to 12 entries is scanned instead, `scan_key`: less flash), a `match` on the
//!   position reaches the field; PDO handles keep the position, so `pdo_read`/`pdo_write` do not search;
//!   one copy of the search per dictionary, and no write code for a read-only entry (`ro`/`const`: every
//!   write path, PDO handles included, answers 0601 0002h); `STREAMS` is whether a string or DOMAIN is
//!   writable and `SEGMENTED_UPLOADS` whether a readable entry has no fixed size of 1..=4 bytes, so that
//!   without one the SDO server builds no streamed-write or segmented-upload path;
//! - `impl OdDescribe for App` (for the EDS writer; its `object_index`, what store/restore walks, answers
//!   from a table of the indices alone, so a firmware that stores links neither names nor defaults);
//! - `restore_defaults` (NMT-04 Reset Application): each entry gets its `default`, or its type's
//!   `Default` when none is given; DOMAIN fields and fields without `#[od]` are left alone.
//!
//! Compile errors (pinned by the trybuild tests in `tests/ui/`): duplicate index/sub-index, a string
//! marked PDO-mappable whose capacity is more than 8 bytes, `eds_default` on anything but a DOMAIN, an index in 0000h–1FFFh, a default outside its limits (or min > max,
//! or a limit outside the type), a text default given as a byte string that is not UTF-8, an unsupported
//! field type, a malformed attribute.

mod emit;

use emit::{DataField, Kind};
use proc_macro::TokenStream;
use proc_macro2::{Span, TokenStream as Ts};
use quote::{quote, quote_spanned, ToTokens};
use syn::spanned::Spanned;
use syn::{parse_macro_input, Data, DeriveInput, Expr, ExprLit, ExprRange, Fields, Ident, Lit, LitStr, Type, UnOp};

/// Derives `ObjectDictionary` and `OdDescribe` for a struct; see the crate docs for the attributes.
#[proc_macro_derive(ObjectDictionary, attributes(od))]
pub fn derive_object_dictionary(input: TokenStream) -> TokenStream {
    let input = parse_macro_input!(input as DeriveInput);
    match expand(&input) {
        Ok(ts) => ts.into(),
        Err(e) => e.to_compile_error().into(),
    }
}

/// What the macro knows about a field's (element) type.
#[derive(Clone, Copy, PartialEq)]
enum Class {
    Bool,
    Signed(u32),
    Unsigned(u32),
    Real32,
    Real64,
    Time,
    Text,
    Bytes,
}

#[derive(Clone)]
struct ScalarType {
    dt: &'static str,
    class: Class,
    /// A fixed-size value (not a string or byte string): written inline, not streamed.
    fixed: bool,
}

fn scalar_type(ty: &Type) -> Option<ScalarType> {
    let Type::Path(p) = ty else { return None };
    let seg = p.path.segments.last()?;
    let name = seg.ident.to_string();
    let (dt, class) = match name.as_str() {
        "bool" => ("Boolean", Class::Bool),
        "i8" => ("Integer8", Class::Signed(8)),
        "i16" => ("Integer16", Class::Signed(16)),
        "I24" => ("Integer24", Class::Signed(24)),
        "i32" => ("Integer32", Class::Signed(32)),
        "I40" => ("Integer40", Class::Signed(40)),
        "I48" => ("Integer48", Class::Signed(48)),
        "I56" => ("Integer56", Class::Signed(56)),
        "i64" => ("Integer64", Class::Signed(64)),
        "u8" => ("Unsigned8", Class::Unsigned(8)),
        "u16" => ("Unsigned16", Class::Unsigned(16)),
        "U24" => ("Unsigned24", Class::Unsigned(24)),
        "u32" => ("Unsigned32", Class::Unsigned(32)),
        "U40" => ("Unsigned40", Class::Unsigned(40)),
        "U48" => ("Unsigned48", Class::Unsigned(48)),
        "U56" => ("Unsigned56", Class::Unsigned(56)),
        "u64" => ("Unsigned64", Class::Unsigned(64)),
        "f32" => ("Real32", Class::Real32),
        "f64" => ("Real64", Class::Real64),
        "TimeOfDay" => ("TimeOfDay", Class::Time),
        "TimeDifference" => ("TimeDifference", Class::Time),
        "VisibleString" => ("VisibleString", Class::Text),
        "UnicodeString" => ("UnicodeString", Class::Text),
        "OctetString" => ("OctetString", Class::Bytes),
        _ => return None,
    };
    let generic = !seg.arguments.is_empty();
    if generic != matches!(class, Class::Text | Class::Bytes) {
        return None;
    }
    let fixed = !matches!(class, Class::Text | Class::Bytes);
    Some(ScalarType { dt, class, fixed })
}

/// The bytes a string type holds when its capacity is an integer literal: `N` of `VisibleString<N>` and
/// `OctetString<N>`, `2·N` of `UnicodeString<N>` (UTF-16 units); `None` for a fixed-size type or a capacity
/// given otherwise (a named constant).
fn literal_capacity(ty: &Type, st: &ScalarType) -> Option<usize> {
    let Type::Path(p) = ty else { return None };
    let syn::PathArguments::AngleBracketed(args) = &p.path.segments.last()?.arguments else { return None };
    let n: usize = match args.args.first()? {
        syn::GenericArgument::Const(Expr::Lit(ExprLit { lit: Lit::Int(i), .. })) => i.base10_parse().ok()?,
        _ => return None,
    };
    Some(if st.dt == "UnicodeString" { n.checked_mul(2)? } else { n })
}

/// A literal from an attribute.
#[derive(Clone, Debug)]
enum ConstLit {
    Int(i128),
    Float(f64),
    Bool(bool),
    Str(String),
    /// A byte string literal (`b"\xAB\xCD"`): an OCTET_STRING default whose bytes need not be UTF-8.
    Bytes(Vec<u8>),
}

impl ConstLit {
    fn parse(e: &Expr) -> syn::Result<ConstLit> {
        match e {
            Expr::Lit(ExprLit { lit, .. }) => match lit {
                Lit::Int(i) => Ok(ConstLit::Int(i.base10_parse()?)),
                Lit::Float(f) => Ok(ConstLit::Float(f.base10_parse()?)),
                Lit::Bool(b) => Ok(ConstLit::Bool(b.value)),
                Lit::Str(s) => Ok(ConstLit::Str(s.value())),
                Lit::ByteStr(s) => Ok(ConstLit::Bytes(s.value())),
                _ => Err(syn::Error::new_spanned(e, "expected an integer, float, bool or string literal")),
            },
            Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => match ConstLit::parse(&u.expr)? {
                ConstLit::Int(i) => Ok(ConstLit::Int(-i)),
                ConstLit::Float(f) => Ok(ConstLit::Float(-f)),
                _ => Err(syn::Error::new_spanned(e, "only numbers can be negative")),
            },
            Expr::Group(g) => ConstLit::parse(&g.expr),
            Expr::Paren(p) => ConstLit::parse(&p.expr),
            _ => Err(syn::Error::new_spanned(e, "expected a literal")),
        }
    }

    fn as_f64(&self) -> Option<f64> {
        match *self {
            ConstLit::Int(i) => Some(i as f64),
            ConstLit::Float(f) => Some(f),
            ConstLit::Bool(b) => Some(f64::from(u8::from(b))),
            ConstLit::Str(_) | ConstLit::Bytes(_) => None,
        }
    }

    fn show(&self) -> String {
        match self {
            ConstLit::Int(i) => i.to_string(),
            ConstLit::Float(f) => f.to_string(),
            ConstLit::Bool(b) => b.to_string(),
            ConstLit::Str(s) => format!("{s:?}"),
            ConstLit::Bytes(b) => format!("b\"{}\"", b.escape_ascii()),
        }
    }
}

#[derive(Default)]
struct FieldAttr {
    index: Option<(u16, Span)>,
    sub: Option<SubSpec>,
    name: Option<String>,
    record: Option<String>,
    access: Option<(String, Span)>,
    pdo: Option<(String, Span)>,
    min: Option<(ConstLit, Expr)>,
    max: Option<(ConstLit, Expr)>,
    default: Option<(ConstLit, Expr)>,
    eds_default: Option<(String, Span)>,
    domain: bool,
    check: Option<Ident>,
    on_write: Option<Ident>,
    count_access: Option<(String, Span)>,
}

#[derive(Clone)]
enum SubSpec {
    One(u8, Span),
    Range(u8, u8, Span),
}

fn int_lit<T: std::str::FromStr>(e: &Expr, what: &str) -> syn::Result<T>
where
    T::Err: std::fmt::Display,
{
    match e {
        Expr::Lit(ExprLit { lit: Lit::Int(i), .. }) => {
            i.base10_parse().map_err(|_| syn::Error::new_spanned(e, format!("{what} out of range")))
        }
        _ => Err(syn::Error::new_spanned(e, format!("{what} must be an integer literal"))),
    }
}

fn str_lit(meta: &syn::meta::ParseNestedMeta) -> syn::Result<(String, Span)> {
    let s: LitStr = meta.value()?.parse()?;
    Ok((s.value(), s.span()))
}

fn parse_field_attr(attr: &syn::Attribute) -> syn::Result<FieldAttr> {
    let mut a = FieldAttr::default();
    attr.parse_nested_meta(|meta| {
        let key = meta.path.get_ident().map(|i| i.to_string()).unwrap_or_default();
        match key.as_str() {
            "index" => {
                let e: Expr = meta.value()?.parse()?;
                a.index = Some((int_lit(&e, "index")?, e.span()));
            }
            "sub" => {
                let e: Expr = meta.value()?.parse()?;
                a.sub = Some(match &e {
                    Expr::Range(ExprRange {
                        start: Some(s),
                        end: Some(t),
                        limits: syn::RangeLimits::Closed(_),
                        ..
                    }) => SubSpec::Range(int_lit(s, "sub-index")?, int_lit(t, "sub-index")?, e.span()),
                    Expr::Range(_) => {
                        return Err(syn::Error::new_spanned(&e, "use an inclusive range: `sub = 1..=N`"));
                    }
                    _ => SubSpec::One(int_lit(&e, "sub-index")?, e.span()),
                });
            }
            "name" => a.name = Some(str_lit(&meta)?.0),
            "record" => a.record = Some(str_lit(&meta)?.0),
            "access" => a.access = Some(str_lit(&meta)?),
            "pdo" => a.pdo = Some(str_lit(&meta)?),
            "count_access" => a.count_access = Some(str_lit(&meta)?),
            "eds_default" => a.eds_default = Some(str_lit(&meta)?),
            "min" | "max" | "default" => {
                let e: Expr = meta.value()?.parse()?;
                let v = (ConstLit::parse(&e)?, e);
                match key.as_str() {
                    "min" => a.min = Some(v),
                    "max" => a.max = Some(v),
                    _ => a.default = Some(v),
                }
            }
            "domain" => a.domain = true,
            "check" | "on_write" => {
                let (s, span) = str_lit(&meta)?;
                let id = syn::parse_str::<Ident>(&s).map_err(|_| syn::Error::new(span, "expected a method name"))?;
                let id = Ident::new(&id.to_string(), span);
                if key == "check" {
                    a.check = Some(id);
                } else {
                    a.on_write = Some(id);
                }
            }
            _ => {
                return Err(meta.error(
                    "unknown `od` key: expected index, sub, name, record, access, pdo, min, max, default, \
                     eds_default, domain, check, on_write or count_access",
                ))
            }
        }
        Ok(())
    })?;
    Ok(a)
}

/// How a row reaches its value.
#[derive(Clone)]
#[allow(clippy::large_enum_variant)]
enum Target {
    /// Sub 00h of an ARRAY/RECORD: a constant count.
    Count(u8),
    /// A field, or element `i` of an array field.
    Field { member: Ts, ty: Type, st: ScalarType, check: Option<Ident>, on_write: Option<Ident> },
    /// A DOMAIN field.
    Domain { member: Ts },
}

struct Row {
    index: u16,
    sub: u8,
    name: String,
    numbered: bool,
    dt: &'static str,
    access: Ts,
    pdo: Ts,
    /// Mapped to PDOs in some direction (`pdo` other than `no`).
    mapped: bool,
    max_size: Ts,
    default: Ts,
    low: Ts,
    high: Ts,
    /// The statement that checks a decoded value `v` against `min`/`max` (empty without limits).
    limits: Ts,
    /// SDO and RPDOs may write it (`rw`, `wo`, `rwr`, `rww`): only then is a write arm generated.
    writable: bool,
    /// The access of its ARRAY's or RECORD's sub-index 00h (`count_access`), when not const.
    count_access: Option<Ts>,
    target: Target,
    span: Span,
    field: String,
}

struct Object {
    index: u16,
    name: String,
    code: &'static str,
    span: Span,
    field: String,
}

fn check_value(lit: &ConstLit, st: &ScalarType, expr: &Expr, what: &str) -> syn::Result<()> {
    let bad = |msg: String| Err(syn::Error::new_spanned(expr, msg));
    match (st.class, lit) {
        (Class::Signed(bits), ConstLit::Int(i)) => {
            let (lo, hi) = (-(1i128 << (bits - 1)), (1i128 << (bits - 1)) - 1);
            if *i < lo || *i > hi {
                return bad(format!("{what} {i} does not fit in {} ({lo}..={hi})", spec_name(st.dt)));
            }
        }
        (Class::Unsigned(bits), ConstLit::Int(i)) => {
            let hi = (1i128 << bits) - 1;
            if *i < 0 || *i > hi {
                return bad(format!("{what} {i} does not fit in {} (0..={hi})", spec_name(st.dt)));
            }
        }
        (Class::Time, ConstLit::Int(i)) if *i < 0 || *i >= 1 << 48 => {
            return bad(format!("{what} {i} does not fit in 48 bits"));
        }
        (Class::Time, ConstLit::Int(_)) => {}
        (Class::Real32 | Class::Real64, ConstLit::Int(_) | ConstLit::Float(_)) => {}
        (Class::Bool, ConstLit::Bool(_)) => {}
        (Class::Bool, ConstLit::Int(0 | 1)) => {}
        (Class::Text | Class::Bytes, ConstLit::Str(_)) if what == "default" => {}
        (Class::Bytes, ConstLit::Bytes(_)) if what == "default" => {}
        // A byte string for text: its bytes must be the text's UTF-8.
        (Class::Text, ConstLit::Bytes(b)) if what == "default" => {
            if std::str::from_utf8(b).is_err() {
                return bad(format!(
                    "default {} is not UTF-8: a {} default is text (a byte string default is for OCTET_STRING)",
                    lit.show(),
                    spec_name(st.dt)
                ));
            }
        }
        (Class::Text | Class::Bytes, _) => return bad(format!("a {what} is not allowed for {}", spec_name(st.dt))),
        _ => return bad(format!("{what} {} does not match the field type {}", lit.show(), spec_name(st.dt))),
    }
    Ok(())
}

/// The CiA 301 spelling of a data type: `VisibleString` → `VISIBLE_STRING`.
fn spec_name(dt: &str) -> String {
    let mut out = String::new();
    for (i, c) in dt.chars().enumerate() {
        if c.is_ascii_uppercase() && i > 0 {
            out.push('_');
        }
        out.push(c.to_ascii_uppercase());
    }
    out
}

fn value_tokens(core: &Ts, lit: &ConstLit, st: &ScalarType) -> Ts {
    match (st.class, lit) {
        (Class::Bool, ConstLit::Bool(b)) => quote!(#core::od::Value::Bool(#b)),
        (Class::Bool, ConstLit::Int(i)) => {
            let b = *i != 0;
            quote!(#core::od::Value::Bool(#b))
        }
        (Class::Signed(_), ConstLit::Int(i)) => {
            let v = proc_macro2::Literal::i64_suffixed(*i as i64);
            quote!(#core::od::Value::Int(#v))
        }
        (Class::Unsigned(_) | Class::Time, ConstLit::Int(i)) => {
            let v = proc_macro2::Literal::u64_suffixed(*i as u64);
            quote!(#core::od::Value::Uint(#v))
        }
        (Class::Real32, l) => {
            let v = proc_macro2::Literal::f32_suffixed(l.as_f64().unwrap_or(0.0) as f32);
            quote!(#core::od::Value::Real32(#v))
        }
        (Class::Real64, l) => {
            let v = proc_macro2::Literal::f64_suffixed(l.as_f64().unwrap_or(0.0));
            quote!(#core::od::Value::Real64(#v))
        }
        (_, ConstLit::Str(s)) => quote!(#core::od::Value::Str(#s)),
        (Class::Bytes, ConstLit::Bytes(b)) => {
            let b = proc_macro2::Literal::byte_string(b);
            quote!(#core::od::Value::Bytes(#b))
        }
        // Text given as a byte string: check_value made sure it is UTF-8.
        (_, ConstLit::Bytes(b)) => {
            let s = String::from_utf8_lossy(b);
            quote!(#core::od::Value::Str(#s))
        }
        _ => quote!(#core::od::Value::Uint(0)),
    }
}

/// The write arms' check of a decoded value `v` against `min`/`max` (0609 0032h below, 0609 0031h above).
/// A Rust integer field with integer limits is compared in its own type (`check_range`, limits typed
/// literals that `check_value` proved in range: a compare and a branch each); any other type through the
/// `Value`s of the entry table (`check_limits`, which also refuses what does not compare, like a NaN).
fn limit_check(core: &Ts, st: &ScalarType, min: Option<&ConstLit>, max: Option<&ConstLit>, low: &Ts, high: &Ts) -> Ts {
    if min.is_none() && max.is_none() {
        return quote!();
    }
    let suffix = match st.class {
        Class::Signed(bits @ (8 | 16 | 32 | 64)) => format!("i{bits}"),
        Class::Unsigned(bits @ (8 | 16 | 32 | 64)) => format!("u{bits}"),
        _ => String::new(),
    };
    let typed = |l: Option<&ConstLit>| match l {
        None => Some(quote!(::core::option::Option::None)),
        Some(ConstLit::Int(i)) if !suffix.is_empty() => {
            let lit = syn::LitInt::new(&format!("{}{suffix}", i.unsigned_abs()), Span::call_site());
            let neg = (*i < 0).then(|| quote!(-));
            Some(quote!(::core::option::Option::Some(#neg #lit)))
        }
        Some(_) => None,
    };
    match (typed(min), typed(max)) {
        (Some(lo), Some(hi)) => quote!(#core::od::check_range(v, #lo, #hi)?;),
        _ => quote!(#core::od::check_limits(&v, (#low).as_ref(), (#high).as_ref())?;),
    }
}

fn opt(ts: Option<Ts>) -> Ts {
    match ts {
        Some(t) => quote!(::core::option::Option::Some(#t)),
        None => quote!(::core::option::Option::None),
    }
}

fn access_tokens(core: &Ts, a: &Option<(String, Span)>) -> syn::Result<(Ts, bool, bool)> {
    let (s, span) = a.clone().unwrap_or_else(|| ("rw".into(), Span::call_site()));
    let (v, r, w) = match s.as_str() {
        "ro" => (quote!(Ro), true, false),
        "wo" => (quote!(Wo), false, true),
        "rw" => (quote!(Rw), true, true),
        "rwr" => (quote!(Rwr), true, true),
        "rww" => (quote!(Rww), true, true),
        "const" => (quote!(Const), true, false),
        _ => {
            return Err(syn::Error::new(
                span,
                "access must be one of \"ro\", \"wo\", \"rw\", \"rwr\", \"rww\", \"const\"",
            ))
        }
    };
    Ok((quote!(#core::od::Access::#v), r, w))
}

fn pdo_tokens(core: &Ts, p: &Option<(String, Span)>) -> syn::Result<(Ts, bool)> {
    let Some((s, span)) = p.clone() else { return Ok((quote!(#core::od::PdoMapping::No), false)) };
    let v = match s.as_str() {
        "no" => return Ok((quote!(#core::od::PdoMapping::No), false)),
        "tpdo" => quote!(Tpdo),
        "rpdo" => quote!(Rpdo),
        "both" => quote!(Both),
        _ => return Err(syn::Error::new(span, "pdo must be one of \"no\", \"tpdo\", \"rpdo\", \"both\"")),
    };
    Ok((quote!(#core::od::PdoMapping::#v), true))
}

/// What the derive emits for the dictionary's accesses.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Layout {
    /// Match arms per entry (the default).
    Code,
    /// `#[od(compact)]`: `od::data` tables and one accessor arm per field.
    Data,
    /// `#[od(compact, zerocopy)]` (or `#[od(zerocopy)]`): `od::data` tables, each field reached by its offset
    /// in the struct's byte view.
    Offsets,
}

/// The struct-level `#[od(...)]` keys: `crate = "path"` (the core crate's path) and `write_events = false`
/// (no `Event::ObjectWritten` for this dictionary's entries).
fn struct_attrs(input: &DeriveInput) -> syn::Result<(Ts, bool, Layout)> {
    let mut path: Ts = quote!(::canopen_core);
    let mut write_events = true;
    let mut compact = Layout::Code;
    for attr in input.attrs.iter().filter(|a| a.path().is_ident("od")) {
        attr.parse_nested_meta(|meta| {
            if meta.path.is_ident("crate") {
                let s: LitStr = meta.value()?.parse()?;
                path = s.parse::<syn::Path>()?.into_token_stream();
                Ok(())
            } else if meta.path.is_ident("write_events") {
                let b: syn::LitBool = meta.value()?.parse()?;
                write_events = b.value;
                Ok(())
            } else if meta.path.is_ident("compact") {
                compact = match compact {
                    Layout::Code => Layout::Data,
                    l => l,
                };
                Ok(())
            } else if meta.path.is_ident("zerocopy") {
                compact = Layout::Offsets;
                Ok(())
            } else {
                Err(meta
                    .error("unknown struct-level `od` key: expected `crate`, `write_events`, `compact` or `zerocopy`"))
            }
        })?;
    }
    Ok((path, write_events, compact))
}

fn expand(input: &DeriveInput) -> syn::Result<Ts> {
    let (core, write_events, compact) = struct_attrs(input)?;
    let ident = &input.ident;
    if !input.generics.params.is_empty() {
        return Err(syn::Error::new_spanned(
            &input.generics,
            "ObjectDictionary cannot be derived for a generic struct",
        ));
    }
    let Data::Struct(data) = &input.data else {
        return Err(syn::Error::new_spanned(ident, "ObjectDictionary can only be derived for a struct"));
    };
    let Fields::Named(fields) = &data.fields else {
        return Err(syn::Error::new_spanned(ident, "ObjectDictionary needs a struct with named fields"));
    };

    let mut errors: Vec<syn::Error> = Vec::new();
    let mut rows: Vec<Row> = Vec::new();
    let mut objects: Vec<Object> = Vec::new();
    let mut type_asserts: Vec<Ts> = Vec::new();
    let mut data_fields: Vec<DataField> = Vec::new();

    for field in &fields.named {
        let Some(attr) = field.attrs.iter().find(|a| a.path().is_ident("od")) else { continue };
        let fname = field.ident.as_ref().map(|i| i.to_string()).unwrap_or_default();
        match field_rows(&core, field, attr, &fname, &mut type_asserts) {
            Ok((mut r, o, d)) => {
                data_fields.push(d);
                rows.append(&mut r);
                if let Some(o) = o {
                    objects.push(o);
                }
            }
            Err(e) => errors.push(e),
        }
    }

    // Records: members (sub >= 1, not array elements) of an index that has no VAR/ARRAY object.
    rows.sort_by_key(|r| (r.index, r.sub));
    let mut record_rows: Vec<Row> = Vec::new();
    let mut dup_indices: Vec<u16> = Vec::new();
    for r in rows.iter().filter(|r| matches!(r.target, Target::Field { .. }) && r.sub > 0 && !r.numbered) {
        if let Some(o) = objects.iter().find(|o| o.index == r.index) {
            if o.code != "Record" && !dup_indices.contains(&r.index) {
                dup_indices.push(r.index);
                errors.push(syn::Error::new(
                    r.span,
                    format!("duplicate object dictionary index {:04X}h: already used by field `{}`", r.index, o.field),
                ));
            }
            continue;
        }
        let highest = rows.iter().filter(|x| x.index == r.index).map(|x| x.sub).max().unwrap_or(0);
        let count_access = rows.iter().filter(|x| x.index == r.index).find_map(|x| x.count_access.clone());
        objects.push(Object {
            index: r.index,
            name: String::new(),
            code: "Record",
            span: r.span,
            field: r.field.clone(),
        });
        record_rows.push(count_row(&core, r.index, highest, r.span, &r.field, count_access));
    }
    rows.append(&mut record_rows);
    rows.sort_by_key(|r| (r.index, r.sub));

    // Duplicate objects (two VARs, a VAR and an ARRAY, ... on one index).
    objects.sort_by_key(|o| o.index);
    for w in objects.windows(2) {
        if w[0].index == w[1].index && !dup_indices.contains(&w[1].index) {
            dup_indices.push(w[1].index);
            errors.push(syn::Error::new(
                w[1].span,
                format!(
                    "duplicate object dictionary index {:04X}h: already used by field `{}`",
                    w[1].index, w[0].field
                ),
            ));
        }
    }
    // Duplicate (index, sub) among record members.
    for w in rows.windows(2) {
        if w[0].index == w[1].index && w[0].sub == w[1].sub && !dup_indices.contains(&w[1].index) {
            dup_indices.push(w[1].index);
            errors.push(syn::Error::new(
                w[1].span,
                format!(
                    "duplicate object dictionary entry {:04X}h sub {}: already defined by field `{}`",
                    w[1].index, w[1].sub, w[0].field
                ),
            ));
        }
    }
    if let Some(e) = errors.into_iter().reduce(|mut a, b| {
        a.combine(b);
        a
    }) {
        return Err(e);
    }

    // Record names.
    let record_names = record_names(fields)?;
    for o in objects.iter_mut().filter(|o| o.code == "Record") {
        o.name = record_names
            .iter()
            .find(|(i, _)| *i == o.index)
            .map(|(_, n)| n.clone())
            .unwrap_or_else(|| format!("Record {:04X}h", o.index));
    }

    // Tables.
    let entries = rows.iter().map(|r| {
        let (index, sub, name, numbered) = (r.index, r.sub, &r.name, r.numbered);
        let dt = Ident::new(r.dt, Span::call_site());
        let (access, pdo, max_size, default, low, high) = (&r.access, &r.pdo, &r.max_size, &r.default, &r.low, &r.high);
        quote! {
            #core::od::EntryDesc {
                index: #index, sub: #sub, name: #name, numbered: #numbered,
                data_type: #core::od::DataType::#dt, access: #access, pdo: #pdo, max_size: #max_size,
                default: #default, low: #low, high: #high,
            }
        }
    });
    // What the SDO/PDO paths need of an entry (data type, access, mapping), in a table of its own: the full
    // OD_ENTRIES (names, defaults, limits; 72 B per entry on a 32-bit target) is then only kept alive by
    // OdDescribe's `object`/`entry` (the EDS writer), and a firmware, storing or not, links 8 B per entry
    // instead (store/restore walks `object_index` and `info`).
    let infos = rows.iter().map(|r| {
        let dt = Ident::new(r.dt, Span::call_site());
        let (access, pdo) = (&r.access, &r.pdo);
        quote! {
            #core::od::SubInfo {
                data_type: #core::od::DataType::#dt, access: #access, pdo: #pdo,
                size: match #core::od::DataType::#dt.size() { ::core::option::Option::Some(n) => n, ::core::option::Option::None => 0 },
            }
        }
    }).collect::<Vec<_>>();
    let object_descs = objects.iter().map(|o| {
        let first = rows.iter().position(|r| r.index == o.index).unwrap_or(0) as u16;
        let subs = rows.iter().filter(|r| r.index == o.index).count() as u16;
        let (index, name) = (o.index, &o.name);
        let code = Ident::new(o.code, Span::call_site());
        quote! {
            #core::od::ObjectDesc { index: #index, name: #name, code: #core::od::ObjectCode::#code, first: #first, subs: #subs }
        }
    });

    let n_entries = rows.len();
    // A position travels as a u16 slot (`slot`, `read_slot`, the PDO handles), with
    // u16::MAX meaning none: every position must fit below it, or a slot would name another entry.
    if n_entries >= usize::from(u16::MAX) {
        return Err(syn::Error::new(
            Span::call_site(),
            format!("{n_entries} dictionary entries: at most 65,534 (a position is a u16 slot)"),
        ));
    }
    let object_indices = objects.iter().map(|o| o.index);
    let max_sizes = data_fields.iter().filter_map(|f| match &f.kind {
        Kind::Fixed(ty) | Kind::Text(ty) => Some(quote!(<#ty as #core::od::OdValue>::MAX_SIZE)),
        Kind::Domain => None,
    });
    // What both layouts emit: the EDS tables (`OdDescribe`) and the constants around them.
    let shell = quote! {
        #[automatically_derived]
        impl #ident {
            /// The object-dictionary entries of this struct, sorted by (index, sub-index): names, defaults
            /// and limits for the EDS writer (`OdDescribe`).
            pub const OD_ENTRIES: &'static [#core::od::EntryDesc] = &[#(#entries),*];
            /// The objects of this struct, sorted by index.
            pub const OD_OBJECTS: &'static [#core::od::ObjectDesc] = &[#(#object_descs),*];
            /// The index of each object of `OD_OBJECTS`: what store/restore walks, so that a firmware
            /// which stores its parameters does not link the names and defaults.
            const __OD_INDICES: &'static [u16] = &[#(#object_indices),*];
            /// The largest encoded size of a non-DOMAIN value (to size an SDO buffer for atomic writes).
            pub const OD_MAX_VALUE_SIZE: usize = {
                let sizes: &[usize] = &[0, #(#max_sizes),*];
                let mut m = 0;
                let mut i = 0;
                while i < sizes.len() {
                    if sizes[i] > m { m = sizes[i]; }
                    i += 1;
                }
                m
            };
        }

        const _: () = assert!(#core::od::is_sorted(#ident::OD_ENTRIES));
        const _: () = assert!(#ident::OD_ENTRIES.len() == #n_entries);

        #[automatically_derived]
        impl #core::od::OdDescribe for #ident {
            fn object_count(&self) -> usize {
                Self::OD_OBJECTS.len()
            }
            fn object(&self, n: usize) -> ::core::option::Option<#core::od::ObjectDesc> {
                Self::OD_OBJECTS.get(n).copied()
            }
            fn entry(&self, index: u16, sub: u8) -> ::core::option::Option<#core::od::EntryDesc> {
                let pos = #core::od::lookup(Self::OD_ENTRIES, index, sub).ok()?;
                Self::OD_ENTRIES.get(pos).copied()
            }
            fn object_index(&self, n: usize) -> ::core::option::Option<u16> {
                Self::__OD_INDICES.get(n).copied()
            }
        }
    };
    let output = |layout: Ts| {
        quote! {
            const _: () = {
                use #core::od::AbortCode as __AbortCode;
                #(#type_asserts)*
                #shell
                #layout
            };
        }
    };

    // `#[od(compact)]`: the dictionary as data (`canopen_core::od::data`); with `zerocopy`, reached by offset.
    if compact != Layout::Code {
        let by_offset = compact == Layout::Offsets;
        return Ok(output(emit::data_impl(&core, ident, data_fields, write_events, by_offset)));
    }

    let mut size_arms = Vec::new();
    let mut read_arms = Vec::new();
    let mut write_arms = Vec::new(); // fixed-size values: inline in every write path
    let mut stream_write_arms = Vec::new(); // strings, byte strings and DOMAINs: out of line
    let mut begin_arms = Vec::new();
    let mut chunk_arms = Vec::new();
    let mut end_arms = Vec::new();
    let mut abort_arms = Vec::new();
    let mut restores = Vec::new();
    let mut var_map_arms = Vec::new(); // the size a mapped string or DOMAIN moves in a PDO

    for (pos, r) in rows.iter().enumerate() {
        let sub = r.sub;
        match &r.target {
            Target::Count(n) => {
                // `copy_at(&[n], offset, buf)` as one byte store: with the constant source LLVM turned the copy
                // into a call to `memset` (220 B of compiler_builtins in a firmware that needs it nowhere else).
                read_arms.push(quote!(#pos => ::core::result::Result::Ok(match (offset, buf.first_mut()) {
                    (0, ::core::option::Option::Some(b)) => {
                        *b = #n;
                        1
                    }
                    _ => 0,
                }),));
            }
            Target::Field { member, ty, st, check, on_write } => {
                let sp = r.span;
                // A fixed-size value's size is its row's in the info table: an arm only for the others.
                if !st.fixed {
                    size_arms.push(quote!(#pos => #core::od::OdValue::size(&self.#member),));
                }
                read_arms.push(
                    quote!(#pos => ::core::result::Result::Ok(#core::od::OdValue::read_bytes(&self.#member, offset, buf)),),
                );
                if r.mapped && !st.fixed {
                    var_map_arms.push(quote!(#pos => <#ty as #core::od::OdValue>::MAX_SIZE,));
                }
                let default = &r.default;
                restores.push(quote! {
                    self.#member = (#default)
                        .as_ref()
                        .and_then(<#ty as #core::od::OdValue>::from_value)
                        .unwrap_or_default();
                });
                let limits = &r.limits;
                // A read-only entry gets no write code: `write`, the expedited download and the streamed
                // write refuse it first (0601 0002h) and an RPDO cannot map it (0604 0041h). Its hooks, if
                // any, keep their arm so that they stay used.
                if !r.writable && check.is_none() && on_write.is_none() {
                    continue;
                }
                let check_call = check.as_ref().map(|c| quote_spanned!(c.span()=> self.#c(#sub, &v)?;));
                let on_write_call = on_write.as_ref().map(|c| quote_spanned!(c.span()=> self.#c(#sub);));
                let arms = if st.fixed { &mut write_arms } else { &mut stream_write_arms };
                arms.push(quote_spanned! {sp=>
                    #pos => {
                        let v = <#ty as #core::od::OdValue>::decode(data)?;
                        #limits
                        #check_call
                        self.#member = v;
                        #on_write_call
                        ::core::result::Result::Ok(())
                    }
                });
                if !st.fixed {
                    begin_arms.push(quote!(#pos => #core::od::OdValue::begin_stream(&mut self.#member, size),));
                    chunk_arms.push(quote!(#pos => #core::od::OdValue::stream_chunk(&mut self.#member, offset, data),));
                    // The streamed bytes are staged in the value (`end_stream` returns the new one): it is
                    // checked like a whole write and stored only then, so an aborted or refused download
                    // leaves the old value.
                    end_arms.push(quote_spanned! {sp=>
                        #pos => {
                            let v = #core::od::OdValue::end_stream(&self.#member, total)?;
                            #limits
                            #check_call
                            self.#member = v;
                            #on_write_call
                            ::core::result::Result::Ok(())
                        }
                    });
                }
            }
            Target::Domain { member } => {
                size_arms.push(quote!(#pos => #core::od::Domain::size(&self.#member).unwrap_or(0),));
                read_arms.push(quote!(#pos => #core::od::Domain::read(&self.#member, offset, buf),));
                if r.mapped {
                    var_map_arms.push(quote!(#pos => #core::od::Domain::size(&self.#member).unwrap_or(0),));
                }
                if !r.writable {
                    continue;
                }
                stream_write_arms.push(quote! {
                    #pos => {
                        #core::od::Domain::begin_write(&mut self.#member, ::core::option::Option::Some(data.len()))?;
                        if let ::core::result::Result::Err(e) = #core::od::Domain::write_chunk(&mut self.#member, 0, data) {
                            #core::od::Domain::abort_write(&mut self.#member);
                            return ::core::result::Result::Err(e);
                        }
                        #core::od::Domain::end_write(&mut self.#member, data.len())
                    }
                });
                begin_arms.push(quote!(#pos => #core::od::Domain::begin_write(&mut self.#member, size),));
                chunk_arms.push(quote!(#pos => #core::od::Domain::write_chunk(&mut self.#member, offset, data),));
                end_arms.push(quote!(#pos => #core::od::Domain::end_write(&mut self.#member, total),));
                abort_arms.push(quote!(#pos => #core::od::Domain::abort_write(&mut self.#member),));
            }
        }
    }

    // The expedited download of a string or DOMAIN (a streamed write of up to 4 bytes), out of line so that the
    // fixed-size path keeps no registers or stack for it; none at all without a writable streamed entry (a
    // read-only one is refused before, by its access).
    let (stream_expedited_arm, stream_expedited_fn) = if begin_arms.is_empty() {
        (quote!(), quote!())
    } else {
        (
            quote!(0 => self.__od_write_expedited_stream(index, sub, data, len),),
            quote! {
                #[inline(never)]
                fn __od_write_expedited_stream(&mut self, index: u16, sub: u8, data: &[u8; 4], len: ::core::option::Option<usize>) -> ::core::result::Result<(), __AbortCode> {
                    let bytes = data.get(..len.unwrap_or(4)).unwrap_or(data);
                    #core::od::write_whole_stream(self, index, sub, bytes)
                }
            },
        )
    };
    // The streamed write of a string or DOMAIN (segmented and block downloads of an entry without a fixed
    // size). A dictionary without a writable one refuses every stream the same way, through one out-of-line
    // check: an unknown entry or a read-only one gets its own code, any other 0601 0000h.
    // `ObjectDictionary::STREAMS`: without a writable streamed entry the SDO server builds no stream path.
    let streams = !begin_arms.is_empty();
    let (stream_write_fns, refuse_stream_fn) = if begin_arms.is_empty() {
        (
            quote! {
                #[allow(unused_variables)]
                fn begin_write(&mut self, index: u16, sub: u8, size: ::core::option::Option<usize>) -> ::core::result::Result<(), __AbortCode> {
                    self.__od_refuse_stream(index, sub)
                }
                #[allow(unused_variables)]
                fn write_chunk(&mut self, index: u16, sub: u8, offset: usize, data: &[u8]) -> ::core::result::Result<(), __AbortCode> {
                    self.__od_refuse_stream(index, sub)
                }
                #[allow(unused_variables)]
                fn end_write(&mut self, index: u16, sub: u8, total: usize) -> ::core::result::Result<(), __AbortCode> {
                    self.__od_refuse_stream(index, sub)
                }
            },
            quote! {
                #[inline(never)]
                fn __od_refuse_stream(&self, index: u16, sub: u8) -> ::core::result::Result<(), __AbortCode> {
                    self.__od_writable(index, sub)?;
                    ::core::result::Result::Err(__AbortCode::UnsupportedAccess)
                }
            },
        )
    } else {
        (
            quote! {
                #[allow(unused_variables)]
                fn begin_write(&mut self, index: u16, sub: u8, size: ::core::option::Option<usize>) -> ::core::result::Result<(), __AbortCode> {
                    let pos = self.__od_writable(index, sub)?;
                    match pos { #(#begin_arms)* _ => ::core::result::Result::Err(__AbortCode::UnsupportedAccess) }
                }
                #[allow(unused_variables)]
                fn write_chunk(&mut self, index: u16, sub: u8, offset: usize, data: &[u8]) -> ::core::result::Result<(), __AbortCode> {
                    let pos = self.__od_writable(index, sub)?;
                    match pos { #(#chunk_arms)* _ => ::core::result::Result::Err(__AbortCode::UnsupportedAccess) }
                }
                #[allow(unused_variables)]
                fn end_write(&mut self, index: u16, sub: u8, total: usize) -> ::core::result::Result<(), __AbortCode> {
                    let pos = self.__od_writable(index, sub)?;
                    match pos { #(#end_arms)* _ => ::core::result::Result::Err(__AbortCode::UnsupportedAccess) }
                }
            },
            quote!(),
        )
    };
    // PDO handles of strings and DOMAINs marked mappable (PDO-33, PDO-36): a string moves its capacity, a
    // DOMAIN the size it has when the mapping is checked; either must be 1..=8 bytes, else 0604 0041h (the
    // core then checks the mapped length against it, and the PDO's 64 bits: 0604 0041h / 0604 0042h).
    // Only a dictionary with such an entry gets this branch.
    let (var_map_branch, var_map_fn) = if var_map_arms.is_empty() {
        (quote!(), quote!())
    } else {
        (
            quote! {
                if e.size == 0 {
                    return self.__od_pdo_resolve_var(index, sub, pos, e, dir);
                }
            },
            quote! {
                #[inline(never)]
                fn __od_pdo_resolve_var(&self, index: u16, sub: u8, pos: usize, e: &#core::od::SubInfo, dir: #core::od::PdoDir) -> ::core::result::Result<#core::od::PdoHandle, __AbortCode> {
                    let size: usize = match pos { #(#var_map_arms)* _ => 0 };
                    let ok = match dir {
                        #core::od::PdoDir::Tpdo => e.pdo.tpdo() && e.access.readable(),
                        #core::od::PdoDir::Rpdo => e.pdo.rpdo() && e.access.writable(),
                    };
                    match u8::try_from(size) {
                        ::core::result::Result::Ok(size @ 1..=8) if ok => {
                            ::core::result::Result::Ok(#core::od::PdoHandle { index, sub, size, slot: pos as u16 })
                        }
                        _ => ::core::result::Result::Err(__AbortCode::NotMappable),
                    }
                }
            },
        )
    };
    let keys: Vec<u32> = rows.iter().map(|r| (u32::from(r.index) << 8) | u32::from(r.sub)).collect();
    // On bare metal a dictionary of 2 to 12 entries is scanned (`scan_key`), each key beside its SubInfo in
    // one row table (no second bounds test): less flash than the binary search and its neighbour tests (the
    // firmware node, 9 entries: 64 B less). Out of line, or LLVM inlined the scan into every access (+272 B
    // there). One entry is one comparison either way; a larger dictionary, and every host build (whose
    // instructions per frame bench-node.sh counts), keep the binary search.
    let (search_cfg, scan_fns) = if (2..=12).contains(&n_entries) {
        (
            quote!(#[cfg(not(target_os = "none"))]),
            quote! {
                /// Each entry's key `index << 8 | sub` beside its `__OD_INFO` row, for the scan.
                #[cfg(target_os = "none")]
                const __OD_ROWS: &'static [(u32, #core::od::SubInfo)] = &[#((#keys, #infos)),*];
                /// The scan of the rows: one copy per dictionary, shared by every access.
                #[cfg(target_os = "none")]
                #[inline(never)]
                fn __od_pos(&self, index: u16, sub: u8) -> ::core::result::Result<(usize, &'static #core::od::SubInfo), __AbortCode> {
                    #core::od::scan_key(Self::__OD_ROWS, index, sub)
                }
                /// The `__OD_ROWS` info at `pos`.
                #[cfg(target_os = "none")]
                #[inline]
                fn __od_info(pos: usize) -> ::core::option::Option<&'static #core::od::SubInfo> {
                    match Self::__OD_ROWS.get(pos) {
                        ::core::option::Option::Some((_, e)) => ::core::option::Option::Some(e),
                        ::core::option::Option::None => ::core::option::Option::None,
                    }
                }
            },
        )
    } else {
        (quote!(), quote!())
    };
    Ok(output(quote! {
            #[automatically_derived]
            impl #ident {
                /// Data type, access and PDO mapping of each entry of `OD_ENTRIES`; `size` is the fixed size of
                /// the type (0 for strings and DOMAINs), not the current one.
                const __OD_INFO: &'static [#core::od::SubInfo] = &[#(#infos),*];
                /// The keys `index << 8 | sub` of `OD_ENTRIES`, for a cache-friendly binary search.
                pub const OD_KEYS: &'static [u32] = &[#(#keys),*];

                /// The current size of the entry at `pos` whose info row is `e`: the row's fixed size, or
                /// for a string or DOMAIN its current length.
                #[inline]
                fn __od_size(&self, pos: usize, e: &#core::od::SubInfo) -> usize {
                    match pos { #(#size_arms)* _ => e.size }
                }
                #[inline]
                fn __od_read(&self, pos: usize, offset: usize, buf: &mut [u8]) -> ::core::result::Result<usize, __AbortCode> {
                    match pos { #(#read_arms)* _ => ::core::result::Result::Err(__AbortCode::ObjectDoesNotExist) }
                }
                /// The store of a fixed-size value, shared by every write path (`write`, the expedited
                /// download, RPDOs through `pdo_write`). Out of line: inlined it was a copy per path, 88 B
                /// of the firmware node's flash for 3 instructions per expedited download (bench-node.sh).
                #[inline(never)]
                fn __od_write(&mut self, pos: usize, data: &[u8]) -> ::core::result::Result<(), __AbortCode> {
                    match pos { #(#write_arms)* _ => self.__od_write_stream_value(pos, data) }
                }
                /// The arms of `__od_write` for strings, byte strings and DOMAINs. Out of line, so that the
                /// fixed-size writes (expedited downloads, RPDOs) do not keep their registers and stack.
                #[inline(never)]
                #[allow(unused_variables)]
                fn __od_write_stream_value(&mut self, pos: usize, data: &[u8]) -> ::core::result::Result<(), __AbortCode> {
                    match pos { #(#stream_write_arms)* _ => ::core::result::Result::Err(__AbortCode::WriteOfReadOnly) }
                }
                #stream_expedited_fn
                #refuse_stream_fn
                #var_map_fn
                /// The binary search of the 4-byte keys and the entry's `__OD_INFO` row: one copy per
                /// dictionary (not inlined), shared by every access.
                #search_cfg
                fn __od_pos(&self, index: u16, sub: u8) -> ::core::result::Result<(usize, &'static #core::od::SubInfo), __AbortCode> {
                    let pos = #core::od::lookup_key(Self::OD_KEYS, index, sub)?;
                    let e = Self::__OD_INFO.get(pos).ok_or(__AbortCode::ObjectDoesNotExist)?;
                    ::core::result::Result::Ok((pos, e))
                }
                /// The `__OD_INFO` row at `pos`.
                #search_cfg
                #[inline]
                fn __od_info(pos: usize) -> ::core::option::Option<&'static #core::od::SubInfo> {
                    Self::__OD_INFO.get(pos)
                }
                #scan_fns
                #[inline]
                fn __od_writable(&self, index: u16, sub: u8) -> ::core::result::Result<usize, __AbortCode> {
                    let (pos, e) = self.__od_pos(index, sub)?;
                    if !e.access.writable() {
                        return ::core::result::Result::Err(__AbortCode::WriteOfReadOnly);
                    }
                    ::core::result::Result::Ok(pos)
                }
                /// The entry-table slot of a PDO handle: the handle came from this dictionary's
                /// `pdo_resolve` (the trait's contract), so its slot is trusted, not checked against the key
                /// table again (that compare cost 6 instructions per mapped entry, 24 per 4-entry TPDO on
                /// x86-64). `None` for a handle without a slot (or one out of range): looked up by index.
                #[inline]
                fn __od_slot(handle: &#core::od::PdoHandle) -> ::core::option::Option<usize> {
                    let pos = usize::from(handle.slot);
                    if pos < #n_entries { ::core::option::Option::Some(pos) } else { ::core::option::Option::None }
                }
            }

            const _: () = assert!(#ident::OD_KEYS.len() == #n_entries);
            const _: () = assert!(#ident::__OD_INFO.len() == #n_entries);

            #[automatically_derived]
            impl #core::od::ObjectDictionary for #ident {
                /// Whether a writable string or DOMAIN takes streamed writes.
                const STREAMS: bool = #streams;
                /// Whether a readable entry's type has no fixed size of 1..=4 bytes (a string, a DOMAIN, a
                /// 64-bit value), so that an upload of it is segmented.
                const SEGMENTED_UPLOADS: bool = {
                    let infos = Self::__OD_INFO;
                    let mut any = false;
                    let mut i = 0;
                    while i < infos.len() {
                        let e = &infos[i];
                        if e.access.readable() && (e.size == 0 || e.size > 4) {
                            any = true;
                        }
                        i += 1;
                    }
                    any
                };

                fn info(&self, index: u16, sub: u8) -> ::core::result::Result<#core::od::SubInfo, __AbortCode> {
                    let (pos, e) = self.__od_pos(index, sub)?;
                    ::core::result::Result::Ok(#core::od::SubInfo { data_type: e.data_type, access: e.access, pdo: e.pdo, size: self.__od_size(pos, e) })
                }
                fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> ::core::result::Result<usize, __AbortCode> {
                    let (pos, e) = self.__od_pos(index, sub)?;
                    if !e.access.readable() {
                        return ::core::result::Result::Err(__AbortCode::ReadOfWriteOnly);
                    }
                    self.__od_read(pos, offset, buf)
                }
                fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> ::core::result::Result<(), __AbortCode> {
                    let pos = self.__od_writable(index, sub)?;
                    self.__od_write(pos, data)
                }
                #stream_write_fns
                /// NMT-04 Reset Application: every entry gets its `default` (or the type's default when none
                /// is given); DOMAIN fields and fields without `#[od]` are left alone.
                fn restore_defaults(&mut self) {
                    #(#restores)*
                }

                #[inline]
                fn write_events(&self) -> bool {
                    #write_events
                }

                fn abort_write(&mut self, index: u16, sub: u8) {
                    if let ::core::result::Result::Ok((pos, _)) = self.__od_pos(index, sub) {
                        match pos { #(#abort_arms)* _ => {} }
                    }
                }
                fn read_expedited(&self, index: u16, sub: u8, buf: &mut [u8; 4]) -> ::core::result::Result<(usize, usize), __AbortCode> {
                    let (pos, e) = self.__od_pos(index, sub)?;
                    if !e.access.readable() {
                        return ::core::result::Result::Err(__AbortCode::ReadOfWriteOnly);
                    }
                    let size = self.__od_size(pos, e);
                    match buf.get_mut(..size) {
                        ::core::option::Option::Some(dst) if size > 0 => ::core::result::Result::Ok((size, self.__od_read(pos, 0, dst)?)),
                        _ => ::core::result::Result::Ok((size, 0)),
                    }
                }
                fn write_expedited(&mut self, index: u16, sub: u8, data: &[u8; 4], len: ::core::option::Option<usize>) -> ::core::result::Result<(), __AbortCode> {
                    let (pos, e) = self.__od_pos(index, sub)?;
                    if !e.access.writable() {
                        return ::core::result::Result::Err(__AbortCode::WriteOfReadOnly);
                    }
                    // The row's size is the type's fixed size (0: a string or DOMAIN), known at compile time:
                    // no match on the data type per download.
                    match e.size {
                        #stream_expedited_arm
                        n => {
                            let bytes = data.get(..len.unwrap_or(n.min(4))).unwrap_or(data);
                            self.__od_write(pos, bytes)
                        }
                    }
                }
                fn slot(&self, index: u16, sub: u8) -> u16 {
                    self.__od_pos(index, sub).map_or(#core::od::PdoHandle::NO_SLOT, |(pos, _)| pos as u16)
                }
                #[inline]
                fn read_slot(&self, index: u16, sub: u8, slot: u16, offset: usize, buf: &mut [u8]) -> ::core::result::Result<(), __AbortCode> {
                    let pos = usize::from(slot);
                    match Self::__od_info(pos) {
                        ::core::option::Option::Some(e) if e.access.readable() => #core::od::filled(self.__od_read(pos, offset, buf)?, buf.len()),
                        ::core::option::Option::Some(_) => ::core::result::Result::Err(__AbortCode::ReadOfWriteOnly),
                        ::core::option::Option::None => #core::od::filled(self.read(index, sub, offset, buf)?, buf.len()),
                    }
                }
                fn pdo_resolve(&self, index: u16, sub: u8, dir: #core::od::PdoDir) -> ::core::result::Result<#core::od::PdoHandle, __AbortCode> {
                    let (pos, e) = self.__od_pos(index, sub)?;
                    #var_map_branch
                    let info = #core::od::SubInfo { data_type: e.data_type, access: e.access, pdo: e.pdo, size: 0 };
                    #core::od::PdoHandle::check(index, sub, &info, dir, pos as u16)
                }
                #[inline(always)]
                fn pdo_read(&self, handle: &#core::od::PdoHandle, buf: &mut [u8]) -> ::core::result::Result<usize, __AbortCode> {
                    match Self::__od_slot(handle) {
                        ::core::option::Option::Some(pos) => self.__od_read(pos, 0, buf),
                        ::core::option::Option::None => self.read(handle.index, handle.sub, 0, buf),
                    }
                }
                fn pdo_write(&mut self, handle: &#core::od::PdoHandle, data: &[u8]) -> ::core::result::Result<(), __AbortCode> {
                    match Self::__od_slot(handle) {
                        ::core::option::Option::Some(pos) => self.__od_write(pos, data),
                        ::core::option::Option::None => self.write(handle.index, handle.sub, data),
                    }
                }
            }
    }))
}

fn record_names(fields: &syn::FieldsNamed) -> syn::Result<Vec<(u16, String)>> {
    let mut out = Vec::new();
    for field in &fields.named {
        if let Some(attr) = field.attrs.iter().find(|a| a.path().is_ident("od")) {
            let a = parse_field_attr(attr)?;
            if let (Some((i, _)), Some(n)) = (a.index, a.record) {
                out.push((i, n));
            }
        }
    }
    Ok(out)
}

/// Sub-index 00h of an ARRAY or RECORD: its highest sub-index, `const` unless `access` (`count_access`)
/// says `ro`.
fn count_row(core: &Ts, index: u16, highest: u8, span: Span, field: &str, access: Option<Ts>) -> Row {
    Row {
        index,
        sub: 0,
        name: "Highest sub-index supported".into(),
        numbered: false,
        dt: "Unsigned8",
        access: access.unwrap_or_else(|| quote!(#core::od::Access::Const)),
        pdo: quote!(#core::od::PdoMapping::No),
        mapped: false,
        max_size: quote!(1),
        default: quote!(::core::option::Option::Some(#core::od::Value::Uint(#highest as u64))),
        low: quote!(::core::option::Option::None),
        high: quote!(::core::option::Option::None),
        limits: quote!(),
        writable: false,
        count_access: None,
        target: Target::Count(highest),
        span,
        field: field.into(),
    }
}

#[allow(clippy::type_complexity)]
fn field_rows(
    core: &Ts,
    field: &syn::Field,
    attr: &syn::Attribute,
    fname: &str,
    type_asserts: &mut Vec<Ts>,
) -> syn::Result<(Vec<Row>, Option<Object>, DataField)> {
    let a = parse_field_attr(attr)?;
    let fident = field.ident.clone().ok_or_else(|| syn::Error::new_spanned(field, "named field expected"))?;
    let span = field.span();
    let (index, ispan) = a.index.ok_or_else(|| syn::Error::new_spanned(attr, "missing `index = 0x....`"))?;
    if index < 0x2000 {
        let msg = if index >= 0x1000 {
            format!(
                "index {index:04X}h is in the communication profile area 1000h–1FFFh, which the core provides; \
                 application objects start at 2000h"
            )
        } else {
            format!("index {index:04X}h is reserved for data types (0000h–0FFFh); application objects start at 2000h")
        };
        return Err(syn::Error::new(ispan, msg));
    }
    // Errors about a duplicate point at the sub-index of a record member, else at the index.
    let key_span = match a.sub {
        Some(SubSpec::One(s, sp)) if s > 0 => sp,
        _ => ispan,
    };
    let name = a.name.clone().unwrap_or_else(|| fname.to_string());
    let (access, readable, writable) = access_tokens(core, &a.access)?;
    let (pdo, mapped) = pdo_tokens(core, &a.pdo)?;
    let ty = &field.ty;
    // The field's row of the data table (`#[od(compact)]`), before hooks, limits and default.
    let plain = |sub: u8, n: u8, dt: &'static str, kind: Kind| DataField {
        index,
        sub,
        n,
        dt,
        kind,
        access: access.clone(),
        pdo: pdo.clone(),
        writable,
        mapped,
        count_ro: false,
        check: None,
        on_write: None,
        min: None,
        max: None,
        default: None,
        default_ts: quote!(::core::option::Option::None),
        member: fident.clone(),
    };

    if a.domain {
        if let Some((_, sp)) = a.count_access {
            return Err(syn::Error::new(sp, "count_access applies to an array field or a record member"));
        }
        if a.min.is_some() || a.max.is_some() || a.default.is_some() || a.check.is_some() || a.on_write.is_some() {
            return Err(syn::Error::new(
                span,
                "a DOMAIN has no limits, default or hooks: validate in its `Domain::end_write` (`eds_default` \
                 gives the EDS a DefaultValue text)",
            ));
        }
        if let Some(SubSpec::One(s, sp) | SubSpec::Range(s, _, sp)) = a.sub {
            if s != 0 {
                return Err(syn::Error::new(sp, "a DOMAIN is a VAR at sub-index 0"));
            }
        }
        let _ = readable;
        type_asserts.push(quote_spanned! {ty.span()=>
            const _: fn(&#ty) -> ::core::option::Option<usize> = <#ty as #core::od::Domain>::size;
        });
        let row = Row {
            index,
            sub: 0,
            name: name.clone(),
            numbered: false,
            dt: "Domain",
            access: access.clone(),
            pdo: pdo.clone(),
            mapped,
            max_size: quote!(usize::MAX),
            // The EDS text only (`eds_default`): the node neither applies nor checks it.
            default: opt(a.eds_default.as_ref().map(|(text, _)| quote!(#core::od::Value::Str(#text)))),
            low: quote!(::core::option::Option::None),
            high: quote!(::core::option::Option::None),
            limits: quote!(),
            writable,
            count_access: None,
            target: Target::Domain { member: quote!(#fident) },
            span: key_span,
            field: fname.into(),
        };
        let data = plain(0, 1, "Domain", Kind::Domain);
        return Ok((vec![row], Some(Object { index, name, code: "Var", span: key_span, field: fname.into() }), data));
    }

    // Array or scalar.
    let (elem_ty, len) = match ty {
        Type::Array(arr) => {
            let n: usize = match &arr.len {
                Expr::Lit(ExprLit { lit: Lit::Int(i), .. }) => i.base10_parse()?,
                other => return Err(syn::Error::new_spanned(other, "the array length must be an integer literal")),
            };
            if n == 0 || n > 254 {
                return Err(syn::Error::new_spanned(&arr.len, "an ARRAY has 1 to 254 elements"));
            }
            ((*arr.elem).clone(), Some(n))
        }
        _ => (ty.clone(), None),
    };
    let st = scalar_type(&elem_ty).ok_or_else(|| {
        syn::Error::new_spanned(
            &elem_ty,
            format!(
                "unsupported field type `{}`: use bool, i8/i16/i32/i64, u8/u16/u32/u64, I24/I40/I48/I56, \
                 U24/U40/U48/U56, f32/f64, TimeOfDay, TimeDifference, VisibleString<N>, OctetString<N>, \
                 UnicodeString<N>, an array of those, or mark a DOMAIN with `domain`",
                elem_ty.to_token_stream().to_string().replace(' ', "")
            ),
        )
    })?;
    if let Some((_, sp)) = a.eds_default {
        return Err(syn::Error::new(
            sp,
            "eds_default is for a DOMAIN (whose content the node does not hold a default of): use `default`",
        ));
    }
    // A mapped string moves its whole capacity (PDO-31: the mapping gives a fixed length), which a PDO's 64
    // bits must hold: a capacity written as a literal is checked here, any other at compile time below.
    if mapped && !st.fixed {
        let pdo_span = a.pdo.as_ref().map(|p| p.1).unwrap_or(span);
        let too_big = |bytes: String| {
            syn::Error::new(
                pdo_span,
                format!(
                    "`{}` ({}) cannot be mapped to a PDO: it holds {bytes} bytes, a PDO 8 (a mapped string \
                     moves its whole capacity)",
                    elem_ty.to_token_stream().to_string().replace(' ', ""),
                    spec_name(st.dt)
                ),
            )
        };
        match literal_capacity(&elem_ty, &st) {
            Some(n) if n > 8 => return Err(too_big(n.to_string())),
            Some(_) => {}
            None => type_asserts.push(quote_spanned! {pdo_span=>
                const _: () = assert!(
                    <#elem_ty as #core::od::OdValue>::MAX_SIZE <= 8,
                    "a string mapped to a PDO holds at most 8 bytes (a mapped string moves its whole capacity)"
                );
            }),
        }
    }
    let dt_ident = Ident::new(st.dt, Span::call_site());
    type_asserts.push(quote_spanned! {elem_ty.span()=>
        const _: () = assert!(
            <#elem_ty as #core::od::OdValue>::DATA_TYPE as u16 == #core::od::DataType::#dt_ident as u16,
            "the field type does not have the data type its name implies"
        );
    });

    // Limits and default.
    for (what, v) in [("min", &a.min), ("max", &a.max), ("default", &a.default)] {
        if let Some((lit, e)) = v {
            check_value(lit, &st, e, what)?;
        }
    }
    let num = |v: &Option<(ConstLit, Expr)>| v.as_ref().and_then(|(l, _)| l.as_f64());
    if let (Some(lo), Some(hi)) = (num(&a.min), num(&a.max)) {
        if lo > hi {
            return Err(syn::Error::new_spanned(a.max.as_ref().map(|m| m.1.clone()), "max is less than min"));
        }
    }
    if let Some((dlit, dexpr)) = &a.default {
        if let Some(d) = dlit.as_f64() {
            if let Some(lo) = num(&a.min) {
                if d < lo {
                    return Err(syn::Error::new_spanned(
                        dexpr,
                        format!(
                            "default value {} is below the low limit (min = {})",
                            dlit.show(),
                            a.min.as_ref().map(|m| m.0.show()).unwrap_or_default()
                        ),
                    ));
                }
            }
            if let Some(hi) = num(&a.max) {
                if d > hi {
                    return Err(syn::Error::new_spanned(
                        dexpr,
                        format!(
                            "default value {} is above the high limit (max = {})",
                            dlit.show(),
                            a.max.as_ref().map(|m| m.0.show()).unwrap_or_default()
                        ),
                    ));
                }
            }
        }
    }
    let default = opt(a.default.as_ref().map(|(l, _)| value_tokens(core, l, &st)));
    let low = opt(a.min.as_ref().map(|(l, _)| value_tokens(core, l, &st)));
    let high = opt(a.max.as_ref().map(|(l, _)| value_tokens(core, l, &st)));
    let limits = limit_check(core, &st, a.min.as_ref().map(|m| &m.0), a.max.as_ref().map(|m| &m.0), &low, &high);
    let _ = readable;
    // Sub-index 00h of an ARRAY or RECORD holds its fixed count: `const` (the default) or `ro`.
    let count_access = match &a.count_access {
        None => None,
        Some((_, sp)) if len.is_none() && !matches!(a.sub, Some(SubSpec::One(1.., _))) => {
            return Err(syn::Error::new(*sp, "count_access applies to an array field or a record member"));
        }
        Some((s, _)) if s == "const" => None,
        Some((s, _)) if s == "ro" => Some(quote!(#core::od::Access::Ro)),
        Some((_, sp)) => {
            return Err(syn::Error::new(
                *sp,
                "count_access must be \"ro\" or \"const\": sub-index 0 holds the fixed number of entries",
            ))
        }
    };

    let data = |sub: u8, n: u8| DataField {
        count_ro: count_access.is_some(),
        check: a.check.clone(),
        on_write: a.on_write.clone(),
        min: a.min.as_ref().map(|m| m.0.clone()),
        max: a.max.as_ref().map(|m| m.0.clone()),
        default: a.default.as_ref().map(|d| d.0.clone()),
        default_ts: default.clone(),
        ..plain(sub, n, st.dt, if st.fixed { Kind::Fixed(elem_ty.clone()) } else { Kind::Text(elem_ty.clone()) })
    };
    let make = |sub: u8, name: String, numbered: bool, member: Ts| Row {
        index,
        sub,
        name,
        numbered,
        dt: st.dt,
        access: access.clone(),
        pdo: pdo.clone(),
        mapped,
        max_size: quote!(<#elem_ty as #core::od::OdValue>::MAX_SIZE),
        default: default.clone(),
        low: low.clone(),
        high: high.clone(),
        limits: limits.clone(),
        writable,
        count_access: count_access.clone(),
        target: Target::Field {
            member,
            ty: elem_ty.clone(),
            st: st.clone(),
            check: a.check.clone(),
            on_write: a.on_write.clone(),
        },
        span: key_span,
        field: fname.into(),
    };

    match len {
        Some(n) => {
            let first = match a.sub {
                None => 1u8,
                Some(SubSpec::Range(lo, hi, sp)) => {
                    if lo == 0 || usize::from(hi) + 1 != usize::from(lo) + n {
                        return Err(syn::Error::new(
                            sp,
                            format!(
                                "the sub-index range must start at 1 or more and have {n} elements, like the array"
                            ),
                        ));
                    }
                    lo
                }
                Some(SubSpec::One(_, sp)) => {
                    return Err(syn::Error::new(sp, format!("an array field takes a sub-index range: `sub = 1..={n}`")))
                }
            };
            let mut rows: Vec<Row> = (0..n)
                .map(|i| {
                    let li = proc_macro2::Literal::usize_unsuffixed(i);
                    make(first + i as u8, name.clone(), true, quote!(#fident[#li]))
                })
                .collect();
            let highest = first + (n - 1) as u8;
            rows.push(count_row(core, index, highest, key_span, fname, count_access.clone()));
            let object = Object { index, name, code: "Array", span: key_span, field: fname.into() };
            Ok((rows, Some(object), data(first, n as u8)))
        }
        None => match a.sub {
            None | Some(SubSpec::One(0, _)) => {
                let row = make(0, name.clone(), false, quote!(#fident));
                let object = Object { index, name, code: "Var", span: key_span, field: fname.into() };
                Ok((vec![row], Some(object), data(0, 1)))
            }
            Some(SubSpec::One(s, _)) => Ok((vec![make(s, name, false, quote!(#fident))], None, data(s, 0))),
            Some(SubSpec::Range(_, _, sp)) => Err(syn::Error::new(sp, "a sub-index range needs an array field")),
        },
    }
}

/// The README's example, compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctest;
