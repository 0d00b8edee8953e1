//! EDS/DCF import (CiA 306): the text of an electronic data sheet into a dictionary description, every
//! object with its sub-entries (index, sub-index, name, data type, access, default, limits, PDO mapping),
//! so that a master can type its reads and writes and accept names for numbers.
//!
//! What real files do is accepted: section names in either case (`[1a00]`, `[1A00sub1]`, `[3010Sub0]`),
//! numbers in decimal or `0x`-hex (`ObjectType=7`, `DataType=0x0007`), access in either case (`RW`),
//! defaults relative to the node-ID (`$NODEID+0x180`, `1280+$NODEID`), empty values, and arrays given
//! with `CompactSubObj` (their names from the `[xxxxName]` section). Unknown sections and keys are kept
//! out (sections that describe no object are kept for the writer); a malformed number, data type or access
//! type is an error naming its line and section, never a panic. DCF additions are read too: `ParameterValue`
//! (and `[xxxxValue]` of a `CompactSubObj` array) and `[DeviceComissioning]`.
//!
//! ```
//! use canopen_eds::{Access, Eds};
//! let eds = Eds::parse("[1017]\nParameterName=Producer heartbeat time\nObjectType=0x7\nDataType=0x0006\nAccessType=rw\nDefaultValue=0\n").unwrap();
//! let e = eds.entry(0x1017, 0).unwrap();
//! assert_eq!((e.name.as_str(), e.data_type, e.access), ("Producer heartbeat time", 0x0006, Access::ReadWrite));
//! assert_eq!(eds.find("producer heartbeat time").map(|(i, s)| (i, s)), Some((0x1017, None)));
//! ```

use std::collections::BTreeMap;
use std::fmt;

/// Access of an entry (`AccessType`).
///
/// ```
/// let eds = canopen_eds::Eds::parse("[1000]\nDataType=7\nAccessType=RO\n").unwrap();
/// assert_eq!(eds.entry(0x1000, 0).map(|e| e.access), Some(canopen_eds::Access::ReadOnly));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Access {
    /// `ro`.
    ReadOnly,
    /// `wo`.
    WriteOnly,
    /// `rw`, `rwr`, `rww`.
    ReadWrite,
    /// `const`.
    Const,
}

impl Access {
    fn parse(s: &str) -> Option<Access> {
        Some(match s.trim().to_ascii_lowercase().as_str() {
            "ro" => Access::ReadOnly,
            "wo" => Access::WriteOnly,
            "rw" | "rwr" | "rww" => Access::ReadWrite,
            "const" => Access::Const,
            _ => return None,
        })
    }

    /// The EDS spelling.
    ///
    /// ```
    /// assert_eq!(canopen_eds::Access::Const.as_str(), "const");
    /// ```
    pub fn as_str(self) -> &'static str {
        match self {
            Access::ReadOnly => "ro",
            Access::WriteOnly => "wo",
            Access::ReadWrite => "rw",
            Access::Const => "const",
        }
    }

    /// Whether an SDO upload may read it.
    ///
    /// ```
    /// assert!(!canopen_eds::Access::WriteOnly.readable());
    /// ```
    pub fn readable(self) -> bool {
        self != Access::WriteOnly
    }
}

/// One value of the dictionary: a VAR, or one sub-entry of an ARRAY or RECORD.
///
/// ```
/// let eds = canopen_eds::Eds::parse("[1017]\nParameterName=Producer heartbeat time\nDataType=6\nDefaultValue=0\nParameterValue=1000\n").unwrap();
/// let e = eds.entry(0x1017, 0).unwrap();
/// assert_eq!((e.default.as_deref(), e.value.as_deref()), (Some("0"), Some("1000")));
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Entry {
    /// Object index.
    pub index: u16,
    /// Sub-index (0 for a VAR).
    pub sub: u8,
    /// `ParameterName`.
    pub name: String,
    /// `DataType`: the CiA 301 data type index (0001h BOOLEAN ... 001Bh UNSIGNED64).
    pub data_type: u16,
    /// `AccessType`.
    pub access: Access,
    /// `DefaultValue` as written (may refer to `$NODEID`), `None` when absent or empty.
    pub default: Option<String>,
    /// `LowLimit` as written.
    pub low: Option<String>,
    /// `HighLimit` as written.
    pub high: Option<String>,
    /// `PDOMapping`.
    pub pdo_mapping: bool,
    /// `ParameterValue` as written (a DCF's configured value, CiA 306), `None` when absent or empty; of a
    /// `CompactSubObj` array, from its `[xxxxValue]` section.
    pub value: Option<String>,
}

/// `ObjectType` of an object.
///
/// ```
/// let eds = canopen_eds::Eds::parse("[1018]\nObjectType=0x9\n[1018sub1]\nDataType=7\n").unwrap();
/// assert_eq!(eds.objects[&0x1018].kind, canopen_eds::ObjectKind::Record);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ObjectKind {
    /// 07h VAR (also 02h DOMAIN, 05h/06h DEFTYPE/DEFSTRUCT as they are).
    Var,
    /// 08h ARRAY.
    Array,
    /// 09h RECORD.
    Record,
}

/// One object: its name, kind and entries by sub-index.
///
/// ```
/// let eds = canopen_eds::Eds::parse("[6000]\nParameterName=Inputs\nObjectType=8\nCompactSubObj=2\nDataType=5\n").unwrap();
/// let o = &eds.objects[&0x6000];
/// assert_eq!((o.name.as_str(), o.entries.len()), ("Inputs", 3)); // sub-index 0, the count, and 1..=2
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Object {
    /// Index.
    pub index: u16,
    /// `ParameterName`.
    pub name: String,
    /// VAR, ARRAY or RECORD.
    pub kind: ObjectKind,
    /// The entries by sub-index (sub 0 only for a VAR).
    pub entries: BTreeMap<u8, Entry>,
}

/// A parsed EDS or DCF.
///
/// ```
/// let eds = canopen_eds::Eds::parse("[DeviceInfo]\nVendorName=Acme\n[1000]\nDataType=7\nAccessType=ro\n").unwrap();
/// assert_eq!(eds.objects.len(), 1);
/// assert_eq!(eds.sections[0].keys, [("VendorName".to_string(), "Acme".to_string())]);
/// assert!(eds.commissioning.is_none()); // an EDS; a DCF has [DeviceComissioning]
/// ```
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Eds {
    /// Every object, by index.
    pub objects: BTreeMap<u16, Object>,
    /// The sections that describe no object (`[FileInfo]`, `[DeviceInfo]`, `[DummyUsage]`, `[Comments]`,
    /// ...), in file order with their keys as written, for the writer to give back. The object lists
    /// (`[MandatoryObjects]` ...), `[xxxxName]`/`[xxxxValue]` and `[DeviceComissioning]` are not among them.
    pub sections: Vec<InfoSection>,
    /// A DCF's `[DeviceComissioning]` section.
    pub commissioning: Option<DeviceCommissioning>,
}

/// A section that describes no object, kept as written.
///
/// ```
/// let eds = canopen_eds::Eds::parse("[FileInfo]\nFileName=io.eds\nFileVersion=1\n").unwrap();
/// assert_eq!(eds.sections[0].get("filename"), Some("io.eds"));
/// ```
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct InfoSection {
    /// The name between the brackets.
    pub name: String,
    /// `(key, value)` in file order, as written.
    pub keys: Vec<(String, String)>,
}

impl InfoSection {
    /// The value of `key`, in any case (the last one when a key is repeated).
    ///
    /// ```
    /// let s = canopen_eds::InfoSection { name: "DeviceInfo".into(), keys: vec![("NrOfRXPDO".into(), "4".into())] };
    /// assert_eq!(s.get("NrOfRxPdo"), Some("4"));
    /// ```
    pub fn get(&self, key: &str) -> Option<&str> {
        self.keys.iter().rev().find(|(k, _)| k.eq_ignore_ascii_case(key)).map(|(_, v)| v.as_str())
    }
}

/// A DCF's `[DeviceComissioning]` section (CiA 306 spells it with one m): where the configured device sits
/// in its network.
///
/// ```
/// let dcf = canopen_eds::Eds::parse("[DeviceComissioning]\nNodeID=0x05\nNodeName=Valve\nBaudrate=500\n").unwrap();
/// let c = dcf.commissioning.unwrap();
/// assert_eq!((c.node_id, c.node_name.as_str(), c.baudrate), (5, "Valve", 500));
/// let e = canopen_eds::Eds::parse("[DeviceComissioning]\nNodeID=200\n").unwrap_err();
/// assert_eq!(e.to_string(), "line 2: [DeviceComissioning] NodeID 200 is not 1..=127");
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DeviceCommissioning {
    /// `NodeID`: 1..=127.
    pub node_id: u8,
    /// `NodeName`.
    pub node_name: String,
    /// `Baudrate`, in kbit/s.
    pub baudrate: u16,
    /// `NetNumber`.
    pub net_number: u32,
    /// `NetworkName`.
    pub network_name: String,
    /// `CANopenManager`: whether this device is the network's CANopen manager.
    pub canopen_manager: bool,
    /// `LSS_SerialNumber`, when the device is to be found by LSS.
    pub lss_serial_number: Option<u32>,
}

impl DeviceCommissioning {
    /// A device at `node_id` on a network at `baudrate` kbit/s, with no names, net 0, no manager, no LSS
    /// serial number.
    ///
    /// ```
    /// let c = canopen_eds::DeviceCommissioning::new(5, 250);
    /// assert_eq!((c.node_id, c.baudrate, c.canopen_manager), (5, 250, false));
    /// ```
    pub fn new(node_id: u8, baudrate: u16) -> DeviceCommissioning {
        DeviceCommissioning {
            node_id,
            node_name: String::new(),
            baudrate,
            net_number: 0,
            network_name: String::new(),
            canopen_manager: false,
            lss_serial_number: None,
        }
    }

    fn parse(s: &Section<'_>) -> Result<DeviceCommissioning, EdsError> {
        let line = |key: &str| s.get(key).map_or(s.line, |(_, l)| l);
        let int = |key: &str, max: u64| -> Result<Option<u64>, EdsError> {
            match s.number(key)? {
                Some(v) if v > max => Err(s.err(line(key), format!("{key} {v} is above {max}"))),
                v => Ok(v),
            }
        };
        let node_id = match int("NodeID", 0xFF)? {
            Some(id @ 1..=127) => id as u8,
            Some(id) => return Err(s.err(line("NodeID"), format!("NodeID {id} is not 1..=127"))),
            None => return Err(s.err(s.line, "no NodeID".into())),
        };
        Ok(DeviceCommissioning {
            node_id,
            node_name: s.text("NodeName").unwrap_or_default(),
            baudrate: int("Baudrate", u64::from(u16::MAX))?.unwrap_or(0) as u16,
            net_number: int("NetNumber", u64::from(u32::MAX))?.unwrap_or(0) as u32,
            network_name: s.text("NetworkName").unwrap_or_default(),
            canopen_manager: int("CANopenManager", u64::MAX)?.is_some_and(|v| v != 0),
            lss_serial_number: int("LSS_SerialNumber", u64::from(u32::MAX))?.map(|v| v as u32),
        })
    }
}

/// Why an EDS could not be read: the line (1-based), its section and what is wrong.
///
/// ```
/// let e = canopen_eds::Eds::parse("[1000]\nParameterName=x\nDataType=0xZZ\n").unwrap_err();
/// assert_eq!((e.line, e.section.as_str()), (3, "1000"));
/// assert_eq!(e.to_string(), "line 3: [1000] DataType '0xZZ' is not a number");
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EdsError {
    /// The line, counted from 1: of the key at fault, or of the section's header when a key is missing.
    pub line: usize,
    /// The section.
    pub section: String,
    /// What is wrong with it.
    pub what: String,
}

impl fmt::Display for EdsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: [{}] {}", self.line, self.section, self.what)
    }
}

impl std::error::Error for EdsError {}

/// A number as EDS files write them: decimal, `0x`-hex, or octal with a leading 0 (CiA 306).
fn number(s: &str) -> Option<u64> {
    let s = s.trim();
    if let Some(hex) = s.strip_prefix("0x").or_else(|| s.strip_prefix("0X")) {
        u64::from_str_radix(hex, 16).ok()
    } else if s.len() > 1 && s.starts_with('0') && s.bytes().all(|b| b.is_ascii_digit()) {
        u64::from_str_radix(&s[1..], 8).ok()
    } else {
        s.parse().ok()
    }
}

/// Evaluates a default that may refer to the node-ID (`$NODEID+0x180`, `1280+$NODEID`, `0x185`).
///
/// ```
/// use canopen_eds::eval_default;
/// assert_eq!(eval_default("$NODEID+0x180", 5), Some(0x185));
/// assert_eq!(eval_default("1280+$NODEID", 5), Some(1285));
/// assert_eq!(eval_default("0x20010032", 5), Some(0x2001_0032));
/// assert_eq!(eval_default("-5", 5), Some(-5));
/// assert_eq!(eval_default("5.2", 5), None);
/// ```
pub fn eval_default(text: &str, node_id: u8) -> Option<i128> {
    let mut total = 0i128;
    for term in text.split('+') {
        let term = term.trim();
        total += if term.eq_ignore_ascii_case("$NODEID") {
            i128::from(node_id)
        } else if let Some(neg) = term.strip_prefix('-') {
            -i128::from(number(neg)?)
        } else {
            i128::from(number(term)?)
        };
    }
    Some(total)
}

/// The bits of a signed integer data type (INTEGER8..INTEGER64), `None` for any other.
fn signed_bits(data_type: u16) -> Option<u32> {
    Some(match data_type {
        0x0002 => 8,
        0x0003 => 16,
        0x0004 => 32,
        0x0010 => 24,
        0x0012 => 40,
        0x0013 => 48,
        0x0014 => 56,
        0x0015 => 64,
        _ => return None,
    })
}

/// The range of an integer data type (INTEGER8..64, UNSIGNED8..64, BOOLEAN as 0..1), `None` for any other.
/// A `LowLimit`/`HighLimit` at its bound limits nothing: `LowLimit=0`, `HighLimit=255` of an UNSIGNED8 (as
/// sample.eds gives the transmission types) is the same entry as one without limits.
///
/// ```
/// use canopen_eds::type_range;
/// assert_eq!(type_range(0x0005), Some((0, 255)));
/// assert_eq!(type_range(0x0003), Some((-32768, 32767)));
/// assert_eq!(type_range(0x0008), None); // REAL32
/// ```
pub fn type_range(data_type: u16) -> Option<(i128, i128)> {
    if let Some(bits) = signed_bits(data_type) {
        return Some((-(1 << (bits - 1)), (1 << (bits - 1)) - 1));
    }
    let bits: u32 = match data_type {
        0x0001 => 1,
        0x0005 => 8,
        0x0006 => 16,
        0x0007 => 32,
        0x0016 => 24,
        0x0018 => 40,
        0x0019 => 48,
        0x001A => 56,
        0x001B => 64,
        _ => return None,
    };
    Some((0, (1 << bits) - 1))
}

/// Whether a `LowLimit` (`low`) or `HighLimit` limits nothing: absent, or at the bound of its integer type
/// ([`type_range`]).
///
/// ```
/// use canopen_eds::no_limit;
/// assert!(no_limit(Some("255"), 0x0005, false) && no_limit(Some("0x0"), 0x0005, true) && no_limit(None, 5, true));
/// assert!(!no_limit(Some("4"), 0x0005, false));
/// assert!(no_limit(Some("0x80"), 0x0002, true)); // INTEGER8's -128 in two's complement
/// ```
pub fn no_limit(limit: Option<&str>, data_type: u16, low: bool) -> bool {
    let Some(text) = limit else { return true };
    let bound = type_range(data_type).map(|(lo, hi)| if low { lo } else { hi });
    bound.is_some() && eval_typed(text, data_type, 0) == bound
}

/// [`eval_default`] for a value of a data type: a signed integer written in hex is its two's complement
/// bits, as tools write limits (`LowLimit=0x80000000` of an INTEGER32 is -2147483648, `0xFFFFFFFFFFFFFFF6`
/// of an INTEGER64 is -10; python canopen reads them so), while a decimal or a `-0x..` value is as written.
///
/// ```
/// use canopen_eds::eval_typed;
/// assert_eq!(eval_typed("0x80000000", 0x0004, 0), Some(-2147483648));
/// assert_eq!(eval_typed("0xFFFFFFFFFFFFFFF6", 0x0015, 0), Some(-10));
/// assert_eq!(eval_typed("0x7F", 0x0002, 0), Some(127));
/// assert_eq!(eval_typed("0x80000000", 0x0007, 0), Some(0x8000_0000));
/// assert_eq!(eval_typed("-0x10", 0x0004, 0), Some(-16));
/// ```
pub fn eval_typed(text: &str, data_type: u16, node_id: u8) -> Option<i128> {
    let v = eval_default(text, node_id)?;
    let t = text.trim();
    let hex = t.starts_with("0x") || t.starts_with("0X");
    match signed_bits(data_type) {
        Some(bits) if hex && v >= 1 << (bits - 1) && v < 1 << bits => Some(v - (1 << bits)),
        _ => Some(v),
    }
}

/// What a section's name says it is.
enum SectionName {
    Object(u16),
    Sub(u16, u8),
    /// `[xxxxName]` / `[xxxxValue]`: the names and DCF values of a `CompactSubObj` array.
    Compact,
    /// `[MandatoryObjects]`, `[OptionalObjects]`, `[ManufacturerObjects]`: the writer lists the objects anew.
    ObjectList,
    /// `[DeviceComissioning]` (CiA 306's spelling), read into [`DeviceCommissioning`].
    Commissioning,
    Other,
}

fn section_name(name: &str) -> SectionName {
    let lower = name.to_ascii_lowercase();
    let hex = |s: &str| {
        (!s.is_empty() && s.len() <= 4 && s.bytes().all(|b| b.is_ascii_hexdigit()))
            .then(|| u16::from_str_radix(s, 16).ok())
            .flatten()
    };
    if let Some((idx, sub)) = lower.split_once("sub") {
        if let (Some(i), Ok(s)) = (hex(idx), u8::from_str_radix(sub, 16)) {
            return SectionName::Sub(i, s);
        }
    }
    if lower.strip_suffix("name").or_else(|| lower.strip_suffix("value")).and_then(hex).is_some() {
        return SectionName::Compact;
    }
    match lower.as_str() {
        "mandatoryobjects" | "optionalobjects" | "manufacturerobjects" => return SectionName::ObjectList,
        "devicecomissioning" | "devicecommissioning" => return SectionName::Commissioning,
        _ => {}
    }
    match hex(&lower) {
        Some(i) => SectionName::Object(i),
        None => SectionName::Other,
    }
}

/// One section of the file as written: its name, the line of its header, its keys with their lines.
struct Section<'a> {
    name: &'a str,
    line: usize,
    /// (key as written, value, line), in file order.
    keys: Vec<(&'a str, &'a str, usize)>,
}

impl<'a> Section<'a> {
    /// The value of a key (any case) and its line; the last one when a key is repeated.
    fn get(&self, key: &str) -> Option<(&'a str, usize)> {
        self.keys.iter().rev().find(|(k, _, _)| k.eq_ignore_ascii_case(key)).map(|&(_, v, l)| (v, l))
    }

    /// A non-empty value as an owned string.
    fn text(&self, key: &str) -> Option<String> {
        self.get(key).map(|(v, _)| v).filter(|v| !v.is_empty()).map(str::to_owned)
    }

    fn err(&self, line: usize, what: String) -> EdsError {
        EdsError { line, section: self.name.to_owned(), what }
    }

    /// A number key: `None` when absent or empty, an error on its line when it is not a number.
    fn number(&self, key: &str) -> Result<Option<u64>, EdsError> {
        match self.get(key).filter(|(v, _)| !v.is_empty()) {
            None => Ok(None),
            Some((v, line)) => {
                number(v).map(Some).ok_or_else(|| self.err(line, format!("{key} '{v}' is not a number")))
            }
        }
    }
}

/// Splits the text into sections; lines outside any section, comments and lines that are no `key=value`
/// are skipped (real files have them), so nothing here fails.
fn sections(text: &str) -> Vec<Section<'_>> {
    let mut sections: Vec<Section<'_>> = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with(';') || line.starts_with('#') {
            continue;
        }
        if let Some(name) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            sections.push(Section { name: name.trim(), line: n + 1, keys: Vec::new() });
        } else if let (Some((key, value)), Some(section)) = (line.split_once('='), sections.last_mut()) {
            section.keys.push((key.trim(), value.trim(), n + 1));
        }
    }
    sections
}

impl Eds {
    /// Parses the text of an EDS or DCF. A malformed number, data type or access type in an object
    /// section, or in `[DeviceComissioning]`, is an [`EdsError`] with its line; anything else a real file
    /// may carry (comments, unknown sections and keys, junk lines) is passed over, never a panic.
    ///
    /// ```
    /// let eds = canopen_eds::Eds::parse("[FileInfo]\nFileName=x.eds\n[1017]\nDataType=0x0006\nDefaultValue=0\n").unwrap();
    /// assert_eq!(eds.entry(0x1017, 0).map(|e| e.data_type), Some(0x0006));
    /// assert_eq!(eds.sections[0].name, "FileInfo");
    /// let e = canopen_eds::Eds::parse("[1017]\nDataType=0x0006\nAccessType=rx\n").unwrap_err();
    /// assert_eq!(e.line, 3);
    /// ```
    pub fn parse(text: &str) -> Result<Eds, EdsError> {
        let sections = sections(text);
        let mut subs: BTreeMap<u16, Vec<(u8, &Section<'_>)>> = BTreeMap::new();
        let mut compact: BTreeMap<String, &Section<'_>> = BTreeMap::new();
        for s in &sections {
            match section_name(s.name) {
                SectionName::Sub(i, sub) => subs.entry(i).or_default().push((sub, s)),
                SectionName::Compact => {
                    compact.insert(s.name.to_ascii_lowercase(), s);
                }
                _ => {}
            }
        }
        let mut eds = Eds::default();
        for s in &sections {
            match section_name(s.name) {
                SectionName::Object(index) => {
                    let object = Self::object(index, s, subs.get(&index).map_or(&[][..], Vec::as_slice), &compact)?;
                    eds.objects.insert(index, object);
                }
                SectionName::Commissioning => eds.commissioning = Some(DeviceCommissioning::parse(s)?),
                SectionName::Other => eds.sections.push(InfoSection {
                    name: s.name.to_owned(),
                    keys: s.keys.iter().map(|&(k, v, _)| (k.to_owned(), v.to_owned())).collect(),
                }),
                SectionName::Sub(..) | SectionName::Compact | SectionName::ObjectList => {}
            }
        }
        Ok(eds)
    }

    fn object(
        index: u16,
        s: &Section<'_>,
        subs: &[(u8, &Section<'_>)],
        compact: &BTreeMap<String, &Section<'_>>,
    ) -> Result<Object, EdsError> {
        let kind = match s.number("ObjectType")? {
            Some(8) => ObjectKind::Array,
            Some(9) => ObjectKind::Record,
            _ => ObjectKind::Var,
        };
        let mut object =
            Object { index, name: s.text("ParameterName").unwrap_or_default(), kind, entries: BTreeMap::new() };
        if kind == ObjectKind::Var {
            object.entries.insert(0, Self::parse_entry(index, 0, s)?);
            return Ok(object);
        }
        let count = match s.number("CompactSubObj")? {
            None | Some(0) => None,
            Some(n) => Some(u8::try_from(n).map_err(|_| {
                let line = s.get("CompactSubObj").map_or(s.line, |(_, l)| l);
                s.err(line, format!("CompactSubObj {n} is above 255"))
            })?),
        };
        if let Some(count) = count {
            let names = compact.get(&format!("{}name", s.name).to_ascii_lowercase());
            let values = compact.get(&format!("{}value", s.name).to_ascii_lowercase());
            object.entries.insert(
                0,
                Entry {
                    index,
                    sub: 0,
                    name: "Number of entries".into(),
                    data_type: 0x0005,
                    access: Access::ReadOnly,
                    default: Some(count.to_string()),
                    low: None,
                    high: None,
                    pdo_mapping: false,
                    value: None,
                },
            );
            for sub in 1..=count {
                let mut e = Self::parse_entry(index, sub, s)?;
                let key = sub.to_string();
                e.name = names.and_then(|n| n.text(&key)).unwrap_or_else(|| format!("{}{sub}", object.name));
                e.value = values.and_then(|v| v.text(&key));
                object.entries.insert(sub, e);
            }
            return Ok(object);
        }
        for &(sub, section) in subs {
            object.entries.insert(sub, Self::parse_entry(index, sub, section)?);
        }
        Ok(object)
    }

    fn parse_entry(index: u16, sub: u8, s: &Section<'_>) -> Result<Entry, EdsError> {
        let data_type = match s.get("DataType") {
            Some((v, line)) => {
                let n = number(v).ok_or_else(|| s.err(line, format!("DataType '{v}' is not a number")))?;
                u16::try_from(n).map_err(|_| s.err(line, format!("DataType '{v}' is above FFFFh")))?
            }
            None => return Err(s.err(s.line, "no DataType".into())),
        };
        let access = match s.get("AccessType") {
            Some((v, line)) => Access::parse(v)
                .ok_or_else(|| s.err(line, format!("AccessType '{v}' is not ro, wo, rw, rwr, rww or const")))?,
            None => Access::ReadWrite,
        };
        let pdo_mapping = s.get("PDOMapping").and_then(|(v, _)| number(v)).is_some_and(|v| v != 0);
        Ok(Entry {
            index,
            sub,
            name: s.text("ParameterName").unwrap_or_default(),
            data_type,
            access,
            default: s.text("DefaultValue"),
            low: s.text("LowLimit"),
            high: s.text("HighLimit"),
            pdo_mapping,
            value: s.text("ParameterValue"),
        })
    }

    /// The entry at `index:sub`.
    ///
    /// ```
    /// let eds = canopen_eds::Eds::parse("[1000]\nParameterName=Device type\nDataType=7\nAccessType=ro\n").unwrap();
    /// assert!(eds.entry(0x1000, 0).is_some() && eds.entry(0x1000, 1).is_none());
    /// ```
    pub fn entry(&self, index: u16, sub: u8) -> Option<&Entry> {
        self.objects.get(&index)?.entries.get(&sub)
    }

    /// Every entry, in index and sub-index order.
    ///
    /// ```
    /// let eds = canopen_eds::Eds::parse("[1000]\nDataType=7\n[1001]\nDataType=5\n").unwrap();
    /// assert_eq!(eds.entries().count(), 2);
    /// ```
    pub fn entries(&self) -> impl Iterator<Item = &Entry> {
        self.objects.values().flat_map(|o| o.entries.values())
    }

    /// Finds a name, case-insensitively: an object's name gives `(index, None)`; `object.sub` (an object's
    /// name, a dot, an entry's name) gives `(index, Some(sub))`.
    ///
    /// ```
    /// let eds = canopen_eds::Eds::parse(
    ///     "[1018]\nParameterName=Identity object\nObjectType=9\n[1018sub4]\nParameterName=Serial number\nDataType=7\n",
    /// ).unwrap();
    /// assert_eq!(eds.find("Identity Object"), Some((0x1018, None)));
    /// assert_eq!(eds.find("identity object.serial number"), Some((0x1018, Some(4))));
    /// ```
    pub fn find(&self, name: &str) -> Option<(u16, Option<u8>)> {
        let name = name.trim();
        if let Some(o) = self.objects.values().find(|o| o.name.eq_ignore_ascii_case(name)) {
            return Some((o.index, None));
        }
        let (object, entry) = name.split_once('.')?;
        let o = self.objects.values().find(|o| o.name.eq_ignore_ascii_case(object.trim()))?;
        let sub = o.entries.values().find(|e| e.name.eq_ignore_ascii_case(entry.trim()))?;
        Some((o.index, Some(sub.sub)))
    }
}

/// The CiA 301 name of a data type index (Table 44), `None` for one this crate does not name.
///
/// ```
/// assert_eq!(canopen_eds::data_type_name(0x0007), Some("UNSIGNED32"));
/// ```
pub fn data_type_name(data_type: u16) -> Option<&'static str> {
    Some(match data_type {
        0x0001 => "BOOLEAN",
        0x0002 => "INTEGER8",
        0x0003 => "INTEGER16",
        0x0004 => "INTEGER32",
        0x0005 => "UNSIGNED8",
        0x0006 => "UNSIGNED16",
        0x0007 => "UNSIGNED32",
        0x0008 => "REAL32",
        0x0009 => "VISIBLE_STRING",
        0x000A => "OCTET_STRING",
        0x000B => "UNICODE_STRING",
        0x000C => "TIME_OF_DAY",
        0x000D => "TIME_DIFFERENCE",
        0x000F => "DOMAIN",
        0x0010 => "INTEGER24",
        0x0011 => "REAL64",
        0x0012 => "INTEGER40",
        0x0013 => "INTEGER48",
        0x0014 => "INTEGER56",
        0x0015 => "INTEGER64",
        0x0016 => "UNSIGNED24",
        0x0018 => "UNSIGNED40",
        0x0019 => "UNSIGNED48",
        0x001A => "UNSIGNED56",
        0x001B => "UNSIGNED64",
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shapes real EDS files take (written here, in the style of tool-generated files): lower-case
    /// hex and `Sub`/`sub` section names, decimal and hex numbers, `RW`, `$NODEID` defaults on either side,
    /// empty values, a float default, a `CompactSubObj` array with and without a `Name` section, a record,
    /// comments, and sections that are no objects.
    const QUIRKS: &str = "\
[FileInfo]
FileName=quirks.eds
; a comment
[DeviceInfo]
NrOfRXPDO=1

[1000]
ParameterName=Device type
ObjectType=0x7
DataType=0x0007
AccessType=ro
PDOMapping=0

[1400]
ParameterName=RPDO 1 communication
ObjectType=9
SubNumber=2

[1400sub0]
ParameterName=Highest sub-index
ObjectType=7
DataType=5
AccessType=ro
DefaultValue=1

[1400sub1]
ParameterName=COB-ID
ObjectType=7
DataType=7
AccessType=RW
DefaultValue=1280+$NODEID

[1a00]
ParameterName=TPDO 1 mapping
ObjectType=0x9
SubNumber=1

[1A00Sub0]
ParameterName=Number of mapped objects
ObjectType=0x7
DataType=0x0005
AccessType=rw
DefaultValue=
LowLimit=0
HighLimit=8

[3002]
ParameterName=Sampling rate (Hz)
DataType=0x0008
AccessType=ro
DefaultValue=5.2

[3004]
ParameterName=Sensor status
ObjectType=8
CompactSubObj=3
DataType=0x0006
AccessType=ro
DefaultValue=3
PDOMapping=1

[3004Name]
NrOfEntries=2
1=First
2=Second

[3006]
ParameterName=Valve
ObjectType=8
CompactSubObj=2
DataType=0x0008
AccessType=rw
DefaultValue=
";

    #[test]
    fn real_world_shapes_parse() {
        let eds = Eds::parse(QUIRKS).unwrap();
        assert_eq!(
            eds.objects.keys().copied().collect::<Vec<_>>(),
            vec![0x1000, 0x1400, 0x1A00, 0x3002, 0x3004, 0x3006]
        );
        let cob = eds.entry(0x1400, 1).unwrap();
        assert_eq!((cob.access, cob.data_type), (Access::ReadWrite, 7));
        assert_eq!(cob.default.as_deref().and_then(|d| eval_default(d, 3)), Some(1283));
        let n = eds.entry(0x1A00, 0).unwrap();
        assert_eq!((n.default.as_deref(), n.low.as_deref(), n.high.as_deref()), (None, Some("0"), Some("8")));
        assert_eq!(eds.entry(0x3002, 0).unwrap().default.as_deref(), Some("5.2"));
        let status = &eds.objects[&0x3004];
        assert_eq!(status.kind, ObjectKind::Array);
        assert_eq!(status.entries.len(), 4);
        assert_eq!(status.entries[&0].default.as_deref(), Some("3"));
        assert_eq!((status.entries[&1].name.as_str(), status.entries[&3].name.as_str()), ("First", "Sensor status3"));
        assert!(status.entries[&2].pdo_mapping && status.entries[&2].data_type == 6);
        assert_eq!(eds.objects[&0x3006].entries.len(), 3);
        assert_eq!(eds.find("tpdo 1 mapping.number of mapped objects"), Some((0x1A00, Some(0))));
    }

    /// A DCF: `ParameterValue` per entry, `[xxxxValue]` for a `CompactSubObj` array, `[DeviceComissioning]`;
    /// the sections that are no objects are kept as written, the object lists are not.
    #[test]
    fn dcf_values_and_commissioning_parse() {
        let text = format!(
            "{QUIRKS}\n[3004Value]\nNrOfEntries=1\n2=0x22\n[MandatoryObjects]\nSupportedObjects=1\n1=0x1000\n\
             [DeviceComissioning]\nNodeID=0x7F\nNodeName=Valve 3\nBaudrate=250\nNetNumber=2\nCANopenManager=1\n\
             LSS_SerialNumber=0x1234\n[2100]\nDataType=7\nParameterValue=0x80000000\n"
        );
        let eds = Eds::parse(&text).unwrap();
        let status = &eds.objects[&0x3004];
        assert_eq!((status.entries[&1].value.as_deref(), status.entries[&2].value.as_deref()), (None, Some("0x22")));
        let c = eds.commissioning.as_ref().unwrap();
        assert_eq!((c.node_id, c.node_name.as_str(), c.baudrate, c.net_number), (0x7F, "Valve 3", 250, 2));
        assert_eq!((c.canopen_manager, c.lss_serial_number, c.network_name.as_str()), (true, Some(0x1234), ""));
        let names: Vec<&str> = eds.sections.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["FileInfo", "DeviceInfo"]);
        assert_eq!(eds.sections[1].get("nrofrxpdo"), Some("1"));
        let v = eds.entry(0x2100, 0).unwrap();
        assert_eq!((v.value.as_deref(), v.default.as_deref()), (Some("0x80000000"), None));
    }

    #[test]
    fn malformed_input_is_an_error_never_a_panic() {
        // Each error names the line of the key at fault, or of the header when a key is missing.
        let line = |text: &str| Eds::parse(text).map_err(|e| (e.line, e.section)).err();
        assert_eq!(line("; c\n[1000]\nObjectType=seven\n"), Some((3, "1000".into())));
        assert_eq!(line("[1000]\nDataType=7\n\nAccessType=rwx\n"), Some((4, "1000".into())));
        assert_eq!(line("[1000]\nObjectType=8\nCompactSubObj=300\nDataType=5\n"), Some((3, "1000".into())));
        assert_eq!(line("[FileInfo]\n[1000]\nParameterName=no type\n"), Some((2, "1000".into())));
        assert_eq!(line("[1018]\nObjectType=9\n[1018sub1]\nDataType=0x10000\n"), Some((4, "1018sub1".into())));
        assert_eq!(line("[2000]\nObjectType=8\nCompactSubObj=2\nDataType=x\n"), Some((4, "2000".into())));
        assert_eq!(line("[DeviceComissioning]\nNodeName=x\n"), Some((1, "DeviceComissioning".into())));
        assert_eq!(line("[DeviceComissioning]\nNodeID=5\nBaudrate=70000\n"), Some((3, "DeviceComissioning".into())));
        // Garbage around is ignored.
        let eds = Eds::parse("junk\n=\n[\n[]\n[zzzz]\nx=y\n[1000sub]\n[10000]\nDataType=1\n").unwrap();
        assert!(eds.objects.is_empty());
        for text in ["[", "]", "[1000", "[1000]\n=", "[1000]\nDataType=", "[1000sub0]\nDataType=5"] {
            let _ = Eds::parse(text);
        }
    }
}
