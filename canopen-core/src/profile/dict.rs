//! The communication profile (1000h–1FFFh) as an object dictionary, built from the core's
//! [`NodeConfig`] and [`CommParams`].
//!
//! Objects: 1000h device type (DEV-01), 1001h error register (ERR-01, ro, TPDO-mappable, from the active
//! errors), 1003h pre-defined error field (ERR-04..09: sub 00h rw, only 0 may be written, else 0609 0030h;
//! empty entry → 0800 0024h), 1005h–1007h SYNC (SYNC-01..08; COB-ID rules COB-15/16), 1008h–100Ah names
//! (DEV-04), 100Ch/100Dh guarding (GUARD-02/03), 1010h/1011h store/restore (STORE-01..11; the node performs
//! the save, see [`crate::storage`]), 1012h COB-ID TIME (TIME-01..03), 1014h COB-ID EMCY (EMCY-02/03),
//! 1015h EMCY inhibit (EMCY-09), 1016h consumer heartbeat times (HB-06..09; omitted when `HB == 0`), 1017h
//! (HB-01), 1018h identity (DEV-03), 1019h SYNC counter overflow (SYNC-10/12), 1029h error behaviour
//! (ERR-10/11), 1400h+k / 1600h+k RPDO communication and mapping (PDO-06..13, PDO-30..37), 1800h+k / 1A00h+k
//! TPDO communication and mapping (PDO-14..18, PDO-24..26), 1F80h NMT startup (NMT-27).
//!
//! PDO change rules (PDO-17, PDO-35): a COB-ID's CAN-ID changes only while bit 31 = 1 (else 0609 0030h); a
//! CAN-ID from the restricted set (COB-13) cannot be made valid (0609 0030h); the inhibit time and SYNC start
//! value change only while the PDO is not valid (0609 0030h: CiA 301 names no code for it); mapping
//! sub 00h and entries change only while the PDO is not valid, and entries only while sub 00h = 0 (0601 0000h,
//! as CANopenNode answers); sub 04h and RPDO sub 06h do not exist (0609 0011h, PDO-11/13); an unsupported
//! transmission type is 0609 0030h (PDO-09/18). Whether a mapping entry names a mappable object (0602 0000h,
//! 0604 0041h, 0604 0042h) needs the application dictionary too and is checked by the node's dictionary view
//! before the value reaches this one.
//!
//! Which sub-entries exist, their type and access, and where each value lives are data: the table of the
//! `table` module, walked once per access; reading and writing a value is one `match` on its slot. The
//! description of the same objects for the EDS (names, object codes, defaults, limits: [`OdDescribe`](crate::od::OdDescribe)) is
//! the `describe` submodule's.

mod describe;

use super::table::{self, in_bounds, Counts, Found, Slot};
use super::{optional, CommParams, NodeConfig, ProfileSizes};
use crate::cob::{is_restricted, CobIdEntry};
use crate::emcy::NodeErrors;
use crate::od::{check_len, copy_at, AbortCode, ObjectDictionary, PdoDir, PdoHandle, SubInfo};
#[cfg(test)]
use crate::od::{Access, DataType, PdoMapping};
use crate::pdo::mapping::MAX_ENTRIES;
#[cfg(feature = "pdo-dynamic-mapping")]
use crate::pdo::PdoDefault;
use crate::pdo::{rpdo_type_ok, tpdo_type_ok, PdoComm, PdoMapParams};
use crate::sizes::Sizes;
#[cfg(feature = "store-restore")]
use crate::storage::{LOAD_SIGNATURE, SAVE_SIGNATURE};

/// `Self::find(index, sub)?`, except that an index the table has not and [`optional`] serves returns
/// `$optional` (the optional objects are asked only where the table has nothing: no cost on the profile's
/// own objects). Without the optional objects' features it is exactly `Self::find(index, sub)?`: the
/// match with a constant-false guard still cost the minimal firmware 240 B of flash.
macro_rules! find_or_optional {
    ($index:expr, $sub:expr, $optional:expr) => {
        find_or_optional!(find, $index, $sub, $optional)
    };
    ($find:ident, $index:expr, $sub:expr, $optional:expr) => {{
        #[cfg(any(
            feature = "manufacturer-status",
            feature = "high-res-time",
            feature = "verify-config",
            feature = "emcy-consumer"
        ))]
        let f = match Self::$find($index, $sub) {
            Ok(f) => f,
            Err(e) => return cold(|| if optional::serves($index) { $optional } else { Err(e) }),
        };
        #[cfg(not(any(
            feature = "manufacturer-status",
            feature = "high-res-time",
            feature = "verify-config",
            feature = "emcy-consumer"
        )))]
        let f = Self::$find($index, $sub)?;
        f
    }};
}

/// What a write of 1010h/1011h with the right signature answers (0606 0000h: this dictionary cannot save or
/// restore by itself). The node's dictionary (`node::dict`) takes it as the go-ahead of its store command:
/// the profile has then checked the entry, its access, its length and the signature (STORE-04/09).
#[cfg(feature = "store-restore")]
pub(crate) const STORE_GO_AHEAD: AbortCode = AbortCode::HardwareError;

/// The length of [`CommProfile`]'s write path for "the entry's own size" (an expedited download without the
/// size indicated, SDO-13): one word where an `Option<usize>` took two at every call.
pub(crate) const SIZE_NOT_INDICATED: usize = usize::MAX;

/// Runs `f` out of line, as the unlikely path: the optional objects' fallback kept the SDO upload of the
/// profile's own objects 4 instructions slower when it was inline (bench-node.sh expedited_upload).
#[cfg(any(
    feature = "manufacturer-status",
    feature = "high-res-time",
    feature = "verify-config",
    feature = "emcy-consumer"
))]
#[cold]
#[inline(never)]
fn cold<T>(f: impl FnOnce() -> T) -> T {
    f()
}

/// The communication-profile dictionary of a node with the capacities `Z` (`Z::HB` heartbeat consumer
/// entries, `Z::RPDO` receive and `Z::TPDO` transmit PDOs; see [`Sizes`]).
///
/// ```
/// # use canopen_core::Sizes;
/// use canopen_core::profile::{CommParams, CommProfile, NodeConfig};
/// use canopen_core::od::{AbortCode, ObjectDictionary};
/// const CFG: NodeConfig = NodeConfig { device_type: 0x0001_0191, ..NodeConfig::DEFAULT };
/// let mut od: CommProfile<Sizes<2, 16, 16, 0, 0>> = CommProfile::new(CFG);
/// let mut b = [0u8; 4];
/// assert_eq!(od.read(0x1000, 0, 0, &mut b), Ok(4));
/// assert_eq!(b, [0x91, 0x01, 0x01, 0x00]);
/// od.write(0x1017, 0, &[0x64, 0x00]).unwrap(); // 1017h = 100 ms: 2B 17 10 00 64 00 00 00
/// assert_eq!(od.params.heartbeat_time_ms, 100);
/// assert_eq!(od.write(0x1000, 0, &b), Err(AbortCode::WriteOfReadOnly));
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CommProfile<Z: ProfileSizes = Sizes> {
    /// The fixed description (identity, names, defaults).
    pub config: NodeConfig,
    /// The run-time values the services use.
    pub params: CommParams<Z>,
    /// The node-ID the node-ID-relative defaults refer to.
    pub node_id: u8,
    /// Active errors, 1001h and the 1003h history.
    pub errors: NodeErrors,
    /// Whether 1010h can save (reads 1 in bit 0, STORE-05) and 1011h can restore (STORE-11).
    pub storage_supported: bool,
    /// 1002h, 1013h, 1020h, 1028h (each behind its Cargo feature; see [`super::optional`]).
    pub optional: super::optional::OptionalObjects,
}

/// Indices of every fixed object a build can have, in increasing order (the PDO ranges and 1F80h follow).
const ALL_OBJECTS: [u16; 21] = [
    0x1000, 0x1001, 0x1003, 0x1005, 0x1006, 0x1007, 0x1008, 0x1009, 0x100A, 0x100C, 0x100D, 0x1010, 0x1011, 0x1012,
    0x1014, 0x1015, 0x1016, 0x1017, 0x1018, 0x1019, 0x1029,
];

/// How many of [`ALL_OBJECTS`] this build has.
const OBJECT_COUNT: usize = {
    let (mut n, mut i) = (0, 0);
    while i < ALL_OBJECTS.len() {
        n += !compiled_out(ALL_OBJECTS[i]) as usize;
        i += 1;
    }
    n
};

/// The fixed objects of this build in increasing order: [`ALL_OBJECTS`] without those [`compiled_out`]
/// names.
const OBJECTS: [u16; OBJECT_COUNT] = {
    let mut t = [0u16; OBJECT_COUNT];
    let (mut n, mut i) = (0, 0);
    while i < ALL_OBJECTS.len() {
        if !compiled_out(ALL_OBJECTS[i]) {
            t[n] = ALL_OBJECTS[i];
            n += 1;
        }
        i += 1;
    }
    t
};

/// The objects of a service or an optional object this build leaves out do not exist: 0602 0000h (OD-16),
/// and they are not in the EDS. (first, last index, whether this build has them) per Cargo feature:
/// `guarding` 100Ch/100Dh, `time` 1012h, and the optional objects of `lib.rs`. A constant per build: no
/// cost with the features on.
const BUILT: [(u16, u16, bool); 9] = [
    (0x100C, 0x100D, cfg!(feature = "guarding")),
    (0x1012, 0x1012, cfg!(feature = "time")),
    (0x1003, 0x1003, cfg!(feature = "error-history")),
    (0x1007, 0x1007, cfg!(feature = "sync-window")),
    (0x1008, 0x100A, cfg!(feature = "manufacturer-strings")),
    (0x1015, 0x1015, cfg!(feature = "emcy-inhibit")),
    (0x1019, 0x1019, cfg!(feature = "sync-counter")),
    (0x1029, 0x1029, cfg!(feature = "error-behaviour")),
    (0x1010, 0x1011, cfg!(feature = "store-restore")),
];

/// Whether `index` is one of [`BUILT`]'s objects this build leaves out.
const fn compiled_out(index: u16) -> bool {
    let mut i = 0;
    while i < BUILT.len() {
        let (first, last, built) = BUILT[i];
        if index >= first && index <= last {
            return !built;
        }
        i += 1;
    }
    false
}

/// Which PDO object an index is.
#[derive(Clone, Copy, PartialEq, Eq)]
enum PdoObj {
    RpdoComm(usize),
    RpdoMap(usize),
    TpdoComm(usize),
    TpdoMap(usize),
}

impl<Z: ProfileSizes> CommProfile<Z> {
    const FITS: () = {
        assert!(Z::HB <= 127, "1016h has at most 127 consumer entries (HB-06)");
        assert!(Z::RPDO <= 512 && Z::TPDO <= 512, "at most 512 RPDOs and 512 TPDOs (PDO-02)");
    };

    /// The power-on state of `config` for node-ID 0 (see [`for_node`](Self::for_node)).
    pub fn new(config: NodeConfig) -> Self {
        Self::for_node(config, 0)
    }

    /// The power-on state of `config` for `node_id`.
    ///
    /// ```
    /// # use canopen_core::Sizes;
    /// # use canopen_core::profile::{CommProfile, NodeConfig};
    /// let od: CommProfile<Sizes<0, 16, 16, 1, 1>> = CommProfile::for_node(NodeConfig::DEFAULT, 3);
    /// assert_eq!(od.params.emcy_cob_id, 0x83);
    /// ```
    pub fn for_node(config: NodeConfig, node_id: u8) -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::FITS;
        CommProfile {
            params: CommParams::for_node(&config, node_id),
            config,
            node_id,
            errors: NodeErrors::new(),
            storage_supported: false,
            optional: super::optional::OptionalObjects::new(),
        }
    }

    /// NMT reset communication: the parameters go back to their power-on values (the error register and
    /// history are kept: they belong to the error handling).
    ///
    /// ```
    /// # use canopen_core::Sizes;
    /// # use canopen_core::profile::{CommProfile, NodeConfig};
    /// let mut od: CommProfile<Sizes<1, 16, 16, 0, 0>> = CommProfile::new(NodeConfig::DEFAULT);
    /// od.params.heartbeat_time_ms = 5;
    /// od.reset_communication();
    /// assert_eq!(od.params.heartbeat_time_ms, 0);
    /// ```
    pub fn reset_communication(&mut self) {
        self.params.set_defaults(&self.config, self.node_id);
        self.optional.reset_communication();
    }

    fn pdo_obj(index: u16) -> Option<PdoObj> {
        let k = usize::from(index & 0x1FF);
        match index {
            0x1400..=0x15FF if k < Z::RPDO => Some(PdoObj::RpdoComm(k)),
            0x1600..=0x17FF if k < Z::RPDO => Some(PdoObj::RpdoMap(k)),
            0x1800..=0x19FF if k < Z::TPDO => Some(PdoObj::TpdoComm(k)),
            0x1A00..=0x1BFF if k < Z::TPDO => Some(PdoObj::TpdoMap(k)),
            _ => None,
        }
    }

    /// The index of the `n`-th object (increasing order).
    fn index_at(n: usize) -> Option<u16> {
        let fixed = OBJECTS.len() - usize::from(Z::HB == 0);
        if n < fixed {
            return OBJECTS.iter().copied().filter(|&i| i != 0x1016 || Z::HB > 0).nth(n);
        }
        let mut m = n - fixed;
        for (base, count) in [(0x1400u16, Z::RPDO), (0x1600, Z::RPDO), (0x1800, Z::TPDO), (0x1A00, Z::TPDO)] {
            if m < count {
                return Some(base + m as u16);
            }
            m -= count;
        }
        (m == 0).then_some(0x1F80)
    }

    const COUNTS: Counts = Counts::new(Z::HB, Z::RPDO, Z::TPDO);

    /// Where a sub-entry is, from the table of `table` (one walk; OD-16 abort codes). One call: the cold
    /// paths (writes, `info`, segmented reads) share the walk.
    fn find(index: u16, sub: u8) -> Result<Found, AbortCode> {
        table::walk(index, sub, Self::COUNTS)
    }

    /// [`find`](Self::find) with a VAR of 1000h–101Fh found inline, for the expedited upload (the hot read:
    /// bench-node.sh expedited_upload).
    #[inline]
    fn find_fast(index: u16, sub: u8) -> Result<Found, AbortCode> {
        table::find(index, sub, Self::COUNTS)
    }

    /// Data type, access and PDO mapping of one sub-entry, or the OD-16 abort code. It must agree with
    /// `desc` (the test `meta_agrees_with_desc` checks every index and sub-index).
    #[cfg(test)]
    fn meta(index: u16, sub: u8) -> Result<(DataType, Access, PdoMapping), AbortCode> {
        Self::find(index, sub).map(|f| f.meta())
    }

    #[cfg(test)]
    fn current_size(&self, index: u16) -> Option<usize> {
        let f = Self::find(index, 0).ok()?;
        self.text(f.slot()).map(str::len)
    }

    /// The text of a VISIBLE_STRING slot (1008h–100Ah, DEV-04); `None` for the numeric ones.
    fn text(&self, slot: Slot) -> Option<&'static str> {
        #[cfg(feature = "manufacturer-strings")]
        let c = &self.config;
        match slot {
            #[cfg(feature = "manufacturer-strings")]
            Slot::DeviceName => Some(c.device_name),
            #[cfg(feature = "manufacturer-strings")]
            Slot::HardwareVersion => Some(c.hardware_version),
            #[cfg(feature = "manufacturer-strings")]
            Slot::SoftwareVersion => Some(c.software_version),
            _ => None,
        }
    }

    fn pdo_comm(&self, f: Found) -> Option<&PdoComm> {
        let p = &self.params;
        let comm = if f.tx() { p.tpdo_comm.as_ref() } else { p.rpdo_comm.as_ref() };
        comm.get(f.k_below(comm.len()))
    }

    fn pdo_map(&self, f: Found) -> Option<&PdoMapParams> {
        let p = &self.params;
        let map = if f.tx() { p.tpdo_map.as_ref() } else { p.rpdo_map.as_ref() };
        map.get(f.k_below(map.len()))
    }

    /// The current value of a numeric entry found by `find` (0 for a string slot). Inlined on the host (into
    /// `read` and `read_expedited`), where the call and the bounds check of the slot's jump table cost the
    /// expedited upload 4 instructions per frame once the slot was a number (bench-node.sh expedited_upload);
    /// a bare-metal build keeps its one out-of-line copy (both inlined: hundreds of bytes of flash).
    #[cfg_attr(not(target_os = "none"), inline(always))]
    fn value(&self, f: Found, sub: u8) -> Result<u32, AbortCode> {
        let p = &self.params;
        let c = &self.config;
        let id = &c.identity;
        Ok(match f.slot() {
            Slot::Count => f.n().into(),
            Slot::DeviceType => c.device_type,
            Slot::ErrorRegister => (self.errors.register() | p.error_register).into(),
            #[cfg(feature = "error-history")]
            Slot::History => self.errors.read_history(sub)?,
            Slot::SyncCob => p.sync.cob_id.raw(),
            Slot::SyncPeriod => p.sync.period_us,
            #[cfg(feature = "sync-window")]
            Slot::SyncWindow => p.sync.window_us,
            #[cfg(feature = "manufacturer-strings")]
            Slot::DeviceName | Slot::HardwareVersion | Slot::SoftwareVersion => 0,
            #[cfg(feature = "guarding")]
            Slot::GuardTime => p.guard_time_ms.into(),
            #[cfg(feature = "guarding")]
            Slot::LifeTimeFactor => p.life_time_factor.into(),
            #[cfg(feature = "store-restore")]
            Slot::Store | Slot::Restore => u32::from(self.storage_supported),
            #[cfg(feature = "time")]
            Slot::TimeCob => p.time_cob_id,
            Slot::EmcyCob => p.emcy_cob_id,
            #[cfg(feature = "emcy-inhibit")]
            Slot::EmcyInhibit => p.emcy_inhibit_100us.into(),
            Slot::Consumer => p.consumer(sub).map_or(0, |e| e.raw()),
            Slot::HeartbeatTime => p.heartbeat_time_ms.into(),
            Slot::Identity => match sub {
                1 => id.vendor_id,
                2 => id.product_code,
                3 => id.revision,
                _ => id.serial,
            },
            #[cfg(feature = "sync-counter")]
            Slot::SyncOverflow => p.sync.counter_overflow.into(),
            #[cfg(feature = "error-behaviour")]
            Slot::ErrorBehaviour => p.error_behaviour.into(),
            Slot::NmtStartup => p.nmt_startup,
            Slot::PdoCob | Slot::PdoType | Slot::PdoInhibit | Slot::PdoEventTimer | Slot::PdoSyncStart => {
                self.pdo_comm(f).map_or(0, |c| pdo_comm_value(c, f.slot()))
            }
            // Slot::MapCount, Slot::MapEntry (the last slots a table row names).
            _ => self.pdo_map(f).map_or(0, |m| pdo_map_value(m, sub)),
        })
    }

    /// Writes a numeric entry found by `find`; `rules` applies the change rules of the module docs (SDO),
    /// without them the value is only range-checked by its type (loading stored values after a reset).
    ///
    /// The COB-IDs 1005h, 1012h and 1014h end in one check of the change rules (COB-15/16) and one store:
    /// which bits make each one active is data (`flip`, `active`: the COB is active when its bits `active`,
    /// XOR-ed with `flip`, are not all 0), not a closure inlined per object.
    fn set(&mut self, f: Found, sub: u8, v: u32, rules: bool) -> Result<(), AbortCode> {
        let p = &mut self.params;
        let (cob, flip, active): (&mut u32, u32, u32) = 'cob: {
            match f.slot() {
                #[cfg(feature = "error-history")]
                Slot::History => self.errors.write_history_count(v as u8)?,
                Slot::SyncCob => {
                    crate::sync::check_producible(v)?; // SYNC-03: also a stored value, the build cannot produce
                    if crate::sync::PRODUCER {
                        break 'cob (p.sync.cob_id.raw_mut(), 0, CobIdEntry::BIT30);
                        // active while producing (bit 30)
                    }
                    // Never active in a build that cannot produce SYNC (bit 30 refused above): only the format
                    // rules, here, where they fold to a mask test (the minimal device, with 1014h alone in the
                    // shared check: 16 B less than through it).
                    if rules {
                        CobIdEntry::from_raw(v).check_change(v, |_| false)?;
                    }
                    p.sync.cob_id = CobIdEntry::from_raw(v);
                }
                Slot::SyncPeriod => p.sync.period_us = v,
                #[cfg(feature = "sync-window")]
                Slot::SyncWindow => p.sync.window_us = v,
                #[cfg(feature = "guarding")]
                Slot::GuardTime => p.guard_time_ms = v as u16,
                #[cfg(feature = "guarding")]
                Slot::LifeTimeFactor => p.life_time_factor = v as u8,
                #[cfg(feature = "store-restore")]
                Slot::Store | Slot::Restore if rules => {
                    let sig = if f.slot() == Slot::Store { SAVE_SIGNATURE } else { LOAD_SIGNATURE };
                    // STORE-04/09: a wrong signature is 0800 0020h; the node performs the real save/restore.
                    return Err(if v != sig { AbortCode::CannotStore } else { STORE_GO_AHEAD });
                }
                #[cfg(feature = "store-restore")]
                Slot::Store | Slot::Restore => {}
                #[cfg(feature = "time")]
                // TIME-01/02: active while consuming or producing.
                Slot::TimeCob => break 'cob (&mut p.time_cob_id, 0, CobIdEntry::BIT31 | CobIdEntry::BIT30),
                // EMCY-02: active while bit 31 (invalid) is 0.
                Slot::EmcyCob => break 'cob (&mut p.emcy_cob_id, CobIdEntry::BIT31, CobIdEntry::BIT31),
                #[cfg(feature = "emcy-inhibit")]
                Slot::EmcyInhibit => p.emcy_inhibit_100us = v as u16,
                Slot::Consumer => p.set_consumer_at(in_bounds(usize::from(sub).wrapping_sub(1), Z::HB), v)?,
                Slot::HeartbeatTime => p.heartbeat_time_ms = v as u16,
                #[cfg(feature = "sync-counter")]
                Slot::SyncOverflow => {
                    if rules && p.sync.period_us != 0 {
                        return Err(AbortCode::CannotStoreDeviceState); // SYNC-12
                    }
                    if v == 1 || v > 240 {
                        return Err(AbortCode::InvalidValue); // SYNC-10
                    }
                    p.sync.counter_overflow = v as u8;
                }
                #[cfg(feature = "error-behaviour")]
                Slot::ErrorBehaviour => {
                    if (3..=0x7F).contains(&v) {
                        return Err(AbortCode::InvalidValue); // ERR-11: reserved
                    }
                    p.error_behaviour = v as u8;
                }
                Slot::NmtStartup => p.nmt_startup = v,
                Slot::PdoCob
                | Slot::PdoType
                | Slot::PdoInhibit
                | Slot::PdoEventTimer
                | Slot::PdoSyncStart
                | Slot::MapCount
                | Slot::MapEntry => return self.set_pdo(f, sub, v, rules),
                _ => return Err(AbortCode::WriteOfReadOnly),
            }
            return Ok(());
        };
        if rules {
            CobIdEntry::from_raw(*cob).check_change(v, |e| (e.raw() ^ flip) & active != 0)?;
        }
        *cob = v;
        Ok(())
    }

    /// A PDO communication record's entry, or (feature `pdo-dynamic-mapping`) a mapping record's.
    fn set_pdo(&mut self, f: Found, sub: u8, v: u32, rules: bool) -> Result<(), AbortCode> {
        let p = &mut self.params;
        let comm = if f.tx() { p.tpdo_comm.as_mut() } else { p.rpdo_comm.as_mut() };
        let Some(comm) = comm.get_mut(f.k_below(comm.len())) else {
            return Err(AbortCode::ObjectDoesNotExist);
        };
        let valid = comm.is_valid();
        #[cfg(not(feature = "pdo-dynamic-mapping"))]
        let _ = sub; // a fixed mapping is const: `write_found` refuses it before this
        match f.slot() {
            #[cfg(feature = "pdo-dynamic-mapping")]
            Slot::MapCount | Slot::MapEntry => {
                let map = if f.tx() { p.tpdo_map.as_mut() } else { p.rpdo_map.as_mut() };
                let Some(map) = map.get_mut(f.k_below(map.len())) else {
                    return Err(AbortCode::ObjectDoesNotExist);
                };
                // Only the highest count of the PDO's default (`PdoDefault::max_mapped`), not a copy of it.
                let defaults = if f.tx() { self.config.tpdo } else { self.config.rpdo };
                let max = defaults.get(f.k()).unwrap_or(&PdoDefault::UNUSED).max_mapped;
                return set_map(comm, map, sub, v, rules, max);
            }
            Slot::PdoCob => {
                if f.tx() {
                    crate::pdo::check_tpdo_rtr(v)?; // a build without TPDO remote requests: bit 30 stays set
                }
                if rules {
                    let new = comm.cob().check_change(v, |e| !e.bit31())?;
                    if !new.bit31() && is_restricted(new.can_id()) {
                        return Err(AbortCode::InvalidValue); // COB-13
                    }
                }
                comm.cob_id = v;
            }
            Slot::PdoType => {
                let ok = if f.tx() { tpdo_type_ok(v as u8) } else { rpdo_type_ok(v as u8) };
                if !ok {
                    return Err(AbortCode::InvalidValue);
                }
                comm.transmission_type = v as u8;
            }
            Slot::PdoInhibit => {
                if rules && valid {
                    return Err(AbortCode::InvalidValue); // PDO-10, PDO-24
                }
                comm.inhibit_100us = v as u16;
            }
            Slot::PdoEventTimer => comm.event_timer_ms = v as u16,
            Slot::PdoSyncStart => {
                if rules && valid || v > 240 {
                    return Err(AbortCode::InvalidValue); // PDO-26
                }
                comm.sync_start = v as u8;
            }
            _ => return Err(AbortCode::SubIndexDoesNotExist),
        }
        Ok(())
    }
}

/// `read_expedited` of a string: its length, and its bytes when it fits. Out of line, so that the numeric
/// reads (the usual ones) do not keep its registers (bench-node.sh expedited_upload: see the commit).
#[inline(never)]
fn text_expedited(text: &str, buf: &mut [u8; 4]) -> (usize, usize) {
    let len = text.len();
    match buf.get_mut(..len) {
        Some(dst) if len > 0 => (len, copy_at(text.as_bytes(), 0, dst)),
        _ => (len, 0),
    }
}

/// Sub 01h–06h of a PDO communication record.
fn pdo_comm_value(c: &PdoComm, slot: Slot) -> u32 {
    match slot {
        Slot::PdoCob => c.cob_id,
        Slot::PdoType => c.transmission_type.into(),
        Slot::PdoInhibit => c.inhibit_100us.into(),
        Slot::PdoEventTimer => c.event_timer_ms.into(),
        _ => c.sync_start.into(),
    }
}

/// Sub `sub` of a PDO mapping record: the count at 00h, the raw entries above.
fn pdo_map_value(m: &PdoMapParams, sub: u8) -> u32 {
    match usize::from(sub).checked_sub(1) {
        None => m.count.into(),
        Some(i) => m.entries.get(in_bounds(i, MAX_ENTRIES)).copied().unwrap_or(0),
    }
}

/// PDO-30/35/37: the mapping changes only while the PDO is not valid, entries only while sub 00h = 0.
/// `max` is the configuration's highest count (`PdoDefault::max_mapped`), above which a count is refused
/// with 0609 0031h (its `HighLimit`).
#[cfg(feature = "pdo-dynamic-mapping")]
fn set_map(comm: &PdoComm, map: &mut PdoMapParams, sub: u8, v: u32, rules: bool, max: u8) -> Result<(), AbortCode> {
    if rules && comm.is_valid() {
        return Err(AbortCode::UnsupportedAccess);
    }
    match usize::from(sub) {
        0 => {
            if crate::pdo::is_mpdo_count(v as u8) && v <= 0xFF {
                map.count = v as u8; // MPDO-05: FEh SAM-MPDO, FFh DAM-MPDO; the entries are not used
                return Ok(());
            }
            if v as usize > MAX_ENTRIES {
                return Err(AbortCode::PdoLengthExceeded);
            }
            if v > u32::from(max) {
                return Err(AbortCode::ValueTooHigh);
            }
            // The first `v` entries (at most MAX_ENTRIES, checked above) as a slice: `take(v)` kept a second
            // counter and its own exit in the loop.
            let mapped = map.entries.get(..v as usize).unwrap_or(&[]);
            if rules && mapped.iter().any(|&e| e & 0xFF == 0) {
                return Err(AbortCode::PdoLengthExceeded); // an empty entry inside the count
            }
            map.count = v as u8;
        }
        s => {
            if rules && map.count != 0 {
                return Err(AbortCode::UnsupportedAccess);
            }
            let slot = map.entries.get_mut(in_bounds(s - 1, MAX_ENTRIES)).ok_or(AbortCode::SubIndexDoesNotExist)?;
            *slot = v;
        }
    }
    Ok(())
}

impl<Z: ProfileSizes> CommProfile<Z> {
    /// Writes the entry `find` found: access (0601 0002h), exact length (0607 0012h/0013h), then `set`.
    fn write_found(&mut self, f: Found, sub: u8, data: &[u8], rules: bool) -> Result<(), AbortCode> {
        if !f.writable() {
            return Err(AbortCode::WriteOfReadOnly);
        }
        // Every writable entry is numeric, 1..=4 bytes; the little-endian value is folded from exactly those
        // bytes (no copy call, no length check that cannot fail).
        check_len(data, f.size())?;
        let v = data.iter().rev().fold(0, |v, &b| v << 8 | u32::from(b));
        self.set(f, sub, v, rules)
    }

    /// The one write path (SDO's `write` and `write_expedited`, stored values' `load_value`): the entry's
    /// bytes are `data`'s first `len`, or as many as the entry has when `len` is [`SIZE_NOT_INDICATED`] (an
    /// expedited download without the size indicated, SDO-13; `data` then holds 4 bytes).
    fn write_checked(&mut self, index: u16, sub: u8, data: &[u8], len: usize, rules: bool) -> Result<(), AbortCode> {
        let f = find_or_optional!(index, sub, {
            let data = data.get(..len).unwrap_or(data);
            if rules {
                self.optional.write(index, sub, data)
            } else {
                self.optional.load(index, sub, data)
            }
        });
        let bytes = data.get(..if len == SIZE_NOT_INDICATED { f.size() } else { len }).unwrap_or(data);
        self.write_found(f, sub, bytes, rules)
    }
    /// The SDO write of an entry, with the change rules: `data`'s first `len` bytes, or as many as the entry
    /// has when `len` is [`SIZE_NOT_INDICATED`] (an expedited download without the size indicated, SDO-13).
    /// What `write` and `write_expedited` do, for the node's dictionary, which routes both through one call.
    pub(crate) fn write_sdo(&mut self, index: u16, sub: u8, data: &[u8], len: usize) -> Result<(), AbortCode> {
        self.write_checked(index, sub, data, len, true)
    }

    /// Writes a stored value without the SDO change rules (store/restore after a reset: the record was
    /// consistent when it was saved; PDO mappings are resolved again when the node applies them).
    ///
    /// ```
    /// # use canopen_core::Sizes;
    /// # use canopen_core::profile::{CommProfile, NodeConfig};
    /// let mut od: CommProfile<Sizes<0, 16, 16, 1, 0>> = CommProfile::for_node(NodeConfig::DEFAULT, 1);
    /// od.load_value(0x1400, 1, &[0x01, 0x02, 0, 0]).unwrap(); // RPDO 1 valid
    /// od.load_value(0x1400, 3, &[10, 0]).unwrap(); // inhibit time while the PDO is valid: only without rules
    /// assert_eq!(od.params.rpdo_comm[0].inhibit_100us, 10);
    /// ```
    pub fn load_value(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        self.write_checked(index, sub, data, data.len(), false)
    }
}

/// A view of a [`CommProfile`] whose writes skip the SDO change rules: what [`crate::storage::load`]
/// writes stored communication values through.
///
/// ```
/// # use canopen_core::Sizes;
/// # use canopen_core::{profile::NodeConfig, od::ObjectDictionary, profile::{CommProfile, Unchecked}};
/// let mut od: CommProfile<Sizes<0, 16, 16, 0, 0>> = CommProfile::new(NodeConfig::DEFAULT);
/// Unchecked(&mut od).write(0x1017, 0, &[10, 0]).unwrap();
/// assert_eq!(od.params.heartbeat_time_ms, 10);
/// ```
pub struct Unchecked<'a, Z: ProfileSizes>(pub &'a mut CommProfile<Z>);

impl<Z: ProfileSizes> ObjectDictionary for Unchecked<'_, Z> {
    const STREAMS: bool = false;
    const SEGMENTED_UPLOADS: bool = CommProfile::<Z>::SEGMENTED_UPLOADS;

    fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
        self.0.info(index, sub)
    }
    fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        self.0.read(index, sub, offset, buf)
    }
    fn read_expedited(&self, index: u16, sub: u8, buf: &mut [u8; 4]) -> Result<(usize, usize), AbortCode> {
        self.0.read_expedited(index, sub, buf)
    }
    fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        self.0.load_value(index, sub, data)
    }
}

impl<Z: ProfileSizes> ObjectDictionary for CommProfile<Z> {
    /// Every writable entry is numeric: `begin_write` below always fails.
    const STREAMS: bool = false;
    /// Every entry but the strings 1008h–100Ah (feature `manufacturer-strings`) has 1..=4 bytes, the optional
    /// objects too (the test `segmented_uploads_agrees_with_the_entries` checks it against the description).
    const SEGMENTED_UPLOADS: bool = cfg!(feature = "manufacturer-strings");

    fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
        let f = find_or_optional!(index, sub, self.optional.info(index, sub));
        let (data_type, access, pdo) = f.meta();
        let size = self.text(f.slot()).map_or(f.size(), str::len);
        Ok(SubInfo { data_type, access, pdo, size })
    }

    /// Out of line: inlined into `Merged::read` it made the application's segmented uploads pay for its
    /// registers (bench-node.sh segmented_upload +10 instructions per frame).
    #[inline(never)]
    fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        let f = find_or_optional!(index, sub, self.optional.read(index, sub, offset, buf));
        // A string's bytes or the value's (one copy for both).
        let v;
        let bytes = match self.text(f.slot()) {
            Some(text) => text.as_bytes(),
            None => {
                v = self.value(f, sub)?.to_le_bytes();
                v.get(..f.size()).unwrap_or(&v)
            }
        };
        Ok(copy_at(bytes, offset, buf))
    }

    fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        self.write_checked(index, sub, data, data.len(), true)
    }

    /// One table walk; every entry here is readable.
    fn read_expedited(&self, index: u16, sub: u8, buf: &mut [u8; 4]) -> Result<(usize, usize), AbortCode> {
        let f = find_or_optional!(find_fast, index, sub, self.optional.read_expedited(index, sub, buf));
        if let Some(text) = self.text(f.slot()) {
            return Ok(text_expedited(text, buf));
        }
        // The bytes above the entry's size are 0 (the value is zero-extended).
        *buf = self.value(f, sub)?.to_le_bytes();
        let n = f.size();
        Ok((n, n))
    }

    /// One table walk; the writable entries are all numeric (1..=4 bytes), so `len` not indicated means
    /// the entry's size (SDO-13).
    fn write_expedited(&mut self, index: u16, sub: u8, data: &[u8; 4], len: Option<usize>) -> Result<(), AbortCode> {
        self.write_checked(index, sub, data, len.unwrap_or(SIZE_NOT_INDICATED), true)
    }

    /// One table walk, no [`SubInfo`]: of the table's entries only 1001h is mappable (TPDO, ERR-01; its
    /// `Found::meta`), an UNSIGNED8 that is read; every other entry is 0604 0041h,
    /// as `PdoHandle::check` answers for its description (`meta_agrees_with_desc` and the test
    /// `pdo_resolve_agrees_with_info` check the two against each other).
    fn pdo_resolve(&self, index: u16, sub: u8, dir: PdoDir) -> Result<PdoHandle, AbortCode> {
        let f = find_or_optional!(index, sub, {
            let info = self.optional.info(index, sub)?;
            PdoHandle::check(index, sub, &info, dir, PdoHandle::NO_SLOT)
        });
        if f.slot() == Slot::ErrorRegister && dir == PdoDir::Tpdo {
            Ok(PdoHandle { index, sub, size: 1, slot: PdoHandle::NO_SLOT })
        } else {
            Err(AbortCode::NotMappable)
        }
    }

    /// No entry of the table is RPDO-mappable (see `pdo_resolve`, which gives no handle for one in an RPDO):
    /// a handle here is an optional object's (1013h, feature `high-res-time`), written as `write` does;
    /// any other is 0604 0041h.
    fn pdo_write(&mut self, handle: &PdoHandle, data: &[u8]) -> Result<(), AbortCode> {
        if optional::serves(handle.index) {
            return self.optional.write(handle.index, handle.sub, data);
        }
        Err(AbortCode::NotMappable)
    }

    fn begin_write(&mut self, index: u16, sub: u8, size: Option<usize>) -> Result<(), AbortCode> {
        let _ = size;
        if optional::serves(index) {
            self.optional.info(index, sub)?;
            return Err(AbortCode::UnsupportedAccess);
        }
        if !Self::find(index, sub)?.writable() {
            return Err(AbortCode::WriteOfReadOnly);
        }
        Err(AbortCode::UnsupportedAccess)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pdo::PdoDefault;
    use crate::profile::Identity;

    use crate::od::{EntryDesc, OdDescribe, Value};

    pub(super) const CFG: NodeConfig = NodeConfig {
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

    /// The configuration as read by SDO: DEV-01 (1000h), DEV-03 (1018h, each of sub 01h-04h apart), DEV-04
    /// (1008h-100Ah), the counts (OD-04) and the OD-16 abort codes.
    #[test]
    fn reads_the_configuration() {
        let od: CommProfile<Sizes<3, 16, 16, 0, 0>> = CommProfile::new(CFG);
        assert_eq!(read(&od, 0x1000, 0).unwrap()[..], [0x91, 0x01, 0x04, 0x00]);
        assert_eq!(read(&od, 0x1001, 0).unwrap()[..], [0]);
        if cfg!(feature = "manufacturer-strings") {
            assert_eq!(read(&od, 0x1008, 0).unwrap()[..], *b"rust node");
            assert_eq!(read(&od, 0x1009, 0).unwrap()[..], []);
        } else {
            assert_eq!(read(&od, 0x1008, 0), Err(AbortCode::ObjectDoesNotExist));
        }
        assert_eq!(read(&od, 0x1017, 0).unwrap()[..], [0xFA, 0]);
        assert_eq!(read(&od, 0x1016, 0).unwrap()[..], [3]);
        assert_eq!(read(&od, 0x1018, 0).unwrap()[..], [4]);
        assert_eq!(read(&od, 0x1018, 1).unwrap()[..], [0xB6, 0x02, 0, 0]);
        assert_eq!(read(&od, 0x1018, 2).unwrap()[..], [2, 0, 0, 0]);
        assert_eq!(read(&od, 0x1018, 3).unwrap()[..], [2, 0, 1, 0]);
        assert_eq!(read(&od, 0x1018, 4).unwrap()[..], [77, 0, 0, 0]);
        assert_eq!(od.read_expedited(0x1018, 3, &mut [0; 4]), Ok((4, 4)));
        assert_eq!(read(&od, 0x1018, 5), Err(AbortCode::SubIndexDoesNotExist));
        assert_eq!(read(&od, 0x1016, 4), Err(AbortCode::SubIndexDoesNotExist));
        assert_eq!(read(&od, 0x1000, 1), Err(AbortCode::SubIndexDoesNotExist));
        assert_eq!(read(&od, 0x1004, 0), Err(AbortCode::ObjectDoesNotExist));
        if cfg!(feature = "manufacturer-strings") {
            assert_eq!(od.info(0x1008, 0).unwrap().size, 9);
            assert_eq!(od.info(0x1008, 0).unwrap().access, Access::Const);
        }
    }

    /// A configuration's own PDO limits (what an EDS says, eds-to-rust carries): a mapping of at most 4
    /// entries has 1A00h:00 limits 0..4 and refuses a count of 5 with 0609 0031h; a TPDO without RTR has
    /// COB-ID bit 30 (PDO-15), relative to the node-ID in the EDS; the defaults state no limits.
    #[test]
    fn pdo_defaults_limit_the_mapping_count_and_set_bit_30() {
        static TPDO: [PdoDefault; 1] = [PdoDefault { max_mapped: 4, rtr_allowed: false, ..PdoDefault::EVENT }];
        let cfg = NodeConfig { tpdo: &TPDO, ..CFG };
        let mut od: CommProfile<Sizes<0, 16, 16, 1, 2>> = CommProfile::for_node(cfg, 5);
        let count = od.entry(0x1A00, 0).unwrap();
        assert_eq!((count.low, count.high), (Some(Value::Uint(0)), Some(Value::Uint(4))));
        assert_eq!(od.entry(0x1A01, 0).unwrap().high, None);
        assert_eq!(od.entry(0x1800, 1).unwrap().default, Some(Value::NodeIdPlus(0x4000_0180)));
        assert_eq!(read(&od, 0x1800, 1).unwrap()[..], [0x85, 0x01, 0, 0x40]);
        od.write(0x1800, 1, &[0x85, 0x01, 0, 0xC0]).unwrap(); // not valid: the mapping may change
        if !cfg!(feature = "pdo-dynamic-mapping") {
            // PDO-30: a fixed mapping is const, whatever the PDO's state.
            assert_eq!(od.write(0x1A00, 0, &[0]), Err(AbortCode::WriteOfReadOnly));
            assert_eq!(od.write(0x1A00, 1, &[0x08, 0x01, 0x00, 0x60]), Err(AbortCode::WriteOfReadOnly));
            assert_eq!(od.info(0x1A00, 1).unwrap().access, Access::Const);
            return;
        }
        for (index, sub) in (1..=5).flat_map(|sub| [(0x1A00, sub), (0x1A01, sub)]) {
            od.write(index, sub, &[0x08, 0x01, 0x00, 0x60]).unwrap();
        }
        assert_eq!(od.write(0x1A00, 0, &[5]), Err(AbortCode::ValueTooHigh));
        od.write(0x1A00, 0, &[4]).unwrap();
        od.write(0x1A01, 0, &[5]).unwrap(); // TPDO 2 (no default): up to MAX_ENTRIES
    }

    /// A stored mapping is loaded without the SDO change rules (PDO-35): an entry, then the count while the
    /// PDO is valid, which SDO refuses with 0601 0000h. (It was the `load_value` doctest's example until a
    /// build without `pdo-dynamic-mapping` ran the doctests too.)
    #[test]
    #[cfg(feature = "pdo-dynamic-mapping")]
    fn load_value_skips_the_mapping_rules() {
        let mut od: CommProfile<Sizes<0, 16, 16, 1, 0>> = CommProfile::for_node(NodeConfig::DEFAULT, 1);
        od.load_value(0x1600, 1, &[8, 0, 1, 0x10]).unwrap(); // entry while sub 00h = 0 is fine anyway
        od.load_value(0x1400, 1, &[0x01, 0x02, 0, 0]).unwrap();
        assert_eq!(od.write(0x1600, 0, &[1]), Err(AbortCode::UnsupportedAccess)); // valid: not by SDO
        od.load_value(0x1600, 0, &[1]).unwrap(); // count while the PDO is valid: only without rules
        assert_eq!(od.params.rpdo_map[0].count, 1);
    }

    /// Heartbeat consumer entries 1016h:01..04 through the dictionary (0002 0064h, 0003 0190h, 0007 0FA0h;
    /// node 2 twice refused, an entry disabled by 0), and wrong writes a tutorial prints (sub 00h, short values).
    #[test]
    fn writes_heartbeat_consumers() {
        let mut od: CommProfile<Sizes<4, 16, 16, 0, 0>> = CommProfile::new(CFG);
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
        #[cfg(feature = "manufacturer-strings")]
        assert_eq!(od.write(0x1008, 0, b"x"), Err(AbortCode::WriteOfReadOnly));
        #[cfg(feature = "guarding")]
        {
            od.write(0x100C, 0, &[10, 0]).unwrap();
            od.write(0x100D, 0, &[3]).unwrap();
            assert_eq!((od.params.guard_time_ms, od.params.life_time_factor), (10, 3));
        }
        od.reset_communication();
        assert_eq!(od.params.heartbeat_time_ms, 250);
        assert_eq!(od.params.heartbeat_consumers, [0; 4]);
    }

    /// `meta` (the SDO/PDO path) and `desc` (the EDS path) describe every sub-entry the same way.
    fn check_meta<Z: ProfileSizes>() {
        let od: CommProfile<Z> = CommProfile::new(CFG);
        for index in (0x1000..=0x1BFF).chain(0x1F00..=0x1FFF) {
            for sub in 0..=255u8 {
                let m = CommProfile::<Z>::meta(index, sub);
                let d = od.desc(index, sub).map(|d| (d.data_type, d.access, d.pdo));
                assert_eq!(m, d, "{index:04X}h sub {sub}");
                if let Ok(d) = od.desc(index, sub) {
                    let info = od.info(index, sub).unwrap();
                    assert_eq!(info.size, od.current_size(index).unwrap_or(d.max_size), "{index:04X}h sub {sub}");
                }
            }
        }
    }

    /// `SEGMENTED_UPLOADS` (whether the SDO server builds its segmented-upload path) agrees with the
    /// description: true exactly when some readable entry has no fixed size of 1..=4 bytes, with the
    /// optional objects of this build.
    #[test]
    fn segmented_uploads_agrees_with_the_entries() {
        type Z = Sizes<4, 16, 16, 4, 4>;
        let od: CommProfile<Z> = CommProfile::new(CFG);
        let large = |e: EntryDesc| e.access.readable() && !matches!(e.data_type.size(), Some(1..=4));
        let any = (0..od.object_count())
            .filter_map(|n| od.object(n))
            .any(|o| (0..=255u8).filter_map(|s| od.entry(o.index, s)).any(large));
        assert_eq!(CommProfile::<Z>::SEGMENTED_UPLOADS, any);
    }

    /// PDO-36 (0602 0000h, 0609 0011h, 0604 0041h): the profile's own `pdo_resolve` answers every index and
    /// sub-index in both directions as the provided method (`info`, then `PdoHandle::check`) does.
    fn check_pdo_resolve<Z: ProfileSizes>() {
        let od: CommProfile<Z> = CommProfile::new(CFG);
        for index in (0x1000..=0x1BFF).chain(0x1F00..=0x1FFF) {
            for sub in 0..=255u8 {
                for dir in [PdoDir::Tpdo, PdoDir::Rpdo] {
                    let provided =
                        od.info(index, sub).and_then(|i| PdoHandle::check(index, sub, &i, dir, PdoHandle::NO_SLOT));
                    assert_eq!(od.pdo_resolve(index, sub, dir), provided, "{index:04X}h sub {sub} {dir:?}");
                }
            }
        }
        assert!(od.pdo_resolve(0x1001, 0, PdoDir::Tpdo).is_ok());
    }

    /// PDO-36: no entry of the profile's table can be mapped into an RPDO (`pdo_resolve` refuses them all,
    /// above), so `pdo_write` refuses a handle of one (0604 0041h) and changes nothing; an optional object's
    /// handle (1013h, RPDO-mappable with `high-res-time`) is written as `write` writes it.
    #[test]
    fn pdo_write_serves_only_rpdo_mappable_objects() {
        let mut od: CommProfile<Sizes<1, 16, 16, 1, 1>> = CommProfile::new(CFG);
        let before = od.clone();
        let h = PdoHandle { index: 0x1017, sub: 0, size: 2, slot: PdoHandle::NO_SLOT };
        assert_eq!(od.pdo_write(&h, &[5, 0]), Err(AbortCode::NotMappable));
        assert_eq!(od, before);
        if let Ok(h) = od.pdo_resolve(0x1013, 0, PdoDir::Rpdo) {
            let mut by_sdo = od.clone();
            by_sdo.write(0x1013, 0, &[1, 2, 3, 4]).unwrap();
            od.pdo_write(&h, &[1, 2, 3, 4]).unwrap();
            assert_eq!(od, by_sdo);
        }
    }

    #[test]
    fn pdo_resolve_agrees_with_info() {
        check_pdo_resolve::<Sizes<4, 16, 16, 4, 4>>();
        check_pdo_resolve::<Sizes<0, 16, 16, 2, 3>>();
    }

    /// OD-16 at every index, not only 1000h–1BFFh and 1F00h–1FFFh (`check_meta`): an index of no profile
    /// object, inside 1000h–1FFFh or outside it (a `CommProfile` asked directly), is 0602 0000h with any
    /// sub-index, and `meta` agrees with `desc` there too.
    #[test]
    fn meta_agrees_with_desc_at_every_index() {
        fn check<Z: ProfileSizes>() {
            let od: CommProfile<Z> = CommProfile::new(CFG);
            for index in 0..=0xFFFFu16 {
                for sub in [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 0x40, 0x7F, 0x80, 0xFE, 0xFF] {
                    let m = CommProfile::<Z>::meta(index, sub);
                    assert_eq!(
                        m,
                        od.desc(index, sub).map(|d| (d.data_type, d.access, d.pdo)),
                        "{index:04X}h sub {sub}"
                    );
                    if !(0x1000..=0x1FFF).contains(&index) {
                        assert_eq!(m, Err(AbortCode::ObjectDoesNotExist), "{index:04X}h sub {sub}");
                    }
                }
            }
        }
        check::<Sizes<4, 16, 16, 4, 4>>();
        check::<Sizes<0, 16, 16, 2, 3>>();
    }

    #[test]
    fn meta_agrees_with_desc() {
        check_meta::<Sizes<4, 16, 16, 4, 4>>();
        check_meta::<Sizes<0, 16, 16, 2, 3>>();
        check_meta::<Sizes<1, 16, 16, 0, 0>>();
    }

    /// The objects of a feature this build leaves out (guarding: 100Ch/100Dh, TIME: 1012h, and the optional
    /// objects 1003h, 1007h, 1008h–100Ah, 1015h, 1019h, 1029h, and 1010h/1011h) do not exist: SDO gets 0602 0000h (OD-16), the
    /// EDS does not list them, and the other objects keep their order. With every feature on, nothing is gone.
    #[test]
    fn compiled_out_objects_do_not_exist() {
        extern crate std;
        let mut od: CommProfile<Sizes<2, 16, 16, 0, 0>> = CommProfile::new(CFG);
        let per_feature: [(&[u16], bool); 9] = [
            (&[0x100C, 0x100D], cfg!(feature = "guarding")),
            (&[0x1012], cfg!(feature = "time")),
            (&[0x1003], cfg!(feature = "error-history")),
            (&[0x1007], cfg!(feature = "sync-window")),
            (&[0x1008, 0x1009, 0x100A], cfg!(feature = "manufacturer-strings")),
            (&[0x1015], cfg!(feature = "emcy-inhibit")),
            (&[0x1019], cfg!(feature = "sync-counter")),
            (&[0x1029], cfg!(feature = "error-behaviour")),
            (&[0x1010, 0x1011], cfg!(feature = "store-restore")),
        ];
        let gone: std::vec::Vec<u16> =
            per_feature.iter().filter(|(_, built)| !built).flat_map(|(indices, _)| indices.iter().copied()).collect();
        for &index in &gone {
            assert_eq!(od.info(index, 0), Err(AbortCode::ObjectDoesNotExist), "{index:04X}h");
            assert_eq!(read(&od, index, 0), Err(AbortCode::ObjectDoesNotExist), "{index:04X}h");
            assert_eq!(od.read_expedited(index, 0, &mut [0; 4]), Err(AbortCode::ObjectDoesNotExist), "{index:04X}h");
            assert_eq!(od.write(index, 0, &[0; 4]), Err(AbortCode::ObjectDoesNotExist), "{index:04X}h");
            assert_eq!(od.entry(index, 0), None, "{index:04X}h");
        }
        assert_eq!(od.object_count(), 22 - gone.len() + od.optional.object_count());
        let all: std::vec::Vec<u16> = (0..od.object_count()).map(|n| od.object(n).unwrap().index).collect();
        assert!(all.windows(2).all(|w| w[0] < w[1]), "{all:X?}");
        assert!(gone.iter().all(|i| !all.contains(i)), "{all:X?}");
        assert!(all.contains(&0x1017) && all.contains(&0x1F80));
    }
}
