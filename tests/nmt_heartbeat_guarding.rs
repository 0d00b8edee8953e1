//! Integration tests on the in-memory bus: NMT command sequences, heartbeat timelines, node guarding.
//! Expected frames are written out byte for byte; requirement IDs (`docs/CONFORMANCE.md`) are
//! cited per test.

mod common;

use canopen::core::{
    guarding::LifeGuardingEvent,
    heartbeat::ConsumerEvent,
    node::{NoApplication, Node},
    profile::NodeConfig,
    wire::error_control::StateCode,
    CanFrame, Event, NmtState, NodeId, Sizes,
};
use common::{events, frame, ms, Bus, Sender};

type TestNode = Node<NoApplication, Sizes<4>>;

fn node(id: u8, heartbeat_ms: u16) -> TestNode {
    let cfg = NodeConfig { heartbeat_time_ms: heartbeat_ms, ..NodeConfig::DEFAULT };
    Node::new(NodeId::new(id).unwrap(), cfg, NoApplication)
}

fn states(bus: &Bus<TestNode>) -> Vec<NmtState> {
    bus.stations.iter().map(|n| n.state()).collect()
}

/// NMT-03, NMT-23, NMT-24: every node boots by itself into Pre-operational with one boot-up frame.
/// NMT-02: the node starts in Initialising and passes its reset sub-states (reset application, reset
/// communication) before Pre-operational, as its events show.
#[test]
fn power_on_boot_up() {
    let mut bus = Bus::new(vec![node(5, 0), node(6, 0), node(42, 0)]);
    bus.run_until(ms(0));
    let boot: Vec<_> = bus.log.iter().map(|s| s.frame).collect();
    assert_eq!(boot, vec![frame("705 [1] 00"), frame("706 [1] 00"), frame("72A [1] 00")]);
    assert_eq!(states(&bus), vec![NmtState::PreOperational; 3]);
    let ev = events(&mut bus.stations[0]);
    assert_eq!(
        ev,
        vec![
            Event::ResetApplication,
            Event::ResetCommunication,
            Event::StateChanged { from: NmtState::Initialising, to: NmtState::PreOperational }
        ]
    );
    // Nothing else is sent with heartbeat off: no periodic traffic.
    bus.run_for_ms(10_000);
    assert_eq!(bus.log.len(), 3);
}

/// NMT-07..NMT-15: unicast and broadcast commands; the slaves never answer on 000h.
/// NMT-01 and COB-02: each node is an NMT slave obeying commands addressed to its own node-ID (06h moves
/// only node 6; 07h, absent, moves none) or to 0, which addresses all. NMT-02: the states the nodes walk
/// through are Pre-operational, Operational and Stopped, and the Initialisation sub-states reset node and
/// reset communication each end with a boot-up into Pre-operational.
#[test]
fn nmt_command_sequence() {
    let mut bus = Bus::new(vec![node(5, 0), node(6, 0), node(42, 0)]);
    bus.run_until(ms(0));
    bus.log.clear();
    bus.take_master_rx();
    use NmtState::*;

    bus.inject(frame("000 [2] 01 06")); // start node 6
    assert_eq!(states(&bus), vec![PreOperational, Operational, PreOperational]);
    bus.inject(frame("000 [2] 01 07")); // start, addressed to a node that is not here
    assert_eq!(states(&bus), vec![PreOperational, Operational, PreOperational]);
    bus.inject(frame("000 [2] 01 00")); // start all
    assert_eq!(states(&bus), vec![Operational; 3]);
    bus.inject(frame("000 [2] 02 00")); // stop all
    assert_eq!(states(&bus), vec![Stopped; 3]);
    bus.inject(frame("000 [2] 80 05")); // pre-operational, node 5
    assert_eq!(states(&bus), vec![PreOperational, Stopped, Stopped]);
    bus.inject(frame("000 [2] 80 00")); // pre-operational, all
    assert_eq!(states(&bus), vec![PreOperational; 3]);
    bus.inject(frame("000 [2] 01 00"));
    // No slave ever transmitted during the commands (NMT-14).
    assert!(bus.log.iter().all(|s| s.from == Sender::Master));

    // Reset node 42 (81 2A) → boot-up 72A [1] 00 and Pre-operational; the others stay Operational.
    bus.inject(frame("000 [2] 81 2A"));
    assert_eq!(states(&bus), vec![Operational, Operational, PreOperational]);
    let replies: Vec<_> = bus.take_master_rx().into_iter().map(|s| s.frame).collect();
    assert_eq!(replies, vec![frame("72A [1] 00")]);
    // Reset communication (82 00), broadcast.
    bus.inject(frame("000 [2] 82 00"));
    let replies: Vec<_> = bus.take_master_rx().into_iter().map(|s| s.frame).collect();
    assert_eq!(replies, vec![frame("705 [1] 00"), frame("706 [1] 00"), frame("72A [1] 00")]);
    assert_eq!(states(&bus), vec![PreOperational; 3]);
}

/// CAN-07: malformed node-control frames change nothing and get no answer.
#[test]
fn malformed_nmt_frames_are_ignored() {
    let mut bus = Bus::new(vec![node(5, 0)]);
    bus.run_until(ms(0));
    bus.take_master_rx();
    for f in [
        CanFrame::new(0x000, &[0x01]).unwrap(),
        CanFrame::new(0x000, &[0x01, 0x05, 0x00]).unwrap(),
        CanFrame::new(0x000, &[0x03, 0x05]).unwrap(),
        CanFrame::new_rtr(0x000, 2).unwrap(),
        CanFrame::new(0x005, &[0x01, 0x05]).unwrap(), // node part must be 0 on the NMT COB
    ] {
        bus.inject(f);
        assert_eq!(bus.stations[0].state(), NmtState::PreOperational, "{f:?}");
    }
    assert!(bus.take_master_rx().is_empty());
}

/// HB-02..HB-04, NMT-18, NMT-21: the heartbeat timeline of node 5 at 100 ms: the boot-up 705 [1] 00, then
/// 705 [1] 7F / 05 / 04 every 100 ms in Pre-operational / Operational / Stopped, a new boot-up after reset
/// communication.
/// GUARD-01 (at least one error-control protocol): the heartbeat producer is one (node guarding, the other,
/// is proven by `guarding_toggle_sequence_vector`).
#[test]
fn heartbeat_timeline_vector() {
    let mut bus = Bus::new(vec![node(5, 100)]);
    bus.run_until(ms(250));
    bus.inject(frame("000 [2] 01 05")); // step 3 at 250 ms
    bus.run_until(ms(450));
    bus.inject(frame("000 [2] 02 05")); // step 5 at 450 ms
    bus.run_until(ms(650));
    bus.inject(frame("000 [2] 82 05")); // step 7 at 650 ms
    bus.run_until(ms(850));
    let hb: Vec<(u64, u8)> = bus.frames_on(0x705).into_iter().map(|(t, d)| (t, d[0])).collect();
    assert_eq!(
        hb,
        vec![
            (0, 0x00), // boot-up = first heartbeat
            (100, 0x7F),
            (200, 0x7F),
            (300, 0x05),
            (400, 0x05),
            (500, 0x04), // heartbeat continues in Stopped
            (600, 0x04),
            (650, 0x00), // reset communication: boot-up, and the timer restarts from it
            (750, 0x7F),
            (850, 0x7F),
        ]
    );
}

/// HB-04: a written period takes effect at once; 0 stops the producer. 2B 17 10 00 64 00 00 00 sets 100 ms.
#[test]
fn heartbeat_period_change() {
    let mut bus = Bus::new(vec![node(9, 0)]);
    bus.run_until(ms(1000));
    let now = bus.now;
    bus.stations[0].set_heartbeat_time(now, 100);
    bus.run_until(ms(1250));
    let now = bus.now;
    bus.stations[0].set_heartbeat_time(now, 30);
    bus.run_until(ms(1345));
    let now = bus.now;
    bus.stations[0].set_heartbeat_time(now, 0);
    bus.run_until(ms(3000));
    let times: Vec<u64> = bus.frames_on(0x709).into_iter().map(|(t, _)| t).collect();
    assert_eq!(times, vec![0, 1100, 1200, 1280, 1310, 1340]);
}

/// NMT-05, NMT-06: reset communication brings the communication parameters back to their power-on values.
#[test]
fn reset_communication_restores_comm_parameters() {
    let mut bus = Bus::new(vec![node(5, 100)]);
    bus.run_until(ms(0));
    bus.stations[0].set_heartbeat_time(ms(0), 20);
    bus.stations[0].set_consumer_heartbeat(ms(0), 1, 0x0002_0064).unwrap();
    bus.stations[0].set_life_guarding(ms(0), 100, 3);
    bus.inject(frame("000 [2] 82 05"));
    let p = bus.stations[0].params();
    assert_eq!(p.heartbeat_time_ms, 100);
    assert_eq!(p.heartbeat_consumers, [0; 4]);
    assert_eq!((p.guard_time_ms, p.life_time_factor), (0, 0));
}

/// HB-06..HB-11, NMT-26: node 9 monitors node 2 (100 ms) and node 7 (never present).
#[test]
fn heartbeat_consumer_timeline() {
    let mut bus = Bus::new(vec![node(9, 0), node(2, 50)]);
    bus.run_until(ms(0));
    let now = bus.now;
    bus.stations[0].set_consumer_heartbeat(now, 1, 0x0002_0064).unwrap();
    bus.stations[0].set_consumer_heartbeat(now, 2, 0x0007_0FA0).unwrap();
    // Node 2 in a second entry is refused with 0604 0043h (HB-09).
    assert_eq!(
        bus.stations[0].set_consumer_heartbeat(now, 3, 0x0002_00C8),
        Err(canopen::core::od::AbortCode::ParameterIncompatibility)
    );
    bus.inject(frame("000 [2] 01 00"));
    events(&mut bus.stations[0]);
    bus.run_until(ms(500));
    let ev = events(&mut bus.stations[0]);
    assert_eq!(
        ev,
        vec![
            Event::Heartbeat(ConsumerEvent::Started { node: 2, state: StateCode::Operational }),
            // Node 2 was already Operational at its first heartbeat after the start command.
        ]
    );
    // Node 2 goes silent after its heartbeat at 500 ms (its producer stops): one consumer time later, at
    // 600 ms, a time-out (HB-11), and node 9 leaves Operational for Pre-operational (NMT-26 default).
    assert_eq!(bus.frames_on(0x702).last(), Some(&(500, vec![0x05])));
    bus.stations[1].set_heartbeat_time(ms(500), 0);
    bus.run_until(ms(599));
    assert!(events(&mut bus.stations[0]).is_empty());
    bus.run_until(ms(600));
    assert_eq!(
        events(&mut bus.stations[0]),
        vec![
            Event::Heartbeat(ConsumerEvent::Timeout { node: 2 }),
            Event::StateChanged { from: NmtState::Operational, to: NmtState::PreOperational }
        ]
    );
    // Node 7 never sent anything: no time-out for it, even after its 4 s (HB-10).
    bus.run_until(ms(10_000));
    assert!(events(&mut bus.stations[0]).is_empty());
    // Recovery: node 2 produces again.
    bus.stations[1].set_heartbeat_time(ms(10_000), 50);
    bus.run_until(ms(10_050));
    assert_eq!(
        events(&mut bus.stations[0]),
        vec![Event::Heartbeat(ConsumerEvent::Resumed { node: 2, state: StateCode::Operational })]
    );
    // State change of the producer is reported; then it reboots (reset node) and that is reported too.
    bus.inject(frame("000 [2] 02 02"));
    bus.run_until(ms(10_100));
    assert_eq!(
        events(&mut bus.stations[0]),
        vec![Event::Heartbeat(ConsumerEvent::StateChanged {
            node: 2,
            from: StateCode::Operational,
            to: StateCode::Stopped
        })]
    );
    bus.inject(frame("000 [2] 81 02"));
    let ev = events(&mut bus.stations[0]);
    assert_eq!(ev, vec![Event::Heartbeat(ConsumerEvent::Rebooted { node: 2 })]);
    // Disabling the entry (1016h:01 = 0) stops monitoring: node 2 silent again, no time-out.
    bus.stations[0].set_consumer_heartbeat(bus.now, 1, 0).unwrap();
    bus.stations[1].set_heartbeat_time(bus.now, 0);
    bus.run_for_ms(1000);
    assert!(events(&mut bus.stations[0]).is_empty());
}

/// GUARD-05..GUARD-08: the toggle sequence of node 5: each 705 [RTR] is answered with the
/// state (7Fh, 05h, 04h) and a toggle bit 7 that alternates from 0 (7F, 85, 7F, FF, ..), back to 0 after reset
/// communication.
/// GUARD-01: node guarding is offered as an error-control protocol.
#[test]
fn guarding_toggle_sequence_vector() {
    let mut bus = Bus::new(vec![node(5, 0)]);
    bus.run_until(ms(0));
    bus.take_master_rx();
    let steps: [(&str, Option<&str>); 10] = [
        ("705 [RTR]", Some("705 [1] 7F")),
        ("000 [2] 01 05", None),
        ("705 [RTR]", Some("705 [1] 85")),
        ("000 [2] 80 05", None),
        ("705 [RTR]", Some("705 [1] 7F")),
        ("705 [RTR]", Some("705 [1] FF")),
        ("000 [2] 02 05", None),
        ("705 [RTR]", Some("705 [1] 04")),
        ("000 [2] 82 05", Some("705 [1] 00")),
        ("705 [RTR]", Some("705 [1] 7F")),
    ];
    for (i, (request, reply)) in steps.iter().enumerate() {
        bus.run_for_ms(10);
        bus.inject(frame(request));
        let got: Vec<CanFrame> = bus.take_master_rx().into_iter().map(|s| s.frame).collect();
        let want: Vec<CanFrame> = reply.iter().map(|r| frame(r)).collect();
        assert_eq!(got, want, "step {}", i + 1);
    }
    // A guarding RTR with DLC 1 (as some masters send) is answered too; a data frame on 705h is not a request.
    bus.inject(CanFrame::new_rtr(0x705, 1).unwrap());
    assert_eq!(bus.take_master_rx().len(), 1);
    bus.inject(frame("705 [1] 00"));
    assert!(bus.take_master_rx().is_empty());
}

/// GUARD-12 with a lost reply: the master polls at the guard time and checks the toggle; a lost reply is
/// detected by the master, the slave's toggle keeps alternating per request it received, and because the
/// request itself arrived the slave's life guarding is not disturbed.
#[test]
fn guarding_with_a_lost_reply() {
    let mut bus = Bus::new(vec![node(5, 0)]);
    bus.run_until(ms(0));
    bus.stations[0].set_life_guarding(ms(0), 100, 3);
    bus.take_master_rx();
    let mut replies = Vec::new();
    for k in 0..6u64 {
        if k == 2 {
            bus.lose_next(|f| f.cob_id() == 0x705 && !f.is_rtr());
        }
        bus.run_until(ms(100 * (k + 1)));
        bus.inject(frame("705 [RTR]"));
        replies.push(bus.take_master_rx().into_iter().map(|s| s.frame.data()[0]).next());
    }
    assert_eq!(replies, vec![Some(0x7F), Some(0xFF), None, Some(0xFF), Some(0x7F), Some(0xFF)]);
    // The master sees that the toggle did not alternate between the 2nd and 4th replies (it never saw the 3rd).
    assert!(events(&mut bus.stations[0]).iter().all(|e| !matches!(e, Event::LifeGuarding(_))));
}

/// GUARD-04, GUARD-09..GUARD-11, NMT-26: life guarding starts with the first RTR; no RTR within
/// 100Ch × 100Dh → event and Operational → Pre-operational; RTRs again → resolved.
#[test]
fn life_guarding_timeout_and_recovery() {
    let mut bus = Bus::new(vec![node(5, 0)]);
    bus.run_until(ms(0));
    bus.stations[0].set_life_guarding(ms(0), 100, 3);
    bus.inject(frame("000 [2] 01 05"));
    bus.run_until(ms(5_000)); // no RTR yet: life guarding not started
    events(&mut bus.stations[0]);
    assert_eq!(bus.stations[0].state(), NmtState::Operational);
    bus.inject(frame("705 [RTR]"));
    bus.run_until(ms(5_299));
    assert!(events(&mut bus.stations[0]).is_empty());
    bus.run_until(ms(5_300));
    assert_eq!(
        events(&mut bus.stations[0]),
        vec![
            Event::LifeGuarding(LifeGuardingEvent::Timeout),
            Event::StateChanged { from: NmtState::Operational, to: NmtState::PreOperational }
        ]
    );
    // GUARD-11, EMCY-07: the life-guarding time-out raised 8130h (register 11h) ...
    assert_eq!(bus.frames_on(0x085), vec![(5_300, vec![0x30, 0x81, 0x11, 0, 0, 0, 0, 0])]);
    bus.run_until(ms(6_000));
    bus.inject(frame("705 [RTR]"));
    assert_eq!(events(&mut bus.stations[0]), vec![Event::LifeGuarding(LifeGuardingEvent::Resolved)]);
    // ... and the guarding master resuming clears it (issue 22): EMCY 0000h, register 00h.
    assert_eq!(bus.frames_on(0x085)[1..], [(6_000, vec![0; 8])]);
    assert_eq!(bus.stations[0].error_register(), 0);
}

/// HB-05: while the heartbeat producer runs, guarding requests are not answered.
#[test]
fn heartbeat_and_guarding_never_both_active() {
    let mut bus = Bus::new(vec![node(5, 100)]);
    bus.run_until(ms(50));
    bus.take_master_rx();
    bus.inject(frame("705 [RTR]"));
    assert!(bus.take_master_rx().is_empty());
    bus.stations[0].set_heartbeat_time(ms(50), 0);
    bus.inject(frame("705 [RTR]"));
    assert_eq!(bus.take_master_rx().len(), 1);
}

/// The runner contract: poll_timeout says exactly when the next work is due, so no tick is needed.
#[test]
fn poll_timeout_is_exact() {
    let mut n = node(5, 100);
    assert_eq!(n.poll_timeout(), Some(ms(0)));
    n.handle_timeout(ms(3));
    assert_eq!(n.poll_timeout(), Some(ms(103)));
    n.handle_timeout(ms(50)); // early: nothing happens
    assert_eq!(n.poll_transmit(), Some(frame("705 [1] 00")));
    assert_eq!(n.poll_transmit(), None);
    n.handle_timeout(ms(103));
    assert_eq!(n.poll_transmit(), Some(frame("705 [1] 7F")));
}

/// The bounded transmit queue drops the newest frame when full and counts it; the loss is reported by EMCY
/// 8110h (CAN overrun, EEC-10) once there is room.
#[test]
fn full_transmit_queue_is_counted() {
    let cfg = NodeConfig::DEFAULT;
    let mut n: Node<NoApplication, Sizes<1, 2, 4>> = Node::new(NodeId::new(5).unwrap(), cfg, NoApplication);
    n.handle_timeout(ms(0)); // boot-up
    for _ in 0..3 {
        n.handle_frame(ms(1), &frame("705 [RTR]"));
    }
    assert_eq!(n.tx_dropped(), 2);
    assert_eq!(n.poll_transmit(), Some(frame("705 [1] 00")));
    assert_eq!(n.poll_transmit(), Some(frame("705 [1] 7F")));
    assert_eq!(n.poll_transmit(), Some(frame("085 [8] 10 81 11 00 00 00 00 00")));
    assert_eq!(n.error_register(), 0x00, "8110h is cleared once everything queued since the overflow went out");
    // EMCY-07: the clearing is sent as EMCY 0000h with the remaining register.
    assert_eq!(n.poll_transmit(), Some(frame("085 [8] 00 00 00 00 00 00 00 00")));
    assert_eq!(n.poll_transmit(), None);
}

/// Issue 22: the stack clears only the 8110h it raised itself; an 8110h the application raises (the example
/// node's 2100h error injection does) stays until the application clears it.
#[test]
fn application_raised_overrun_is_the_applications_to_clear() {
    let mut n: Node<NoApplication, Sizes<1, 4, 4>> =
        Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
    n.handle_timeout(ms(0));
    while n.poll_transmit().is_some() {}
    assert!(n.raise_error(0x8110, [0; 5]));
    assert_eq!(n.poll_transmit(), Some(frame("085 [8] 10 81 11 00 00 00 00 00")));
    for _ in 0..3 {
        assert_eq!(n.poll_transmit(), None);
    }
    assert_eq!(n.error_register(), 0x11);
    assert!(n.clear_error(0x8110));
    assert_eq!(n.poll_transmit(), Some(frame("085 [8] 00 00 00 00 00 00 00 00")));
}

/// Node 9 consumes the heartbeats of nodes 2 and 3 (100 ms each) and says so on its EMCY COB-ID 089h.
fn watcher_bus() -> Bus<TestNode> {
    let mut bus = Bus::booted(vec![node(9, 0), node(2, 50), node(3, 50)]);
    let now = bus.now;
    bus.stations[0].set_consumer_heartbeat(now, 1, 0x0002_0064).unwrap();
    bus.stations[0].set_consumer_heartbeat(now, 2, 0x0003_0064).unwrap();
    bus.run_until(ms(60)); // both monitored nodes heard once: monitoring started (HB-10)
    bus
}

fn emcys(bus: &Bus<TestNode>) -> Vec<(u64, Vec<u8>)> {
    bus.frames_on(0x089)
}

/// EMCY-07, ERR-02, HB-11, HB-13 (issue 22): a heartbeat time-out raises EMCY 8130h with 1001h = 11h; when the
/// monitored node is heard again the error is cleared: EMCY 0000h with register 00h, 1001h back to 0. Lost
/// again, raised again.
#[test]
fn heartbeat_error_is_cleared_when_the_node_is_heard_again() {
    let mut bus = watcher_bus();
    bus.stations[1].set_heartbeat_time(ms(60), 0); // node 2 falls silent after its heartbeat at 50 ms
    bus.run_until(ms(149));
    assert!(emcys(&bus).is_empty());
    bus.run_until(ms(150));
    assert_eq!(emcys(&bus), vec![(150, vec![0x30, 0x81, 0x11, 0, 0, 0, 0, 0])]);
    assert_eq!(bus.stations[0].error_register(), 0x11);
    bus.run_until(ms(400));
    assert_eq!(emcys(&bus).len(), 1, "the error is not repeated while it lasts");
    // Node 2 produces again: its first heartbeat ends the time-out and clears 8130h.
    bus.stations[1].set_heartbeat_time(ms(400), 50);
    bus.run_until(ms(450));
    assert_eq!(emcys(&bus)[1..], [(450, vec![0; 8])]);
    assert_eq!(bus.stations[0].error_register(), 0x00);
    // Lost again: raised again.
    bus.stations[1].set_heartbeat_time(ms(460), 0);
    bus.run_until(ms(600));
    assert_eq!(emcys(&bus)[2..], [(550, vec![0x30, 0x81, 0x11, 0, 0, 0, 0, 0])]);
    assert_eq!(bus.stations[0].error_register(), 0x11);
}

/// Issue 22: with two monitored nodes lost, 8130h stays until BOTH are heard again; an application error
/// raised meanwhile keeps its bit in the register sent with the clearing (EMCY-07, ERR-02).
#[test]
fn heartbeat_error_waits_for_every_lost_node_and_keeps_other_errors() {
    let mut bus = watcher_bus();
    bus.stations[1].set_heartbeat_time(ms(60), 0);
    bus.stations[2].set_heartbeat_time(ms(60), 0);
    bus.run_until(ms(200));
    assert_eq!(emcys(&bus), vec![(150, vec![0x30, 0x81, 0x11, 0, 0, 0, 0, 0])], "one EMCY for one active code");
    // The application raises a device-specific error (FF00h: register bit 7 and bit 0).
    assert!(bus.stations[0].raise_error(0xFF00, [1, 2, 3, 4, 5]));
    bus.run_until(ms(210));
    assert_eq!(emcys(&bus)[1..], [(200, vec![0x00, 0xFF, 0x91, 1, 2, 3, 4, 5])]);
    // Node 2 back, node 3 still silent: 8130h stays.
    bus.stations[1].set_heartbeat_time(ms(300), 50);
    bus.run_until(ms(400));
    assert_eq!(emcys(&bus).len(), 2);
    assert_eq!(bus.stations[0].error_register(), 0x91);
    // Node 3 back: 8130h cleared; the register sent keeps the application's error (bits 7 and 0).
    bus.stations[2].set_heartbeat_time(ms(400), 50);
    bus.run_until(ms(450));
    assert_eq!(emcys(&bus)[2..], [(450, vec![0, 0, 0x81, 0, 0, 0, 0, 0])]);
    assert_eq!(bus.stations[0].error_register(), 0x81);
    // The application clears its own error: register 0.
    assert!(bus.stations[0].clear_error(0xFF00));
    bus.run_until(ms(460));
    assert_eq!(emcys(&bus)[3..], [(450, vec![0; 8])]);
    assert_eq!(bus.stations[0].error_register(), 0);
}

/// Issue 22: removing the entry of a timed-out node (1016h:01 = 0) removes the cause: 8130h is cleared.
#[test]
fn heartbeat_error_is_cleared_when_the_lost_node_is_no_longer_monitored() {
    let mut bus = watcher_bus();
    bus.stations[1].set_heartbeat_time(ms(60), 0);
    bus.run_until(ms(200));
    assert_eq!(bus.stations[0].error_register(), 0x11);
    let now = bus.now;
    bus.stations[0].set_consumer_heartbeat(now, 1, 0).unwrap();
    bus.run_until(ms(210));
    assert_eq!(emcys(&bus)[1..], [(200, vec![0; 8])]);
    assert_eq!(bus.stations[0].error_register(), 0);
}

/// NMT-16, NMT-17: local control may enter Operational without a master; a local reset node boots again.
#[test]
fn local_control_and_local_reset() {
    let mut bus = Bus::new(vec![node(5, 0)]);
    bus.run_until(ms(0));
    events(&mut bus.stations[0]);
    bus.take_master_rx();
    bus.stations[0].enter_state(NmtState::Operational);
    assert_eq!(
        events(&mut bus.stations[0]),
        vec![Event::StateChanged { from: NmtState::PreOperational, to: NmtState::Operational }]
    );
    bus.stations[0].enter_state(NmtState::Operational); // already there: no event
    assert!(events(&mut bus.stations[0]).is_empty());
    bus.stations[0].enter_state(NmtState::Initialising); // not a local target: ignored
    assert_eq!(bus.stations[0].state(), NmtState::Operational);
    let now = bus.now;
    bus.stations[0].reset_node(now);
    bus.run_for_ms(1);
    assert_eq!(bus.take_master_rx().iter().map(|s| s.frame).collect::<Vec<_>>(), vec![frame("705 [1] 00")]);
    assert_eq!(
        events(&mut bus.stations[0]),
        vec![
            Event::ResetApplication,
            Event::ResetCommunication,
            Event::StateChanged { from: NmtState::Initialising, to: NmtState::PreOperational }
        ]
    );
}
