//! CiA 306 EDS (electronic data sheet) export from the same description the dictionary runs on.
//!
//! [`write_eds`] writes to any [`core::fmt::Write`] (no heap): `[FileInfo]`, `[DeviceInfo]`,
//! `[DummyUsage]`, `[Comments]`, `[MandatoryObjects]` (1000h, 1001h, 1018h: OD-12), `[OptionalObjects]`
//! (the other 1000h–1FFFh objects and 6000h–FFFFh), `[ManufacturerObjects]` (2000h–5FFFh), then one
//! section per object (`[2001]`) and per sub-entry of an ARRAY/RECORD (`[1018sub1]`, hex sub-index) with
//! ParameterName, ObjectType, DataType, AccessType, DefaultValue, PDOMapping, LowLimit/HighLimit and
//! SubNumber (OD-11).
//!
//! What the format choices rely on (python `canopen` 2.4.1, `canopen/objectdictionary/eds.py`, read for
//! this; and the EDS sample of seed 003 §5.6):
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
//!   verbatim, OCTET_STRING by `bytes.fromhex(x)` (hex pairs, no prefix). DOMAIN gets no DefaultValue.
//! - `LowLimit`/`HighLimit`: signed limits of INTEGER8/16/32/64 go through `int(x, 0)` then a two's
//!   complement fix-up, so decimal negatives are fine; python ignores limits of the other widths.
//! - `AccessType` is lower-cased by python and compared with ro/wo/rw/rwr/rww/const.
//! - The INI reader treats `;` after whitespace as a comment: keep `" ;"` out of names and strings.

use core::fmt::{self, Write};

use super::{Access, DataType, EntryDesc, ObjectCode, ObjectDesc, OdDescribe, PdoMapping, Value};

/// What the EDS says that the dictionary does not: file and device information.
///
/// ```
/// use canopen_core::od::eds::EdsInfo;
/// const INFO: EdsInfo = EdsInfo { product_name: "Demo", ..EdsInfo::DEFAULT };
/// assert_eq!(INFO.baud_rates_kbit, &[125, 250, 500, 1000]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EdsInfo {
    /// `[FileInfo] FileName`.
    pub file_name: &'static str,
    /// `[FileInfo] Description`.
    pub description: &'static str,
    /// `[FileInfo] CreatedBy` / `ModifiedBy`.
    pub created_by: &'static str,
    /// `[FileInfo] CreationDate` / `ModificationDate`, `MM-DD-YYYY`.
    pub creation_date: &'static str,
    /// `[FileInfo] CreationTime` / `ModificationTime`, `hh:mmAM`.
    pub creation_time: &'static str,
    /// `[DeviceInfo] VendorName`.
    pub vendor_name: &'static str,
    /// `[DeviceInfo] ProductName`.
    pub product_name: &'static str,
    /// `[DeviceInfo] OrderCode`.
    pub order_code: &'static str,
    /// Supported bit rates in kbit/s, from {10, 20, 50, 125, 250, 500, 800, 1000} (CAN-03).
    pub baud_rates_kbit: &'static [u16],
    /// `[DeviceInfo] Granularity`: mapping granularity in bits (8: byte-wise; 0: mapping not changeable).
    pub granularity: u8,
    /// `[DeviceInfo] LSS_Supported`.
    pub lss_supported: bool,
}

impl EdsInfo {
    /// Neutral defaults.
    pub const DEFAULT: EdsInfo = EdsInfo {
        file_name: "device.eds",
        description: "",
        created_by: "canopen-rs",
        creation_date: "01-01-2025",
        creation_time: "12:00AM",
        vendor_name: "",
        product_name: "",
        order_code: "",
        baud_rates_kbit: &[125, 250, 500, 1000],
        granularity: 8,
        lss_supported: false,
    };
}

impl Default for EdsInfo {
    fn default() -> Self {
        EdsInfo::DEFAULT
    }
}

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
        (_, DataType::Domain) => {}
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

fn write_object<W: Write, D: OdDescribe + ?Sized>(w: &mut W, od: &D, o: &ObjectDesc) -> fmt::Result {
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

#[derive(Clone, Copy, PartialEq)]
enum Category {
    Mandatory,
    Optional,
    Manufacturer,
}

fn category(index: u16) -> Category {
    match index {
        0x1000 | 0x1001 | 0x1018 => Category::Mandatory,
        0x2000..=0x5FFF => Category::Manufacturer,
        _ => Category::Optional,
    }
}

fn write_list<W: Write, D: OdDescribe + ?Sized>(w: &mut W, od: &D, section: &str, cat: Category) -> fmt::Result {
    let objects = || (0..od.object_count()).filter_map(|n| od.object(n)).filter(|o| category(o.index) == cat);
    writeln!(w, "[{section}]")?;
    writeln!(w, "SupportedObjects={}", objects().count())?;
    for (i, o) in objects().enumerate() {
        writeln!(w, "{}=0x{:04X}", i + 1, o.index)?;
    }
    w.write_char('\n')
}

fn identity<D: OdDescribe + ?Sized>(od: &D, sub: u8) -> u64 {
    match od.entry(0x1018, sub).and_then(|e| e.default) {
        Some(Value::Uint(v)) => v,
        _ => 0,
    }
}

/// Writes the complete EDS of `od`.
///
/// ```
/// use canopen_core::comm::NodeConfig;
/// use canopen_core::od::{comm::CommProfile, eds::{write_eds, EdsInfo}};
/// let od: CommProfile<1> = CommProfile::new(NodeConfig::DEFAULT);
/// let mut s = heapless::String::<8192>::new();
/// write_eds(&mut s, &EdsInfo::DEFAULT, &od).unwrap();
/// assert!(s.contains("[1018sub1]\nParameterName=Vendor-ID\nObjectType=0x7\nDataType=0x0007\n"));
/// ```
pub fn write_eds<W: Write, D: OdDescribe + ?Sized>(w: &mut W, info: &EdsInfo, od: &D) -> fmt::Result {
    writeln!(w, "[FileInfo]")?;
    writeln!(w, "FileName={}", info.file_name)?;
    writeln!(w, "FileVersion=1\nFileRevision=0\nEDSVersion=4.0")?;
    writeln!(w, "Description={}", info.description)?;
    writeln!(w, "CreationTime={}\nCreationDate={}", info.creation_time, info.creation_date)?;
    writeln!(w, "CreatedBy={}", info.created_by)?;
    writeln!(w, "ModificationTime={}\nModificationDate={}", info.creation_time, info.creation_date)?;
    writeln!(w, "ModifiedBy={}\n", info.created_by)?;

    let count = |lo: u16, hi: u16| {
        (0..od.object_count()).filter_map(|n| od.object(n)).filter(|o| (lo..=hi).contains(&o.index)).count()
    };
    writeln!(w, "[DeviceInfo]")?;
    writeln!(w, "VendorName={}", info.vendor_name)?;
    writeln!(w, "VendorNumber=0x{:X}", identity(od, 1))?;
    writeln!(w, "ProductName={}", info.product_name)?;
    writeln!(w, "ProductNumber=0x{:X}", identity(od, 2))?;
    writeln!(w, "RevisionNumber=0x{:X}", identity(od, 3))?;
    writeln!(w, "OrderCode={}", info.order_code)?;
    for rate in [10u16, 20, 50, 125, 250, 500, 800, 1000] {
        writeln!(w, "BaudRate_{rate}={}", u8::from(info.baud_rates_kbit.contains(&rate)))?;
    }
    writeln!(w, "SimpleBootUpMaster=0\nSimpleBootUpSlave=1")?;
    writeln!(w, "Granularity={}", info.granularity)?;
    writeln!(w, "DynamicChannelsSupported=0\nGroupMessaging=0")?;
    writeln!(w, "NrOfRXPDO={}", count(0x1400, 0x15FF))?;
    writeln!(w, "NrOfTXPDO={}", count(0x1800, 0x19FF))?;
    writeln!(w, "LSS_Supported={}\n", u8::from(info.lss_supported))?;

    writeln!(w, "[DummyUsage]")?;
    for i in 1..=7 {
        writeln!(w, "Dummy{i:04}=0")?;
    }
    writeln!(w, "\n[Comments]\nLines=0\n")?;

    write_list(w, od, "MandatoryObjects", Category::Mandatory)?;
    write_list(w, od, "OptionalObjects", Category::Optional)?;
    write_list(w, od, "ManufacturerObjects", Category::Manufacturer)?;

    for n in 0..od.object_count() {
        if let Some(o) = od.object(n) {
            write_object(w, od, &o)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::comm::{Identity, NodeConfig};
    use crate::od::comm::CommProfile;

    #[test]
    fn comm_profile_eds() {
        const CFG: NodeConfig = NodeConfig {
            identity: Identity { vendor_id: 0x2B6, product_code: 7, revision: 1, serial: 0 },
            device_name: "dev",
            ..NodeConfig::DEFAULT
        };
        let od: CommProfile<2> = CommProfile::new(CFG);
        let mut s = heapless::String::<16384>::new();
        write_eds(&mut s, &EdsInfo::DEFAULT, &od).unwrap();
        assert!(s.contains("VendorNumber=0x2B6\n"));
        assert!(s.contains("ProductNumber=0x7\n"));
        assert!(s.contains("[MandatoryObjects]\nSupportedObjects=3\n1=0x1000\n2=0x1001\n3=0x1018\n"));
        assert!(s.contains("[1016]\nParameterName=Consumer heartbeat time\nObjectType=0x8\nSubNumber=0x3\n"));
        assert!(s.contains("[1016sub2]\nParameterName=Consumer heartbeat time 2\n"));
        assert!(s.contains("[1008]\nParameterName=Manufacturer device name\nObjectType=0x7\nDataType=0x0009\nAccessType=const\nDefaultValue=dev\n"));
        assert!(s.contains("BaudRate_250=1\n"));
        assert!(s.contains("BaudRate_10=0\n"));
        // No empty numeric field anywhere.
        for line in s.lines() {
            if let Some((k, v)) = line.split_once('=') {
                let textual = matches!(
                    k,
                    "Description" | "VendorName" | "ProductName" | "OrderCode" | "DefaultValue" | "CreatedBy"
                );
                assert!(textual || !v.is_empty(), "empty field {k}");
            }
        }
    }

    /// `[DeviceInfo]` counts the PDO communication objects; every PDO object gets its sections.
    #[test]
    fn pdo_objects_in_the_eds() {
        extern crate std;
        let od: CommProfile<0, 3, 2> = CommProfile::for_node(NodeConfig::DEFAULT, 1);
        let mut s = std::string::String::new();
        write_eds(&mut s, &EdsInfo::DEFAULT, &od).unwrap();
        assert!(s.contains("NrOfRXPDO=3\nNrOfTXPDO=2\n"));
        assert!(s.contains("[1400sub1]\nParameterName=COB-ID used by RPDO\nObjectType=0x7\nDataType=0x0007\nAccessType=rw\nDefaultValue=$NODEID+0x80000200\n"));
        assert!(s.contains("[1A01]\nParameterName=TPDO mapping parameter\nObjectType=0x9\nSubNumber=0x9\n"));
        assert!(s.contains("[1801sub6]\nParameterName=SYNC start value\n"));
        assert!(!s.contains("[1400sub4]") && !s.contains("[1400sub6]"));
    }
}
