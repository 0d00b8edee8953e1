//! Multiplexed PDOs (MPDO-01..05, CiA 301 §7.2.3, §7.5.2.36/38/39/40), the Cargo feature `mpdo`: the
//! frame, the mapping values that make a PDO an MPDO, and the object scanner / dispatching list entries.
//!
//! - [`Mpdo`] (MPDO-01, fig. 19): 8 bytes; byte 0 bit 7 = address type f (0 source, 1 destination), bits
//!   6–0 the node-ID (DAM: the consumer, 0 = every DAM consumer; SAM: the producer, 0 reserved); bytes 1–2
//!   index (LE), byte 3 sub-index (the multiplexer); bytes 4–7 data (at most 4 bytes). A frame of another
//!   length, or a SAM frame with node-ID 0, is not an MPDO and is ignored (CAN-07).
//! - [`AddressMode::of_mapping`] (MPDO-05, PDO-30 Tables 69/73): mapping sub 00h FEh = SAM-MPDO, FFh =
//!   DAM-MPDO; the mapping entries are then not used.
//! - [`ScannerEntry`] (MPDO-03, 1FA0h–1FCFh, UNSIGNED32, fig. 75): bits 31–24 block size, 23–8 index, 7–0
//!   sub-index; the SAM producer sends only what one of its entries covers.
//! - [`DispatchEntry`] (MPDO-03, 1FD0h–1FFFh, UNSIGNED64, fig. 76): bits 63–56 block size, 55–40 local
//!   index, 39–32 local sub-index, 31–16 producer index, 15–8 producer sub-index, 7–0 producer node-ID; a
//!   SAM consumer writes what one of its entries maps to a local object. An entry of value 0 is not
//!   configured (MPDO-03). The seed translation of CiA 301 has the text of §7.5.2.39/40 but not the two
//!   figures; the bit layout above is CiA 301's fig. 75/76 as the lely stack reads them (`co_dev_chk_sam_mpdo`,
//!   `co_dev_map_sam_mpdo`). Block size: the number of consecutive sub-indices an entry covers from its
//!   first one (§7.5.2.40's example: producer sub 1, local sub 11, block 9 maps 1–9 to 11–19); a block
//!   size of 0 covers the one sub-index (as lely reads it).
//!
//! What the node does with them (`Node::send_dam_mpdo`, `Node::send_sam_mpdo`, and the reception path) is
//! in the node's MPDO wiring; the checklist rows there: MPDO-02 (DAM consumer, EMCY 8230h EEC-18), MPDO-03
//! (SAM producer and consumer), MPDO-04 (event-driven only, inhibit time).

use crate::abort::AbortCode;
use crate::wire::WireError;

/// Why the node did not send an MPDO (`Node::send_dam_mpdo`, `Node::send_sam_mpdo`).
///
/// ```
/// use canopen_core::pdo::mpdo::MpdoRefused;
/// assert_ne!(MpdoRefused::Inhibited, MpdoRefused::NotMpdo);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum MpdoRefused {
    /// The node is not Operational (PDO-04).
    NotOperational,
    /// No such TPDO, or it is not valid, not event-driven (FEh/FFh, MPDO-04) or not an MPDO of this kind.
    NotMpdo,
    /// Its inhibit time still runs (MPDO-04): nothing is held back, send again later.
    Inhibited,
    /// DAM: a destination node-ID above 127.
    InvalidNode,
    /// More than 4 data bytes (DAM), or an object larger than 4 bytes (SAM): an MPDO carries at most 4.
    TooLong,
    /// SAM: no entry of the object scanner list 1FA0h covers the object (MPDO-03).
    NotScanned,
    /// SAM: the object cannot be sent (it does not exist, 0602 0000h / 0609 0011h, or is not
    /// TPDO-mappable, 0604 0041h).
    Object(AbortCode),
}

/// Address type f of an MPDO (MPDO-01), and the kind of MPDO a PDO's mapping makes it (MPDO-05).
///
/// ```
/// use canopen_core::pdo::mpdo::AddressMode;
/// assert_eq!(AddressMode::of_mapping(0xFE), Some(AddressMode::Source));
/// assert_eq!(AddressMode::of_mapping(0xFF), Some(AddressMode::Destination));
/// assert_eq!(AddressMode::of_mapping(8), None); // a plain PDO
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum AddressMode {
    /// f = 0, SAM: the node-ID is the producer's, the multiplexer its object (MPDO-03).
    Source,
    /// f = 1, DAM: the node-ID is the consumer's (0 = all), the multiplexer the consumer's object (MPDO-02).
    Destination,
}

impl AddressMode {
    /// Mapping sub 00h FEh (SAM-MPDO), FFh (DAM-MPDO); `None` for a count (PDO-30, MPDO-05).
    pub const fn of_mapping(count: u8) -> Option<Self> {
        match count {
            0xFE => Some(AddressMode::Source),
            0xFF => Some(AddressMode::Destination),
            _ => None,
        }
    }

    /// The mapping sub 00h value of this kind of MPDO.
    ///
    /// ```
    /// # use canopen_core::pdo::mpdo::AddressMode;
    /// assert_eq!(AddressMode::Source.mapping_count(), 0xFE);
    /// ```
    pub const fn mapping_count(self) -> u8 {
        match self {
            AddressMode::Source => 0xFE,
            AddressMode::Destination => 0xFF,
        }
    }
}

/// One MPDO frame (MPDO-01, CiA 301 fig. 19).
///
/// ```
/// use canopen_core::pdo::mpdo::{AddressMode, Mpdo};
/// // DAM to node 5: write 2000h:01 = 1234_5678h.
/// let f = Mpdo::parse(&[0x85, 0x00, 0x20, 0x01, 0x78, 0x56, 0x34, 0x12]).unwrap();
/// assert_eq!((f.mode, f.node, f.index, f.sub), (AddressMode::Destination, 5, 0x2000, 1));
/// assert_eq!(f.data, [0x78, 0x56, 0x34, 0x12]);
/// assert_eq!(f.emit(), [0x85, 0x00, 0x20, 0x01, 0x78, 0x56, 0x34, 0x12]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Mpdo {
    /// Address type f (byte 0 bit 7).
    pub mode: AddressMode,
    /// Byte 0 bits 6–0: the consumer's node-ID (DAM, 0 = all) or the producer's (SAM, 1–127).
    pub node: u8,
    /// Multiplexer index (bytes 1–2, LE).
    pub index: u16,
    /// Multiplexer sub-index (byte 3).
    pub sub: u8,
    /// Bytes 4–7: the value, little-endian, unused high bytes as sent.
    pub data: [u8; 4],
}

impl Mpdo {
    /// Parses a received payload: exactly 8 bytes (else [`WireError::Length`]); a SAM frame with node-ID 0
    /// is reserved ([`WireError::Value`]).
    ///
    /// ```
    /// use canopen_core::{pdo::mpdo::Mpdo, wire::WireError};
    /// assert_eq!(Mpdo::parse(&[0x85, 0x00, 0x20, 0x01]), Err(WireError::Length));
    /// assert_eq!(Mpdo::parse(&[0x00, 0x00, 0x20, 0x01, 0, 0, 0, 0]), Err(WireError::Value)); // SAM, node 0
    /// ```
    pub fn parse(data: &[u8]) -> Result<Self, WireError> {
        let b: &[u8; 8] = data.try_into().map_err(|_| WireError::Length)?;
        let mode = if b[0] & 0x80 != 0 { AddressMode::Destination } else { AddressMode::Source };
        let node = b[0] & 0x7F;
        if mode == AddressMode::Source && node == 0 {
            return Err(WireError::Value);
        }
        Ok(Mpdo { mode, node, index: u16::from_le_bytes([b[1], b[2]]), sub: b[3], data: [b[4], b[5], b[6], b[7]] })
    }

    /// The 8 bytes on the bus (the node-ID's bit 7 is not sent: it is f's place).
    pub const fn emit(&self) -> [u8; 8] {
        let f = match self.mode {
            AddressMode::Source => 0,
            AddressMode::Destination => 0x80,
        };
        let i = self.index.to_le_bytes();
        let d = self.data;
        [f | (self.node & 0x7F), i[0], i[1], self.sub, d[0], d[1], d[2], d[3]]
    }

    /// Whether a DAM-MPDO is for the DAM consumer `own` (its node-ID, or 0 = every consumer, MPDO-02).
    ///
    /// ```
    /// # use canopen_core::pdo::mpdo::{AddressMode, Mpdo};
    /// let f = Mpdo { mode: AddressMode::Destination, node: 0, index: 0x2000, sub: 0, data: [0; 4] };
    /// assert!(f.addresses(7));
    /// assert!(!Mpdo { node: 6, ..f }.addresses(7));
    /// ```
    pub const fn addresses(&self, own: u8) -> bool {
        matches!(self.mode, AddressMode::Destination) && (self.node == 0 || self.node == own)
    }
}

/// First sub-index `first` and block size `block` cover `sub` (0 counts as 1; the block ends at FFh).
const fn in_block(first: u8, block: u8, sub: u8) -> bool {
    let last = first as u16 + if block == 0 { 0 } else { block as u16 - 1 };
    sub >= first && sub as u16 <= last
}

/// One object scanner list entry (1FA0h–1FCFh sub 01h–FEh, MPDO-03): what the SAM producer may send.
///
/// ```
/// use canopen_core::pdo::mpdo::ScannerEntry;
/// // 6000h sub 01h..04h: block 4.
/// let e = ScannerEntry::from_raw(0x0460_0001);
/// assert_eq!((e.block, e.index, e.sub), (4, 0x6000, 1));
/// assert!(e.covers(0x6000, 4) && !e.covers(0x6000, 5) && !e.covers(0x6001, 1));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ScannerEntry {
    /// Bits 31–24: the number of consecutive sub-indices from `sub`.
    pub block: u8,
    /// Bits 23–8: the object's index.
    pub index: u16,
    /// Bits 7–0: the first sub-index.
    pub sub: u8,
}

impl ScannerEntry {
    /// Decodes the UNSIGNED32 value.
    pub const fn from_raw(raw: u32) -> Self {
        ScannerEntry { block: (raw >> 24) as u8, index: (raw >> 8) as u16, sub: raw as u8 }
    }

    /// Encodes as the UNSIGNED32 value.
    ///
    /// ```
    /// # use canopen_core::pdo::mpdo::ScannerEntry;
    /// assert_eq!(ScannerEntry { block: 1, index: 0x2000, sub: 3 }.raw(), 0x0120_0003);
    /// ```
    pub const fn raw(self) -> u32 {
        ((self.block as u32) << 24) | ((self.index as u32) << 8) | self.sub as u32
    }

    /// Whether the entry is configured and covers (`index`, `sub`).
    pub const fn covers(&self, index: u16, sub: u8) -> bool {
        self.raw() != 0 && self.index == index && in_block(self.sub, self.block, sub)
    }
}

/// Whether one entry of a scanner list covers (`index`, `sub`) (MPDO-03).
///
/// ```
/// use canopen_core::pdo::mpdo::scanned;
/// assert!(scanned(&[0, 0x0120_0003], 0x2000, 3));
/// assert!(!scanned(&[0, 0x0120_0003], 0x2000, 4));
/// ```
pub fn scanned(list: &[u32], index: u16, sub: u8) -> bool {
    list.iter().any(|&raw| ScannerEntry::from_raw(raw).covers(index, sub))
}

/// One object dispatching list entry (1FD0h–1FFFh sub 01h–FEh, MPDO-03): where the SAM consumer writes a
/// producer's object.
///
/// ```
/// use canopen_core::pdo::mpdo::DispatchEntry;
/// // §7.5.2.40's example: node 0Ah's 6000h sub 1..9 → local 2100h sub 11..19 (block 9).
/// let e = DispatchEntry::from_raw(0x0921_000B_6000_010A);
/// assert_eq!((e.block, e.local_index, e.local_sub), (9, 0x2100, 11));
/// assert_eq!((e.producer_index, e.producer_sub, e.producer_node), (0x6000, 1, 0x0A));
/// assert_eq!(e.target(0x0A, 0x6000, 9), Some((0x2100, 19)));
/// assert_eq!(e.target(0x0A, 0x6000, 10), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct DispatchEntry {
    /// Bits 63–56: the number of consecutive sub-indices.
    pub block: u8,
    /// Bits 55–40: the local object's index.
    pub local_index: u16,
    /// Bits 39–32: the local first sub-index.
    pub local_sub: u8,
    /// Bits 31–16: the producer's object index.
    pub producer_index: u16,
    /// Bits 15–8: the producer's first sub-index.
    pub producer_sub: u8,
    /// Bits 7–0: the producer's node-ID.
    pub producer_node: u8,
}

impl DispatchEntry {
    /// Decodes the UNSIGNED64 value.
    pub const fn from_raw(raw: u64) -> Self {
        DispatchEntry {
            block: (raw >> 56) as u8,
            local_index: (raw >> 40) as u16,
            local_sub: (raw >> 32) as u8,
            producer_index: (raw >> 16) as u16,
            producer_sub: (raw >> 8) as u8,
            producer_node: raw as u8,
        }
    }

    /// Encodes as the UNSIGNED64 value.
    ///
    /// ```
    /// # use canopen_core::pdo::mpdo::DispatchEntry;
    /// let e = DispatchEntry { block: 1, local_index: 0x2001, local_sub: 0, producer_index: 0x6000, producer_sub: 1, producer_node: 3 };
    /// assert_eq!(e.raw(), 0x0120_0100_6000_0103);
    /// ```
    pub const fn raw(self) -> u64 {
        ((self.block as u64) << 56)
            | ((self.local_index as u64) << 40)
            | ((self.local_sub as u64) << 32)
            | ((self.producer_index as u64) << 16)
            | ((self.producer_sub as u64) << 8)
            | self.producer_node as u64
    }

    /// The local (index, sub-index) for producer `node`'s (`index`, `sub`), if the entry is configured and
    /// covers it.
    pub const fn target(&self, node: u8, index: u16, sub: u8) -> Option<(u16, u8)> {
        if self.raw() == 0
            || self.producer_node != node
            || self.producer_index != index
            || !in_block(self.producer_sub, self.block, sub)
        {
            return None;
        }
        let local = self.local_sub as u16 + (sub - self.producer_sub) as u16;
        if local > 0xFF {
            return None; // the local block would run past sub-index FFh
        }
        Some((self.local_index, local as u8))
    }
}

/// The local object the first matching entry of a dispatching list gives producer `node`'s (`index`,
/// `sub`) (MPDO-03).
///
/// ```
/// use canopen_core::pdo::mpdo::dispatch;
/// let list = [0, 0x0120_0100_6000_0103];
/// assert_eq!(dispatch(&list, 3, 0x6000, 1), Some((0x2001, 0)));
/// assert_eq!(dispatch(&list, 4, 0x6000, 1), None); // another producer
/// ```
pub fn dispatch(list: &[u64], node: u8, index: u16, sub: u8) -> Option<(u16, u8)> {
    list.iter().find_map(|&raw| DispatchEntry::from_raw(raw).target(node, index, sub))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// MPDO-01: frames typed from fig. 19's field list, both address types.
    #[test]
    fn frame_layout_mpdo_01() {
        // SAM from node 0Ah: its 6000h:01 = 0x000000AB.
        let sam = [0x0A, 0x00, 0x60, 0x01, 0xAB, 0x00, 0x00, 0x00];
        let f = Mpdo::parse(&sam).unwrap();
        assert_eq!(f, Mpdo { mode: AddressMode::Source, node: 10, index: 0x6000, sub: 1, data: [0xAB, 0, 0, 0] });
        assert_eq!(f.emit(), sam);
        // DAM to every consumer (addr 0): 2001h:02 = 0x1122.
        let dam = [0x80, 0x01, 0x20, 0x02, 0x22, 0x11, 0x00, 0x00];
        let f = Mpdo::parse(&dam).unwrap();
        assert_eq!((f.mode, f.node, f.index, f.sub), (AddressMode::Destination, 0, 0x2001, 2));
        assert!(f.addresses(1) && f.addresses(127));
        assert_eq!(f.emit(), dam);
        // DAM to node 7Fh.
        let f = Mpdo::parse(&[0xFF, 0x00, 0x20, 0x00, 1, 2, 3, 4]).unwrap();
        assert_eq!((f.node, f.addresses(0x7F), f.addresses(0x7E)), (0x7F, true, false));
        // A SAM frame never addresses a consumer by node-ID.
        assert!(!Mpdo::parse(&sam).unwrap().addresses(10));
    }

    /// MPDO-01: anything but 8 bytes is not an MPDO; SAM with addr 0 is reserved.
    #[test]
    fn malformed_frames_are_refused() {
        for n in 0..8 {
            assert_eq!(Mpdo::parse(&[0x85; 8][..n]), Err(WireError::Length), "{n} bytes");
        }
        assert_eq!(Mpdo::parse(&[0x80; 9]), Err(WireError::Length));
        assert_eq!(Mpdo::parse(&[0x00, 0x00, 0x20, 0x00, 0, 0, 0, 0]), Err(WireError::Value));
    }

    /// MPDO-03: an entry of value 0 is not configured, even for 0000h:00; blocks end at sub-index FFh.
    #[test]
    fn list_entries_mpdo_03() {
        assert!(!ScannerEntry::from_raw(0).covers(0, 0));
        assert!(ScannerEntry::from_raw(0x0000_0100).covers(0x0001, 0)); // block 0 = one sub-index
        assert!(!ScannerEntry::from_raw(0x0000_0100).covers(0x0001, 1));
        let e = ScannerEntry::from_raw(0xFF20_00F0); // 2000h:F0 block FFh: F0..FF
        assert!(e.covers(0x2000, 0xFF) && !e.covers(0x2000, 0xEF));
        assert_eq!(DispatchEntry::from_raw(0).target(0, 0, 0), None);
        // Local F8h + 9 sub-indices would pass FFh: the ones beyond are not mapped.
        let d = DispatchEntry::from_raw(0x0921_00F8_6000_0105);
        assert_eq!(d.target(5, 0x6000, 8), Some((0x2100, 0xFF)));
        assert_eq!(d.target(5, 0x6000, 9), None);
        assert_eq!(d.target(5, 0x6000, 0), None);
    }
}
