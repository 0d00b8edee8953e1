//! A simulated axis for tests and examples: a mass that the demand accelerates at most at its torque
//! limit (inertia), at most at its top speed, between two hard stops with a limit switch at each; integer
//! math only. Not for firmware: a real [`Motor`] drives hardware.

use crate::motor::{Demand, LimitSwitches, Motor};

/// A simulated axis.
///
/// ```
/// use canopen_cia402::{Demand, Motor, SimAxis};
/// let mut axis = SimAxis::new(-100_000, 100_000);
/// axis.set_power(true);
/// for _ in 0..1000 {
///     axis.follow(Demand::Velocity(1000), 1000);
/// }
/// assert_eq!(axis.velocity(), 1000);
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SimAxis {
    pos: i64,
    vel: i64,
    rem: i64,
    /// The most the motor can accelerate the mass, inc/s² (its torque over the inertia).
    pub max_acceleration: i64,
    /// Top speed, inc/s.
    pub max_velocity: i64,
    /// Deceleration by friction while unpowered, inc/s².
    pub friction: i64,
    /// The hard stops (and limit switches), inc.
    pub travel: (i32, i32),
    /// Position loop gain, 1/s.
    pub gain: i64,
    /// A fault to report ([`Motor::fault`]); the simulation's fault injection.
    pub fault: Option<u16>,
    powered: bool,
}

impl SimAxis {
    /// An axis at 0 between the hard stops `min` and `max` (inc), 2,000,000 inc/s² at most, 50,000 inc/s
    /// top speed, 20,000 inc/s² friction, gain 200/s.
    ///
    /// ```
    /// assert_eq!(canopen_cia402::SimAxis::new(-10, 10).travel, (-10, 10));
    /// ```
    pub fn new(min: i32, max: i32) -> Self {
        SimAxis {
            pos: 0,
            vel: 0,
            rem: 0,
            max_acceleration: 2_000_000,
            max_velocity: 50_000,
            friction: 20_000,
            travel: (min, max),
            gain: 200,
            fault: None,
            powered: false,
        }
    }

    /// Whether the power stage is on.
    ///
    /// ```
    /// assert!(!canopen_cia402::SimAxis::new(-10, 10).powered());
    /// ```
    pub fn powered(&self) -> bool {
        self.powered
    }
}

impl Motor for SimAxis {
    fn set_power(&mut self, on: bool) {
        self.powered = on;
    }

    fn follow(&mut self, demand: Demand, dt_us: u32) {
        let dt = i64::from(dt_us.min(100_000));
        // Everything in milli-units: inc·1000, inc/s·1000.
        let wanted = match (self.powered, demand) {
            (true, Demand::Position { position, velocity }) => {
                let err = i64::from(position) * 1000 - self.pos;
                Some(i64::from(velocity) * 1000 + err * self.gain)
            }
            (true, Demand::Velocity(v)) => Some(i64::from(v) * 1000),
            _ => None,
        };
        let top = self.max_velocity * 1000;
        let (target, rate) = match wanted {
            Some(w) => (w.clamp(-top, top), self.max_acceleration),
            None => (0, self.friction),
        };
        let dv = (rate * dt / 1000).max(1);
        self.vel = if target > self.vel { (self.vel + dv).min(target) } else { (self.vel - dv).max(target) };
        let moved = self.vel * dt + self.rem;
        self.pos += moved / 1_000_000;
        self.rem = moved % 1_000_000;
        let (lo, hi) = (i64::from(self.travel.0) * 1000, i64::from(self.travel.1) * 1000);
        if self.pos <= lo || self.pos >= hi {
            self.pos = self.pos.clamp(lo, hi);
            self.vel = 0;
            self.rem = 0;
        }
    }

    fn position(&self) -> i32 {
        (self.pos.div_euclid(1000)).clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
    }

    fn velocity(&self) -> i32 {
        (self.vel / 1000).clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
    }

    fn limit_switches(&self) -> LimitSwitches {
        let p = self.position();
        LimitSwitches { negative: p <= self.travel.0, positive: p >= self.travel.1 }
    }

    fn fault(&self) -> Option<u16> {
        self.fault
    }
}
