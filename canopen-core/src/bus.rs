//! The CAN controller's state as the node hears it (CiA 301 EMCY 8120h/8140h, 1029h:01).
//!
//! An adapter that can see the controller (the kernel's error frames on SocketCAN; a status register on a
//! microcontroller) reports each change with [`Node::set_bus_state`](crate::Node::set_bus_state); the node
//! raises and clears the matching emergencies (see the table in the [`node`](crate::node) error docs):
//!
//! | state | the node |
//! |---|---|
//! | [`BusState::ErrorActive`] | clears 8120h and 8140h |
//! | [`BusState::Warning`] | nothing (CiA 301 has no code for it) |
//! | [`BusState::ErrorPassive`] | raises 8120h (EEC-11) |
//! | [`BusState::BusOff`] | a communication error for 1029h:01 (ERR-10, ERR-13) |
//! | [`BusState::Recovered`] | clears 8120h, raises 8140h (EEC-13), cleared by the next frame received |

/// A state of the CAN controller (ISO 11898-1 fault confinement), plus the restart after bus-off.
///
/// ```
/// use canopen_core::bus::BusState;
/// assert!(BusState::BusOff.is_error());
/// assert!(!BusState::Warning.is_error());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BusState {
    /// Both error counters below 96 (or back below 128 from passive): normal operation.
    ErrorActive,
    /// An error counter reached the warning level (96): still error active on the bus.
    Warning,
    /// An error counter reached 128: the controller sends passive error flags only.
    ErrorPassive,
    /// The transmit error counter passed 255: the controller is off the bus.
    BusOff,
    /// The controller restarted after bus-off and takes part in the bus again, error active.
    Recovered,
}

impl BusState {
    /// Whether the state is an error the node reports (error passive or bus-off).
    ///
    /// ```
    /// assert!(canopen_core::bus::BusState::ErrorPassive.is_error());
    /// ```
    pub const fn is_error(self) -> bool {
        matches!(self, BusState::ErrorPassive | BusState::BusOff)
    }
}

impl core::fmt::Display for BusState {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            BusState::ErrorActive => "error active",
            BusState::Warning => "error warning",
            BusState::ErrorPassive => "error passive",
            BusState::BusOff => "bus-off",
            BusState::Recovered => "recovered from bus-off",
        })
    }
}
