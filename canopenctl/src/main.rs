//! `canopenctl`: a CANopen master on the command line (see the README). Exit status: 0 done, 1 the
//! operation failed (an SDO abort, a time-out, a socket error; the message says which), 2 bad usage.

use std::io::{IsTerminal, Write};
use std::process::ExitCode;
use std::time::Duration;

use canopen_core::wire::lss::{IdentityField, LssMode};
use canopen_core::NodeId;
use canopen_eds::{data_type_name, Eds};
use canopen_master::slcan::Interface;
use canopen_master::{Error, Master, Mode, NmtCommand, StateCode, BLOCK};
use canopenctl::bench::{Bench, Counted};
use canopenctl::{guess, monitor_line, parse_in, parse_node, Type};
use clap::{Args, Parser, Subcommand, ValueEnum};

mod drive_cmd;

#[derive(Parser)]
#[command(
    name = "canopenctl",
    version,
    about = "A CANopen (CiA 301) master for Linux SocketCAN and slcan serial adapters"
)]
#[command(after_help = "Numbers (nodes, indices, sub-indices, values) are decimal or 0x-hex.\n\
Example: canopenctl --iface can0 read 5 0x1018 1")]
struct Cli {
    /// The CAN interface: a SocketCAN name (can0), or an slcan adapter: slcan:/dev/ttyACM0, slcan:COM3,
    /// slcan:tcp:HOST:PORT, each optionally @BITRATE in bit/s (slcan:/dev/ttyACM0@500000) to set its bit rate.
    #[arg(long, global = true, default_value = "vcan0")]
    iface: String,
    /// SDO time-out per protocol step, in ms.
    #[arg(long, global = true, default_value_t = 1000)]
    timeout: u64,
    /// The node's EDS or DCF (CiA 306): types reads and writes, and lets objects be named.
    #[arg(long, global = true, value_name = "FILE")]
    eds: Option<std::path::PathBuf>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// List the nodes that answer an SDO read of 1000h (all 127 asked at once), with their device name.
    Scan,
    /// Read NODE INDEX SUB and print the value.
    Read {
        #[command(flatten)]
        at: Object,
        /// The data type (u8..u64, i8..i64, f32, f64, bool, str, bytes); without it the size decides.
        #[arg(long = "type")]
        ty: Option<Type>,
    },
    /// Write VALUE to NODE INDEX SUB (negative numbers, floats and strings too).
    Write {
        #[command(flatten)]
        at: Object,
        #[arg(allow_hyphen_values = true)]
        value: String,
        /// The data type; without it a number takes the object's size (read first), text is a string.
        #[arg(long = "type")]
        ty: Option<Type>,
        /// A segmented transfer even when the value fits an expedited one.
        #[arg(long)]
        segmented: bool,
    },
    /// Send an NMT command to NODE (or `all`).
    Nmt {
        command: NmtArg,
        /// A node-ID, or `all`.
        node: String,
        /// Wait up to 3 s for NODE's heartbeat to report the state the command leads to (boot-up after a
        /// reset); exit 1 if it does not.
        #[arg(long)]
        wait: bool,
    },
    /// LSS (CiA 305): find and configure nodes without a node-ID.
    Lss {
        #[command(subcommand)]
        command: LssCommand,
    },
    /// Read every readable entry of the EDS (--eds) from NODE and print it with its name and type.
    Dump {
        #[arg(value_parser = parse_node)]
        node: u8,
    },
    /// Print a Rust module for an EDS: the application objects as a derived object dictionary and the
    /// node configuration (uses only canopen-core and canopen-od-derive). Needs no bus.
    EdsToRust {
        file: std::path::PathBuf,
        /// How the struct is served: `code` (match arms, fewest instructions), `compact` (tables), or
        /// `zerocopy` (tables and offsets, least flash; the crate needs `zerocopy` with `derive`).
        #[arg(long, default_value = "code")]
        layout: canopen_eds::StructLayout,
    },
    /// Print every frame on the bus, decoded, candump style.
    Monitor {
        /// Stop after this many frames.
        #[arg(long)]
        count: Option<u64>,
        /// Stop after this many seconds.
        #[arg(long)]
        duration: Option<f64>,
    },
    /// Read a DOMAIN (or any object) of NODE into FILE.
    Upload {
        #[command(flatten)]
        at: Object,
        file: std::path::PathBuf,
        /// segmented or block (with CRC).
        #[arg(long, default_value = "block")]
        mode: ModeArg,
    },
    /// Write FILE into a DOMAIN (or any object) of NODE.
    Download {
        #[command(flatten)]
        at: Object,
        file: std::path::PathBuf,
        #[arg(long, default_value = "block")]
        mode: ModeArg,
    },
    /// A CiA 402 drive: state, enable, disable, quick-stop, fault-reset, mode, move, velocity, home, stream.
    Drive {
        #[arg(value_parser = parse_node)]
        node: u8,
        #[command(subcommand)]
        command: drive_cmd::DriveCommand,
    },
    /// SDO throughput to and from a DOMAIN of NODE, every byte checked: block transfer with CRC (and
    /// segmented with --segmented-size), KiB/s and frames on the bus each way.
    Bench {
        #[arg(value_parser = parse_node)]
        node: u8,
        /// Bytes each way.
        #[arg(long, default_value_t = 1 << 20)]
        size: usize,
        /// The DOMAIN.
        #[arg(long, default_value = "0x2005", value_parser = parse_in::<u16>)]
        index: u16,
        /// Bytes per transfer (the DOMAIN's capacity).
        #[arg(long, default_value_t = 65_536, value_parser = clap::value_parser!(u32).range(1..))]
        chunk: u32,
        /// Also segmented transfers of this many bytes each way (0: none).
        #[arg(long, default_value_t = 0)]
        segmented_size: usize,
        /// The node's process ID: print its CPU time per frame (from /proc/PID/stat).
        #[arg(long)]
        node_pid: Option<u32>,
    },
}

/// NODE INDEX SUB, numbers in decimal or 0x-hex; with `--eds`, INDEX and SUB may be names.
#[derive(Args, Clone)]
struct Object {
    /// Node-ID, 1..=127.
    #[arg(value_parser = parse_node)]
    node: u8,
    /// Object index, or with --eds its name (e.g. "Identity object").
    index: String,
    /// Sub-index, or with --eds the entry's name (e.g. "Serial number").
    sub: String,
}

impl Object {
    /// The node, index and sub-index, names looked up in `eds`.
    fn resolve(&self, eds: Option<&Eds>) -> Result<(u8, u16, u8), String> {
        let index = match (parse_in::<u16>(&self.index), eds) {
            (Ok(i), _) => i,
            (Err(_), Some(eds)) => match eds.find(&self.index) {
                Some((i, None)) => i,
                _ => return Err(format!("no object named '{}' in the EDS", self.index)),
            },
            (Err(e), None) => return Err(format!("{e} (names need --eds)")),
        };
        let sub = match (parse_in::<u8>(&self.sub), eds) {
            (Ok(s), _) => s,
            (Err(_), Some(eds)) => eds
                .objects
                .get(&index)
                .and_then(|o| o.entries.values().find(|e| e.name.eq_ignore_ascii_case(self.sub.trim())))
                .map(|e| e.sub)
                .ok_or_else(|| format!("no entry named '{}' in {index:04X}h of the EDS", self.sub))?,
            (Err(e), None) => return Err(format!("{e} (names need --eds)")),
        };
        Ok((self.node, index, sub))
    }
}

#[derive(Clone, Copy, ValueEnum)]
enum NmtArg {
    Start,
    Stop,
    Preop,
    Reset,
    ResetComm,
}

#[derive(Clone, Copy, ValueEnum)]
enum ModeArg {
    /// Expedited up to 4 bytes, else segmented.
    Auto,
    /// Segmented transfer.
    Segmented,
    /// Block transfer with CRC.
    Block,
    /// Block transfer without CRC.
    BlockNoCrc,
}

#[derive(Subcommand)]
enum LssCommand {
    /// Find one node without a node-ID (it is then in LSS configuration) and print its LSS address.
    Fastscan,
    /// Give the node in LSS configuration this node-ID.
    SetId {
        #[arg(value_parser = parse_in::<u8>)]
        node_id: u8,
    },
    /// Make the node in LSS configuration store its node-ID and bit timing.
    Store,
    /// Switch every node to LSS `waiting` (the configured one boots with its new node-ID) or `config`.
    Switch { mode: SwitchArg },
    /// Print the LSS address and node-ID of the node in LSS configuration.
    Inquire,
    /// Give every node without a node-ID one, from FIRST upwards (fastscan, set, store when asked).
    Commission {
        #[arg(value_parser = parse_node)]
        first: u8,
        #[arg(long)]
        store: bool,
    },
}

#[derive(Clone, Copy, ValueEnum)]
enum SwitchArg {
    Waiting,
    Config,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    if let Command::EdsToRust { file, layout } = &cli.command {
        return match std::fs::read_to_string(file)
            .map_err(|e| e.to_string())
            .and_then(|t| Eds::parse(&t).map_err(|e| e.to_string()))
        {
            Ok(eds) => {
                let name =
                    file.file_name().map_or_else(|| file.display().to_string(), |n| n.to_string_lossy().into_owned());
                let g = canopen_eds::rust_module_as(&eds, &name, *layout);
                print!("{}", g.rust);
                // What the module leaves out, on stderr too (a comment in the module says each where it is).
                for l in &g.left_out {
                    eprintln!("canopenctl: {name}: {l}");
                }
                ExitCode::SUCCESS
            }
            Err(e) => fail(&format!("{}: {e}", file.display())),
        };
    }
    // Arguments clap cannot check alone (names and numbers against the EDS) are usage errors too: exit 2.
    if let Err(e) = check(&cli) {
        eprintln!("canopenctl: {e}");
        return ExitCode::from(2);
    }
    let rt = match tokio::runtime::Builder::new_current_thread().enable_all().build() {
        Ok(rt) => rt,
        Err(e) => return fail(&format!("cannot start the runtime: {e}")),
    };
    match rt.block_on(run(cli)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => fail(&e),
    }
}

fn load_eds(cli: &Cli) -> Result<Option<Eds>, String> {
    let Some(path) = &cli.eds else { return Ok(None) };
    let t = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    Eds::parse(&t).map(Some).map_err(|e| format!("{}: {e}", path.display()))
}

fn check(cli: &Cli) -> Result<(), String> {
    let eds = load_eds(cli)?;
    match &cli.command {
        Command::Read { at, .. }
        | Command::Write { at, .. }
        | Command::Upload { at, .. }
        | Command::Download { at, .. } => at.resolve(eds.as_ref()).map(|_| ()),
        Command::Dump { .. } if eds.is_none() => Err("dump needs the node's EDS: --eds FILE".into()),
        Command::Nmt { node, wait: true, .. } if node.eq_ignore_ascii_case("all") => {
            Err("nmt --wait needs one node, not all".into())
        }
        _ => Ok(()),
    }
}

fn fail(message: &str) -> ExitCode {
    eprintln!("canopenctl: {message}");
    ExitCode::FAILURE
}

fn text(e: Error) -> String {
    e.to_string()
}

async fn run(cli: Cli) -> Result<(), String> {
    let eds = load_eds(&cli)?;
    let eds = eds.as_ref();
    // The type of `index:sub`: --type, else the EDS's.
    let typed = |ty: Option<Type>, index: u16, sub: u8| {
        ty.or_else(|| eds.and_then(|e| e.entry(index, sub)).and_then(|e| Type::from_data_type(e.data_type)))
    };
    // The socket counts its frames, for `bench`.
    let io = Counted::new(Interface::open(&cli.iface).await.map_err(|e| text(e.into()))?);
    let frames = io.count();
    let master = Master::new(io).with_sdo_timeout(Duration::from_millis(cli.timeout));
    let mut out = std::io::stdout().lock();
    let mut say = |line: String| {
        // A closed pipe (`| head`) ends the output, not the program with a panic.
        let _ = writeln!(out, "{line}");
    };
    match cli.command {
        Command::Scan => {
            let found = master.scan(Duration::from_millis(cli.timeout.min(500))).await.map_err(text)?;
            for node in &found {
                let device_type = master.read::<u32>(*node, 0x1000, 0).await;
                let name = master.read::<String>(*node, 0x1008, 0).await;
                let mut line = format!("node {node} (0x{node:02X})");
                if let Ok(t) = device_type {
                    line += &format!(": device type 0x{t:08X}");
                }
                if let Ok(n) = name {
                    line += &format!(", \"{n}\"");
                }
                say(line);
            }
            say(format!("{} node(s)", found.len()));
        }
        Command::Drive { node, command } => {
            for line in drive_cmd::run(&master, node, command).await? {
                say(line);
            }
        }
        Command::Read { at, ty } => {
            let (node, index, sub) = at.resolve(eds)?;
            let ty = typed(ty, index, sub);
            let bytes = master.upload(node, index, sub, Mode::Auto).await.map_err(text)?;
            say(match ty {
                Some(t) => t.decode(&bytes)?,
                None => guess(&bytes),
            });
        }
        Command::Write { at, value, ty, segmented } => {
            let (node, index, sub) = at.resolve(eds)?;
            let ty = match typed(ty, index, sub) {
                Some(t) => t,
                None => {
                    let numeric = Type::infer(&value, Some(8)).is_ok_and(|t| t != Type::Str);
                    let len = if numeric {
                        master.upload(node, index, sub, Mode::Auto).await.ok().map(|b| b.len())
                    } else {
                        None
                    };
                    Type::infer(&value, len)?
                }
            };
            let bytes = ty.encode(&value)?;
            let mode = if segmented { Mode::Segmented } else { Mode::Auto };
            master.download(node, index, sub, &bytes, mode).await.map_err(text)?;
        }
        Command::Nmt { command, node, wait } => {
            let target = if node.eq_ignore_ascii_case("all") { 0 } else { parse_node(&node)? };
            let command = match command {
                NmtArg::Start => NmtCommand::Start,
                NmtArg::Stop => NmtCommand::Stop,
                NmtArg::Preop => NmtCommand::EnterPreOperational,
                NmtArg::Reset => NmtCommand::ResetNode,
                NmtArg::ResetComm => NmtCommand::ResetCommunication,
            };
            // Subscribed before the command goes out: a boot-up right after it is not missed.
            let mut beats = master.heartbeats();
            master.nmt(target, command).await.map_err(text)?;
            if wait {
                let state = match command {
                    NmtCommand::Start => StateCode::Operational,
                    NmtCommand::Stop => StateCode::Stopped,
                    NmtCommand::EnterPreOperational => StateCode::PreOperational,
                    NmtCommand::ResetNode | NmtCommand::ResetCommunication => StateCode::BootUp,
                };
                let until = tokio::time::Instant::now() + Duration::from_secs(3);
                loop {
                    match tokio::time::timeout_at(until, beats.recv()).await {
                        Ok(Ok(hb)) if hb.node == target && hb.state() == Some(state) => break,
                        Ok(Ok(_)) | Ok(Err(tokio::sync::broadcast::error::RecvError::Lagged(_))) => {}
                        Ok(Err(tokio::sync::broadcast::error::RecvError::Closed)) | Err(_) => {
                            return Err(format!("node {target} did not report {state:?} within 3 s"));
                        }
                    }
                }
                say(format!("node {target} reports {state:?}"));
            }
        }
        Command::Lss { command } => {
            let mut lss = master.lss().await.map_err(text)?.with_timeout(Duration::from_millis(cli.timeout.min(500)));
            match command {
                LssCommand::Fastscan => match lss.fastscan().await.map_err(text)? {
                    Some(id) => say(format!(
                        "vendor 0x{:08X} product 0x{:08X} revision 0x{:08X} serial 0x{:08X} (now in LSS configuration)",
                        id.vendor_id, id.product_code, id.revision, id.serial
                    )),
                    None => return Err("no node without a node-ID answered".into()),
                },
                LssCommand::SetId { node_id } => {
                    let status = lss.configure_node_id(node_id).await.map_err(text)?;
                    if !status.is_success() {
                        return Err(format!("the node refused node-ID {node_id}: error {}", status.error));
                    }
                }
                LssCommand::Store => {
                    let status = lss.store().await.map_err(text)?;
                    if !status.is_success() {
                        return Err(format!("the node could not store: error {}", status.error));
                    }
                }
                LssCommand::Switch { mode } => {
                    let mode = match mode {
                        SwitchArg::Waiting => LssMode::Waiting,
                        SwitchArg::Config => LssMode::Configuration,
                    };
                    lss.switch_global(mode).await.map_err(text)?;
                }
                LssCommand::Inquire => {
                    let mut line = String::new();
                    for (name, field) in [
                        ("vendor", IdentityField::VendorId),
                        ("product", IdentityField::ProductCode),
                        ("revision", IdentityField::Revision),
                        ("serial", IdentityField::Serial),
                    ] {
                        line += &format!("{name} 0x{:08X} ", lss.inquire(field).await.map_err(text)?);
                    }
                    let id = lss.inquire_node_id().await.map_err(text)?;
                    say(format!("{line}node-ID {}", if id == 0xFF { "none".to_owned() } else { id.to_string() }));
                }
                LssCommand::Commission { first, store } => {
                    let first = NodeId::new(first).ok_or("bad node-ID")?;
                    let assigned = lss.commission(first, store).await.map_err(text)?;
                    for (id, node) in &assigned {
                        say(format!("serial 0x{:08X} -> node {}", id.serial, node.get()));
                    }
                    say(format!("{} node(s) configured", assigned.len()));
                }
            }
        }
        Command::Dump { node } => {
            let eds = eds.ok_or("dump needs the node's EDS: --eds FILE")?;
            for e in eds.entries() {
                let kind = data_type_name(e.data_type).unwrap_or("?");
                let head = format!("{:04X}h:{:02X} {} ({kind}, {})", e.index, e.sub, e.name, e.access.as_str());
                if !e.access.readable() {
                    say(format!("{head}: write-only"));
                    continue;
                }
                let value = match master.upload(node, e.index, e.sub, Mode::Auto).await {
                    Ok(bytes) if e.data_type == 0x000F => format!("{} bytes", bytes.len()),
                    Ok(bytes) => match Type::from_data_type(e.data_type) {
                        Some(t) => t.decode(&bytes).unwrap_or_else(|m| format!("{} ({m})", canopenctl::hex(&bytes))),
                        None => guess(&bytes),
                    },
                    Err(err) => format!("! {err}"),
                };
                say(format!("{head} = {value}"));
            }
        }
        Command::EdsToRust { .. } => unreachable!("handled in main without a bus"),
        Command::Monitor { count, duration } => {
            let mut frames = master.frames();
            let until = duration.map(|s| tokio::time::Instant::now() + Duration::from_secs_f64(s.max(0.0)));
            let mut seen = 0u64;
            while count.is_none_or(|c| seen < c) {
                let next = async {
                    match until {
                        Some(t) => tokio::time::timeout_at(t, frames.recv()).await.ok(),
                        None => Some(frames.recv().await),
                    }
                };
                match next.await {
                    None => break,
                    Some(Ok(f)) => {
                        seen += 1;
                        say(monitor_line(&cli.iface, &f));
                    }
                    Some(Err(tokio::sync::broadcast::error::RecvError::Lagged(n))) => {
                        say(format!("  ({n} frames lost: the output is slower than the bus)"));
                    }
                    Some(Err(tokio::sync::broadcast::error::RecvError::Closed)) => break,
                }
            }
        }
        Command::Upload { at, file, mode } => {
            let (node, index, sub) = at.resolve(eds)?;
            let mut f = std::fs::File::create(&file).map_err(|e| format!("{}: {e}", file.display()))?;
            let mut bar = Bar::new(None);
            let len = master
                .upload_to(node, index, sub, mode.into(), &mut f, Some(&mut |n| bar.show(n)))
                .await
                .map_err(text)?;
            bar.done();
            say(format!("{len} bytes into {}", file.display()));
        }
        Command::Bench { node, size, index, chunk, segmented_size, node_pid } => {
            let mut runs =
                vec![Bench { node, index, size, chunk: chunk as usize, mode: BLOCK, label: "block+CRC", node_pid }];
            if segmented_size > 0 {
                runs.push(Bench { size: segmented_size, mode: Mode::Segmented, label: "segmented", ..runs[0].clone() });
            }
            for run in &runs {
                for line in run.run(&master, &frames).await? {
                    say(line);
                }
            }
        }
        Command::Download { at, file, mode } => {
            let (node, index, sub) = at.resolve(eds)?;
            let mut f = std::fs::File::open(&file).map_err(|e| format!("{}: {e}", file.display()))?;
            let len = f.metadata().map_err(|e| format!("{}: {e}", file.display()))?.len();
            let mut bar = Bar::new(Some(len));
            master
                .download_from(node, index, sub, mode.into(), &mut f, len, Some(&mut |n| bar.show(n)))
                .await
                .map_err(text)?;
            bar.done();
            say(format!("{len} bytes from {}", file.display()));
        }
    }
    Ok(())
}

impl From<ModeArg> for Mode {
    fn from(m: ModeArg) -> Mode {
        match m {
            ModeArg::Auto => Mode::Auto,
            ModeArg::Segmented => Mode::Segmented,
            ModeArg::Block => BLOCK,
            ModeArg::BlockNoCrc => Mode::Block { crc: false, blksize: 127, pst: 0 },
        }
    }
}

/// A progress line on stderr, only when stderr is a terminal (nothing in a pipe or a log).
struct Bar {
    total: Option<u64>,
    tty: bool,
    start: std::time::Instant,
    last: Option<std::time::Instant>,
}

impl Bar {
    fn new(total: Option<u64>) -> Self {
        Bar { total, tty: std::io::stderr().is_terminal(), start: std::time::Instant::now(), last: None }
    }

    fn show(&mut self, n: u64) {
        if !self.tty || self.last.is_some_and(|t| t.elapsed() < Duration::from_millis(100)) {
            return;
        }
        self.last = Some(std::time::Instant::now());
        let rate = n as f64 / 1024.0 / self.start.elapsed().as_secs_f64().max(1e-3);
        let line = match self.total {
            Some(t) if t > 0 => {
                let filled = (n.min(t) * 30 / t) as usize;
                format!("[{}{}] {n}/{t} bytes, {rate:.1} KiB/s", "#".repeat(filled), " ".repeat(30 - filled))
            }
            _ => format!("{n} bytes, {rate:.1} KiB/s"),
        };
        eprint!("\r{line}");
    }

    fn done(&self) {
        if self.tty && self.last.is_some() {
            eprintln!();
        }
    }
}
