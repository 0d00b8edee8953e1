//! The application's side of a drive: the power stage, the brake, and a motor that follows the demand
//! [`Drive`](crate::Drive) computes each cycle for the mode that runs.

/// What the motor is asked to do for one cycle.
///
/// ```
/// use canopen_cia402::Demand;
/// let d = Demand::Position { position: 10, velocity: 0 };
/// assert_ne!(d, Demand::Off);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Demand {
    /// The drive function is disabled: no torque (the brake holds when engaged).
    Off,
    /// Follow a position (raw increments of [`Motor::position`]) with this velocity feed-forward (inc/s):
    /// profile position, homing, cyclic synchronous position, and the stop ramps of those modes.
    Position {
        /// The demand position.
        position: i32,
        /// The demand velocity.
        velocity: i32,
    },
    /// Follow a velocity (inc/s): profile velocity, cyclic synchronous velocity and their stop ramps.
    Velocity(i32),
}

/// Both limit switches' inputs.
///
/// ```
/// let l = canopen_cia402::LimitSwitches { negative: true, positive: false };
/// assert!(l.negative);
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LimitSwitches {
    /// The negative limit switch is active.
    pub negative: bool,
    /// The positive limit switch is active.
    pub positive: bool,
}

/// The drive's hardware, as the application provides it.
///
/// ```
/// use canopen_cia402::{Demand, Motor};
/// /// A motor that is exactly where it is told to be.
/// #[derive(Default)]
/// struct Ideal { pos: i32, vel: i32, powered: bool }
/// impl Motor for Ideal {
///     fn set_power(&mut self, on: bool) { self.powered = on; }
///     fn follow(&mut self, demand: Demand, _dt_us: u32) {
///         match demand {
///             Demand::Off => self.vel = 0,
///             Demand::Position { position, velocity } => (self.pos, self.vel) = (position, velocity),
///             Demand::Velocity(v) => self.vel = v,
///         }
///     }
///     fn position(&self) -> i32 { self.pos }
///     fn velocity(&self) -> i32 { self.vel }
/// }
/// let mut m = Ideal::default();
/// m.follow(Demand::Position { position: 5, velocity: 0 }, 1000);
/// assert_eq!(m.position(), 5);
/// ```
pub trait Motor {
    /// Power to the motor on (Operation enabled, Quick stop active, a ramped fault reaction) or off.
    fn set_power(&mut self, on: bool);
    /// The holding brake: engaged whenever the power is off. Default: no brake.
    fn set_brake(&mut self, _engaged: bool) {}
    /// Follow `demand` for the next `dt_us` µs (called every cycle, [`Demand::Off`] while the power is
    /// off). What a mode does each cycle reaches the hardware here.
    fn follow(&mut self, demand: Demand, dt_us: u32);
    /// The position actual value, raw increments (before the home offset).
    fn position(&self) -> i32;
    /// The velocity actual value, inc/s.
    fn velocity(&self) -> i32;
    /// The limit switches (homing methods 17/18, statusword bit 11). Default: none active.
    fn limit_switches(&self) -> LimitSwitches {
        LimitSwitches::default()
    }
    /// A fault the hardware detects, as its error code (603Fh, the EMCY): over-current, over-temperature,
    /// ... `None` when there is none (a fault reset succeeds only then). Default: none.
    fn fault(&self) -> Option<u16> {
        None
    }
    /// A warning (statusword bit 7). Default: none.
    fn warning(&self) -> bool {
        false
    }
    /// Whether the self-test passed (transition 1 leaves Not ready to switch on). Default: at once.
    fn ready(&self) -> bool {
        true
    }
}
