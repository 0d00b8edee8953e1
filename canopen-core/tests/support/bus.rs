//! One shared lossy CAN bus for several SDO client ↔ server pairs and background traffic, on simulated time
//! (issue 21 item 3).
//!
//! Every frame of every COB-ID goes through one wire queue. Seeded faults, each with its own rate:
//! - **drop**: the frame never arrives (an overflowing receive buffer, a receiver that missed it);
//! - **duplicate**: the frame arrives twice in a row (CAN's automatic retransmission after an error frame
//!   that the receiver did not see), except a sub-block acknowledge of a block transfer without CRC (see
//!   [`Bus::unprotected`]);
//! - **reorder**: the frame overtakes up to three frames queued before it, as long as none of them has its
//!   COB-ID. Frames of one COB-ID keep their order, as on a real bus where one sender's queue is FIFO, but
//!   the two directions of a transfer and other traffic interleave differently.
//!
//! Time advances by [`FRAME_TIME`] per delivered frame and jumps to the next deadline when the wire is quiet.
//! `SDO_BUS_TRACE=<node-ID>` prints every frame delivered on that node's SDO COB-IDs.

use std::collections::VecDeque;

use canopen_core::sdo::client::{ClientEvent, Mode, SdoClient, SliceData};
use canopen_core::sdo::{SdoClientParams, SdoEvent, SdoServer, SdoServerParams};
use canopen_core::wire::sdo::Multiplexer;
use canopen_core::{Duration, Instant, NodeId};

use super::harness::{unprotected, Dir, Rng};
use super::od::TestOd;

/// Time one frame takes on the simulated bus.
pub const FRAME_TIME: Duration = Duration::from_micros(100);

/// The object every transfer reads or writes.
pub const DOMAIN: Multiplexer = Multiplexer::new(0x2000, 0);

/// Fault rates in 1/1000 per frame put on the wire.
#[derive(Debug, Clone, Copy, Default)]
pub struct Rates {
    pub drop: u32,
    pub dup: u32,
    pub reorder: u32,
}

/// One transfer to run.
#[derive(Debug, Clone)]
pub struct Job {
    pub dir: Dir,
    pub mode: Mode,
    pub payload: Vec<u8>,
}

/// How a transfer ended, seen from both sides.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub job: Job,
    /// The client's event (`None` would be a hang: the run ends only when every client is idle).
    pub client: Option<ClientEvent>,
    /// Every server event from the transfer's start until the server was idle again.
    pub server: Vec<SdoEvent>,
    /// Uploaded bytes (upload) or the server's 2000h when the server was idle again (download).
    pub data: Vec<u8>,
    /// 2000h before the transfer.
    pub before: Vec<u8>,
    /// Writes the dictionary committed during the transfer (an aborted download commits none).
    pub commits: u32,
    pub started: Instant,
    /// When the client reported its outcome, when the server last received or sent a frame, and when it was
    /// idle afterwards.
    pub client_done: Instant,
    pub server_active: Instant,
    pub server_idle: Instant,
}

/// A client and the server it talks to (node `node`), with the queue of transfers still to run.
pub struct Pair {
    pub client: SdoClient,
    pub server: SdoServer,
    pub od: Box<TestOd>,
    pub node: u8,
    /// The block size the server asks for in block download.
    pub server_blksize: u8,
    jobs: VecDeque<Job>,
    current: Option<Running>,
    pub done: Vec<Outcome>,
}

struct Running {
    job: Job,
    dn_buf: Vec<u8>,
    up_buf: Vec<u8>,
    up_len: usize,
    client: Option<ClientEvent>,
    server: Vec<SdoEvent>,
    before: Vec<u8>,
    writes_before: u32,
    started: Instant,
    client_done: Option<Instant>,
    server_active: Instant,
    /// When the server last went idle (None while it is busy).
    server_idle: Option<Instant>,
}

impl Running {
    /// Records the server's events and when it was last active or went idle.
    fn note_server(&mut self, server: &SdoServer, event: Option<SdoEvent>, active: bool, now: Instant) {
        self.server.extend(event);
        if active {
            self.server_active = now;
        }
        self.server_idle = if server.is_idle() { Some(self.server_idle.unwrap_or(now)) } else { None };
    }
}

impl Pair {
    pub fn new(node: u8, server_blksize: u8, timeout: Duration, jobs: Vec<Job>) -> Self {
        let id = NodeId::new(node).unwrap();
        Pair {
            client: SdoClient::new(SdoClientParams::for_server(id)).with_timeout(timeout),
            server: SdoServer::new(SdoServerParams::default_server(id))
                .with_block_size(server_blksize)
                .with_timeout(timeout),
            od: Box::new(TestOd::new()),
            node,
            server_blksize,
            jobs: jobs.into(),
            current: None,
            done: Vec::new(),
        }
    }

    fn rx_cob(&self) -> u16 {
        0x600 + u16::from(self.node)
    }

    fn tx_cob(&self) -> u16 {
        0x580 + u16::from(self.node)
    }

    fn busy(&self) -> bool {
        self.current.is_some() || !self.jobs.is_empty()
    }
}

/// A frame on the wire.
type Frame = (u16, [u8; 8]);

/// Decides whether a frame is lost on purpose (a test's planted fault), besides the random ones.
pub type LoseRule = Box<dyn FnMut(u16, &[u8; 8]) -> bool>;

pub struct Bus {
    pub now: Instant,
    pub pairs: Vec<Pair>,
    pub rates: Rates,
    rng: Rng,
    wire: VecDeque<Frame>,
    /// Background traffic: one frame on COB-ID 181h every this many delivered frames (0 = none).
    pub noise_every: u32,
    delivered: u64,
    lose: Option<LoseRule>,
    /// The longest stretch of silence on the wire while a transfer was under way.
    pub longest_silence: Duration,
}

impl Bus {
    pub fn new(pairs: Vec<Pair>, rates: Rates, seed: u64) -> Self {
        Bus {
            now: Instant::from_millis(1),
            pairs,
            rates,
            rng: Rng::new(seed),
            wire: VecDeque::new(),
            noise_every: 5,
            delivered: 0,
            lose: None,
            longest_silence: Duration::from_micros(0),
        }
    }

    /// Loses every frame for which `rule` says so (in addition to the random faults).
    pub fn lose(&mut self, rule: impl FnMut(u16, &[u8; 8]) -> bool + 'static) {
        self.lose = Some(Box::new(rule));
    }

    fn put(&mut self, cob: u16, data: [u8; 8]) {
        if self.lose.as_mut().is_some_and(|rule| rule(cob, &data)) || self.rng.per_mille(self.rates.drop) {
            return;
        }
        let copies = if self.rng.per_mille(self.rates.dup) && !self.unprotected(cob, &data) { 2 } else { 1 };
        for _ in 0..copies {
            self.wire.push_back((cob, data));
        }
        if copies == 1 && self.rng.per_mille(self.rates.reorder) {
            // overtake up to three queued frames of other COB-IDs
            let depth = 1 + (self.rng.next() % 3) as usize;
            let mut at = self.wire.len() - 1;
            while at > 0 && self.wire.len() - 1 - at < depth && self.wire[at - 1].0 != cob {
                self.wire.swap(at - 1, at);
                at -= 1;
            }
        }
    }

    /// Whether `data` on `cob` belongs to a block transfer without CRC and is one of the frames whose duplicate
    /// no receiver can tell from a new one ([`unprotected`]: the sub-block acknowledges, and the segments when
    /// a sub-block is one segment long). Those are never duplicated; every other frame of those transfers is.
    fn unprotected(&self, cob: u16, data: &[u8; 8]) -> bool {
        self.pairs.iter().any(|p| {
            let Some(Running { job: Job { dir, mode: Mode::Block { crc: false, blksize, .. }, .. }, .. }) = &p.current
            else {
                return false;
            };
            let sub_block = if *dir == Dir::Download { p.server_blksize } else { *blksize };
            (cob == p.rx_cob() || cob == p.tx_cob()) && unprotected(Some((*dir, sub_block)), cob == p.rx_cob(), data)
        })
    }

    /// Runs every pair's jobs to the end. Panics if the bus is quiet while a side is busy without a deadline,
    /// or would stay silent longer than `timeout` (a hang).
    pub fn run(&mut self, timeout: Duration) {
        let limit = 2_000_000u64;
        let mut steps = 0u64;
        while self.pairs.iter().any(|p| p.busy() || !p.client.is_idle() || !p.server.is_idle()) || !self.wire.is_empty()
        {
            steps += 1;
            assert!(steps < limit, "no end after {limit} steps");
            self.start_and_finish_jobs();
            self.transmit();
            if let Some((cob, data)) = self.wire.pop_front() {
                self.now += FRAME_TIME;
                self.delivered += 1;
                if self.noise_every > 0 && self.delivered % u64::from(self.noise_every) == 0 {
                    let n = self.delivered.to_le_bytes();
                    self.put(0x181, n);
                }
                self.deliver(cob, &data);
                continue;
            }
            if self.pairs.iter().any(|p| p.server.wants_transmit()) {
                continue;
            }
            // quiet wire: jump to the next deadline
            let next =
                self.pairs.iter().flat_map(|p| [p.client.poll_timeout(), p.server.poll_timeout()]).flatten().min();
            let busy_side = self.pairs.iter().any(|p| !p.client.is_idle() || !p.server.is_idle());
            for p in &self.pairs {
                for d in [p.client.poll_timeout(), p.server.poll_timeout()].into_iter().flatten() {
                    assert!(d <= self.now + timeout, "node {}: a deadline more than the SDO timeout ahead", p.node);
                }
            }
            let Some(t) = next else {
                assert!(!busy_side, "a side is busy without a deadline: hang");
                continue;
            };
            let silence = t.saturating_duration_since(self.now);
            assert!(silence <= timeout, "silence of {silence:?} > SDO timeout {timeout:?}");
            if silence > self.longest_silence {
                self.longest_silence = silence;
            }
            self.now = self.now.max(t);
            let now = self.now;
            for i in 0..self.pairs.len() {
                let p = &mut self.pairs[i];
                if let Some(ev) = p.client.handle_timeout(now) {
                    if let Some(r) = p.current.as_mut() {
                        r.client.get_or_insert(ev);
                    }
                }
                let r = p.server.handle_timeout(now, &mut *p.od);
                if let Some(run) = p.current.as_mut() {
                    run.note_server(&p.server, r.event, r.frame.is_some(), now);
                }
                let cob = p.tx_cob();
                if let Some(f) = r.frame {
                    self.put(cob, f);
                }
            }
        }
    }

    fn start_and_finish_jobs(&mut self) {
        let now = self.now;
        for p in &mut self.pairs {
            // a transfer is over when the client has its outcome, the server is idle again and no frame of the
            // pair is still on the wire
            let in_flight = self.wire.iter().any(|&(cob, _)| cob == p.rx_cob() || cob == p.tx_cob());
            if let Some(run) = p.current.as_mut() {
                if run.client.is_some() && run.client_done.is_none() {
                    run.client_done = Some(now);
                }
                if run.client.is_some() && p.client.is_idle() && p.server.is_idle() && !in_flight {
                    let run = p.current.take().unwrap();
                    let data = match run.job.dir {
                        Dir::Download => p.od.domain().to_vec(),
                        Dir::Upload => run.up_buf[..run.up_len].to_vec(),
                    };
                    p.done.push(Outcome {
                        job: run.job,
                        client: run.client,
                        server: run.server,
                        data,
                        before: run.before,
                        commits: p.od.writes - run.writes_before,
                        started: run.started,
                        client_done: run.client_done.unwrap_or(now),
                        server_active: run.server_active,
                        server_idle: run.server_idle.unwrap_or(now),
                    });
                }
            }
            if p.current.is_none() {
                if let Some(job) = p.jobs.pop_front() {
                    let before = p.od.domain().to_vec();
                    match job.dir {
                        Dir::Download => p.client.start_download(now, DOMAIN, job.payload.len(), job.mode).unwrap(),
                        Dir::Upload => {
                            p.od.set_domain(&job.payload);
                            p.client.start_upload(now, DOMAIN, job.mode).unwrap();
                        }
                    }
                    p.current = Some(Running {
                        dn_buf: job.payload.clone(),
                        up_buf: vec![0; job.payload.len() + 64],
                        up_len: 0,
                        job,
                        client: None,
                        server: Vec::new(),
                        before,
                        writes_before: p.od.writes,
                        started: now,
                        client_done: None,
                        server_active: now,
                        server_idle: None,
                    });
                }
            }
        }
    }

    fn transmit(&mut self) {
        let now = self.now;
        let mut out = Vec::new();
        for p in &mut self.pairs {
            let rx = p.rx_cob();
            if let Some(run) = p.current.as_mut() {
                let mut data = match run.job.dir {
                    Dir::Download => SliceData::download(&mut run.dn_buf),
                    Dir::Upload => SliceData::upload(&mut run.up_buf),
                };
                while let Some(f) = p.client.poll_transmit(now, &mut data) {
                    out.push((rx, f));
                }
            }
            // one server frame per step: a bounded TX queue
            if let Some(r) = p.server.poll_transmit(now, &mut *p.od) {
                if let Some(run) = p.current.as_mut() {
                    run.note_server(&p.server, r.event, true, now);
                }
                let cob = p.tx_cob();
                out.extend(r.frame.map(|f| (cob, f)));
            }
        }
        for (cob, f) in out {
            self.put(cob, f);
        }
    }

    fn deliver(&mut self, cob: u16, data: &[u8; 8]) {
        let now = self.now;
        if std::env::var("SDO_BUS_TRACE").is_ok_and(|v| v.parse::<u16>().is_ok_and(|n| cob & 0x7F == n)) {
            eprintln!("{:>9} {cob:03X} {data:02X?}", now.as_micros());
        }
        let mut out = None;
        for p in &mut self.pairs {
            if cob == p.rx_cob() {
                let r = p.server.handle_request(now, data, &mut *p.od);
                if let Some(run) = p.current.as_mut() {
                    run.note_server(&p.server, r.event, true, now);
                }
                let tx = p.tx_cob();
                out = r.frame.map(|f| (tx, f));
            } else if cob == p.tx_cob() {
                let Some(run) = p.current.as_mut() else { continue };
                let mut buf = match run.job.dir {
                    Dir::Download => SliceData::download(&mut run.dn_buf),
                    Dir::Upload => SliceData::upload(&mut run.up_buf),
                };
                let ev = p.client.handle_response(now, data, &mut buf);
                if run.job.dir == Dir::Upload {
                    run.up_len = run.up_len.max(buf.len());
                }
                if let Some(ev) = ev {
                    run.client.get_or_insert(ev);
                }
            }
        }
        if let Some((cob, f)) = out {
            self.put(cob, f);
        }
    }
}
