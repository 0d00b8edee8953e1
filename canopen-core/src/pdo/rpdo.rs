//! The RPDO state machine (PDO-06..PDO-13, PDO-38..PDO-40).
//!
//! - 00h–F0h (synchronous): the received data is kept and handed to the application at the next SYNC; a
//!   frame that arrives after the synchronous window (1007h) closed is discarded (SYNC-09, PDO-40).
//! - FEh/FFh: applied at once.
//! - Length (PDO-38/39): shorter than the mapping → not applied, EMCY 8210h; longer → the leading bytes are
//!   applied, EMCY 8220h.
//! - Event timer (PDO-12): deadline monitoring armed by each received frame; expiry → EMCY 8250h.
//! - An MPDO consumer (feature `mpdo`, mapping sub 00h FEh/FFh) maps nothing and never reaches
//!   [`Rpdo::receive`]: the node decodes each frame and writes the object it addresses (MPDO-02/03).

use super::mapping::ResolvedMap;
use super::PdoComm;
use crate::cob::CobIdEntry;
use crate::frame::CanFrame;
use crate::time::{Deadline, Duration, Instant};

/// What to do with a received RPDO frame.
///
/// ```
/// use canopen_core::pdo::rpdo::RxOutcome;
/// assert_ne!(RxOutcome::TooShort, RxOutcome::Apply { exceeded: false });
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RxOutcome {
    /// Shorter than the mapping: discarded (EMCY 8210h).
    TooShort,
    /// Apply the first [`ResolvedMap::bytes`] bytes now; `exceeded` when the frame was longer (EMCY 8220h).
    Apply {
        /// The frame was longer than the mapping.
        exceeded: bool,
    },
    /// Kept for the next SYNC; `exceeded` as above.
    Buffered {
        /// The frame was longer than the mapping.
        exceeded: bool,
    },
}

/// One RPDO.
///
/// ```
/// use canopen_core::{pdo::{rpdo::{Rpdo, RxOutcome}, PdoComm, mapping::ResolvedMap}, CanFrame, Instant};
/// let mut r = Rpdo::new(&PdoComm { cob_id: 0x201, transmission_type: 255, ..PdoComm::default() }, ResolvedMap::EMPTY);
/// let frame = CanFrame::new(0x201, &[1]).unwrap();
/// assert_eq!(r.receive(Instant::ZERO, &frame), RxOutcome::Apply { exceeded: true });
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Rpdo {
    cob: CobIdEntry,
    ttype: u8,
    /// Event timer, ms (the 1400h sub 05h value: 2 bytes kept instead of an 8-byte `Duration`).
    event_timer_ms: u16,
    /// The resolved mapping.
    pub map: ResolvedMap,
    pending: Option<[u8; 8]>,
    /// The event-timer deadline (8 bytes where `Option<Instant>` takes 16).
    deadline: Deadline,
    /// A length error is active (cleared by the next correct frame).
    pub length_error: bool,
    /// The event timer expired (cleared by the next frame).
    pub timed_out: bool,
    /// The MPDO consumer kind (feature `mpdo`, mapping sub 00h FEh/FFh, MPDO-05), `None` for a plain RPDO:
    /// kept here, set when the RPDO is configured, so that a frame tests one byte of the RPDO it already
    /// holds instead of looking the mapping up.
    #[cfg(feature = "mpdo")]
    mpdo: Option<super::mpdo::AddressMode>,
}

impl Rpdo {
    /// An RPDO with the given parameters and mapping.
    pub const fn new(comm: &PdoComm, map: ResolvedMap) -> Self {
        Rpdo {
            cob: comm.cob(),
            ttype: comm.transmission_type,
            event_timer_ms: comm.event_timer_ms,
            map,
            pending: None,
            deadline: Deadline::NONE,
            length_error: false,
            timed_out: false,
            #[cfg(feature = "mpdo")]
            mpdo: None,
        }
    }

    /// This RPDO as an MPDO consumer of kind `mode` (`None`: a plain RPDO).
    ///
    /// ```
    /// use canopen_core::pdo::{mapping::ResolvedMap, mpdo::AddressMode, rpdo::Rpdo, PdoComm};
    /// let r = Rpdo::new(&PdoComm { cob_id: 0x201, transmission_type: 254, ..PdoComm::default() }, ResolvedMap::EMPTY)
    ///     .with_mpdo(Some(AddressMode::Source));
    /// assert_eq!(r.mpdo(), Some(AddressMode::Source));
    /// ```
    #[cfg(feature = "mpdo")]
    pub const fn with_mpdo(mut self, mode: Option<super::mpdo::AddressMode>) -> Self {
        self.mpdo = mode;
        self
    }

    /// The MPDO consumer kind, `None` for a plain RPDO.
    #[cfg(feature = "mpdo")]
    pub const fn mpdo(&self) -> Option<super::mpdo::AddressMode> {
        self.mpdo
    }

    /// Whether the RPDO exists (bit 31 = 0).
    pub const fn is_valid(&self) -> bool {
        !self.cob.bit31()
    }

    /// The CAN-ID.
    pub const fn can_id(&self) -> u16 {
        self.cob.can_id()
    }

    /// Whether the data waits for the next SYNC (types 00h–F0h).
    pub const fn is_synchronous(&self) -> bool {
        self.ttype <= 240
    }

    /// A frame arrived at `now` (in Operational). A synchronous RPDO keeps the frame's data as the frame
    /// holds it, zero-padded to 8 bytes ([`CanFrame::padded`]).
    pub fn receive(&mut self, now: Instant, frame: &CanFrame) -> RxOutcome {
        let data = frame.data();
        let need = self.map.bytes();
        if data.len() < need {
            return RxOutcome::TooShort;
        }
        let exceeded = data.len() > need;
        if self.event_timer_ms != 0 {
            self.deadline = Deadline::at(now + Duration::from_millis(self.event_timer_ms.into()));
        }
        if self.is_synchronous() {
            self.pending = Some(frame.padded());
            RxOutcome::Buffered { exceeded }
        } else {
            RxOutcome::Apply { exceeded }
        }
    }

    /// A SYNC: the data received since the last one, if any.
    pub fn take_pending(&mut self) -> Option<[u8; 8]> {
        // Checked first: the common case (nothing buffered) then writes nothing.
        if self.pending.is_some() {
            self.pending.take()
        } else {
            None
        }
    }

    /// Drops buffered data (the synchronous window closed, or the node left Operational).
    pub fn discard(&mut self) {
        self.pending = None;
    }

    /// Leaving Operational: no deadline monitoring, nothing buffered.
    pub fn stop(&mut self) {
        self.pending = None;
        self.deadline = Deadline::NONE;
    }

    /// The event-timer deadline.
    pub const fn poll_timeout(&self) -> Option<Instant> {
        self.deadline.get()
    }

    /// [`poll_timeout`](Self::poll_timeout) as a [`Deadline`], for the node's minimum over its services.
    pub(crate) const fn deadline(&self) -> Deadline {
        self.deadline
    }

    /// Returns true once when the deadline passed (EMCY 8250h).
    pub fn handle_timeout(&mut self, now: Instant) -> bool {
        if self.deadline.passed(now) {
            self.deadline = Deadline::NONE;
            self.timed_out = true;
            return true;
        }
        false
    }
}
