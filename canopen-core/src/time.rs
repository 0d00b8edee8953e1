//! Time as a value: the core never reads a clock (the smoltcp / quinn-proto shape).
//!
//! The caller passes a monotonic [`Instant`] (integer microseconds since any origin) into every call
//! that depends on time. Deadlines come back out of `Node::poll_timeout`, so a runner sleeps exactly until
//! the next one and no fixed tick is needed. Integer microseconds keep floating point out of the core.
//!
//! The three types hold a `u64` at 4-byte alignment (`repr(C, packed(4))`, read and written by value only), so
//! that the services that keep them, and with them the node, are 4-aligned on a 32-bit target: building or
//! resetting a node then copies and clears with `__aeabi_memcpy4`/`memclr4`, which a firmware links anyway,
//! and not also with their 8-byte variants (392 B of the firmware example's flash, 48 B of its RAM).

use core::ops::{Add, AddAssign, Sub};

/// A point on the caller's monotonic clock, in microseconds.
///
/// The arithmetic relies on one bound: an instant is below 2⁶³ µs (some 292,000 years after the runner's
/// epoch) and a [`Duration`] is at most [`Duration::MAX`] (2⁶³ − 1 µs, its constructors clamp), so
/// `Instant + Duration` never overflows a `u64` and is a plain addition (two instructions on a Cortex-M, where
/// a saturating one costs six: 324 B of the firmware's flash). An instant beyond the bound wraps; it never
/// panics.
///
/// ```
/// use canopen_core::time::{Duration, Instant};
/// let t = Instant::from_millis(5) + Duration::from_micros(250);
/// assert_eq!(t.as_micros(), 5_250);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
#[repr(C, packed(4))] // 4-byte aligned: see the module docs
pub struct Instant(u64);

impl Instant {
    /// The origin of the clock.
    pub const ZERO: Instant = Instant(0);

    /// An instant `us` microseconds after the origin.
    ///
    /// ```
    /// # use canopen_core::time::Instant;
    /// assert_eq!(Instant::from_micros(7).as_micros(), 7);
    /// ```
    pub const fn from_micros(us: u64) -> Self {
        Instant(us)
    }

    /// An instant `ms` milliseconds after the origin.
    ///
    /// ```
    /// # use canopen_core::time::Instant;
    /// assert_eq!(Instant::from_millis(2).as_micros(), 2_000);
    /// ```
    pub const fn from_millis(ms: u64) -> Self {
        Instant(ms.saturating_mul(1_000))
    }

    /// Microseconds since the origin.
    ///
    /// ```
    /// # use canopen_core::time::Instant;
    /// assert_eq!(Instant::from_millis(1).as_micros(), 1_000);
    /// ```
    pub const fn as_micros(self) -> u64 {
        self.0
    }

    /// Time elapsed from `earlier` to `self`, zero if `earlier` is later.
    ///
    /// ```
    /// # use canopen_core::time::{Duration, Instant};
    /// let a = Instant::from_millis(1);
    /// let b = Instant::from_millis(3);
    /// assert_eq!(b.saturating_duration_since(a), Duration::from_millis(2));
    /// assert_eq!(a.saturating_duration_since(b), Duration::ZERO);
    /// ```
    pub const fn saturating_duration_since(self, earlier: Instant) -> Duration {
        Duration::from_micros(self.0.saturating_sub(earlier.0))
    }
}

/// A span of time in microseconds.
///
/// ```
/// use canopen_core::time::Duration;
/// assert_eq!(Duration::from_millis(3).as_micros(), 3_000);
/// assert_eq!(Duration::from_100us(15).as_micros(), 1_500);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
#[repr(C, packed(4))] // 4-byte aligned: see the module docs
pub struct Duration(u64);

impl Duration {
    /// No time at all.
    pub const ZERO: Duration = Duration(0);

    /// The longest duration, 2⁶³ − 1 µs (some 292,000 years): the constructors clamp to it, so that adding
    /// one to an [`Instant`] never overflows (see [`Instant`]).
    ///
    /// ```
    /// # use canopen_core::time::Duration;
    /// assert_eq!(Duration::from_millis(u64::MAX), Duration::MAX);
    /// ```
    pub const MAX: Duration = Duration(i64::MAX as u64);

    /// `us` microseconds, at most [`Duration::MAX`].
    ///
    /// ```
    /// # use canopen_core::time::Duration;
    /// assert_eq!(Duration::from_micros(9).as_micros(), 9);
    /// assert_eq!(Duration::from_micros(u64::MAX), Duration::MAX);
    /// ```
    pub const fn from_micros(us: u64) -> Self {
        if us > Self::MAX.0 {
            Self::MAX
        } else {
            Duration(us)
        }
    }

    /// `ms` milliseconds (the unit of 1017h, 1016h, 100Ch and event timers).
    ///
    /// ```
    /// # use canopen_core::time::Duration;
    /// assert_eq!(Duration::from_millis(9).as_micros(), 9_000);
    /// ```
    pub const fn from_millis(ms: u64) -> Self {
        Self::from_micros(ms.saturating_mul(1_000))
    }

    /// `ms` milliseconds of a 16- or 32-bit object (1017h, 1016h, 100Ch × 100Dh, an LSS switch delay): exact,
    /// at most 4,294,967,295,000 µs, so one 32 × 32-bit multiply with no saturation or clamp (what
    /// [`from_millis`](Self::from_millis) needs for any `u64`).
    #[cfg_attr(not(feature = "guarding"), allow(dead_code))] // life guarding is its only user so far
    pub(crate) const fn from_millis_u32(ms: u32) -> Self {
        Duration(ms as u64 * 1_000)
    }

    /// `n` × 100 µs (the unit of inhibit times, 1015h and 18xxh sub 3).
    ///
    /// ```
    /// # use canopen_core::time::Duration;
    /// assert_eq!(Duration::from_100us(10), Duration::from_millis(1));
    /// ```
    pub const fn from_100us(n: u64) -> Self {
        Self::from_micros(n.saturating_mul(100))
    }

    /// The length in microseconds.
    ///
    /// ```
    /// # use canopen_core::time::Duration;
    /// assert_eq!(Duration::from_millis(1).as_micros(), 1_000);
    /// ```
    pub const fn as_micros(self) -> u64 {
        self.0
    }

    /// Whether this is zero (CANopen uses 0 to mean "off" for every period).
    ///
    /// ```
    /// # use canopen_core::time::Duration;
    /// assert!(Duration::ZERO.is_zero());
    /// ```
    pub const fn is_zero(self) -> bool {
        self.0 == 0
    }
}

/// A plain addition: no overflow below the bound of [`Instant`], a wrap (not a panic) above it.
impl Add<Duration> for Instant {
    type Output = Instant;
    fn add(self, rhs: Duration) -> Instant {
        Instant(self.0.wrapping_add(rhs.0))
    }
}

impl AddAssign<Duration> for Instant {
    fn add_assign(&mut self, rhs: Duration) {
        *self = *self + rhs;
    }
}

impl Sub<Instant> for Instant {
    type Output = Duration;
    fn sub(self, rhs: Instant) -> Duration {
        self.saturating_duration_since(rhs)
    }
}

/// At most [`Duration::MAX`].
impl Add for Duration {
    type Output = Duration;
    fn add(self, rhs: Duration) -> Duration {
        Duration::from_micros(self.0.saturating_add(rhs.0))
    }
}

/// An optional deadline in 8 bytes, where `Option<Instant>` takes 12 (a flag padded to the
/// alignment): what the services keep their timers in. The instant `u64::MAX` µs (some 585,000 years after
/// the runner's epoch) stands for "no deadline"; an instant plus a duration never reaches it (see [`Instant`]).
///
/// ```
/// use canopen_core::time::{Deadline, Instant};
/// let mut d = Deadline::NONE;
/// assert_eq!(d.get(), None);
/// d.set(Some(Instant::from_millis(5)));
/// assert!(!d.passed(Instant::from_millis(4)) && d.passed(Instant::from_millis(5)));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[repr(C, packed(4))] // 4-byte aligned: see the module docs
pub struct Deadline(u64);

/// `Instant(5000)`, as the derive would print it (a derive cannot: it borrows the packed field).
#[cfg(feature = "defmt")]
impl defmt::Format for Instant {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(f, "Instant({=u64})", self.as_micros())
    }
}

/// `Duration(5000)`, as the derive would print it (a derive cannot: it borrows the packed field).
#[cfg(feature = "defmt")]
impl defmt::Format for Duration {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(f, "Duration({=u64})", self.as_micros())
    }
}

impl Default for Deadline {
    fn default() -> Self {
        Self::NONE
    }
}

impl Deadline {
    /// No deadline.
    pub const NONE: Deadline = Deadline(u64::MAX);

    /// A deadline at `t`, or none.
    pub const fn new(t: Option<Instant>) -> Self {
        match t {
            Some(t) => Deadline(t.0),
            None => Self::NONE,
        }
    }

    /// The deadline, if any.
    pub const fn get(self) -> Option<Instant> {
        if self.0 == u64::MAX {
            None
        } else {
            Some(Instant(self.0))
        }
    }

    /// A deadline at `t`.
    ///
    /// ```
    /// use canopen_core::time::{Deadline, Instant};
    /// assert_eq!(Deadline::at(Instant::from_millis(5)).get(), Some(Instant::from_millis(5)));
    /// ```
    pub const fn at(t: Instant) -> Self {
        Deadline(t.0)
    }

    /// `d` after `now`, or none when `d` is [`Duration::MAX`] (a disabled timer kept as the longest
    /// duration, so that its owner needs no flag).
    ///
    /// ```
    /// use canopen_core::time::{Deadline, Duration, Instant};
    /// let now = Instant::from_millis(5);
    /// assert_eq!(Deadline::after(now, Duration::from_millis(2)).get(), Some(Instant::from_millis(7)));
    /// assert_eq!(Deadline::after(now, Duration::MAX), Deadline::NONE);
    /// ```
    pub const fn after(now: Instant, d: Duration) -> Self {
        if d.0 == Duration::MAX.0 {
            Self::NONE
        } else {
            Deadline(now.0 + d.0)
        }
    }

    /// The instant (`u64::MAX` µs when there is no deadline): for a caller that has just seen it
    /// [`passed`](Self::passed).
    pub(crate) const fn instant(self) -> Instant {
        Instant(self.0)
    }

    /// Sets or clears the deadline.
    pub fn set(&mut self, t: Option<Instant>) {
        *self = Self::new(t);
    }

    /// Whether there is a deadline and `now` has reached it. One comparison: no deadline is `u64::MAX` µs,
    /// which no instant reaches (instants are below 2⁶³ µs, see [`Instant`]).
    pub const fn passed(self, now: Instant) -> bool {
        self.0 <= now.0
    }
}

/// The earlier of two optional deadlines (`None` = no deadline).
///
/// ```
/// use canopen_core::time::{earliest, Instant};
/// let a = Some(Instant::from_millis(5));
/// assert_eq!(earliest(a, None), a);
/// assert_eq!(earliest(a, Some(Instant::from_millis(2))), Some(Instant::from_millis(2)));
/// ```
pub fn earliest(a: Option<Instant>, b: Option<Instant>) -> Option<Instant> {
    match (a, b) {
        (Some(x), Some(y)) => Some(x.min(y)),
        (x, None) => x,
        (None, y) => y,
    }
}

/// `Instant::from_millis`, short for the unit tests' timelines.
#[cfg(test)]
pub(crate) const fn ms(v: u64) -> Instant {
    Instant::from_millis(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::mem::{align_of, size_of};

    /// The layout the module docs promise: 8 bytes at 4-byte alignment, on a 64-bit host as on a Cortex-M,
    /// and so a struct of them with `u32`s is 4-aligned ([`crate::sdo::server::SdoServer`] too).
    #[test]
    fn time_values_are_8_bytes_4_aligned() {
        assert_eq!((size_of::<Instant>(), align_of::<Instant>()), (8, 4));
        assert_eq!((size_of::<Duration>(), align_of::<Duration>()), (8, 4));
        assert_eq!((size_of::<Deadline>(), align_of::<Deadline>()), (8, 4));
        assert_eq!(align_of::<crate::sdo::server::SdoServer>(), 4);
    }

    /// The bound of [`Instant`]: below 2⁶³ µs, adding any duration (clamped to [`Duration::MAX`]) neither
    /// wraps nor reaches [`Deadline::NONE`]; every constructor and the sums clamp to the maximum.
    #[test]
    fn durations_clamp_and_sums_stay_below_no_deadline() {
        for d in [Duration::from_micros(u64::MAX), Duration::from_millis(u64::MAX), Duration::from_100us(u64::MAX)] {
            assert_eq!(d, Duration::MAX);
        }
        assert_eq!(Duration::MAX + Duration::MAX, Duration::MAX);
        assert_eq!(Instant::from_micros(u64::MAX) - Instant::ZERO, Duration::MAX);
        let last = Instant::from_micros((1 << 63) - 1);
        for t in [Instant::ZERO, Instant::from_millis(1_000), last] {
            let sum = t + Duration::MAX;
            assert!(sum >= t, "{t:?} + MAX wrapped");
            assert_ne!(Deadline::new(Some(sum)), Deadline::NONE);
        }
        assert_eq!((last + Duration::MAX).as_micros(), u64::MAX - 1);
        // No deadline is never passed, at any instant of the bound or at the largest sum.
        for t in [Instant::ZERO, last, last + Duration::MAX] {
            assert!(!Deadline::NONE.passed(t));
            assert!(Deadline::at(t).passed(t));
        }
    }
}
