//! The application's wake-up for the driver.

use core::future::Future;

use canopen_core::driver::Wake;
use embassy_sync::blocking_mutex::raw::CriticalSectionRawMutex;
use embassy_sync::signal::Signal;

/// The application's wake-up for the driver: [`signal`](AppWake::signal) after changing the node from
/// another task (process values, an event-driven TPDO, an EMCY), and the driver sends what was queued at
/// once instead of at its next deadline.
///
/// ```
/// use canopen_core::driver::Wake;
/// use canopen_embassy::AppWake;
///
/// static WAKE: AppWake = AppWake::new();
/// WAKE.signal();
/// embassy_futures::block_on(WAKE.wait()); // returns at once: it was signalled
/// ```
pub struct AppWake(Signal<CriticalSectionRawMutex, ()>);

impl AppWake {
    /// A wake-up source nobody has signalled yet (usable in a `static`).
    ///
    /// ```
    /// static WAKE: canopen_embassy::AppWake = canopen_embassy::AppWake::new();
    /// ```
    pub const fn new() -> Self {
        AppWake(Signal::new())
    }

    /// Wakes the driver so it sends what the application queued (event-driven TPDOs, EMCY).
    ///
    /// ```
    /// canopen_embassy::AppWake::new().signal();
    /// ```
    pub fn signal(&self) {
        self.0.signal(())
    }
}

impl Default for AppWake {
    fn default() -> Self {
        Self::new()
    }
}

impl Wake for AppWake {
    fn wait(&self) -> impl Future<Output = ()> {
        self.0.wait()
    }
}
