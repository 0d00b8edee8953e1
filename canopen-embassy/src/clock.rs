//! The node's clock on `embassy-time`.

use core::future::Future;

use canopen_core::driver::Timer;
use canopen_core::Instant;

/// The driver's [`Timer`] on `embassy-time`: `now` from [`embassy_time::Instant`], sleeping with
/// [`embassy_time::Timer::at`]. Both count microseconds from the same tick source as every other embassy
/// timer; with the default 1 MHz tick no conversion loses precision, and the time never goes backwards
/// across restarts of the driver (it is the hardware's, not the runner's).
///
/// ```
/// use canopen_core::driver::Timer;
/// use canopen_embassy::EmbassyClock;
/// let (a, b) = (EmbassyClock.now(), EmbassyClock.now());
/// assert!(b >= a);
/// ```
#[derive(Debug, Clone, Copy, Default)]
pub struct EmbassyClock;

impl Timer for EmbassyClock {
    #[inline(never)] // one copy: the driver reads the clock at several places (footprint.sh: see the commit)
    fn now(&self) -> Instant {
        Instant::from_micros(embassy_time::Instant::now().as_micros())
    }

    fn sleep_until(&mut self, deadline: Instant) -> impl Future<Output = ()> {
        embassy_time::Timer::at(embassy_time::Instant::from_micros(deadline.as_micros()))
    }
}
