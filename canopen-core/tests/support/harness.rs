//! In-memory client ↔ server link with simulated time and optional frame faults (loss, adjacent
//! duplication, adjacent reordering), driven frame by frame.

use std::collections::VecDeque;

use canopen_core::od::AbortCode;
use canopen_core::sdo::client::{ClientEvent, Mode, SdoClient, SliceData};
use canopen_core::sdo::{SdoClientParams, SdoEvent, SdoServer, SdoServerParams};
use canopen_core::wire::sdo::Multiplexer;
use canopen_core::{Duration, Instant, NodeId};

use super::od::TestOd;

/// Time one frame takes on the simulated bus.
pub const FRAME_TIME: Duration = Duration::from_micros(100);

/// Fault probabilities in 1/1000 per frame.
#[derive(Debug, Clone, Copy, Default)]
pub struct Faults {
    pub loss: u32,
    pub dup: u32,
    pub swap: u32,
    /// A block transfer without CRC in this direction, with this many segments per sub-block: its frames
    /// that no receiver can tell from new ones when repeated are never duplicated (see [`unprotected`]).
    pub no_crc_block: Option<(Dir, u8)>,
}

/// Whether `f` (client → server when `c2s`) is a frame of a block transfer without CRC whose duplicate no
/// receiver can tell from a new frame: the sub-block acknowledge A2h (a repeat arriving after the sender moved
/// on is byte-identical to the next acknowledge when nothing was lost), and with one segment per sub-block the
/// segments 01h/81h (a repeat matches the next segment's sequence number, and its bytes with repeating data).
/// Without the CRC (SDO-48, SDO-49) nothing catches the wrong data either one causes.
pub fn unprotected(no_crc_block: Option<(Dir, u8)>, c2s: bool, f: &[u8; 8]) -> bool {
    let Some((dir, sub_block)) = no_crc_block else { return false };
    let acks_c2s = dir == Dir::Upload;
    (c2s == acks_c2s && f[0] == 0xA2) || (c2s != acks_c2s && sub_block == 1 && f[0] & 0x7F == 1)
}

/// A tiny deterministic PRNG (xorshift64*).
#[derive(Debug, Clone)]
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed | 1)
    }
    pub fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    pub fn per_mille(&mut self, p: u32) -> bool {
        p > 0 && (self.next() % 1000) < u64::from(p)
    }
}

/// Direction of a transfer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dir {
    Download,
    Upload,
}

/// The result of one simulated transfer.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The client's final event.
    pub client: Option<ClientEvent>,
    /// Every event the server reported.
    pub server_events: Vec<SdoEvent>,
    /// Uploaded bytes (upload) or the OD's 2000h after the transfer (download).
    pub data: Vec<u8>,
    /// Frames delivered in each direction.
    pub frames: (usize, usize),
    /// Both sides idle, nothing in flight at the end.
    pub settled: bool,
    /// Simulated time at the end.
    pub end: Instant,
}

pub struct Link {
    pub client: SdoClient,
    pub server: SdoServer,
    pub od: Box<TestOd>,
    pub now: Instant,
    pub faults: Faults,
    pub rng: Rng,
    c2s: VecDeque<[u8; 8]>,
    s2c: VecDeque<[u8; 8]>,
}

impl Link {
    pub fn new(block_size: u8, faults: Faults, seed: u64) -> Self {
        let node = NodeId::new(3).unwrap();
        Link {
            client: SdoClient::new(SdoClientParams::for_server(node)),
            server: SdoServer::new(SdoServerParams::default_server(node)).with_block_size(block_size),
            od: Box::new(TestOd::new()),
            now: Instant::from_millis(1),
            faults,
            rng: Rng::new(seed),
            c2s: VecDeque::new(),
            s2c: VecDeque::new(),
        }
    }

    fn push(q: &mut VecDeque<[u8; 8]>, f: [u8; 8], faults: Faults, rng: &mut Rng, c2s: bool) {
        if rng.per_mille(faults.loss) {
            return;
        }
        q.push_back(f);
        if rng.per_mille(faults.dup) && !unprotected(faults.no_crc_block, c2s, &f) {
            q.push_back(f);
        }
        let n = q.len();
        if n >= 2 && rng.per_mille(faults.swap) {
            q.swap(n - 1, n - 2);
        }
    }

    /// Runs one transfer of `payload` (download: client → 2000h; upload: 2000h → client) to the end.
    pub fn transfer(&mut self, dir: Dir, mux: Multiplexer, payload: &[u8], mode: Mode) -> Outcome {
        let mut up_buf = vec![0u8; payload.len().max(8) + 64];
        let mut dn_buf = payload.to_vec();
        let mut server_events = Vec::new();
        let mut client_ev = None;
        let mut frames = (0, 0);
        match dir {
            Dir::Download => {
                self.client.start_download(self.now, mux, payload.len(), mode).unwrap();
            }
            Dir::Upload => {
                if mux.index == 0x2000 {
                    self.od.set_domain(payload);
                }
                self.client.start_upload(self.now, mux, mode).unwrap();
            }
        }
        let limit = 40 * (payload.len() / 7 + 10) + 200;
        let mut steps = 0;
        let mut settled = false;
        let mut up_len = 0;
        while steps < limit {
            steps += 1;
            let mut data = match dir {
                Dir::Download => SliceData::download(&mut dn_buf),
                Dir::Upload => SliceData::upload(&mut up_buf),
            };
            // client frames out
            while let Some(f) = self.client.poll_transmit(self.now, &mut data) {
                Self::push(&mut self.c2s, f, self.faults, &mut self.rng, true);
            }
            // server sub-block frames out (one per step: a bounded TX queue)
            if let Some(r) = self.server.poll_transmit(self.now, &mut *self.od) {
                if let Some(f) = r.frame {
                    Self::push(&mut self.s2c, f, self.faults, &mut self.rng, false);
                }
                server_events.extend(r.event);
            }
            let mut moved = false;
            if let Some(f) = self.c2s.pop_front() {
                self.now += FRAME_TIME;
                frames.0 += 1;
                let r = self.server.handle_request(self.now, &f, &mut *self.od);
                if let Some(f) = r.frame {
                    Self::push(&mut self.s2c, f, self.faults, &mut self.rng, false);
                }
                server_events.extend(r.event);
                moved = true;
            }
            if let Some(f) = self.s2c.pop_front() {
                self.now += FRAME_TIME;
                frames.1 += 1;
                if let Some(ev) = self.client.handle_response(self.now, &f, &mut data) {
                    client_ev.get_or_insert(ev);
                }
                moved = true;
            }
            if dir == Dir::Upload {
                up_len = up_len.max(data.len());
            }
            if moved || self.server.wants_transmit() {
                continue;
            }
            // nothing in flight: check for more client frames, else jump to the next deadline
            if let Some(f) = self.client.poll_transmit(self.now, &mut data) {
                Self::push(&mut self.c2s, f, self.faults, &mut self.rng, true);
                continue;
            }
            if self.client.is_idle() && self.server.is_idle() {
                settled = true;
                break;
            }
            let next = canopen_core::time::earliest(self.client.poll_timeout(), self.server.poll_timeout());
            let Some(t) = next else { break };
            self.now = self.now.max(t);
            if let Some(ev) = self.client.handle_timeout(self.now) {
                client_ev.get_or_insert(ev);
            }
            let r = self.server.handle_timeout(self.now, &mut *self.od);
            if let Some(f) = r.frame {
                Self::push(&mut self.s2c, f, self.faults, &mut self.rng, false);
            }
            server_events.extend(r.event);
        }
        let data = match dir {
            Dir::Download => self.od.domain().to_vec(),
            Dir::Upload => up_buf[..up_len].to_vec(),
        };
        Outcome { client: client_ev, server_events, data, frames, settled, end: self.now }
    }
}

/// Whether `code` is a Table 22 abort code.
pub fn is_spec_code(code: u32) -> bool {
    AbortCode::from_code(code).is_some()
}
