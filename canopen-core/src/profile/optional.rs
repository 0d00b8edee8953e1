//! The optional communication objects 1002h manufacturer status register, 1013h high-resolution time
//! stamp, 1020h verify configuration and 1028h emergency consumer, each behind its own Cargo feature
//! (`manufacturer-status`, `high-res-time`, `verify-config`, `emcy-consumer`; on by default, off in the
//! firmware's reference builds), and the MPDO lists 1FA0h / 1FD0h (feature `mpdo`).
//!
//! [`OptionalObjects`] is a small dictionary part the [`CommProfile`](super::CommProfile) owns and asks
//! first for these four indices ([`serves`], a constant per build: a build without the features has an
//! empty struct and compiles no extra test). Being part of the profile, they are in the EDS, reached by SDO
//! and by `Node::dictionary`, stored and restored with the communication parameters (1010h/1011h) and set
//! back by reset communication (NMT-05) like the profile's own objects.
//!
//! What each one does (CiA 301 §7.5.2.3, §7.5.2.16, §7.5.2.23, §7.5.2.31; the checklist rows cited):
//!
//! - **1002h** (ERR-03): VAR UNSIGNED32, ro, TPDO-mappable; the application sets it
//!   (`Node::set_manufacturer_status`), the stack never does. CiA 301 gives no default; it is 0 at power-on
//!   here, and the EDS says so (as for 1001h).
//! - **1013h** (TIME-06): VAR UNSIGNED32 in µs, rw, mappable both ways, default 0. It is a running
//!   microsecond clock: it reads its last set value plus the time passed since (the node's clock, so a
//!   TPDO that maps it carries the time of its own transmission), modulo 2³². Writing it (SDO, or an RPDO:
//!   a high-resolution time stamp consumed) sets it. It is produced and consumed with TIME: when the node
//!   receives a TIME message (1012h bit 31) or produces one (`Node::produce_time`), 1013h is set to that
//!   time of day's milliseconds × 1000 (mod 2³²), so both stamps tell the same time and 1013h refines it
//!   in µs until the next TIME. Not stored (a clock, not a parameter).
//! - **1020h** (STORE-12): ARRAY UNSIGNED32, sub 00h const 02h, sub 01h configuration date (days since
//!   1984-01-01), sub 02h configuration time (ms after midnight), rw, default 0. Saved and loaded with the
//!   communication parameters (1010h/1011h). The device sets both to 0 when another command changes the
//!   boot-up configuration: a 1011h restore (any sub-index) — the live value at once, and the stored one
//!   (`Node` rewrites the stored record without 1020h), so a configuration manager that compares 1020h
//!   with its DCF after the next reset configures the device again. A 1010h save is the command the
//!   configuration tool itself pairs with 1020h, so it stores 1020h as it is (CiA 301's note: the
//!   integrator keeps a configuration changed and saved without a new 1020h consistent).
//! - **1028h** (EMCY-10, COB-14/15/16): ARRAY UNSIGNED32, sub 00h const 7Fh, sub n the COB-ID of node n's
//!   EMCY as this device consumes it: bit 31 = 0 valid (consumed), bit 30 reserved (writing 1 is 0609
//!   0030h), bit 29 frame (1 is 0609 0030h: 11-bit only), bits 10–0 the CAN-ID (bits 28–11 set: 0609
//!   0030h); the CAN-ID does not change while the entry is valid (0609 0030h; invalidate, change,
//!   validate). Only an EMCY on a valid entry's CAN-ID reaches the application, as
//!   `Event::Emergency { node: n, .. }` (EMCY-11: the reaction is the application's). Default: every sub n
//!   valid on 80h + n, the pre-defined connection set (the same EMCYs a node without 1028h reports).
//!   Reception is one bit test per frame that reaches the EMCY stage (a 2048-bit map of the valid
//!   CAN-IDs); a hit finds its sub-index at 80h + n first, else by a scan of the 127 entries.
//! - **1FA0h** object scanner list (MPDO-03, §7.5.2.39): ARRAY UNSIGNED32, sub 00h const
//!   [`MPDO_SCANNER_ENTRIES`], sub n rw, default 0 (not configured); what the SAM producer may send
//!   ([`crate::pdo::mpdo::ScannerEntry`]). One list: CiA 301 allows 1FA0h–1FCFh, this build has the first.
//! - **1FD0h** object dispatching list (MPDO-03, §7.5.2.40): ARRAY UNSIGNED64, sub 00h const
//!   [`MPDO_DISPATCH_ENTRIES`], sub n rw, default 0; where the SAM consumer writes a producer's object
//!   ([`crate::pdo::mpdo::DispatchEntry`]). One list of 1FD0h–1FFFh. Both are communication parameters:
//!   stored with 1010h, set back to 0 by reset communication. Entries are not checked when written (an
//!   entry naming a missing object is a frame ignored at reception, as lely does).

#[cfg(feature = "emcy-consumer")]
use crate::cob::CobIdEntry;
use crate::od::{check_len, copy_at, AbortCode, DataType, EntryDesc, ObjectDesc, SubInfo};
#[cfg(any(feature = "verify-config", feature = "emcy-consumer", feature = "mpdo"))]
use crate::od::{count_entry, ObjectCode};
#[cfg(feature = "high-res-time")]
use crate::time::Instant;

/// The indices this build has, in increasing order.
const INDICES: &[u16] = &[
    #[cfg(feature = "manufacturer-status")]
    0x1002,
    #[cfg(feature = "high-res-time")]
    0x1013,
    #[cfg(feature = "verify-config")]
    0x1020,
    #[cfg(feature = "emcy-consumer")]
    0x1028,
    #[cfg(feature = "mpdo")]
    0x1FA0,
    #[cfg(feature = "mpdo")]
    0x1FD0,
];

/// 1028h sub 00h: one entry per node-ID.
pub const EMCY_CONSUMERS: usize = 127;

/// 1FA0h sub 00h: the object scanner list's entries (MPDO-03; CiA 301 allows up to FEh).
pub const MPDO_SCANNER_ENTRIES: usize = 16;

/// 1FD0h sub 00h: the object dispatching list's entries (MPDO-03; CiA 301 allows up to FEh).
pub const MPDO_DISPATCH_ENTRIES: usize = 16;

/// Whether `index` is one of the optional objects this build has (a constant `false` without the features).
///
/// ```
/// use canopen_core::profile::optional::serves;
/// assert_eq!(serves(0x1028), cfg!(feature = "emcy-consumer"));
/// assert!(!serves(0x1017));
/// ```
#[inline(always)]
pub const fn serves(index: u16) -> bool {
    (cfg!(feature = "manufacturer-status") && index == 0x1002)
        || (cfg!(feature = "high-res-time") && index == 0x1013)
        || (cfg!(feature = "verify-config") && index == 0x1020)
        || (cfg!(feature = "emcy-consumer") && index == 0x1028)
        || (cfg!(feature = "mpdo") && (index == 0x1FA0 || index == 0x1FD0))
}

/// The entries of 1FA0h (UNSIGNED32 scanner entries) and 1FD0h (UNSIGNED64 dispatcher entries): sub 00h
/// const, the entries rw with default 0 (MPDO-03).
#[cfg(feature = "mpdo")]
fn mpdo_list_entry(index: u16, sub: u8) -> Result<EntryDesc, AbortCode> {
    use crate::od::{Access::Rw, DataType::*, Value};
    let (n, name, data_type) = if index == 0x1FA0 {
        (MPDO_SCANNER_ENTRIES, "Scanned object", Unsigned32)
    } else {
        (MPDO_DISPATCH_ENTRIES, "Dispatched object", Unsigned64)
    };
    match usize::from(sub) {
        0 => Ok(count_entry(index, n as u8)),
        s if s <= n => Ok(EntryDesc {
            numbered: true,
            ..EntryDesc::var(index, sub, name, data_type, Rw).with_default(Value::Uint(0))
        }),
        _ => Err(AbortCode::SubIndexDoesNotExist),
    }
}

/// 1013h as a running µs clock: `base` at the instant `at`.
#[cfg(feature = "high-res-time")]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct HighResTime {
    base: u32,
    at: Instant,
    /// The node's latest time (the node passes every instant in).
    now: Instant,
}

#[cfg(feature = "high-res-time")]
impl HighResTime {
    fn value(&self) -> u32 {
        // Modulo 2³² µs by definition: the truncation is the object's wrap-around.
        self.base.wrapping_add(self.now.saturating_duration_since(self.at).as_micros() as u32)
    }
    fn set(&mut self, v: u32) {
        self.base = v;
        self.at = self.now;
    }
}

/// 1028h: the entries (bit 15 = entry bit 31, "not valid"; bits 10–0 the CAN-ID) and a map of the valid
/// entries' CAN-IDs.
#[cfg(feature = "emcy-consumer")]
#[derive(Debug, Clone, PartialEq, Eq)]
struct EmcyConsumer {
    entries: [u16; EMCY_CONSUMERS],
    consumed: [u32; 64],
}

#[cfg(feature = "emcy-consumer")]
impl EmcyConsumer {
    const NOT_VALID: u16 = 0x8000;

    fn new() -> Self {
        let mut c = EmcyConsumer { entries: [0; EMCY_CONSUMERS], consumed: [0; 64] };
        c.set_defaults();
        c
    }

    fn set_defaults(&mut self) {
        for (n, e) in self.entries.iter_mut().enumerate() {
            *e = 0x81 + n as u16;
        }
        self.rebuild();
    }

    fn rebuild(&mut self) {
        self.consumed = [0; 64];
        for &e in &self.entries {
            if e & Self::NOT_VALID == 0 {
                self.consumed[usize::from(e >> 5) & 63] |= 1 << (e & 31);
            }
        }
    }

    fn raw(e: u16) -> u32 {
        (u32::from(e & Self::NOT_VALID) << 16) | u32::from(e & 0x7FF)
    }

    fn get(&self, sub: u8) -> Result<u32, AbortCode> {
        let i = usize::from(sub).checked_sub(1).ok_or(AbortCode::SubIndexDoesNotExist)?;
        self.entries.get(i).map(|&e| Self::raw(e)).ok_or(AbortCode::SubIndexDoesNotExist)
    }

    /// COB-14/15/16, EMCY-10: frame bit, bits 28–11 and bit 30 refused, the CAN-ID fixed while valid.
    fn set(&mut self, sub: u8, v: u32, rules: bool) -> Result<(), AbortCode> {
        let cur = self.get(sub)?;
        let valid = |e: CobIdEntry| !e.bit31();
        let new = if rules { CobIdEntry::from_raw(cur).check_change(v, valid)? } else { CobIdEntry::from_raw(v) };
        if new.bit30() || new.is_extended() || v & 0x1FFF_F800 != 0 {
            return Err(AbortCode::InvalidValue);
        }
        let flag = if new.bit31() { Self::NOT_VALID } else { 0 };
        self.entries[usize::from(sub) - 1] = flag | new.can_id();
        self.rebuild();
        Ok(())
    }

    #[inline]
    fn producer(&self, can_id: u16) -> Option<u8> {
        let id = can_id & 0x7FF;
        if self.consumed[usize::from(id >> 5)] & (1 << (id & 31)) == 0 {
            return None;
        }
        self.producer_of_consumed(id)
    }

    /// The sub-index of a consumed CAN-ID: 80h + n first (the pre-defined set), else the first entry.
    #[inline(never)]
    fn producer_of_consumed(&self, id: u16) -> Option<u8> {
        if let Some(n) = id.checked_sub(0x81).filter(|&i| self.entries.get(usize::from(i)) == Some(&id)) {
            return Some(n as u8 + 1);
        }
        self.entries.iter().position(|&e| e == id).map(|i| i as u8 + 1)
    }
}

/// The optional objects' values (an empty struct in a build without their features).
///
/// ```
/// use canopen_core::profile::optional::OptionalObjects;
/// let mut o = OptionalObjects::new();
/// # #[cfg(feature = "emcy-consumer")] {
/// assert_eq!(o.emcy_producer(0x085), Some(5)); // default: node 5's EMCY on 85h is consumed
/// o.load(0x1028, 5, &0x8000_0085u32.to_le_bytes()).unwrap(); // entry 5 not valid
/// assert_eq!(o.emcy_producer(0x085), None);
/// # }
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OptionalObjects {
    /// 1002h manufacturer status register.
    #[cfg(feature = "manufacturer-status")]
    pub manufacturer_status: u32,
    #[cfg(feature = "high-res-time")]
    high_res: HighResTime,
    /// 1020h sub 01h configuration date, sub 02h configuration time.
    #[cfg(feature = "verify-config")]
    pub verify_configuration: [u32; 2],
    #[cfg(feature = "emcy-consumer")]
    emcy: EmcyConsumer,
    /// 1FA0h sub 01h.. object scanner list.
    #[cfg(feature = "mpdo")]
    mpdo_scanner: [u32; MPDO_SCANNER_ENTRIES],
    /// 1FD0h sub 01h.. object dispatching list.
    #[cfg(feature = "mpdo")]
    mpdo_dispatch: [u64; MPDO_DISPATCH_ENTRIES],
}

impl Default for OptionalObjects {
    fn default() -> Self {
        Self::new()
    }
}

impl OptionalObjects {
    /// The power-on values.
    pub fn new() -> Self {
        OptionalObjects {
            #[cfg(feature = "manufacturer-status")]
            manufacturer_status: 0,
            #[cfg(feature = "high-res-time")]
            high_res: HighResTime::default(),
            #[cfg(feature = "verify-config")]
            verify_configuration: [0; 2],
            #[cfg(feature = "emcy-consumer")]
            emcy: EmcyConsumer::new(),
            #[cfg(feature = "mpdo")]
            mpdo_scanner: [0; MPDO_SCANNER_ENTRIES],
            #[cfg(feature = "mpdo")]
            mpdo_dispatch: [0; MPDO_DISPATCH_ENTRIES],
        }
    }

    /// Reset communication (NMT-05): 1020h and 1028h back to their defaults (the stored values are loaded
    /// after this); 1002h and 1013h keep their values (a status and a clock, not parameters).
    pub fn reset_communication(&mut self) {
        #[cfg(feature = "verify-config")]
        {
            self.verify_configuration = [0; 2];
        }
        #[cfg(feature = "emcy-consumer")]
        self.emcy.set_defaults();
        #[cfg(feature = "mpdo")]
        {
            self.mpdo_scanner = [0; MPDO_SCANNER_ENTRIES];
            self.mpdo_dispatch = [0; MPDO_DISPATCH_ENTRIES];
        }
    }

    /// Whether an entry of the object scanner list 1FA0h covers (`index`, `sub`): the SAM producer may send
    /// it (MPDO-03).
    ///
    /// ```
    /// # use canopen_core::profile::optional::OptionalObjects;
    /// let mut o = OptionalObjects::new();
    /// assert!(!o.mpdo_scanned(0x2000, 1)); // no entry configured
    /// o.write(0x1FA0, 1, &0x0220_0001u32.to_le_bytes()).unwrap(); // 2000h sub 01h..02h
    /// assert!(o.mpdo_scanned(0x2000, 2));
    /// ```
    #[cfg(feature = "mpdo")]
    pub fn mpdo_scanned(&self, index: u16, sub: u8) -> bool {
        crate::pdo::mpdo::scanned(&self.mpdo_scanner, index, sub)
    }

    /// The local object the object dispatching list 1FD0h maps producer `node`'s (`index`, `sub`) to
    /// (MPDO-03).
    ///
    /// ```
    /// # use canopen_core::profile::optional::OptionalObjects;
    /// let mut o = OptionalObjects::new();
    /// o.write(0x1FD0, 1, &0x0120_0100_6000_0103u64.to_le_bytes()).unwrap(); // node 3's 6000h:01 → 2001h:00
    /// assert_eq!(o.mpdo_dispatch(3, 0x6000, 1), Some((0x2001, 0)));
    /// ```
    #[cfg(feature = "mpdo")]
    pub fn mpdo_dispatch(&self, node: u8, index: u16, sub: u8) -> Option<(u16, u8)> {
        crate::pdo::mpdo::dispatch(&self.mpdo_dispatch, node, index, sub)
    }

    /// The node's clock moved to `now` (1013h reads relative to it).
    ///
    /// ```
    /// # use canopen_core::{profile::optional::OptionalObjects, Instant};
    /// let mut o = OptionalObjects::new();
    /// o.set_now(Instant::from_micros(250));
    /// # #[cfg(feature = "high-res-time")]
    /// assert_eq!(o.high_res_time(), 250);
    /// ```
    #[inline(always)]
    pub fn set_now(&mut self, now: crate::time::Instant) {
        #[cfg(feature = "high-res-time")]
        {
            self.high_res.now = now;
        }
        let _ = now;
    }

    /// 1013h now, µs (mod 2³²).
    #[cfg(feature = "high-res-time")]
    pub fn high_res_time(&self) -> u32 {
        self.high_res.value()
    }

    /// A TIME message with `ms` milliseconds after midnight was received or produced now: 1013h becomes
    /// `ms` × 1000 (mod 2³², TIME-06).
    ///
    /// ```
    /// # use canopen_core::profile::optional::OptionalObjects;
    /// let mut o = OptionalObjects::new();
    /// o.time_of_day(5_000);
    /// # #[cfg(feature = "high-res-time")]
    /// assert_eq!(o.high_res_time(), 5_000_000);
    /// ```
    pub fn time_of_day(&mut self, ms: u32) {
        #[cfg(feature = "high-res-time")]
        self.high_res.set(ms.wrapping_mul(1000));
        let _ = ms;
    }

    /// 1020h set to 0 (a command other than the configuration tool's changed the boot-up configuration).
    pub fn configuration_changed(&mut self) {
        #[cfg(feature = "verify-config")]
        {
            self.verify_configuration = [0; 2];
        }
    }

    /// The 1028h sub-index (the producer's node-ID) whose valid entry has CAN-ID `can_id`, if any
    /// (EMCY-10); always `None` without the `emcy-consumer` feature.
    #[inline]
    pub fn emcy_producer(&self, can_id: u16) -> Option<u8> {
        #[cfg(feature = "emcy-consumer")]
        return self.emcy.producer(can_id);
        #[cfg(not(feature = "emcy-consumer"))]
        {
            let _ = can_id;
            None
        }
    }

    /// The CAN-IDs of the valid 1028h entries outside 081h–0FFh (the receive filters add them to the EMCY
    /// range's filter).
    pub fn emcy_ids_outside_range(&self) -> impl Iterator<Item = u16> + '_ {
        #[cfg(feature = "emcy-consumer")]
        let ids = self.emcy.entries.iter().copied();
        #[cfg(not(feature = "emcy-consumer"))]
        let ids = [].into_iter();
        ids.filter(|&e| e & 0x8000 == 0 && !(0x81..=0xFF).contains(&e))
    }

    /// The number of objects this build has.
    pub const fn object_count(&self) -> usize {
        INDICES.len()
    }

    /// The index of the `n`-th object (increasing index).
    ///
    /// ```
    /// # use canopen_core::profile::optional::OptionalObjects;
    /// let o = OptionalObjects::default();
    /// assert_eq!(o.object_index(o.object_count()), None);
    /// ```
    pub fn object_index(&self, n: usize) -> Option<u16> {
        INDICES.get(n).copied()
    }

    /// The `n`-th object (increasing index).
    pub fn object(&self, n: usize) -> Option<ObjectDesc> {
        let index = *INDICES.get(n)?;
        let var = |name| ObjectDesc { index, name, code: crate::od::ObjectCode::Var, first: 0, subs: 1 };
        Some(match index {
            0x1002 => var("Manufacturer status register"),
            0x1013 => var("High resolution time stamp"),
            #[cfg(feature = "verify-config")]
            0x1020 => ObjectDesc { index, name: "Verify configuration", code: ObjectCode::Array, first: 0, subs: 3 },
            #[cfg(feature = "emcy-consumer")]
            0x1028 => ObjectDesc {
                index,
                name: "Emergency consumer object",
                code: ObjectCode::Array,
                first: 0,
                subs: EMCY_CONSUMERS as u16 + 1,
            },
            #[cfg(feature = "mpdo")]
            0x1FA0 => ObjectDesc {
                index,
                name: "Object scanner list",
                code: ObjectCode::Array,
                first: 0,
                subs: MPDO_SCANNER_ENTRIES as u16 + 1,
            },
            #[cfg(feature = "mpdo")]
            0x1FD0 => ObjectDesc {
                index,
                name: "Object dispatching list",
                code: ObjectCode::Array,
                first: 0,
                subs: MPDO_DISPATCH_ENTRIES as u16 + 1,
            },
            _ => return None,
        })
    }

    /// The description of one sub-entry, or the OD-16 abort code.
    pub fn entry(&self, index: u16, sub: u8) -> Result<EntryDesc, AbortCode> {
        use crate::od::{Access::*, DataType::*, PdoMapping, Value};
        if !serves(index) {
            return Err(AbortCode::ObjectDoesNotExist);
        }
        let zero = Value::Uint(0);
        Ok(match (index, sub) {
            (0x1002, 0) => EntryDesc::var(index, 0, "Manufacturer status register", Unsigned32, Ro)
                .with_pdo(PdoMapping::Tpdo)
                .with_default(zero),
            (0x1013, 0) => EntryDesc::var(index, 0, "High resolution time stamp", Unsigned32, Rw)
                .with_pdo(PdoMapping::Both)
                .with_default(zero),
            #[cfg(feature = "verify-config")]
            (0x1020, 0) => count_entry(index, 2),
            (0x1020, 1) => EntryDesc::var(index, 1, "Configuration date", Unsigned32, Rw).with_default(zero),
            (0x1020, 2) => EntryDesc::var(index, 2, "Configuration time", Unsigned32, Rw).with_default(zero),
            #[cfg(feature = "emcy-consumer")]
            (0x1028, 0) => count_entry(index, EMCY_CONSUMERS as u8),
            (0x1028, 1..=0x7F) => EntryDesc {
                numbered: true,
                ..EntryDesc::var(index, sub, "Emergency consumer", Unsigned32, Rw)
                    .with_default(Value::Uint(0x80 + u64::from(sub)))
            },
            #[cfg(feature = "mpdo")]
            (0x1FA0 | 0x1FD0, _) => return mpdo_list_entry(index, sub),
            _ => return Err(AbortCode::SubIndexDoesNotExist),
        })
    }

    /// Data type, access, PDO mapping and size of one sub-entry.
    pub fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
        let e = self.entry(index, sub)?;
        Ok(SubInfo { data_type: e.data_type, access: e.access, pdo: e.pdo, size: e.max_size })
    }

    /// The current value of a sub-entry (every one is numeric, at most 8 bytes).
    fn value(&self, index: u16, sub: u8) -> Result<u64, AbortCode> {
        let e = self.entry(index, sub)?;
        if e.sub == 0 && e.data_type == DataType::Unsigned8 {
            return Ok(match e.default {
                Some(crate::od::Value::Uint(n)) => n,
                _ => 0,
            });
        }
        match index {
            #[cfg(feature = "manufacturer-status")]
            0x1002 => Ok(self.manufacturer_status.into()),
            #[cfg(feature = "high-res-time")]
            0x1013 => Ok(self.high_res.value().into()),
            #[cfg(feature = "verify-config")]
            0x1020 => Ok(self.verify_configuration[usize::from(sub) - 1].into()),
            #[cfg(feature = "emcy-consumer")]
            0x1028 => self.emcy.get(sub).map(u64::from),
            #[cfg(feature = "mpdo")]
            0x1FA0 => Ok(self.mpdo_scanner[usize::from(sub) - 1].into()),
            #[cfg(feature = "mpdo")]
            0x1FD0 => Ok(self.mpdo_dispatch[usize::from(sub) - 1]),
            _ => Err(AbortCode::ObjectDoesNotExist),
        }
    }

    /// Reads bytes `offset..` of a sub-entry (SDO, PDO, store).
    pub fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        let size = self.info(index, sub)?.size;
        let v = self.value(index, sub)?.to_le_bytes();
        Ok(copy_at(v.get(..size).unwrap_or(&v), offset, buf))
    }

    /// An expedited upload: (size, bytes copied); an 8-byte entry (1FD0h) copies none (segmented upload).
    pub fn read_expedited(&self, index: u16, sub: u8, buf: &mut [u8; 4]) -> Result<(usize, usize), AbortCode> {
        let size = self.info(index, sub)?.size;
        let v = self.value(index, sub)?;
        if size > 4 {
            return Ok((size, 0));
        }
        *buf = (v as u32).to_le_bytes(); // zero-extended: the value fits its `size` bytes
        Ok((size, size))
    }

    /// An SDO (or RPDO) write, with the change rules of the module docs.
    pub fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        self.write_checked(index, sub, data, true)
    }

    /// A stored value written back after a reset (no change rules: the record was consistent when saved).
    pub fn load(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        self.write_checked(index, sub, data, false)
    }

    fn write_checked(&mut self, index: u16, sub: u8, data: &[u8], rules: bool) -> Result<(), AbortCode> {
        let e = self.entry(index, sub)?;
        if !e.access.writable() {
            return Err(AbortCode::WriteOfReadOnly);
        }
        check_len(data, e.max_size)?;
        let wide = data.iter().rev().fold(0u64, |v, &b| v << 8 | u64::from(b));
        // Every entry but 1FD0h's is at most 4 bytes (checked above): the truncation keeps it whole.
        let v = wide as u32;
        let _ = (v, rules, wide);
        match index {
            #[cfg(feature = "high-res-time")]
            0x1013 => {
                self.high_res.set(v);
                Ok(())
            }
            #[cfg(feature = "verify-config")]
            0x1020 => {
                self.verify_configuration[usize::from(sub) - 1] = v;
                Ok(())
            }
            #[cfg(feature = "emcy-consumer")]
            0x1028 => self.emcy.set(sub, v, rules),
            #[cfg(feature = "mpdo")]
            0x1FA0 => {
                self.mpdo_scanner[usize::from(sub) - 1] = v;
                Ok(())
            }
            #[cfg(feature = "mpdo")]
            0x1FD0 => {
                self.mpdo_dispatch[usize::from(sub) - 1] = wide;
                Ok(())
            }
            _ => Err(AbortCode::WriteOfReadOnly),
        }
    }
}
