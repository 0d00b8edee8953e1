//! Property test: random frames on every COB-ID, with random time steps, never make a node panic, and
//! everything it sends is a frame the spec allows it to send (CAN-07, NMT-14, NMT-18, HB-02, GUARD-06,
//! PDO-04, EMCY-04/08, SYNC-04/05, TIME-04/05).

use canopen::core::{
    comm::NodeConfig,
    node::{NoApplication, Node},
    od::AbortCode,
    pdo::PdoDefault,
    sync::SyncParams,
    wire::emcy::Emergency,
    wire::sdo::{BlockSegment, ServerResponse},
    CanFrame, Instant, NmtState, NodeId,
};
use proptest::prelude::*;

#[derive(Debug, Clone)]
enum Input {
    Frame { id: u16, rtr: bool, data: Vec<u8> },
    Wait(u64),
}

fn input() -> impl Strategy<Value = Input> {
    let frame = |(id, rtr, data)| Input::Frame { id, rtr, data };
    prop_oneof![
        // Any identifier at all...
        (0u16..=0x7FF, any::<bool>(), prop::collection::vec(any::<u8>(), 0..=8)).prop_map(frame),
        // ...and a bias towards the identifiers the node listens on, with plausible payloads...
        (
            prop::sample::select(vec![0x000u16, 0x705, 0x702, 0x77F]),
            any::<bool>(),
            prop::collection::vec(any::<u8>(), 0..=3)
        )
            .prop_map(frame),
        // ...SDO requests to this node, with a valid command byte aimed at 1017h half the time...
        (
            prop::sample::select(vec![0x20u8, 0x21, 0x23, 0x2B, 0x40, 0x60, 0x70, 0x80, 0xA0, 0xA3, 0xC2, 0xC6]),
            any::<[u8; 7]>(),
            any::<bool>()
        )
            .prop_map(|(cs, rest, aimed)| {
                let mut data = vec![if aimed { cs } else { rest[0] }];
                data.extend_from_slice(&rest);
                if aimed {
                    data[1..4].copy_from_slice(&[0x17, 0x10, 0x00]);
                }
                Input::Frame { id: 0x605, rtr: false, data }
            }),
        // ...PDO, SYNC, TIME and EMCY identifiers of this node and others, any length...
        (
            prop::sample::select(vec![0x080u16, 0x081, 0x085, 0x100, 0x185, 0x205, 0x305, 0x285]),
            any::<bool>(),
            prop::collection::vec(any::<u8>(), 0..=8)
        )
            .prop_map(frame),
        // ...NMT commands, so that every state is visited...
        prop::sample::select(vec![[0x01u8, 0x05], [0x02, 0x00], [0x80, 0x05], [0x82, 0x00]])
            .prop_map(|d| Input::Frame { id: 0x000, rtr: false, data: d.to_vec() }),
        (0u64..300_000).prop_map(Input::Wait),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 384, ..ProptestConfig::default() })]

    #[test]
    fn random_frames_never_panic_and_replies_are_well_formed(
        inputs in prop::collection::vec(input(), 1..200),
        heartbeat in prop::sample::select(vec![0u16, 1, 50, 1000]),
    ) {
        const RPDO: &[PdoDefault] = &[PdoDefault { mapping: &[0x0005_0008, 0x0006_0010], event_timer_ms: 20, ..PdoDefault::EVENT }, PdoDefault { transmission_type: 1, mapping: &[0x0007_0020], ..PdoDefault::EVENT }];
        const TPDO: &[PdoDefault] = &[PdoDefault { mapping: &[0x1001_0008], event_timer_ms: 30, inhibit_100us: 50, ..PdoDefault::EVENT }, PdoDefault { transmission_type: 2, mapping: &[0x1001_0008], ..PdoDefault::EVENT }];
        let sync = SyncParams { counter_overflow: 4, ..SyncParams::DEFAULT };
        let cfg = NodeConfig { heartbeat_time_ms: heartbeat, guard_time_ms: 10, life_time_factor: 2, rpdo: RPDO, tpdo: TPDO, sync, time_cob_id: 0xC000_0100, ..NodeConfig::DEFAULT };
        let mut node: Node<NoApplication, 2, 8, 8> = Node::new(NodeId::new(5).unwrap(), cfg, NoApplication);
        let _ = node.set_consumer_heartbeat(Instant::ZERO, 1, 0x0002_0032);
        let mut now = Instant::ZERO;
        for inp in inputs {
            match inp {
                Input::Frame { id, rtr, data } => {
                    let f = if rtr { CanFrame::new_rtr(id, data.len() as u8) } else { CanFrame::new(id, &data) };
                    node.handle_frame(now, &f.unwrap());
                    node.handle_timeout(now);
                }
                Input::Wait(us) => {
                    now = Instant::from_micros(now.as_micros() + us);
                    node.handle_timeout(now);
                }
            }
            // Every input was followed by handle_timeout or cannot create a due deadline: a deadline at or
            // before `now` would make a runner spin.
            if let Some(t) = node.poll_timeout() {
                prop_assert!(t > now, "deadline {:?} not after now {:?}", t, now);
            }
            while let Some(out) = node.poll_transmit() {
                prop_assert!(!out.is_rtr());
                let state = node.state();
                match out.cob_id() {
                    // EMCY (EMCY-04): DLC 8, never in Stopped (EMCY-08); the register has bit 0 iff the code
                    // is not 0000h or other errors remain.
                    0x085 => {
                        prop_assert_eq!(out.data().len(), 8);
                        prop_assert!(state != NmtState::Stopped);
                        let e = Emergency::parse(out.data()).unwrap();
                        prop_assert!(e.code == 0 || e.register & 1 == 1, "{:?}", e);
                    }
                    // TPDOs only in Operational (PDO-04), with the mapped length (1001h: 1 byte).
                    0x185 | 0x285 => {
                        prop_assert_eq!(state, NmtState::Operational);
                        prop_assert_eq!(out.data().len(), 1);
                    }
                    // Boot-up, heartbeat or guarding reply: DLC 1, a CiA 301 v4.2 state code.
                    0x705 => {
                        prop_assert_eq!(out.data().len(), 1);
                        let b = out.data()[0] & 0x7F;
                        prop_assert!(matches!(b, 0x00 | 0x04 | 0x05 | 0x7F), "state code {:02X}", b);
                    }
                    // SDO: DLC 8, a well-formed server frame; an abort carries a Table 22 code.
                    0x585 => {
                        prop_assert_eq!(out.data().len(), 8);
                        match ServerResponse::parse(out.data()) {
                            Ok(ServerResponse::Abort { code, .. }) => prop_assert!(AbortCode::from_code(code).is_some()),
                            Ok(_) => {}
                            Err(_) => prop_assert!(BlockSegment::parse(out.data()).is_ok(), "{:?}", out),
                        }
                    }
                    // LSS (CiA 305) answer to a random 7E5h frame: DLC 8, a well-formed response (tests/lss.rs
                    // checks when answers are allowed).
                    0x7E4 => {
                        prop_assert_eq!(out.data().len(), 8);
                        prop_assert!(canopen::core::wire::lss::LssResponse::parse(out.data()).is_ok(), "{:?}", out);
                    }
                    other => prop_assert!(false, "frame on {:03X}", other),
                }
            }
            while node.poll_event().is_some() {}
            prop_assert!(node.state() != NmtState::Initialising);
        }
    }
}
