//! The EDS/DCF writer (CiA 306): an [`Eds`] back into the text a CANopen tool reads.
//!
//! What is written, in this order: the sections that describe no object as they were read (`[FileInfo]`,
//! `[DeviceInfo]`, ...), a DCF's `[DeviceComissioning]`, then the three object lists of CiA 306, each
//! followed by its objects: `[MandatoryObjects]` (1000h, 1001h, 1018h), `[OptionalObjects]` (the rest of
//! 1000h–1FFFh, 6000h–FFFFh and anything below 1000h) and `[ManufacturerObjects]` (2000h–5FFFh), the
//! split python canopen's exporter makes too. An object is `[xxxx]` with `ParameterName` and `ObjectType`
//! (and `SubNumber` for an ARRAY or RECORD, whose entries follow as `[xxxxsubN]`); an entry has
//! `ParameterName`, `ObjectType=0x7`, `DataType`, `AccessType`, `DefaultValue`, `LowLimit`, `HighLimit`,
//! `PDOMapping` and a DCF's `ParameterValue`, each only when it has a value.
//!
//! Parsing what this writes gives the same [`Eds`]: that is the writer's contract, tested here and on
//! python canopen's files (tests/eds_real.rs). What parsing itself folds together stays folded: a
//! `CompactSubObj` array is written with its entries in full, `rwr`/`rww` as `rw`, and ObjectType 02h
//! (DOMAIN), 05h and 06h as a VAR (07h). Text is written as it is: a name or value with a line break (which
//! no parsed file has, but a hand-built [`Eds`] may) makes a file that does not read back the same.

use std::fmt::{self, Write as _};

use crate::eds::{Eds, Entry, Object, ObjectKind};

/// Whether an object list holds an index.
type Holds = fn(u16) -> bool;

/// The three object lists of CiA 306 and which indices each holds.
const LISTS: [(&str, Holds); 3] = [
    ("MandatoryObjects", |i| matches!(i, 0x1000 | 0x1001 | 0x1018)),
    ("OptionalObjects", |i| !matches!(i, 0x1000 | 0x1001 | 0x1018 | 0x2000..=0x5FFF)),
    ("ManufacturerObjects", |i| (0x2000..=0x5FFF).contains(&i)),
];

/// Writes the EDS, or the DCF when it has values and a `[DeviceComissioning]` (see the module docs).
///
/// ```
/// let text = "[1017]\nParameterName=Producer heartbeat time\nObjectType=0x7\nDataType=0x0006\nAccessType=rw\nDefaultValue=0\n";
/// let eds = canopen_eds::Eds::parse(text).unwrap();
/// let written = eds.to_string();
/// assert!(written.contains("[OptionalObjects]\nSupportedObjects=1\n1=0x1017\n"));
/// assert!(written.contains("[1017]\nParameterName=Producer heartbeat time\nObjectType=0x7\nDataType=0x0006\n"));
/// assert_eq!(canopen_eds::Eds::parse(&written).unwrap(), eds);
/// ```
impl fmt::Display for Eds {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for s in &self.sections {
            writeln!(f, "[{}]", s.name)?;
            for (k, v) in &s.keys {
                writeln!(f, "{k}={v}")?;
            }
            writeln!(f)?;
        }
        if let Some(c) = &self.commissioning {
            writeln!(f, "[DeviceComissioning]\nNodeID={}\nNodeName={}", c.node_id, c.node_name)?;
            writeln!(f, "Baudrate={}\nNetNumber={}\nNetworkName={}", c.baudrate, c.net_number, c.network_name)?;
            writeln!(f, "CANopenManager={}", u8::from(c.canopen_manager))?;
            if let Some(serial) = c.lss_serial_number {
                writeln!(f, "LSS_SerialNumber=0x{serial:08X}")?;
            }
            writeln!(f)?;
        }
        for (list, holds) in LISTS {
            let objects: Vec<&Object> = self.objects.values().filter(|o| holds(o.index)).collect();
            writeln!(f, "[{list}]\nSupportedObjects={}", objects.len())?;
            for (n, o) in (1..).zip(&objects) {
                writeln!(f, "{n}=0x{:04X}", o.index)?;
            }
            writeln!(f)?;
            for o in objects {
                object(f, o)?;
            }
        }
        Ok(())
    }
}

fn object(f: &mut fmt::Formatter<'_>, o: &Object) -> fmt::Result {
    let code = match o.kind {
        ObjectKind::Var => return o.entries.get(&0).map_or(Ok(()), |e| entry(f, &format!("{:04X}", o.index), e)),
        ObjectKind::Array => 8,
        ObjectKind::Record => 9,
    };
    writeln!(f, "[{:04X}]\nParameterName={}\nObjectType=0x{code:X}", o.index, o.name)?;
    writeln!(f, "SubNumber=0x{:X}\n", o.entries.len())?;
    for e in o.entries.values() {
        entry(f, &format!("{:04X}sub{:X}", o.index, e.sub), e)?;
    }
    Ok(())
}

fn entry(f: &mut fmt::Formatter<'_>, section: &str, e: &Entry) -> fmt::Result {
    let mut s = format!("[{section}]\nParameterName={}\nObjectType=0x7\n", e.name);
    let _ = write!(s, "DataType=0x{:04X}\nAccessType={}\n", e.data_type, e.access.as_str());
    for (key, value) in [("DefaultValue", &e.default), ("LowLimit", &e.low), ("HighLimit", &e.high)] {
        if let Some(v) = value {
            let _ = writeln!(s, "{key}={v}");
        }
    }
    let _ = writeln!(s, "PDOMapping={}", u8::from(e.pdo_mapping));
    if let Some(v) = &e.value {
        let _ = writeln!(s, "ParameterValue={v}");
    }
    writeln!(f, "{s}")
}

#[cfg(test)]
mod tests {
    use crate::eds::{DeviceCommissioning, Eds};

    /// Every shape the parser knows survives parse -> write -> parse: info sections in order, a record, a
    /// CompactSubObj array with names and DCF values, limits, defaults, PDO mapping, ParameterValue and
    /// [DeviceComissioning]. The object lists are written anew (a stale one in the input is not kept).
    #[test]
    fn written_text_parses_to_the_same_eds() {
        let text = "\
[FileInfo]
FileName=rt.eds
[DeviceInfo]
VendorName=Acme
NrOfTXPDO=1
[MandatoryObjects]
SupportedObjects=9
1=0x7777
[DeviceComissioning]
NodeID=9
NodeName=Pump 2
Baudrate=125
LSS_SerialNumber=0xCAFE
[1018]
ParameterName=Identity object
ObjectType=0x9
[1018sub0]
DataType=5
AccessType=ro
DefaultValue=1
[1018sub1]
ParameterName=Vendor-ID
DataType=7
AccessType=ro
DefaultValue=0x1234
ParameterValue=0x1234
[1800sub1]
ParameterName=orphan, no object: dropped by parse
DataType=7
[2000]
ParameterName=Gains
ObjectType=8
CompactSubObj=2
DataType=0x0003
AccessType=rww
LowLimit=-100
HighLimit=100
PDOMapping=1
[2000Name]
1=Kp
[2000Value]
2=-7
[6001]
ParameterName=Label
DataType=9
AccessType=rw
DefaultValue=a b
ParameterValue=c d
";
        let eds = Eds::parse(text).unwrap();
        let written = eds.to_string();
        assert_eq!(Eds::parse(&written).unwrap(), eds, "{written}");
        assert!(written.contains("[MandatoryObjects]\nSupportedObjects=1\n1=0x1018\n"), "{written}");
        assert!(written.contains("[ManufacturerObjects]\nSupportedObjects=1\n1=0x2000\n"), "{written}");
        assert!(written.contains("[2000sub2]\nParameterName=Gains2\n"), "{written}");
        assert!(written.contains("AccessType=rw\nLowLimit=-100\nHighLimit=100\nPDOMapping=1\nParameterValue=-7\n"));
        assert!(written.starts_with("[FileInfo]\nFileName=rt.eds\n\n[DeviceInfo]\nVendorName=Acme\nNrOfTXPDO=1\n"));
        let c = DeviceCommissioning {
            node_name: "Pump 2".into(),
            lss_serial_number: Some(0xCAFE),
            ..DeviceCommissioning::new(9, 125)
        };
        assert_eq!(eds.commissioning, Some(c));
    }
}
