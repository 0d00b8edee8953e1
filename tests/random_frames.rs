//! Property test: random frames on every COB-ID, with random time steps, never make a node panic, and
//! everything it sends is a frame the spec allows it to send (CAN-07, NMT-14, NMT-18, HB-02, GUARD-06,
//! PDO-04, EMCY-04/08, SYNC-04/05, TIME-04/05).

use canopen::core::{
    event::Event,
    node::{NoApplication, Node},
    od::AbortCode,
    pdo::PdoDefault,
    profile::NodeConfig,
    sync::SyncParams,
    wire::emcy::Emergency,
    wire::sdo::ServerResponse,
    CanFrame, Instant, NmtState, NodeId, Sizes,
};
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;

/// What node 5's SDO server may send next, followed from the frames on 605h/585h as a client would follow
/// them. Block-upload segments carry no command specifier (SDO-37: byte 0 is `c ‖ seqno`), so a frame on
/// 585h can only be checked against the transfer's state: 81h is "segment 1, last" in a sub-block and an
/// abort with reserved bits set anywhere else.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum SdoView {
    /// No block upload: every server frame is a command (SDO-03).
    Idle,
    /// The client asked for a block upload with this block size (SDO-42); the answer is an initiate block
    /// upload response, a normal upload response (protocol switch, SDO-43) or an abort.
    Requested { blksize: u8 },
    /// Initiate answered (SDO-44): the server is silent until the client's "start upload" (A3h, SDO-45).
    Initiated { blksize: u8 },
    /// Sub-block going out: the next frame is segment `next`, in order (SDO-37, SDO-38).
    Segments { blksize: u8, next: u8 },
    /// The sub-block ended (its last segment, or seqno = blksize): silent until the client's ack.
    AwaitAck,
    /// Acknowledged (SDO-46): segment 1 of the next sub-block (SDO-40), or the end block upload response (SDO-47).
    Acked { blksize: u8 },
}

impl SdoView {
    /// The client frame `b` reached the server (an SDO-serving state, DLC 8): the state the server is in.
    fn client(self, b: &[u8]) -> SdoView {
        use SdoView::*;
        match (self, b[0]) {
            (_, c) if c >> 5 == 4 => Idle, // abort: the server drops the transfer
            (_, c) if c & 0xE3 == 0xA0 => Requested { blksize: b[4] }, // initiate block upload
            (Initiated { blksize }, c) if c & 0xE3 == 0xA3 => Segments { blksize, next: 1 },
            (Segments { .. } | AwaitAck | Acked { .. }, c) if c & 0xE3 == 0xA2 => Acked { blksize: b[2] },
            _ => Idle, // anything else ends a block upload (a new transfer, or the server aborts it)
        }
    }

    /// The server sent `b`: is it allowed here, and what state follows.
    fn server(self, b: &[u8]) -> Result<SdoView, String> {
        use SdoView::*;
        if b[0] == 0x80 {
            let code = u32::from_le_bytes([b[4], b[5], b[6], b[7]]);
            return match AbortCode::from_code(code) {
                Some(_) => Ok(Idle),
                None => Err(format!("abort code {code:08X} is not in Table 22")),
            };
        }
        let segment = |blksize: u8, next: u8| {
            let (last, seqno) = (b[0] & 0x80 != 0, b[0] & 0x7F);
            if seqno != next || seqno > blksize {
                return Err(format!("segment {seqno} where {next} of {blksize} was due"));
            }
            Ok(if last || seqno == blksize { AwaitAck } else { Segments { blksize, next: next + 1 } })
        };
        match self {
            Segments { blksize, next } => segment(blksize, next),
            Acked { blksize } if b[0] & 0x7F == 1 => segment(blksize, 1),
            Acked { .. } => match ServerResponse::parse(b) {
                Ok(ServerResponse::BlockUploadEnd { .. }) => Ok(Idle),
                other => Err(format!("after an ack: {other:?}")),
            },
            Initiated { .. } | AwaitAck => Err("the server must wait for the client here".into()),
            Requested { blksize } => match ServerResponse::parse(b) {
                Ok(ServerResponse::BlockUploadInitiate { .. }) => Ok(Initiated { blksize }),
                Ok(ServerResponse::InitiateUpload { .. }) => Ok(Idle),
                other => Err(format!("answer to initiate block upload: {other:?}")),
            },
            Idle => match ServerResponse::parse(b) {
                Ok(ServerResponse::Abort { .. }) => Err("an abort with reserved bits set".into()),
                Ok(_) => Ok(Idle),
                Err(e) => Err(format!("not a server command: {e:?}")),
            },
        }
    }
}

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

/// Two heartbeat consumers, 8 frames queued, 8 events queued.
type TestNode = Node<NoApplication, Sizes<2, 8, 8>>;

/// Drains the node's events. A reset communication (the server's parameters are set anew) or Stopped (NMT-18)
/// ends any SDO transfer silently.
fn drain_events(node: &mut TestNode, sdo: &mut SdoView) {
    while let Some(ev) = node.poll_event() {
        if matches!(ev, Event::ResetCommunication | Event::StateChanged { to: NmtState::Stopped, .. }) {
            *sdo = SdoView::Idle;
        }
    }
}

/// Feeds `inputs` to a node and checks everything it sends (the property below, and its regressions).
fn check(inputs: Vec<Input>, heartbeat: u16) -> Result<(), TestCaseError> {
    {
        const RPDO: &[PdoDefault] = &[
            PdoDefault { mapping: &[0x0005_0008, 0x0006_0010], event_timer_ms: 20, ..PdoDefault::EVENT },
            PdoDefault { transmission_type: 1, mapping: &[0x0007_0020], ..PdoDefault::EVENT },
        ];
        const TPDO: &[PdoDefault] = &[
            PdoDefault { mapping: &[0x1001_0008], event_timer_ms: 30, inhibit_100us: 50, ..PdoDefault::EVENT },
            PdoDefault { transmission_type: 2, mapping: &[0x1001_0008], ..PdoDefault::EVENT },
        ];
        let sync = SyncParams { counter_overflow: 4, ..SyncParams::DEFAULT };
        let cfg = NodeConfig {
            heartbeat_time_ms: heartbeat,
            guard_time_ms: 10,
            life_time_factor: 2,
            rpdo: RPDO,
            tpdo: TPDO,
            sync,
            time_cob_id: 0xC000_0100,
            ..NodeConfig::DEFAULT
        };
        let mut node: TestNode = Node::new(NodeId::new(5).unwrap(), cfg, NoApplication);
        let _ = node.set_consumer_heartbeat(Instant::ZERO, 1, 0x0002_0032);
        let mut now = Instant::ZERO;
        let mut sdo = SdoView::Idle;
        for inp in inputs {
            match inp {
                Input::Frame { id, rtr, data } => {
                    let f = if rtr { CanFrame::new_rtr(id, data.len() as u8) } else { CanFrame::new(id, &data) };
                    node.handle_frame(now, &f.unwrap());
                    // The first frame boots the node (a reset) before it is handled; then the request counts.
                    drain_events(&mut node, &mut sdo);
                    // SDO-01, NMT-18: the server sees requests in Pre-operational and Operational only.
                    let serving = matches!(node.state(), NmtState::PreOperational | NmtState::Operational);
                    if id == 0x605 && !rtr && data.len() == 8 && serving {
                        sdo = sdo.client(&data);
                    }
                    node.handle_timeout(now);
                }
                Input::Wait(us) => {
                    now = Instant::from_micros(now.as_micros() + us);
                    node.handle_timeout(now);
                }
            }
            // Every input was followed by handle_timeout or cannot create a due deadline: a deadline at or
            // before `now` would make a runner spin.
            drain_events(&mut node, &mut sdo);
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
                    // SDO: DLC 8, never in Stopped (NMT-18), the frame the transfer's state allows (a block
                    // segment in order, or a command); an abort is exactly 80h with a Table 22 code.
                    0x585 => {
                        prop_assert_eq!(out.data().len(), 8);
                        prop_assert!(state != NmtState::Stopped, "SDO frame in Stopped: {:?}", out);
                        sdo = match sdo.server(out.data()) {
                            Ok(next) => next,
                            Err(e) => return Err(TestCaseError::fail(format!("{e}: {:?} in {:?}", out, sdo))),
                        };
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
            prop_assert!(node.state() != NmtState::Initialising);
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 384, ..ProptestConfig::default() })]

    #[test]
    fn random_frames_never_panic_and_replies_are_well_formed(
        inputs in prop::collection::vec(input(), 1..200),
        heartbeat in prop::sample::select(vec![0u16, 1, 50, 1000]),
    ) {
        check(inputs, heartbeat)?;
    }
}

fn sdo(data: [u8; 8]) -> Input {
    Input::Frame { id: 0x605, rtr: false, data: data.to_vec() }
}

/// Shrunk cases the property once failed on, kept as regressions.
#[test]
fn regressions() {
    let cases: [(&str, Vec<Input>); 3] = [
        // A block upload of 1017h with block size 1: the server's segment 81h (seqno 1, last) is a segment,
        // not an abort with code 0 (the oracle follows the transfer, SDO-37).
        (
            "block upload, blksize 1",
            vec![sdo([0xA0, 0x17, 0x10, 0, 1, 0, 0, 0]), sdo([0xA3, 0x17, 0x10, 0, 0, 0, 0, 0])],
        ),
        // The same upload acknowledged: the end block upload response follows (SDO-47).
        (
            "block upload, acknowledged",
            vec![
                sdo([0xA4, 0x17, 0x10, 0, 1, 0, 0, 0]),
                sdo([0xA3, 0x17, 0x10, 0, 0, 0, 0, 0]),
                sdo([0xA2, 1, 1, 0, 0, 0, 0, 0]),
                sdo([0xA1, 0, 0, 0, 0, 0, 0, 0]),
            ],
        ),
        // A segmented download begun, then NMT Stop: the SDO time-out must not send an abort in Stopped
        // (NMT-18); the node drops the transfer when it stops.
        (
            "transfer open at NMT Stop",
            vec![
                sdo([0x20, 0x17, 0x10, 0, 0, 0, 0, 0]),
                Input::Frame { id: 0, rtr: false, data: vec![0x02, 0x00] },
                Input::Wait(190_613),
                Input::Wait(298_603),
                Input::Wait(294_766),
            ],
        ),
    ];
    for (name, inputs) in cases {
        for heartbeat in [0u16, 1000] {
            if let Err(e) = check(inputs.clone(), heartbeat) {
                panic!("{name} (heartbeat {heartbeat}): {e}");
            }
        }
    }
}
