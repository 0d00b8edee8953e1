//! The communication profile's objects as data: which sub-indices each object of 1000h–1FFFh has, their
//! data type and access, and the [`Slot`] that names where the value lives (and so which rule checks a
//! write). [`find`] walks it for every SDO access; `CommProfile` (`dict`) reads and writes a slot with one
//! `match` on the slot number, so an object costs a few bytes of table instead of an arm in each of
//! `meta`, `value` and `set`.
//!
//! Lookup (OD-16: unknown index 0602 0000h, unknown sub-index 0609 0011h): 1000h–101Fh index a 32-entry
//! array directly, the PDO ranges 1400h–1BFFh are computed from the index (PDO-02: PDO `k` at base + k),
//! 1F80h is the one object above; the object's runs of sub-indices are then scanned (at most 6).
//!
//! A device that leaves an object out (a Cargo feature) puts `#[cfg(feature = "...")]` on its rows and on
//! its entry in [`FIXED`]; the test `meta_agrees_with_desc` (dict.rs) checks the table against the EDS
//! descriptions of every index and sub-index.

use crate::emcy::HISTORY;
use crate::od::{AbortCode, Access, DataType, PdoMapping};
use crate::pdo::mapping::MAX_ENTRIES;

/// Where a sub-entry's value lives; [`Slot::Count`] is the "highest sub-index supported" of its object
/// (OD-04), computed from the table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Slot {
    Count,
    DeviceType,
    ErrorRegister,
    History,
    SyncCob,
    SyncPeriod,
    SyncWindow,
    DeviceName,
    HardwareVersion,
    SoftwareVersion,
    GuardTime,
    LifeTimeFactor,
    Store,
    Restore,
    TimeCob,
    EmcyCob,
    EmcyInhibit,
    Consumer,
    HeartbeatTime,
    Identity,
    SyncOverflow,
    ErrorBehaviour,
    NmtStartup,
    PdoCob,
    PdoType,
    PdoInhibit,
    PdoEventTimer,
    PdoSyncStart,
    MapCount,
    MapEntry,
}

/// Data type and access of a run of sub-entries (the profile uses these seven).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Ty {
    U8Const,
    U8Ro,
    U8Rw,
    U16Rw,
    U32Ro,
    U32Rw,
    StrConst,
}

impl Ty {
    /// The data type and access it stands for.
    pub(super) const fn parts(self) -> (DataType, Access) {
        match self {
            Ty::U8Const => (DataType::Unsigned8, Access::Const),
            Ty::U8Ro => (DataType::Unsigned8, Access::Ro),
            Ty::U8Rw => (DataType::Unsigned8, Access::Rw),
            Ty::U16Rw => (DataType::Unsigned16, Access::Rw),
            Ty::U32Ro => (DataType::Unsigned32, Access::Ro),
            Ty::U32Rw => (DataType::Unsigned32, Access::Rw),
            Ty::StrConst => (DataType::VisibleString, Access::Const),
        }
    }

    /// Whether SDO may write it.
    pub(super) const fn writable(self) -> bool {
        matches!(self, Ty::U8Rw | Ty::U16Rw | Ty::U32Rw)
    }

    /// The encoded size of a numeric entry (1, 2 or 4), 0 for a string.
    pub(super) const fn size(self) -> usize {
        match self {
            Ty::U8Const | Ty::U8Ro | Ty::U8Rw => 1,
            Ty::U16Rw => 2,
            Ty::U32Ro | Ty::U32Rw => 4,
            Ty::StrConst => 0,
        }
    }
}

/// Sub-indices `first..=last` of one object: type, access and value slot. `last == HB` stands for the
/// node's number of heartbeat consumers (1016h). An object's count run (sub 00h) comes first, its highest
/// sub-index last.
#[derive(Debug, Clone, Copy)]
struct Run {
    first: u8,
    last: u8,
    ty: Ty,
    slot: Slot,
}

const HB: u8 = 0xFF;

const fn run(first: u8, last: u8, ty: Ty, slot: Slot) -> Run {
    Run { first, last, ty, slot }
}

const fn var(ty: Ty, slot: Slot) -> Run {
    run(0, 0, ty, slot)
}

/// Sub 00h of an ARRAY/RECORD: the highest sub-index, the `last` of the object's final run.
const fn count() -> Run {
    var(Ty::U8Const, Slot::Count)
}

/// Every run, object by object; [`FIXED`] and the PDO constants point into it.
const RUNS: [Run; 36] = [
    var(Ty::U32Ro, Slot::DeviceType),                     // 0: 1000h
    var(Ty::U8Ro, Slot::ErrorRegister),                   // 1: 1001h
    var(Ty::U8Rw, Slot::History),                         // 2: 1003h sub 00h
    run(1, HISTORY as u8, Ty::U32Ro, Slot::History),      // 3
    var(Ty::U32Rw, Slot::SyncCob),                        // 4: 1005h
    var(Ty::U32Rw, Slot::SyncPeriod),                     // 5: 1006h
    var(Ty::U32Rw, Slot::SyncWindow),                     // 6: 1007h
    var(Ty::StrConst, Slot::DeviceName),                  // 7: 1008h
    var(Ty::StrConst, Slot::HardwareVersion),             // 8: 1009h
    var(Ty::StrConst, Slot::SoftwareVersion),             // 9: 100Ah
    var(Ty::U16Rw, Slot::GuardTime),                      // 10: 100Ch
    var(Ty::U8Rw, Slot::LifeTimeFactor),                  // 11: 100Dh
    count(),                                              // 12: 1010h
    run(1, 3, Ty::U32Rw, Slot::Store),                    // 13
    count(),                                              // 14: 1011h
    run(1, 3, Ty::U32Rw, Slot::Restore),                  // 15
    var(Ty::U32Rw, Slot::TimeCob),                        // 16: 1012h
    var(Ty::U32Rw, Slot::EmcyCob),                        // 17: 1014h
    var(Ty::U16Rw, Slot::EmcyInhibit),                    // 18: 1015h
    count(),                                              // 19: 1016h
    run(1, HB, Ty::U32Rw, Slot::Consumer),                // 20
    var(Ty::U16Rw, Slot::HeartbeatTime),                  // 21: 1017h
    count(),                                              // 22: 1018h
    run(1, 4, Ty::U32Ro, Slot::Identity),                 // 23
    var(Ty::U8Rw, Slot::SyncOverflow),                    // 24: 1019h
    count(),                                              // 25: 1029h
    run(1, 1, Ty::U8Rw, Slot::ErrorBehaviour),            // 26
    var(Ty::U32Rw, Slot::NmtStartup),                     // 27: 1F80h
    count(),                                              // 28: PDO communication (PDO-06..18)
    run(1, 1, Ty::U32Rw, Slot::PdoCob),                   // 29
    run(2, 2, Ty::U8Rw, Slot::PdoType),                   // 30
    run(3, 3, Ty::U16Rw, Slot::PdoInhibit),               // 31
    run(5, 5, Ty::U16Rw, Slot::PdoEventTimer),            // 32: RPDO: 28..33
    run(6, 6, Ty::U8Rw, Slot::PdoSyncStart),              // 33: TPDO: 28..34
    var(Ty::U8Rw, Slot::MapCount),                        // 34: mapping (PDO-30..37)
    run(1, MAX_ENTRIES as u8, Ty::U32Rw, Slot::MapEntry), // 35
];

/// 1000h–101Fh: (first run, number of runs) of each index; 0 runs = no such object.
const FIXED: [(u8, u8); 32] = {
    let mut t = [(0u8, 0u8); 32];
    t[0x00] = (0, 1);
    t[0x01] = (1, 1);
    t[0x03] = (2, 2);
    t[0x05] = (4, 1);
    t[0x06] = (5, 1);
    t[0x07] = (6, 1);
    t[0x08] = (7, 1);
    t[0x09] = (8, 1);
    t[0x0A] = (9, 1);
    t[0x0C] = (10, 1);
    t[0x0D] = (11, 1);
    t[0x10] = (12, 2);
    t[0x11] = (14, 2);
    t[0x12] = (16, 1);
    t[0x14] = (17, 1);
    t[0x15] = (18, 1);
    t[0x16] = (19, 2);
    t[0x17] = (21, 1);
    t[0x18] = (22, 2);
    t[0x19] = (24, 1);
    t
};

/// The capacities the table depends on (from `ProfileSizes`), passed by value so [`find`] is not generic.
#[derive(Debug, Clone, Copy)]
pub(super) struct Counts {
    /// Heartbeat consumer entries (1016h; no 1016h when 0).
    pub hb: u8,
    /// RPDOs.
    pub rpdo: usize,
    /// TPDOs.
    pub tpdo: usize,
}

/// One sub-entry found in the table (4 bytes: returned in registers).
#[derive(Debug, Clone, Copy)]
pub(super) struct Found {
    /// Data type and access.
    pub ty: Ty,
    /// Where the value lives.
    pub slot: Slot,
    /// For [`Slot::Count`]: the highest sub-index; for the PDO slots: the PDO number `k` (0-based), plus
    /// [`TX`] for a TPDO object (1800h/1A00h range).
    pub n: u16,
}

/// The bit of [`Found::n`] that marks a TPDO object.
const TX: u16 = 0x8000;

impl Found {
    /// A TPDO object (1800h/1A00h range).
    pub(super) const fn tx(&self) -> bool {
        self.n & TX != 0
    }

    /// The PDO number `k` of a PDO slot.
    pub(super) const fn k(&self) -> usize {
        (self.n & !TX) as usize
    }

    /// Data type, access and PDO mapping (only 1001h is mappable: TPDO, ERR-01).
    pub(super) const fn meta(&self) -> (DataType, Access, PdoMapping) {
        let (dt, access) = self.ty.parts();
        let pdo = if matches!(self.slot, Slot::ErrorRegister) { PdoMapping::Tpdo } else { PdoMapping::No };
        (dt, access, pdo)
    }
}

/// The runs of object `index` and the PDO number (0 for the others; with [`TX`] for a TPDO object).
fn object(index: u16, c: Counts) -> Option<(&'static [Run], u16)> {
    let (first, n) = match index {
        0x1000..=0x101F => FIXED[usize::from(index & 0x1F)],
        0x1029 => (25, 2),
        0x1F80 => (27, 1),
        0x1400..=0x1BFF => {
            // PDO-02: PDO k at base + k; the runs of a communication or mapping record.
            let (k, tx) = (index & 0x1FF, index >= 0x1800);
            if usize::from(k) >= if tx { c.tpdo } else { c.rpdo } {
                return None;
            }
            let runs = match (index & 0x200 != 0, tx) {
                (true, _) => &RUNS[34..36],
                (false, false) => &RUNS[28..33],
                (false, true) => &RUNS[28..34],
            };
            return Some((runs, if tx { k | TX } else { k }));
        }
        _ => return None,
    };
    if n == 0 || (index == 0x1016 && c.hb == 0) {
        return None;
    }
    Some((RUNS.get(usize::from(first)..usize::from(first) + usize::from(n))?, 0))
}

/// The sub-entry `(index, sub)` of the communication profile, or the OD-16 abort code.
pub(super) fn find(index: u16, sub: u8, c: Counts) -> Result<Found, AbortCode> {
    let (runs, k) = object(index, c).ok_or(AbortCode::ObjectDoesNotExist)?;
    let last = |r: &Run| if r.last == HB { c.hb } else { r.last };
    for r in runs {
        if sub >= r.first && sub <= last(r) {
            // A count (sub 00h) is the highest sub-index: the `last` of the object's final run.
            let n = if matches!(r.slot, Slot::Count) { runs.last().map_or(0, |f| last(f).into()) } else { k };
            return Ok(Found { ty: r.ty, slot: r.slot, n });
        }
    }
    Err(AbortCode::SubIndexDoesNotExist)
}
