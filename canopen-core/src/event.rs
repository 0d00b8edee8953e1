//! What the node tells the application (drained with `Node::poll_event`).

use crate::guarding::LifeGuardingEvent;
use crate::heartbeat::ConsumerEvent;
use crate::nmt::NmtState;

/// An event for the application.
///
/// ```
/// use canopen_core::{event::Event, nmt::NmtState};
/// let e = Event::StateChanged { from: NmtState::PreOperational, to: NmtState::Operational };
/// assert!(matches!(e, Event::StateChanged { to: NmtState::Operational, .. }));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Event {
    /// The NMT state changed (by a command, a reset, local control or the error behaviour).
    StateChanged {
        /// The state before.
        from: NmtState,
        /// The state now.
        to: NmtState,
    },
    /// Reset Application ran: application values were set back to their power-on values (NMT-04).
    ResetApplication,
    /// Reset Communication ran: communication parameters were set back to their power-on values (NMT-05).
    ResetCommunication,
    /// A heartbeat consumer observation (HB-10, HB-11).
    Heartbeat(ConsumerEvent),
    /// A life-guarding observation (GUARD-10).
    LifeGuarding(LifeGuardingEvent),
}
