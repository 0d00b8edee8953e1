//! A small command-line CANopen master on SocketCAN, on our own sans-IO SDO client
//! (`canopen_core::sdo::client`) driven by `canopen_socketcan::Master`.
//!
//! ```text
//! cargo run --example master -- read 0x1008 0 --type str
//! cargo run --example master -- write 0x2001 0 -500 --type i16
//! cargo run --example master -- nmt start            # stop | preop | reset | reset-comm; --all = broadcast
//! cargo run --example master -- write 0x2005 0 --file image.bin --block --crc
//! cargo run --example master -- read 0x2005 0 --out copy.bin --block --crc
//! cargo run --example master -- bench --size 1048576 --node-pid 1234
//! ```
//!
//! `bench` moves `--size` bytes to and from the 2005h DOMAIN (64 KiB at a time, its capacity) by block
//! transfer with CRC, and by segmented transfer, checks every byte, and prints the throughput in KiB/s; with
//! `--node-pid` it also reads the node process's CPU time from `/proc/<pid>/stat` before and after, and
//! prints the node's CPU time per frame it handled (received + sent).

use std::process::ExitCode;
use std::time::{Duration, Instant};

use canopen_core::sdo::client::Mode;
use canopen_core::wire::nmt::NmtCommand;
use canopen_core::NodeId;
use canopen_socketcan::{BlockingBus, Master, MasterError};
use canopenctl::{parse_in, Type};
use clap::{Parser, Subcommand, ValueEnum};

/// A CANopen master on SocketCAN for trying a node: SDO read/write, block transfer of files, NMT
/// commands, a throughput bench.
#[derive(Parser, Debug)]
#[command(
    version,
    after_help = "Example: cargo run --example master -- --iface vcan0 --node 5 read 0x1008 0 --type str"
)]
struct Args {
    /// SocketCAN interface.
    #[arg(long, default_value = "vcan0", global = true)]
    iface: String,
    /// Node-ID of the server, 1..=127.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u8).range(1..=127), global = true)]
    node: u8,
    /// SDO time-out in ms.
    #[arg(long, default_value_t = 1000, global = true)]
    timeout_ms: u64,
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand, Debug)]
enum Cmd {
    /// SDO upload (read) INDEX SUB.
    Read {
        #[arg(value_parser = parse_u16)]
        index: u16,
        #[arg(value_parser = parse_u8)]
        sub: u8,
        /// How to print the value (canopenctl's types: u8..u64, i8..i64, f32, f64, bool, str, bytes).
        #[arg(long, default_value = "bytes")]
        r#type: Type,
        /// Write the bytes to FILE instead of printing them.
        #[arg(long, value_name = "FILE")]
        out: Option<String>,
        /// Block upload.
        #[arg(long)]
        block: bool,
        /// Ask for a CRC (block transfer).
        #[arg(long)]
        crc: bool,
    },
    /// SDO download (write) VALUE (or --file) to INDEX SUB.
    Write {
        #[arg(value_parser = parse_u16)]
        index: u16,
        #[arg(value_parser = parse_u8)]
        sub: u8,
        /// The value, encoded as --type.
        #[arg(allow_hyphen_values = true)]
        value: Option<String>,
        /// How to encode the value (canopenctl's types: u8..u64, i8..i64, f32, f64, bool, str, bytes).
        #[arg(long, default_value = "bytes")]
        r#type: Type,
        /// Send the bytes of FILE.
        #[arg(long, value_name = "FILE")]
        file: Option<String>,
        /// Block download.
        #[arg(long)]
        block: bool,
        /// Use a CRC (block transfer).
        #[arg(long)]
        crc: bool,
        /// Segmented even when the value would fit an expedited transfer.
        #[arg(long)]
        segmented: bool,
    },
    /// NMT node control.
    Nmt {
        #[arg(value_enum)]
        command: NmtCmd,
        /// Address every node (node-ID 0).
        #[arg(long)]
        all: bool,
    },
    /// Throughput of block and segmented transfers to/from a DOMAIN, byte-exact.
    Bench {
        /// Bytes each way.
        #[arg(long, default_value_t = 1 << 20)]
        size: usize,
        /// The DOMAIN.
        #[arg(long, default_value = "0x2005", value_parser = parse_u16)]
        index: u16,
        /// Bytes per transfer (the DOMAIN's capacity).
        #[arg(long, default_value_t = 65_536)]
        chunk: usize,
        /// Also measure segmented transfers of this many bytes each way (0 = skip).
        #[arg(long, default_value_t = 0)]
        segmented_size: usize,
        /// PID of the node process, to report its CPU time per frame.
        #[arg(long)]
        node_pid: Option<u32>,
    },
}

#[derive(ValueEnum, Clone, Copy, Debug)]
enum NmtCmd {
    Start,
    Stop,
    Preop,
    Reset,
    ResetComm,
}

fn parse_u16(s: &str) -> Result<u16, String> {
    parse_in(s)
}

fn parse_u8(s: &str) -> Result<u8, String> {
    parse_in(s)
}

fn block_mode(crc: bool) -> Mode {
    Mode::Block { crc, blksize: 127, pst: 0 }
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("master: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: Args) -> Result<(), Box<dyn std::error::Error>> {
    let node = NodeId::new(args.node).ok_or("node-ID must be 1..=127")?;
    let mut m = Master::new(BlockingBus::open(&args.iface)?, node)?;
    m.set_timeout(Duration::from_millis(args.timeout_ms));
    match args.cmd {
        Cmd::Read { index, sub, r#type, out, block, crc } => {
            let mode = if block { block_mode(crc) } else { Mode::Auto };
            let t = Instant::now();
            let data = m.upload(index, sub, mode, usize::MAX)?;
            match out {
                Some(path) => {
                    std::fs::write(&path, &data)?;
                    println!(
                        "{index:04X}h:{sub:02X}: {} bytes to {path} in {:.3} s",
                        data.len(),
                        t.elapsed().as_secs_f64()
                    );
                }
                None => println!("{}", r#type.decode(&data)?),
            }
        }
        Cmd::Write { index, sub, value, r#type, file, block, crc, segmented } => {
            let data = match (file, value) {
                (Some(path), _) => std::fs::read(path)?,
                (None, Some(v)) => r#type.encode(&v)?,
                (None, None) => return Err("give a VALUE or --file".into()),
            };
            let mode = if block {
                block_mode(crc)
            } else if segmented {
                Mode::Segmented
            } else {
                Mode::Auto
            };
            let t = Instant::now();
            m.download(index, sub, &data, mode)?;
            println!("{index:04X}h:{sub:02X}: {} bytes written in {:.3} s", data.len(), t.elapsed().as_secs_f64());
        }
        Cmd::Nmt { command, all } => {
            let cmd = match command {
                NmtCmd::Start => NmtCommand::Start,
                NmtCmd::Stop => NmtCommand::Stop,
                NmtCmd::Preop => NmtCommand::EnterPreOperational,
                NmtCmd::Reset => NmtCommand::ResetNode,
                NmtCmd::ResetComm => NmtCommand::ResetCommunication,
            };
            m.nmt(cmd, all)?;
            match m.wait_heartbeat(Duration::from_secs(3))? {
                Some(state) => println!("NMT {command:?} sent; node {} now reports state {state:02X}h", node.get()),
                None => println!("NMT {command:?} sent; no heartbeat within 3 s"),
            }
        }
        Cmd::Bench { size, index, chunk, segmented_size, node_pid } => {
            bench(&mut m, index, size, chunk, block_mode(true), "block+CRC", node_pid)?;
            if segmented_size > 0 {
                bench(&mut m, index, segmented_size, chunk, Mode::Segmented, "segmented", node_pid)?;
            }
        }
    }
    for e in m.take_adapter_events() {
        eprintln!("master: adapter: {e}");
    }
    Ok(())
}

/// CPU time (user + system) of `pid` in seconds, from `/proc/<pid>/stat` (clock ticks of 10 ms).
fn cpu_seconds(pid: u32) -> Option<f64> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // Fields after the command name (which may contain spaces) start after the last ')'.
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let utime: f64 = fields.get(11)?.parse().ok()?;
    let stime: f64 = fields.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

fn pattern(len: usize, seed: u32) -> Vec<u8> {
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

fn bench(
    m: &mut Master,
    index: u16,
    size: usize,
    chunk: usize,
    mode: Mode,
    label: &str,
    node_pid: Option<u32>,
) -> Result<(), MasterError> {
    let upload_mode = if matches!(mode, Mode::Segmented) { Mode::Auto } else { mode };
    let differs = |what: &str| MasterError::Io(std::io::Error::other(format!("{label} {what}: data differs")));
    let count = size.div_ceil(chunk).max(1);
    let chunks: Vec<Vec<u8>> = (0..count).map(|i| pattern(chunk.min(size - i * chunk), i as u32 + 1)).collect();
    for down in [true, false] {
        if !down {
            // The upload phase reads back the last chunk, put in place untimed.
            m.download(index, 0, &chunks[count - 1], block_mode(true))?;
        }
        let cpu0 = node_pid.and_then(cpu_seconds);
        let frames0 = m.stats();
        let t = Instant::now();
        for data in &chunks {
            if down {
                m.download(index, 0, data, mode)?;
            } else if m.upload(index, 0, upload_mode, chunk)? != chunks[count - 1] {
                return Err(differs("upload"));
            }
        }
        let secs = t.elapsed().as_secs_f64();
        let cpu = node_pid.and_then(cpu_seconds).zip(cpu0).map(|(b, a)| b - a);
        let frames = m.stats().sent + m.stats().received - frames0.sent - frames0.received;
        if down && m.upload(index, 0, block_mode(true), chunk)? != chunks[count - 1] {
            return Err(differs("download"));
        }
        let moved: usize = if down { size } else { chunks[count - 1].len() * count };
        print!(
            "bench {label} {}: {moved} bytes in {count} transfers, {secs:.3} s = {:.1} KiB/s, {frames} frames",
            if down { "download" } else { "upload" },
            moved as f64 / 1024.0 / secs
        );
        if let Some(cpu) = cpu {
            print!(", node CPU {cpu:.2} s = {:.2} us/frame", cpu * 1e6 / frames.max(1) as f64);
        }
        println!();
    }
    Ok(())
}
