//! The communication profile (1000h–1FFFh) as an object dictionary, built from the core's
//! [`NodeConfig`] and [`CommParams`].
//!
//! Objects: 1000h device type (DEV-01, ro), 1001h error register (ERR-01, ro, TPDO-mappable), 1008h/1009h/
//! 100Ah names (DEV-04, const VISIBLE_STRING), 100Ch guard time and 100Dh life time factor (GUARD-02/03,
//! rw), 1016h consumer heartbeat times (HB-06..HB-09: ARRAY of UNSIGNED32, sub 00h const = `HB`, entries rw
//! through [`CommParams::set_consumer`], so a duplicate node-ID is refused with 0604 0043h; omitted when
//! `HB == 0`), 1017h producer heartbeat time (HB-01, rw), 1018h identity (DEV-03, RECORD, sub 00h const 4,
//! subs ro). OD-12 (1000h, 1001h, 1018h mandatory) and OD-16 (abort codes) hold.
//!
//! Not here yet: 1005h–1007h SYNC, 1010h/1011h store/restore, 1012h–1015h TIME/EMCY, 1019h, 1029h,
//! 1200h SDO server, 1400h–1BFFh PDOs. They are added the same way: one arm per object in [`CommProfile`]'s
//! `desc`/`read`/`write` and one index in its object list, kept sorted. Dispatch is a `match` on the index
//! (compiled to a jump table / comparison tree), no table search.

use super::{
    copy_at, count_entry, AbortCode, Access, DataType, EntryDesc, ObjectCode, ObjectDesc, ObjectDictionary, OdDescribe,
    OdValue, PdoMapping, SubInfo, Value,
};
use crate::comm::{CommParams, NodeConfig};

/// The communication-profile dictionary of a node with `HB` heartbeat consumer entries.
///
/// ```
/// use canopen_core::comm::{CommParams, NodeConfig};
/// use canopen_core::od::{comm::CommProfile, AbortCode, ObjectDictionary};
/// const CFG: NodeConfig = NodeConfig { device_type: 0x0001_0191, ..NodeConfig::DEFAULT };
/// let mut od: CommProfile<2> = CommProfile::new(CFG);
/// let mut b = [0u8; 4];
/// assert_eq!(od.read(0x1000, 0, 0, &mut b), Ok(4));
/// assert_eq!(b, [0x91, 0x01, 0x01, 0x00]);
/// od.write(0x1017, 0, &[0x64, 0x00]).unwrap(); // V-HB-04
/// assert_eq!(od.params.heartbeat_time_ms, 100);
/// assert_eq!(od.write(0x1000, 0, &b), Err(AbortCode::WriteOfReadOnly));
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CommProfile<const HB: usize> {
    /// The fixed description (identity, names, defaults).
    pub config: NodeConfig,
    /// The run-time values the services use.
    pub params: CommParams<HB>,
}

/// Indices of the objects, in increasing order.
const OBJECTS: [u16; 10] = [0x1000, 0x1001, 0x1008, 0x1009, 0x100A, 0x100C, 0x100D, 0x1016, 0x1017, 0x1018];

impl<const HB: usize> CommProfile<HB> {
    const HB_FITS: () = assert!(HB <= 127, "1016h has at most 127 consumer entries (HB-06)");

    /// The power-on state of `config`.
    pub const fn new(config: NodeConfig) -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::HB_FITS;
        CommProfile { params: CommParams::new(&config), config }
    }

    /// NMT reset communication: the parameters go back to their power-on values (the error register
    /// is kept, as it belongs to the error handling).
    ///
    /// ```
    /// # use canopen_core::{comm::NodeConfig, od::comm::CommProfile};
    /// let mut od: CommProfile<1> = CommProfile::new(NodeConfig::DEFAULT);
    /// od.params.heartbeat_time_ms = 5;
    /// od.reset_communication();
    /// assert_eq!(od.params.heartbeat_time_ms, 0);
    /// ```
    pub fn reset_communication(&mut self) {
        let err = self.params.error_register;
        self.params = CommParams::new(&self.config);
        self.params.error_register = err;
    }

    fn has(index: u16) -> bool {
        OBJECTS.contains(&index) && (index != 0x1016 || HB > 0)
    }

    /// The description of one sub-entry, or the OD-16 abort code.
    fn desc(&self, index: u16, sub: u8) -> Result<EntryDesc, AbortCode> {
        use Access::*;
        use DataType::*;
        let c = &self.config;
        let var = |name, dt, access, default: Value| {
            if sub == 0 {
                Ok(EntryDesc::var(index, 0, name, dt, access).with_default(default))
            } else {
                Err(AbortCode::SubIndexDoesNotExist)
            }
        };
        match index {
            0x1000 => var("Device type", Unsigned32, Ro, Value::Uint(c.device_type.into())),
            0x1001 => var("Error register", Unsigned8, Ro, Value::Uint(0)).map(|e| e.with_pdo(PdoMapping::Tpdo)),
            0x1008 => var("Manufacturer device name", VisibleString, Const, Value::Str(c.device_name)),
            0x1009 => var("Manufacturer hardware version", VisibleString, Const, Value::Str(c.hardware_version)),
            0x100A => var("Manufacturer software version", VisibleString, Const, Value::Str(c.software_version)),
            0x100C => var("Guard time", Unsigned16, Rw, Value::Uint(c.guard_time_ms.into())),
            0x100D => var("Life time factor", Unsigned8, Rw, Value::Uint(c.life_time_factor.into())),
            0x1016 if HB > 0 => match sub {
                0 => Ok(count_entry(index, HB as u8)),
                s if usize::from(s) <= HB => Ok(EntryDesc {
                    numbered: true,
                    ..EntryDesc::var(index, s, "Consumer heartbeat time", Unsigned32, Rw).with_default(Value::Uint(0))
                }),
                _ => Err(AbortCode::SubIndexDoesNotExist),
            },
            0x1017 => var("Producer heartbeat time", Unsigned16, Rw, Value::Uint(c.heartbeat_time_ms.into())),
            0x1018 => {
                let id = &c.identity;
                let (name, v) = match sub {
                    0 => return Ok(count_entry(index, 4)),
                    1 => ("Vendor-ID", id.vendor_id),
                    2 => ("Product code", id.product_code),
                    3 => ("Revision number", id.revision),
                    4 => ("Serial number", id.serial),
                    _ => return Err(AbortCode::SubIndexDoesNotExist),
                };
                Ok(EntryDesc::var(index, sub, name, Unsigned32, Ro).with_default(Value::Uint(v.into())))
            }
            _ => Err(AbortCode::ObjectDoesNotExist),
        }
    }

    fn current_size(&self, index: u16) -> Option<usize> {
        match index {
            0x1008 => Some(self.config.device_name.len()),
            0x1009 => Some(self.config.hardware_version.len()),
            0x100A => Some(self.config.software_version.len()),
            _ => None,
        }
    }
}

impl<const HB: usize> ObjectDictionary for CommProfile<HB> {
    fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
        let d = self.desc(index, sub)?;
        let size = self.current_size(index).unwrap_or(d.max_size);
        Ok(SubInfo { data_type: d.data_type, access: d.access, pdo: d.pdo, size })
    }

    fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        self.desc(index, sub)?;
        let p = &self.params;
        let c = &self.config;
        let mut tmp = [0u8; 4];
        let n = match (index, sub) {
            (0x1008, _) => return Ok(copy_at(c.device_name.as_bytes(), offset, buf)),
            (0x1009, _) => return Ok(copy_at(c.hardware_version.as_bytes(), offset, buf)),
            (0x100A, _) => return Ok(copy_at(c.software_version.as_bytes(), offset, buf)),
            (0x1000, _) => c.device_type.read_bytes(0, &mut tmp),
            (0x1001, _) => p.error_register.read_bytes(0, &mut tmp),
            (0x100C, _) => p.guard_time_ms.read_bytes(0, &mut tmp),
            (0x100D, _) => p.life_time_factor.read_bytes(0, &mut tmp),
            (0x1016, 0) => (HB as u8).read_bytes(0, &mut tmp),
            (0x1016, s) => p.consumer(s).map_or(0, |e| e.raw()).read_bytes(0, &mut tmp),
            (0x1017, _) => p.heartbeat_time_ms.read_bytes(0, &mut tmp),
            (0x1018, 0) => 4u8.read_bytes(0, &mut tmp),
            (0x1018, 1) => c.identity.vendor_id.read_bytes(0, &mut tmp),
            (0x1018, 2) => c.identity.product_code.read_bytes(0, &mut tmp),
            (0x1018, 3) => c.identity.revision.read_bytes(0, &mut tmp),
            (0x1018, _) => c.identity.serial.read_bytes(0, &mut tmp),
            _ => return Err(AbortCode::ObjectDoesNotExist),
        };
        Ok(copy_at(&tmp[..n], offset, buf))
    }

    fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        let d = self.desc(index, sub)?;
        if !d.access.writable() {
            return Err(AbortCode::WriteOfReadOnly);
        }
        let p = &mut self.params;
        match index {
            0x100C => p.guard_time_ms = u16::decode(data)?,
            0x100D => p.life_time_factor = u8::decode(data)?,
            0x1016 => p.set_consumer(sub, u32::decode(data)?)?,
            0x1017 => p.heartbeat_time_ms = u16::decode(data)?,
            _ => return Err(AbortCode::WriteOfReadOnly),
        }
        Ok(())
    }

    fn begin_write(&mut self, index: u16, sub: u8, size: Option<usize>) -> Result<(), AbortCode> {
        let _ = size;
        let d = self.desc(index, sub)?;
        if !d.access.writable() {
            return Err(AbortCode::WriteOfReadOnly);
        }
        Err(AbortCode::UnsupportedAccess)
    }
}

impl<const HB: usize> OdDescribe for CommProfile<HB> {
    fn object_count(&self) -> usize {
        OBJECTS.iter().filter(|&&i| Self::has(i)).count()
    }

    fn object(&self, n: usize) -> Option<ObjectDesc> {
        let index = OBJECTS.iter().copied().filter(|&i| Self::has(i)).nth(n)?;
        let (name, code, subs) = match index {
            0x1016 => ("Consumer heartbeat time", ObjectCode::Array, HB as u16 + 1),
            0x1018 => ("Identity object", ObjectCode::Record, 5),
            _ => (self.desc(index, 0).ok()?.name, ObjectCode::Var, 1),
        };
        Some(ObjectDesc { index, name, code, first: 0, subs })
    }

    fn entry(&self, index: u16, sub: u8) -> Option<EntryDesc> {
        self.desc(index, sub).ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::comm::Identity;

    const CFG: NodeConfig = NodeConfig {
        device_type: 0x0004_0191,
        identity: Identity { vendor_id: 0x2B6, product_code: 2, revision: 0x0001_0002, serial: 77 },
        device_name: "rust node",
        heartbeat_time_ms: 250,
        ..NodeConfig::DEFAULT
    };

    fn read(od: &impl ObjectDictionary, i: u16, s: u8) -> Result<heapless::Vec<u8, 32>, AbortCode> {
        let mut b = [0u8; 32];
        let n = od.read(i, s, 0, &mut b)?;
        Ok(heapless::Vec::from_slice(&b[..n]).unwrap_or_default())
    }

    #[test]
    fn reads_the_configuration() {
        let od: CommProfile<3> = CommProfile::new(CFG);
        assert_eq!(read(&od, 0x1000, 0).unwrap()[..], [0x91, 0x01, 0x04, 0x00]);
        assert_eq!(read(&od, 0x1001, 0).unwrap()[..], [0]);
        assert_eq!(read(&od, 0x1008, 0).unwrap()[..], *b"rust node");
        assert_eq!(read(&od, 0x1009, 0).unwrap()[..], []);
        assert_eq!(read(&od, 0x1017, 0).unwrap()[..], [0xFA, 0]);
        assert_eq!(read(&od, 0x1016, 0).unwrap()[..], [3]);
        assert_eq!(read(&od, 0x1018, 0).unwrap()[..], [4]);
        assert_eq!(read(&od, 0x1018, 1).unwrap()[..], [0xB6, 0x02, 0, 0]);
        assert_eq!(read(&od, 0x1018, 4).unwrap()[..], [77, 0, 0, 0]);
        assert_eq!(read(&od, 0x1018, 5), Err(AbortCode::SubIndexDoesNotExist));
        assert_eq!(read(&od, 0x1016, 4), Err(AbortCode::SubIndexDoesNotExist));
        assert_eq!(read(&od, 0x1000, 1), Err(AbortCode::SubIndexDoesNotExist));
        assert_eq!(read(&od, 0x1002, 0), Err(AbortCode::ObjectDoesNotExist));
        assert_eq!(od.info(0x1008, 0).unwrap().size, 9);
        assert_eq!(od.info(0x1008, 0).unwrap().access, Access::Const);
    }

    /// V-HBC-01..05 through the dictionary, and the seed's wrong writes of §4.
    #[test]
    fn writes_heartbeat_consumers() {
        let mut od: CommProfile<4> = CommProfile::new(CFG);
        assert_eq!(od.write(0x1016, 0, &[3]), Err(AbortCode::WriteOfReadOnly));
        assert_eq!(od.write(0x1016, 1, &[0x64, 0, 2]), Err(AbortCode::LengthTooLow));
        od.write(0x1016, 1, &[0x64, 0, 2, 0]).unwrap();
        od.write(0x1016, 2, &[0x90, 1, 3, 0]).unwrap();
        od.write(0x1016, 3, &[0xA0, 0x0F, 7, 0]).unwrap();
        assert_eq!(od.write(0x1016, 4, &[0xC8, 0, 2, 0]), Err(AbortCode::ParameterIncompatibility));
        assert_eq!(od.params.heartbeat_consumers[3], 0);
        od.write(0x1016, 1, &[0, 0, 0, 0]).unwrap();
        assert_eq!(read(&od, 0x1016, 2).unwrap()[..], [0x90, 1, 3, 0]);
        assert_eq!(od.write(0x1018, 1, &[0; 4]), Err(AbortCode::WriteOfReadOnly));
        assert_eq!(od.write(0x1008, 0, b"x"), Err(AbortCode::WriteOfReadOnly));
        od.write(0x100C, 0, &[10, 0]).unwrap();
        od.write(0x100D, 0, &[3]).unwrap();
        assert_eq!((od.params.guard_time_ms, od.params.life_time_factor), (10, 3));
        od.reset_communication();
        assert_eq!(od.params.heartbeat_time_ms, 250);
        assert_eq!(od.params.heartbeat_consumers, [0; 4]);
    }

    #[test]
    fn describes_itself() {
        let od: CommProfile<2> = CommProfile::new(CFG);
        assert_eq!(od.object_count(), 10);
        assert_eq!(od.object(7).unwrap().code, ObjectCode::Array);
        assert_eq!(od.object(7).unwrap().subs, 3);
        assert!(od.entry(0x1016, 2).unwrap().numbered);
        let none: CommProfile<0> = CommProfile::new(CFG);
        assert_eq!(none.object_count(), 9);
        assert_eq!(none.info(0x1016, 0), Err(AbortCode::ObjectDoesNotExist));
        assert_eq!(none.object(7).unwrap().index, 0x1017);
    }
}
