//! `canopenctl bench`: SDO throughput to and from a DOMAIN of a node, every byte checked, with the frames on
//! the bus per run and, given the node's process ID, the node's CPU time per frame (from
//! `/proc/<pid>/stat`). It moves `size` bytes in transfers of `chunk` bytes (the DOMAIN's capacity) down,
//! then reads the last chunk back `size / chunk` times. scripts/bench-vcan.sh runs it against the example
//! node (it was the `bench` of the retired `examples/master.rs`).

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Instant;

use canopen_core::CanFrame;
use canopen_master::{CanIo, IoFuture, Master, Mode, BLOCK};

/// The frames a [`Counted`] socket sent and received so far.
///
/// ```
/// let count = canopenctl::bench::FrameCount::default();
/// assert_eq!((count.sent(), count.received(), count.total()), (0, 0, 0));
/// ```
#[derive(Debug, Default)]
pub struct FrameCount {
    sent: AtomicU64,
    received: AtomicU64,
}

impl FrameCount {
    /// Frames sent.
    ///
    /// ```
    /// assert_eq!(canopenctl::bench::FrameCount::default().sent(), 0);
    /// ```
    pub fn sent(&self) -> u64 {
        self.sent.load(Ordering::Relaxed)
    }

    /// Frames received (every frame on the bus the socket sees, not only the answers).
    ///
    /// ```
    /// assert_eq!(canopenctl::bench::FrameCount::default().received(), 0);
    /// ```
    pub fn received(&self) -> u64 {
        self.received.load(Ordering::Relaxed)
    }

    /// Frames sent and received.
    ///
    /// ```
    /// assert_eq!(canopenctl::bench::FrameCount::default().total(), 0);
    /// ```
    pub fn total(&self) -> u64 {
        self.sent() + self.received()
    }
}

/// A [`CanIo`] that counts the frames going through it into a shared [`FrameCount`].
///
/// ```
/// use canopen_master::{sim::SimBus, CanIo};
/// use canopenctl::bench::Counted;
/// # let rt = tokio::runtime::Builder::new_current_thread().build().unwrap();
/// # rt.block_on(async {
/// let bus = SimBus::new();
/// let (a, b) = (Counted::new(bus.port()), Counted::new(bus.port()));
/// let (sent, received) = (a.count(), b.count());
/// a.send_many(&[canopen_core::CanFrame::new(0x80, &[]).unwrap(); 2]).await.unwrap();
/// let mut out = Vec::new();
/// while out.len() < 2 {
///     b.recv_many(&mut out).await.unwrap();
/// }
/// assert_eq!((sent.sent(), received.received()), (2, 2));
/// # });
/// ```
pub struct Counted<I> {
    io: I,
    count: Arc<FrameCount>,
}

impl<I: CanIo> Counted<I> {
    /// `io`, counted from zero.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().build().unwrap();
    /// # rt.block_on(async {
    /// let io = canopenctl::bench::Counted::new(canopen_master::sim::SimBus::new().port());
    /// assert_eq!(io.count().total(), 0);
    /// # });
    /// ```
    pub fn new(io: I) -> Self {
        Counted { io, count: Arc::default() }
    }

    /// The counters, shared: they go on counting after the socket moved into a [`Master`].
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// let io = canopenctl::bench::Counted::new(canopen_master::sim::SimBus::new().port());
    /// let count = io.count();
    /// let master = canopen_master::Master::new(io);
    /// master.send(&canopen_core::CanFrame::new(0x80, &[]).unwrap()).await.unwrap();
    /// assert_eq!(count.sent(), 1);
    /// # });
    /// ```
    pub fn count(&self) -> Arc<FrameCount> {
        self.count.clone()
    }
}

impl<I: CanIo> CanIo for Counted<I> {
    fn send<'a>(&'a self, frame: &'a CanFrame) -> IoFuture<'a, ()> {
        Box::pin(async move {
            self.io.send(frame).await?;
            self.count.sent.fetch_add(1, Ordering::Relaxed);
            Ok(())
        })
    }

    fn recv(&self) -> IoFuture<'_, CanFrame> {
        Box::pin(async move {
            let frame = self.io.recv().await?;
            self.count.received.fetch_add(1, Ordering::Relaxed);
            Ok(frame)
        })
    }

    fn send_many<'a>(&'a self, frames: &'a [CanFrame]) -> IoFuture<'a, ()> {
        Box::pin(async move {
            self.io.send_many(frames).await?;
            self.count.sent.fetch_add(frames.len() as u64, Ordering::Relaxed);
            Ok(())
        })
    }

    fn recv_many<'a>(&'a self, out: &'a mut Vec<CanFrame>) -> IoFuture<'a, usize> {
        Box::pin(async move {
            let n = self.io.recv_many(out).await?;
            self.count.received.fetch_add(n as u64, Ordering::Relaxed);
            Ok(n)
        })
    }

    fn reopen(&self) -> IoFuture<'_, bool> {
        self.io.reopen()
    }
}

/// `len` bytes of a xorshift sequence from `seed`: every transfer of a bench carries other bytes, so a
/// chunk read back from an earlier transfer is seen.
///
/// ```
/// use canopenctl::bench::pattern;
/// assert_eq!(pattern(5, 1).len(), 5);
/// assert_ne!(pattern(64, 1), pattern(64, 2));
/// ```
pub fn pattern(len: usize, seed: u32) -> Vec<u8> {
    let mut x = seed.wrapping_mul(2_654_435_761).max(1);
    (0..len)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x as u8
        })
        .collect()
}

/// The CPU time (user + system) in seconds in the text of a `/proc/<pid>/stat`, at 100 clock ticks per
/// second (Linux's `USER_HZ`); `None` when the text is not one.
///
/// ```
/// let stat = "42 (my node) S 1 42 42 0 -1 4194560 100 0 0 0 150 50 0 0 20 0 3 0";
/// assert_eq!(canopenctl::bench::cpu_seconds(stat), Some(2.0));
/// assert_eq!(canopenctl::bench::cpu_seconds("garbage"), None);
/// ```
pub fn cpu_seconds(stat: &str) -> Option<f64> {
    // The fields after the command name (which may contain spaces and parentheses) start after the last ')'.
    let rest = stat.get(stat.rfind(')')? + 1..)?;
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let utime: f64 = fields.get(11)?.parse().ok()?;
    let stime: f64 = fields.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

fn process_cpu_seconds(pid: u32) -> Option<f64> {
    cpu_seconds(&std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?)
}

/// One bench run: what to move, how, and whose CPU time to report.
///
/// ```
/// let run = canopenctl::bench::Bench { node: 5, index: 0x2005, size: 1 << 20, chunk: 65_536, mode: canopen_master::BLOCK, label: "block+CRC", node_pid: None };
/// assert_eq!(run.transfers(), 16);
/// ```
#[derive(Debug, Clone)]
pub struct Bench {
    /// The node-ID.
    pub node: u8,
    /// The DOMAIN (sub-index 0).
    pub index: u16,
    /// Bytes each way.
    pub size: usize,
    /// Bytes per transfer (at least 1; the DOMAIN's capacity).
    pub chunk: usize,
    /// The download mode; uploads use it too, except that a segmented bench uploads in [`Mode::Auto`].
    pub mode: Mode,
    /// The name of the mode in the output.
    pub label: &'static str,
    /// The node's process, for its CPU time per frame.
    pub node_pid: Option<u32>,
}

impl Bench {
    /// How many transfers each way.
    ///
    /// ```
    /// let run = canopenctl::bench::Bench { node: 5, index: 0x2005, size: 10, chunk: 4, mode: canopen_master::BLOCK, label: "", node_pid: None };
    /// assert_eq!(run.transfers(), 3);
    /// ```
    pub fn transfers(&self) -> usize {
        self.size.div_ceil(self.chunk.max(1)).max(1)
    }

    /// Runs the bench on `master` (whose socket counts into `frames`): the download, then the upload; one
    /// line each, with the bytes, the time, KiB/s and the frames on the bus (and the node's CPU time per
    /// frame). A byte that comes back different is an error.
    ///
    /// ```no_run
    /// # async fn demo() -> Result<(), String> {
    /// use canopenctl::bench::{Bench, Counted};
    /// let io = Counted::new(canopen_master::SocketCan::open("vcan0").map_err(|e| e.to_string())?);
    /// let frames = io.count();
    /// let master = canopen_master::Master::new(io);
    /// let run = Bench { node: 5, index: 0x2005, size: 1 << 20, chunk: 65_536, mode: canopen_master::BLOCK, label: "block+CRC", node_pid: None };
    /// for line in run.run(&master, &frames).await? {
    ///     println!("{line}");
    /// }
    /// # Ok(()) }
    /// ```
    pub async fn run(&self, master: &Master, frames: &FrameCount) -> Result<Vec<String>, String> {
        let (node, index, chunk, count) = (self.node, self.index, self.chunk.max(1), self.transfers());
        let failed = |what: &str, e: canopen_master::Error| format!("bench {} {what}: {e}", self.label);
        let chunks: Vec<Vec<u8>> =
            (0..count).map(|i| pattern(chunk.min(self.size.saturating_sub(i * chunk)), i as u32 + 1)).collect();
        let last = chunks.last().cloned().unwrap_or_default();
        let upload_mode = if matches!(self.mode, Mode::Segmented) { Mode::Auto } else { self.mode };
        let mut lines = Vec::new();
        for down in [true, false] {
            if !down {
                // The upload phase reads back the last chunk, put in place untimed.
                master.download(node, index, 0, &last, BLOCK).await.map_err(|e| failed("download", e))?;
            }
            let cpu0 = self.node_pid.and_then(process_cpu_seconds);
            let frames0 = frames.total();
            let t = Instant::now();
            for data in &chunks {
                if down {
                    master.download(node, index, 0, data, self.mode).await.map_err(|e| failed("download", e))?;
                } else if master.upload(node, index, 0, upload_mode).await.map_err(|e| failed("upload", e))? != last {
                    return Err(format!("bench {} upload: the bytes differ", self.label));
                }
            }
            let secs = t.elapsed().as_secs_f64().max(1e-9);
            let cpu = self.node_pid.and_then(process_cpu_seconds).zip(cpu0).map(|(b, a)| b - a);
            let on_bus = frames.total() - frames0;
            if down && master.upload(node, index, 0, BLOCK).await.map_err(|e| failed("upload", e))? != last {
                return Err(format!("bench {} download: the bytes differ", self.label));
            }
            let moved = if down { self.size } else { last.len() * count };
            let mut line = format!(
                "bench {} {}: {moved} bytes in {count} transfers, {secs:.3} s = {:.1} KiB/s, {on_bus} frames",
                self.label,
                if down { "download" } else { "upload" },
                moved as f64 / 1024.0 / secs
            );
            if let Some(cpu) = cpu {
                line += &format!(", node CPU {cpu:.2} s = {:.2} us/frame", cpu * 1e6 / on_bus.max(1) as f64);
            }
            lines.push(line);
        }
        Ok(lines)
    }
}
