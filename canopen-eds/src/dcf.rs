//! DCF out: from a node's EDS and the values a master configured, the node's DCF (CiA 306); from a DCF, the
//! concise DCF a CANopen manager downloads to 1F22h (CiA 302-3); and the concise DCF parsed back.
//!
//! What this relies on, from the public descriptions of the two documents:
//!
//! - CiA 306 (electronic data sheet specification): a DCF is an EDS of one configured device. Each entry may
//!   carry `ParameterValue=`, its configured value in the same notation as `DefaultValue` (numbers in
//!   decimal or `0x` hex, `$NODEID` allowed, strings as they are, OCTET_STRING as hex pairs), and the file
//!   has a `[DeviceComissioning]` section (one m) with `NodeID`, `NodeName`, `Baudrate` (kbit/s),
//!   `NetNumber`, `NetworkName`, `CANopenManager` (0/1) and `LSS_SerialNumber`.
//! - CiA 302-3 (configuration and program download), object 1F22h "concise DCF": a DOMAIN per node
//!   holding UNSIGNED32 the number of entries, then per entry UNSIGNED16 index, UNSIGNED8 sub-index,
//!   UNSIGNED32 the data size in bytes, and the data, all little-endian as every CANopen value is; a
//!   manager writes each entry to the node by SDO.
//!
//! Choices made here where the descriptions leave room:
//!
//! - A configured value is given as the bytes the master wrote (the SDO download's data), which is what a
//!   concise DCF holds; the DCF writes it in the notation above: unsigned integers in `0x` hex, signed ones
//!   in decimal, REAL32/REAL64 in the shortest decimal that reads back to the same bits, VISIBLE_STRING and
//!   UNICODE_STRING as text, OCTET_STRING and DOMAIN as hex pairs, TIME_OF_DAY and TIME_DIFFERENCE as the
//!   48-bit unsigned number of their 6 bytes. A value whose text a DCF line cannot hold is refused (an
//!   empty string, one with a line break or with leading or trailing spaces, which a reader trims).
//! - The concise DCF holds every entry with a `ParameterValue` that a master can write (`rw`, `wo`), in
//!   index and sub-index order: `ro` and `const` values describe the device, they configure nothing.
//!   `$NODEID` is the `[DeviceComissioning]` node-ID.

use std::fmt;

use crate::eds::{eval_typed, type_range, Access, DeviceCommissioning, Eds, Entry};

/// A value a master configured: what it wrote to `index:sub`, as the data of the SDO download. It is also
/// one entry of a concise DCF.
///
/// ```
/// let heartbeat = canopen_eds::Configured::new(0x1017, 0, 1000u16.to_le_bytes());
/// assert_eq!((heartbeat.index, heartbeat.sub, heartbeat.data.as_slice()), (0x1017, 0, &[0xE8, 0x03][..]));
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Configured {
    /// Object index.
    pub index: u16,
    /// Sub-index.
    pub sub: u8,
    /// The value's bytes, little-endian as CANopen sends them.
    pub data: Vec<u8>,
}

impl Configured {
    /// `data` written to `index:sub`.
    ///
    /// ```
    /// let name = canopen_eds::Configured::new(0x2004, 0, "idle");
    /// assert_eq!(name.data, b"idle");
    /// ```
    pub fn new(index: u16, sub: u8, data: impl Into<Vec<u8>>) -> Configured {
        Configured { index, sub, data: data.into() }
    }
}

/// Why a DCF or concise DCF could not be made: the entry and what is wrong with it.
///
/// ```
/// let eds = canopen_eds::Eds::parse("[1017]\nDataType=0x0006\nAccessType=rw\n").unwrap();
/// let c = canopen_eds::DeviceCommissioning::new(5, 500);
/// let e = eds.to_dcf(c, &[canopen_eds::Configured::new(0x1017, 0, [1, 2, 3])]).unwrap_err();
/// assert_eq!(e.to_string(), "1017h:00: 3 bytes for UNSIGNED16, which has 2");
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DcfError {
    /// Object index.
    pub index: u16,
    /// Sub-index.
    pub sub: u8,
    /// What is wrong.
    pub what: String,
}

impl fmt::Display for DcfError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:04X}h:{:02X}: {}", self.index, self.sub, self.what)
    }
}

impl std::error::Error for DcfError {}

/// The size in bytes of a data type's values, `None` for the ones of any length (strings, DOMAIN) and the
/// ones this crate does not know.
fn fixed_size(data_type: u16) -> Option<usize> {
    Some(match data_type {
        0x0001 | 0x0002 | 0x0005 => 1,
        0x0003 | 0x0006 => 2,
        0x0010 | 0x0016 => 3,
        0x0004 | 0x0007 | 0x0008 => 4,
        0x0012 | 0x0018 => 5,
        0x000C | 0x000D | 0x0013 | 0x0019 => 6,
        0x0014 | 0x001A => 7,
        0x0011 | 0x0015 | 0x001B => 8,
        _ => return None,
    })
}

fn type_name(data_type: u16) -> String {
    crate::eds::data_type_name(data_type).map_or_else(|| format!("data type {data_type:04X}h"), str::to_owned)
}

fn hex_pairs(data: &[u8]) -> String {
    data.iter().map(|b| format!("{b:02X}")).collect()
}

/// A text a DCF line holds as it is: not empty, no line break or other control character, nothing a reader
/// trims.
fn line_safe(text: String) -> Result<String, String> {
    if text.is_empty() || text.trim() != text || text.chars().any(char::is_control) {
        Err(format!("{text:?} cannot be written on a DCF line (empty, a control character or edge spaces)"))
    } else {
        Ok(text)
    }
}

/// The DCF notation of `data`, a value of `data_type` (see the module docs).
fn value_text(data: &[u8], data_type: u16) -> Result<String, String> {
    if let Some(size) = fixed_size(data_type) {
        if data.len() != size {
            return Err(format!("{} bytes for {}, which has {size}", data.len(), type_name(data_type)));
        }
    }
    let mut raw = [0u8; 8];
    raw[..data.len().min(8)].copy_from_slice(&data[..data.len().min(8)]);
    let unsigned = u64::from_le_bytes(raw);
    match data_type {
        0x0001 if unsigned > 1 => Err(format!("BOOLEAN {unsigned} is not 0 or 1")),
        0x0008 => Ok(format!("{:?}", f32::from_le_bytes([raw[0], raw[1], raw[2], raw[3]]))),
        0x0011 => Ok(format!("{:?}", f64::from_le_bytes(raw))),
        0x0009 => String::from_utf8(data.to_vec()).map_err(|_| "not UTF-8 text".to_owned()).and_then(line_safe),
        0x000B if data.len() % 2 != 0 => Err("an odd number of bytes for UNICODE_STRING".into()),
        0x000B => {
            let units: Vec<u16> = data.chunks_exact(2).map(|c| u16::from_le_bytes([c[0], c[1]])).collect();
            String::from_utf16(&units).map_err(|_| "not UTF-16 text".to_owned()).and_then(line_safe)
        }
        0x000A | 0x000F => line_safe(hex_pairs(data)),
        _ if type_range(data_type).is_some_and(|(lo, _)| lo < 0) => {
            let bits = 8 * data.len() as u32;
            let shift = 64 - bits;
            Ok(((unsigned << shift) as i64 >> shift).to_string())
        }
        _ if fixed_size(data_type).is_some() => Ok(format!("0x{unsigned:X}")),
        _ => Err(format!("{} has no DCF notation here", type_name(data_type))),
    }
}

/// The bytes of a DCF value of `data_type` (the inverse of [`value_text`]), `$NODEID` being `node_id`.
fn value_bytes(text: &str, data_type: u16, node_id: u8) -> Result<Vec<u8>, String> {
    let not_number = || format!("'{text}' is not a {}", type_name(data_type));
    let t = text.trim();
    let hex = t.strip_prefix("0x").or_else(|| t.strip_prefix("0X"));
    match data_type {
        // REAL32/REAL64: a decimal number, or the bits in hex as some tools write them.
        0x0008 => match hex {
            Some(h) => u32::from_str_radix(h, 16).ok(),
            None => t.parse::<f32>().ok().map(f32::to_bits),
        }
        .map(|b| b.to_le_bytes().to_vec())
        .ok_or_else(not_number),
        0x0011 => match hex {
            Some(h) => u64::from_str_radix(h, 16).ok(),
            None => t.parse::<f64>().ok().map(f64::to_bits),
        }
        .map(|b| b.to_le_bytes().to_vec())
        .ok_or_else(not_number),
        0x0009 => Ok(text.as_bytes().to_vec()),
        0x000B => Ok(text.encode_utf16().flat_map(u16::to_le_bytes).collect()),
        0x000A | 0x000F => {
            let hex: String = text.split_whitespace().collect();
            (0..hex.len())
                .step_by(2)
                .map(|i| hex.get(i..i + 2).and_then(|b| u8::from_str_radix(b, 16).ok()))
                .collect::<Option<Vec<u8>>>()
                .ok_or_else(|| format!("'{text}' is not hex pairs"))
        }
        _ => {
            let size =
                fixed_size(data_type).ok_or_else(|| format!("{} has no DCF notation here", type_name(data_type)))?;
            // TIME_OF_DAY and TIME_DIFFERENCE: their 6 bytes as an unsigned number.
            let (lo, hi) = type_range(data_type).unwrap_or((0, (1 << 48) - 1));
            let v = eval_typed(text, data_type, node_id)
                .filter(|v| (lo..=hi).contains(v))
                .ok_or_else(|| format!("'{text}' is not a {} (node-ID {node_id})", type_name(data_type)))?;
            Ok(v.to_le_bytes()[..size].to_vec())
        }
    }
}

impl Eds {
    /// The DCF of a node described by this EDS, configured with `values` and commissioned as `commissioning`:
    /// a copy with each value as its entry's `ParameterValue` and the `[DeviceComissioning]` section. Its
    /// text is `to_string()` ([`Display`](fmt::Display)). A value for an entry the EDS does not have, of
    /// the wrong size for its type, or whose text a DCF line cannot hold is an error.
    ///
    /// ```
    /// use canopen_eds::{Configured, DeviceCommissioning, Eds};
    /// let eds = Eds::parse("[1017]\nParameterName=Producer heartbeat time\nDataType=0x0006\nAccessType=rw\nDefaultValue=0\n").unwrap();
    /// let dcf = eds.to_dcf(DeviceCommissioning::new(5, 500), &[Configured::new(0x1017, 0, 250u16.to_le_bytes())]).unwrap();
    /// let text = dcf.to_string();
    /// assert!(text.contains("[DeviceComissioning]\nNodeID=5\n"));
    /// assert!(text.contains("DefaultValue=0\nPDOMapping=0\nParameterValue=0xFA\n"));
    /// ```
    pub fn to_dcf(&self, commissioning: DeviceCommissioning, values: &[Configured]) -> Result<Eds, DcfError> {
        let mut dcf = self.clone();
        for v in values {
            let err = |what: String| DcfError { index: v.index, sub: v.sub, what };
            let entry = dcf
                .objects
                .get_mut(&v.index)
                .and_then(|o| o.entries.get_mut(&v.sub))
                .ok_or_else(|| err("not in the EDS".into()))?;
            entry.value = Some(value_text(&v.data, entry.data_type).map_err(err)?);
        }
        dcf.commissioning = Some(commissioning);
        Ok(dcf)
    }
}

/// A concise DCF (CiA 302-3, the DOMAIN a manager holds in 1F22h for a node): the values to write, in order.
///
/// ```
/// use canopen_eds::{ConciseDcf, Configured};
/// let c = ConciseDcf { entries: vec![Configured::new(0x1017, 0, 1000u16.to_le_bytes())] };
/// let bytes = c.to_bytes();
/// assert_eq!(bytes, [1, 0, 0, 0, 0x17, 0x10, 0x00, 2, 0, 0, 0, 0xE8, 0x03]);
/// assert_eq!(ConciseDcf::parse(&bytes).unwrap(), c);
/// ```
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ConciseDcf {
    /// The entries in the order a manager writes them.
    pub entries: Vec<Configured>,
}

/// Why bytes are no concise DCF: the offset where it went wrong and what.
///
/// ```
/// let e = canopen_eds::ConciseDcf::parse(&[1, 0, 0, 0, 0x17, 0x10]).unwrap_err();
/// assert_eq!(e.to_string(), "concise DCF byte 4: entry 1 of 1 has 2 of its 7 header bytes");
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ConciseError {
    /// The byte offset where the fault starts.
    pub offset: usize,
    /// What is wrong.
    pub what: String,
}

impl fmt::Display for ConciseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "concise DCF byte {}: {}", self.offset, self.what)
    }
}

impl std::error::Error for ConciseError {}

impl ConciseDcf {
    /// The concise DCF of a DCF: every entry with a `ParameterValue` that a master can write (rw, wo), in
    /// index and sub-index order, `$NODEID` being the `[DeviceComissioning]` node-ID. A value that is no
    /// value of its type, or refers to `$NODEID` in a file without node-ID, is an error.
    ///
    /// ```
    /// use canopen_eds::{ConciseDcf, Eds};
    /// let dcf = Eds::parse("[DeviceComissioning]\nNodeID=5\n[1400]\nObjectType=9\n\
    ///     [1400sub1]\nDataType=7\nAccessType=rw\nParameterValue=$NODEID+0x200\n\
    ///     [1400sub2]\nDataType=5\nAccessType=ro\nParameterValue=1\n").unwrap();
    /// let c = ConciseDcf::from_dcf(&dcf).unwrap();
    /// assert_eq!(c.entries.len(), 1); // 1400h:02 is ro: it configures nothing
    /// assert_eq!(c.entries[0].data, 0x205u32.to_le_bytes());
    /// ```
    pub fn from_dcf(dcf: &Eds) -> Result<ConciseDcf, DcfError> {
        let node_id = dcf.commissioning.as_ref().map(|c| c.node_id);
        let writable = |e: &&Entry| matches!(e.access, Access::ReadWrite | Access::WriteOnly);
        let entries = dcf
            .entries()
            .filter(writable)
            .filter_map(|e| e.value.as_deref().map(|v| (e, v)))
            .map(|(e, v)| {
                let err = |what: String| DcfError { index: e.index, sub: e.sub, what };
                let id = match node_id {
                    Some(id) => id,
                    None if v.to_ascii_uppercase().contains("$NODEID") => {
                        return Err(err("$NODEID without [DeviceComissioning] NodeID".into()))
                    }
                    None => 0,
                };
                Ok(Configured::new(e.index, e.sub, value_bytes(v, e.data_type, id).map_err(err)?))
            })
            .collect::<Result<_, _>>()?;
        Ok(ConciseDcf { entries })
    }

    /// The bytes of 1F22h: the number of entries, then index, sub-index, size and data of each, all
    /// little-endian.
    ///
    /// ```
    /// let c = canopen_eds::ConciseDcf { entries: vec![canopen_eds::Configured::new(0x2000, 3, [7])] };
    /// assert_eq!(c.to_bytes(), [1, 0, 0, 0, 0x00, 0x20, 3, 1, 0, 0, 0, 7]);
    /// ```
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = (self.entries.len() as u32).to_le_bytes().to_vec();
        for e in &self.entries {
            out.extend_from_slice(&e.index.to_le_bytes());
            out.push(e.sub);
            out.extend_from_slice(&(e.data.len() as u32).to_le_bytes());
            out.extend_from_slice(&e.data);
        }
        out
    }

    /// Parses the bytes of 1F22h. Too few bytes for the count, an entry's header or its data, and bytes
    /// after the last entry, are errors with the offset; nothing is allocated ahead of the bytes there are.
    ///
    /// ```
    /// let c = canopen_eds::ConciseDcf::parse(&[1, 0, 0, 0, 0x00, 0x20, 3, 1, 0, 0, 0, 7]).unwrap();
    /// assert_eq!((c.entries[0].index, c.entries[0].sub, c.entries[0].data.as_slice()), (0x2000, 3, &[7u8][..]));
    /// assert!(canopen_eds::ConciseDcf::parse(&[0, 0, 0, 0, 9]).is_err()); // a byte after the last entry
    /// ```
    pub fn parse(bytes: &[u8]) -> Result<ConciseDcf, ConciseError> {
        let err = |offset: usize, what: String| ConciseError { offset, what };
        let count = bytes
            .get(..4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .ok_or_else(|| err(0, format!("{} bytes, too few for the number of entries", bytes.len())))?;
        let mut at = 4;
        let mut entries = Vec::new();
        for n in 1..=count {
            let header = bytes.get(at..at + 7).ok_or_else(|| {
                err(at, format!("entry {n} of {count} has {} of its 7 header bytes", bytes.len() - at))
            })?;
            let size = u32::from_le_bytes([header[3], header[4], header[5], header[6]]) as usize;
            let data = bytes.get(at + 7..).and_then(|rest| rest.get(..size)).ok_or_else(|| {
                err(at + 7, format!("entry {n} of {count} has {} of its {size} data bytes", bytes.len() - at - 7))
            })?;
            entries.push(Configured::new(u16::from_le_bytes([header[0], header[1]]), header[2], data));
            at += 7 + size;
        }
        if at != bytes.len() {
            return Err(err(at, format!("{} bytes after the last of {count} entries", bytes.len() - at)));
        }
        Ok(ConciseDcf { entries })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An EDS of every data type the DCF notation covers, each entry rw.
    fn all_types_eds() -> Eds {
        let mut text = String::new();
        for (i, dt) in [1u16, 2, 3, 4, 5, 6, 7, 8, 9, 0xA, 0xB, 0xC, 0xD, 0xF, 0x10, 0x11, 0x12, 0x15, 0x16, 0x1B]
            .into_iter()
            .enumerate()
        {
            text += &format!("[{:04X}]\nParameterName=T{dt:X}\nDataType=0x{dt:04X}\nAccessType=rw\n", 0x2000 + i);
        }
        text += "[1017]\nParameterName=Producer heartbeat time\nDataType=0x0006\nAccessType=rw\nDefaultValue=0\n\
                 [1018]\nObjectType=9\n[1018sub1]\nParameterName=Vendor-ID\nDataType=7\nAccessType=ro\nDefaultValue=0x1\n";
        Eds::parse(&text).unwrap()
    }

    /// EDS + configured values -> DCF text -> parse -> concise DCF -> bytes -> parse: the same values come
    /// out, for every data type, extreme values and negative numbers included.
    #[test]
    fn eds_to_dcf_to_concise_round_trip() {
        let eds = all_types_eds();
        let values = vec![
            Configured::new(0x1017, 0, 1000u16.to_le_bytes()),
            Configured::new(0x2000, 0, [1]),
            Configured::new(0x2001, 0, (-128i8).to_le_bytes()),
            Configured::new(0x2002, 0, (-2i16).to_le_bytes()),
            Configured::new(0x2003, 0, i32::MIN.to_le_bytes()),
            Configured::new(0x2004, 0, [0xFF]),
            Configured::new(0x2005, 0, 0xBEEFu16.to_le_bytes()),
            Configured::new(0x2006, 0, u32::MAX.to_le_bytes()),
            Configured::new(0x2007, 0, (-1.25e-7f32).to_le_bytes()),
            Configured::new(0x2008, 0, "Pump 2"),
            Configured::new(0x2009, 0, [0x00, 0xFF, 0x10]),
            Configured::new(0x200A, 0, "grün\u{2713}".encode_utf16().flat_map(u16::to_le_bytes).collect::<Vec<u8>>()),
            Configured::new(0x200B, 0, [1, 2, 3, 4, 5, 6]),
            Configured::new(0x200C, 0, [0xFF; 6]),
            Configured::new(0x200D, 0, [0xDE, 0xAD]),
            Configured::new(0x200E, 0, [0x00, 0x00, 0x80]), // INTEGER24 -8388608
            Configured::new(0x200F, 0, std::f64::consts::PI.to_le_bytes()),
            Configured::new(0x2010, 0, [0xFF, 0xFF, 0xFF, 0xFF, 0x7F]), // INTEGER40 max
            Configured::new(0x2011, 0, i64::MIN.to_le_bytes()),
            Configured::new(0x2012, 0, [1, 2, 3]),
            Configured::new(0x2013, 0, u64::MAX.to_le_bytes()),
        ];
        let mut c = DeviceCommissioning::new(0x22, 250);
        c.node_name = "Pump 2".into();
        let dcf = eds.to_dcf(c.clone(), &values).unwrap();
        let text = dcf.to_string();
        let back = Eds::parse(&text).unwrap();
        assert_eq!(back, dcf, "{text}");
        assert_eq!(back.commissioning, Some(c));
        assert!(text.contains("ParameterValue=-2147483648\n") && text.contains("ParameterValue=0xFFFFFFFF\n"));
        let concise = ConciseDcf::from_dcf(&back).unwrap();
        assert_eq!(concise.entries, values);
        assert_eq!(ConciseDcf::parse(&concise.to_bytes()).unwrap(), concise);
    }

    #[test]
    fn values_a_dcf_cannot_hold_are_errors() {
        let eds = all_types_eds();
        let c = || DeviceCommissioning::new(5, 500);
        let fails = |v: Configured| eds.to_dcf(c(), &[v]).unwrap_err().to_string();
        assert_eq!(fails(Configured::new(0x3000, 0, [1])), "3000h:00: not in the EDS");
        assert_eq!(fails(Configured::new(0x2004, 0, [1, 2])), "2004h:00: 2 bytes for UNSIGNED8, which has 1");
        assert_eq!(fails(Configured::new(0x2000, 0, [2])), "2000h:00: BOOLEAN 2 is not 0 or 1");
        assert!(fails(Configured::new(0x2008, 0, "two\nlines")).contains("cannot be written on a DCF line"));
        assert!(fails(Configured::new(0x2008, 0, " edge")).contains("cannot be written on a DCF line"));
        assert!(fails(Configured::new(0x2008, 0, [0xC3])).contains("not UTF-8"));
        assert!(fails(Configured::new(0x200A, 0, [0x41])).contains("odd number"));
        // Values in a DCF that are no values of their type.
        for (section, what) in [
            ("[2004]\nDataType=5\nAccessType=rw\nParameterValue=0x100\n", "'0x100' is not a UNSIGNED8"),
            ("[2009]\nDataType=0xA\nAccessType=wo\nParameterValue=zz\n", "'zz' is not hex pairs"),
            ("[1400sub1]\nDataType=7\nAccessType=rw\nParameterValue=$NODEID+0x200\n", "without [DeviceComissioning]"),
        ] {
            let dcf = Eds::parse(&format!("[1400]\nObjectType=9\n{section}")).unwrap();
            let e = ConciseDcf::from_dcf(&dcf).unwrap_err().to_string();
            assert!(e.contains(what), "{section}: {e}");
        }
    }

    /// Every truncation of a valid concise DCF, and every extension, is an error with the offset, never a
    /// panic.
    #[test]
    fn malformed_concise_dcf_is_an_error() {
        let c = ConciseDcf { entries: vec![Configured::new(0x1017, 0, [0xE8, 3]), Configured::new(0x1800, 1, [])] };
        let bytes = c.to_bytes();
        assert_eq!(ConciseDcf::parse(&bytes).unwrap(), c);
        for len in 0..bytes.len() {
            let e = ConciseDcf::parse(&bytes[..len]).unwrap_err();
            assert!(e.offset <= len, "{len}: {e}");
        }
        let mut long = bytes.clone();
        long.push(0);
        assert_eq!(ConciseDcf::parse(&long).unwrap_err().offset, bytes.len());
        // A count far beyond the bytes: an error, nothing reserved for it.
        assert!(ConciseDcf::parse(&[0xFF, 0xFF, 0xFF, 0xFF]).is_err());
        // A size beyond the bytes.
        assert_eq!(ConciseDcf::parse(&[1, 0, 0, 0, 0, 0x20, 0, 0xFF, 0xFF, 0xFF, 0xFF]).unwrap_err().offset, 11);
    }
}
