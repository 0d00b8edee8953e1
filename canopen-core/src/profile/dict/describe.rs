//! The communication profile's description (CiA 306 EDS, [`OdDescribe`]): the name, object code, data type,
//! access, PDO mapping, default and limits of every object and sub-entry of [`CommProfile`] (OD-11), in
//! increasing index order with the optional objects of [`optional`] merged in. SDO and PDO access never come
//! here: they read the `table` module's rows (see the parent module); the test `meta_agrees_with_desc` there
//! checks that both say the same of every sub-entry.
//!
//! The objects are the parent module's (its docs list them with their checklist IDs); their names and
//! defaults follow CiA 301 §7.5.2 and Annex A. A PDO mapping record is rw with `pdo-dynamic-mapping` and
//! const without (PDO-30); an object a build leaves out is not described (OD-16).

use super::super::{optional, ProfileSizes};
use super::{compiled_out, CommProfile, PdoObj, OBJECTS};
use crate::emcy::HISTORY;
use crate::od::{
    count_entry, AbortCode, Access, DataType, EntryDesc, ObjectCode, ObjectDesc, OdDescribe, PdoMapping, Value,
};
use crate::pdo::mapping::MAX_ENTRIES;

#[cfg(feature = "store-restore")]
const STORE_NAMES: [&str; 3] = ["Save all parameters", "Save communication parameters", "Save application parameters"];
#[cfg(feature = "store-restore")]
const RESTORE_NAMES: [&str; 3] = [
    "Restore all default parameters",
    "Restore communication default parameters",
    "Restore application default parameters",
];

impl<Z: ProfileSizes> CommProfile<Z> {
    fn pdo_cob_default(&self, tx: bool, k: usize) -> Value {
        let d = if tx { self.config.tpdo_default(k) } else { self.config.rpdo_default(k) };
        let base = if tx { 0x180 } else { 0x200 };
        let (c, _) = d.params(k, base, 0);
        if d.can_id.is_none() && k < 4 {
            Value::NodeIdPlus(c.cob_id)
        } else {
            Value::Uint(c.cob_id.into())
        }
    }

    /// The description of one sub-entry, or the OD-16 abort code.
    pub(super) fn desc(&self, index: u16, sub: u8) -> Result<EntryDesc, AbortCode> {
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
        let uint = |v: u32| Value::Uint(v.into());
        if compiled_out(index) {
            return Err(AbortCode::ObjectDoesNotExist);
        }
        if let Some(obj) = Self::pdo_obj(index) {
            return self.pdo_desc(obj, index, sub);
        }
        match index {
            0x1000 => var("Device type", Unsigned32, Ro, uint(c.device_type)),
            0x1001 => var("Error register", Unsigned8, Ro, uint(0)).map(|e| e.with_pdo(PdoMapping::Tpdo)),
            #[cfg(feature = "error-history")]
            0x1003 => match sub {
                0 => Ok(EntryDesc::var(index, 0, "Number of errors", Unsigned8, Rw).with_default(uint(0))),
                s if usize::from(s) <= HISTORY => Ok(EntryDesc {
                    numbered: true,
                    ..EntryDesc::var(index, s, "Standard error field", Unsigned32, Ro).with_default(uint(0))
                }),
                _ => Err(AbortCode::SubIndexDoesNotExist),
            },
            0x1005 => var("COB-ID SYNC message", Unsigned32, Rw, uint(c.sync.supported().cob_id.raw())),
            0x1006 => var("Communication cycle period", Unsigned32, Rw, uint(c.sync.period_us)),
            0x1007 => var("Synchronous window length", Unsigned32, Rw, uint(c.sync.window_us)),
            0x1008 => var("Manufacturer device name", VisibleString, Const, Value::Str(c.device_name)),
            0x1009 => var("Manufacturer hardware version", VisibleString, Const, Value::Str(c.hardware_version)),
            0x100A => var("Manufacturer software version", VisibleString, Const, Value::Str(c.software_version)),
            0x100C => var("Guard time", Unsigned16, Rw, uint(c.guard_time_ms.into())),
            0x100D => var("Life time factor", Unsigned8, Rw, uint(c.life_time_factor.into())),
            #[cfg(feature = "store-restore")]
            0x1010 | 0x1011 => {
                let names = if index == 0x1010 { &STORE_NAMES } else { &RESTORE_NAMES };
                match sub {
                    0 => Ok(count_entry(index, 3)),
                    1..=3 => Ok(EntryDesc::var(index, sub, names[usize::from(sub) - 1], Unsigned32, Rw)
                        .with_default(uint(u32::from(self.storage_supported)))),
                    _ => Err(AbortCode::SubIndexDoesNotExist),
                }
            }
            0x1012 => var("COB-ID time stamp object", Unsigned32, Rw, uint(c.time_cob_id)),
            0x1014 => var("COB-ID EMCY", Unsigned32, Rw, Value::NodeIdPlus(0x80)),
            0x1015 => var("Inhibit time EMCY", Unsigned16, Rw, uint(c.emcy_inhibit_100us.into())),
            0x1016 if Z::HB > 0 => match sub {
                0 => Ok(count_entry(index, Z::HB as u8)),
                s if usize::from(s) <= Z::HB => Ok(EntryDesc {
                    numbered: true,
                    ..EntryDesc::var(index, s, "Consumer heartbeat time", Unsigned32, Rw).with_default(uint(0))
                }),
                _ => Err(AbortCode::SubIndexDoesNotExist),
            },
            0x1017 => var("Producer heartbeat time", Unsigned16, Rw, uint(c.heartbeat_time_ms.into())),
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
                Ok(EntryDesc::var(index, sub, name, Unsigned32, Ro).with_default(uint(v)))
            }
            0x1019 => var("Synchronous counter overflow value", Unsigned8, Rw, uint(c.sync.counter_overflow.into())),
            0x1029 => match sub {
                0 => Ok(count_entry(index, 1)),
                1 => Ok(EntryDesc::var(index, 1, "Communication error", Unsigned8, Rw)
                    .with_default(uint(c.error_behaviour.into()))),
                _ => Err(AbortCode::SubIndexDoesNotExist),
            },
            0x1F80 => var("NMT startup", Unsigned32, Rw, uint(c.nmt_startup)),
            _ => Err(AbortCode::ObjectDoesNotExist),
        }
    }

    fn pdo_desc(&self, obj: PdoObj, index: u16, sub: u8) -> Result<EntryDesc, AbortCode> {
        use Access::*;
        use DataType::*;
        let uint = |v: u32| Value::Uint(v.into());
        match obj {
            PdoObj::RpdoComm(k) | PdoObj::TpdoComm(k) => {
                let tx = matches!(obj, PdoObj::TpdoComm(_));
                let d = if tx { self.config.tpdo_default(k) } else { self.config.rpdo_default(k) };
                let e = |name, dt, v| Ok(EntryDesc::var(index, sub, name, dt, Rw).with_default(v));
                match sub {
                    0 => Ok(count_entry(index, if tx { 6 } else { 5 })),
                    1 if tx => e("COB-ID used by TPDO", Unsigned32, self.pdo_cob_default(true, k)),
                    1 => e("COB-ID used by RPDO", Unsigned32, self.pdo_cob_default(false, k)),
                    2 => e("Transmission type", Unsigned8, uint(d.transmission_type.into())),
                    3 => e("Inhibit time", Unsigned16, uint(d.inhibit_100us.into())),
                    5 => e("Event timer", Unsigned16, uint(d.event_timer_ms.into())),
                    6 if tx => e("SYNC start value", Unsigned8, uint(d.sync_start.into())),
                    _ => Err(AbortCode::SubIndexDoesNotExist),
                }
            }
            PdoObj::RpdoMap(k) | PdoObj::TpdoMap(k) => {
                let tx = matches!(obj, PdoObj::TpdoMap(_));
                let d = if tx { self.config.tpdo_default(k) } else { self.config.rpdo_default(k) };
                let m = d.map_params();
                // PDO-30: rw with dynamic mapping, const when the mapping is fixed.
                let access = if cfg!(feature = "pdo-dynamic-mapping") { Rw } else { Const };
                match usize::from(sub) {
                    0 => {
                        let e =
                            EntryDesc::var(index, 0, "Number of mapped application objects in PDO", Unsigned8, access)
                                .with_default(uint(m.count.into()));
                        // A limit below MAX_ENTRIES is the configuration's own: the EDS says it.
                        Ok(if usize::from(d.max_mapped) < MAX_ENTRIES {
                            e.with_limits(Some(uint(0)), Some(uint(d.max_mapped.into())))
                        } else {
                            e
                        })
                    }
                    s if s <= MAX_ENTRIES => Ok(EntryDesc {
                        numbered: true,
                        ..EntryDesc::var(index, sub, "Application object", Unsigned32, access)
                            .with_default(uint(m.entries[s - 1]))
                    }),
                    _ => Err(AbortCode::SubIndexDoesNotExist),
                }
            }
        }
    }
}

impl<Z: ProfileSizes> CommProfile<Z> {
    /// The number of the profile's own objects (without [`optional`]'s).
    const fn own_object_count() -> usize {
        OBJECTS.len() - (Z::HB == 0) as usize + 2 * Z::RPDO + 2 * Z::TPDO + 1
    }

    fn own_object(&self, n: usize) -> Option<ObjectDesc> {
        let index = Self::index_at(n)?;
        let (name, code, subs) = match (index, Self::pdo_obj(index)) {
            (_, Some(PdoObj::RpdoComm(_))) => ("RPDO communication parameter", ObjectCode::Record, 5),
            (_, Some(PdoObj::TpdoComm(_))) => ("TPDO communication parameter", ObjectCode::Record, 6),
            (_, Some(PdoObj::RpdoMap(_))) => ("RPDO mapping parameter", ObjectCode::Record, MAX_ENTRIES as u16 + 1),
            (_, Some(PdoObj::TpdoMap(_))) => ("TPDO mapping parameter", ObjectCode::Record, MAX_ENTRIES as u16 + 1),
            (0x1003, _) => ("Pre-defined error field", ObjectCode::Array, HISTORY as u16 + 1),
            (0x1010, _) => ("Store parameters", ObjectCode::Array, 4),
            (0x1011, _) => ("Restore default parameters", ObjectCode::Array, 4),
            (0x1016, _) => ("Consumer heartbeat time", ObjectCode::Array, Z::HB as u16 + 1),
            (0x1018, _) => ("Identity object", ObjectCode::Record, 5),
            (0x1029, _) => ("Error behaviour", ObjectCode::Array, 2),
            _ => (self.desc(index, 0).ok()?.name, ObjectCode::Var, 1),
        };
        Some(ObjectDesc { index, name, code, first: 0, subs })
    }
}

impl<Z: ProfileSizes> CommProfile<Z> {
    /// Where the `n`-th object of the merged order is: (true, own object `i`) or (false, optional `j`).
    fn locate(&self, n: usize) -> Option<(bool, usize)> {
        let own = |i| Self::index_at(i).unwrap_or(u16::MAX);
        let opt = |j| self.optional.object_index(j).unwrap_or(u16::MAX);
        crate::od::merge_nth(n, Self::own_object_count(), own, self.optional.object_count(), opt)
    }
}

impl<Z: ProfileSizes> OdDescribe for CommProfile<Z> {
    fn object_count(&self) -> usize {
        Self::own_object_count() + self.optional.object_count()
    }

    /// The profile's own objects and [`optional`]'s, merged in increasing index order.
    fn object(&self, n: usize) -> Option<ObjectDesc> {
        match self.locate(n)? {
            (true, i) => self.own_object(i),
            (false, j) => self.optional.object(j),
        }
    }

    /// [`object`](Self::object)'s index alone, from the profile's table of indices: a firmware that stores
    /// its parameters does not link the object and entry names.
    fn object_index(&self, n: usize) -> Option<u16> {
        match self.locate(n)? {
            (true, i) => Self::index_at(i),
            (false, j) => self.optional.object_index(j),
        }
    }

    fn entry(&self, index: u16, sub: u8) -> Option<EntryDesc> {
        if optional::serves(index) {
            return self.optional.entry(index, sub).ok();
        }
        self.desc(index, sub).ok()
    }
}

#[cfg(all(test, feature = "guarding", feature = "time"))]
mod tests {
    use super::*;
    use crate::od::ObjectDictionary;
    use crate::profile::dict::tests::CFG;
    use crate::sizes::Sizes;

    #[test]
    fn describes_itself() {
        extern crate std;
        let od: CommProfile<Sizes<2, 16, 16, 0, 0>> = CommProfile::new(CFG);
        // The optional objects (1002h, 1013h, 1020h, 1028h, 1FA0h, 1FD0h: those this build has) merge into
        // the order.
        let opt = od.optional.object_count();
        let after_1f80 = 2 * usize::from(cfg!(feature = "mpdo"));
        let before_1016 = opt
            - usize::from(cfg!(feature = "verify-config"))
            - usize::from(cfg!(feature = "emcy-consumer"))
            - after_1f80;
        assert_eq!(od.object_count(), 22 + opt);
        let hb = od.object(16 + before_1016).unwrap();
        assert_eq!((hb.index, hb.code, hb.subs), (0x1016, ObjectCode::Array, 3));
        assert!(od.entry(0x1016, 2).unwrap().numbered);
        let none: CommProfile<Sizes<0, 16, 16, 0, 0>> = CommProfile::new(CFG);
        assert_eq!(none.object_count(), 21 + opt);
        assert_eq!(none.info(0x1016, 0), Err(AbortCode::ObjectDoesNotExist));
        assert_eq!(none.object(16 + before_1016).unwrap().index, 0x1017);
        let pdos: CommProfile<Sizes<0, 16, 16, 2, 3>> = CommProfile::new(CFG);
        let all: std::vec::Vec<u16> = (0..pdos.object_count()).map(|n| pdos.object(n).unwrap().index).collect();
        assert!(all.windows(2).all(|w| w[0] < w[1]), "{all:X?}");
        let pdo_objects = [0x1400, 0x1401, 0x1600, 0x1601, 0x1800, 0x1801, 0x1802, 0x1A00, 0x1A01, 0x1A02, 0x1F80];
        assert_eq!(all[20 + opt - after_1f80..all.len() - after_1f80], pdo_objects);
        for index in [0x1002, 0x1013, 0x1020, 0x1028, 0x1FA0, 0x1FD0] {
            assert_eq!(all.contains(&index), optional::serves(index), "{index:04X}h");
        }
    }
}
