//! Process data objects (PDO-01..PDO-40): communication and mapping parameters, the RPDO and TPDO
//! state machines, and the resolved mappings that move process data without searching the dictionary.
//!
//! - [`PdoComm`] / [`PdoMapParams`] are the values of 1400h–15FFh / 1800h–19FFh and 1600h–17FFh /
//!   1A00h–1BFFh, kept in [`CommParams`](crate::profile::CommParams) and served through the
//!   [`CommProfile`](crate::profile::CommProfile) with the spec's change rules;
//! - [`PdoDefault`] is how a [`NodeConfig`](crate::profile::NodeConfig) gives each PDO its defaults;
//! - [`rpdo::Rpdo`] / [`tpdo::Tpdo`] are the run-time state machines the `Node` drives;
//! - [`mapping`] resolves and packs mappings.
//!
//! MPDO (MPDO-01..05, optional) is the Cargo feature `mpdo` ([`mpdo`]). A mapping holds at most [`mapping::MAX_ENTRIES`] entries:
//! 8, or the 64 of CiA 301 (PDO-30) with the Cargo feature `pdo-mapping-64` (off by default: RAM, see there).
//!
//! Remote requests of TPDOs (PDO-29: "the PDO read service is optional"; PDO-21/22: the RTR-only types FCh
//! and FDh) are the Cargo feature `pdo-rtr` (on by default). Without it no TPDO answers a remote frame: a
//! TPDO's COB-ID has bit 30 set (no RTR allowed) in its defaults and writing it clear is refused with
//! 0609 0030h, as are the transmission types FCh and FDh (PDO-18, [`tpdo_type_ok`]); the RTR path is not in
//! the build (about 140 B of Cortex-M flash).

pub mod mapping;
#[cfg(feature = "mpdo")]
pub mod mpdo;
pub mod rpdo;
pub mod tpdo;

use crate::cob::CobIdEntry;

/// Whether TPDOs answer remote requests in this build (the feature `pdo-rtr`, see the module docs).
pub const RTR: bool = cfg!(feature = "pdo-rtr");

/// The communication parameter record of one PDO (1400h+k / 1800h+k, PDO-06..PDO-26).
///
/// ```
/// use canopen_core::pdo::PdoComm;
/// let c = PdoComm { cob_id: 0x0000_0185, transmission_type: 254, inhibit_100us: 0, event_timer_ms: 0, sync_start: 0 };
/// assert!(c.is_valid());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PdoComm {
    /// Sub 01h COB-ID: bit 31 = 1 not valid, bit 30 (TPDO) = 1 no RTR allowed, bits 10–0 CAN-ID.
    pub cob_id: u32,
    /// Sub 02h transmission type.
    pub transmission_type: u8,
    /// Sub 03h inhibit time, 100 µs.
    pub inhibit_100us: u16,
    /// Sub 05h event timer, ms.
    pub event_timer_ms: u16,
    /// Sub 06h SYNC start value (TPDO only).
    pub sync_start: u8,
}

impl PdoComm {
    /// The COB-ID entry.
    pub const fn cob(&self) -> CobIdEntry {
        CobIdEntry::from_raw(self.cob_id)
    }

    /// Bit 31 clear: the PDO exists (PDO-07, PDO-15).
    pub const fn is_valid(&self) -> bool {
        !self.cob().bit31()
    }
}

/// The mapping parameter record of one PDO (1600h+k / 1A00h+k, PDO-30/31): raw entries and their count.
///
/// ```
/// use canopen_core::pdo::PdoMapParams;
/// let m = PdoMapParams::from_slice(&[0x6040_0010, 0x607A_0020]);
/// assert_eq!(m.active(), &[0x6040_0010, 0x607A_0020]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PdoMapParams {
    /// Sub 00h: number of valid entries.
    pub count: u8,
    /// Sub 01h..08h (01h..40h with the feature `pdo-mapping-64`).
    pub entries: [u32; mapping::MAX_ENTRIES],
}

/// No entries (the derive stops at arrays of 32).
impl Default for PdoMapParams {
    fn default() -> Self {
        Self::from_slice(&[])
    }
}

impl PdoMapParams {
    /// A mapping with `raw` entries (at most [`mapping::MAX_ENTRIES`] are kept).
    pub const fn from_slice(raw: &[u32]) -> Self {
        let mut entries = [0u32; mapping::MAX_ENTRIES];
        let mut i = 0;
        while i < raw.len() && i < mapping::MAX_ENTRIES {
            entries[i] = raw[i];
            i += 1;
        }
        PdoMapParams { count: i as u8, entries }
    }

    /// Entries 1..=count; none for an MPDO (count FEh/FFh, whose entries are not used, MPDO-05).
    pub fn active(&self) -> &[u32] {
        if is_mpdo_count(self.count) {
            return &[]; // a constant `false` without the feature: the build without MPDO is unchanged
        }
        // All of them for a count above MAX_ENTRIES (the same as the count clamped: one compare, no second exit).
        &self.entries[..usize::from(self.count).min(mapping::MAX_ENTRIES)]
    }
}

/// Whether mapping sub 00h value `count` makes the PDO an MPDO in this build (FEh SAM, FFh DAM; PDO-30,
/// MPDO-05): always `false` without the feature `mpdo`.
///
/// ```
/// use canopen_core::pdo::is_mpdo_count;
/// assert_eq!(is_mpdo_count(0xFF), cfg!(feature = "mpdo"));
/// assert!(!is_mpdo_count(8));
/// ```
pub const fn is_mpdo_count(count: u8) -> bool {
    cfg!(feature = "mpdo") && count >= 0xFE
}

/// The defaults of one PDO in a [`NodeConfig`](crate::profile::NodeConfig).
///
/// ```
/// use canopen_core::pdo::PdoDefault;
/// const TPDO1: PdoDefault = PdoDefault { mapping: &[0x6000_0108], ..PdoDefault::EVENT };
/// assert_eq!(TPDO1.transmission_type, 254);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PdoDefault {
    /// Whether the PDO starts valid (bit 31 = 0).
    pub valid: bool,
    /// The CAN-ID; `None` = the pre-defined connection set for PDOs 1–4 (COB-05/06), else 0 and invalid.
    pub can_id: Option<u16>,
    /// Default transmission type.
    pub transmission_type: u8,
    /// Default inhibit time, 100 µs.
    pub inhibit_100us: u16,
    /// Default event timer, ms.
    pub event_timer_ms: u16,
    /// Default SYNC start value (TPDO).
    pub sync_start: u8,
    /// Default mapping entries (raw UNSIGNED32, at most [`mapping::MAX_ENTRIES`]).
    pub mapping: &'static [u32],
    /// The most entries the mapping takes (sub-index 00h's `HighLimit`; an EDS's "0..4"): writing a larger
    /// count is refused with 0609 0031h. [`mapping::MAX_ENTRIES`] (the default) states no limit of its own.
    pub max_mapped: u8,
    /// The default entry count (sub-index 00h) when it is not all of `mapping`: `Some(0)` keeps the entries
    /// but maps none (an EDS whose count has no `DefaultValue`), at most `mapping.len()`. `None`: all.
    /// With the feature `mpdo`, `Some(0xFE)` / `Some(0xFF)` make the PDO a SAM- / DAM-MPDO (MPDO-05).
    pub count: Option<u8>,
    /// (TPDO) Whether a remote request is served: `false` sets COB-ID bit 30 (PDO-15, PDO-29). An RPDO's
    /// bit 30 is reserved (PDO-07): leave it `true`.
    pub rtr_allowed: bool,
}

impl PdoDefault {
    /// Valid, event-driven (FEh), pre-defined COB-ID, no mapping.
    pub const EVENT: PdoDefault = PdoDefault {
        valid: true,
        can_id: None,
        transmission_type: 254,
        inhibit_100us: 0,
        event_timer_ms: 0,
        sync_start: 0,
        mapping: &[],
        max_mapped: mapping::MAX_ENTRIES as u8,
        count: None,
        rtr_allowed: true,
    };
    /// Not valid, event-driven, pre-defined COB-ID, no mapping: a PDO without a configured default.
    pub const UNUSED: PdoDefault = PdoDefault { valid: false, ..Self::EVENT };

    /// The default parameters of PDO number `k` (0-based) for `node_id`; `base` is 180h (TPDO) or 200h (RPDO).
    /// A TPDO's COB-ID has bit 30 set (no RTR allowed) in a build without the feature `pdo-rtr`.
    ///
    /// ```
    /// use canopen_core::pdo::{self, PdoDefault};
    /// let (c, _) = PdoDefault::EVENT.params(2, 0x180, 5);
    /// assert_eq!(c.cob_id, if pdo::RTR { 0x385 } else { 0x4000_0385 }); // COB-05: TPDO3 = 380h + node
    /// let (c, _) = PdoDefault::UNUSED.params(4, 0x200, 5);
    /// assert_eq!(c.cob_id, 0x8000_0000); // PDO-08: beyond 4, no pre-defined ID, invalid
    /// let (c, _) = PdoDefault { rtr_allowed: false, ..PdoDefault::EVENT }.params(0, 0x180, 5);
    /// assert_eq!(c.cob_id, 0x4000_0185); // PDO-15: bit 30, no RTR allowed
    /// ```
    pub const fn params(&self, k: usize, base: u16, node_id: u8) -> (PdoComm, PdoMapParams) {
        let id = match self.can_id {
            Some(id) => id,
            None if k < 4 => base + 0x100 * k as u16 + node_id as u16,
            None => 0,
        };
        let valid = self.valid && id != 0;
        let mut cob_id = if valid { id as u32 } else { CobIdEntry::BIT31 | id as u32 };
        if !self.rtr_allowed || (!RTR && base == TPDO_BASE) {
            // No RTR allowed: the device's EDS says so, or this build serves none (PDO-15, PDO-29).
            cob_id |= CobIdEntry::BIT30;
        }
        let comm = PdoComm {
            cob_id,
            transmission_type: self.transmission_type,
            inhibit_100us: self.inhibit_100us,
            event_timer_ms: self.event_timer_ms,
            sync_start: self.sync_start,
        };
        (comm, self.map_params())
    }

    /// The default mapping parameters: `mapping`'s entries, `count` of them mapped (all by default).
    ///
    /// ```
    /// use canopen_core::pdo::PdoDefault;
    /// let d = PdoDefault { mapping: &[0x6000_0108, 0x6001_0108], count: Some(0), ..PdoDefault::EVENT };
    /// assert_eq!((d.map_params().count, d.map_params().entries[1]), (0, 0x6001_0108));
    /// ```
    pub const fn map_params(&self) -> PdoMapParams {
        let mut m = PdoMapParams::from_slice(self.mapping);
        if let Some(c) = self.count {
            if c < m.count || is_mpdo_count(c) {
                m.count = c;
            }
        }
        m
    }
}

/// The CAN-ID base of TPDO 1 in the pre-defined connection set (COB-05: 180h + node).
const TPDO_BASE: u16 = 0x180;

/// Bit 30 of a TPDO's COB-ID as this build can have it: without the feature `pdo-rtr` it must be set (no
/// RTR allowed), else 0609 0030h (PDO-15, PDO-29).
///
/// ```
/// use canopen_core::pdo;
/// assert_eq!(pdo::check_tpdo_rtr(0x4000_0181), Ok(()));
/// assert_eq!(pdo::check_tpdo_rtr(0x0000_0181).is_ok(), pdo::RTR);
/// ```
pub const fn check_tpdo_rtr(raw: u32) -> Result<(), crate::abort::AbortCode> {
    if !RTR && raw & CobIdEntry::BIT30 == 0 {
        return Err(crate::abort::AbortCode::InvalidValue);
    }
    Ok(())
}

/// RPDO transmission types (PDO-09): 00h–F0h synchronous, FEh/FFh event-driven.
///
/// ```
/// assert!(canopen_core::pdo::rpdo_type_ok(0xF0));
/// assert!(!canopen_core::pdo::rpdo_type_ok(0xFC)); // RPDO type FCh is reserved
/// ```
pub const fn rpdo_type_ok(t: u8) -> bool {
    t <= 240 || t >= 254
}

/// TPDO transmission types (PDO-18): 00h–F0h, FCh–FFh; without the feature `pdo-rtr` not the RTR-only FCh
/// and FDh.
///
/// ```
/// use canopen_core::pdo::{self, tpdo_type_ok};
/// assert_eq!(tpdo_type_ok(0xFC), pdo::RTR);
/// assert!(tpdo_type_ok(0xFE));
/// assert!(!tpdo_type_ok(0xF1));
/// ```
pub const fn tpdo_type_ok(t: u8) -> bool {
    if RTR {
        t <= 240 || t >= 252
    } else {
        t <= 240 || t >= 254
    }
}
