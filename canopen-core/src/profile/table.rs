//! The communication profile's objects as data: which sub-indices each object of 1000h–1FFFh has, their
//! data type and access, and the [`Slot`] that names where the value lives (and so which rule checks a
//! write). [`find`] walks it for every SDO access; `CommProfile` (`dict`) reads and writes a slot with one
//! `match` on the slot number, so an object costs a few bytes of table instead of an arm in each of
//! `meta`, `value` and `set`.
//!
//! The table is described by [`DESC`] (read at compile time only): each object's runs of sub-indices,
//! tagged with its index, one object's rows together. A device that leaves an object out (a Cargo feature)
//! puts `#[cfg(feature = "...")]` on its rows and nothing else changes here (its `desc` arm in dict.rs goes
//! too: the test `meta_agrees_with_desc` checks the table against the EDS descriptions of every index and
//! sub-index). The flash holds what is built from it at compile time: [`FIXED_VAR`], the type and slot of
//! each VAR of 1000h up to the highest VAR of 1000h–101Fh by index (2 bytes each), and [`ROWS`], the rows of
//! every other object (a VAR's row would be a second copy of its entry), 4 bytes each: the object as a
//! one-byte key ([`key_of`]), the last sub-index of the run (it starts after the previous row's) and its
//! type and slot. 6 bytes a row with the index and the first sub-index; the one gap, 1400h sub 04h, is a
//! row of its own.
//!
//! Lookup (OD-16: unknown index 0602 0000h, unknown sub-index 0609 0011h): a VAR of 1000h–101Fh by index,
//! anything else by one scan of the rows ([`walk`]); the PDO ranges 1400h–1BFFh read their template's rows
//! (PDO-02: PDO `k` at base + k). The expedited upload finds sub 00h of such a VAR inline ([`find`]).

#[cfg(feature = "error-history")]
use crate::emcy::HISTORY;
use crate::od::{AbortCode, Access, DataType, PdoMapping};
use crate::pdo::mapping::MAX_ENTRIES;

/// Where a sub-entry's value lives; [`Slot::Count`] is the "highest sub-index supported" of its object
/// (OD-04), computed from the table. A number rather than an enum, so that a [`Found`] is one `u32` (see
/// there); its constants are named as the enum's variants were, and the slots of every build come first,
/// so that a `match` on a slot in a build without the optional objects has no holes in its jump table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Slot(u8);

#[allow(non_upper_case_globals)] // named as enum variants: `match` arms read as they did
impl Slot {
    pub(super) const Count: Slot = Slot(0);
    pub(super) const DeviceType: Slot = Slot(1);
    pub(super) const ErrorRegister: Slot = Slot(2);
    pub(super) const SyncCob: Slot = Slot(3);
    pub(super) const SyncPeriod: Slot = Slot(4);
    pub(super) const EmcyCob: Slot = Slot(5);
    pub(super) const Consumer: Slot = Slot(6);
    pub(super) const HeartbeatTime: Slot = Slot(7);
    pub(super) const Identity: Slot = Slot(8);
    pub(super) const NmtStartup: Slot = Slot(9);
    pub(super) const PdoCob: Slot = Slot(10);
    pub(super) const PdoType: Slot = Slot(11);
    pub(super) const PdoInhibit: Slot = Slot(12);
    pub(super) const PdoEventTimer: Slot = Slot(13);
    pub(super) const PdoSyncStart: Slot = Slot(14);
    pub(super) const MapCount: Slot = Slot(15);
    pub(super) const MapEntry: Slot = Slot(16);
    #[cfg(feature = "error-history")]
    pub(super) const History: Slot = Slot(17);
    #[cfg(feature = "sync-window")]
    pub(super) const SyncWindow: Slot = Slot(18);
    #[cfg(feature = "manufacturer-strings")]
    pub(super) const DeviceName: Slot = Slot(19);
    #[cfg(feature = "manufacturer-strings")]
    pub(super) const HardwareVersion: Slot = Slot(20);
    #[cfg(feature = "manufacturer-strings")]
    pub(super) const SoftwareVersion: Slot = Slot(21);
    #[cfg(feature = "guarding")]
    pub(super) const GuardTime: Slot = Slot(22);
    #[cfg(feature = "guarding")]
    pub(super) const LifeTimeFactor: Slot = Slot(23);
    #[cfg(feature = "store-restore")]
    pub(super) const Store: Slot = Slot(24);
    #[cfg(feature = "store-restore")]
    pub(super) const Restore: Slot = Slot(25);
    #[cfg(feature = "time")]
    pub(super) const TimeCob: Slot = Slot(26);
    #[cfg(feature = "emcy-inhibit")]
    pub(super) const EmcyInhibit: Slot = Slot(27);
    #[cfg(feature = "sync-counter")]
    pub(super) const SyncOverflow: Slot = Slot(28);
    #[cfg(feature = "error-behaviour")]
    pub(super) const ErrorBehaviour: Slot = Slot(29);
}

/// Data type and access of a run of sub-entries (the profile uses these eight at most). The discriminant
/// holds the encoded size (bits 0–2: 1, 2 or 4; 0 for a string), the access (bits 4–5: 0 const, 1 ro, 2 rw)
/// and whether SDO may write it ([`WRITABLE`]), so [`Found::size`], [`Found::writable`] and [`Found::meta`] are a
/// mask or a small lookup each, not a match on the eight types at every caller.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub(super) enum Ty {
    U8Const = 0x01,
    U8Ro = 0x11,
    U8Rw = 0x21 | WRITABLE,
    U16Rw = 0x22 | WRITABLE,
    U32Ro = 0x14,
    U32Rw = 0x24 | WRITABLE,
    #[cfg(not(feature = "pdo-dynamic-mapping"))]
    U32Const = 0x04,
    #[cfg(feature = "manufacturer-strings")]
    StrConst = 0x00,
}

/// The bit of a [`Ty`] discriminant that marks a type SDO may write.
const WRITABLE: u8 = 0x80;

/// The data type and access a [`Ty`] discriminant stands for: the data type from the size bits, the access
/// from bits 4–5.
const fn ty_parts(bits: u8) -> (DataType, Access) {
    let dt = match bits & 0x07 {
        1 => DataType::Unsigned8,
        2 => DataType::Unsigned16,
        4 => DataType::Unsigned32,
        _ => DataType::VisibleString,
    };
    let access = match (bits >> 4) & 3 {
        0 => Access::Const,
        1 => Access::Ro,
        _ => Access::Rw,
    };
    (dt, access)
}

/// PDO-30: the mapping records are rw with dynamic mapping (feature `pdo-dynamic-mapping`), const when the
/// mapping is fixed.
#[cfg(feature = "pdo-dynamic-mapping")]
const MAP_COUNT: Ty = Ty::U8Rw;
#[cfg(feature = "pdo-dynamic-mapping")]
const MAP_ENTRY: Ty = Ty::U32Rw;
#[cfg(not(feature = "pdo-dynamic-mapping"))]
const MAP_COUNT: Ty = Ty::U8Const;
#[cfg(not(feature = "pdo-dynamic-mapping"))]
const MAP_ENTRY: Ty = Ty::U32Const;

/// Sub-indices `first..=last` of object `index`: type, access and value slot. `last == HB` stands for the
/// node's number of heartbeat consumers (1016h). An object's rows are together, its count row (sub 00h)
/// first, its highest sub-index last. The description the flash's [`Row`]s are built from.
#[derive(Debug, Clone, Copy)]
struct Run {
    index: u16,
    first: u8,
    last: u8,
    /// The low half of the [`Found`] of its sub-entries (type and slot; `n` 0).
    found: u16,
}

impl Run {
    const fn slot(&self) -> Slot {
        Found(self.found as u32).slot()
    }
}

/// One row of [`ROWS`] (4 bytes): the sub-indices from the previous row's `last + 1` (00h for an object's
/// first row) to `last`, of the object [`key_of`] gives `key` for. A gap between two runs of an object is a
/// row of its own, [`HOLE`].
#[derive(Debug, Clone, Copy)]
struct Row {
    key: u8,
    last: u8,
    /// The low half of the [`Found`] of its sub-entries (type and slot; `n` 0), [`HOLE`] for sub-indices
    /// that do not exist: one load where a type and a slot were two and a shift.
    found: u16,
}

impl Row {
    const fn slot(&self) -> Slot {
        Found(self.found as u32).slot()
    }
}

/// The `found` of a [`Row`] of sub-indices that do not exist (a count's type is never a string).
const HOLE: u16 = 0;
const _: () = assert!(Found::new(Ty::U8Const, Slot::Count, 0).0 as u16 != HOLE);

/// The one-byte key of an object of [`ROWS`]: 1000h–103Fh their low byte, the PDO templates 1400h, 1600h,
/// 1800h and 1F80h bits 4–11 (40h, 60h, 80h, F8h); `None` for any other index (no rows).
const fn key_of(index: u16) -> Option<u8> {
    match index {
        0x1000..=0x103F => Some(index as u8),
        0x1400 | 0x1600 | 0x1800 | 0x1F80 => Some((index >> 4) as u8),
        _ => None,
    }
}

const HB: u8 = 0xFF;

const fn run(index: u16, first: u8, last: u8, ty: Ty, slot: Slot) -> Run {
    Run { index, first, last, found: Found::new(ty, slot, 0).0 as u16 }
}

const fn var(index: u16, ty: Ty, slot: Slot) -> Run {
    run(index, 0, 0, ty, slot)
}

/// The keys of the PDO templates' rows: a mapping record's (1600h), a communication record's (1400h; a TPDO's
/// 1800h row is keyed by its index bits 4–11, as `walk` computes it).
const MAP: u8 = key(0x1600);
const COMM: u8 = key(0x1400);
const _: () = assert!(key(0x1800) == (0x1800u16 >> 4) as u8 && key(0x1400) == (0x1400u16 >> 4) as u8);

/// [`key_of`] an index that has one.
const fn key(index: u16) -> u8 {
    match key_of(index) {
        Some(k) => k,
        None => panic!("an object of the table has a key"),
    }
}

/// Sub 00h of an ARRAY/RECORD: the highest sub-index, the `last` of the object's final row.
const fn count(index: u16) -> Run {
    var(index, Ty::U8Const, Slot::Count)
}

/// Every object of the profile, one object's rows together (a count row first), in increasing index
/// order. The PDO records are templates: 1400h holds the communication record of every PDO (an RPDO has
/// subs 00h–05h), 1800h adds the TPDO's sub 06h right after it, 1600h is the mapping record of both.
/// Read at compile time only: the device's flash holds [`FIXED_VAR`] and [`ROWS`], built from it.
const DESC: &[Run] = &[
    var(0x1000, Ty::U32Ro, Slot::DeviceType),   // DEV-01
    var(0x1001, Ty::U8Ro, Slot::ErrorRegister), // ERR-01
    #[cfg(feature = "error-history")]
    var(0x1003, Ty::U8Rw, Slot::History), // ERR-04..09
    #[cfg(feature = "error-history")]
    run(0x1003, 1, HISTORY as u8, Ty::U32Ro, Slot::History),
    var(0x1005, Ty::U32Rw, Slot::SyncCob),    // SYNC-01..08
    var(0x1006, Ty::U32Rw, Slot::SyncPeriod), //
    #[cfg(feature = "sync-window")]
    var(0x1007, Ty::U32Rw, Slot::SyncWindow), // SYNC-08/09
    #[cfg(feature = "manufacturer-strings")]
    var(0x1008, Ty::StrConst, Slot::DeviceName), // DEV-04
    #[cfg(feature = "manufacturer-strings")]
    var(0x1009, Ty::StrConst, Slot::HardwareVersion),
    #[cfg(feature = "manufacturer-strings")]
    var(0x100A, Ty::StrConst, Slot::SoftwareVersion),
    #[cfg(feature = "guarding")]
    var(0x100C, Ty::U16Rw, Slot::GuardTime), // GUARD-02
    #[cfg(feature = "guarding")]
    var(0x100D, Ty::U8Rw, Slot::LifeTimeFactor), // GUARD-03
    #[cfg(feature = "store-restore")]
    count(0x1010), // STORE-01..05
    #[cfg(feature = "store-restore")]
    run(0x1010, 1, 3, Ty::U32Rw, Slot::Store),
    #[cfg(feature = "store-restore")]
    count(0x1011), // STORE-08..11
    #[cfg(feature = "store-restore")]
    run(0x1011, 1, 3, Ty::U32Rw, Slot::Restore),
    #[cfg(feature = "time")]
    var(0x1012, Ty::U32Rw, Slot::TimeCob), // TIME-01..03
    var(0x1014, Ty::U32Rw, Slot::EmcyCob), // EMCY-02/03
    #[cfg(feature = "emcy-inhibit")]
    var(0x1015, Ty::U16Rw, Slot::EmcyInhibit), // EMCY-09
    count(0x1016),                         // HB-06..09
    run(0x1016, 1, HB, Ty::U32Rw, Slot::Consumer), //
    var(0x1017, Ty::U16Rw, Slot::HeartbeatTime), // HB-01
    count(0x1018),                         // DEV-03
    run(0x1018, 1, 4, Ty::U32Ro, Slot::Identity), //
    #[cfg(feature = "sync-counter")]
    var(0x1019, Ty::U8Rw, Slot::SyncOverflow), // SYNC-10/12
    #[cfg(feature = "error-behaviour")]
    count(0x1029), // ERR-10/11
    #[cfg(feature = "error-behaviour")]
    run(0x1029, 1, 1, Ty::U8Rw, Slot::ErrorBehaviour),
    count(0x1400),                                                // PDO-06..18
    run(0x1400, 1, 1, Ty::U32Rw, Slot::PdoCob),                   //
    run(0x1400, 2, 2, Ty::U8Rw, Slot::PdoType),                   //
    run(0x1400, 3, 3, Ty::U16Rw, Slot::PdoInhibit),               //
    run(0x1400, 5, 5, Ty::U16Rw, Slot::PdoEventTimer),            //
    run(0x1800, 6, 6, Ty::U8Rw, Slot::PdoSyncStart),              // PDO-26
    var(0x1600, MAP_COUNT, Slot::MapCount),                       // PDO-30..37
    run(0x1600, 1, MAX_ENTRIES as u8, MAP_ENTRY, Slot::MapEntry), //
    var(0x1F80, Ty::U32Rw, Slot::NmtStartup),                     // NMT-27
];

/// The rows of one object are together, in increasing sub-index order without overlap from sub 00h, and
/// 1800h's row follows 1400h's (checked at compile time: [`walk`] takes the first row of an object that
/// reaches a sub-index, and the final row of an object, a TPDO's 1800h row after 1400h's, for its highest
/// sub-index). Every object has a key of its own ([`key_of`]).
const _: () = {
    let mut i = 0;
    while i < DESC.len() {
        let cur = DESC[i];
        assert!(key_of(cur.index).is_some(), "an object of the table has a key");
        let same = i > 0 && (DESC[i - 1].index == cur.index || (DESC[i - 1].index == 0x1400 && cur.index == 0x1800));
        if !same {
            assert!(cur.first == 0, "an object's rows start at sub 00h");
            let mut j = 0;
            while j < i {
                assert!(DESC[j].index != cur.index, "the rows of one object are together");
                j += 1;
            }
        } else {
            let prev = DESC[i - 1];
            assert!(prev.last != HB && cur.first > prev.last, "an object's rows go up without overlap");
        }
        assert!(cur.index != 0x1800 || DESC[i - 1].index == 0x1400, "1800h's row follows 1400h's");
        i += 1;
    }
};

/// Whether row `i` of [`DESC`] is the whole of a VAR of 1000h–101Fh (a row of sub 00h alone): such an
/// object is in [`FIXED_VAR`], not in [`ROWS`].
const fn is_fixed_var(i: usize) -> bool {
    let r = DESC[i];
    let alone = (i == 0 || DESC[i - 1].index != r.index) && (i + 1 == DESC.len() || DESC[i + 1].index != r.index);
    alone && r.index >= 0x1000 && r.index <= 0x101F && r.first == 0 && r.last == 0
}

/// Whether row `i` of [`DESC`] starts above the sub-index after its object's previous row: [`ROWS`] has a
/// [`HOLE`] row before it (1400h sub 04h).
const fn has_gap(i: usize) -> bool {
    i > 0 && !is_fixed_var(i) && DESC[i].first != 0 && DESC[i].first > DESC[i - 1].last + 1
}

/// How many entries [`FIXED_VAR`] has: up to the highest VAR of 1000h–101Fh this build has.
const FIXED_LEN: usize = {
    let (mut n, mut i) = (0, 0);
    while i < DESC.len() {
        if is_fixed_var(i) && (DESC[i].index - 0x1000) as usize >= n {
            n = (DESC[i].index - 0x1000) as usize + 1;
        }
        i += 1;
    }
    n
};

/// 1000h up to the highest VAR of 1000h–101Fh: the entry of an object that is one VAR (the low half of its
/// [`Found`]), found without a scan (the device type, error register and the other VARs the SDO paths read
/// most); [`NOT_VAR`] where there is none.
const FIXED_VAR: [u16; FIXED_LEN] = {
    let mut t = [Found::new(Ty::U8Const, NOT_VAR, 0).0 as u16; FIXED_LEN];
    let mut i = 0;
    while i < DESC.len() {
        if is_fixed_var(i) {
            let r = DESC[i];
            assert!(!matches!(r.slot(), NOT_VAR), "a VAR's slot is not NOT_VAR");
            t[(r.index - 0x1000) as usize] = r.found;
        }
        i += 1;
    }
    t
};

/// The slot of [`FIXED_VAR`] where 1000h–101Fh has no VAR: a count is never a VAR's.
const NOT_VAR: Slot = Slot::Count;

/// How many rows [`ROWS`] has.
const ROW_COUNT: usize = {
    let (mut n, mut i) = (0, 0);
    while i < DESC.len() {
        n += !is_fixed_var(i) as usize + has_gap(i) as usize;
        i += 1;
    }
    n
};

/// The rows [`walk`] scans: those of [`DESC`] but the VARs of [`FIXED_VAR`] (the ARRAYs and RECORDs of
/// 1000h–101Fh, 1029h, the PDO templates and 1F80h), with a [`HOLE`] row for each gap.
const ROWS: [Row; ROW_COUNT] = {
    let mut t = [Row { key: 0, last: 0, found: HOLE }; ROW_COUNT];
    let (mut n, mut i) = (0, 0);
    while i < DESC.len() {
        let r = DESC[i];
        let key = key(r.index);
        if has_gap(i) {
            t[n] = Row { key, last: r.first - 1, found: HOLE };
            n += 1;
        }
        if !is_fixed_var(i) {
            t[n] = Row { key, last: r.last, found: r.found };
            n += 1;
        }
        i += 1;
    }
    t
};

/// The capacities the table depends on (from `ProfileSizes`), packed in one `u32` so that [`find`] is
/// not generic and gets them in a register: heartbeat consumers (bits 0–7; no 1016h when 0), RPDOs (bits
/// 8–19) and TPDOs (bits 20–31), at most 512 each (PDO-02).
#[derive(Debug, Clone, Copy)]
pub(super) struct Counts(u32);

impl Counts {
    /// The capacities `hb` (at most 127, HB-06), `rpdo` and `tpdo` (at most 512).
    pub(super) const fn new(hb: usize, rpdo: usize, tpdo: usize) -> Counts {
        assert!(hb <= 0xFF && rpdo <= 0xFFF && tpdo <= 0xFFF);
        Counts(hb as u32 | (rpdo as u32) << 8 | (tpdo as u32) << 20)
    }

    const fn hb(self) -> u8 {
        self.0 as u8
    }

    const fn pdos(self, tx: bool) -> u16 {
        (if tx { self.0 >> 20 } else { (self.0 >> 8) & 0xFFF }) as u16
    }
}

/// One sub-entry found in the table: its [`Ty`]'s discriminant (bits 0–7), its [`Slot`] (bits 11–15) and `n`
/// (bits 16–31): for [`Slot::Count`] the highest sub-index, for the PDO slots the PDO number `k` (0-based),
/// plus [`TX`] for a TPDO object (1800h/1A00h range). One `u32`, so that the `Result` of a lookup comes back
/// in two registers: a struct of the three fields went through memory, at every caller. The slot has 5 bits
/// of its own (`ubfx` on the target, one instruction, and a range a `match` can know).
#[derive(Debug, Clone, Copy)]
pub(super) struct Found(u32);

/// The bit of [`Found::n`] that marks a TPDO object.
const TX: u16 = 0x8000;
const _: () = assert!(TX == 1 << 15, "walk sets TX as bit 15");

impl Found {
    const fn new(ty: Ty, slot: Slot, n: u16) -> Found {
        assert!(slot.0 < 32, "a slot fits in 5 bits");
        Found(ty as u32 | (slot.0 as u32) << 11 | (n as u32) << 16)
    }

    /// Where the value lives.
    pub(super) const fn slot(self) -> Slot {
        Slot((self.0 >> 11) as u8 & 0x1F)
    }

    /// The highest sub-index of a [`Slot::Count`], the PDO number and direction of a PDO slot.
    pub(super) const fn n(self) -> u16 {
        (self.0 >> 16) as u16
    }

    /// A TPDO object (1800h/1A00h range).
    pub(super) const fn tx(self) -> bool {
        self.n() & TX != 0
    }

    /// The PDO number `k` of a PDO slot.
    pub(super) const fn k(self) -> usize {
        (self.n() & !TX) as usize
    }

    /// [`k`](Self::k), which `walk` found below the number of PDOs `len` of its direction, as [`in_bounds`]
    /// gives it.
    pub(super) const fn k_below(self, len: usize) -> usize {
        in_bounds(self.k(), len)
    }

    /// The encoded size of a numeric entry (1, 2 or 4), 0 for a string.
    pub(super) const fn size(self) -> usize {
        (self.0 & 0x07) as usize
    }

    /// Whether SDO may write it.
    pub(super) const fn writable(self) -> bool {
        self.0 as u8 & WRITABLE != 0
    }

    /// Data type, access and PDO mapping (only 1001h is mappable: TPDO, ERR-01).
    pub(super) const fn meta(self) -> (DataType, Access, PdoMapping) {
        let (dt, access) = ty_parts(self.0 as u8);
        let pdo = if self.slot().0 == Slot::ErrorRegister.0 { PdoMapping::Tpdo } else { PdoMapping::No };
        (dt, access, pdo)
    }
}

/// `i`, an index below `len` that [`walk`] already checked (a PDO's number, a sub-index of 1016h or of a
/// mapping record, minus 1), clamped to `len - 1` (`len` 0 leaves it as it is): for LLVM, which then knows
/// that an array of `len` indexed by it is in bounds and drops the `None` branch of the `get` (footprint.sh
/// node: 100 B in all).
pub(super) const fn in_bounds(i: usize, len: usize) -> usize {
    let last = len.wrapping_sub(1);
    if i < last {
        i
    } else {
        last
    }
}

/// The sub-entry `(index, sub)` of the communication profile, or the OD-16 abort code.
/// Inline: sub 00h of a VAR of 1000h–101Fh is an array read and two compares at the caller, the rest
/// (other sub-indices of such a VAR too) one call of [`walk`].
#[inline]
pub(super) fn find(index: u16, sub: u8, c: Counts) -> Result<Found, AbortCode> {
    if let (Some(&f), 0) = (FIXED_VAR.get(usize::from(index.wrapping_sub(0x1000))), sub) {
        let f = Found(f.into());
        if f.slot() != NOT_VAR {
            return Ok(f);
        }
    }
    walk(index, sub, c)
}

/// [`find`]: a VAR of 1000h–101Fh from [`FIXED_VAR`] (sub 00h alone), any other object by one scan of
/// [`ROWS`] (all of them: a loop that stops after the object's rows cost 44 B of flash in the node, for a
/// path no SDO service depends on for speed): the rows with the object's key (PDO-02: PDO `k` of a range at
/// base + k reads its template's rows; a TPDO's communication record 1400h's and 1800h's). An object without
/// rows does not exist (0602 0000h), a sub-index above its last row neither (0609 0011h), nor one of a
/// [`HOLE`]; the row of a sub-index is the object's first that reaches it; a count (sub 00h) is the highest
/// sub-index, the `last` of the object's final row.
#[inline(never)]
pub(super) fn walk(index: u16, sub: u8, c: Counts) -> Result<Found, AbortCode> {
    if let Some(&f) = FIXED_VAR.get(usize::from(index.wrapping_sub(0x1000))) {
        let f = Found(f.into());
        if f.slot() != NOT_VAR {
            return if sub == 0 { Ok(f) } else { Err(AbortCode::SubIndexDoesNotExist) };
        }
    }
    let (key, alt, k) = match index {
        0x1400..=0x1BFF => {
            let (k, tx) = (index & 0x1FF, index >= 0x1800);
            if k >= c.pdos(tx) {
                return Err(AbortCode::ObjectDoesNotExist);
            }
            // A mapping record reads 1600h's rows, a communication record 1400h's (and a TPDO's 1800h's).
            let (key, alt) = if index & 0x200 != 0 { (MAP, MAP) } else { (((index & 0xFE00) >> 4) as u8, COMM) };
            (key, alt, k | u16::from(tx) << 15)
        }
        0x1016 if c.hb() == 0 => return Err(AbortCode::ObjectDoesNotExist),
        _ => {
            let key = key_of(index).ok_or(AbortCode::ObjectDoesNotExist)?;
            (key, key, 0)
        }
    };
    // The runs of an object go up from sub 00h: each starts after the previous one's last sub-index, so
    // after the scan `first` is the highest sub-index + 1 (0: no rows, no object).
    let (mut found, mut first) = (None, 0);
    for r in ROWS.iter().filter(|r| r.key == key || r.key == alt) {
        let last = if r.last == HB { c.hb() } else { r.last };
        if u32::from(sub) >= first && sub <= last {
            found = Some(r);
        }
        first = u32::from(last) + 1;
    }
    if first == 0 {
        return Err(AbortCode::ObjectDoesNotExist);
    }
    let r = found.filter(|r| r.found != HOLE).ok_or(AbortCode::SubIndexDoesNotExist)?;
    let n = if r.slot() == Slot::Count { (first - 1) as u16 } else { k };
    Ok(Found(u32::from(r.found) | u32::from(n) << 16))
}

#[cfg(test)]
mod tests {
    use super::{Found, Slot, Ty};

    /// The size and writability packed into each [`Ty`] discriminant agree with the data type and access it
    /// stands for, read back from a [`Found`] as the SDO paths read them (OD-08: only rw entries are written
    /// by SDO; DT-05: UNSIGNEDn is n/8 bytes).
    #[test]
    fn ty_bits_agree_with_parts() {
        let all = [
            Ty::U8Const,
            Ty::U8Ro,
            Ty::U8Rw,
            Ty::U16Rw,
            Ty::U32Ro,
            Ty::U32Rw,
            #[cfg(not(feature = "pdo-dynamic-mapping"))]
            Ty::U32Const,
            #[cfg(feature = "manufacturer-strings")]
            Ty::StrConst,
        ];
        use crate::od::{Access, DataType};
        let intended = [
            (DataType::Unsigned8, Access::Const),
            (DataType::Unsigned8, Access::Ro),
            (DataType::Unsigned8, Access::Rw),
            (DataType::Unsigned16, Access::Rw),
            (DataType::Unsigned32, Access::Ro),
            (DataType::Unsigned32, Access::Rw),
            #[cfg(not(feature = "pdo-dynamic-mapping"))]
            (DataType::Unsigned32, Access::Const),
            #[cfg(feature = "manufacturer-strings")]
            (DataType::VisibleString, Access::Const),
        ];
        for (ty, parts) in all.into_iter().zip(intended) {
            let f = Found::new(ty, Slot::DeviceType, 0);
            let (dt, access, _) = f.meta();
            assert_eq!((dt, access), parts, "{ty:?}: the name says the data type and access");
            assert_eq!(f.size(), dt.size().unwrap_or(0), "{ty:?}");
            assert_eq!(f.writable(), access.writable(), "{ty:?}");
        }
    }

    /// A [`Found`] gives back the slot and `n` it was packed from: a PDO's number and direction (PDO-02), the
    /// highest sub-index of a count (OD-04); only 1001h is TPDO-mappable (ERR-01).
    #[test]
    fn found_unpacks_its_fields() {
        let f = Found::new(Ty::U32Rw, Slot::PdoCob, 0x8000 | 511);
        assert_eq!((f.slot(), f.tx(), f.k(), f.size()), (Slot::PdoCob, true, 511, 4));
        assert_eq!((f.k_below(512), f.k_below(4), f.k_below(0)), (511, 3, 511));
        let f = Found::new(Ty::U8Const, Slot::Count, 254);
        assert_eq!((f.slot(), f.n(), f.tx(), f.writable()), (Slot::Count, 254, false, false));
        assert_eq!(Found::new(Ty::U8Ro, Slot::ErrorRegister, 0).meta().2, crate::od::PdoMapping::Tpdo);
        assert_eq!(Found::new(Ty::U32Ro, Slot::DeviceType, 0).meta().2, crate::od::PdoMapping::No);
    }
}
