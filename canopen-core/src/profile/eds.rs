//! The communication profile's part of the CiA 306 EDS: `[FileInfo]`, `[DeviceInfo]` (vendor and product
//! numbers from 1018h, PDO counts from 1400h/1800h), `[DummyUsage]`, `[Comments]` and the object lists
//! (`[MandatoryObjects]` = 1000h, 1001h, 1018h: OD-12). The per-object sections are the dictionary
//! layer's [`write_object`]; the format notes are in [`crate::od::eds`].

use core::fmt::{self, Write};

use crate::od::eds::write_object;
use crate::od::{OdDescribe, Value};

/// What the EDS says that the dictionary does not: file and device information.
///
/// ```
/// use canopen_core::profile::eds::EdsInfo;
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
    /// `[DeviceInfo] LSS_Supported` (written as 0 in a build without the `lss` feature: the node has no LSS
    /// slave then).
    pub lss_supported: bool,
}

impl EdsInfo {
    /// Neutral defaults.
    pub const DEFAULT: EdsInfo = EdsInfo {
        file_name: "device.eds",
        description: "",
        created_by: "canopener",
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
/// # use canopen_core::Sizes;
/// use canopen_core::profile::{eds::{write_eds, EdsInfo}, CommProfile, NodeConfig};
/// let od: CommProfile<Sizes<1, 16, 16, 0, 0>> = CommProfile::new(NodeConfig::DEFAULT);
/// let mut s = String::new();
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
    writeln!(w, "LSS_Supported={}\n", u8::from(info.lss_supported && cfg!(feature = "lss")))?;

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
    use crate::profile::{CommProfile, Identity, NodeConfig};
    use crate::Sizes;

    #[test]
    fn comm_profile_eds() {
        const CFG: NodeConfig = NodeConfig {
            identity: Identity { vendor_id: 0x2B6, product_code: 7, revision: 1, serial: 0 },
            device_name: "dev",
            ..NodeConfig::DEFAULT
        };
        extern crate std;
        let od: CommProfile<Sizes<2, 16, 16, 0, 0>> = CommProfile::new(CFG);
        // A String: 1028h's 127 entries alone are some 17 kB of EDS.
        let mut s = std::string::String::new();
        write_eds(&mut s, &EdsInfo::DEFAULT, &od).unwrap();
        assert!(s.contains("VendorNumber=0x2B6\n"));
        assert!(s.contains("ProductNumber=0x7\n"));
        assert!(s.contains("[MandatoryObjects]\nSupportedObjects=3\n1=0x1000\n2=0x1001\n3=0x1018\n"));
        assert!(s.contains("[1016]\nParameterName=Consumer heartbeat time\nObjectType=0x8\nSubNumber=0x3\n"));
        assert!(s.contains("[1016sub2]\nParameterName=Consumer heartbeat time 2\n"));
        let device_name =
            "[1008]\nParameterName=Manufacturer device name\nObjectType=0x7\nDataType=0x0009\nAccessType=const\nDefaultValue=dev\n";
        assert_eq!(s.contains(device_name), cfg!(feature = "manufacturer-strings"));
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
        let od: CommProfile<Sizes<0, 16, 16, 3, 2>> = CommProfile::for_node(NodeConfig::DEFAULT, 1);
        let mut s = std::string::String::new();
        write_eds(&mut s, &EdsInfo::DEFAULT, &od).unwrap();
        assert!(s.contains("NrOfRXPDO=3\nNrOfTXPDO=2\n"));
        assert!(s.contains("[1400sub1]\nParameterName=COB-ID used by RPDO\nObjectType=0x7\nDataType=0x0007\nAccessType=rw\nDefaultValue=$NODEID+0x80000200\n"));
        let subs = crate::pdo::mapping::MAX_ENTRIES + 1; // 9, or 41h with `pdo-mapping-64` (PDO-30)
        let want = std::format!("[1A01]\nParameterName=TPDO mapping parameter\nObjectType=0x9\nSubNumber={subs:#X}\n");
        assert!(s.contains(&want));
        assert!(s.contains("[1801sub6]\nParameterName=SYNC start value\n"));
        assert!(!s.contains("[1400sub4]") && !s.contains("[1400sub6]"));
    }

    /// `LSS_Supported` follows the build: a node without the `lss` feature has no LSS slave to offer.
    #[test]
    fn lss_supported_follows_the_build() {
        extern crate std;
        let od: CommProfile<Sizes<0, 16, 16, 0, 0>> = CommProfile::new(NodeConfig::DEFAULT);
        let mut s = std::string::String::new();
        write_eds(&mut s, &EdsInfo { lss_supported: true, ..EdsInfo::DEFAULT }, &od).unwrap();
        let want = if cfg!(feature = "lss") { "LSS_Supported=1\n" } else { "LSS_Supported=0\n" };
        assert!(s.contains(want), "{s}");
    }
}
