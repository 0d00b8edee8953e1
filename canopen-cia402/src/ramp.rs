//! The demand generator every motion mode shares: a position and a velocity moved toward a target with
//! acceleration and deceleration limits, in integers only (no float math: the core's rule for hot paths).
//!
//! Units: the demand position is kept in milli-increments and the velocity in milli-increments per
//! second, so that slow ramps on a fast cycle do not round to nothing; the cycle time is in µs and is
//! capped at 1 s per step. The position profile brakes on the curve `v = sqrt(2·d·s)` (s the distance
//! left, d the deceleration), the usual trapezoid: at most the profile velocity, at most `a` more per
//! second, and where the next step would pass the target it ends on it.

/// Milli-units per unit.
const MILLI: i64 = 1_000;
/// µs per second.
const MICROS: i64 = 1_000_000;
/// The longest step integrated at once.
pub const MAX_STEP_US: u32 = 1_000_000;

/// A demand position and velocity.
///
/// ```
/// use canopen_cia402::Ramp;
/// let mut r = Ramp::default();
/// // 1000 inc away, 2000 inc/s max, 10_000 inc/s² up and down, 1 ms steps.
/// let mut steps = 0;
/// while !r.position_step(1000, 2000, 10_000, 10_000, 1000) {
///     steps += 1;
/// }
/// assert_eq!((r.position(), r.velocity()), (1000, 0));
/// assert!((600..800).contains(&steps)); // 0.2 s ramps + 0.3 s at 2000 inc/s: 0.7 s
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Ramp {
    pos: i64,
    vel: i64,
    rem: i64,
}

fn sat_i32(v: i64) -> i32 {
    v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
}

/// Integer square root (floor).
fn isqrt(n: u64) -> u64 {
    if n < 2 {
        return n;
    }
    let mut x = 1u64 << ((64 - n.leading_zeros()).div_ceil(2));
    loop {
        let y = (x + n / x) / 2;
        if y >= x {
            return x;
        }
        x = y;
    }
}

impl Ramp {
    /// The demand position, in increments.
    ///
    /// ```
    /// assert_eq!(canopen_cia402::Ramp::at(5, 0).position(), 5);
    /// ```
    pub fn position(&self) -> i32 {
        sat_i32(self.pos.div_euclid(MILLI))
    }

    /// The demand velocity, in increments per second.
    ///
    /// ```
    /// assert_eq!(canopen_cia402::Ramp::at(0, -7).velocity(), -7);
    /// ```
    pub fn velocity(&self) -> i32 {
        sat_i32(self.vel / MILLI)
    }

    /// A ramp standing at `position` moving at `velocity` (inc, inc/s).
    ///
    /// ```
    /// assert_eq!(canopen_cia402::Ramp::at(3, 4).velocity(), 4);
    /// ```
    pub fn at(position: i32, velocity: i32) -> Ramp {
        Ramp { pos: i64::from(position) * MILLI, vel: i64::from(velocity) * MILLI, rem: 0 }
    }

    /// Moves the position by `delta` increments (a new home), keeping the velocity.
    ///
    /// ```
    /// let mut r = canopen_cia402::Ramp::at(3, 0);
    /// r.shift(-3);
    /// assert_eq!(r.position(), 0);
    /// ```
    pub fn shift(&mut self, delta: i64) {
        self.pos += delta * MILLI;
    }

    /// One step of `dt_us` toward the velocity `target` (inc/s): at most `accel` inc/s² faster, at most
    /// `decel` inc/s² slower. Returns whether the velocity equals the target.
    ///
    /// ```
    /// let mut r = canopen_cia402::Ramp::default();
    /// assert!(!r.velocity_step(100, 1000, 1000, 50_000)); // 50 ms at 1000 inc/s²: 50 inc/s
    /// assert_eq!(r.velocity(), 50);
    /// assert!(r.velocity_step(100, 1000, 1000, 50_000));
    /// ```
    pub fn velocity_step(&mut self, target: i32, accel: u32, decel: u32, dt_us: u32) -> bool {
        let dt = i64::from(dt_us.min(MAX_STEP_US));
        self.toward(i64::from(target) * MILLI, accel, decel, dt);
        self.integrate(dt);
        self.vel == i64::from(target) * MILLI
    }

    /// One step toward standstill with deceleration `decel`; returns whether the velocity is 0.
    ///
    /// ```
    /// let mut r = canopen_cia402::Ramp::at(0, 10);
    /// assert!(r.stop_step(1_000_000, 1000));
    /// ```
    pub fn stop_step(&mut self, decel: u32, dt_us: u32) -> bool {
        self.velocity_step(0, decel, decel, dt_us)
    }

    /// One step of `dt_us` toward the position `target` (inc) with the profile velocity `vmax`, `accel`
    /// and `decel`; returns whether the demand stands on the target.
    ///
    /// ```
    /// let mut r = canopen_cia402::Ramp::at(10, 0);
    /// assert!(r.position_step(10, 100, 100, 100, 1000));
    /// ```
    pub fn position_step(&mut self, target: i32, vmax: u32, accel: u32, decel: u32, dt_us: u32) -> bool {
        let dt = i64::from(dt_us.min(MAX_STEP_US));
        let goal = i64::from(target) * MILLI;
        let dist = goal - self.pos;
        if dist == 0 && self.vel == 0 {
            return true;
        }
        // Speed allowed so that `decel` still stops on the target: v = sqrt(2 d s), in milli units.
        let allowed =
            isqrt(2u64.saturating_mul(u64::from(decel)).saturating_mul(dist.unsigned_abs()).saturating_mul(1000));
        let speed = (u64::from(vmax) * 1000).min(allowed) as i64;
        self.toward(dist.signum() * speed, accel, decel, dt);
        self.integrate(dt);
        // The step passed (or reached) the target: end on it.
        if (goal - self.pos).signum() != dist.signum() || (self.vel == 0 && (goal - self.pos).abs() < MILLI) {
            self.pos = goal;
            self.vel = 0;
            self.rem = 0;
            return true;
        }
        false
    }

    fn toward(&mut self, target: i64, accel: u32, decel: u32, dt: i64) {
        let speeding_up = target.signum() * self.vel.signum() >= 0 && target.abs() > self.vel.abs();
        let rate = i64::from(if speeding_up { accel } else { decel });
        // rate [inc/s²] · dt [µs] = milli-inc/s · 1000.
        let dv = (rate * dt / MILLI).max(1);
        self.vel = if target > self.vel { (self.vel + dv).min(target) } else { (self.vel - dv).max(target) };
    }

    fn integrate(&mut self, dt: i64) {
        let moved = self.vel * dt + self.rem;
        self.pos += moved / MICROS;
        self.rem = moved % MICROS;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn isqrt_is_the_floor_square_root() {
        for n in (0u64..10_000).chain([u64::MAX, u64::MAX - 1, 1 << 62, (1 << 32) - 1]) {
            let r = isqrt(n);
            assert!(r * r <= n && (r + 1).checked_mul(r + 1).is_none_or(|s| s > n), "{n}: {r}");
        }
    }

    #[test]
    fn moves_end_on_the_target_both_ways_and_from_motion() {
        for (start, v0, target) in [(0, 0, 1000), (0, 0, -1000), (500, 3000, 0), (0, -2000, 10), (7, 0, 8)] {
            let mut r = Ramp::at(start, v0);
            let mut n = 0;
            while !r.position_step(target, 2000, 10_000, 10_000, 1000) {
                n += 1;
                assert!(n < 100_000, "never arrived: {start} {v0} {target}");
                assert!(r.velocity().abs() <= 3000);
            }
            assert_eq!((r.position(), r.velocity()), (target, 0));
        }
    }

    #[test]
    fn velocity_ramps_respect_the_limits() {
        let mut r = Ramp::default();
        let mut last = 0;
        for _ in 0..100 {
            r.velocity_step(5000, 20_000, 40_000, 1000);
            assert!(r.velocity() - last <= 20);
            last = r.velocity();
        }
        assert_eq!(r.velocity(), 2000);
        for _ in 0..10 {
            r.velocity_step(0, 20_000, 40_000, 1000);
        }
        assert_eq!(r.velocity(), 1600);
        assert!(r.position() > 0);
    }
}
