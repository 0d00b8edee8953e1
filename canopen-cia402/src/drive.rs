//! The device: the state machine of [`state`](crate::state) run against the controlword, the option
//! codes' stop ramps, the modes of operation, the fault reaction and the statusword, one cycle at a time
//! (sans-IO: the caller passes the cycle time and the [`Motor`]; no clock, no allocation).
//!
//! Call [`Drive::cycle`] periodically (the motion cycle, e.g. every 1 ms) and after the controlword, the
//! mode or a target changed (an RPDO or an SDO write), and [`Drive::sync`] at each SYNC for the cyclic
//! synchronous modes. On a node, [`cycle_node`] does both halves: the cycle, then the EMCY a fault raises
//! or a fault reset clears, then the event-driven TPDOs whose data changed.

use canopen_core::node::NodeSizes;
use canopen_core::od::ObjectDictionary;
use canopen_core::storage::Storage;
use canopen_core::Node;

use crate::homing::{Homing, HomingMethod};
use crate::motor::{Demand, Motor};
use crate::objects::Objects;
use crate::ramp::Ramp;
use crate::state::{cw, sw, transition, Command, State};
use crate::{Mode, Stop};

/// EMCY error code of a following error (CiA 301 Table 21: 8611h "following error").
pub const FOLLOWING_ERROR: u16 = 0x8611;

/// A transition the last cycle took: its number in the standard's table, from, to.
pub type Transition = (u8, State, State);

/// What one cycle did that the node must know.
///
/// ```
/// let c = canopen_cia402::Cycle::default();
/// assert_eq!(c.transitions().count(), 0);
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Cycle {
    list: [Option<Transition>; 4],
    /// A fault was raised with this error code (603Fh; the node raises it: 1001h, 1003h, EMCY).
    pub raised: Option<u16>,
    /// The fault with this error code was reset (the node clears it: EMCY 0000h when none is left).
    pub cleared: Option<u16>,
}

impl Cycle {
    /// The transitions taken, in order (at most four: a fault reaction ending in the same cycle, 3 + 4, ...).
    ///
    /// ```
    /// assert!(canopen_cia402::Cycle::default().transitions().next().is_none());
    /// ```
    pub fn transitions(&self) -> impl Iterator<Item = Transition> + '_ {
        self.list.iter().flatten().copied()
    }

    fn push(&mut self, t: Transition) {
        if let Some(slot) = self.list.iter_mut().find(|s| s.is_none()) {
            *slot = Some(t);
        }
    }
}

/// State of the profile position mode: the set-point handshake and the move.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
struct ProfilePosition {
    /// The set-point being moved to.
    target: i32,
    /// A set-point accepted while a move ran (bit 5 = 0): it starts when the move ends.
    pending: Option<i32>,
    /// Statusword bit 12: the set-point was taken; cleared when bit 4 falls and the buffer has room.
    ack: bool,
    /// A move runs.
    moving: bool,
}

/// One axis of a CiA 402 drive: its [`Objects`], the application's own dictionary `A` (the node sees both
/// as one dictionary: 6000h–67FFh here, every other index the application's) and the state machine.
///
/// ```
/// use canopen_cia402::{Demand, Drive, Motor, State};
/// use canopen_core::od::NoApplication;
/// # #[derive(Default)] struct Ideal { pos: i32, vel: i32 }
/// # impl Motor for Ideal {
/// #     fn set_power(&mut self, _on: bool) {}
/// #     fn follow(&mut self, d: Demand, _dt: u32) {
/// #         if let Demand::Position { position, velocity } = d { (self.pos, self.vel) = (position, velocity) }
/// #     }
/// #     fn position(&self) -> i32 { self.pos }
/// #     fn velocity(&self) -> i32 { self.vel }
/// # }
/// let mut drive = Drive::new(NoApplication);
/// let mut motor = Ideal::default();
/// drive.cycle(&mut motor, 1000); // transition 1: Switch on disabled
/// for cw in [0x06, 0x07, 0x0F] {
///     drive.objects.controlword = cw;
///     drive.cycle(&mut motor, 1000);
/// }
/// assert_eq!(drive.state(), State::OperationEnabled);
/// assert_eq!(drive.objects.statusword & 0x6F, 0x27);
/// ```
#[derive(Debug, Clone)]
pub struct Drive<A> {
    /// The drive's objects (6000h–67FFh).
    pub objects: Objects,
    /// The application's dictionary (every other index).
    pub app: A,
    state: State,
    mode: Mode,
    ramp: Ramp,
    /// Added to the motor's raw position to give 6064h (set by homing).
    offset: i64,
    pp: ProfilePosition,
    homing: Homing,
    /// The set-point the last SYNC latched (csp: position, csv: velocity) and the one before it.
    cs_target: i32,
    cs_previous: i32,
    /// µs since the last SYNC: the velocity feed-forward holds for one interpolation period only.
    since_sync: i64,
    /// The fault being handled (603Fh), until a reset succeeds.
    fault: Option<u16>,
    /// A fault the application raised ([`Drive::raise_fault`]), taken at the next cycle.
    raised: Option<u16>,
    /// Statusword bit 11 in the last cycle.
    limited: bool,
}

impl<A> Drive<A> {
    /// A drive at power-on (Not ready to switch on) with its objects at their defaults, composed with the
    /// application's dictionary `app`.
    ///
    /// ```
    /// let d = canopen_cia402::Drive::new(canopen_core::od::NoApplication);
    /// assert_eq!(d.state(), canopen_cia402::State::NotReadyToSwitchOn);
    /// ```
    pub fn new(app: A) -> Self {
        Drive {
            objects: Objects::new(),
            app,
            state: State::NotReadyToSwitchOn,
            mode: Mode::NoMode,
            ramp: Ramp::default(),
            offset: 0,
            pp: ProfilePosition::default(),
            homing: Homing::Idle,
            cs_target: 0,
            cs_previous: 0,
            since_sync: 0,
            fault: None,
            raised: None,
            limited: false,
        }
    }

    /// The state of the power drive system.
    ///
    /// ```
    /// let d = canopen_cia402::Drive::new(());
    /// assert_eq!(d.state(), canopen_cia402::State::NotReadyToSwitchOn);
    /// ```
    pub fn state(&self) -> State {
        self.state
    }

    /// The mode that runs (6061h).
    ///
    /// ```
    /// assert_eq!(canopen_cia402::Drive::new(()).mode(), canopen_cia402::Mode::NoMode);
    /// ```
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// Where homing is.
    ///
    /// ```
    /// assert_eq!(canopen_cia402::Drive::new(()).homing(), canopen_cia402::Homing::Idle);
    /// ```
    pub fn homing(&self) -> Homing {
        self.homing
    }

    /// Raises a fault the application detected (e.g. an over-temperature it measured): the next cycle
    /// takes transition 13 with this error code. A fault the [`Motor`] reports needs no call.
    ///
    /// ```
    /// let mut d = canopen_cia402::Drive::new(());
    /// d.raise_fault(0x4210);
    /// ```
    pub fn raise_fault(&mut self, code: u16) {
        self.raised = Some(code);
    }

    /// At a SYNC: the cyclic synchronous modes take their set-point (607Ah in csp, 60FFh in csv).
    ///
    /// ```
    /// let mut d = canopen_cia402::Drive::new(());
    /// d.sync(); // nothing to take outside csp/csv
    /// ```
    pub fn sync(&mut self) {
        self.since_sync = 0;
        self.cs_previous = self.cs_target;
        self.cs_target = match self.mode {
            Mode::CyclicSyncPosition => self.objects.target_position,
            Mode::CyclicSyncVelocity => self.objects.target_velocity,
            _ => return,
        };
    }

    /// The interpolation period 60C2h in µs (value × 10^index s), at least 1.
    fn period_us(&self) -> i64 {
        let mut us = i64::from(self.objects.interpolation_period_value);
        let exp = 6 + i32::from(self.objects.interpolation_period_index.clamp(-6, 0));
        for _ in 0..exp {
            us = us.saturating_mul(10);
        }
        us.max(1)
    }

    /// One cycle of `dt_us` µs: the controlword's command, the option codes' ramps, the fault reaction,
    /// the running mode's demand to `motor`, and the statusword and actual values.
    ///
    /// ```
    /// # use canopen_cia402::{Demand, Drive, Motor};
    /// # struct Still;
    /// # impl Motor for Still {
    /// #     fn set_power(&mut self, _on: bool) {}
    /// #     fn follow(&mut self, _d: Demand, _dt: u32) {}
    /// #     fn position(&self) -> i32 { 0 }
    /// #     fn velocity(&self) -> i32 { 0 }
    /// # }
    /// let mut d = Drive::new(());
    /// let c = d.cycle(&mut Still, 1000);
    /// assert_eq!(c.transitions().next().map(|t| t.0), Some(1));
    /// ```
    pub fn cycle<M: Motor + ?Sized>(&mut self, motor: &mut M, dt_us: u32) -> Cycle {
        let mut out = Cycle::default();
        let rising = self.objects.take_rising();
        let word = self.objects.controlword;
        let actual = i64::from(motor.position()) + self.offset;

        // Faults first (transition 13): the motor's, the application's, a following error.
        let fault = self.raised.take().or_else(|| motor.fault()).or_else(|| self.following_error(actual));
        if let Some(code) = fault {
            if self.fault.is_none() {
                self.fault = Some(code);
                self.objects.error_code = code;
                out.raised = Some(code);
                let from = self.state;
                self.go(&mut out, 13, from, State::FaultReactionActive);
            }
        }

        match self.state {
            State::NotReadyToSwitchOn => {
                if motor.ready() {
                    self.go(&mut out, 1, State::NotReadyToSwitchOn, State::SwitchOnDisabled);
                }
            }
            State::Fault => {
                if rising & cw::FAULT_RESET != 0 && motor.fault().is_none() {
                    out.cleared = self.fault.take();
                    self.objects.error_code = 0;
                    self.go(&mut out, 15, State::Fault, State::SwitchOnDisabled);
                }
            }
            State::FaultReactionActive => {}
            state => self.command(&mut out, state, Command::decode(word)),
        }

        // Modes change only where no motion runs from the old one's set-points.
        let wanted = Mode::from_code(self.objects.modes_of_operation).unwrap_or(self.mode);
        if wanted != self.mode {
            self.enter_mode(wanted, actual);
        }

        // The demand for this cycle.
        if self.state.power_applied() {
            self.motion(&mut out, motor, rising, word, actual, dt_us);
        } else {
            // Power off: the demand follows the axis, so enabling never jumps.
            self.ramp = Ramp::at(sat(actual), motor.velocity());
            self.pp.moving = false;
            self.pp.pending = None;
            if self.homing.running() {
                self.homing = Homing::Error;
            }
        }
        let power = self.state.power_applied();
        motor.set_power(power);
        motor.set_brake(!power);
        let demand = if !power {
            Demand::Off
        } else if matches!(self.mode, Mode::ProfileVelocity | Mode::CyclicSyncVelocity) {
            Demand::Velocity(self.ramp.velocity())
        } else {
            let raw = i64::from(self.ramp.position()) - self.offset;
            Demand::Position { position: sat(raw), velocity: self.ramp.velocity() }
        };
        motor.follow(demand, dt_us);
        self.report(motor, word);
        out
    }

    fn go(&mut self, out: &mut Cycle, n: u8, from: State, to: State) {
        out.push((n, from, to));
        self.state = to;
    }

    /// A command in a state that obeys the controlword (not Not ready, Fault reaction active, Fault).
    fn command(&mut self, out: &mut Cycle, state: State, command: Command) {
        let quick = Stop::quick_stop(self.objects.quick_stop_option).unwrap_or((Stop::QuickStopRamp, false));
        let Some((n, to)) = transition(state, command, quick.1) else { return };
        // Transitions 5 and 8 wait for the stop ramp their option code (605Ch, 605Bh) asks for;
        // `motion` takes them when the axis stands.
        let ramped = match n {
            5 => Stop::shutdown(self.objects.disable_operation_option) == Some(Stop::SlowDownRamp),
            8 => Stop::shutdown(self.objects.shutdown_option) == Some(Stop::SlowDownRamp),
            _ => false,
        };
        if ramped && self.ramp.velocity() != 0 {
            return;
        }
        self.go(out, n, state, to);
        // Switch on + enable operation from Ready to switch on: 3 then 4.
        if n == 3 && command == Command::EnableOperation {
            self.go(out, 4, State::SwitchedOn, State::OperationEnabled);
        }
        if matches!(n, 4 | 16) {
            self.pp.ack = false;
        }
    }

    fn enter_mode(&mut self, mode: Mode, actual: i64) {
        self.mode = mode;
        self.objects.modes_of_operation_display = mode.code();
        self.pp = ProfilePosition { target: sat(actual), ..ProfilePosition::default() };
        if self.homing.running() {
            self.homing = Homing::Error;
        }
        self.cs_target = match mode {
            Mode::CyclicSyncPosition => self.ramp.position(),
            _ => 0,
        };
        self.cs_previous = self.cs_target;
    }

    fn following_error(&self, actual: i64) -> Option<u16> {
        let window = self.objects.following_error_window;
        let position_mode = matches!(self.mode, Mode::ProfilePosition | Mode::CyclicSyncPosition | Mode::Homing);
        let err = (i64::from(self.ramp.position()) - actual).unsigned_abs();
        (window != u32::MAX && self.state == State::OperationEnabled && position_mode && err > u64::from(window))
            .then_some(FOLLOWING_ERROR)
    }

    /// The demand while power is applied: the stop ramps of the states and option codes, else the mode.
    fn motion<M: Motor + ?Sized>(
        &mut self,
        out: &mut Cycle,
        motor: &mut M,
        rising: u16,
        word: u16,
        actual: i64,
        dt: u32,
    ) {
        let o = &self.objects;
        let ramp_of = |stop: Stop| match stop {
            Stop::SlowDownRamp => o.profile_deceleration,
            Stop::QuickStopRamp | Stop::Coast => o.quick_stop_deceleration,
        };
        match self.state {
            State::FaultReactionActive => {
                let stop = Stop::fault_reaction(o.fault_reaction_option).unwrap_or(Stop::QuickStopRamp);
                if stop == Stop::Coast || self.ramp.stop_step(ramp_of(stop), dt) {
                    self.go(out, 14, State::FaultReactionActive, State::Fault);
                }
                return;
            }
            State::QuickStopActive => {
                let (stop, stays) = Stop::quick_stop(o.quick_stop_option).unwrap_or((Stop::QuickStopRamp, false));
                if (stop == Stop::Coast || self.ramp.stop_step(ramp_of(stop), dt)) && !stays {
                    self.go(out, 12, State::QuickStopActive, State::SwitchOnDisabled);
                }
                return;
            }
            _ => {}
        }
        // Operation enabled. A disable operation or shutdown waiting for its slow-down ramp.
        let command = Command::decode(word);
        let waiting = (command == Command::SwitchOn
            && Stop::shutdown(o.disable_operation_option) == Some(Stop::SlowDownRamp))
            || (command == Command::Shutdown && Stop::shutdown(o.shutdown_option) == Some(Stop::SlowDownRamp));
        if waiting {
            if self.ramp.stop_step(o.profile_deceleration, dt) {
                self.command(out, State::OperationEnabled, command);
            }
            return;
        }
        if word & cw::HALT != 0 {
            let stop = Stop::halt(o.halt_option).unwrap_or(Stop::SlowDownRamp);
            self.ramp.stop_step(ramp_of(stop), dt);
            if self.homing.running() {
                self.homing = Homing::Interrupted;
            }
            return;
        }
        match self.mode {
            Mode::NoMode => {
                self.ramp.stop_step(o.quick_stop_deceleration, dt);
            }
            Mode::ProfilePosition => self.profile_position(rising, word, dt),
            Mode::ProfileVelocity => {
                let (a, d) = (o.profile_acceleration, o.profile_deceleration);
                self.ramp.velocity_step(o.target_velocity, a, d, dt);
            }
            Mode::Homing => self.homing_step(motor, rising, actual, dt),
            Mode::CyclicSyncPosition => {
                let target = self.limit(self.cs_target);
                let period = self.period_us();
                self.since_sync = self.since_sync.saturating_add(i64::from(dt));
                // The set-points' own speed, while they come (a SYNC missed for a whole period: none).
                let velocity = if self.since_sync <= period {
                    (i64::from(target) - i64::from(self.cs_previous)) * 1_000_000 / period
                } else {
                    0
                };
                self.ramp = Ramp::at(target, sat(velocity));
            }
            Mode::CyclicSyncVelocity => {
                let here = self.ramp.position();
                self.ramp = Ramp::at(here, self.cs_target);
                self.ramp.velocity_step(self.cs_target, u32::MAX, u32::MAX, dt);
            }
        }
    }

    /// The software position limits 607Dh (both 0: none), applied to a position set-point.
    fn limit(&mut self, target: i32) -> i32 {
        let [min, max] = self.objects.software_position_limit;
        if min == 0 && max == 0 {
            return target;
        }
        let limited = target.clamp(min, max.max(min));
        self.limited |= limited != target;
        limited
    }

    fn profile_position(&mut self, rising: u16, word: u16, dt: u32) {
        let pp = self.pp;
        // Bit 4 fell: the master saw the acknowledge; room again unless a set-point waits.
        if word & cw::NEW_SET_POINT == 0 && pp.pending.is_none() {
            self.pp.ack = false;
        }
        if rising & cw::NEW_SET_POINT != 0 && !self.pp.ack {
            let base = if pp.moving || pp.pending.is_some() { pp.pending.unwrap_or(pp.target) } else { pp.target };
            let wanted = if word & cw::RELATIVE != 0 {
                sat(i64::from(base) + i64::from(self.objects.target_position))
            } else {
                self.objects.target_position
            };
            let target = self.limit(wanted);
            self.pp.ack = true;
            if pp.moving && word & cw::CHANGE_SET_IMMEDIATELY == 0 {
                self.pp.pending = Some(target);
            } else {
                self.pp.target = target;
                self.pp.moving = true;
            }
        }
        if self.pp.moving {
            let o = &self.objects;
            let (v, a, d) = (o.profile_velocity, o.profile_acceleration, o.profile_deceleration);
            if self.ramp.position_step(self.pp.target, v, a, d, dt) {
                self.pp.moving = false;
                if let Some(next) = self.pp.pending.take() {
                    self.pp.target = next;
                    self.pp.moving = true;
                }
            }
        } else {
            let here = self.ramp.position();
            self.ramp.position_step(here, 0, 1, self.objects.quick_stop_deceleration, dt);
        }
    }

    fn homing_step<M: Motor + ?Sized>(&mut self, motor: &mut M, rising: u16, actual: i64, dt: u32) {
        let o = &self.objects;
        let method = HomingMethod::from_code(o.homing_method);
        if rising & cw::NEW_SET_POINT != 0 && !self.homing.running() {
            self.homing = match method {
                Some(HomingMethod::CurrentPosition) => {
                    self.set_home(actual);
                    Homing::Attained
                }
                Some(_) => Homing::InProgress,
                None => Homing::Error,
            };
        }
        let o = &self.objects;
        let (fast, slow, acc) = (o.homing_speeds[0], o.homing_speeds[1], o.homing_acceleration);
        let switches = motor.limit_switches();
        let (toward, on_switch) = match method {
            Some(HomingMethod::PositiveLimitSwitch) => (1i64, switches.positive),
            _ => (-1i64, switches.negative),
        };
        match self.homing {
            Homing::InProgress => {
                if on_switch {
                    // Stopped by the switch: the demand restarts from where the axis is.
                    self.ramp = Ramp::at(sat(actual), 0);
                    self.homing = Homing::Leaving;
                } else {
                    self.ramp.velocity_step(sat(toward * i64::from(fast)), acc, acc, dt);
                }
            }
            Homing::Leaving => {
                if on_switch {
                    self.ramp.velocity_step(sat(-toward * i64::from(slow)), acc, acc, dt);
                } else {
                    self.set_home(actual);
                    self.homing = Homing::Attained;
                }
            }
            Homing::Attained => {
                if self.ramp.stop_step(acc, dt) {
                    self.homing = Homing::Completed;
                }
            }
            _ => {
                self.ramp.stop_step(acc, dt);
            }
        }
    }

    /// The axis is at home: 6064h there becomes 607Ch.
    fn set_home(&mut self, actual: i64) {
        let delta = i64::from(self.objects.home_offset) - actual;
        self.offset += delta;
        self.ramp.shift(delta);
        self.pp.target = sat(i64::from(self.pp.target) + delta);
    }

    /// 6041h and the actual and demand values.
    fn report<M: Motor + ?Sized>(&mut self, motor: &M, word: u16) {
        let actual = i64::from(motor.position()) + self.offset;
        let o = &mut self.objects;
        o.position_actual = sat(actual);
        o.velocity_actual = motor.velocity();
        o.position_demand = self.ramp.position();
        o.velocity_demand = self.ramp.velocity();
        let switches = motor.limit_switches();
        let mut status = self.state.statusword_bits() | sw::REMOTE;
        if motor.warning() {
            status |= sw::WARNING;
        }
        if core::mem::take(&mut self.limited) || switches.negative || switches.positive {
            status |= sw::INTERNAL_LIMIT_ACTIVE;
        }
        let halted = word & cw::HALT != 0;
        let standing = self.ramp.velocity() == 0;
        if self.state == State::OperationEnabled {
            status |= match self.mode {
                Mode::NoMode => 0,
                Mode::ProfilePosition => {
                    let near = (actual - i64::from(self.pp.target)).unsigned_abs() <= u64::from(o.position_window);
                    let reached = (!self.pp.moving && near) || (halted && standing);
                    let ack = if self.pp.ack { sw::OMS_12 } else { 0 };
                    (if reached { sw::TARGET_REACHED } else { 0 }) | ack
                }
                Mode::ProfileVelocity => {
                    let reached = if halted { standing } else { self.ramp.velocity() == o.target_velocity };
                    let zero = if motor.velocity() == 0 { sw::OMS_12 } else { 0 };
                    (if reached { sw::TARGET_REACHED } else { 0 }) | zero
                }
                Mode::Homing => {
                    let bits = self.homing.status_bits();
                    // A homing error with the axis still moving: bit 10 low.
                    if self.homing == Homing::Error && !standing {
                        sw::OMS_13
                    } else {
                        bits
                    }
                }
                Mode::CyclicSyncPosition | Mode::CyclicSyncVelocity => {
                    if halted {
                        0
                    } else {
                        sw::OMS_12
                    }
                }
            };
        } else if self.state == State::QuickStopActive && standing {
            status |= sw::TARGET_REACHED;
        }
        o.statusword = status;
    }
}

fn sat(v: i64) -> i32 {
    v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
}

/// One drive cycle on a node: [`Drive::cycle`], then the node raises the fault's error code (1001h,
/// 1003h, an EMCY) or clears it after a fault reset (EMCY 0000h when no error is left), then sends the
/// event-driven TPDOs whose data changed (the statusword, the actual values).
///
/// ```
/// use canopen_cia402::{cycle_node, Demand, Drive, Motor};
/// use canopen_core::{od::NoApplication, profile::NodeConfig, Node, NodeId};
/// # struct Still;
/// # impl Motor for Still {
/// #     fn set_power(&mut self, _on: bool) {}
/// #     fn follow(&mut self, _d: Demand, _dt: u32) {}
/// #     fn position(&self) -> i32 { 0 }
/// #     fn velocity(&self) -> i32 { 0 }
/// #     fn fault(&self) -> Option<u16> { Some(0x2310) }
/// # }
/// let id = NodeId::new(3).unwrap();
/// let mut node: Node<Drive<NoApplication>> = Node::new(id, NodeConfig::DEFAULT, Drive::new(NoApplication));
/// let c = cycle_node(&mut node, &mut Still, 1000);
/// assert_eq!(c.raised, Some(0x2310));
/// assert_eq!(node.app().objects.error_code, 0x2310);
/// ```
pub fn cycle_node<A, Z, S, M>(node: &mut Node<Drive<A>, Z, S>, motor: &mut M, dt_us: u32) -> Cycle
where
    A: ObjectDictionary,
    Z: NodeSizes,
    S: Storage,
    M: Motor + ?Sized,
{
    let c = node.app_mut().cycle(motor, dt_us);
    if let Some(code) = c.cleared {
        node.clear_error(code);
    }
    if let Some(code) = c.raised {
        node.raise_error(code, [0; 5]);
    }
    node.trigger_changed_tpdos();
    c
}
