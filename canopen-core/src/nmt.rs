//! NMT slave state machine (NMT-01..NMT-27).
//!
//! Implemented here: NMT-02 ([`NmtState`]), NMT-09..NMT-13 and NMT-15 (every command from every
//! operational state, [`Nmt::handle_command`]), NMT-14 (no reply: this module produces none), NMT-16 (only
//! commands, resets and local requests change the state), NMT-18..NMT-21 ([`NmtState::allows`]),
//! NMT-25 ([`NmtState::code`]). The power-on sequence (NMT-03), what the resets restore (NMT-04..NMT-06),
//! the boot-up message (NMT-23, NMT-24) and NMT-26 are carried out by `Node`, which owns the services
//! the resets act on.

use crate::wire::{error_control::StateCode, nmt::NmtCommand};

/// The NMT states of a slave (NMT-02). Initialization's sub-states are transient inside `Node`'s reset
/// sequence; the only one visible from outside is `Initialising`, before the first boot.
///
/// ```
/// use canopen_core::nmt::NmtState;
/// assert_eq!(NmtState::PreOperational.code(), 0x7F);
/// assert_eq!(NmtState::Operational.code(), 0x05);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
// In the order of how much a state allows (Stopped before Pre-operational), so that `allows` is one comparison
// of the discriminant for most services.
pub enum NmtState {
    /// Initialization (before boot-up; no communication).
    Initialising,
    /// Stopped: only NMT and error control.
    Stopped,
    /// Pre-operational: SDO, no PDO.
    PreOperational,
    /// Operational: all services.
    Operational,
}

/// The communication services whose availability depends on the NMT state (NMT-18, 000 Table 37).
///
/// ```
/// use canopen_core::nmt::{NmtState, Service};
/// assert!(NmtState::Operational.allows(Service::Pdo));
/// assert!(!NmtState::PreOperational.allows(Service::Pdo));
/// assert!(!NmtState::Stopped.allows(Service::Sdo));
/// assert!(NmtState::Stopped.allows(Service::ErrorControl));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Service {
    /// PDO (Operational only).
    Pdo,
    /// SDO.
    Sdo,
    /// SYNC.
    Sync,
    /// TIME.
    Time,
    /// EMCY.
    Emcy,
    /// NMT node control.
    NodeControl,
    /// Heartbeat and node guarding.
    ErrorControl,
}

impl NmtState {
    /// The state code in heartbeat and guarding frames (NMT-25); `Initialising` reports the boot-up code.
    pub const fn code(self) -> u8 {
        self.state_code() as u8
    }

    /// The state as a wire [`StateCode`].
    pub const fn state_code(self) -> StateCode {
        match self {
            NmtState::Initialising => StateCode::BootUp,
            NmtState::PreOperational => StateCode::PreOperational,
            NmtState::Operational => StateCode::Operational,
            NmtState::Stopped => StateCode::Stopped,
        }
    }

    /// Whether `service` may run in this state (NMT-18..NMT-21; where CiA 301's secondary sources
    /// disagree, CiA 301 Table 37 decides: no SDO in Stopped, SYNC in Pre-operational and Operational).
    pub const fn allows(self, service: Service) -> bool {
        match self {
            NmtState::Initialising => false,
            NmtState::PreOperational => !matches!(service, Service::Pdo),
            NmtState::Operational => true,
            NmtState::Stopped => matches!(service, Service::NodeControl | Service::ErrorControl),
        }
    }
}

/// What the node must do after a node-control command.
///
/// ```
/// use canopen_core::nmt::{NmtState, Transition};
/// let t = Transition::Enter(NmtState::Operational);
/// assert_ne!(t, Transition::ResetCommunication);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Transition {
    /// Nothing changes (already in the target state).
    None,
    /// Enter this state.
    Enter(NmtState),
    /// Run Reset Application, then Reset Communication (NMT-04, NMT-12).
    ResetApplication,
    /// Run Reset Communication (NMT-05, NMT-13).
    ResetCommunication,
}

/// The NMT slave: the current state and the command rules.
///
/// ```
/// use canopen_core::{nmt::{Nmt, NmtState, Transition}, wire::nmt::NmtCommand};
/// let mut nmt = Nmt::new();
/// nmt.boot_completed();
/// assert_eq!(nmt.handle_command(NmtCommand::Start), Transition::Enter(NmtState::Operational));
/// assert_eq!(nmt.state(), NmtState::Operational);
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Nmt {
    state: NmtState,
}

impl Default for Nmt {
    fn default() -> Self {
        Nmt::new()
    }
}

impl Nmt {
    /// A slave in Initialization (NMT-03: power-on).
    pub const fn new() -> Self {
        Nmt { state: NmtState::Initialising }
    }

    /// The current state.
    pub const fn state(&self) -> NmtState {
        self.state
    }

    /// Initialization finished (the boot-up message has been queued): enter Pre-operational (NMT-03, NMT-05).
    pub fn boot_completed(&mut self) {
        self.state = NmtState::PreOperational;
    }

    /// Applies a node-control command addressed to this node (NMT-09..NMT-13, NMT-15). Commands are
    /// ignored in Initialization (the node is not on the bus yet).
    pub fn handle_command(&mut self, command: NmtCommand) -> Transition {
        if self.state == NmtState::Initialising {
            return Transition::None;
        }
        let target = match command {
            NmtCommand::Start => NmtState::Operational,
            NmtCommand::Stop => NmtState::Stopped,
            NmtCommand::EnterPreOperational => NmtState::PreOperational,
            NmtCommand::ResetNode => return self.begin_reset(Transition::ResetApplication),
            NmtCommand::ResetCommunication => return self.begin_reset(Transition::ResetCommunication),
        };
        self.enter(target)
    }

    /// A local (application or error-behaviour) request to change state (NMT-16, NMT-17, NMT-26).
    pub fn enter(&mut self, target: NmtState) -> Transition {
        if self.state == target || self.state == NmtState::Initialising || target == NmtState::Initialising {
            return Transition::None;
        }
        self.state = target;
        Transition::Enter(target)
    }

    fn begin_reset(&mut self, reset: Transition) -> Transition {
        self.state = NmtState::Initialising;
        reset
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const OPERATING: [NmtState; 3] = [NmtState::PreOperational, NmtState::Operational, NmtState::Stopped];

    fn in_state(s: NmtState) -> Nmt {
        let mut n = Nmt::new();
        n.boot_completed();
        n.enter(s);
        assert_eq!(n.state(), s);
        n
    }

    /// NMT-09..NMT-13, NMT-15: every command from every operating state.
    #[test]
    fn every_command_from_every_state() {
        for from in OPERATING {
            for (cmd, expect) in [
                (NmtCommand::Start, Some(NmtState::Operational)),
                (NmtCommand::Stop, Some(NmtState::Stopped)),
                (NmtCommand::EnterPreOperational, Some(NmtState::PreOperational)),
            ] {
                let mut n = in_state(from);
                let t = n.handle_command(cmd);
                let to = expect.unwrap();
                assert_eq!(n.state(), to);
                assert_eq!(t, if from == to { Transition::None } else { Transition::Enter(to) });
            }
            let mut n = in_state(from);
            assert_eq!(n.handle_command(NmtCommand::ResetNode), Transition::ResetApplication);
            assert_eq!(n.state(), NmtState::Initialising);
            let mut n = in_state(from);
            assert_eq!(n.handle_command(NmtCommand::ResetCommunication), Transition::ResetCommunication);
        }
    }

    /// NMT-03: nothing is obeyed before boot-up.
    #[test]
    fn initialising_ignores_commands() {
        let mut n = Nmt::new();
        assert_eq!(n.handle_command(NmtCommand::Start), Transition::None);
        assert_eq!(n.state(), NmtState::Initialising);
    }

    /// NMT-18..NMT-21: the service table.
    #[test]
    fn services_per_state() {
        use Service::*;
        let all = [Pdo, Sdo, Sync, Time, Emcy, NodeControl, ErrorControl];
        for s in all {
            assert!(!NmtState::Initialising.allows(s));
            assert!(NmtState::Operational.allows(s));
            assert_eq!(NmtState::PreOperational.allows(s), s != Pdo);
            assert_eq!(NmtState::Stopped.allows(s), matches!(s, NodeControl | ErrorControl));
        }
    }

    /// NMT-25.
    #[test]
    fn state_codes() {
        assert_eq!(NmtState::Initialising.code(), 0x00);
        assert_eq!(NmtState::Stopped.code(), 0x04);
        assert_eq!(NmtState::Operational.code(), 0x05);
        assert_eq!(NmtState::PreOperational.code(), 0x7F);
    }
}
