//! The node's emergency wiring: the public raise/clear API, the EMCY producer with 1014h/1015h, the
//! Stopped rule and the EMCY consumer.
//!
//! Every error the stack raises itself follows one rule: raised when its cause appears, cleared when the cause
//! is gone; each clearing is sent as EMCY 0000h with the remaining error register (EMCY-07), and 1001h/1003h
//! follow (ERR-02, ERR-06). A code is one entry however many objects share the cause, so it is cleared only
//! when no object has the cause any more.
//!
//! | code | raised when | cleared when |
//! |---|---|---|
//! | 8110h CAN overrun | the transmit queue was full and a frame was dropped (EEC-10), once there is room for the EMCY | the transmit queue has drained empty: every frame queued since the overflow, the 8110h EMCY included, went out (only an 8110h the stack raised; one the application raises is the application's to clear) |
//! | 8120h CAN in error passive | the controller reports error passive, [`BusState::ErrorPassive`] (EEC-11) | the controller reports error active again, [`BusState::ErrorActive`], or restarts after bus-off, [`BusState::Recovered`] |
//! | 8130h heartbeat / life guarding | a monitored node's heartbeat times out (HB-11, HB-13) or life guarding times out (GUARD-11) | no monitored node is timed out (each lost one heard again, or its 1016h entry removed) and life guarding is not (the guarding master's next request, or 100Ch/100Dh rewritten) |
//! | 8140h recovered from bus-off | the controller restarts after bus-off, [`BusState::Recovered`] (EEC-13); the bus-off itself is a communication error for 1029h:01 (ERR-13) and sends nothing, the controller being off the bus | the first frame received after the restart (the bus carries frames again), or the controller reports [`BusState::ErrorActive`] |
//! | 8210h / 8220h PDO length | an RPDO shorter / longer than its mapping (PDO-39) | no RPDO's last frame had a wrong length |
//! | 8240h SYNC length | a SYNC with the wrong DLC (SYNC-14) | the next SYNC of the right length |
//! | 8250h RPDO time-out | an RPDO event-timer deadline passes (PDO-12, EEC-20) | no RPDO is timed out (each received again) |
//!
//! A reset communication or reset node clears them all (1001h = 0). Errors the application raises with
//! [`Node::raise_error`] are cleared by it with [`Node::clear_error`].

use super::{Node, NodeSizes};
use crate::bus::BusState;
use crate::cob::CobIdEntry;
use crate::emcy::codes;
use crate::event::Event;
use crate::frame::CanFrame;
use crate::nmt::{NmtState, Service};
use crate::od::ObjectDictionary;
use crate::storage::Storage;
use crate::time::{Deadline, Instant};
use crate::wire::emcy::Emergency;

impl<A: ObjectDictionary, Z: NodeSizes, S: Storage> Node<A, Z, S> {
    /// Raises error `code` with manufacturer bytes `manufacturer` (EMCY-05/07, ERR-02, ERR-06/07): 1001h and
    /// 1003h follow, an EMCY is queued (spaced by 1015h, held in Stopped). Returns `false` when the code is
    /// already active (nothing is repeated) or is 0000h.
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{Node, NoApplication}, od::ObjectDictionary, Instant, NodeId};
    /// let mut node: Node<NoApplication> = Node::new(NodeId::new(3).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// node.handle_timeout(Instant::ZERO);
    /// while node.poll_transmit().is_some() {}
    /// assert!(node.raise_error(0x1000, [0; 5]));
    /// assert_eq!(node.poll_transmit().map(|f| (f.cob_id(), f.padded())), Some((0x83, [0x00, 0x10, 0x01, 0, 0, 0, 0, 0]))); // generic error 1000h, error register 01h
    /// let mut reg = [0u8; 1];
    /// assert_eq!(node.dictionary().read(0x1001, 0, 0, &mut reg), Ok(1)); // 1001h (ERR-01/02)
    /// assert_eq!(reg, [0x01]);
    /// assert!(node.clear_error(0x1000));
    /// assert_eq!(node.poll_transmit().unwrap().data(), &[0; 8]); // error reset: code 0000h, register 00h
    /// assert_eq!(node.dictionary().read(0x1001, 0, 0, &mut reg), Ok(1));
    /// assert_eq!(reg, [0x00]);
    /// ```
    // Inline: the five bytes go on as a u32 and a u8, in registers, to the out-of-line body; as an array
    // every caller built them on its stack and passed a pointer (footprint.sh node 56 B more).
    #[inline]
    pub fn raise_error(&mut self, code: u16, manufacturer: [u8; 5]) -> bool {
        let (low, high) = crate::emcy::manufacturer_in_registers(manufacturer);
        self.raise_error_in_registers(code, low, high)
    }

    /// [`raise_error`](Self::raise_error) with manufacturer bytes 0-3 in `low` (little-endian) and byte 4 in
    /// `high`.
    // Out of line on a bare-metal target, as LTO had it there, said here: with the active set's change
    // now one shared function (`ErrorState::change`), the smaller bodies were otherwise inlined into the
    // firmware's driver task (footprint.sh node +536 B). Not on a host: there the hint cost the RPDO path 2
    // instructions per frame (bench-node.sh), where the inlined copies cost nothing.
    #[cfg_attr(target_os = "none", inline(never))]
    fn raise_error_in_registers(&mut self, code: u16, low: u32, high: u8) -> bool {
        // 1001h reads the active errors' register (`NodeErrors`) itself: no copy into the parameters.
        let raised = self.comm.errors.raise_in_registers(code, low, high);
        self.flush_emcy(self.now);
        raised
    }

    /// Clears error `code`: an EMCY 0000h with the remaining register follows (EMCY-07). Returns `false` when
    /// the code was not active.
    #[cfg_attr(target_os = "none", inline(never))] // as raise_error_in_registers
    pub fn clear_error(&mut self, code: u16) -> bool {
        let cleared = self.comm.errors.clear(code);
        self.flush_emcy(self.now);
        cleared
    }

    /// The CAN controller's state changed (see [`crate::bus`] and the table above): error passive raises
    /// 8120h (EEC-11), error active clears it, bus-off is a communication error for 1029h:01 (ERR-10..13),
    /// the restart after bus-off sends 8140h (EEC-13). A state equal to the last one reported does nothing.
    ///
    /// ```
    /// use canopen_core::{bus::BusState, profile::NodeConfig, node::{Node, NoApplication}, Instant, NodeId};
    /// let mut node: Node<NoApplication> = Node::new(NodeId::new(3).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// node.handle_timeout(Instant::ZERO);
    /// while node.poll_transmit().is_some() {}
    /// node.set_bus_state(Instant::ZERO, BusState::ErrorPassive);
    /// assert_eq!(node.poll_transmit().unwrap().data(), &[0x20, 0x81, 0x11, 0, 0, 0, 0, 0]);
    /// node.set_bus_state(Instant::ZERO, BusState::ErrorActive);
    /// assert_eq!(node.poll_transmit().unwrap().data(), &[0; 8]);
    /// assert_eq!(node.bus_state(), BusState::ErrorActive);
    /// ```
    pub fn set_bus_state(&mut self, now: Instant, state: BusState) {
        self.ensure_booted(now);
        if state == self.bus {
            return;
        }
        self.bus = state;
        match state {
            BusState::ErrorActive => {
                self.clear_error(codes::CAN_ERROR_PASSIVE);
                self.bus_works_again();
            }
            BusState::Warning => {}
            BusState::ErrorPassive => {
                self.raise_error(codes::CAN_ERROR_PASSIVE, [0; 5]);
            }
            BusState::BusOff => self.communication_error(now),
            BusState::Recovered => {
                self.raise_error(codes::RECOVERED_FROM_BUS_OFF, [0; 5]);
                self.bus_recovered = true;
                self.clear_error(codes::CAN_ERROR_PASSIVE);
            }
        }
    }

    /// The CAN controller's last reported state ([`BusState::ErrorActive`] until one is reported).
    pub const fn bus_state(&self) -> BusState {
        self.bus
    }

    /// 8140h is cleared: the bus carries frames again.
    pub(super) fn bus_works_again(&mut self) {
        if core::mem::take(&mut self.bus_recovered) {
            self.clear_error(codes::RECOVERED_FROM_BUS_OFF);
        }
    }

    /// The error register 1001h.
    pub fn error_register(&self) -> u8 {
        self.comm.errors.register()
    }

    /// Moves pending EMCYs to the transmit queue while the state, the 1015h inhibit time and the queue
    /// allow (EMCY-08/09, NMT-22). A not-valid 1014h (bit 31) drops them: there is no EMCY object.
    ///
    /// Called after every transmitted frame: the check for pending EMCYs is inlined into the caller, the
    /// work is out of line ([`flush_emcy`](Self::flush_emcy)).
    #[inline]
    pub(super) fn pump_emcy(&mut self, now: Instant) {
        if self.comm.errors.has_pending() {
            self.flush_emcy(now);
        }
    }

    /// [`pump_emcy`](Self::pump_emcy) without the inlined check: for callers that have just queued an EMCY.
    #[inline(never)]
    pub(super) fn flush_emcy(&mut self, now: Instant) {
        let cob = CobIdEntry::from_raw(self.comm.params.emcy_cob_id);
        if cob.bit31() {
            self.comm.errors.drop_pending();
            return;
        }
        match self.nmt.state() {
            NmtState::Stopped => return self.comm.errors.keep_most_recent(),
            NmtState::Initialising => return,
            _ => {}
        }
        // No `has_pending` test here: `pop_pending` answers it (the other two tests have no side effect).
        while self.emcy.may_send(now) && !self.tx.is_full() {
            let Some(e) = self.comm.errors.pop_pending() else { break };
            self.send(cob.can_id(), e.emit(), 8);
            self.emcy.sent(now);
        }
    }

    pub(super) fn emcy_timeout(&self) -> Deadline {
        let sendable = self.nmt.state().allows(Service::Emcy) && self.comm.errors.has_pending();
        if sendable {
            self.emcy.deadline()
        } else {
            Deadline::NONE
        }
    }

    /// Another node's EMCY, `node` the producer's node-ID (EMCY-11: reported, the reaction is the
    /// application's): without the `emcy-consumer` feature every EMCY on 081h–0FFh, with it those on a valid
    /// 1028h entry's CAN-ID (EMCY-10, `node` its sub-index). EMCY-06: an RTR is never answered.
    pub(super) fn handle_emcy(&mut self, node: u8, frame: &CanFrame) {
        if frame.is_rtr() || node == self.node_id.get() || !self.nmt.state().allows(Service::Emcy) {
            return;
        }
        if let Ok(emcy) = Emergency::parse(frame.data()) {
            self.push_event(Event::Emergency { node, emcy });
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::node::{NoApplication, Node};
    use crate::od::ObjectDictionary;
    use crate::profile::NodeConfig;
    use crate::{CanFrame, Instant, NodeId};

    /// EMCY-12, ERR-06, ERR-07: an application error's five manufacturer bytes go out unchanged after the
    /// error register, and its 1003h entry carries the first two in bits 31-16 above the code; the clearing
    /// EMCY 0000h carries none (EMCY-07).
    #[test]
    fn manufacturer_bytes_in_the_emcy_and_the_history_emcy_12_err_07() {
        let mut n: Node<NoApplication> = Node::new(NodeId::new(3).unwrap(), NodeConfig::DEFAULT, NoApplication);
        n.handle_timeout(Instant::ZERO);
        while n.poll_transmit().is_some() {}
        assert!(n.raise_error(0xFF01, [0x11, 0x22, 0x33, 0x44, 0x55]));
        assert_eq!(n.poll_transmit(), CanFrame::new(0x83, &[0x01, 0xFF, 0x81, 0x11, 0x22, 0x33, 0x44, 0x55]));
        if cfg!(feature = "error-history") {
            let mut entry = [0u8; 4];
            assert_eq!(n.dictionary().read(0x1003, 1, 0, &mut entry), Ok(4));
            assert_eq!(u32::from_le_bytes(entry), 0x2211_FF01);
        }
        assert!(n.clear_error(0xFF01));
        assert_eq!(n.poll_transmit(), CanFrame::new(0x83, &[0; 8]));
    }

    /// EMCY-06, EMCY-11, CAN-07: a remote frame on another node's EMCY CAN-ID is no EMCY (it has no data):
    /// no event, whatever its DLC, and no answer; the same CAN-ID with 8 data bytes is reported
    /// (EMCY-11).
    #[test]
    fn remote_frames_on_an_emcy_id_are_no_emcy_emcy_06() {
        let mut n: Node<NoApplication> = Node::new(NodeId::new(3).unwrap(), NodeConfig::DEFAULT, NoApplication);
        n.handle_timeout(Instant::ZERO);
        while n.poll_transmit().is_some() {}
        while n.poll_event().is_some() {}
        for dlc in [0, 1, 8] {
            n.handle_frame(Instant::ZERO, &CanFrame::new_rtr(0x85, dlc).unwrap());
        }
        assert_eq!((n.poll_transmit(), n.poll_event()), (None, None));
        // (With the `emcy-consumer` feature only a valid 1028h entry's CAN-ID is consumed: none by default.)
        if !cfg!(feature = "emcy-consumer") {
            n.handle_frame(Instant::ZERO, &CanFrame::new(0x85, &[0x00, 0x10, 0x01, 0, 0, 0, 0, 0]).unwrap());
            assert!(matches!(n.poll_event(), Some(crate::event::Event::Emergency { node: 5, .. })));
        }
    }
}
