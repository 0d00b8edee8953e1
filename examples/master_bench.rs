//! Throughput bench of the async master (`canopen-master`, issue 23 item 4) against example nodes on a
//! SocketCAN interface, run by scripts/bench-master.sh inside the with-vcan VM.
//!
//! ```text
//! cargo run --release --example master_bench -- block --node 5 --size 1048576
//! cargo run --release --example master_bench -- ten --first 11 --rounds 20
//! ```
//!
//! `block` moves `--size` bytes to and then from the 2005h DOMAIN (64 KiB at a time, its capacity) by block
//! transfer with CRC, checks every byte and prints KiB/s each way, and the frames on the bus (received:
//! counted; sent: what the protocol makes the master send for them), for a system-call count per frame.
//! `ten` reads 1018h:04 (the serial number) of ten nodes at once, `--rounds` times, and prints the time
//! per round; each answer must be its node's own serial (1000 + node-ID, as scripts/bench-master.sh starts
//! them), so no transfer took another's frames.

use std::process::ExitCode;
use std::time::{Duration, Instant};

use canopen_master::{Master, BLOCK};
use clap::{Parser, Subcommand};
use tokio::sync::broadcast::{error::TryRecvError, Receiver};

/// The async master's throughput bench: block transfers to one node, ten nodes read at once.
#[derive(Parser, Debug)]
#[command(
    version,
    after_help = "Example: cargo run --example master_bench -- block --node 5 (with --release for figures)"
)]
struct Args {
    /// SocketCAN interface.
    #[arg(long, default_value = "vcan0", global = true)]
    iface: String,
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand, Debug)]
enum Cmd {
    /// `--size` bytes down and up by block transfer with CRC, 64 KiB at a time.
    Block {
        /// Node-ID of the example node.
        #[arg(long, default_value_t = 5)]
        node: u8,
        /// Bytes each way (a multiple of 64 KiB moves whole transfers).
        #[arg(long, default_value_t = 1 << 20)]
        size: usize,
    },
    /// Ten nodes (`--first` .. `--first`+9) read at once.
    Ten {
        /// The first node-ID.
        #[arg(long, default_value_t = 11)]
        first: u8,
        /// How many rounds of ten reads.
        #[arg(long, default_value_t = 20)]
        rounds: u32,
    },
}

const CHUNK: usize = 65_536;

fn pattern(len: usize, seed: usize) -> Vec<u8> {
    (0..len).map(|i| ((i * 7 + (i >> 8) + seed) & 0xFF) as u8).collect()
}

/// Frames the master sends in one block transfer of `len` bytes with 127-segment sub-blocks (SDO block
/// protocol, CiA 301 7.2.4.3.11ff): download: initiate, the segments, end; upload: initiate, start, one
/// acknowledgement per sub-block, the end response.
fn sent_frames(len: usize, download: bool) -> u64 {
    let segments = len.div_ceil(7) as u64;
    if download {
        segments + 2
    } else {
        3 + segments.div_ceil(127)
    }
}

/// How many frames `rx` got since the last call (those it lost by lagging behind included).
fn drain<T: Clone>(rx: &mut Receiver<T>) -> u64 {
    let mut n = 0;
    loop {
        match rx.try_recv() {
            Ok(_) => n += 1,
            Err(TryRecvError::Lagged(lost)) => n += lost,
            Err(_) => return n,
        }
    }
}

async fn block(m: &Master, node: u8, size: usize) -> Result<(), String> {
    let mut frames = m.frames();
    let (mut down, mut up, mut sent) = (Duration::ZERO, Duration::ZERO, 0u64);
    let chunks: Vec<Vec<u8>> = (0..size.div_ceil(CHUNK)).map(|i| pattern(CHUNK.min(size - i * CHUNK), i)).collect();
    let (mut rx_down, mut rx_up) = (0u64, 0u64);
    for data in &chunks {
        let t = Instant::now();
        m.download(node, 0x2005, 0, data, BLOCK).await.map_err(|e| format!("download: {e}"))?;
        down += t.elapsed();
        rx_down += drain(&mut frames);
        let t = Instant::now();
        let back = m.upload(node, 0x2005, 0, BLOCK).await.map_err(|e| format!("upload: {e}"))?;
        up += t.elapsed();
        rx_up += drain(&mut frames);
        if back != *data {
            return Err("the uploaded bytes differ from the downloaded ones".into());
        }
        sent += sent_frames(data.len(), true) + sent_frames(data.len(), false);
    }
    let kib_s = |d: Duration| size as f64 / 1024.0 / d.as_secs_f64();
    println!(
        "canopen-master block+CRC, {size} bytes ({} x {CHUNK}): download {:.1} KiB/s ({:.2} s), upload {:.1} KiB/s ({:.2} s)",
        chunks.len(),
        kib_s(down),
        down.as_secs_f64(),
        kib_s(up),
        up.as_secs_f64()
    );
    let received = rx_down + rx_up;
    println!(
        "frames={} (received {received} = {rx_down} during downloads + {rx_up} during uploads, sent {sent})",
        received + sent
    );
    Ok(())
}

async fn ten(m: &Master, first: u8, rounds: u32) -> Result<(), String> {
    let nodes: Vec<u8> = (first..first.saturating_add(10)).collect();
    let (mut best, mut total) = (Duration::MAX, Duration::ZERO);
    for _ in 0..rounds {
        let t = Instant::now();
        let mut set = tokio::task::JoinSet::new();
        for &node in &nodes {
            let m = m.clone();
            set.spawn(async move { (node, m.read::<u32>(node, 0x1018, 4).await) });
        }
        while let Some(r) = set.join_next().await {
            let (node, serial) = r.map_err(|e| e.to_string())?;
            let serial = serial.map_err(|e| format!("node {node}: {e}"))?;
            if serial != 1000 + u32::from(node) {
                return Err(format!("node {node} answered serial {serial}: another node's frames"));
            }
        }
        let d = t.elapsed();
        best = best.min(d);
        total += d;
    }
    println!(
        "canopen-master: 10 nodes ({}..={}) read at once (1018h:04 each), {rounds} rounds: {:.2} ms per round \
         (best {:.2} ms), {:.0} reads/s",
        nodes[0],
        nodes[nodes.len() - 1],
        total.as_secs_f64() * 1e3 / f64::from(rounds),
        best.as_secs_f64() * 1e3,
        f64::from(rounds) * 10.0 / total.as_secs_f64()
    );
    Ok(())
}

#[tokio::main(flavor = "current_thread")]
async fn main() -> ExitCode {
    let args = Args::parse();
    let m = match Master::open(&args.iface) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("master_bench: {}: {e}", args.iface);
            return ExitCode::FAILURE;
        }
    };
    let r = match args.cmd {
        Cmd::Block { node, size } => block(&m, node, size).await,
        Cmd::Ten { first, rounds } => ten(&m, first, rounds).await,
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("master_bench: {e}");
            ExitCode::FAILURE
        }
    }
}
