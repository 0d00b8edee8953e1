//! The power drive system (PDS) state machine: its eight states, the commands the controlword 6040h
//! encodes, the numbered transitions 0–16 of the standard's table and the state bits of the statusword
//! 6041h.
//!
//! This module is the table alone, a pure function of (state, command): what a drive does *during* a
//! transition (ramping down before the power goes off, as 605Ah–605Eh ask) is [`Drive`](crate::Drive)'s.
//!
//! The table (IEC 61800-7-201 / CiA 402-2 "PDS FSA"; as restated by python canopen's `p402.py`
//! `TRANSITIONTABLE` and drive manuals):
//!
//! | # | from | to | cause |
//! |---|---|---|---|
//! | 0 | (power on) | Not ready to switch on | automatic |
//! | 1 | Not ready to switch on | Switch on disabled | automatic (self-test passed) |
//! | 2 | Switch on disabled | Ready to switch on | Shutdown |
//! | 3 | Ready to switch on | Switched on | Switch on (and Switch on + enable operation) |
//! | 4 | Switched on | Operation enabled | Enable operation |
//! | 5 | Operation enabled | Switched on | Disable operation |
//! | 6 | Switched on | Ready to switch on | Shutdown |
//! | 7 | Ready to switch on | Switch on disabled | Disable voltage, Quick stop |
//! | 8 | Operation enabled | Ready to switch on | Shutdown |
//! | 9 | Operation enabled | Switch on disabled | Disable voltage |
//! | 10 | Switched on | Switch on disabled | Disable voltage, Quick stop |
//! | 11 | Operation enabled | Quick stop active | Quick stop |
//! | 12 | Quick stop active | Switch on disabled | Disable voltage, or the quick stop ended (605Ah 1, 2) |
//! | 13 | any but Fault | Fault reaction active | a fault |
//! | 14 | Fault reaction active | Fault | the fault reaction ended |
//! | 15 | Fault | Switch on disabled | Fault reset (rising edge of bit 7) |
//! | 16 | Quick stop active | Operation enabled | Enable operation (605Ah 5–8 only) |
//!
//! Controlword commands (bits 7, 3, 2, 1, 0; x = any): Shutdown `0xx110`, Switch on `0x0111`, Switch on +
//! enable operation `0x1111` (transitions 3 and then 4), Disable voltage `0xxx0x`, Quick stop `0xx01x`,
//! Disable operation `0x0111`, Enable operation `0x1111`, Fault reset `0→1` on bit 7. While bit 7 is set no
//! other command applies (the standard gives every other command with bit 7 = 0).

/// A state of the power drive system state machine.
///
/// ```
/// use canopen_cia402::State;
/// assert_eq!(State::OperationEnabled.statusword_bits(), 0x0037);
/// assert_eq!(State::from_statusword(0x0237), Some(State::OperationEnabled));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum State {
    /// Low-level power on, the drive initialises and runs its self-test; brake applied, drive function
    /// disabled.
    NotReadyToSwitchOn,
    /// Initialisation done; high voltage may be off; drive function disabled.
    SwitchOnDisabled,
    /// High voltage may be applied; drive function disabled.
    ReadyToSwitchOn,
    /// High voltage applied, power amplifier ready; drive function disabled.
    SwitchedOn,
    /// No fault; drive function enabled and power applied to the motor.
    OperationEnabled,
    /// The quick stop function runs (605Ah); drive function enabled and power applied.
    QuickStopActive,
    /// A fault occurred; the fault reaction (605Eh) runs; drive function enabled and power applied while
    /// it ramps down.
    FaultReactionActive,
    /// A fault occurred; high voltage may be applied; drive function disabled.
    Fault,
}

/// Statusword bits of the state (bits 0–3, 5, 6) and "voltage enabled" (bit 4).
///
/// ```
/// use canopen_cia402::state::sw;
/// // Operation enabled: bits 0, 1, 2 and 5 (xx1x x111 in the state mask).
/// let statusword = sw::READY_TO_SWITCH_ON | sw::SWITCHED_ON | sw::OPERATION_ENABLED | sw::QUICK_STOP;
/// assert_eq!(statusword & sw::STATE_MASK, 0x0027);
/// ```
pub mod sw {
    /// Bit 0: ready to switch on.
    pub const READY_TO_SWITCH_ON: u16 = 1 << 0;
    /// Bit 1: switched on.
    pub const SWITCHED_ON: u16 = 1 << 1;
    /// Bit 2: operation enabled.
    pub const OPERATION_ENABLED: u16 = 1 << 2;
    /// Bit 3: fault.
    pub const FAULT: u16 = 1 << 3;
    /// Bit 4: voltage enabled (high voltage applied).
    pub const VOLTAGE_ENABLED: u16 = 1 << 4;
    /// Bit 5: quick stop (active low: 0 = a quick stop is active).
    pub const QUICK_STOP: u16 = 1 << 5;
    /// Bit 6: switch on disabled.
    pub const SWITCH_ON_DISABLED: u16 = 1 << 6;
    /// Bit 7: warning.
    pub const WARNING: u16 = 1 << 7;
    /// Bit 9: remote (the controlword is processed).
    pub const REMOTE: u16 = 1 << 9;
    /// Bit 10: target reached.
    pub const TARGET_REACHED: u16 = 1 << 10;
    /// Bit 11: internal limit active.
    pub const INTERNAL_LIMIT_ACTIVE: u16 = 1 << 11;
    /// Bit 12: operation mode specific (profile position: set-point acknowledge; homing: homing attained;
    /// profile velocity: speed = 0; cyclic synchronous: the drive follows the command value).
    pub const OMS_12: u16 = 1 << 12;
    /// Bit 13: operation mode specific (profile position: following error; homing: homing error).
    pub const OMS_13: u16 = 1 << 13;
    /// The bits that tell the state: 0–3, 5, 6 (mask 6Fh; 4Fh for the states where bit 5 is "x").
    pub const STATE_MASK: u16 = 0x006F;
}

/// Controlword bits (6040h).
///
/// ```
/// use canopen_cia402::state::cw;
/// // "Enable operation": switch on, enable voltage, quick stop (inactive, so set), enable operation.
/// assert_eq!(cw::SWITCH_ON | cw::ENABLE_VOLTAGE | cw::QUICK_STOP | cw::ENABLE_OPERATION, 0x000F);
/// ```
pub mod cw {
    /// Bit 0: switch on.
    pub const SWITCH_ON: u16 = 1 << 0;
    /// Bit 1: enable voltage.
    pub const ENABLE_VOLTAGE: u16 = 1 << 1;
    /// Bit 2: quick stop (active low).
    pub const QUICK_STOP: u16 = 1 << 2;
    /// Bit 3: enable operation.
    pub const ENABLE_OPERATION: u16 = 1 << 3;
    /// Bit 4: operation mode specific (profile position: new set-point; homing: start homing).
    pub const NEW_SET_POINT: u16 = 1 << 4;
    /// Bit 5: profile position: change set immediately.
    pub const CHANGE_SET_IMMEDIATELY: u16 = 1 << 5;
    /// Bit 6: profile position: the target is relative (to the last target).
    pub const RELATIVE: u16 = 1 << 6;
    /// Bit 7: fault reset (on its rising edge).
    pub const FAULT_RESET: u16 = 1 << 7;
    /// Bit 8: halt.
    pub const HALT: u16 = 1 << 8;
}

impl State {
    /// Every state of the power drive system, in the standard's order.
    ///
    /// ```
    /// use canopen_cia402::State;
    /// assert_eq!(State::ALL.len(), 8);
    /// assert!(State::ALL.iter().all(|s| State::from_statusword(s.statusword_bits()) == Some(*s)));
    /// ```
    pub const ALL: [State; 8] = [
        State::NotReadyToSwitchOn,
        State::SwitchOnDisabled,
        State::ReadyToSwitchOn,
        State::SwitchedOn,
        State::OperationEnabled,
        State::QuickStopActive,
        State::FaultReactionActive,
        State::Fault,
    ];

    /// The state's statusword bits 0–6 (bit 4 "voltage enabled" set where high voltage is applied; bit 5
    /// "quick stop" set where no quick stop is active and the standard does not leave it open).
    ///
    /// ```
    /// use canopen_cia402::State;
    /// assert_eq!(State::SwitchOnDisabled.statusword_bits(), 0x0040);
    /// assert_eq!(State::QuickStopActive.statusword_bits(), 0x0017);
    /// ```
    pub const fn statusword_bits(self) -> u16 {
        use sw::*;
        match self {
            State::NotReadyToSwitchOn => 0,
            State::SwitchOnDisabled => SWITCH_ON_DISABLED,
            State::ReadyToSwitchOn => QUICK_STOP | READY_TO_SWITCH_ON | VOLTAGE_ENABLED,
            State::SwitchedOn => QUICK_STOP | READY_TO_SWITCH_ON | SWITCHED_ON | VOLTAGE_ENABLED,
            State::OperationEnabled => {
                QUICK_STOP | READY_TO_SWITCH_ON | SWITCHED_ON | OPERATION_ENABLED | VOLTAGE_ENABLED
            }
            State::QuickStopActive => READY_TO_SWITCH_ON | SWITCHED_ON | OPERATION_ENABLED | VOLTAGE_ENABLED,
            State::FaultReactionActive => {
                FAULT | READY_TO_SWITCH_ON | SWITCHED_ON | OPERATION_ENABLED | VOLTAGE_ENABLED
            }
            State::Fault => FAULT,
        }
    }

    /// The state a statusword reports (the standard's masks: 4Fh for Not ready to switch on, Switch on
    /// disabled, Fault reaction active and Fault, 6Fh for the others); `None` for a combination that is
    /// no state.
    ///
    /// ```
    /// use canopen_cia402::State;
    /// assert_eq!(State::from_statusword(0x0008), Some(State::Fault));
    /// assert_eq!(State::from_statusword(0x0001), None);
    /// ```
    pub const fn from_statusword(word: u16) -> Option<State> {
        Some(match (word & 0x4F, word & 0x6F) {
            (0x00, _) => State::NotReadyToSwitchOn,
            (0x40, _) => State::SwitchOnDisabled,
            (0x0F, _) => State::FaultReactionActive,
            (0x08, _) => State::Fault,
            (_, 0x21) => State::ReadyToSwitchOn,
            (_, 0x23) => State::SwitchedOn,
            (_, 0x27) => State::OperationEnabled,
            (_, 0x07) => State::QuickStopActive,
            _ => return None,
        })
    }

    /// Whether the drive function is enabled and power applied to the motor in this state.
    ///
    /// ```
    /// use canopen_cia402::State;
    /// assert!(State::QuickStopActive.power_applied());
    /// assert!(!State::SwitchedOn.power_applied());
    /// ```
    pub const fn power_applied(self) -> bool {
        matches!(self, State::OperationEnabled | State::QuickStopActive | State::FaultReactionActive)
    }

    /// The state's name as python canopen's `BaseNode402.state` spells it (upper case).
    ///
    /// ```
    /// use canopen_cia402::State;
    /// assert_eq!(State::ReadyToSwitchOn.name(), "READY TO SWITCH ON");
    /// ```
    pub const fn name(self) -> &'static str {
        match self {
            State::NotReadyToSwitchOn => "NOT READY TO SWITCH ON",
            State::SwitchOnDisabled => "SWITCH ON DISABLED",
            State::ReadyToSwitchOn => "READY TO SWITCH ON",
            State::SwitchedOn => "SWITCHED ON",
            State::OperationEnabled => "OPERATION ENABLED",
            State::QuickStopActive => "QUICK STOP ACTIVE",
            State::FaultReactionActive => "FAULT REACTION ACTIVE",
            State::Fault => "FAULT",
        }
    }
}

/// A device control command decoded from the controlword 6040h.
///
/// ```
/// use canopen_cia402::Command;
/// assert_eq!(Command::decode(0x0006), Command::Shutdown);
/// assert_eq!(Command::decode(0x000F), Command::EnableOperation);
/// assert_eq!(Command::decode(0x0002), Command::QuickStop);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Command {
    /// `0xxx x110`: transitions 2, 6, 8.
    Shutdown,
    /// `0xxx 0111`: transition 3 (Switch on) and 5 (Disable operation).
    SwitchOn,
    /// `0xxx 1111`: transition 4 and 16 (Enable operation); from Ready to switch on 3 then 4.
    EnableOperation,
    /// `0xxx xx0x`: transitions 7, 9, 10, 12.
    DisableVoltage,
    /// `0xxx x01x`: transitions 7, 10, 11.
    QuickStop,
    /// Bit 7 set: fault reset on its rising edge (transition 15), nothing else while it stays set.
    FaultReset,
}

impl Command {
    /// The command a controlword encodes (bits 7, 3, 2, 1, 0).
    ///
    /// ```
    /// use canopen_cia402::Command;
    /// assert_eq!(Command::decode(0x0080), Command::FaultReset);
    /// assert_eq!(Command::decode(0x0000), Command::DisableVoltage);
    /// ```
    pub const fn decode(controlword: u16) -> Command {
        if controlword & cw::FAULT_RESET != 0 {
            Command::FaultReset
        } else if controlword & cw::ENABLE_VOLTAGE == 0 {
            Command::DisableVoltage
        } else if controlword & cw::QUICK_STOP == 0 {
            Command::QuickStop
        } else if controlword & cw::SWITCH_ON == 0 {
            Command::Shutdown
        } else if controlword & cw::ENABLE_OPERATION == 0 {
            Command::SwitchOn
        } else {
            Command::EnableOperation
        }
    }
}

/// What the table says for a state and a command: the transition number and the state it leads to.
///
/// Transitions 0, 1, 13 and 14 are not caused by a command (power on, self-test, a fault, the end of the
/// fault reaction) and 12 also ends a quick stop by itself: [`Drive`](crate::Drive) takes those. Transition
/// 16 is allowed only when the quick stop option code keeps the drive in Quick stop active
/// (`quick_stop_stays`, 605Ah 5–8). A `None` is "no transition": the state stays.
///
/// ```
/// use canopen_cia402::{transition, Command, State};
/// assert_eq!(transition(State::SwitchedOn, Command::EnableOperation, false), Some((4, State::OperationEnabled)));
/// assert_eq!(transition(State::SwitchOnDisabled, Command::EnableOperation, false), None);
/// ```
pub const fn transition(state: State, command: Command, quick_stop_stays: bool) -> Option<(u8, State)> {
    use Command as C;
    use State as S;
    Some(match (state, command) {
        (S::SwitchOnDisabled, C::Shutdown) => (2, S::ReadyToSwitchOn),
        (S::ReadyToSwitchOn, C::SwitchOn | C::EnableOperation) => (3, S::SwitchedOn),
        (S::SwitchedOn, C::EnableOperation) => (4, S::OperationEnabled),
        (S::OperationEnabled, C::SwitchOn) => (5, S::SwitchedOn),
        (S::SwitchedOn, C::Shutdown) => (6, S::ReadyToSwitchOn),
        (S::ReadyToSwitchOn, C::DisableVoltage | C::QuickStop) => (7, S::SwitchOnDisabled),
        (S::OperationEnabled, C::Shutdown) => (8, S::ReadyToSwitchOn),
        (S::OperationEnabled, C::DisableVoltage) => (9, S::SwitchOnDisabled),
        (S::SwitchedOn, C::DisableVoltage | C::QuickStop) => (10, S::SwitchOnDisabled),
        (S::OperationEnabled, C::QuickStop) => (11, S::QuickStopActive),
        (S::QuickStopActive, C::DisableVoltage) => (12, S::SwitchOnDisabled),
        (S::QuickStopActive, C::EnableOperation) if quick_stop_stays => (16, S::OperationEnabled),
        _ => return None,
    })
}

/// Every transition of the standard's table as (number, from, to) but 0 (from power-off), with each "any
/// state" of 13 spelled out: what the property tests check every observed change against.
///
/// ```
/// use canopen_cia402::{State, TABLE};
/// assert!(TABLE.contains(&(15, State::Fault, State::SwitchOnDisabled)));
/// ```
pub const TABLE: [(u8, State, State); 21] = [
    (1, State::NotReadyToSwitchOn, State::SwitchOnDisabled),
    (2, State::SwitchOnDisabled, State::ReadyToSwitchOn),
    (3, State::ReadyToSwitchOn, State::SwitchedOn),
    (4, State::SwitchedOn, State::OperationEnabled),
    (5, State::OperationEnabled, State::SwitchedOn),
    (6, State::SwitchedOn, State::ReadyToSwitchOn),
    (7, State::ReadyToSwitchOn, State::SwitchOnDisabled),
    (8, State::OperationEnabled, State::ReadyToSwitchOn),
    (9, State::OperationEnabled, State::SwitchOnDisabled),
    (10, State::SwitchedOn, State::SwitchOnDisabled),
    (11, State::OperationEnabled, State::QuickStopActive),
    (12, State::QuickStopActive, State::SwitchOnDisabled),
    (13, State::NotReadyToSwitchOn, State::FaultReactionActive),
    (13, State::SwitchOnDisabled, State::FaultReactionActive),
    (13, State::ReadyToSwitchOn, State::FaultReactionActive),
    (13, State::SwitchedOn, State::FaultReactionActive),
    (13, State::OperationEnabled, State::FaultReactionActive),
    (13, State::QuickStopActive, State::FaultReactionActive),
    (14, State::FaultReactionActive, State::Fault),
    (15, State::Fault, State::SwitchOnDisabled),
    (16, State::QuickStopActive, State::OperationEnabled),
];

#[cfg(test)]
mod tests {
    use super::*;

    const COMMANDS: [Command; 6] = [
        Command::Shutdown,
        Command::SwitchOn,
        Command::EnableOperation,
        Command::DisableVoltage,
        Command::QuickStop,
        Command::FaultReset,
    ];

    /// Every (state, command) pair against the standard's table, written out as the expected answer.
    #[test]
    fn every_command_in_every_state() {
        use Command as C;
        use State as S;
        let expected = |s: State, c: Command, stays: bool| -> Option<(u8, State)> {
            match (s, c) {
                (S::SwitchOnDisabled, C::Shutdown) => Some((2, S::ReadyToSwitchOn)),
                (S::ReadyToSwitchOn, C::SwitchOn) => Some((3, S::SwitchedOn)),
                (S::ReadyToSwitchOn, C::EnableOperation) => Some((3, S::SwitchedOn)),
                (S::SwitchedOn, C::EnableOperation) => Some((4, S::OperationEnabled)),
                (S::OperationEnabled, C::SwitchOn) => Some((5, S::SwitchedOn)),
                (S::SwitchedOn, C::Shutdown) => Some((6, S::ReadyToSwitchOn)),
                (S::ReadyToSwitchOn, C::DisableVoltage) => Some((7, S::SwitchOnDisabled)),
                (S::ReadyToSwitchOn, C::QuickStop) => Some((7, S::SwitchOnDisabled)),
                (S::OperationEnabled, C::Shutdown) => Some((8, S::ReadyToSwitchOn)),
                (S::OperationEnabled, C::DisableVoltage) => Some((9, S::SwitchOnDisabled)),
                (S::SwitchedOn, C::DisableVoltage) => Some((10, S::SwitchOnDisabled)),
                (S::SwitchedOn, C::QuickStop) => Some((10, S::SwitchOnDisabled)),
                (S::OperationEnabled, C::QuickStop) => Some((11, S::QuickStopActive)),
                (S::QuickStopActive, C::DisableVoltage) => Some((12, S::SwitchOnDisabled)),
                (S::QuickStopActive, C::EnableOperation) if stays => Some((16, S::OperationEnabled)),
                _ => None,
            }
        };
        let mut count = 0;
        for s in State::ALL {
            for c in COMMANDS {
                for stays in [false, true] {
                    assert_eq!(transition(s, c, stays), expected(s, c, stays), "{s:?} {c:?} {stays}");
                    if let Some((n, to)) = transition(s, c, stays) {
                        assert!(TABLE.contains(&(n, s, to)));
                        count += 1;
                    }
                }
            }
        }
        // 14 pairs lead somewhere in both option settings, 16 only with 605Ah 5..8.
        assert_eq!(count, 14 * 2 + 1);
    }

    #[test]
    fn statusword_round_trips_with_any_other_bits() {
        for s in State::ALL {
            let bits = s.statusword_bits();
            assert_eq!(State::from_statusword(bits), Some(s));
            // Bits 7..15 do not change the state.
            assert_eq!(State::from_statusword(bits | 0xFF80), Some(s));
        }
    }

    /// python canopen's SW_MASK table (p402.py) reads every state this module reports.
    #[test]
    fn python_canopen_masks_read_our_words() {
        let masks: [(State, u16, u16); 8] = [
            (State::NotReadyToSwitchOn, 0x4F, 0x00),
            (State::SwitchOnDisabled, 0x4F, 0x40),
            (State::ReadyToSwitchOn, 0x6F, 0x21),
            (State::SwitchedOn, 0x6F, 0x23),
            (State::OperationEnabled, 0x6F, 0x27),
            (State::Fault, 0x4F, 0x08),
            (State::FaultReactionActive, 0x4F, 0x0F),
            (State::QuickStopActive, 0x6F, 0x07),
        ];
        for (s, mask, value) in masks {
            assert_eq!(s.statusword_bits() & mask, value, "{s:?}");
        }
    }

    #[test]
    fn decode_every_controlword_pattern() {
        for word in 0..=u16::MAX {
            let c = Command::decode(word);
            let low = word & 0x8F;
            let want = if low & 0x80 != 0 {
                Command::FaultReset
            } else if low & 0x02 == 0 {
                Command::DisableVoltage
            } else if low & 0x06 == 0x02 {
                Command::QuickStop
            } else if low & 0x07 == 0x06 {
                Command::Shutdown
            } else if low & 0x0F == 0x07 {
                Command::SwitchOn
            } else {
                assert_eq!(low & 0x0F, 0x0F);
                Command::EnableOperation
            };
            assert_eq!(c, want, "{word:04X}");
        }
        // python canopen's commands (p402.py State402.CW_*).
        assert_eq!(Command::decode(0x000F), Command::EnableOperation);
        assert_eq!(Command::decode(0x0006), Command::Shutdown);
        assert_eq!(Command::decode(0x0007), Command::SwitchOn);
        assert_eq!(Command::decode(0x0002), Command::QuickStop);
        assert_eq!(Command::decode(0x0000), Command::DisableVoltage);
        assert_eq!(Command::decode(0x0080), Command::FaultReset);
    }
}
