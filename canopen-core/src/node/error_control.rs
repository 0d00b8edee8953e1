//! The node's NMT node control and error control: NMT commands addressed to it (NMT-08: its own node-ID or
//! 0 for all; CAN-07: a malformed command is ignored; NMT-14: never answered), node guarding answered as the
//! NMT slave (GUARD-05: an RTR; HB-05: only while the heartbeat producer is off), remote heartbeats fed to
//! the consumer (HB-10/HB-11), and what an error-control loss does: EMCY 8130h while it lasts (see `errors.rs`)
//! and a communication error (HB-13, GUARD-11), whose reaction 1029h sub 01h chooses (NMT-26, ERR-10..13).
//!
//! The heartbeat producer and the time-outs are driven from [`Node::handle_timeout`]; the services
//! themselves (`heartbeat`, `guarding`, `nmt`) know nothing of the node.

use super::{Node, NodeSizes};
use crate::cob::FunctionCode;
use crate::emcy::codes;
use crate::event::Event;
use crate::frame::CanFrame;
use crate::heartbeat::ConsumerEvent;
use crate::nmt::{NmtState, Service, Transition};
use crate::od::ObjectDictionary;
use crate::storage::Storage;
use crate::time::Instant;
use crate::wire::error_control::Heartbeat;
use crate::wire::nmt::NodeControl;

impl<A: ObjectDictionary, Z: NodeSizes, S: Storage> Node<A, Z, S> {
    /// Out of line (a node-control command is rare; inlined into the frame dispatch it was 4 B more of the
    /// minimal firmware's flash).
    #[inline(never)]
    pub(super) fn handle_node_control(&mut self, now: Instant, frame: &CanFrame) {
        // CAN-07: a malformed node-control frame is ignored; an RTR too (its data is empty), so the frame
        // dispatch does not test for one.
        let Ok(request) = NodeControl::parse(frame.data()) else {
            return;
        };
        if !request.addresses(self.node_id.get()) {
            return;
        }
        let from = self.nmt.state();
        match self.nmt.handle_command(request.command) {
            Transition::None => {}
            Transition::Enter(to) => self.state_changed(from, to),
            // One call for both resets (NMT-04/NMT-05): reset node also runs Reset Application.
            t => self.reset(t == Transition::ResetApplication, now),
        }
    }

    /// An NMT error-control frame (701h..77Fh) of node `node`, one path with one exit for both services:
    /// on the node's own ID it is a node-guarding request, answered as the NMT slave (GUARD-05: an RTR;
    /// HB-05: only while the heartbeat producer is off; GUARD-11: a guarding master heard again after a
    /// life-guarding time-out resolves it), on another ID a remote heartbeat fed to the consumer (HB-10,
    /// HB-11: a node heard again after its time-out resumes). Both only where NMT allows error control;
    /// an event that resolves a loss clears 8130h once no other loss remains.
    pub(super) fn handle_error_control(&mut self, now: Instant, node: u8, frame: &CanFrame) {
        if !self.nmt.state().allows(Service::ErrorControl) {
            return;
        }
        // (event, whether it resolves an error-control loss)
        let outcome = if node == self.node_id.get() {
            #[cfg(not(feature = "guarding"))]
            return;
            #[cfg(feature = "guarding")]
            {
                if !frame.is_rtr() || self.producer.is_active() {
                    return;
                }
                let (reply, resolved) = self.guarding.handle_request(
                    now,
                    self.nmt.state().state_code(),
                    self.comm.params.guard_time_ms,
                    self.comm.params.life_time_factor,
                );
                self.send_error_control(reply.emit());
                resolved.map(|ev| (Event::LifeGuarding(ev), true))
            }
        } else {
            if frame.is_rtr() {
                return;
            }
            let Ok(Heartbeat(state)) = Heartbeat::parse(frame.data()) else {
                return;
            };
            self.consumer
                .handle_heartbeat(now, node, state)
                .map(|ev| (Event::Heartbeat(ev), matches!(ev, ConsumerEvent::Resumed { .. })))
        };
        if let Some((event, resolves)) = outcome {
            self.push_event(event);
            if resolves {
                self.error_control_recovered();
            }
        }
    }

    /// EMCY 8130h is cleared once its cause is gone: no monitored node is timed out and life guarding is not
    /// (the node's error state machine then sends EMCY 0000h with the remaining error register, EMCY-07).
    pub(super) fn error_control_recovered(&mut self) {
        #[cfg(feature = "guarding")]
        if self.guarding.is_timed_out() {
            return;
        }
        if !self.consumer.any_timed_out() {
            self.clear_error(codes::HEARTBEAT_OR_LIFE_GUARD);
        }
    }

    /// A heartbeat consumer or life guarding time-out (HB-11, GUARD-10): reported, EMCY 8130h, and a
    /// communication error (HB-13, GUARD-11).
    pub(super) fn error_control_lost(&mut self, now: Instant, event: Event) {
        self.push_event(event);
        self.raise_error(codes::HEARTBEAT_OR_LIFE_GUARD, [0; 5]);
        self.communication_error(now);
    }

    /// HB-13, GUARD-11, NMT-26, ERR-10..13: a communication error; 1029h sub 01h says what happens: 0 (the
    /// default) Operational → Pre-operational, 1 no change, 2 Stopped, 80h–FFh (manufacturer) as 1. Out of
    /// line: reached from the bus-off report and every error-control time-out, all rare. A build without
    /// 1029h (the Cargo feature `error-behaviour`) always does 0.
    #[inline(never)]
    pub(super) fn communication_error(&mut self, _now: Instant) {
        let behaviour = if cfg!(feature = "error-behaviour") { self.comm.params.error_behaviour } else { 0 };
        match behaviour {
            0 if self.nmt.state() == NmtState::Operational => self.enter_state(NmtState::PreOperational),
            2 => self.enter_state(NmtState::Stopped),
            _ => {}
        }
    }

    /// Out of line: one copy for its three callers (heartbeat, boot-up, guarding reply), 20 B of the node
    /// firmware's flash less than inlined into each.
    #[inline(never)]
    pub(super) fn send_error_control(&mut self, data: [u8; 1]) {
        let mut buf = [0u8; 8];
        buf[0] = data[0];
        self.send(FunctionCode::NmtErrorControl.cob_id(self.node_id), buf, 1)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use crate::node::{NoApplication, Node};
    use crate::profile::NodeConfig;
    use crate::{CanFrame, Instant, NodeId};
    use std::vec::Vec;

    fn drain(n: &mut Node<NoApplication>) -> Vec<CanFrame> {
        core::iter::from_fn(|| n.poll_transmit()).collect()
    }

    /// The one error-control path's branches (GUARD-05, HB-05, HB-10): on the node's own ID only an RTR is
    /// a guarding request and only while the producer is off; on another ID only a data frame is a
    /// heartbeat; 700h (node 0) is neither.
    #[test]
    fn error_control_frames_are_told_apart_guard_05_hb_05_hb_10() {
        let cfg = NodeConfig { guard_time_ms: 100, life_time_factor: 3, ..NodeConfig::DEFAULT };
        let mut n: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), cfg, NoApplication);
        n.handle_timeout(Instant::ZERO);
        drain(&mut n);
        while n.poll_event().is_some() {}
        let t = Instant::from_millis(10);
        // Own ID, data frame: not a guarding request.
        n.handle_frame(t, &CanFrame::new(0x705, &[0x7F]).unwrap());
        // Node 0 and a remote RTR: nothing.
        n.handle_frame(t, &CanFrame::new_rtr(0x700, 1).unwrap());
        n.handle_frame(t, &CanFrame::new_rtr(0x706, 1).unwrap());
        assert_eq!(drain(&mut n), []);
        // A remote heartbeat 1016h does not monitor: no event.
        n.handle_frame(t, &CanFrame::new(0x706, &[0x05]).unwrap());
        assert_eq!(n.poll_event(), None);
        // Own ID, RTR, producer off: answered with toggle 0 and state 7Fh (when node guarding is built in).
        n.handle_frame(t, &CanFrame::new_rtr(0x705, 1).unwrap());
        let answer = Vec::from([CanFrame::new(0x705, &[0x7F]).unwrap()]);
        assert_eq!(drain(&mut n), if cfg!(feature = "guarding") { answer } else { Vec::new() });
        // HB-05: with the producer on, a guarding request is not answered.
        n.set_heartbeat_time(t, 100);
        n.handle_frame(t, &CanFrame::new_rtr(0x705, 1).unwrap());
        assert_eq!(drain(&mut n), []);
    }

    /// A full event queue drops the new event and counts it (`Node::events_dropped`), keeping the older
    /// ones in order: 20 node-control transitions (NMT-09, NMT-11) with nobody polling the 16 events.
    #[test]
    fn a_full_event_queue_drops_and_counts_the_newest_nmt_09_nmt_11() {
        use crate::event::Event;
        use crate::nmt::NmtState::{Operational, PreOperational};
        let mut n: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
        n.handle_timeout(Instant::ZERO);
        drain(&mut n);
        while n.poll_event().is_some() {}
        for i in 0..20 {
            let cs = if i % 2 == 0 { 0x01 } else { 0x80 }; // start, enter pre-operational
            n.handle_frame(Instant::ZERO, &CanFrame::new(0x000, &[cs, 5]).unwrap());
        }
        assert_eq!(n.events_dropped(), 4);
        let events: Vec<Event> = core::iter::from_fn(|| n.poll_event()).collect();
        assert_eq!(events.len(), 16);
        for (i, e) in events.iter().enumerate() {
            let (from, to) = if i % 2 == 0 { (PreOperational, Operational) } else { (Operational, PreOperational) };
            assert_eq!(*e, Event::StateChanged { from, to });
        }
    }
}
