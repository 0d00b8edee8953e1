//! CiA 306 EDS (electronic data sheet) export from the same description the dictionary runs on.
//!
//! The dictionary layer's part: [`write_object`] writes to any [`core::fmt::Write`] (no heap) one
//! section per object (`[2001]`) and per sub-entry of an ARRAY/RECORD (`[1018sub1]`, hex sub-index) with
//! ParameterName, ObjectType, DataType, AccessType, DefaultValue, PDOMapping, LowLimit/HighLimit and
//! SubNumber (OD-11).
//!
//! What the format choices rely on (python `canopen` 2.4.1, `canopen/objectdictionary/eds.py`, read for
//! this; and the EDS sample of a CiA 306 device description tutorial):
//! - `import_eds` parses `[DeviceInfo]` numbers with `int(x, 0)` and raises on an empty one, so every
//!   numeric field is always written (a missing default becomes `0`); `BaudRate_<kbit>` keys are looked up
//!   with exactly that spelling; `[DummyUsage]` is read with `getint` for all of `Dummy0001`..`Dummy0007`,
//!   so all seven are written (as 0: no dummy mapping).
//! - Object sections match `^[0-9A-Fa-f]{4}$` and sub-entry sections `^XXXXsub<hex>$`; an object section
//!   must come before its sub-entries (it is looked up by index when the sub section is read).
//! - `ObjectType` and `DataType` are parsed with `int(x, 0)`: written `0x7` and `0x0007`. DOMAIN entries
//!   are VAR objects (`ObjectType=0x7`) with `DataType=0x000F`.
//! - `DefaultValue`: integers by `int(x, 0)` (unsigned in hex `0x…`, signed in decimal so negative values
//!   parse), `$NODEID+0x…` for node-ID-relative values, REAL32/64 by `float(x)`, VISIBLE/UNICODE_STRING
//!   verbatim, OCTET_STRING by `bytes.fromhex(x)` (hex pairs, no prefix). A DOMAIN gets a DefaultValue only
//!   when its description has one (the derive's `eds_default`: text written as it is, which python keeps as
//!   its raw text and re-exports unchanged even when it is no hex pairs).
//! - `LowLimit`/`HighLimit`: signed limits of INTEGER8/16/32/64 go through `int(x, 0)` then a two's
//!   complement fix-up, so decimal negatives are fine; python ignores limits of the other widths.
//! - `AccessType` is lower-cased by python and compared with ro/wo/rw/rwr/rww/const.
//! - The INI reader treats `;` after whitespace as a comment: keep `" ;"` out of names and strings.

use core::fmt::{self, Write};

use super::{Access, DataType, EntryDesc, ObjectCode, ObjectDesc, OdDescribe, PdoMapping, Value};

/// The EDS spelling of an access type.
///
/// ```
/// use canopen_core::od::{eds::access_str, Access};
/// assert_eq!(access_str(Access::Const), "const");
/// ```
pub const fn access_str(a: Access) -> &'static str {
    match a {
        Access::Ro => "ro",
        Access::Wo => "wo",
        Access::Rw => "rw",
        Access::Rwr => "rwr",
        Access::Rww => "rww",
        Access::Const => "const",
    }
}

fn is_string(dt: DataType) -> bool {
    matches!(dt, DataType::VisibleString | DataType::UnicodeString | DataType::OctetString)
}

/// Writes `v` in the EDS syntax for data type `dt` (see the module docs).
///
/// ```
/// use canopen_core::od::{eds::write_value, DataType, Value};
/// let mut s = heapless::String::<32>::new();
/// write_value(&mut s, DataType::Unsigned32, &Value::NodeIdPlus(0x180)).unwrap();
/// assert_eq!(s.as_str(), "$NODEID+0x180");
/// ```
pub fn write_value<W: Write>(w: &mut W, dt: DataType, v: &Value) -> fmt::Result {
    match *v {
        Value::Bool(b) => write!(w, "{}", u8::from(b)),
        Value::Int(i) => write!(w, "{i}"),
        Value::Uint(u) => write!(w, "0x{u:X}"),
        Value::Real32(f) => write!(w, "{f}"),
        Value::Real64(f) => write!(w, "{f}"),
        Value::Str(s) if dt == DataType::OctetString => s.bytes().try_for_each(|b| write!(w, "{b:02X}")),
        Value::Str(s) => w.write_str(s),
        Value::Bytes(b) => b.iter().try_for_each(|b| write!(w, "{b:02X}")),
        Value::NodeIdPlus(n) => write!(w, "$NODEID+0x{n:X}"),
    }
}

fn write_entry_fields<W: Write>(w: &mut W, e: &EntryDesc) -> fmt::Result {
    writeln!(w, "DataType=0x{:04X}", e.data_type as u16)?;
    writeln!(w, "AccessType={}", access_str(e.access))?;
    match (&e.default, e.data_type) {
        (None, DataType::Domain) => {}
        (Some(v), dt) => {
            w.write_str("DefaultValue=")?;
            write_value(w, dt, v)?;
            w.write_char('\n')?;
        }
        (None, dt) if is_string(dt) => writeln!(w, "DefaultValue=")?,
        (None, _) => writeln!(w, "DefaultValue=0")?,
    }
    writeln!(w, "PDOMapping={}", u8::from(e.pdo != PdoMapping::No))?;
    for (key, v) in [("LowLimit", &e.low), ("HighLimit", &e.high)] {
        if let Some(v) = v {
            write!(w, "{key}=")?;
            write_value(w, e.data_type, v)?;
            w.write_char('\n')?;
        }
    }
    Ok(())
}

fn write_name<W: Write>(w: &mut W, e: &EntryDesc) -> fmt::Result {
    if e.numbered {
        writeln!(w, "ParameterName={} {}", e.name, e.sub)
    } else {
        writeln!(w, "ParameterName={}", e.name)
    }
}

/// Writes the section of object `o` and the sections of its sub-entries, as found in `od`.
///
/// ```
/// use canopen_core::od::{eds::write_object, lookup, DataType, EntryDesc, ObjectCode, ObjectDesc, OdDescribe};
/// # use canopen_core::od::Access;
/// struct One;
/// const E: EntryDesc = EntryDesc::var(0x2000, 0, "Speed", DataType::Unsigned16, Access::Rw);
/// impl OdDescribe for One {
///     fn object_count(&self) -> usize { 1 }
///     fn object(&self, n: usize) -> Option<ObjectDesc> {
///         (n == 0).then_some(ObjectDesc { index: 0x2000, name: "Speed", code: ObjectCode::Var, first: 0, subs: 1 })
///     }
///     fn entry(&self, index: u16, sub: u8) -> Option<EntryDesc> { (index == 0x2000 && sub == 0).then_some(E) }
/// }
/// let mut s = heapless::String::<256>::new();
/// write_object(&mut s, &One, &One.object(0).unwrap()).unwrap();
/// assert!(s.starts_with("[2000]\nParameterName=Speed\nObjectType=0x7\n"));
/// ```
pub fn write_object<W: Write, D: OdDescribe + ?Sized>(w: &mut W, od: &D, o: &ObjectDesc) -> fmt::Result {
    writeln!(w, "[{:04X}]", o.index)?;
    match o.code {
        ObjectCode::Array | ObjectCode::Record => {
            writeln!(w, "ParameterName={}", o.name)?;
            writeln!(w, "ObjectType=0x{:X}", o.code as u8)?;
            writeln!(w, "SubNumber=0x{:X}\n", o.subs)?;
            for sub in 0..=255u8 {
                if let Some(e) = od.entry(o.index, sub) {
                    writeln!(w, "[{:04X}sub{:X}]", o.index, sub)?;
                    write_name(w, &e)?;
                    writeln!(w, "ObjectType=0x7")?;
                    write_entry_fields(w, &e)?;
                    w.write_char('\n')?;
                }
            }
            Ok(())
        }
        _ => {
            writeln!(w, "ParameterName={}", o.name)?;
            writeln!(w, "ObjectType=0x7")?;
            if let Some(e) = od.entry(o.index, 0) {
                write_entry_fields(w, &e)?;
            }
            w.write_char('\n')
        }
    }
}
