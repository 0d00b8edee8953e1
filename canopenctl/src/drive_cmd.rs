//! `canopenctl drive NODE ...`: CiA 402 drives through `canopen_master::Drive402`.

use std::time::Duration;

use canopen_cia402::{Mode, State};
use canopen_master::drive::Cyclic;
use canopen_master::Master;
use clap::{Subcommand, ValueEnum};

/// What to do with the drive.
#[derive(Subcommand)]
pub enum DriveCommand {
    /// Print the state, the statusword and the mode of operation.
    State,
    /// Walk the state machine to Operation enabled (resetting a fault first).
    Enable,
    /// Disable voltage: to Switch on disabled.
    Disable,
    /// Quick stop (controlword 02h); prints the state the drive settles in.
    QuickStop,
    /// Fault reset: from Fault to Switch on disabled.
    FaultReset,
    /// Set the mode of operation (6060h), confirmed by 6061h.
    Mode { mode: ModeArg },
    /// Profile position: move to POSITION (increments) and wait for target reached; prints 6064h.
    Move {
        #[arg(allow_hyphen_values = true)]
        position: i32,
        /// POSITION is relative to the last target.
        #[arg(long)]
        relative: bool,
        /// Seconds to wait for target reached.
        #[arg(long, default_value_t = 30.0)]
        wait: f64,
    },
    /// Profile velocity: set 60FFh (inc/s) and wait until the drive runs at it.
    Velocity {
        #[arg(allow_hyphen_values = true)]
        velocity: i32,
    },
    /// Homing: run METHOD (6098h; default: the drive's) and wait for homing attained and target reached.
    Home {
        #[arg(long, allow_hyphen_values = true)]
        method: Option<i8>,
        /// Seconds to wait.
        #[arg(long, default_value_t = 60.0)]
        wait: f64,
    },
    /// Cyclic synchronous set-points: FROM to TO by STEP, one per period, each in RPDO3 (position) or RPDO4
    /// (velocity) followed by a SYNC.
    Stream {
        kind: CyclicArg,
        #[arg(allow_hyphen_values = true)]
        from: i32,
        #[arg(allow_hyphen_values = true)]
        to: i32,
        /// The change per period.
        #[arg(long, default_value_t = 10)]
        step: u32,
        /// The SYNC period, ms.
        #[arg(long, default_value_t = 2)]
        period_ms: u64,
    },
}

/// A mode of operation by its short name.
#[derive(Clone, Copy, ValueEnum)]
pub enum ModeArg {
    /// 0: no mode.
    None,
    /// 1: profile position.
    Pp,
    /// 3: profile velocity.
    Pv,
    /// 6: homing.
    Hm,
    /// 8: cyclic synchronous position.
    Csp,
    /// 9: cyclic synchronous velocity.
    Csv,
}

impl ModeArg {
    fn mode(self) -> Mode {
        match self {
            ModeArg::None => Mode::NoMode,
            ModeArg::Pp => Mode::ProfilePosition,
            ModeArg::Pv => Mode::ProfileVelocity,
            ModeArg::Hm => Mode::Homing,
            ModeArg::Csp => Mode::CyclicSyncPosition,
            ModeArg::Csv => Mode::CyclicSyncVelocity,
        }
    }
}

/// Which set-point a stream carries.
#[derive(Clone, Copy, ValueEnum)]
pub enum CyclicArg {
    /// 607Ah in RPDO3.
    Position,
    /// 60FFh in RPDO4.
    Velocity,
}

fn secs(s: f64) -> Result<Duration, String> {
    Duration::try_from_secs_f64(s).map_err(|e| format!("{s} s: {e}"))
}

/// Runs `command` on drive `node`; returns the lines to print.
pub async fn run(master: &Master, node: u8, command: DriveCommand) -> Result<Vec<String>, String> {
    let d = master.drive(node).map_err(|e| e.to_string())?;
    let e = |e: canopen_master::Error| e.to_string();
    Ok(match command {
        DriveCommand::State => {
            let word = d.statusword().await.map_err(e)?;
            let mode: i8 = master.read(node, 0x6061, 0).await.map_err(e)?;
            let state = State::from_statusword(word).map_or("UNKNOWN", State::name);
            vec![format!("{state} (statusword 0x{word:04X}, mode of operation {mode})")]
        }
        DriveCommand::Enable => {
            d.enable().await.map_err(e)?;
            vec![State::OperationEnabled.name().to_owned()]
        }
        DriveCommand::Disable => {
            d.disable().await.map_err(e)?;
            vec![State::SwitchOnDisabled.name().to_owned()]
        }
        DriveCommand::QuickStop => vec![d.quick_stop().await.map_err(e)?.name().to_owned()],
        DriveCommand::FaultReset => {
            d.fault_reset().await.map_err(e)?;
            vec![State::SwitchOnDisabled.name().to_owned()]
        }
        DriveCommand::Mode { mode } => {
            d.set_mode(mode.mode()).await.map_err(e)?;
            vec![format!("mode of operation {}", mode.mode().code())]
        }
        DriveCommand::Move { position, relative, wait } => {
            let at = d.move_to(position, relative, secs(wait)?).await.map_err(e)?;
            vec![format!("target reached, position actual value {at}")]
        }
        DriveCommand::Velocity { velocity } => {
            d.velocity(velocity, Duration::from_secs(30)).await.map_err(e)?;
            let actual: i32 = master.read(node, 0x606C, 0).await.map_err(e)?;
            vec![format!("target reached, velocity actual value {actual}")]
        }
        DriveCommand::Home { method, wait } => {
            d.home(method, secs(wait)?).await.map_err(e)?;
            let at: i32 = master.read(node, 0x6064, 0).await.map_err(e)?;
            vec![format!("homing attained, position actual value {at}")]
        }
        DriveCommand::Stream { kind, from, to, step, period_ms } => {
            if step == 0 || period_ms == 0 {
                return Err("--step and --period-ms must be above 0".into());
            }
            let step = i64::from(step) * if to >= from { 1 } else { -1 };
            let n = (i64::from(to) - i64::from(from)) / step;
            let points = (0..=n).map(|k| (i64::from(from) + k * step) as i32);
            let kind = match kind {
                CyclicArg::Position => Cyclic::Position,
                CyclicArg::Velocity => Cyclic::Velocity,
            };
            let sent = d.stream(kind, Duration::from_millis(period_ms), points).await.map_err(e)?;
            vec![format!("{sent} set-point(s) sent")]
        }
    })
}
