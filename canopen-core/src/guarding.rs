//! Node guarding and life guarding, slave side (100Ch, 100Dh; GUARD-01..GUARD-13).
//!
//! Implemented: GUARD-04 (node life time = 100Ch × 100Dh, 0 = no life guarding), GUARD-05/06 (answer an RTR on
//! 700h + node with toggle ‖ state), GUARD-07 (toggle starts at 0, alternates, only reset communication
//! clears it: [`Guarding::reset`]), GUARD-08 (answered in Pre-operational, Operational, Stopped), GUARD-09
//! (life guarding starts with the first RTR), GUARD-10 (time-out and resolution events), GUARD-13 (only
//! 04h/05h/7Fh). GUARD-11 (time-out is a communication error per 1029h) and HB-05 (no guarding replies while
//! the heartbeat producer runs) are enforced by `Node`. GUARD-12 is master behaviour (tested on the bus).

use crate::time::{Deadline, Duration, Instant};
use crate::wire::error_control::{GuardReply, StateCode};

/// A life-guarding observation for the application (GUARD-10).
///
/// ```
/// use canopen_core::guarding::LifeGuardingEvent;
/// assert_ne!(LifeGuardingEvent::Timeout, LifeGuardingEvent::Resolved);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum LifeGuardingEvent {
    /// Life-guarding event "occurred / time-out": no guarding request within the node life time.
    Timeout,
    /// Life-guarding event "resolved": guarding requests arrived again.
    Resolved,
}

/// The slave's node-guarding state.
///
/// ```
/// use canopen_core::{guarding::Guarding, Instant};
/// use canopen_core::wire::error_control::StateCode;
/// let mut g = Guarding::new();
/// let (reply, _) = g.handle_request(Instant::ZERO, StateCode::PreOperational, 0, 0);
/// assert_eq!(reply.emit(), [0x7F]); // toggle 0 first
/// let (reply, _) = g.handle_request(Instant::ZERO, StateCode::PreOperational, 0, 0);
/// assert_eq!(reply.emit(), [0xFF]); // then 1
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Guarding {
    toggle: bool,
    deadline: Deadline,
    timed_out: bool,
}

impl Guarding {
    /// Guarding after reset communication: toggle 0, life guarding not started.
    pub const fn new() -> Self {
        Guarding { toggle: false, deadline: Deadline::NONE, timed_out: false }
    }

    /// Reset communication: toggle back to 0, life guarding waits for the first request (GUARD-07, GUARD-09).
    pub fn reset(&mut self) {
        *self = Guarding::new();
    }

    /// Answers a guarding RTR received at `now` while in `state`, with the current 100Ch/100Dh values.
    /// Returns the reply and, when the request ends a life-guarding time-out, [`LifeGuardingEvent::Resolved`].
    pub fn handle_request(
        &mut self,
        now: Instant,
        state: StateCode,
        guard_time_ms: u16,
        life_time_factor: u8,
    ) -> (GuardReply, Option<LifeGuardingEvent>) {
        let reply = GuardReply { toggle: self.toggle, state };
        self.toggle = !self.toggle;
        let life_ms = u32::from(guard_time_ms) * u32::from(life_time_factor);
        self.deadline.set((life_ms != 0).then(|| now + Duration::from_millis_u32(life_ms)));
        let resolved = core::mem::replace(&mut self.timed_out, false);
        (reply, resolved.then_some(LifeGuardingEvent::Resolved))
    }

    /// Applies new 100Ch/100Dh values written at `now`: 0 in either stops life guarding; otherwise a running
    /// life guard gets the new node life time from now.
    pub fn set_life_time(&mut self, now: Instant, guard_time_ms: u16, life_time_factor: u8) {
        let life_ms = u32::from(guard_time_ms) * u32::from(life_time_factor);
        if life_ms == 0 {
            self.deadline = Deadline::NONE;
            self.timed_out = false;
        } else if self.deadline.get().is_some() {
            self.deadline.set(Some(now + Duration::from_millis_u32(life_ms)));
        }
    }

    /// When the node life time ends.
    pub const fn poll_timeout(&self) -> Option<Instant> {
        self.deadline.get()
    }

    /// [`poll_timeout`](Self::poll_timeout) as a [`Deadline`], for the node's minimum over its services.
    pub(crate) const fn deadline(&self) -> Deadline {
        self.deadline
    }

    /// Whether life guarding is currently timed out.
    pub const fn is_timed_out(&self) -> bool {
        self.timed_out
    }

    /// Reports [`LifeGuardingEvent::Timeout`] once when the node life time has elapsed at `now` (GUARD-10).
    pub fn handle_timeout(&mut self, now: Instant) -> Option<LifeGuardingEvent> {
        if !self.deadline.passed(now) {
            return None;
        }
        self.deadline = Deadline::NONE;
        self.timed_out = true;
        Some(LifeGuardingEvent::Timeout)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::time::ms;

    /// GUARD-09/10: starts with the first RTR, times out once, resolves on the next RTR.
    #[test]
    fn life_guarding() {
        let mut g = Guarding::new();
        assert_eq!(g.poll_timeout(), None);
        let _ = g.handle_request(ms(0), StateCode::Operational, 100, 3);
        assert_eq!(g.poll_timeout(), Some(ms(300)));
        assert_eq!(g.handle_timeout(ms(299)), None);
        assert_eq!(g.handle_timeout(ms(300)), Some(LifeGuardingEvent::Timeout));
        assert_eq!(g.handle_timeout(ms(900)), None);
        let (_, ev) = g.handle_request(ms(1000), StateCode::Operational, 100, 3);
        assert_eq!(ev, Some(LifeGuardingEvent::Resolved));
    }

    /// GUARD-04: a zero guard time or factor means no life guarding.
    #[test]
    fn zero_disables_life_guarding() {
        let mut g = Guarding::new();
        let _ = g.handle_request(ms(0), StateCode::Operational, 100, 0);
        assert_eq!(g.poll_timeout(), None);
        let _ = g.handle_request(ms(0), StateCode::Operational, 100, 2);
        g.set_life_time(ms(50), 0, 2);
        assert_eq!(g.poll_timeout(), None);
    }

    /// GUARD-07: only reset clears the toggle.
    #[test]
    fn toggle_reset() {
        let mut g = Guarding::new();
        let _ = g.handle_request(ms(0), StateCode::Operational, 0, 0);
        let (r, _) = g.handle_request(ms(0), StateCode::Stopped, 0, 0);
        assert_eq!(r.emit(), [0x84]);
        g.reset();
        let (r, _) = g.handle_request(ms(0), StateCode::Stopped, 0, 0);
        assert_eq!(r.emit(), [0x04]);
    }
}
