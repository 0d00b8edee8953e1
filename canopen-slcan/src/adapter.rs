//! [`Adapter`]: the adapter end of the link, for a firmware that *is* the serial CAN interface (or, as in
//! `examples/qemu-m4`, a node reached through one). It keeps the channel state the commands set and gives
//! the answer a host expects to each line; frames pass only while the channel is open, as on a CANable or
//! USBtin.
//!
//! Answers (LAWICEL): `O`/`L` on a closed channel, `C`, `S`n on a closed channel and `Z0` answer ok (`\r`);
//! a frame on an open channel answers `z`/`Z`; `V`, `N`, `F` answer `Vhhss`, `Nxxxx`, `Fxx` (reading `F`
//! clears the flags); anything else (a bad line, a frame on a closed or listen-only channel, `S`n while
//! open, `Z1`: this adapter has no timestamps) answers BEL. Answers a host sends (ok, error, `z` ...) are
//! not commands and get no answer, so two adapters wired together cannot ping-pong.

use embedded_can::Frame;

use crate::decode::LineError;
use crate::frame::SlcanFrame;
use crate::line::Message;

/// Status flag (`F`): a frame from the host was lost (bit 3, data overrun).
///
/// ```
/// use canopen_slcan::{STATUS_BUS_ERROR, STATUS_DATA_OVERRUN, STATUS_ERROR_PASSIVE};
/// assert_eq!((STATUS_DATA_OVERRUN, STATUS_ERROR_PASSIVE, STATUS_BUS_ERROR), (0x08, 0x20, 0x80));
/// ```
pub const STATUS_DATA_OVERRUN: u8 = 1 << 3;
/// Status flag (`F`): the CAN controller is error passive (bit 5).
///
/// ```
/// assert_eq!(canopen_slcan::STATUS_ERROR_PASSIVE, 1 << 5);
/// ```
pub const STATUS_ERROR_PASSIVE: u8 = 1 << 5;
/// Status flag (`F`): bus error (bit 7).
///
/// ```
/// assert_eq!(canopen_slcan::STATUS_BUS_ERROR, 1 << 7);
/// ```
pub const STATUS_BUS_ERROR: u8 = 1 << 7;

/// What the adapter does with one line.
///
/// ```
/// use canopen_slcan::{Adapter, Message};
/// let mut a = Adapter::new(0x10, 0x01, 0x0001);
/// let r = a.handle(Ok(Message::Open));
/// assert_eq!((r.to_bus, r.answer), (None, Some(Message::Ok)));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Reply {
    /// A frame for the CAN side.
    pub to_bus: Option<SlcanFrame>,
    /// The answer to write back to the host.
    pub answer: Option<Message>,
}

/// The adapter's channel state.
///
/// ```
/// use canopen_slcan::{Adapter, Message, SlcanFrame};
/// let mut a = Adapter::new(0x10, 0x01, 0x0001);
/// let f = SlcanFrame::from_raw(0x605, false, false, 0, &[]).unwrap();
/// assert_eq!(a.handle(Ok(Message::Frame(f))).answer, Some(Message::Error)); // closed
/// a.handle(Ok(Message::Open));
/// assert_eq!(a.handle(Ok(Message::Frame(f))).to_bus, Some(f));
/// assert!(a.is_open());
/// ```
#[derive(Debug, Clone)]
pub struct Adapter {
    open: bool,
    listen_only: bool,
    bitrate: Option<u8>,
    hardware: u8,
    software: u8,
    serial: u16,
    status: u8,
}

impl Adapter {
    /// A closed adapter answering `V` with `hardware`/`software` and `N` with `serial`.
    ///
    /// ```
    /// let a = canopen_slcan::Adapter::new(1, 2, 3);
    /// assert!(!a.is_open());
    /// ```
    pub const fn new(hardware: u8, software: u8, serial: u16) -> Self {
        Adapter { open: false, listen_only: false, bitrate: None, hardware, software, serial, status: 0 }
    }

    /// Whether the channel is open, i.e. frames from the CAN side go to the host.
    ///
    /// ```
    /// use canopen_slcan::{Adapter, Message};
    /// let mut a = Adapter::new(1, 2, 3);
    /// a.handle(Ok(Message::ListenOnly));
    /// assert!(a.is_open());
    /// ```
    pub fn is_open(&self) -> bool {
        self.open
    }

    /// The last bit rate code set by `S`n, if any.
    ///
    /// ```
    /// use canopen_slcan::{Adapter, Message};
    /// let mut a = Adapter::new(1, 2, 3);
    /// a.handle(Ok(Message::Bitrate(5)));
    /// assert_eq!(a.bitrate(), Some(5));
    /// ```
    pub fn bitrate(&self) -> Option<u8> {
        self.bitrate
    }

    /// Sets status flags (`STATUS_*`) for the next `F`.
    ///
    /// ```
    /// use canopen_slcan::{Adapter, Message, STATUS_DATA_OVERRUN};
    /// let mut a = Adapter::new(1, 2, 3);
    /// a.raise(STATUS_DATA_OVERRUN);
    /// assert_eq!(a.handle(Ok(Message::Status)).answer, Some(Message::StatusIs(STATUS_DATA_OVERRUN)));
    /// assert_eq!(a.handle(Ok(Message::Status)).answer, Some(Message::StatusIs(0)));
    /// ```
    pub fn raise(&mut self, flags: u8) {
        self.status |= flags;
    }

    /// Handles one decoded line (from [`Decoder::push`](crate::Decoder::push)).
    ///
    /// ```
    /// use canopen_slcan::{Adapter, LineError, Message};
    /// let mut a = Adapter::new(1, 2, 3);
    /// assert_eq!(a.handle(Err(LineError::Unknown)).answer, Some(Message::Error));
    /// ```
    pub fn handle(&mut self, line: Result<Message, LineError>) -> Reply {
        let answer = |m| Reply { to_bus: None, answer: Some(m) };
        let Ok(message) = line else { return answer(Message::Error) };
        match message {
            Message::Frame(f) if self.open && !self.listen_only => {
                Reply { to_bus: Some(f), answer: Some(Message::Sent { extended: f.is_extended() }) }
            }
            Message::Open | Message::ListenOnly if !self.open => {
                self.open = true;
                self.listen_only = message == Message::ListenOnly;
                answer(Message::Ok)
            }
            Message::Close => {
                self.open = false;
                answer(Message::Ok)
            }
            Message::Bitrate(code) if !self.open => {
                self.bitrate = Some(code);
                answer(Message::Ok)
            }
            Message::Timestamps(false) if !self.open => answer(Message::Ok),
            Message::Version => answer(Message::VersionIs { hardware: self.hardware, software: self.software }),
            Message::SerialNumber => answer(Message::SerialNumberIs(self.serial)),
            Message::Status => answer(Message::StatusIs(core::mem::take(&mut self.status))),
            Message::Ok
            | Message::Error
            | Message::Sent { .. }
            | Message::VersionIs { .. }
            | Message::SerialNumberIs(_)
            | Message::StatusIs(_) => Reply { to_bus: None, answer: None },
            Message::Frame(_) | Message::Open | Message::ListenOnly | Message::Bitrate(_) | Message::Timestamps(_) => {
                answer(Message::Error)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn python_can_start_up_then_a_frame() {
        // python-can's slcan bus with a bit rate: "C", "S5", "O", then frames.
        let mut a = Adapter::new(1, 2, 3);
        for m in [Message::Close, Message::Bitrate(5), Message::Open] {
            assert_eq!(a.handle(Ok(m)).answer, Some(Message::Ok), "{m:?}");
        }
        let f = SlcanFrame::from_raw(0x000, false, false, 2, &[1, 5]).unwrap();
        assert_eq!(
            a.handle(Ok(Message::Frame(f))),
            Reply { to_bus: Some(f), answer: Some(Message::Sent { extended: false }) }
        );
    }

    #[test]
    fn refusals() {
        let mut a = Adapter::new(1, 2, 3);
        a.handle(Ok(Message::Open));
        assert_eq!(a.handle(Ok(Message::Open)).answer, Some(Message::Error)); // already open
        assert_eq!(a.handle(Ok(Message::Bitrate(4))).answer, Some(Message::Error)); // only while closed
        assert_eq!(a.handle(Ok(Message::Timestamps(true))).answer, Some(Message::Error)); // no timestamps
        assert_eq!(a.handle(Err(LineError::Overlong)).answer, Some(Message::Error));
        assert_eq!(a.handle(Ok(Message::Ok)).answer, None); // answers are not commands
        a.handle(Ok(Message::Close));
        a.handle(Ok(Message::ListenOnly));
        let f = SlcanFrame::from_raw(0x1, false, false, 0, &[]).unwrap();
        assert_eq!(a.handle(Ok(Message::Frame(f))), Reply { to_bus: None, answer: Some(Message::Error) });
        assert_eq!(a.handle(Ok(Message::Version)).answer, Some(Message::VersionIs { hardware: 1, software: 2 }));
        assert_eq!(a.handle(Ok(Message::SerialNumber)).answer, Some(Message::SerialNumberIs(3)));
    }
}
