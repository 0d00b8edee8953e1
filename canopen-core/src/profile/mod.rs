//! Communication-profile values (1000h–1FFFh) and the node configuration they start from.
//!
//! [`NodeConfig`] is the device's fixed description (identity, names, defaults); [`CommParams`] holds the
//! run-time values of the communication objects that the services read. NMT reset communication sets
//! [`CommParams`] back to its power-on values (NMT-05, NMT-06), and store/restore (1010h/1011h) saves and
//! loads it. [`CommProfile`] (`dict`) is the object-dictionary view over these values (SDO access to
//! 1000h–1FFFh; which objects exist and where their values live is a const table, `table`) and [`eds`]
//! writes the profile's part of the EDS; the rules that belong to a value rather
//! than to its encoding are enforced by the setters here.
//!
//! Layer: the profile sits above the services (it is built from their parameter types: [`PdoComm`],
//! [`SyncParams`], [`ConsumerEntry`], [`Identity`], the EMCY error state) and below the node.
//!
//! Implemented here: HB-01 (1017h), HB-06..HB-09 (1016h entries, duplicate node → 0604 0043h), GUARD-02/03
//! (100Ch, 100Dh), DEV-01/DEV-03/DEV-04 (1000h, 1018h, 1008h–100Ah as configuration).

mod dict;
pub mod eds;
pub mod optional;
mod table;

pub use crate::heartbeat::ConsumerEntry;
pub use crate::lss::Identity;
pub(crate) use dict::SIZE_NOT_INDICATED;
#[cfg(feature = "store-restore")]
pub(crate) use dict::STORE_GO_AHEAD;
pub use dict::{CommProfile, Unchecked};

use crate::abort::AbortCode;
use crate::heartbeat::ConsumerSizes;
use crate::pdo::{mapping::MAX_ENTRIES, PdoComm, PdoDefault, PdoMapParams};
use crate::sizes::{Sizes, Slots};
use crate::sync::SyncParams;

/// The fixed description of a node and the defaults of its communication parameters.
///
/// ```
/// use canopen_core::profile::NodeConfig;
/// const CFG: NodeConfig = NodeConfig { heartbeat_time_ms: 1000, ..NodeConfig::DEFAULT };
/// assert_eq!(CFG.heartbeat_time_ms, 1000);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct NodeConfig {
    /// 1000h device type (DEV-01).
    pub device_type: u32,
    /// 1018h identity (DEV-03).
    pub identity: Identity,
    /// 1008h manufacturer device name (DEV-04).
    pub device_name: &'static str,
    /// 1009h manufacturer hardware version (DEV-04).
    pub hardware_version: &'static str,
    /// 100Ah manufacturer software version (DEV-04).
    pub software_version: &'static str,
    /// Default 1017h producer heartbeat time in ms (HB-01; 0 = off).
    pub heartbeat_time_ms: u16,
    /// Default 100Ch guard time in ms (GUARD-02; 0 = off).
    pub guard_time_ms: u16,
    /// Default 100Dh life time factor (GUARD-03; 0 = off).
    pub life_time_factor: u8,
    /// Default SYNC parameters 1005h, 1006h, 1007h, 1019h.
    pub sync: SyncParams,
    /// Default 1012h COB-ID TIME (bit 31 consume, bit 30 produce; TIME-01/02).
    pub time_cob_id: u32,
    /// Default 1015h EMCY inhibit time, 100 µs (EMCY-09).
    pub emcy_inhibit_100us: u16,
    /// Default 1029h sub 01h, the reaction to a communication error (ERR-10/11: 0 Pre-operational, 1 no
    /// change, 2 Stopped).
    pub error_behaviour: u8,
    /// Default 1F80h NMT startup (CiA 302-2). Only bit 2 is evaluated: 0 = enter Operational by itself after
    /// boot-up (NMT-17, NMT-27).
    pub nmt_startup: u32,
    /// Defaults of RPDO 1..n (1400h+k, 1600h+k); PDOs beyond the slice use [`PdoDefault::UNUSED`].
    pub rpdo: &'static [PdoDefault],
    /// Defaults of TPDO 1..n (1800h+k, 1A00h+k).
    pub tpdo: &'static [PdoDefault],
}

impl NodeConfig {
    /// A neutral configuration: no profile, no error control enabled, empty names.
    pub const DEFAULT: NodeConfig = NodeConfig {
        device_type: 0,
        identity: Identity { vendor_id: 0, product_code: 0, revision: 0, serial: 0 },
        device_name: "",
        hardware_version: "",
        software_version: "",
        heartbeat_time_ms: 0,
        guard_time_ms: 0,
        life_time_factor: 0,
        sync: SyncParams::DEFAULT,
        time_cob_id: 0x8000_0100,
        emcy_inhibit_100us: 0,
        error_behaviour: 0,
        nmt_startup: 0x0000_0004,
        rpdo: &[],
        tpdo: &[],
    };

    /// The default of RPDO `k` (0-based).
    pub const fn rpdo_default(&self, k: usize) -> PdoDefault {
        if k < self.rpdo.len() {
            self.rpdo[k]
        } else {
            PdoDefault::UNUSED
        }
    }

    /// The default of TPDO `k` (0-based).
    pub const fn tpdo_default(&self, k: usize) -> PdoDefault {
        if k < self.tpdo.len() {
            self.tpdo[k]
        } else {
            PdoDefault::UNUSED
        }
    }
}

impl Default for NodeConfig {
    fn default() -> Self {
        NodeConfig::DEFAULT
    }
}

/// How many PDOs the communication profile holds, as its storage types (see [`crate::sizes`]); implemented
/// for [`Sizes`].
///
/// ```
/// use canopen_core::{profile::ProfileSizes, Sizes};
/// assert_eq!(<Sizes<0, 8, 8, 2, 1> as ProfileSizes>::RPDO, 2);
/// ```
pub trait ProfileSizes: ConsumerSizes {
    /// The number of receive PDOs.
    const RPDO: usize;
    /// The number of transmit PDOs.
    const TPDO: usize;
    /// `[PdoComm; RPDO]`.
    type RpdoComm: Slots<PdoComm> + Copy + core::fmt::Debug + PartialEq + Eq;
    /// `[PdoMapParams; RPDO]`.
    type RpdoMap: Slots<PdoMapParams> + Copy + core::fmt::Debug + PartialEq + Eq;
    /// `[PdoComm; TPDO]`.
    type TpdoComm: Slots<PdoComm> + Copy + core::fmt::Debug + PartialEq + Eq;
    /// `[PdoMapParams; TPDO]`.
    type TpdoMap: Slots<PdoMapParams> + Copy + core::fmt::Debug + PartialEq + Eq;
    /// Every RPDO communication parameter zero (filled in by [`CommParams::for_node`]).
    const RPDO_COMM: Self::RpdoComm;
    /// Every RPDO mapping empty.
    const RPDO_MAP: Self::RpdoMap;
    /// Every TPDO communication parameter zero.
    const TPDO_COMM: Self::TpdoComm;
    /// Every TPDO mapping empty.
    const TPDO_MAP: Self::TpdoMap;
}

const NO_COMM: PdoComm =
    PdoComm { cob_id: 0, transmission_type: 0, inhibit_100us: 0, event_timer_ms: 0, sync_start: 0 };
const NO_MAP: PdoMapParams = PdoMapParams { count: 0, entries: [0; crate::pdo::mapping::MAX_ENTRIES] };

impl<const HB: usize, const TXQ: usize, const EVQ: usize, const RPDO: usize, const TPDO: usize> ProfileSizes
    for Sizes<HB, TXQ, EVQ, RPDO, TPDO>
{
    const RPDO: usize = RPDO;
    const TPDO: usize = TPDO;
    type RpdoComm = [PdoComm; RPDO];
    type RpdoMap = [PdoMapParams; RPDO];
    type TpdoComm = [PdoComm; TPDO];
    type TpdoMap = [PdoMapParams; TPDO];
    const RPDO_COMM: [PdoComm; RPDO] = [NO_COMM; RPDO];
    const RPDO_MAP: [PdoMapParams; RPDO] = [NO_MAP; RPDO];
    const TPDO_COMM: [PdoComm; TPDO] = [NO_COMM; TPDO];
    const TPDO_MAP: [PdoMapParams; TPDO] = [NO_MAP; TPDO];
}

/// Run-time values of the communication objects, for a node with the capacities `Z` (`Z::HB` heartbeat
/// consumer entries, `Z::RPDO` receive and `Z::TPDO` transmit PDOs; see [`Sizes`]).
///
/// ```
/// use canopen_core::{profile::{CommParams, NodeConfig}, Sizes};
/// let mut p: CommParams<Sizes<4>> = CommParams::new(&NodeConfig::DEFAULT);
/// p.set_consumer(1, 0x0002_0064).unwrap();
/// assert!(p.set_consumer(2, 0x0002_00C8).is_err()); // node 2 monitored twice (HB-09)
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CommParams<Z: ProfileSizes = Sizes> {
    /// 1017h producer heartbeat time, ms (HB-01).
    pub heartbeat_time_ms: u16,
    /// 1016h:01..HB raw consumer entries (HB-06, HB-07).
    pub heartbeat_consumers: Z::ConsumerTimes,
    /// 100Ch guard time, ms (GUARD-02).
    pub guard_time_ms: u16,
    /// 100Dh life time factor (GUARD-03).
    pub life_time_factor: u8,
    /// 1001h error register bits beyond those of the active errors (ERR-01/ERR-02; ro on SDO): 1001h reads
    /// this OR-ed with the register of the active errors ([`crate::emcy::NodeErrors`]), which the EMCY/error handling
    /// keeps. A node leaves it 0 (reset communication clears it); a `CommProfile` used without a node may
    /// set it.
    pub error_register: u8,
    /// 1005h, 1006h, 1007h, 1019h.
    pub sync: SyncParams,
    /// 1012h COB-ID TIME.
    pub time_cob_id: u32,
    /// 1014h COB-ID EMCY (EMCY-02: default 80h + node).
    pub emcy_cob_id: u32,
    /// 1015h inhibit time EMCY, 100 µs.
    pub emcy_inhibit_100us: u16,
    /// 1029h sub 01h communication error behaviour.
    pub error_behaviour: u8,
    /// 1F80h NMT startup.
    pub nmt_startup: u32,
    /// 1400h+k RPDO communication parameters.
    pub rpdo_comm: Z::RpdoComm,
    /// 1600h+k RPDO mapping.
    pub rpdo_map: Z::RpdoMap,
    /// 1800h+k TPDO communication parameters.
    pub tpdo_comm: Z::TpdoComm,
    /// 1A00h+k TPDO mapping.
    pub tpdo_map: Z::TpdoMap,
}

impl<Z: ProfileSizes> CommParams<Z> {
    /// The power-on defaults of `config` (nothing stored) for node-ID 0 (node-ID-relative defaults such as
    /// the PDO COB-IDs are then relative to 0; a node uses [`for_node`](Self::for_node)).
    pub fn new(config: &NodeConfig) -> Self {
        Self::for_node(config, 0)
    }

    /// The power-on defaults of `config` for `node_id` (COB-04/05/06, COB-10). Not a `const fn` (it fills
    /// the PDO tables through `Z`'s storage types); a `static` node is built at run time (`StaticCell`).
    ///
    /// ```
    /// use canopen_core::{profile::{CommParams, NodeConfig}, Sizes};
    /// let p: CommParams<Sizes<0, 16, 16, 4, 4>> = CommParams::for_node(&NodeConfig::DEFAULT, 5);
    /// assert_eq!(p.emcy_cob_id, 0x85);
    /// assert_eq!(p.rpdo_comm[1].cob_id, 0x8000_0305); // no default mapping: not valid
    /// ```
    pub fn for_node(config: &NodeConfig, node_id: u8) -> Self {
        let mut p: Self = CommParams {
            heartbeat_time_ms: 0,
            heartbeat_consumers: Z::ZERO_TIMES,
            guard_time_ms: 0,
            life_time_factor: 0,
            error_register: 0,
            sync: SyncParams::DEFAULT,
            time_cob_id: 0,
            emcy_cob_id: 0,
            emcy_inhibit_100us: 0,
            error_behaviour: 0,
            nmt_startup: 0,
            rpdo_comm: Z::RPDO_COMM,
            rpdo_map: Z::RPDO_MAP,
            tpdo_comm: Z::TPDO_COMM,
            tpdo_map: Z::TPDO_MAP,
        };
        p.set_defaults(config, node_id);
        p
    }

    /// Every value back to its power-on default of `config` for `node_id` except the error register (which
    /// belongs to the error handling): NMT reset communication (NMT-05). In place: no 440-byte copy.
    pub(crate) fn set_defaults(&mut self, config: &NodeConfig, node_id: u8) {
        self.heartbeat_time_ms = config.heartbeat_time_ms;
        self.heartbeat_consumers = Z::ZERO_TIMES;
        self.guard_time_ms = config.guard_time_ms;
        self.life_time_factor = config.life_time_factor;
        self.sync = config.sync.supported();
        self.time_cob_id = config.time_cob_id;
        self.emcy_cob_id = 0x80 + node_id as u32;
        // Without their objects (features `emcy-inhibit`, `error-behaviour`) these stay at the default, 0.
        self.emcy_inhibit_100us = if crate::emcy::INHIBIT { config.emcy_inhibit_100us } else { 0 };
        self.error_behaviour = if cfg!(feature = "error-behaviour") { config.error_behaviour } else { 0 };
        self.nmt_startup = config.nmt_startup;
        pdo_defaults(self.rpdo_comm.as_mut(), self.rpdo_map.as_mut(), config.rpdo, 0x200, node_id);
        pdo_defaults(self.tpdo_comm.as_mut(), self.tpdo_map.as_mut(), config.tpdo, 0x180, node_id);
    }

    /// The decoded consumer entry at 1016h sub-index `sub` (1-based), if it exists.
    ///
    /// ```
    /// # use canopen_core::{profile::{CommParams, NodeConfig}, Sizes};
    /// let p: CommParams<Sizes<2>> = CommParams::new(&NodeConfig::DEFAULT);
    /// assert!(p.consumer(1).is_some());
    /// assert!(p.consumer(3).is_none());
    /// ```
    pub fn consumer(&self, sub: u8) -> Option<ConsumerEntry> {
        let i = usize::from(sub).checked_sub(1)?;
        self.heartbeat_consumers.as_ref().get(i).map(|&raw| ConsumerEntry::from_raw(raw))
    }

    /// Writes 1016h sub-index `sub`: refuses a missing sub-index (0609 0011h) and a second active entry for
    /// a node-ID that another active entry already monitors (HB-09, 0604 0043h).
    ///
    /// ```
    /// # use canopen_core::{profile::{CommParams, NodeConfig}, od::AbortCode, Sizes};
    /// let mut p: CommParams<Sizes<2>> = CommParams::new(&NodeConfig::DEFAULT);
    /// assert_eq!(p.set_consumer(3, 0), Err(AbortCode::SubIndexDoesNotExist));
    /// ```
    pub fn set_consumer(&mut self, sub: u8, raw: u32) -> Result<(), AbortCode> {
        let i = usize::from(sub).checked_sub(1).filter(|&i| i < Z::HB).ok_or(AbortCode::SubIndexDoesNotExist)?;
        self.set_consumer_at(i, raw)
    }

    /// [`set_consumer`](Self::set_consumer) of entry `i` (0-based, below `Z::HB`: the profile's dictionary,
    /// whose table has only those sub-indices, calls it without the sub-index test).
    pub(crate) fn set_consumer_at(&mut self, i: usize, raw: u32) -> Result<(), AbortCode> {
        let new = ConsumerEntry::from_raw(raw);
        if new.is_active() {
            let duplicate = self.heartbeat_consumers.as_ref().iter().enumerate().any(|(j, &other)| {
                j != i
                    && ConsumerEntry::from_raw(other).is_active()
                    && ConsumerEntry::from_raw(other).node_id == new.node_id
            });
            if duplicate {
                return Err(AbortCode::ParameterIncompatibility);
            }
        }
        if let Some(entry) = self.heartbeat_consumers.as_mut().get_mut(i) {
            *entry = raw;
        }
        Ok(())
    }
}

/// Fills the communication and mapping parameters of every PDO of one direction (`base` 200h: RPDO,
/// 180h: TPDO) from its default, [`PdoDefault::UNUSED`] beyond `defaults`. Not generic: one copy for both
/// directions and every `Z`.
fn pdo_defaults(comm: &mut [PdoComm], map: &mut [PdoMapParams], defaults: &[PdoDefault], base: u16, node_id: u8) {
    for (k, (c, m)) in comm.iter_mut().zip(map).enumerate() {
        let d = defaults.get(k).unwrap_or(&PdoDefault::UNUSED);
        *c = d.params(k, base, node_id).0;
        // The mapping written in place (`PdoMapParams::from_slice` in place): through `params`' tuple it went
        // via three copies on the stack.
        let raw = d.mapping.get(..MAX_ENTRIES).unwrap_or(d.mapping);
        m.entries = [0; MAX_ENTRIES];
        if let Some(dst) = m.entries.get_mut(..raw.len()) {
            dst.copy_from_slice(raw);
        }
        m.count = match d.count {
            Some(c) if usize::from(c) < raw.len() || crate::pdo::is_mpdo_count(c) => c,
            _ => raw.len() as u8,
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The power-on mappings (PDO-30..33) are the defaults' entries, as `PdoMapParams::from_slice` reads them:
    /// none, one, eight, and a ninth entry kept only up to [`MAX_ENTRIES`] (left out unless the feature
    /// `pdo-mapping-64` is on); PDOs past the defaults are empty.
    #[test]
    fn for_node_fills_the_default_mappings() {
        const NINE: [u32; 9] = [
            0x6000_0108,
            0x6001_0108,
            0x6002_0108,
            0x6003_0108,
            0x6004_0108,
            0x6005_0108,
            0x6006_0108,
            0x6007_0108,
            0x6008_0108,
        ];
        const EIGHT: [u32; 8] =
            [0x6000_0108, 0x6001_0108, 0x6002_0108, 0x6003_0108, 0x6004_0108, 0x6005_0108, 0x6006_0108, 0x6007_0108];
        static RPDO: [PdoDefault; 4] = [
            PdoDefault { mapping: &[], ..PdoDefault::EVENT },
            PdoDefault { mapping: &[0x6200_0108], ..PdoDefault::EVENT },
            PdoDefault { mapping: &EIGHT, ..PdoDefault::EVENT },
            // Entries prepared, none mapped (an EDS whose count has no DefaultValue: e35.eds's 1600h).
            PdoDefault { mapping: &[0x6200_0108, 0x6201_0108], count: Some(0), ..PdoDefault::EVENT },
        ];
        static TPDO: [PdoDefault; 1] = [PdoDefault { mapping: &NINE, ..PdoDefault::EVENT }];
        let cfg = NodeConfig { rpdo: &RPDO, tpdo: &TPDO, ..NodeConfig::DEFAULT };
        let p: CommParams<Sizes<0, 8, 8, 4, 2>> = CommParams::for_node(&cfg, 5);
        for (k, m) in p.rpdo_map.iter().enumerate() {
            assert_eq!(*m, cfg.rpdo_default(k).map_params(), "RPDO {k}");
        }
        assert_eq!((p.rpdo_map[2].count, p.rpdo_map[3].count), (8, 0));
        assert_eq!(p.rpdo_map[3].entries[..3], [0x6200_0108, 0x6201_0108, 0]);
        assert_eq!(p.tpdo_map[0], PdoMapParams::from_slice(&NINE[..MAX_ENTRIES.min(9)]));
        assert_eq!(p.tpdo_map[0].count, if MAX_ENTRIES == 8 { 8 } else { 9 });
        assert_eq!(p.tpdo_map[1], PdoMapParams::from_slice(&[]));
        assert_eq!(p.rpdo_comm[1], cfg.rpdo_default(1).params(1, 0x200, 5).0);
    }

    /// NMT-05: reset communication sets every communication value back to its power-on default, in place,
    /// and keeps only the error register (the error handling's).
    #[test]
    fn set_defaults_is_for_node_but_the_error_register() {
        static TPDO: [PdoDefault; 1] =
            [PdoDefault { event_timer_ms: 100, mapping: &[0x1001_0008], ..PdoDefault::EVENT }];
        let cfg = NodeConfig {
            heartbeat_time_ms: 100,
            guard_time_ms: 50,
            life_time_factor: 3,
            emcy_inhibit_100us: 10,
            error_behaviour: 1,
            tpdo: &TPDO,
            ..NodeConfig::DEFAULT
        };
        let fresh: CommParams<Sizes<2, 8, 8, 2, 2>> = CommParams::for_node(&cfg, 5);
        let mut p = fresh.clone();
        p.heartbeat_time_ms = 1;
        p.heartbeat_consumers[0] = 0x0002_0064;
        (p.guard_time_ms, p.life_time_factor, p.error_register) = (9, 9, 0x11);
        (p.sync.period_us, p.sync.window_us, p.sync.counter_overflow) = (7, 7, 7);
        (p.time_cob_id, p.emcy_cob_id, p.emcy_inhibit_100us) = (1, 1, 1);
        (p.error_behaviour, p.nmt_startup) = (2, 0);
        (p.rpdo_comm[0].cob_id, p.rpdo_map[0].count, p.rpdo_map[1].entries[7]) = (1, 1, 1);
        (p.tpdo_comm[0].transmission_type, p.tpdo_map[0].count, p.tpdo_map[0].entries[0]) = (3, 0, 1);
        p.set_defaults(&cfg, 5);
        assert_eq!(p.error_register, 0x11);
        p.error_register = 0;
        assert_eq!(p, fresh);
    }

    /// 1016h entries 0002 0064h (node 2, 100 ms), 0003 0190h (node 3, 400 ms), 0007 0FA0h (node 7, 4000 ms);
    /// node 2 in a second entry refused with 0604 0043h; an entry disabled by 0.
    #[test]
    fn consumer_entries_vectors() {
        let mut p: CommParams<Sizes<4>> = CommParams::new(&NodeConfig::DEFAULT);
        assert_eq!(
            ConsumerEntry::from_raw(u32::from_le_bytes([0x64, 0, 2, 0])),
            ConsumerEntry { node_id: 2, time_ms: 100 }
        );
        assert_eq!(p.set_consumer(1, 0x0002_0064), Ok(()));
        assert_eq!(p.set_consumer(2, 0x0003_0190), Ok(()));
        assert_eq!(p.set_consumer(3, 0x0007_0FA0), Ok(()));
        // HB-09: node 2 again.
        assert_eq!(p.set_consumer(4, 0x0002_00C8), Err(AbortCode::ParameterIncompatibility));
        assert_eq!(p.heartbeat_consumers[3], 0);
        // Rewriting the same entry with a new time is not a duplicate.
        assert_eq!(p.set_consumer(1, 0x0002_00C8), Ok(()));
        // Disable entry 1; then node 2 may go elsewhere.
        assert_eq!(p.set_consumer(1, 0), Ok(()));
        assert_eq!(p.set_consumer(4, 0x0002_00C8), Ok(()));
        // An inactive duplicate (time 0) is accepted (HB-08).
        assert_eq!(p.set_consumer(1, 0x0002_0000), Ok(()));
        assert_eq!(p.set_consumer(0, 0), Err(AbortCode::SubIndexDoesNotExist));
        assert_eq!(p.set_consumer(5, 0), Err(AbortCode::SubIndexDoesNotExist));
    }
}
