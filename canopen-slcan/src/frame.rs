//! [`SlcanFrame`]: a classic CAN frame as an slcan line carries it (11- or 29-bit identifier, data or
//! remote, DLC 0..=8), implementing [`embedded_can::Frame`] so that any CAN type converts to and from it
//! (`canopen_core::CanFrame::from_frame` takes the 11-bit ones).

use embedded_can::{ExtendedId, Frame, Id, StandardId};

/// A classic CAN frame (no CAN FD: slcan's `d`/`D`/`b`/`B` lines are not decoded).
///
/// ```
/// use canopen_slcan::SlcanFrame;
/// use embedded_can::{Frame, StandardId};
/// let f = SlcanFrame::new(StandardId::new(0x181).unwrap(), &[1, 2]).unwrap();
/// assert_eq!((f.dlc(), f.data()), (2, &[1u8, 2][..]));
/// assert!(SlcanFrame::new(StandardId::ZERO, &[0; 9]).is_none());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SlcanFrame {
    id: Id,
    remote: bool,
    dlc: u8,
    data: [u8; 8],
}

impl Frame for SlcanFrame {
    fn new(id: impl Into<Id>, data: &[u8]) -> Option<Self> {
        let mut buf = [0u8; 8];
        buf.get_mut(..data.len())?.copy_from_slice(data);
        Some(SlcanFrame { id: id.into(), remote: false, dlc: data.len() as u8, data: buf })
    }

    fn new_remote(id: impl Into<Id>, dlc: usize) -> Option<Self> {
        (dlc <= 8).then(|| SlcanFrame { id: id.into(), remote: true, dlc: dlc as u8, data: [0; 8] })
    }

    fn is_extended(&self) -> bool {
        matches!(self.id, Id::Extended(_))
    }

    fn is_remote_frame(&self) -> bool {
        self.remote
    }

    fn id(&self) -> Id {
        self.id
    }

    fn dlc(&self) -> usize {
        usize::from(self.dlc)
    }

    fn data(&self) -> &[u8] {
        if self.remote {
            &[]
        } else {
            &self.data[..usize::from(self.dlc)]
        }
    }
}

impl SlcanFrame {
    /// A frame from a raw identifier: 11-bit if `extended` is false, else 29-bit; `None` if the identifier
    /// does not fit or `data` (or the remote `dlc`) is longer than 8.
    ///
    /// ```
    /// use canopen_slcan::SlcanFrame;
    /// assert!(SlcanFrame::from_raw(0x7FF, false, false, 0, &[]).is_some());
    /// assert!(SlcanFrame::from_raw(0x800, false, false, 0, &[]).is_none());
    /// assert!(SlcanFrame::from_raw(0x1FFF_FFFF, true, true, 8, &[]).is_some());
    /// ```
    pub fn from_raw(id: u32, extended: bool, remote: bool, dlc: u8, data: &[u8]) -> Option<Self> {
        let id: Id =
            if extended { ExtendedId::new(id)?.into() } else { StandardId::new(u16::try_from(id).ok()?)?.into() };
        if remote {
            Self::new_remote(id, usize::from(dlc))
        } else {
            Self::new(id, data)
        }
    }

    /// The identifier as a number (11 or 29 bits, see [`Frame::is_extended`]).
    ///
    /// ```
    /// use canopen_slcan::SlcanFrame;
    /// assert_eq!(SlcanFrame::from_raw(0x1234_5678, true, false, 0, &[]).unwrap().raw_id(), 0x1234_5678);
    /// ```
    pub fn raw_id(&self) -> u32 {
        match self.id {
            Id::Standard(id) => u32::from(id.as_raw()),
            Id::Extended(id) => id.as_raw(),
        }
    }

    /// A copy of any [`Frame`] (data beyond 8 bytes, which a classic frame cannot have, is refused).
    ///
    /// ```
    /// use canopen_slcan::SlcanFrame;
    /// let f = SlcanFrame::from_raw(0x80, false, false, 0, &[]).unwrap();
    /// assert_eq!(SlcanFrame::from_frame(&f), Some(f));
    /// ```
    pub fn from_frame<F: Frame>(frame: &F) -> Option<Self> {
        if frame.is_remote_frame() {
            Self::new_remote(frame.id(), frame.dlc())
        } else {
            Self::new(frame.id(), frame.data())
        }
    }
}
