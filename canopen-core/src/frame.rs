//! The CAN frame the core consumes and produces (CAN-01, CAN-06, COB-11).
//!
//! CANopen's pre-defined connection set uses 11-bit identifiers only, so [`CanFrame`] carries an 11-bit
//! identifier, 0–8 data bytes, and the RTR flag. It implements [`embedded_can::Frame`], so any
//! `embedded-can` driver's frames convert with [`CanFrame::from_frame`] / [`CanFrame::to_frame`]; a 29-bit
//! frame from the bus does not convert (the stack ignores it, CAN-01).

use embedded_can::{Frame, Id, StandardId};

/// Largest 11-bit identifier.
pub const MAX_STANDARD_ID: u16 = 0x7FF;

/// A classic CAN frame with an 11-bit identifier.
///
/// ```
/// use canopen_core::CanFrame;
/// let f = CanFrame::new(0x705, &[0x7F]).unwrap();
/// assert_eq!(f.cob_id(), 0x705);
/// assert_eq!(f.data(), &[0x7F]);
/// assert!(!f.is_rtr());
/// ```
#[derive(Clone, Copy, Eq)]
pub struct CanFrame {
    id: u16,
    len: Len,
    rtr: bool,
    data: [u8; 8],
}

/// Every field, as the derived comparison, but without its early exits: the header as one word and the
/// eight data bytes as another (the driver compares the sent frame with the queue's front once per frame:
/// `Node::transmitted`).
impl PartialEq for CanFrame {
    #[inline]
    fn eq(&self, other: &Self) -> bool {
        let header = |f: &CanFrame| u32::from(f.id) | u32::from(f.len as u8) << 16 | u32::from(f.rtr) << 24;
        (header(self) == header(other)) & (u64::from_ne_bytes(self.data) == u64::from_ne_bytes(other.data))
    }
}

/// The fields [`PartialEq`] compares, in declaration order (what `derive(Hash)` hashed).
impl core::hash::Hash for CanFrame {
    fn hash<H: core::hash::Hasher>(&self, state: &mut H) {
        self.id.hash(state);
        self.len.hash(state);
        self.rtr.hash(state);
        self.data.hash(state);
    }
}

/// A data length 0–8 as a type whose values the compiler knows: reading `len` then needs no range check, so
/// [`CanFrame::data`] has no bounds check (and no panic path) where a frame is read.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
enum Len {
    L0,
    L1,
    L2,
    L3,
    L4,
    L5,
    L6,
    L7,
    L8,
}

impl Len {
    /// `n` bytes, 8 for anything above.
    const fn at_most_8(n: usize) -> Len {
        match n {
            0 => Len::L0,
            1 => Len::L1,
            2 => Len::L2,
            3 => Len::L3,
            4 => Len::L4,
            5 => Len::L5,
            6 => Len::L6,
            7 => Len::L7,
            _ => Len::L8,
        }
    }

    const fn get(self) -> u8 {
        self as u8
    }
}

impl CanFrame {
    /// A data frame; `None` if the identifier is above 7FFh or there are more than 8 bytes.
    ///
    /// ```
    /// # use canopen_core::CanFrame;
    /// assert!(CanFrame::new(0x800, &[]).is_none());
    /// assert!(CanFrame::new(0x100, &[0; 9]).is_none());
    /// ```
    pub fn new(cob_id: u16, data: &[u8]) -> Option<Self> {
        if cob_id > MAX_STANDARD_ID || data.len() > 8 {
            return None;
        }
        let mut buf = [0u8; 8];
        buf[..data.len()].copy_from_slice(data);
        Some(CanFrame { id: cob_id, len: Len::at_most_8(data.len()), rtr: false, data: buf })
    }

    /// A remote (RTR) frame with the given DLC; `None` if the identifier or DLC is out of range.
    ///
    /// ```
    /// # use canopen_core::CanFrame;
    /// let f = CanFrame::new_rtr(0x705, 1).unwrap();
    /// assert!(f.is_rtr());
    /// assert_eq!(f.dlc(), 1);
    /// assert!(f.data().is_empty());
    /// ```
    pub fn new_rtr(cob_id: u16, dlc: u8) -> Option<Self> {
        if cob_id > MAX_STANDARD_ID || dlc > 8 {
            return None;
        }
        Some(CanFrame { id: cob_id, len: Len::at_most_8(dlc as usize), rtr: true, data: [0; 8] })
    }

    /// A data frame from an identifier the stack computed itself and a full 8-byte payload of which the
    /// first `len` bytes are used. Identifier bits above 11 and lengths above 8 are masked/clamped, so this
    /// never fails; use it only for identifiers that were validated when they were configured.
    ///
    /// ```
    /// # use canopen_core::CanFrame;
    /// let f = CanFrame::from_parts(0x585, [0x60, 0x17, 0x10, 0, 0, 0, 0, 0], 8);
    /// assert_eq!(f.dlc(), 8);
    /// ```
    #[inline]
    pub const fn from_parts(cob_id: u16, data: [u8; 8], len: u8) -> Self {
        CanFrame { id: cob_id & MAX_STANDARD_ID, len: Len::at_most_8(len as usize), rtr: false, data }
    }

    /// The 11-bit identifier (the COB-ID's CAN-ID part).
    ///
    /// ```
    /// # use canopen_core::CanFrame;
    /// assert_eq!(CanFrame::new(0x80, &[]).unwrap().cob_id(), 0x80);
    /// ```
    #[inline]
    pub const fn cob_id(&self) -> u16 {
        self.id
    }

    /// Whether this is a remote transmission request.
    ///
    /// ```
    /// # use canopen_core::CanFrame;
    /// assert!(!CanFrame::new(0x80, &[]).unwrap().is_rtr());
    /// ```
    #[inline]
    pub const fn is_rtr(&self) -> bool {
        self.rtr
    }

    /// The DLC: the number of data bytes, or for an RTR frame the requested length.
    ///
    /// ```
    /// # use canopen_core::CanFrame;
    /// assert_eq!(CanFrame::new(0x80, &[1, 2]).unwrap().dlc(), 2);
    /// ```
    #[inline]
    pub const fn dlc(&self) -> u8 {
        self.len.get()
    }

    /// The data bytes (empty for an RTR frame).
    ///
    /// ```
    /// # use canopen_core::CanFrame;
    /// assert_eq!(CanFrame::new(0x80, &[1, 2]).unwrap().data(), &[1, 2]);
    /// ```
    #[inline]
    pub fn data(&self) -> &[u8] {
        if self.rtr {
            &[]
        } else {
            &self.data[..self.len.get() as usize]
        }
    }

    /// The data bytes padded with zeros to 8 (reserved bytes are 0 on the wire, SDO-02).
    ///
    /// ```
    /// # use canopen_core::CanFrame;
    /// assert_eq!(CanFrame::new(0x80, &[1]).unwrap().padded(), [1, 0, 0, 0, 0, 0, 0, 0]);
    /// ```
    #[inline]
    pub const fn padded(&self) -> [u8; 8] {
        self.data
    }

    /// [`padded`](Self::padded) in place: a reference to the frame's 8 data bytes, for a callee that reads
    /// them where they are (the node's RPDO path) instead of a copy on the caller's stack.
    #[inline]
    pub(crate) const fn padded_ref(&self) -> &[u8; 8] {
        &self.data
    }

    /// Converts a driver's frame; `None` for a 29-bit frame (CAN-01: the stack ignores them).
    ///
    /// ```
    /// # use canopen_core::CanFrame;
    /// let f = CanFrame::new(0x181, &[1]).unwrap();
    /// let copy: CanFrame = CanFrame::from_frame(&f).unwrap();
    /// assert_eq!(copy, f);
    /// ```
    pub fn from_frame<F: Frame>(frame: &F) -> Option<Self> {
        let Id::Standard(id) = frame.id() else {
            return None;
        };
        if frame.is_remote_frame() {
            CanFrame::new_rtr(id.as_raw(), frame.dlc().min(8) as u8)
        } else {
            CanFrame::new(id.as_raw(), frame.data())
        }
    }

    /// Converts into a driver's frame type.
    ///
    /// ```
    /// # use canopen_core::CanFrame;
    /// let f = CanFrame::new(0x181, &[1]).unwrap();
    /// let out: Option<CanFrame> = f.to_frame();
    /// assert_eq!(out, Some(f));
    /// ```
    pub fn to_frame<F: Frame>(&self) -> Option<F> {
        let id = StandardId::new(self.id)?;
        if self.rtr {
            F::new_remote(id, usize::from(self.len.get()))
        } else {
            F::new(id, self.data())
        }
    }
}

impl Frame for CanFrame {
    fn new(id: impl Into<Id>, data: &[u8]) -> Option<Self> {
        match id.into() {
            Id::Standard(id) => CanFrame::new(id.as_raw(), data),
            Id::Extended(_) => None,
        }
    }

    fn new_remote(id: impl Into<Id>, dlc: usize) -> Option<Self> {
        match id.into() {
            Id::Standard(id) if dlc <= 8 => CanFrame::new_rtr(id.as_raw(), dlc as u8),
            _ => None,
        }
    }

    fn is_extended(&self) -> bool {
        false
    }

    fn is_remote_frame(&self) -> bool {
        self.rtr
    }

    fn id(&self) -> Id {
        // `id` is always <= 7FFh (checked or masked by every constructor).
        Id::Standard(StandardId::new(self.id).unwrap_or(StandardId::ZERO))
    }

    fn dlc(&self) -> usize {
        usize::from(self.len.get())
    }

    fn data(&self) -> &[u8] {
        CanFrame::data(self)
    }
}

#[cfg(feature = "defmt")]
impl defmt::Format for CanFrame {
    /// candump-like, as `Debug`: `705 [1] 7F`, `705 [RTR]`.
    fn format(&self, f: defmt::Formatter<'_>) {
        if self.rtr {
            defmt::write!(f, "{=u16:03X} [RTR]", self.id)
        } else {
            defmt::write!(f, "{=u16:03X} [{=u8}] {=[u8]:02X}", self.id, self.len.get(), self.data())
        }
    }
}

impl core::fmt::Debug for CanFrame {
    /// candump-like: `705 [1] 7F`, `705 [RTR]`.
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "{:03X} ", self.id)?;
        if self.rtr {
            return write!(f, "[RTR]");
        }
        write!(f, "[{}]", self.len.get())?;
        for b in self.data() {
            write!(f, " {b:02X}")?;
        }
        Ok(())
    }
}

impl core::fmt::Display for CanFrame {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        core::fmt::Debug::fmt(self, f)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// Frames are equal exactly when every field is: the identifier (all 11 bits), the length, the RTR bit
    /// and each of the eight data bytes (also those beyond the length), as the derived comparison was.
    #[test]
    fn equal_exactly_when_every_field_is() {
        let base = CanFrame::from_parts(0x7FF, [1, 2, 3, 4, 5, 6, 7, 8], 8);
        assert_eq!(base, CanFrame::from_parts(0x7FF, [1, 2, 3, 4, 5, 6, 7, 8], 8));
        let mut others = std::vec![
            CanFrame::from_parts(0x3FF, base.data, 8),
            CanFrame::from_parts(0x7FE, base.data, 8),
            CanFrame::from_parts(0x7FF, base.data, 7),
            CanFrame { rtr: true, ..base },
        ];
        for i in 0..8 {
            let mut data = base.data;
            data[i] ^= 0x80;
            others.push(CanFrame::from_parts(0x7FF, data, 8));
        }
        // Bytes beyond the length count too.
        let short = CanFrame::from_parts(0x100, [9, 0, 0, 0, 0, 0, 0, 0], 1);
        assert_ne!(short, CanFrame::from_parts(0x100, [9, 0, 0, 0, 0, 0, 0, 1], 1));
        for other in others {
            assert_ne!(base, other, "{other:?}");
            assert_ne!(other, base);
        }
        // Identifier, length and RTR bit never stand in for one another: every pair of distinct headers (an
        // identifier with each single bit, and 0; every length; both RTR values) compares unequal.
        let ids = core::iter::once(0).chain((0..11).map(|b| 1u16 << b));
        let headers: std::vec::Vec<_> =
            ids.flat_map(|id| (0..=8u8).flat_map(move |len| [false, true].map(|rtr| (id, len, rtr)))).collect();
        for &(id, len, rtr) in &headers {
            for &(id2, len2, rtr2) in &headers {
                let a = CanFrame { rtr, ..CanFrame::from_parts(id, [0; 8], len) };
                let b = CanFrame { rtr: rtr2, ..CanFrame::from_parts(id2, [0; 8], len2) };
                assert_eq!(a == b, (id, len, rtr) == (id2, len2, rtr2), "{a:?} {b:?}");
            }
        }
    }

    #[test]
    fn rejects_out_of_range() {
        assert!(CanFrame::new(0x800, &[]).is_none());
        assert!(CanFrame::new_rtr(0x100, 9).is_none());
        assert!(<CanFrame as Frame>::new(embedded_can::ExtendedId::new(0x100).unwrap(), &[]).is_none());
    }

    #[test]
    fn debug_is_candump_like() {
        struct S(heapless::String<32>);
        impl core::fmt::Write for S {
            fn write_str(&mut self, s: &str) -> core::fmt::Result {
                self.0.push_str(s).map_err(|_| core::fmt::Error)
            }
        }
        let mut s = S(heapless::String::new());
        core::fmt::write(&mut s, format_args!("{:?}", CanFrame::new(0x705, &[0x7F]).unwrap())).unwrap();
        assert_eq!(s.0.as_str(), "705 [1] 7F");
        let mut s = S(heapless::String::new());
        core::fmt::write(&mut s, format_args!("{:?}", CanFrame::new_rtr(0x705, 0).unwrap())).unwrap();
        assert_eq!(s.0.as_str(), "705 [RTR]");
    }

    /// Every length 0..=8 keeps its bytes; `from_parts` clamps a length above 8 and masks the identifier.
    #[test]
    fn lengths_round_trip_and_clamp() {
        let bytes = [1, 2, 3, 4, 5, 6, 7, 8];
        for n in 0..=8 {
            let f = CanFrame::new(0x181, &bytes[..n]).unwrap();
            assert_eq!((f.dlc(), f.data()), (n as u8, &bytes[..n]));
            let mut padded = [0; 8];
            padded[..n].copy_from_slice(&bytes[..n]);
            assert_eq!(CanFrame::from_parts(0x181, padded, n as u8), f);
            assert_eq!(CanFrame::new_rtr(0x181, n as u8).map(|r| r.dlc()), Some(n as u8));
        }
        for n in [9, 15, 255] {
            let f = CanFrame::from_parts(0xF181, bytes, n);
            assert_eq!((f.cob_id(), f.dlc(), f.data()), (0x181, 8, &bytes[..]));
        }
    }

    #[test]
    fn rtr_has_no_data_and_keeps_dlc() {
        let f = CanFrame::new_rtr(0x705, 1).unwrap();
        assert_eq!(f.data(), &[] as &[u8]);
        assert_eq!(Frame::dlc(&f), 1);
        assert!(f.is_remote_frame());
    }
}
