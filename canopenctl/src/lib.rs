//! The parts of `canopenctl` worth testing without a bus: numbers in decimal or 0x-hex, values of every
//! CiA 301 basic type (negatives, floats, strings, bytes) to and from their SDO bytes, and the one-line
//! decoding of any CANopen frame that `canopenctl monitor` prints; and [`bench`](mod@bench), the SDO throughput bench.

#![warn(missing_docs)]

pub mod bench;

use std::fmt::Write as _;

use canopen_core::CanFrame;

/// Parses an integer in decimal or `0x`-hex, with an optional `-` and `_` separators.
///
/// ```
/// use canopenctl::parse_int;
/// assert_eq!(parse_int("0x1018").unwrap(), 0x1018);
/// assert_eq!(parse_int("-0x10").unwrap(), -16);
/// assert_eq!(parse_int("1_000").unwrap(), 1000);
/// assert!(parse_int("0x").is_err() && parse_int("12a").is_err());
/// ```
pub fn parse_int(text: &str) -> Result<i128, String> {
    let t = text.trim().replace('_', "");
    let (neg, t) = match t.strip_prefix('-') {
        Some(rest) => (true, rest.to_owned()),
        None => (false, t.strip_prefix('+').unwrap_or(&t).to_owned()),
    };
    let v = match t.strip_prefix("0x").or_else(|| t.strip_prefix("0X")) {
        Some(hex) => i128::from_str_radix(hex, 16),
        None => t.parse::<i128>(),
    }
    .map_err(|_| format!("'{text}' is not a number (decimal, or hex with 0x)"))?;
    Ok(if neg { -v } else { v })
}

/// Parses an integer that must fit `T` (node-IDs, indices, sub-indices).
///
/// ```
/// assert_eq!(canopenctl::parse_in::<u16>("0x6000").unwrap(), 0x6000);
/// assert!(canopenctl::parse_in::<u8>("256").is_err());
/// ```
pub fn parse_in<T: TryFrom<i128>>(text: &str) -> Result<T, String> {
    let v = parse_int(text)?;
    T::try_from(v).map_err(|_| format!("{text} is out of range"))
}

/// A node-ID: 1..=127 in decimal or 0x-hex.
///
/// ```
/// assert_eq!(canopenctl::parse_node("0x7F").unwrap(), 127);
/// assert!(canopenctl::parse_node("0").is_err() && canopenctl::parse_node("128").is_err());
/// ```
pub fn parse_node(text: &str) -> Result<u8, String> {
    match parse_in::<u8>(text) {
        Ok(n @ 1..=127) => Ok(n),
        _ => Err(format!("node-ID {text} is not in 1..=127")),
    }
}

/// The data types `--type` names (CiA 301 basic types; the EDS names work too).
///
/// ```
/// use canopenctl::Type;
/// assert_eq!("i16".parse::<Type>().unwrap(), Type::I16);
/// assert_eq!("UNSIGNED32".parse::<Type>().unwrap(), Type::U32);
/// assert_eq!("visible_string".parse::<Type>().unwrap(), Type::Str);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Type {
    /// BOOLEAN.
    Bool,
    /// UNSIGNED8.
    U8,
    /// UNSIGNED16.
    U16,
    /// UNSIGNED32.
    U32,
    /// UNSIGNED64.
    U64,
    /// INTEGER8.
    I8,
    /// INTEGER16.
    I16,
    /// INTEGER32.
    I32,
    /// INTEGER64.
    I64,
    /// REAL32.
    F32,
    /// REAL64.
    F64,
    /// VISIBLE_STRING (UTF-8 text).
    Str,
    /// OCTET_STRING / DOMAIN as hex bytes (`01 02 ff` or `0102ff`).
    Bytes,
}

impl std::str::FromStr for Type {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Ok(match s.to_ascii_lowercase().as_str() {
            "bool" | "boolean" => Type::Bool,
            "u8" | "unsigned8" => Type::U8,
            "u16" | "unsigned16" => Type::U16,
            "u32" | "unsigned32" => Type::U32,
            "u64" | "unsigned64" => Type::U64,
            "i8" | "integer8" => Type::I8,
            "i16" | "integer16" => Type::I16,
            "i32" | "integer32" => Type::I32,
            "i64" | "integer64" => Type::I64,
            "f32" | "real32" => Type::F32,
            "f64" | "real64" => Type::F64,
            "str" | "string" | "visible_string" | "unicode_string" => Type::Str,
            "bytes" | "octet_string" | "domain" => Type::Bytes,
            _ => return Err(format!("unknown type '{s}' (u8..u64, i8..i64, f32, f64, bool, str, bytes)")),
        })
    }
}

impl Type {
    /// The type of a CiA 301 data type index (an EDS `DataType`); `None` for types without a text form here
    /// (INTEGER24, TIME_OF_DAY, ...: read as bytes).
    ///
    /// ```
    /// use canopenctl::Type;
    /// assert_eq!(Type::from_data_type(0x0003), Some(Type::I16));
    /// assert_eq!(Type::from_data_type(0x0009), Some(Type::Str));
    /// assert_eq!(Type::from_data_type(0x0010), None);
    /// ```
    pub fn from_data_type(data_type: u16) -> Option<Type> {
        Some(match data_type {
            0x0001 => Type::Bool,
            0x0002 => Type::I8,
            0x0003 => Type::I16,
            0x0004 => Type::I32,
            0x0005 => Type::U8,
            0x0006 => Type::U16,
            0x0007 => Type::U32,
            0x0008 => Type::F32,
            0x0009 | 0x000B => Type::Str,
            0x000A | 0x000F => Type::Bytes,
            0x0011 => Type::F64,
            0x0015 => Type::I64,
            0x001B => Type::U64,
            _ => return None,
        })
    }

    /// The type a value of `len` bytes is written as when no `--type` is given: an integer of that size
    /// (signed when the text is negative), a float for a text with a `.` or an exponent, a string for a text
    /// that is no number.
    ///
    /// ```
    /// use canopenctl::Type;
    /// assert_eq!(Type::infer("-100", Some(2)), Ok(Type::I16));
    /// assert_eq!(Type::infer("0x10", Some(4)), Ok(Type::U32));
    /// assert_eq!(Type::infer("1.5", Some(4)), Ok(Type::F32));
    /// assert_eq!(Type::infer("hello", None), Ok(Type::Str));
    /// assert!(Type::infer("7", None).is_err()); // a number needs the object's size or --type
    /// ```
    pub fn infer(text: &str, len: Option<usize>) -> Result<Type, String> {
        let is_int = parse_int(text).is_ok();
        let is_float = !is_int && text.parse::<f64>().is_ok();
        if !is_int && !is_float {
            return Ok(Type::Str);
        }
        let neg = text.trim().starts_with('-');
        Ok(match (len, is_float, neg) {
            (Some(4), true, _) => Type::F32,
            (Some(8), true, _) => Type::F64,
            (Some(1), false, false) => Type::U8,
            (Some(2), false, false) => Type::U16,
            (Some(4), false, false) => Type::U32,
            (Some(8), false, false) => Type::U64,
            (Some(1), false, true) => Type::I8,
            (Some(2), false, true) => Type::I16,
            (Some(4), false, true) => Type::I32,
            (Some(8), false, true) => Type::I64,
            (Some(n), _, _) => return Err(format!("the object has {n} bytes: give --type")),
            (None, _, _) => return Err("the object's size is unknown (it cannot be read): give --type".into()),
        })
    }

    /// The SDO bytes of `text` as this type, range-checked.
    ///
    /// ```
    /// use canopenctl::Type;
    /// assert_eq!(Type::I16.encode("-2").unwrap(), vec![0xFE, 0xFF]);
    /// assert_eq!(Type::U8.encode("0xFF").unwrap(), vec![0xFF]);
    /// assert!(Type::U8.encode("256").is_err() && Type::U8.encode("-1").is_err());
    /// assert_eq!(Type::F32.encode("1.5").unwrap(), 1.5f32.to_le_bytes().to_vec());
    /// assert_eq!(Type::Bytes.encode("01 02 ff").unwrap(), vec![1, 2, 0xFF]);
    /// assert_eq!(Type::Bool.encode("true").unwrap(), vec![1]);
    /// ```
    pub fn encode(self, text: &str) -> Result<Vec<u8>, String> {
        fn int<T: TryFrom<i128>>(text: &str, name: &str) -> Result<T, String> {
            parse_in::<T>(text).map_err(|_| format!("{text} does not fit {name}"))
        }
        let float = |t: &str| t.trim().parse::<f64>().map_err(|_| format!("'{t}' is not a number"));
        Ok(match self {
            Type::Bool => match text.trim().to_ascii_lowercase().as_str() {
                "true" | "1" => vec![1],
                "false" | "0" => vec![0],
                _ => return Err(format!("'{text}' is not a boolean (true, false, 1, 0)")),
            },
            Type::U8 => int::<u8>(text, "u8")?.to_le_bytes().to_vec(),
            Type::U16 => int::<u16>(text, "u16")?.to_le_bytes().to_vec(),
            Type::U32 => int::<u32>(text, "u32")?.to_le_bytes().to_vec(),
            Type::U64 => int::<u64>(text, "u64")?.to_le_bytes().to_vec(),
            Type::I8 => int::<i8>(text, "i8")?.to_le_bytes().to_vec(),
            Type::I16 => int::<i16>(text, "i16")?.to_le_bytes().to_vec(),
            Type::I32 => int::<i32>(text, "i32")?.to_le_bytes().to_vec(),
            Type::I64 => int::<i64>(text, "i64")?.to_le_bytes().to_vec(),
            Type::F32 => (float(text)? as f32).to_le_bytes().to_vec(),
            Type::F64 => float(text)?.to_le_bytes().to_vec(),
            Type::Str => text.as_bytes().to_vec(),
            Type::Bytes => {
                let hex: String = text.chars().filter(|c| !c.is_whitespace()).collect();
                let hex = hex.strip_prefix("0x").unwrap_or(&hex);
                if hex.len() % 2 != 0 {
                    return Err(format!("'{text}' is not whole hex bytes"));
                }
                (0..hex.len())
                    .step_by(2)
                    .map(|i| u8::from_str_radix(&hex[i..i + 2], 16).map_err(|_| format!("'{text}' is not hex bytes")))
                    .collect::<Result<_, _>>()?
            }
        })
    }

    /// The text of an uploaded value of this type.
    ///
    /// ```
    /// use canopenctl::Type;
    /// assert_eq!(Type::I16.decode(&[0xFE, 0xFF]).unwrap(), "-2");
    /// assert_eq!(Type::U32.decode(&[0x91, 0x01, 0x0F, 0x00]).unwrap(), "983441 (0x000F0191)");
    /// assert!(Type::U32.decode(&[1, 2]).is_err());
    /// ```
    pub fn decode(self, bytes: &[u8]) -> Result<String, String> {
        fn arr<const N: usize>(b: &[u8]) -> Result<[u8; N], String> {
            b.try_into().map_err(|_| format!("the object has {} bytes, the type {N}", b.len()))
        }
        Ok(match self {
            Type::Bool => (arr::<1>(bytes)?[0] != 0).to_string(),
            Type::U8 => unsigned(u64::from(arr::<1>(bytes)?[0]), 1),
            Type::U16 => unsigned(u64::from(u16::from_le_bytes(arr(bytes)?)), 2),
            Type::U32 => unsigned(u64::from(u32::from_le_bytes(arr(bytes)?)), 4),
            Type::U64 => unsigned(u64::from_le_bytes(arr(bytes)?), 8),
            Type::I8 => i8::from_le_bytes(arr(bytes)?).to_string(),
            Type::I16 => i16::from_le_bytes(arr(bytes)?).to_string(),
            Type::I32 => i32::from_le_bytes(arr(bytes)?).to_string(),
            Type::I64 => i64::from_le_bytes(arr(bytes)?).to_string(),
            Type::F32 => f32::from_le_bytes(arr(bytes)?).to_string(),
            Type::F64 => f64::from_le_bytes(arr(bytes)?).to_string(),
            Type::Str => String::from_utf8_lossy(bytes).trim_end_matches('\0').to_owned(),
            Type::Bytes => hex(bytes),
        })
    }
}

fn unsigned(v: u64, size: usize) -> String {
    format!("{v} (0x{v:0width$X})", width = size * 2)
}

/// Bytes as `01 02 FF`.
///
/// ```
/// assert_eq!(canopenctl::hex(&[1, 0xAB]), "01 AB");
/// ```
pub fn hex(bytes: &[u8]) -> String {
    let mut s = String::with_capacity(bytes.len() * 3);
    for (i, b) in bytes.iter().enumerate() {
        if i > 0 {
            s.push(' ');
        }
        let _ = write!(s, "{b:02X}");
    }
    s
}

/// The text of a value read without `--type`: a number for 1, 2, 4 or 8 bytes, a string when the bytes are
/// printable text, else hex bytes.
///
/// ```
/// assert_eq!(canopenctl::guess(&[0x91, 0x01, 0x0F, 0x00]), "983441 (0x000F0191)");
/// assert_eq!(canopenctl::guess(b"canopen example node"), "\"canopen example node\"");
/// assert_eq!(canopenctl::guess(&[1, 2, 3]), "01 02 03");
/// ```
pub fn guess(bytes: &[u8]) -> String {
    match bytes.len() {
        1 | 2 | 4 | 8 => {
            let mut b = [0u8; 8];
            b[..bytes.len()].copy_from_slice(bytes);
            unsigned(u64::from_le_bytes(b), bytes.len())
        }
        _ => match std::str::from_utf8(bytes) {
            Ok(s) if !s.is_empty() && s.chars().all(|c| !c.is_control() || c == '\0') => {
                format!("{:?}", s.trim_end_matches('\0'))
            }
            _ => hex(bytes),
        },
    }
}

fn nmt_state(code: u8) -> &'static str {
    match code & 0x7F {
        0x00 => "boot-up",
        0x04 => "stopped",
        0x05 => "operational",
        0x7F => "pre-operational",
        _ => "unknown state",
    }
}

fn mux(d: &[u8]) -> String {
    match d {
        [_, lo, hi, sub, ..] => format!("{:04X}h:{sub:02X}", u16::from_le_bytes([*lo, *hi])),
        _ => "?".into(),
    }
}

fn abort(d: &[u8]) -> String {
    let code = match d {
        [_, _, _, _, a, b, c, e] => u32::from_le_bytes([*a, *b, *c, *e]),
        _ => return "abort (short frame)".into(),
    };
    let meaning = canopen_master::abort_meaning(code).unwrap_or("unknown abort code");
    format!("abort {}: {:04X} {:04X}h {meaning}", mux(d), code >> 16, code & 0xFFFF)
}

fn expedited(d: &[u8]) -> String {
    let n = if d[0] & 0x01 != 0 { 4 - usize::from((d[0] >> 2) & 3) } else { 4 };
    hex(d.get(4..4 + n).unwrap_or(&[]))
}

/// What an SDO request (client → server, 600h + node) says. Block segments carry no command byte, so a
/// frame inside a sub-block reads as whatever its first byte would mean.
fn sdo_request(d: &[u8]) -> String {
    let Some(&b0) = d.first() else { return "empty".into() };
    match b0 >> 5 {
        1 if b0 & 0x02 != 0 => format!("download {} = {}", mux(d), expedited(d)),
        1 => format!("initiate download {}", mux(d)),
        0 => format!("download segment{}", if b0 & 1 != 0 { " (last)" } else { "" }),
        2 => format!("upload {}", mux(d)),
        3 => "upload segment".into(),
        4 => abort(d),
        6 if b0 & 1 == 0 => format!("block download {}", mux(d)),
        6 => "block download end".into(),
        5 => match b0 & 3 {
            0 => format!("block upload {}", mux(d)),
            3 => "block upload start".into(),
            2 => "block upload ack".into(),
            _ => "block upload end".into(),
        },
        _ => "unknown command".into(),
    }
}

/// What an SDO response (server → client, 580h + node) says.
fn sdo_response(d: &[u8]) -> String {
    let Some(&b0) = d.first() else { return "empty".into() };
    match b0 >> 5 {
        3 => format!("download {} done", mux(d)),
        1 => "download segment ack".into(),
        2 if b0 & 0x02 != 0 => format!("{} = {}", mux(d), expedited(d)),
        2 => format!("upload {} (segmented)", mux(d)),
        0 => format!("upload segment{}", if b0 & 1 != 0 { " (last)" } else { "" }),
        4 => abort(d),
        5 => "block download ack".into(),
        6 => "block upload".into(),
        _ => "unknown command".into(),
    }
}

/// One line describing `frame` (NMT, SYNC, EMCY, TIME, PDO with the pre-defined connection set, SDO,
/// heartbeat/boot-up/guarding, LSS).
///
/// ```
/// use canopen_core::CanFrame;
/// use canopenctl::describe;
/// assert_eq!(describe(&CanFrame::new(0x705, &[0x7F]).unwrap()), "heartbeat node 5: pre-operational");
/// assert_eq!(describe(&CanFrame::new(0x000, &[0x01, 0x00]).unwrap()), "NMT start all nodes");
/// assert_eq!(describe(&CanFrame::new(0x585, &[0x80, 0x00, 0x30, 0x00, 0x00, 0x00, 0x02, 0x06]).unwrap()),
///     "SDO response node 5: abort 3000h:00: 0602 0000h object does not exist in the object dictionary");
/// ```
pub fn describe(frame: &CanFrame) -> String {
    let (id, d) = (frame.cob_id(), frame.data());
    let node = (id & 0x7F) as u8;
    if frame.is_rtr() {
        return match id {
            0x701..=0x77F => format!("node guarding request node {node}"),
            _ => format!("remote request {id:03X}h"),
        };
    }
    match id {
        0x000 => {
            let cmd = match d.first() {
                Some(0x01) => "start",
                Some(0x02) => "stop",
                Some(0x80) => "enter pre-operational",
                Some(0x81) => "reset node",
                Some(0x82) => "reset communication",
                _ => "unknown command",
            };
            match d.get(1) {
                Some(0) => format!("NMT {cmd} all nodes"),
                Some(n) => format!("NMT {cmd} node {n}"),
                None => format!("NMT {cmd}"),
            }
        }
        0x080 => match d.first() {
            Some(c) => format!("SYNC counter {c}"),
            None => "SYNC".into(),
        },
        0x081..=0x0FF => match canopen_core::wire::emcy::Emergency::parse(d) {
            Ok(e) if e.code == 0 => format!("EMCY node {node}: error reset, register {:02X}h", e.register),
            Ok(e) => format!(
                "EMCY node {node}: code {:04X}h, register {:02X}h, data {}",
                e.code,
                e.register,
                hex(&e.manufacturer)
            ),
            Err(_) => format!("EMCY node {node} (malformed)"),
        },
        0x100 => "TIME".into(),
        0x181..=0x1FF | 0x281..=0x2FF | 0x381..=0x3FF | 0x481..=0x4FF => {
            format!("TPDO{} node {node}", (id >> 8) as u8)
        }
        0x201..=0x27F | 0x301..=0x37F | 0x401..=0x47F | 0x501..=0x57F => {
            format!("RPDO{} node {node}", (id >> 8) as u8 - 1)
        }
        0x581..=0x5FF => format!("SDO response node {node}: {}", sdo_response(d)),
        0x601..=0x67F => format!("SDO request node {node}: {}", sdo_request(d)),
        0x701..=0x77F => match d {
            [0] => format!("boot-up node {node}"),
            [s] if s & 0x80 != 0 => format!("guarding reply node {node}: {}", nmt_state(*s)),
            [s] => format!("heartbeat node {node}: {}", nmt_state(*s)),
            _ => format!("error control node {node} (malformed)"),
        },
        0x7E4 => format!("LSS response {:02X}h", d.first().copied().unwrap_or(0)),
        0x7E5 => format!("LSS request {:02X}h", d.first().copied().unwrap_or(0)),
        _ => String::new(),
    }
}

/// A candump-style line: interface, identifier, `[len]`, the bytes, and the description.
///
/// ```
/// use canopen_core::CanFrame;
/// let line = canopenctl::monitor_line("vcan0", &CanFrame::new(0x705, &[0x05]).unwrap());
/// assert_eq!(line, "  vcan0  705   [1]  05                        heartbeat node 5: operational");
/// ```
pub fn monitor_line(iface: &str, frame: &CanFrame) -> String {
    let data = if frame.is_rtr() { "remote request".to_owned() } else { hex(frame.data()) };
    format!("  {iface}  {:03X}   [{}]  {data:<24}  {}", frame.cob_id(), frame.dlc(), describe(frame))
        .trim_end()
        .to_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn f(id: u16, d: &[u8]) -> String {
        describe(&CanFrame::new(id, d).unwrap())
    }

    #[test]
    fn every_service_is_described() {
        assert_eq!(f(0x080, &[]), "SYNC");
        assert_eq!(
            f(0x085, &[0x34, 0x12, 0x01, 1, 2, 3, 4, 5]),
            "EMCY node 5: code 1234h, register 01h, data 01 02 03 04 05"
        );
        assert_eq!(f(0x185, &[1]), "TPDO1 node 5");
        assert_eq!(f(0x205, &[1]), "RPDO1 node 5");
        assert_eq!(f(0x485, &[1]), "TPDO4 node 5");
        assert_eq!(f(0x505, &[1]), "RPDO4 node 5");
        assert_eq!(f(0x605, &[0x40, 0x18, 0x10, 0x01, 0, 0, 0, 0]), "SDO request node 5: upload 1018h:01");
        assert_eq!(
            f(0x585, &[0x43, 0x00, 0x10, 0x00, 0x91, 0x01, 0x0F, 0x00]),
            "SDO response node 5: 1000h:00 = 91 01 0F 00"
        );
        assert_eq!(
            f(0x605, &[0x2B, 0x17, 0x10, 0x00, 0xE8, 0x03, 0, 0]),
            "SDO request node 5: download 1017h:00 = E8 03"
        );
        assert_eq!(f(0x705, &[0]), "boot-up node 5");
        assert_eq!(f(0x705, &[0x85]), "guarding reply node 5: operational");
        assert_eq!(describe(&CanFrame::new_rtr(0x705, 1).unwrap()), "node guarding request node 5");
        assert_eq!(f(0x7E5, &[0x51, 0, 0, 0, 0, 0x80, 0, 0]), "LSS request 51h");
        assert_eq!(f(0x123, &[]), "");
    }

    #[test]
    fn hostile_frames_never_panic() {
        for id in 0..=0x7FFu16 {
            for len in 0..=8 {
                let d = [0xFFu8; 8];
                let _ = describe(&CanFrame::new(id, &d[..len]).unwrap());
                let d = [0u8; 8];
                let _ = describe(&CanFrame::new(id, &d[..len]).unwrap());
            }
        }
    }

    #[test]
    fn values_round_trip_through_their_types() {
        for (t, v) in [
            (Type::I8, "-128"),
            (Type::I64, "-9223372036854775808"),
            (Type::U64, "18446744073709551615"),
            (Type::Str, "hé"),
        ] {
            let bytes = t.encode(v).unwrap();
            assert_eq!(t.decode(&bytes).unwrap().split(' ').next().unwrap(), v);
        }
        assert!(Type::I8.encode("128").is_err());
        assert!(Type::Bytes.encode("123").is_err());
    }
}

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctest;
