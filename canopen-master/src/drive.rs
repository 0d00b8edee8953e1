//! CiA 402 drives from the master: [`Master::drive`] gives a [`Drive402`] handle that walks the power
//! state machine (enable, disable, quick stop, fault reset), sets the mode of operation, moves in profile
//! position and awaits target reached, runs profile velocity and homing, and streams cyclic synchronous
//! set-points at SYNC.
//!
//! Everything but the stream goes through SDO (6040h written, 6041h read back every [`POLL`]), so it
//! works with any PDO mapping the drive has; the stream uses the drive's default RPDO3 (6040h + 607Ah,
//! 400h + node) or RPDO4 (6040h + 60FFh, 500h + node) and a SYNC after each (`canopen_cia402::pdo`). The
//! state machine, the controlword commands and the statusword bits are `canopen-cia402`'s, the same the
//! device side runs, written from public descriptions of IEC 61800-7-201 (python canopen's `p402.py`
//! among them; see that crate's docs).

use std::time::Duration;

use canopen_cia402::state::{cw, sw};
use canopen_cia402::{Mode, State};
use canopen_core::CanFrame;

use crate::{node_id, Error, Master};

/// How often a wait reads the statusword again.
///
/// ```
/// assert!(canopen_master::drive::POLL.as_millis() > 0);
/// ```
pub const POLL: Duration = Duration::from_millis(5);
/// How long a state change may take before [`Drive402`] gives up (each step of a path).
///
/// ```
/// assert!(canopen_master::drive::STATE_TIMEOUT >= canopen_master::drive::POLL);
/// ```
pub const STATE_TIMEOUT: Duration = Duration::from_millis(500);

/// The controlword command that leads from `from` one step toward `to` (the standard's table, the way
/// python canopen's `BaseNode402` walks it): `None` when `from` is `to`, or when only the drive can leave
/// `from` (Not ready to switch on, Fault reaction active) or no command reaches `to` (those two and Fault).
///
/// ```
/// use canopen_cia402::State;
/// use canopen_master::drive::next_command;
/// assert_eq!(next_command(State::SwitchOnDisabled, State::OperationEnabled), Some(0x06));
/// assert_eq!(next_command(State::Fault, State::OperationEnabled), Some(0x80));
/// assert_eq!(next_command(State::OperationEnabled, State::QuickStopActive), Some(0x02));
/// ```
pub fn next_command(from: State, to: State) -> Option<u16> {
    use State as S;
    if from == to || matches!(to, S::NotReadyToSwitchOn | S::FaultReactionActive | S::Fault) {
        return None;
    }
    Some(match (from, to) {
        (S::NotReadyToSwitchOn | S::FaultReactionActive, _) => return None,
        (S::Fault, _) => 0x80,
        (_, S::SwitchOnDisabled) => 0x00,
        (S::OperationEnabled, S::QuickStopActive) => 0x02,
        (S::QuickStopActive, S::OperationEnabled) => 0x0F,
        (S::QuickStopActive, _) => 0x00,
        (_, S::QuickStopActive) => return next_command(from, S::OperationEnabled),
        (S::SwitchOnDisabled, _) => 0x06,
        (S::ReadyToSwitchOn, S::SwitchedOn | S::OperationEnabled) => 0x07,
        (S::SwitchedOn | S::OperationEnabled, S::ReadyToSwitchOn) => 0x06,
        (S::SwitchedOn, S::OperationEnabled) => 0x0F,
        (S::OperationEnabled, S::SwitchedOn) => 0x07,
        _ => return None,
    })
}

/// Which set-point a cyclic stream carries.
///
/// ```
/// let _ = canopen_master::drive::Cyclic::Position;
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cyclic {
    /// Cyclic synchronous position: 607Ah in RPDO3 (400h + node).
    Position,
    /// Cyclic synchronous velocity: 60FFh in RPDO4 (500h + node).
    Velocity,
}

/// A CiA 402 drive on the bus ([`Master::drive`]). Cheap to clone.
///
/// ```no_run
/// # async fn demo() -> Result<(), canopen_master::Error> {
/// use canopen_cia402::Mode;
/// let master = canopen_master::Master::open("vcan0")?;
/// let drive = master.drive(6)?;
/// drive.set_mode(Mode::ProfilePosition).await?;
/// drive.enable().await?;
/// drive.move_to(10_000, false, std::time::Duration::from_secs(5)).await?;
/// # Ok(()) }
/// ```
#[derive(Clone)]
pub struct Drive402 {
    master: Master,
    node: u8,
}

impl Master {
    /// A handle on the CiA 402 drive `node`.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// assert!(m.drive(6).is_ok());
    /// assert!(m.drive(0).is_err());
    /// # });
    /// ```
    pub fn drive(&self, node: u8) -> Result<Drive402, Error> {
        node_id(node)?;
        Ok(Drive402 { master: self.clone(), node })
    }
}

impl Drive402 {
    /// 6041h statusword.
    ///
    /// ```no_run
    /// # async fn demo(d: canopen_master::Drive402) -> Result<(), canopen_master::Error> {
    /// let word = d.statusword().await?;
    /// # Ok(()) }
    /// ```
    pub async fn statusword(&self) -> Result<u16, Error> {
        self.master.read(self.node, 0x6041, 0).await
    }

    /// The state the statusword tells.
    ///
    /// ```no_run
    /// # async fn demo(d: canopen_master::Drive402) -> Result<(), canopen_master::Error> {
    /// let state = d.state().await?;
    /// # Ok(()) }
    /// ```
    pub async fn state(&self) -> Result<State, Error> {
        let word = self.statusword().await?;
        State::from_statusword(word).ok_or_else(|| Error::Protocol(format!("statusword {word:04X}h is no state")))
    }

    /// Writes 6040h controlword.
    ///
    /// ```no_run
    /// # async fn demo(d: canopen_master::Drive402) -> Result<(), canopen_master::Error> {
    /// d.controlword(0x06).await?; // shutdown
    /// # Ok(()) }
    /// ```
    pub async fn controlword(&self, word: u16) -> Result<(), Error> {
        self.master.write(self.node, 0x6040, 0, word).await
    }

    /// Reads the statusword until `done` says so, or fails with [`Error::Timeout`] after `timeout`; returns
    /// the last statusword.
    ///
    /// ```no_run
    /// # async fn demo(d: canopen_master::Drive402) -> Result<(), canopen_master::Error> {
    /// d.wait_status(std::time::Duration::from_secs(1), |w| w & 0x0400 != 0).await?;
    /// # Ok(()) }
    /// ```
    pub async fn wait_status(&self, timeout: Duration, done: impl Fn(u16) -> bool) -> Result<u16, Error> {
        let end = tokio::time::Instant::now() + timeout;
        loop {
            let word = self.statusword().await?;
            if done(word) {
                return Ok(word);
            }
            if tokio::time::Instant::now() >= end {
                return Err(Error::Timeout);
            }
            tokio::time::sleep(POLL).await;
        }
    }

    /// Walks the state machine to `target` one commanded transition at a time, each confirmed by the
    /// statusword. Fault, Fault reaction active and Not ready to switch on cannot be commanded
    /// ([`Error::InvalidArgument`]); a drive that enters Fault on the way ends the walk with
    /// [`Error::Protocol`].
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// let d = m.drive(6).unwrap();
    /// assert!(d.go_to(canopen_cia402::State::Fault).await.is_err());
    /// # });
    /// ```
    pub async fn go_to(&self, target: State) -> Result<(), Error> {
        if matches!(target, State::Fault | State::FaultReactionActive | State::NotReadyToSwitchOn) {
            return Err(Error::InvalidArgument(format!("{} cannot be commanded", target.name())));
        }
        for _ in 0..8 {
            let now = self.state().await?;
            if now == target {
                return Ok(());
            }
            let Some(word) = next_command(now, target) else {
                // Not ready to switch on or a fault reaction: the drive moves on by itself.
                self.wait_status(STATE_TIMEOUT, |w| State::from_statusword(w) != Some(now)).await?;
                continue;
            };
            if now == State::Fault {
                // Fault reset acts on the rising edge of bit 7.
                self.controlword(0x00).await?;
            }
            self.controlword(word).await?;
            let to = self.wait_status(STATE_TIMEOUT, |w| State::from_statusword(w) != Some(now)).await;
            match to {
                Ok(w) if State::from_statusword(w) == Some(State::Fault) && now != State::Fault => {
                    return Err(Error::Protocol(format!("the drive entered Fault on the way to {}", target.name())))
                }
                Ok(_) => {}
                Err(Error::Timeout) => {
                    return Err(Error::Protocol(format!(
                        "controlword {word:02X}h did not leave {} (on the way to {})",
                        now.name(),
                        target.name()
                    )))
                }
                Err(e) => return Err(e),
            }
        }
        Err(Error::Protocol(format!("{} not reached", target.name())))
    }

    /// To Operation enabled (from Fault too: the fault is reset first).
    ///
    /// ```no_run
    /// # async fn demo(d: canopen_master::Drive402) -> Result<(), canopen_master::Error> {
    /// d.enable().await?;
    /// # Ok(()) }
    /// ```
    pub async fn enable(&self) -> Result<(), Error> {
        self.go_to(State::OperationEnabled).await
    }

    /// To Switch on disabled (disable voltage).
    ///
    /// ```no_run
    /// # async fn demo(d: canopen_master::Drive402) -> Result<(), canopen_master::Error> {
    /// d.disable().await?;
    /// # Ok(()) }
    /// ```
    pub async fn disable(&self) -> Result<(), Error> {
        self.go_to(State::SwitchOnDisabled).await
    }

    /// Quick stop (controlword 02h) from Operation enabled; returns the state the drive then settles in
    /// (Quick stop active, or Switch on disabled with quick stop option codes 0–2).
    ///
    /// ```no_run
    /// # async fn demo(d: canopen_master::Drive402) -> Result<(), canopen_master::Error> {
    /// let settled = d.quick_stop().await?;
    /// # Ok(()) }
    /// ```
    pub async fn quick_stop(&self) -> Result<State, Error> {
        self.controlword(0x02).await?;
        let w = self
            .wait_status(STATE_TIMEOUT * 4, |w| {
                matches!(State::from_statusword(w), Some(State::QuickStopActive | State::SwitchOnDisabled))
                    && w & sw::TARGET_REACHED != 0
                    || State::from_statusword(w) == Some(State::SwitchOnDisabled)
            })
            .await?;
        State::from_statusword(w).ok_or_else(|| Error::Protocol(format!("statusword {w:04X}h is no state")))
    }

    /// Fault reset: from Fault to Switch on disabled. Fails with [`Error::Protocol`] when the drive stays in
    /// Fault (the cause is still there).
    ///
    /// ```no_run
    /// # async fn demo(d: canopen_master::Drive402) -> Result<(), canopen_master::Error> {
    /// d.fault_reset().await?;
    /// # Ok(()) }
    /// ```
    pub async fn fault_reset(&self) -> Result<(), Error> {
        self.go_to(State::SwitchOnDisabled).await
    }

    /// 6060h modes of operation, confirmed by 6061h.
    ///
    /// ```no_run
    /// # async fn demo(d: canopen_master::Drive402) -> Result<(), canopen_master::Error> {
    /// d.set_mode(canopen_cia402::Mode::ProfileVelocity).await?;
    /// # Ok(()) }
    /// ```
    pub async fn set_mode(&self, mode: Mode) -> Result<(), Error> {
        self.master.write(self.node, 0x6060, 0, mode.code()).await?;
        let end = tokio::time::Instant::now() + STATE_TIMEOUT;
        loop {
            let shown: i8 = self.master.read(self.node, 0x6061, 0).await?;
            if shown == mode.code() {
                return Ok(());
            }
            if tokio::time::Instant::now() >= end {
                return Err(Error::Protocol(format!("6061h shows {shown}, not {}", mode.code())));
            }
            tokio::time::sleep(POLL).await;
        }
    }

    /// Profile position: 607Ah = `target` (relative to the last target with `relative`), the set-point
    /// handshake (bit 4 up, acknowledge bit 12, bit 4 down), then waits up to `timeout` for target reached
    /// (bit 10). The drive must be in profile position and Operation enabled. Returns 6064h at the end.
    ///
    /// ```no_run
    /// # async fn demo(d: canopen_master::Drive402) -> Result<(), canopen_master::Error> {
    /// let at = d.move_to(1_000, true, std::time::Duration::from_secs(5)).await?;
    /// # Ok(()) }
    /// ```
    pub async fn move_to(&self, target: i32, relative: bool, timeout: Duration) -> Result<i32, Error> {
        self.master.write(self.node, 0x607A, 0, target).await?;
        let base = 0x0F | if relative { cw::RELATIVE } else { 0 } | cw::CHANGE_SET_IMMEDIATELY;
        self.controlword(base | cw::NEW_SET_POINT).await?;
        self.wait_status(STATE_TIMEOUT, |w| w & sw::OMS_12 != 0 || w & 0x6F != 0x27).await?;
        self.controlword(base).await?;
        let w = self
            .wait_status(timeout, |w| (w & sw::TARGET_REACHED != 0 && w & sw::OMS_12 == 0) || w & 0x6F != 0x27)
            .await?;
        if w & 0x6F != 0x27 {
            return Err(Error::Protocol(format!("the drive left Operation enabled (statusword {w:04X}h)")));
        }
        self.master.read(self.node, 0x6064, 0).await
    }

    /// Profile velocity: 60FFh = `velocity`; waits up to `timeout` for target reached (the velocity is
    /// reached). The drive must be in profile velocity and Operation enabled.
    ///
    /// ```no_run
    /// # async fn demo(d: canopen_master::Drive402) -> Result<(), canopen_master::Error> {
    /// d.velocity(2_000, std::time::Duration::from_secs(1)).await?;
    /// # Ok(()) }
    /// ```
    pub async fn velocity(&self, velocity: i32, timeout: Duration) -> Result<(), Error> {
        self.master.write(self.node, 0x60FF, 0, velocity).await?;
        tokio::time::sleep(POLL).await;
        self.wait_status(timeout, |w| w & sw::TARGET_REACHED != 0).await.map(|_| ())
    }

    /// Homing with `method` (6098h; `None` keeps the drive's): the drive must be in homing mode and
    /// Operation enabled. Starts it (bit 4), waits up to `timeout` for homing attained and target reached
    /// (bits 12 and 10); a homing error (bit 13) or an interruption is [`Error::Protocol`].
    ///
    /// ```no_run
    /// # async fn demo(d: canopen_master::Drive402) -> Result<(), canopen_master::Error> {
    /// d.home(Some(37), std::time::Duration::from_secs(30)).await?;
    /// # Ok(()) }
    /// ```
    pub async fn home(&self, method: Option<i8>, timeout: Duration) -> Result<(), Error> {
        if let Some(m) = method {
            self.master.write(self.node, 0x6098, 0, m).await?;
        }
        self.controlword(0x0F).await?;
        self.controlword(0x0F | cw::NEW_SET_POINT).await?;
        let w = self
            .wait_status(timeout, |w| {
                let bits = w & 0x3400;
                bits == 0x1400 || bits & 0x2000 != 0 || bits == 0x0400 || w & 0x6F != 0x27
            })
            .await?;
        self.controlword(0x0F).await?;
        match w & 0x3400 {
            0x1400 if w & 0x6F == 0x27 => Ok(()),
            0x0400 => Err(Error::Protocol("homing interrupted".into())),
            _ => Err(Error::Protocol(format!("homing failed (statusword {w:04X}h)"))),
        }
    }

    /// Cyclic synchronous set-points: for each of `points`, one RPDO (RPDO3 with 6040h = 0Fh and 607Ah for
    /// [`Cyclic::Position`], RPDO4 with 60FFh for [`Cyclic::Velocity`]) then a SYNC, every `period`. The
    /// drive must be Operational (NMT), in the matching mode and Operation enabled, with its default
    /// RPDO3/RPDO4. Returns how many set-points went out.
    ///
    /// ```no_run
    /// # async fn demo(d: canopen_master::Drive402) -> Result<(), canopen_master::Error> {
    /// use canopen_master::drive::Cyclic;
    /// d.stream(Cyclic::Position, std::time::Duration::from_millis(2), (0..1000).map(|k| k * 10)).await?;
    /// # Ok(()) }
    /// ```
    pub async fn stream(
        &self,
        kind: Cyclic,
        period: Duration,
        points: impl IntoIterator<Item = i32>,
    ) -> Result<usize, Error> {
        if period.is_zero() {
            return Err(Error::InvalidArgument("a SYNC period of 0".into()));
        }
        let cob = u16::from(self.node) + if kind == Cyclic::Position { 0x400 } else { 0x500 };
        let sync = CanFrame::from_parts(0x80, [0; 8], 0);
        let mut tick = tokio::time::interval(period);
        tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
        let mut sent = 0;
        for p in points {
            tick.tick().await;
            let v = p.to_le_bytes();
            let rpdo = CanFrame::from_parts(cob, [0x0F, 0x00, v[0], v[1], v[2], v[3], 0, 0], 6);
            self.master.send(&rpdo).await?;
            self.master.send(&sync).await?;
            sent += 1;
        }
        Ok(sent)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// From every state, following `next_command` through the device's own table reaches every
    /// commandable target within 4 steps.
    #[test]
    fn every_commandable_state_is_reached_through_the_table() {
        for from in State::ALL {
            for to in [
                State::SwitchOnDisabled,
                State::ReadyToSwitchOn,
                State::SwitchedOn,
                State::OperationEnabled,
                State::QuickStopActive,
            ] {
                let mut s = from;
                for _ in 0..5 {
                    let Some(word) = next_command(s, to) else { break };
                    let next = if s == State::Fault {
                        State::SwitchOnDisabled
                    } else {
                        let c = canopen_cia402::Command::decode(word);
                        canopen_cia402::transition(s, c, true).map(|t| t.1).unwrap_or(s)
                    };
                    assert_ne!(next, s, "{word:02X}h does not leave {s:?} toward {to:?}");
                    s = next;
                }
                let by_itself = matches!(from, State::NotReadyToSwitchOn | State::FaultReactionActive);
                assert!(s == to || by_itself, "{from:?} -> {to:?} stopped at {s:?}");
            }
        }
    }
}
