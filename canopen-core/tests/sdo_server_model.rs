//! Properties 1 and 4 of issue 4: arbitrary frame sequences to the SDO server never panic, every reply is a
//! well-formed SDO frame that the spec allows in the current state, and a reference model of the server's
//! states agrees with the server on every step.
//!
//! Run: `cargo test -p canopen-core --test sdo_server_model`.

mod support;

use canopen_core::od::AbortCode;
use canopen_core::sdo::{SdoServer, SdoServerParams, ServerState as S};
use canopen_core::wire::sdo::{
    BlockSegment, ClientRequest, Expedited, InitiateData, Multiplexer, Segment, ServerResponse,
};
use canopen_core::{Duration, Instant, NodeId};
use proptest::prelude::*;
use support::od::TestOd;

const BLKSIZE: u8 = 4;
const TIMEOUT: Duration = Duration::from_millis(50);

#[derive(Debug, Clone)]
enum Action {
    Frame(Vec<u8>),
    Wait(u64),
    Pull,
}

fn mux() -> impl Strategy<Value = Multiplexer> {
    prop_oneof![
        Just(Multiplexer::new(0x2000, 0)),
        Just(Multiplexer::new(0x2007, 0)),
        Just(Multiplexer::new(0x1017, 0)),
        Just(Multiplexer::new(0x2005, 0)),
        Just(Multiplexer::new(0x1000, 0)),
        Just(Multiplexer::new(0x2001, 0)),
        Just(Multiplexer::new(0x2004, 0)),
        Just(Multiplexer::new(0x5000, 0)),
        Just(Multiplexer::new(0x1018, 9)),
    ]
}

fn request() -> impl Strategy<Value = ClientRequest> {
    let data7 = proptest::array::uniform7(any::<u8>());
    prop_oneof![
        (mux(), proptest::array::uniform4(any::<u8>()), 1u8..=4).prop_map(|(mux, d, n)| {
            ClientRequest::InitiateDownload {
                mux,
                data: InitiateData::Expedited(Expedited::new(&d[..usize::from(n)]).unwrap()),
            }
        }),
        (mux(), proptest::option::of(0u32..40))
            .prop_map(|(mux, size)| ClientRequest::InitiateDownload { mux, data: InitiateData::Segmented { size } }),
        (any::<bool>(), any::<bool>(), 0u8..=7, data7)
            .prop_map(|(t, c, len, d)| ClientRequest::DownloadSegment(Segment::new(t, c, &d[..usize::from(len)]))),
        mux().prop_map(|mux| ClientRequest::InitiateUpload { mux }),
        any::<bool>().prop_map(|toggle| ClientRequest::UploadSegment { toggle }),
        (mux(), any::<u32>()).prop_map(|(mux, code)| ClientRequest::Abort { mux, code }),
        (mux(), any::<bool>(), proptest::option::of(0u32..40))
            .prop_map(|(mux, crc, size)| ClientRequest::BlockDownloadInitiate { mux, crc, size }),
        (0u8..=7, any::<u16>()).prop_map(|(unused, crc)| ClientRequest::BlockDownloadEnd { unused, crc }),
        (mux(), any::<bool>(), prop_oneof![Just(0u8), 1u8..=8, Just(128u8)], prop_oneof![Just(0u8), any::<u8>()])
            .prop_map(|(mux, crc, blksize, pst)| ClientRequest::BlockUploadInitiate { mux, crc, blksize, pst }),
        Just(ClientRequest::BlockUploadStart),
        (0u8..=5, prop_oneof![Just(0u8), 1u8..=8, Just(200u8)])
            .prop_map(|(ackseq, blksize)| ClientRequest::BlockUploadAck { ackseq, blksize }),
        Just(ClientRequest::BlockUploadEnd),
    ]
}

fn action() -> impl Strategy<Value = Action> {
    prop_oneof![
        6 => request().prop_map(|r| Action::Frame(r.emit().to_vec())),
        3 => (any::<bool>(), 0u8..=6, proptest::array::uniform7(any::<u8>())).prop_map(|(last, seqno, data)| {
            Action::Frame(BlockSegment { last, seqno, data }.emit().to_vec())
        }),
        1 => proptest::collection::vec(any::<u8>(), 0..=8).prop_map(Action::Frame),
        1 => (0u64..=80).prop_map(Action::Wait),
        2 => Just(Action::Pull),
    ]
}

/// What the server may answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Reply {
    None,
    /// An abort with this code (None: any Table 22 code).
    Abort(Option<AbortCode>),
    InitDownload,
    DownloadSegment,
    InitUploadExpedited,
    InitUploadSegmented,
    UploadSegment {
        last: bool,
    },
    BlockDownloadInit,
    BlockDownloadAck,
    BlockDownloadEnd,
    BlockUploadInit,
    BlockUploadEnd,
    SubBlockSegment {
        last: bool,
    },
}

fn classify(frame: Option<[u8; 8]>, pulled: bool) -> Reply {
    let Some(f) = frame else { return Reply::None };
    if pulled && f[0] != 0x80 {
        let s = BlockSegment::parse(&f).unwrap();
        return Reply::SubBlockSegment { last: s.last };
    }
    match ServerResponse::parse(&f).expect("every reply is a well-formed SDO frame") {
        ServerResponse::Abort { code, .. } => {
            Reply::Abort(Some(AbortCode::from_code(code).expect("abort codes come from Table 22")))
        }
        ServerResponse::InitiateDownload { .. } => Reply::InitDownload,
        ServerResponse::DownloadSegment { .. } => Reply::DownloadSegment,
        ServerResponse::InitiateUpload { data: InitiateData::Expedited(_), .. } => Reply::InitUploadExpedited,
        ServerResponse::InitiateUpload { data: InitiateData::Segmented { .. }, .. } => Reply::InitUploadSegmented,
        ServerResponse::UploadSegment(s) => Reply::UploadSegment { last: s.last },
        ServerResponse::BlockDownloadInitiate { .. } => Reply::BlockDownloadInit,
        ServerResponse::BlockDownloadAck { .. } => Reply::BlockDownloadAck,
        ServerResponse::BlockDownloadEnd => Reply::BlockDownloadEnd,
        ServerResponse::BlockUploadInitiate { .. } => Reply::BlockUploadInit,
        ServerResponse::BlockUploadEnd { .. } => Reply::BlockUploadEnd,
    }
}

/// The reference model: the protocol states and the segmented toggle.
#[derive(Debug, Clone, Copy)]
struct Model {
    state: S,
    toggle: bool,
    /// The SDO timeout's deadline: one `TIMEOUT` after the last frame (SDO-31).
    deadline: Option<Instant>,
    /// A block upload's sub-block was handed out and the time has not been checked since: the deadline is
    /// due, and the first check starts the time-out from there (the sub-block has gone out by then).
    sent: bool,
}

/// A quarter of the SDO timeout: after that long without a frame, a sub-block with in-order segments is
/// acknowledged up to them (SDO-40, the server's stall rule). Whether the sub-block has in-order segments
/// depends on sequence numbers the model does not follow, so both deadlines are allowed there.
const STALL: Duration = Duration::from_micros(TIMEOUT.as_micros() / 4);

const ANY_ABORT: Reply = Reply::Abort(None);

fn abort(code: AbortCode) -> Reply {
    Reply::Abort(Some(code))
}

impl Model {
    /// Allowed (reply, next state) pairs for a frame.
    fn on_frame(&self, f: &[u8]) -> Vec<(Reply, S)> {
        use Reply as R;
        let st = self.state;
        let Ok(b) = <[u8; 8]>::try_from(f) else { return vec![(R::None, st)] }; // CAN-07 choice
        if b[0] == 0x80 {
            return vec![(R::None, S::Idle)]; // SDO-33
        }
        if st == S::BlockDownloadSubBlock {
            let seqno = b[0] & 0x7F;
            if seqno == 0 || seqno > BLKSIZE {
                return vec![(abort(AbortCode::InvalidSequenceNumber), S::Idle)];
            }
            return vec![
                (R::None, st),
                (R::BlockDownloadAck, st),
                (R::BlockDownloadAck, S::BlockDownloadEnd),
                (ANY_ABORT, S::Idle),
            ];
        }
        // SDO-40/SDO-41: waiting for the end frame, a frame that can be a segment of the transfer (seqno
        // 1..=blksize, a late or repeated one) is ignored; the end frame C1h + 4·n is never taken for one.
        if st == S::BlockDownloadEnd && b[0] & 0xE1 != 0xC1 && (1..=BLKSIZE).contains(&(b[0] & 0x7F)) {
            return vec![(R::None, st)];
        }
        self.on_request(&b)
    }

    /// Allowed (reply, next state) pairs for an 8-byte frame read as a client request.
    fn on_request(&self, b: &[u8; 8]) -> Vec<(Reply, S)> {
        use Reply as R;
        let st = self.state;
        let Ok(req) = ClientRequest::parse(b) else {
            return vec![(abort(AbortCode::InvalidCommandSpecifier), S::Idle)];
        };
        let wrong = vec![(abort(AbortCode::InvalidCommandSpecifier), S::Idle)];
        match req {
            ClientRequest::Abort { .. } => vec![(R::None, S::Idle)],
            ClientRequest::InitiateDownload { data: InitiateData::Expedited(_), .. } => {
                vec![(R::InitDownload, S::Idle), (ANY_ABORT, S::Idle)]
            }
            ClientRequest::InitiateDownload { .. } => vec![(R::InitDownload, S::Downloading), (ANY_ABORT, S::Idle)],
            ClientRequest::InitiateUpload { .. } => {
                vec![(R::InitUploadExpedited, S::Idle), (R::InitUploadSegmented, S::Uploading), (ANY_ABORT, S::Idle)]
            }
            ClientRequest::BlockDownloadInitiate { .. } => {
                vec![(R::BlockDownloadInit, S::BlockDownloadSubBlock), (ANY_ABORT, S::Idle)]
            }
            ClientRequest::BlockUploadInitiate { blksize, .. } if blksize == 0 || blksize > 127 => {
                vec![(abort(AbortCode::InvalidBlockSize), S::Idle)]
            }
            ClientRequest::BlockUploadInitiate { .. } => vec![
                (R::BlockUploadInit, S::BlockUploadStart),
                (R::InitUploadExpedited, S::Idle),
                (R::InitUploadSegmented, S::Uploading),
                (ANY_ABORT, S::Idle),
            ],
            ClientRequest::DownloadSegment(seg) if st == S::Downloading => {
                if seg.toggle != self.toggle {
                    vec![(abort(AbortCode::ToggleNotAlternated), S::Idle)]
                } else if seg.last {
                    vec![(R::DownloadSegment, S::Idle), (ANY_ABORT, S::Idle)]
                } else {
                    vec![(R::DownloadSegment, S::Downloading), (ANY_ABORT, S::Idle)]
                }
            }
            ClientRequest::UploadSegment { toggle } if st == S::Uploading => {
                if toggle != self.toggle {
                    vec![(abort(AbortCode::ToggleNotAlternated), S::Idle)]
                } else {
                    vec![
                        (R::UploadSegment { last: false }, S::Uploading),
                        (R::UploadSegment { last: true }, S::Idle),
                        (ANY_ABORT, S::Idle),
                    ]
                }
            }
            ClientRequest::BlockDownloadEnd { .. } if st == S::BlockDownloadEnd => {
                vec![(R::BlockDownloadEnd, S::Idle), (ANY_ABORT, S::Idle)]
            }
            ClientRequest::BlockUploadStart if st == S::BlockUploadStart => vec![(R::None, S::BlockUploadSending)],
            ClientRequest::BlockUploadAck { .. } if matches!(st, S::BlockUploadSending | S::BlockUploadAck) => vec![
                (R::None, S::BlockUploadSending),
                (R::BlockUploadEnd, S::BlockUploadEnd),
                (abort(AbortCode::InvalidSequenceNumber), S::Idle),
                (abort(AbortCode::InvalidBlockSize), S::Idle),
            ],
            ClientRequest::BlockUploadEnd if st == S::BlockUploadEnd => vec![(R::None, S::Idle)],
            _ => wrong,
        }
    }

    fn on_pull(&self) -> Vec<(Reply, S)> {
        if self.state == S::BlockUploadSending {
            vec![
                (Reply::SubBlockSegment { last: false }, S::BlockUploadSending),
                (Reply::SubBlockSegment { last: false }, S::BlockUploadAck),
                (Reply::SubBlockSegment { last: true }, S::BlockUploadAck),
                (ANY_ABORT, S::Idle),
            ]
        } else {
            vec![(Reply::None, self.state)]
        }
    }

    fn on_timeout(&self, now: Instant) -> Vec<(Reply, S)> {
        let sub_block = self.state == S::BlockDownloadSubBlock;
        match self.deadline {
            Some(d) if now >= d && self.sent => vec![(Reply::None, self.state)],
            Some(d) if now >= d && sub_block => {
                vec![(abort(AbortCode::SdoTimeout), S::Idle), (Reply::BlockDownloadAck, S::BlockDownloadSubBlock)]
            }
            Some(d) if now >= d && self.state != S::Idle => vec![(abort(AbortCode::SdoTimeout), S::Idle)],
            Some(d) if sub_block && now + TIMEOUT >= d + STALL => {
                vec![(Reply::None, self.state), (Reply::BlockDownloadAck, S::BlockDownloadSubBlock)]
            }
            _ => vec![(Reply::None, self.state)],
        }
    }

    /// Whether the server's deadline is the model's, or in a sub-block the stall deadline before it.
    fn deadline_ok(&self, server: Option<Instant>) -> bool {
        match (self.deadline, server) {
            (Some(d), Some(s)) if self.state == S::BlockDownloadSubBlock => s == d || s + TIMEOUT == d + STALL,
            (d, s) => d == s,
        }
    }

    fn advance(&mut self, before: S, reply: Reply, next: S, now: Instant, touched: bool, waited: bool) {
        if matches!(reply, Reply::DownloadSegment | Reply::UploadSegment { .. }) {
            self.toggle = !self.toggle;
        }
        if before != next && matches!(next, S::Downloading | S::Uploading) {
            self.toggle = false;
        }
        if matches!(reply, Reply::InitDownload | Reply::InitUploadSegmented) {
            self.toggle = false;
        }
        self.state = next;
        if next == S::Idle {
            self.deadline = None;
            self.sent = false;
        } else if matches!(reply, Reply::SubBlockSegment { .. }) && next == S::BlockUploadAck {
            self.deadline = Some(now); // the sub-block's last segment: the time-out starts at the next check
            self.sent = true;
        } else if touched || waited && self.sent && self.deadline.is_some_and(|d| now >= d) {
            self.deadline = Some(now + TIMEOUT);
            self.sent = false;
        }
    }
}

fn allowed(set: &[(Reply, S)], got: Reply, next: S) -> bool {
    set.iter().any(|&(r, s)| s == next && (r == got || (r == ANY_ABORT && matches!(got, Reply::Abort(_)))))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: support::cases(512), ..ProptestConfig::default() })]

    /// Properties 1 and 4.
    #[test]
    fn server_agrees_with_model(actions in proptest::collection::vec(action(), 1..60), preset in 0usize..40) {
        let mut od = Box::new(TestOd::new());
        od.set_domain(&[0xA5; 40][..preset]);
        let mut server = SdoServer::new(SdoServerParams::default_server(NodeId::new(3).unwrap()))
            .with_timeout(TIMEOUT)
            .with_block_size(BLKSIZE);
        let mut model = Model { state: S::Idle, toggle: false, deadline: None, sent: false };
        let mut now = Instant::from_millis(1);
        for a in actions {
            let before = model.state;
            prop_assert_eq!(server.state(), before);
            prop_assert!(model.deadline_ok(server.poll_timeout()), "deadline {:?}, model {:?}", server.poll_timeout(), model.deadline);
            let (set, r, pulled, touched) = match &a {
                Action::Frame(f) => {
                    let set = model.on_frame(f);
                    (set, server.handle_request(now, f, &mut *od), false, f.len() == 8)
                }
                Action::Wait(ms) => {
                    now += Duration::from_millis(*ms);
                    let set = model.on_timeout(now);
                    (set, server.handle_timeout(now, &mut *od), false, false)
                }
                Action::Pull => {
                    let set = model.on_pull();
                    let r = server.poll_transmit(now, &mut *od).unwrap_or(canopen_core::sdo::Response::NONE);
                    (set, r, true, r.frame.is_some())
                }
            };
            let got = classify(r.frame, pulled);
            let next = server.state();
            prop_assert!(allowed(&set, got, next), "{:?} in {:?}: got {:?} → {:?}, allowed {:?}", a, before, got, next, set);
            model.advance(before, got, next, now, touched, matches!(a, Action::Wait(_)));
        }
        // every frame of a stream write was either committed or abandoned
        prop_assert!(server.state() != S::Idle || od.stream.is_none());
    }
}
