//! The TPDO state machine (PDO-15..PDO-29).
//!
//! - 00h (PDO-19): an application event marks the TPDO; the next SYNC samples and sends it.
//! - 01h–F0h (PDO-20): sent on every n-th SYNC; with a SYNC start value (PDO-26/27) and the SYNC counter on,
//!   counting starts at the SYNC whose counter equals the start value (sent on that SYNC, then every n-th).
//! - FCh (PDO-21): sampled at every SYNC, sent on RTR; FDh (PDO-22): sampled and sent on RTR.
//! - FEh/FFh (PDO-23..25, PDO-28): sent on an application event ([`Tpdo::trigger`]), on event-timer expiry,
//!   and right after entering Operational; the inhibit time holds a transmission back (the TPDO stays
//!   pending and is sampled when the inhibit time ends, so the latest value goes out, PDO-24).
//! - The event timer restarts at every transmission of the TPDO (the CANopenNode choice; the CiA text does
//!   not say), so "no data change" gives one TPDO per event-timer period (type FEh, event timer 1000 ms:
//!   one TPDO per second).
//! - RTR (PDO-29): any valid TPDO with COB-ID bit 30 = 0 answers a remote frame.
//! - An MPDO (feature `mpdo`, mapping sub 00h FEh/FFh, MPDO-04) is event-driven only: no SYNC, RTR, event
//!   timer or send on entering Operational, and [`Tpdo::trigger`] does nothing; the application sends each
//!   one (`Node::send_dam_mpdo` / `Node::send_sam_mpdo`) through [`Tpdo::mpdo_ready`] and
//!   [`Tpdo::mpdo_sent`], which keep the inhibit time.
//!
//! The state machine decides *when*; the `Node` samples the mapped objects and queues the frame.

use super::mapping::ResolvedMap;
use super::PdoComm;
use crate::cob::CobIdEntry;
use crate::time::{Deadline, Duration, Instant};

/// What a SYNC means for a TPDO.
///
/// ```
/// use canopen_core::pdo::tpdo::SyncAction;
/// assert_ne!(SyncAction::Send, SyncAction::Sample);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SyncAction {
    /// Nothing.
    None,
    /// Sample and send now.
    Send,
    /// Sample into the RTR buffer (type FCh, in a build with the feature `pdo-rtr`).
    Sample,
}

/// One TPDO.
///
/// ```
/// use canopen_core::{pdo::{tpdo::{Tpdo, SyncAction}, PdoComm, mapping::ResolvedMap}, Instant};
/// let mut t = Tpdo::new(&PdoComm { cob_id: 0x181, transmission_type: 2, ..PdoComm::default() }, ResolvedMap::EMPTY);
/// assert_eq!(t.on_sync(None), SyncAction::None);
/// assert_eq!(t.on_sync(None), SyncAction::Send); // every 2nd SYNC
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Tpdo {
    cob: CobIdEntry,
    /// The transmission type in effect: FDh for a TPDO that is not valid (see [`Tpdo::transmission_type`]).
    ttype: u8,
    /// Inhibit time, 100 µs (the 1800h sub 03h value: 2 bytes kept instead of an 8-byte `Duration`).
    inhibit_100us: u16,
    /// Event timer, ms (sub 05h).
    event_timer_ms: u16,
    sync_start: u8,
    /// The resolved mapping.
    pub map: ResolvedMap,
    sync_count: u8,
    started: bool,
    pending: bool,
    /// The end of the inhibit time (sub 03h) after the last transmission.
    inhibit: Deadline,
    /// The event timer's expiry (sub 05h).
    timer: Deadline,
    /// The payload sampled at the last SYNC for type FCh (sent on RTR, PDO-21), or the payload last sent for
    /// FEh/FFh (change-of-value detection, PDO-23): one buffer, since a TPDO has one type.
    last: Option<([u8; 8], u8)>,
    /// The MPDO kind (mapping sub 00h FEh/FFh), `None` for a plain TPDO.
    #[cfg(feature = "mpdo")]
    mpdo: Option<super::mpdo::AddressMode>,
}

impl Tpdo {
    /// A TPDO with the given parameters and mapping.
    pub const fn new(comm: &PdoComm, map: ResolvedMap) -> Self {
        Tpdo {
            cob: comm.cob(),
            // Not valid: FDh, the type that never sends on a SYNC, an event or a timer, so that those paths
            // need no validity test of their own (a remote request tests it, `rtr_allowed`).
            ttype: if comm.is_valid() { comm.transmission_type } else { 253 },
            inhibit_100us: comm.inhibit_100us,
            event_timer_ms: comm.event_timer_ms,
            sync_start: comm.sync_start,
            map,
            sync_count: 0,
            started: false,
            pending: false,
            inhibit: Deadline::NONE,
            timer: Deadline::NONE,
            last: None,
            #[cfg(feature = "mpdo")]
            mpdo: None,
        }
    }

    /// This TPDO as an MPDO producer of kind `mode` (`None`: a plain TPDO).
    ///
    /// ```
    /// use canopen_core::{pdo::{tpdo::Tpdo, mpdo::AddressMode, PdoComm, mapping::ResolvedMap}, Instant};
    /// let t = Tpdo::new(&PdoComm { cob_id: 0x181, transmission_type: 254, ..PdoComm::default() }, ResolvedMap::EMPTY)
    ///     .with_mpdo(Some(AddressMode::Destination));
    /// assert_eq!(t.mpdo(), Some(AddressMode::Destination));
    /// ```
    #[cfg(feature = "mpdo")]
    pub const fn with_mpdo(mut self, mode: Option<super::mpdo::AddressMode>) -> Self {
        self.mpdo = mode;
        self
    }

    /// The MPDO kind, `None` for a plain TPDO.
    #[cfg(feature = "mpdo")]
    pub const fn mpdo(&self) -> Option<super::mpdo::AddressMode> {
        self.mpdo
    }

    /// Whether this TPDO is an MPDO (always `false` without the feature `mpdo`).
    const fn is_mpdo(&self) -> bool {
        #[cfg(feature = "mpdo")]
        return self.mpdo.is_some();
        #[cfg(not(feature = "mpdo"))]
        false
    }

    /// Whether MPDO `mode` may go out at `now` (MPDO-04): the TPDO is valid, event-driven (FEh/FFh), an MPDO
    /// of that kind, and its inhibit time has passed.
    ///
    /// ```
    /// use canopen_core::{pdo::{tpdo::Tpdo, mpdo::{AddressMode, MpdoRefused}, PdoComm, mapping::ResolvedMap}, Instant};
    /// let comm = PdoComm { cob_id: 0x181, transmission_type: 254, inhibit_100us: 10, ..PdoComm::default() };
    /// let mut t = Tpdo::new(&comm, ResolvedMap::EMPTY).with_mpdo(Some(AddressMode::Destination));
    /// assert_eq!(t.mpdo_ready(Instant::ZERO, AddressMode::Source), Err(MpdoRefused::NotMpdo));
    /// assert_eq!(t.mpdo_ready(Instant::ZERO, AddressMode::Destination), Ok(()));
    /// t.mpdo_sent(Instant::ZERO);
    /// assert_eq!(t.mpdo_ready(Instant::from_micros(999), AddressMode::Destination), Err(MpdoRefused::Inhibited));
    /// assert_eq!(t.mpdo_ready(Instant::from_millis(1), AddressMode::Destination), Ok(()));
    /// ```
    #[cfg(feature = "mpdo")]
    pub fn mpdo_ready(&self, now: Instant, mode: super::mpdo::AddressMode) -> Result<(), super::mpdo::MpdoRefused> {
        use super::mpdo::MpdoRefused;
        if !self.event_driven() || self.mpdo != Some(mode) {
            return Err(MpdoRefused::NotMpdo);
        }
        if self.inhibited(now) {
            return Err(MpdoRefused::Inhibited);
        }
        Ok(())
    }

    /// An MPDO was sent at `now`: its inhibit time starts (MPDO-04); no event timer.
    #[cfg(feature = "mpdo")]
    pub fn mpdo_sent(&mut self, now: Instant) {
        self.start_inhibit(now);
    }

    /// Whether the TPDO exists (COB-ID bit 31 = 0).
    pub const fn is_valid(&self) -> bool {
        !self.cob.bit31()
    }

    /// The CAN-ID.
    pub const fn can_id(&self) -> u16 {
        self.cob.can_id()
    }

    /// Whether a remote request is served (bit 30 = 0, PDO-29; never without the feature `pdo-rtr`).
    pub const fn rtr_allowed(&self) -> bool {
        super::RTR && self.is_valid() && !self.cob.bit30() && !self.is_mpdo()
    }

    /// The transmission type in effect: the configured one, or FDh (RTR-only, PDO-22) for a TPDO that is
    /// not valid, which sends nothing on a SYNC, an application event or a timer.
    ///
    /// ```
    /// use canopen_core::pdo::{tpdo::Tpdo, PdoComm, mapping::ResolvedMap};
    /// let t = Tpdo::new(&PdoComm { cob_id: 0x181, transmission_type: 254, ..PdoComm::default() }, ResolvedMap::EMPTY);
    /// assert_eq!(t.transmission_type(), 254);
    /// let t = Tpdo::new(&PdoComm { cob_id: 0x8000_0181, transmission_type: 254, ..PdoComm::default() }, ResolvedMap::EMPTY);
    /// assert_eq!((t.is_valid(), t.transmission_type(), t.rtr_allowed()), (false, 253, false));
    /// ```
    pub const fn transmission_type(&self) -> u8 {
        self.ttype
    }

    const fn event_driven(&self) -> bool {
        self.ttype >= 254
    }

    /// Entering Operational (PDO-27, PDO-28): SYNC counting restarts; an event-driven TPDO is due at
    /// once.
    pub fn start(&mut self) -> bool {
        self.sync_count = 0;
        self.started = false;
        self.pending = false;
        self.inhibit = Deadline::NONE;
        self.last = None;
        self.timer = Deadline::NONE;
        self.event_driven() && !self.is_mpdo()
    }

    /// Leaving Operational: no timers.
    pub fn stop(&mut self) {
        self.pending = false;
        self.timer = Deadline::NONE;
        self.inhibit = Deadline::NONE;
    }

    /// A SYNC with `counter` (`None` when the SYNC counter is off).
    pub fn on_sync(&mut self, counter: Option<u8>) -> SyncAction {
        if self.is_mpdo() {
            return SyncAction::None;
        }
        match self.ttype {
            n @ 1..=240 => self.cyclic(n, counter),
            0 if core::mem::take(&mut self.pending) => SyncAction::Send,
            // Sampled for a remote request: never in a build without `pdo-rtr`, where nothing would read it
            // (and type FCh is refused, PDO-18).
            252 if super::RTR => SyncAction::Sample,
            _ => SyncAction::None,
        }
    }

    /// Types 01h–F0h: every `n`-th SYNC, counted from the SYNC start value when the counter is on (PDO-20,
    /// PDO-26).
    fn cyclic(&mut self, n: u8, counter: Option<u8>) -> SyncAction {
        if !self.started {
            match (self.sync_start, counter) {
                (s, Some(c)) if crate::sync::COUNTER && s != 0 => {
                    if c != s {
                        return SyncAction::None;
                    }
                    self.started = true;
                    self.sync_count = 0;
                    return SyncAction::Send;
                }
                _ => self.started = true,
            }
        }
        self.sync_count += 1;
        if self.sync_count < n {
            return SyncAction::None;
        }
        self.sync_count = 0;
        SyncAction::Send
    }

    /// An application event at `now` (PDO-19, PDO-23): returns whether to send now. Type 00h sends at the
    /// next SYNC; FEh/FFh now unless the inhibit time runs (then when it ends); RTR-only types ignore it.
    pub fn trigger(&mut self, now: Instant) -> bool {
        if self.is_mpdo() {
            return false;
        }
        match self.ttype {
            0 => {
                self.pending = true;
                false
            }
            254 | 255 => {
                if self.inhibited(now) {
                    self.pending = true;
                    false
                } else {
                    true
                }
            }
            _ => false,
        }
    }

    /// A transmission at `now` starts the inhibit time (sub 03h). Without one its deadline is never set, so
    /// there is nothing to clear.
    #[inline]
    fn start_inhibit(&mut self, now: Instant) {
        let inhibit = self.inhibit_100us;
        if inhibit != 0 {
            self.inhibit = Deadline::at(now + Duration::from_100us(inhibit.into()));
        }
    }

    /// Whether the inhibit time of the last transmission still runs at `now` (PDO-24).
    fn inhibited(&self, now: Instant) -> bool {
        self.inhibit != Deadline::NONE && !self.inhibit.passed(now)
    }

    /// The TPDO was sent at `now` with `payload`: an event-driven TPDO starts its inhibit time and event
    /// timer and keeps the payload for [`last`](Self::last).
    pub fn sent(&mut self, now: Instant, payload: ([u8; 8], u8)) {
        if self.event_driven() {
            // Only FEh/FFh hold an event back (type 00h keeps its event for the next SYNC, the other types
            // never have one), so only they look at the inhibit time (PDO-24), and only they run the event
            // timer (start/stop clear both for the others).
            self.start_inhibit(now);
            self.pending = false;
            self.last = Some(payload);
            let timer = self.event_timer_ms;
            if timer != 0 {
                self.timer = Deadline::at(now + Duration::from_millis(timer.into()));
            }
        }
    }

    /// Type FCh: the payload sampled at a SYNC, sent on the next remote request (PDO-21).
    pub fn sampled(&mut self, payload: ([u8; 8], u8)) {
        self.last = Some(payload);
    }

    /// The payload sampled at the last SYNC (type FCh) or last sent (FEh/FFh), `None` before the first one
    /// since entering Operational.
    ///
    /// ```
    /// use canopen_core::{pdo::{tpdo::Tpdo, PdoComm, mapping::ResolvedMap}, Instant};
    /// let mut t = Tpdo::new(&PdoComm { cob_id: 0x181, transmission_type: 254, ..PdoComm::default() }, ResolvedMap::EMPTY);
    /// assert_eq!(t.last(), None);
    /// t.sent(Instant::ZERO, ([7, 0, 0, 0, 0, 0, 0, 0], 1));
    /// assert_eq!(t.last(), Some(([7, 0, 0, 0, 0, 0, 0, 0], 1))); // kept for change-of-value detection
    /// ```
    pub const fn last(&self) -> Option<([u8; 8], u8)> {
        self.last
    }

    /// The next instant at which [`handle_timeout`](Self::handle_timeout) has work.
    pub fn poll_timeout(&self) -> Option<Instant> {
        self.deadline().get()
    }

    /// [`poll_timeout`](Self::poll_timeout) as a [`Deadline`], for the node's minimum over its services.
    pub(crate) fn deadline(&self) -> Deadline {
        // A held-back event waits for the end of the inhibit time (one `min` either way). Only an event-driven
        // TPDO starts an inhibit time (`sent`): a type-00h TPDO's event (pending until the SYNC) has none.
        let held = if self.pending { self.inhibit } else { Deadline::NONE };
        self.timer.min(held)
    }

    /// Time passed: returns whether to send now (a held-back event at the end of the inhibit time, or the
    /// event timer, which itself waits for the inhibit time).
    pub fn handle_timeout(&mut self, now: Instant) -> bool {
        if !self.event_driven() || self.is_mpdo() {
            return false;
        }
        if self.timer.passed(now) {
            self.timer = Deadline::NONE;
            self.pending = true;
        }
        if self.pending && !self.inhibited(now) {
            self.inhibit = Deadline::NONE;
            return true;
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tpdo(ttype: u8, start: u8) -> Tpdo {
        Tpdo::new(
            &PdoComm { cob_id: 0x181, transmission_type: ttype, sync_start: start, ..PdoComm::default() },
            ResolvedMap::EMPTY,
        )
    }

    /// Type 2, SYNC start value 2, counter 1..4 → after counters 2, 4, 2, 4.
    #[test]
    fn sync_start_value() {
        let mut t = tpdo(2, 2);
        let sent: std::vec::Vec<u8> =
            [1u8, 2, 3, 4, 1, 2, 3, 4].iter().filter(|&&c| t.on_sync(Some(c)) == SyncAction::Send).copied().collect();
        assert_eq!(sent, [2, 4, 2, 4]);
        // Counter off: the start value is ignored (PDO-26).
        let mut t = tpdo(3, 2);
        let n: std::vec::Vec<usize> = (1..=9).filter(|_| t.on_sync(None) == SyncAction::Send).collect();
        assert_eq!(n, [3, 6, 9]); // type 3, counter off: SYNCs #3, #6, #9
    }

    extern crate std;

    /// PDO-21: type FCh is sampled at every SYNC for the next remote request; a build without `pdo-rtr`
    /// (which refuses type FCh, PDO-18) samples nothing, whatever the parameters say.
    #[test]
    fn rtr_type_samples_only_with_rtr() {
        let mut t = tpdo(252, 0);
        let expect = if crate::pdo::RTR { SyncAction::Sample } else { SyncAction::None };
        assert_eq!((t.on_sync(None), t.on_sync(Some(3))), (expect, expect));
    }

    /// Type 0 sends once after the SYNC that follows an event.
    #[test]
    fn acyclic_sync() {
        let mut t = tpdo(0, 0);
        assert_eq!(t.on_sync(None), SyncAction::None);
        assert!(!t.trigger(Instant::ZERO));
        assert_eq!(t.on_sync(None), SyncAction::Send);
        assert_eq!(t.on_sync(None), SyncAction::None);
    }

    /// PDO-19, PDO-24: the inhibit time holds back event-driven transmissions only; a type-00h TPDO sends at
    /// every SYNC after an event however soon, and neither it nor a cyclic one ever has a deadline.
    #[test]
    fn inhibit_is_for_event_driven_types_only() {
        let comm =
            |ttype| PdoComm { cob_id: 0x181, transmission_type: ttype, inhibit_100us: 200, ..PdoComm::default() };
        let mut t = Tpdo::new(&comm(0), ResolvedMap::EMPTY);
        for ms in [0, 1, 2] {
            assert!(!t.trigger(Instant::from_millis(ms)));
            assert_eq!(t.poll_timeout(), None);
            assert_eq!(t.on_sync(None), SyncAction::Send);
            t.sent(Instant::from_millis(ms), ([0; 8], 0));
            assert_eq!(t.poll_timeout(), None);
        }
        let mut t = Tpdo::new(&comm(1), ResolvedMap::EMPTY);
        assert_eq!(t.on_sync(None), SyncAction::Send);
        t.sent(Instant::ZERO, ([0; 8], 0));
        assert_eq!((t.poll_timeout(), t.on_sync(None)), (None, SyncAction::Send));
    }

    /// The inhibit time holds an event back, it is not lost.
    #[test]
    fn inhibit_holds_back() {
        let mut t = Tpdo::new(
            &PdoComm { cob_id: 0x181, transmission_type: 254, inhibit_100us: 200, ..PdoComm::default() },
            ResolvedMap::EMPTY,
        );
        assert!(t.trigger(Instant::ZERO));
        t.sent(Instant::ZERO, ([0; 8], 0));
        assert!(!t.trigger(Instant::from_millis(5)));
        assert_eq!(t.poll_timeout(), Some(Instant::from_millis(20)));
        assert!(!t.handle_timeout(Instant::from_millis(19)));
        assert!(t.handle_timeout(Instant::from_millis(20)));
    }
}
