//! NMT node-control frame (NMT-07..NMT-14): CAN-ID 000h, DLC 2, byte 0 command specifier,
//! byte 1 target node-ID (00h = all nodes).

use super::WireError;

/// NMT node-control command specifiers (NMT-09..NMT-13).
///
/// ```
/// use canopen_core::wire::nmt::NmtCommand;
/// assert_eq!(NmtCommand::from_cs(0x82), Some(NmtCommand::ResetCommunication));
/// assert_eq!(NmtCommand::ResetNode as u8, 0x81);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u8)]
pub enum NmtCommand {
    /// 01h: start remote node → Operational (NMT-09).
    Start = 0x01,
    /// 02h: stop remote node → Stopped (NMT-10).
    Stop = 0x02,
    /// 80h: enter Pre-operational (NMT-11).
    EnterPreOperational = 0x80,
    /// 81h: reset node → Reset Application (NMT-12).
    ResetNode = 0x81,
    /// 82h: reset communication (NMT-13; the Chinese translation of CiA 301 §7.2.8.3.1.5
    /// misprints 129, the value of Reset Node).
    ResetCommunication = 0x82,
}

impl NmtCommand {
    /// The command for a command specifier byte, `None` if undefined.
    pub const fn from_cs(cs: u8) -> Option<Self> {
        Some(match cs {
            0x01 => NmtCommand::Start,
            0x02 => NmtCommand::Stop,
            0x80 => NmtCommand::EnterPreOperational,
            0x81 => NmtCommand::ResetNode,
            0x82 => NmtCommand::ResetCommunication,
            _ => return None,
        })
    }
}

/// A node-control request: command and target (0 = broadcast).
///
/// ```
/// use canopen_core::wire::nmt::{NmtCommand, NodeControl};
/// let req = NodeControl::parse(&[0x01, 0x06]).unwrap(); // start node 6
/// assert_eq!(req, NodeControl { command: NmtCommand::Start, node: 6 });
/// assert!(req.addresses(6) && !req.addresses(5));
/// assert_eq!(NodeControl { command: NmtCommand::Stop, node: 0 }.emit(), [0x02, 0x00]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct NodeControl {
    /// The command.
    pub command: NmtCommand,
    /// The addressed node-ID, 0 = all nodes.
    pub node: u8,
}

impl NodeControl {
    /// Parses the 2 data bytes; any other length or an unknown command specifier is an error (CAN-07: ignore).
    pub fn parse(data: &[u8]) -> Result<Self, WireError> {
        let [cs, node] = data else {
            return Err(WireError::Length);
        };
        let command = NmtCommand::from_cs(*cs).ok_or(WireError::Value)?;
        Ok(NodeControl { command, node: *node })
    }

    /// The 2 data bytes.
    pub const fn emit(&self) -> [u8; 2] {
        [self.command as u8, self.node]
    }

    /// Whether a node with ID `own` must act on it (NMT-08: own ID or 00h).
    pub const fn addresses(&self, own: u8) -> bool {
        self.node == 0 || self.node == own
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Node control frames: stop all (02 00), reset node 42 (81 2A), pre-operational all / node 5 (80 00,
    /// 80 05), reset communication (82 05); a start for node 7 (01 07) does not address node 5, a broadcast does.
    #[test]
    fn nmt_vectors() {
        let v = |b: [u8; 2]| NodeControl::parse(&b).unwrap();
        assert_eq!(v([0x02, 0x00]), NodeControl { command: NmtCommand::Stop, node: 0 });
        assert_eq!(v([0x81, 0x2A]), NodeControl { command: NmtCommand::ResetNode, node: 42 });
        assert_eq!(v([0x80, 0x00]), NodeControl { command: NmtCommand::EnterPreOperational, node: 0 });
        assert_eq!(v([0x80, 0x05]), NodeControl { command: NmtCommand::EnterPreOperational, node: 5 });
        assert_eq!(v([0x82, 0x05]).command, NmtCommand::ResetCommunication);
        assert!(!v([0x01, 0x07]).addresses(5));
        assert!(v([0x02, 0x00]).addresses(5));
    }

    #[test]
    fn malformed_is_an_error() {
        assert_eq!(NodeControl::parse(&[]), Err(WireError::Length));
        assert_eq!(NodeControl::parse(&[0x01, 0x05, 0x00]), Err(WireError::Length));
        assert_eq!(NodeControl::parse(&[0x03, 0x05]), Err(WireError::Value));
        for cs in 0..=255u8 {
            let ok = NodeControl::parse(&[cs, 1]).is_ok();
            assert_eq!(ok, matches!(cs, 0x01 | 0x02 | 0x80 | 0x81 | 0x82));
        }
    }
}
