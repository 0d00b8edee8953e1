//! The CAN controller's state for the node (issue "errors that come and go"; EEC-11, EEC-13, ERR-13): a
//! receive half wrapped with a probe of the controller's status register.
//!
//! [`ReportState`] reads the error mode after every frame or bus error the inner receive half delivers and,
//! when it changed, hands the driver a [`BusState`] first; the node raises EMCY 8120h on error passive and
//! clears it on error active, treats bus-off as a communication error for 1029h:01 and sends 8140h after
//! the recovery (see [`canopen_core::bus`]). A frame that came with the change is kept and delivered next
//! (cancel-safe: it is stored before the future returns). Protocol errors (stuff, form, CRC, ACK) without a
//! change of state no longer end the driver: the controller counts them, and the state says when they
//! matter.

use canopen_core::bus::BusState;
use canopen_core::driver::{CanRx, Received};
use canopen_core::CanFrame;

/// The controller's fault-confinement mode as its status register shows it (ISO 11898-1).
///
/// ```
/// use canopen_embassy::bus_state::ErrorMode;
/// assert_eq!(ErrorMode::from_flags(false, true, true), ErrorMode::Passive); // passive implies warning
/// assert_eq!(ErrorMode::from_flags(true, true, true), ErrorMode::BusOff);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorMode {
    /// Both error counters below 96.
    Active,
    /// An error counter at 96 or more: still error active.
    Warning,
    /// An error counter at 128 or more.
    Passive,
    /// The transmit error counter passed 255.
    BusOff,
}

impl ErrorMode {
    /// From the status flags a controller has (bxCAN ESR: BOFF, EPVF, EWGF), the most severe wins.
    ///
    /// See [`ErrorMode`] for an example.
    pub const fn from_flags(bus_off: bool, passive: bool, warning: bool) -> Self {
        if bus_off {
            ErrorMode::BusOff
        } else if passive {
            ErrorMode::Passive
        } else if warning {
            ErrorMode::Warning
        } else {
            ErrorMode::Active
        }
    }
}

/// What the node is told when the mode goes from `before` to `now` (`None`: no change).
fn transition(before: ErrorMode, now: ErrorMode) -> Option<BusState> {
    Some(match (before, now) {
        (b, n) if b == n => return None,
        (ErrorMode::BusOff, ErrorMode::Active | ErrorMode::Warning) => BusState::Recovered,
        (_, ErrorMode::Active) => BusState::ErrorActive,
        (_, ErrorMode::Warning) => BusState::Warning,
        (_, ErrorMode::Passive) => BusState::ErrorPassive,
        (_, ErrorMode::BusOff) => BusState::BusOff,
    })
}

/// A receive half that also reports the controller's state; see the [module docs](self).
///
/// ```
/// use canopen_core::{bus::BusState, driver::{CanRx, Received}, CanFrame};
/// use canopen_embassy::bus_state::{ErrorMode, ReportState};
///
/// struct OneFrame(Option<CanFrame>);
/// impl CanRx for OneFrame {
///     type Error = ();
///     async fn receive(&mut self) -> Result<CanFrame, ()> { self.0.take().ok_or(()) }
/// }
/// let frame = CanFrame::new(0x605, &[0x40, 0, 0x10, 0, 0, 0, 0, 0]).unwrap();
/// // The controller went error passive while the frame came in: the state first, then the frame.
/// let mut rx = ReportState::new(OneFrame(Some(frame)), || ErrorMode::Passive);
/// assert_eq!(embassy_futures::block_on(rx.receive_event()), Ok(Received::Bus(BusState::ErrorPassive)));
/// assert_eq!(embassy_futures::block_on(rx.receive_event()), Ok(Received::Frame(frame)));
/// ```
pub struct ReportState<R, P> {
    rx: R,
    probe: P,
    mode: ErrorMode,
    held: Option<CanFrame>,
}

impl<R: CanRx, P: FnMut() -> ErrorMode> ReportState<R, P> {
    /// Wraps `rx`; `probe` reads the controller's mode (a status register: cheap, no side effects the
    /// receive half depends on).
    ///
    /// See [`ReportState`] for an example.
    pub fn new(rx: R, probe: P) -> Self {
        ReportState { rx, probe, mode: ErrorMode::Active, held: None }
    }
}

impl<R: CanRx, P: FnMut() -> ErrorMode> CanRx for ReportState<R, P> {
    type Error = R::Error;

    /// Frames only, as the inner half delivers them (a frame held back by a state change first).
    async fn receive(&mut self) -> Result<CanFrame, Self::Error> {
        match self.held.take() {
            Some(f) => Ok(f),
            None => self.rx.receive().await,
        }
    }

    async fn receive_event(&mut self) -> Result<Received, Self::Error> {
        if let Some(f) = self.held.take() {
            return Ok(Received::Frame(f));
        }
        loop {
            let frame = self.rx.receive().await.ok();
            let now = (self.probe)();
            if let Some(state) = transition(core::mem::replace(&mut self.mode, now), now) {
                self.held = frame;
                return Ok(Received::Bus(state));
            }
            if let Some(f) = frame {
                return Ok(Received::Frame(f));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// EEC-11/EEC-13 as the node needs them: active -> warning -> passive -> bus-off -> recovered -> active.
    #[test]
    fn transitions_walk_the_fault_confinement_states() {
        use ErrorMode::*;
        let walk = [Active, Warning, Passive, BusOff, Active, Active, Passive, Active];
        let seen: [Option<BusState>; 7] = core::array::from_fn(|i| transition(walk[i], walk[i + 1]));
        assert_eq!(
            seen,
            [
                Some(BusState::Warning),
                Some(BusState::ErrorPassive),
                Some(BusState::BusOff),
                Some(BusState::Recovered),
                None,
                Some(BusState::ErrorPassive),
                Some(BusState::ErrorActive),
            ]
        );
    }
}
