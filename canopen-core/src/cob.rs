//! Node-IDs, the pre-defined connection set and the COB-ID entry layout (COB-01..COB-17).
//!
//! Implemented: COB-01 (function code ‖ node-ID), COB-02 ([`NodeId`] 1..127, 0 = broadcast), COB-03..COB-08
//! (the default identifiers of [`FunctionCode`]), COB-11 (11-bit only), COB-13 ([`is_restricted`]), COB-14 and
//! COB-15 ([`CobIdEntry`] with the frame bit refused). COB-16 (no ID change while valid) is a rule of each
//! COB-ID object's write path and is enforced there with [`CobIdEntry::check_change`]. COB-09/10/12 are
//! properties of the node as a whole (only the COBs a node supports get identifiers; defaults apply after
//! reset communication).

use crate::abort::AbortCode;

/// A CANopen node-ID, 1..=127 (COB-02).
///
/// ```
/// use canopen_core::NodeId;
/// assert_eq!(NodeId::new(5).map(NodeId::get), Some(5));
/// assert!(NodeId::new(0).is_none());
/// assert!(NodeId::new(128).is_none());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct NodeId(u8);

impl NodeId {
    /// A node-ID if `id` is in 1..=127.
    ///
    /// ```
    /// # use canopen_core::NodeId;
    /// assert!(NodeId::new(127).is_some());
    /// ```
    pub const fn new(id: u8) -> Option<Self> {
        if id >= 1 && id <= 127 {
            Some(NodeId(id))
        } else {
            None
        }
    }

    /// The raw value.
    ///
    /// ```
    /// # use canopen_core::NodeId;
    /// assert_eq!(NodeId::new(3).unwrap().get(), 3);
    /// ```
    pub const fn get(self) -> u8 {
        self.0
    }
}

/// The function codes of the pre-defined connection set (COB-01, COB-03..COB-08; 000 §7.3.3 Tables 38–39).
///
/// The 11-bit CAN-ID is `function code << 7 | node-ID`.
///
/// ```
/// use canopen_core::{cob::FunctionCode, NodeId};
/// let n = NodeId::new(5).unwrap();
/// assert_eq!(FunctionCode::NmtErrorControl.cob_id(n), 0x705);
/// assert_eq!(FunctionCode::SdoRx.cob_id(n), 0x605);
/// assert_eq!(FunctionCode::of(0x185), Some((FunctionCode::Tpdo1, 5)));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u8)]
pub enum FunctionCode {
    /// 0000b: NMT node control (000h, node part 0).
    Nmt = 0b0000,
    /// 0001b: SYNC (080h) and EMCY (081h–0FFh).
    SyncEmcy = 0b0001,
    /// 0010b: TIME (100h).
    Time = 0b0010,
    /// 0011b: TPDO1 (181h–1FFh).
    Tpdo1 = 0b0011,
    /// 0100b: RPDO1 (201h–27Fh).
    Rpdo1 = 0b0100,
    /// 0101b: TPDO2.
    Tpdo2 = 0b0101,
    /// 0110b: RPDO2.
    Rpdo2 = 0b0110,
    /// 0111b: TPDO3.
    Tpdo3 = 0b0111,
    /// 1000b: RPDO3.
    Rpdo3 = 0b1000,
    /// 1001b: TPDO4.
    Tpdo4 = 0b1001,
    /// 1010b: RPDO4.
    Rpdo4 = 0b1010,
    /// 1011b: SDO server → client (580h + node), device view (COB-07).
    SdoTx = 0b1011,
    /// 1100b: SDO client → server (600h + node), device view (COB-07).
    SdoRx = 0b1100,
    /// 1110b: NMT error control: boot-up, heartbeat, node guarding (700h + node, COB-08).
    NmtErrorControl = 0b1110,
}

impl FunctionCode {
    /// The default CAN-ID of this function for `node` (COB-01).
    ///
    /// ```
    /// # use canopen_core::{cob::FunctionCode, NodeId};
    /// assert_eq!(FunctionCode::SyncEmcy.cob_id(NodeId::new(9).unwrap()), 0x089);
    /// ```
    pub const fn cob_id(self, node: NodeId) -> u16 {
        ((self as u16) << 7) | node.get() as u16
    }

    /// Splits a CAN-ID into function code and node part; `None` for function codes 1101b and 1111b,
    /// which the pre-defined set does not use.
    ///
    /// ```
    /// # use canopen_core::cob::FunctionCode;
    /// assert_eq!(FunctionCode::of(0x000), Some((FunctionCode::Nmt, 0)));
    /// assert_eq!(FunctionCode::of(0x7E5), None);
    /// ```
    pub const fn of(cob_id: u16) -> Option<(FunctionCode, u8)> {
        let node = (cob_id & 0x7F) as u8;
        let fc = match (cob_id >> 7) & 0xF {
            0b0000 => FunctionCode::Nmt,
            0b0001 => FunctionCode::SyncEmcy,
            0b0010 => FunctionCode::Time,
            0b0011 => FunctionCode::Tpdo1,
            0b0100 => FunctionCode::Rpdo1,
            0b0101 => FunctionCode::Tpdo2,
            0b0110 => FunctionCode::Rpdo2,
            0b0111 => FunctionCode::Tpdo3,
            0b1000 => FunctionCode::Rpdo3,
            0b1001 => FunctionCode::Tpdo4,
            0b1010 => FunctionCode::Rpdo4,
            0b1011 => FunctionCode::SdoTx,
            0b1100 => FunctionCode::SdoRx,
            0b1110 => FunctionCode::NmtErrorControl,
            _ => return None,
        };
        Some((fc, node))
    }
}

/// NMT node control CAN-ID (COB-03).
pub const NMT_ID: u16 = 0x000;
/// Default SYNC CAN-ID (COB-03).
pub const SYNC_ID: u16 = 0x080;
/// Default TIME CAN-ID (COB-03).
pub const TIME_ID: u16 = 0x100;
/// LSS master → slave (CiA 305).
pub const LSS_MASTER_ID: u16 = 0x7E5;
/// LSS slave → master (CiA 305).
pub const LSS_SLAVE_ID: u16 = 0x7E4;

/// Whether `can_id` is one of the restricted CAN-IDs that must never be assigned to SYNC, TIME, EMCY, PDO or
/// SDO (COB-13, 000 §7.3.5 Table 40): 000h, 001h–07Fh, 101h–180h, 581h–5FFh, 601h–67Fh, 6E0h–6FFh,
/// 701h–77Fh, 780h–7FFh.
///
/// ```
/// use canopen_core::cob::is_restricted;
/// assert!(is_restricted(0x000));
/// assert!(is_restricted(0x705));
/// assert!(!is_restricted(0x080)); // SYNC
/// assert!(!is_restricted(0x181)); // TPDO1 of node 1
/// assert!(is_restricted(0x180));
/// ```
pub const fn is_restricted(can_id: u16) -> bool {
    matches!(can_id,
        0x000..=0x07F | 0x101..=0x180 | 0x581..=0x5FF | 0x601..=0x67F | 0x6E0..=0x6FF | 0x701..=0x7FF)
}

/// A COB-ID entry as stored in 1005h, 1012h, 1014h, 1028h, 1200h+, 1400h+, 1800h+ (COB-14, DT-22).
///
/// Bit 31 and bit 30 are object-specific flags (valid, gen, consume/produce, dyn, RTR), bit 29 is the frame
/// bit (1 = 29-bit), bits 10–0 the 11-bit CAN-ID.
///
/// ```
/// use canopen_core::cob::CobIdEntry;
/// let e = CobIdEntry::from_raw(0x8000_0180);
/// assert!(e.bit31());
/// assert_eq!(e.can_id(), 0x180);
/// assert_eq!(e.raw(), 0x8000_0180);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CobIdEntry(u32);

impl CobIdEntry {
    /// Bit 31 (valid/invalid, consume, ...).
    pub const BIT31: u32 = 1 << 31;
    /// Bit 30 (RTR, gen, produce, dyn, ...).
    pub const BIT30: u32 = 1 << 30;
    /// Bit 29: 29-bit frame.
    pub const FRAME: u32 = 1 << 29;

    /// Wraps a raw UNSIGNED32.
    ///
    /// ```
    /// # use canopen_core::cob::CobIdEntry;
    /// assert_eq!(CobIdEntry::from_raw(0x80).can_id(), 0x80);
    /// ```
    pub const fn from_raw(raw: u32) -> Self {
        CobIdEntry(raw)
    }

    /// Builds an entry from flags and an 11-bit CAN-ID.
    ///
    /// ```
    /// # use canopen_core::cob::CobIdEntry;
    /// assert_eq!(CobIdEntry::new(true, false, 0x200).raw(), 0x8000_0200);
    /// ```
    pub const fn new(bit31: bool, bit30: bool, can_id: u16) -> Self {
        let mut raw = (can_id & 0x7FF) as u32;
        if bit31 {
            raw |= Self::BIT31;
        }
        if bit30 {
            raw |= Self::BIT30;
        }
        CobIdEntry(raw)
    }

    /// The raw UNSIGNED32.
    pub const fn raw(self) -> u32 {
        self.0
    }

    /// The raw UNSIGNED32, to store a new value in place (the profile's one COB-ID write, `profile::dict`).
    pub(crate) fn raw_mut(&mut self) -> &mut u32 {
        &mut self.0
    }

    /// Bit 31.
    pub const fn bit31(self) -> bool {
        self.0 & Self::BIT31 != 0
    }

    /// Bit 30.
    pub const fn bit30(self) -> bool {
        self.0 & Self::BIT30 != 0
    }

    /// Bit 29, the frame bit (29-bit identifier).
    pub const fn is_extended(self) -> bool {
        self.0 & Self::FRAME != 0
    }

    /// The 11-bit CAN-ID (bits 10–0).
    pub const fn can_id(self) -> u16 {
        (self.0 & 0x7FF) as u16
    }

    /// Checks a new value written by SDO against this (current) value, for an object whose "active" flag is
    /// `active(self)`: the frame bit is refused (COB-15, this stack is 11-bit only), an 11-bit entry with
    /// bits 28–11 set is refused, and the CAN-ID bits may not change while the COB is active (COB-16).
    /// Every refusal is abort 0609 0030h.
    ///
    /// ```
    /// use canopen_core::{cob::CobIdEntry, od::AbortCode};
    /// let cur = CobIdEntry::from_raw(0x0000_0181); // valid TPDO
    /// let valid = |e: CobIdEntry| !e.bit31();
    /// assert_eq!(cur.check_change(0x0000_0182, valid), Err(AbortCode::InvalidValue));
    /// assert_eq!(cur.check_change(0x8000_0181, valid), Ok(CobIdEntry::from_raw(0x8000_0181)));
    /// assert_eq!(cur.check_change(0x2000_0181, valid), Err(AbortCode::InvalidValue));
    /// ```
    pub fn check_change(self, new_raw: u32, active: impl Fn(CobIdEntry) -> bool) -> Result<CobIdEntry, AbortCode> {
        let new = CobIdEntry(new_raw);
        if new.is_extended() || new_raw & 0x1FFF_F800 != 0 {
            return Err(AbortCode::InvalidValue);
        }
        if active(self) && active(new) && new.can_id() != self.can_id() {
            return Err(AbortCode::InvalidValue);
        }
        Ok(new)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pre-defined connection set for node 5: NMT 000h, SYNC 080h, EMCY 085h, TIME 100h, TPDO1..4
    /// 185h..485h, RPDO1..4 205h..505h, SDO 585h/605h, NMT error control 705h.
    #[test]
    fn default_identifiers_vectors() {
        let n = NodeId::new(5).unwrap();
        assert_eq!(FunctionCode::Nmt.cob_id(NodeId::new(1).unwrap()) & !0x7F, NMT_ID);
        assert_eq!(FunctionCode::SyncEmcy.cob_id(n), 0x085);
        assert_eq!(FunctionCode::Time.cob_id(n) & !0x7F, TIME_ID);
        let tpdo = [FunctionCode::Tpdo1, FunctionCode::Tpdo2, FunctionCode::Tpdo3, FunctionCode::Tpdo4];
        let rpdo = [FunctionCode::Rpdo1, FunctionCode::Rpdo2, FunctionCode::Rpdo3, FunctionCode::Rpdo4];
        for (k, fc) in tpdo.iter().enumerate() {
            assert_eq!(fc.cob_id(n), 0x180 + 0x100 * k as u16 + 5);
        }
        for (k, fc) in rpdo.iter().enumerate() {
            assert_eq!(fc.cob_id(n), 0x200 + 0x100 * k as u16 + 5);
        }
        assert_eq!(FunctionCode::SdoTx.cob_id(n), 0x585);
        assert_eq!(FunctionCode::SdoRx.cob_id(n), 0x605);
        assert_eq!(FunctionCode::NmtErrorControl.cob_id(n), 0x705);
    }

    #[test]
    fn function_code_round_trips_every_id() {
        for id in 0..=0x7FFu16 {
            if let Some((fc, node)) = FunctionCode::of(id) {
                assert_eq!(((fc as u16) << 7) | node as u16, id);
            } else {
                assert!(matches!(id >> 7, 0b1101 | 0b1111));
            }
        }
    }

    /// COB-13: exactly the Table 40 ranges are restricted.
    #[test]
    fn restricted_ranges_cob13() {
        let table: [(u16, u16); 6] =
            [(0x000, 0x07F), (0x101, 0x180), (0x581, 0x5FF), (0x601, 0x67F), (0x6E0, 0x6FF), (0x701, 0x7FF)];
        for id in 0..=0x7FFu16 {
            let expected = table.iter().any(|&(lo, hi)| (lo..=hi).contains(&id));
            assert_eq!(is_restricted(id), expected, "{id:03X}");
        }
        // The defaults that a device allocates itself are never restricted.
        for node in 1..=127u8 {
            let n = NodeId::new(node).unwrap();
            for fc in [FunctionCode::SyncEmcy, FunctionCode::Tpdo1, FunctionCode::Rpdo4] {
                assert!(!is_restricted(fc.cob_id(n)));
            }
        }
    }

    /// COB-15/COB-16.
    #[test]
    fn cob_id_entry_change_rules() {
        let valid = |e: CobIdEntry| !e.bit31();
        let cur = CobIdEntry::from_raw(0x0000_0181);
        // Invalidate first, then change, then re-validate: allowed.
        let off = cur.check_change(0x8000_0181, valid).unwrap();
        let moved = off.check_change(0x8000_0191, valid).unwrap();
        assert_eq!(moved.check_change(0x0000_0191, valid), Ok(CobIdEntry::from_raw(0x191)));
        // Frame bit always refused, even when invalid.
        assert_eq!(off.check_change(0xA000_0181, valid), Err(AbortCode::InvalidValue));
        // Bits 28–11 set on an 11-bit entry.
        assert_eq!(off.check_change(0x8000_0981, valid), Err(AbortCode::InvalidValue));
    }
}
