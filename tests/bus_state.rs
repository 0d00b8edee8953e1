//! The CAN controller's state reaches the node (issue 22 item 2): a simulated controller walks error active
//! → warning → error passive → bus-off → recovered → error active, with simulated time, and the EMCY frames
//! and 1001h are checked at each step. EEC-11 (8120h), EEC-13 (8140h), ERR-10..13 (bus-off is a
//! communication error for 1029h:01), EMCY-07 (each clearing is EMCY 0000h with the remaining register).

use canopen::core::{
    bus::BusState, node::NoApplication, node::Node, profile::NodeConfig, CanFrame, Instant, NmtState, NodeId,
};

fn booted(id: u8) -> Node<NoApplication> {
    let mut node = Node::new(NodeId::new(id).unwrap(), NodeConfig::DEFAULT, NoApplication);
    node.handle_timeout(Instant::ZERO);
    while node.poll_transmit().is_some() {}
    node
}

/// Every frame the node queued, as (COB-ID, the 8 padded bytes).
fn sent(node: &mut Node<NoApplication>) -> Vec<(u16, [u8; 8])> {
    std::iter::from_fn(|| node.poll_transmit()).map(|f| (f.cob_id(), f.padded())).collect()
}

fn ms(v: u64) -> Instant {
    Instant::from_millis(v)
}

/// EMCY of node 5: code, register, no manufacturer bytes.
fn emcy(code: u16, register: u8) -> (u16, [u8; 8]) {
    let c = code.to_le_bytes();
    (0x085, [c[0], c[1], register, 0, 0, 0, 0, 0])
}

/// EEC-11, EEC-13, ERR-12/13, EMCY-07: the whole walk with the default 1029h:01 (0: Operational →
/// Pre-operational on a communication error).
#[test]
fn controller_walks_active_passive_bus_off_recovered_active() {
    let mut node = booted(5);
    node.handle_frame(ms(1), &CanFrame::new(0x000, &[0x01, 0x05]).unwrap()); // NMT start
    assert_eq!(node.state(), NmtState::Operational);
    sent(&mut node);

    // Warning: no CiA 301 code, nothing sent, 1001h stays 0.
    node.set_bus_state(ms(10), BusState::Warning);
    assert_eq!(sent(&mut node), []);
    assert_eq!(node.error_register(), 0);

    // Error passive: 8120h, register generic + communication (11h).
    node.set_bus_state(ms(20), BusState::ErrorPassive);
    assert_eq!(sent(&mut node), [emcy(0x8120, 0x11)]);
    assert_eq!(node.error_register(), 0x11);
    // Reported again: nothing is repeated.
    node.set_bus_state(ms(21), BusState::ErrorPassive);
    assert_eq!(sent(&mut node), []);

    // Bus-off: a communication error (ERR-12/13: Operational → Pre-operational); nothing can be sent.
    node.set_bus_state(ms(30), BusState::BusOff);
    assert_eq!(node.state(), NmtState::PreOperational);
    assert_eq!(node.error_register(), 0x11);
    assert_eq!(sent(&mut node), []);

    // Restarted: 8140h (register still 11h), then 8120h cleared: EMCY 0000h with the remaining register 11h
    // (8140h is still active).
    node.set_bus_state(ms(40), BusState::Recovered);
    assert_eq!(sent(&mut node), [emcy(0x8140, 0x11), emcy(0x0000, 0x11)]);
    assert_eq!(node.error_register(), 0x11);
    assert_eq!(node.state(), NmtState::PreOperational, "nothing but the master moves the node back");

    // The first frame received after the restart: the bus works, 8140h is cleared, register 0.
    node.handle_frame(ms(50), &CanFrame::new(0x701, &[0x05]).unwrap());
    assert_eq!(sent(&mut node), [emcy(0x0000, 0x00)]);
    assert_eq!(node.error_register(), 0);
    node.handle_frame(ms(51), &CanFrame::new(0x701, &[0x05]).unwrap());
    assert_eq!(sent(&mut node), [], "cleared once");

    // Error active: nothing left to clear.
    node.set_bus_state(ms(60), BusState::ErrorActive);
    assert_eq!(sent(&mut node), []);
    assert_eq!(node.bus_state(), BusState::ErrorActive);
}

/// EEC-11, EMCY-07: back to error active from passive clears 8120h; a restart that the controller reports
/// as error active before any frame was received clears 8140h too.
#[test]
fn error_active_clears_8120h_and_8140h() {
    let mut node = booted(5);
    node.set_bus_state(ms(1), BusState::ErrorPassive);
    node.set_bus_state(ms(2), BusState::ErrorActive);
    assert_eq!(sent(&mut node), [emcy(0x8120, 0x11), emcy(0x0000, 0x00)]);
    node.set_bus_state(ms(3), BusState::BusOff);
    node.set_bus_state(ms(4), BusState::Recovered);
    node.set_bus_state(ms(5), BusState::ErrorActive);
    assert_eq!(sent(&mut node), [emcy(0x8140, 0x11), emcy(0x0000, 0x00)]);
    assert_eq!(node.error_register(), 0);
}

/// ERR-10, ERR-11, ERR-13: 1029h:01 = 2 makes a bus-off enter Stopped; 1 leaves the state alone.
#[test]
fn bus_off_follows_1029h_01() {
    for (behaviour, expect) in [(1u8, NmtState::Operational), (2, NmtState::Stopped)] {
        let mut node = booted(5);
        node.handle_frame(ms(1), &CanFrame::new(0x605, &[0x2F, 0x29, 0x10, 0x01, behaviour, 0, 0, 0]).unwrap());
        assert_eq!(sent(&mut node), [(0x585, [0x60, 0x29, 0x10, 0x01, 0, 0, 0, 0])]);
        node.handle_frame(ms(2), &CanFrame::new(0x000, &[0x01, 0x05]).unwrap());
        node.set_bus_state(ms(3), BusState::BusOff);
        assert_eq!(node.state(), expect, "1029h:01 = {behaviour}");
    }
}

/// An application error raised through the public API stays in 1001h while the bus errors come and go.
#[test]
fn application_error_keeps_its_bit_through_bus_errors() {
    let mut node = booted(5);
    assert!(node.raise_error(0x4200, [0; 5])); // temperature, device
    node.set_bus_state(ms(1), BusState::ErrorPassive);
    node.set_bus_state(ms(2), BusState::ErrorActive);
    assert_eq!(sent(&mut node), [emcy(0x4200, 0x09), emcy(0x8120, 0x19), emcy(0x0000, 0x09)]);
    assert!(node.clear_error(0x4200));
    assert_eq!(sent(&mut node), [emcy(0x0000, 0x00)]);
}
