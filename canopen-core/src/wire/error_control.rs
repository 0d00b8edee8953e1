//! NMT error-control frames on 700h + node (NMT-23..NMT-25, HB-02, GUARD-05, GUARD-06, GUARD-13):
//! boot-up (`00h`), heartbeat (state code, bit 7 = 0) and the node-guarding reply (bit 7 = toggle,
//! bits 6–0 = state). The guarding request is an RTR frame on the same identifier.

use super::WireError;

/// The NMT state codes carried by error-control frames (NMT-25).
///
/// ```
/// use canopen_core::wire::error_control::StateCode;
/// assert_eq!(StateCode::from_code(0x7F), Some(StateCode::PreOperational));
/// assert_eq!(StateCode::from_code(0x01), None); // pre-v4 "disconnected" is not a CiA 301 v4.2 state (GUARD-13)
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u8)]
pub enum StateCode {
    /// 00h: boot-up.
    BootUp = 0x00,
    /// 04h: Stopped.
    Stopped = 0x04,
    /// 05h: Operational.
    Operational = 0x05,
    /// 7Fh: Pre-operational.
    PreOperational = 0x7F,
}

impl StateCode {
    /// The state for a 7-bit code, `None` if CiA 301 v4.2 does not define it.
    pub const fn from_code(code: u8) -> Option<Self> {
        Some(match code {
            0x00 => StateCode::BootUp,
            0x04 => StateCode::Stopped,
            0x05 => StateCode::Operational,
            0x7F => StateCode::PreOperational,
            _ => return None,
        })
    }
}

/// A heartbeat or boot-up message: one byte, the state code with bit 7 = 0 (HB-02, NMT-23).
///
/// ```
/// use canopen_core::wire::error_control::{Heartbeat, StateCode};
/// assert_eq!(Heartbeat::parse(&[0x7F]), Ok(Heartbeat(StateCode::PreOperational))); // heartbeat 705 [1] 7F
/// assert_eq!(Heartbeat(StateCode::BootUp).emit(), [0x00]); // boot-up 705 [1] 00
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Heartbeat(pub StateCode);

impl Heartbeat {
    /// Parses a heartbeat/boot-up payload: exactly one byte with bit 7 clear and a defined state code.
    pub fn parse(data: &[u8]) -> Result<Self, WireError> {
        let [b] = data else {
            return Err(WireError::Length);
        };
        if b & 0x80 != 0 {
            return Err(WireError::Value);
        }
        StateCode::from_code(*b).map(Heartbeat).ok_or(WireError::Value)
    }

    /// The one data byte.
    pub const fn emit(&self) -> [u8; 1] {
        [self.0 as u8]
    }
}

/// A node-guarding reply: bit 7 toggle, bits 6–0 state (GUARD-06).
///
/// ```
/// use canopen_core::wire::error_control::{GuardReply, StateCode};
/// let r = GuardReply { toggle: true, state: StateCode::PreOperational };
/// assert_eq!(r.emit(), [0xFF]); // toggle 1, Pre-operational
/// assert_eq!(GuardReply::parse(&[0x85]), Ok(GuardReply { toggle: true, state: StateCode::Operational }));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct GuardReply {
    /// The toggle bit.
    pub toggle: bool,
    /// The node's state (never boot-up in a reply).
    pub state: StateCode,
}

impl GuardReply {
    /// Parses a reply: one byte, state 04h/05h/7Fh (GUARD-13).
    pub fn parse(data: &[u8]) -> Result<Self, WireError> {
        let [b] = data else {
            return Err(WireError::Length);
        };
        match StateCode::from_code(b & 0x7F) {
            Some(StateCode::BootUp) | None => Err(WireError::Value),
            Some(state) => Ok(GuardReply { toggle: b & 0x80 != 0, state }),
        }
    }

    /// The one data byte.
    pub const fn emit(&self) -> [u8; 1] {
        [(self.toggle as u8) << 7 | self.state as u8]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// State bytes 04h Stopped, 05h Operational, 7Fh Pre-operational; a guarding reply adds the toggle in bit 7
    /// (85h = toggle 1, Operational) and the pre-v4 states 1, 2, 3 are refused.
    #[test]
    fn state_code_vectors() {
        assert_eq!(Heartbeat::parse(&[0x04]), Ok(Heartbeat(StateCode::Stopped)));
        assert_eq!(Heartbeat::parse(&[0x05]), Ok(Heartbeat(StateCode::Operational)));
        assert_eq!(Heartbeat::parse(&[0x7F]), Ok(Heartbeat(StateCode::PreOperational)));
        assert_eq!(GuardReply { toggle: false, state: StateCode::Stopped }.emit(), [0x04]);
        assert_eq!(GuardReply { toggle: true, state: StateCode::Operational }.emit(), [0x85]);
        for legacy in [1u8, 2, 3] {
            assert_eq!(GuardReply::parse(&[legacy]), Err(WireError::Value));
        }
    }

    #[test]
    fn malformed() {
        assert_eq!(Heartbeat::parse(&[]), Err(WireError::Length));
        assert_eq!(Heartbeat::parse(&[0x05, 0x00]), Err(WireError::Length));
        assert_eq!(Heartbeat::parse(&[0x85]), Err(WireError::Value));
        assert_eq!(GuardReply::parse(&[0x80]), Err(WireError::Value));
    }
}
