//! Glue between `canopen-core`'s executor-agnostic driver ([`canopen_core::driver`]) and embassy on an
//! STM32 with bxCAN. `canopen-core` has no embassy dependency; everything embassy-specific lives here, in
//! four small types:
//!
//! - [`BxCanTx`] / [`BxCanRx`]: the core's `CanTx` / `CanRx` for the split halves of
//!   `embassy_stm32::can::Can` (bxCAN). The receive future is a single `read().await`, which is
//!   cancel-safe (a frame is taken out of the FIFO only when the future completes);
//! - [`EmbassyClock`]: the core's `Timer` on `embassy-time` (`now` from `embassy_time::Instant`, sleep with
//!   `embassy_time::Timer::at`). Both count microseconds with the default 1 MHz tick, so no conversion
//!   loses precision;
//! - [`NodeCell`]: the core's `Shared` over an `embassy-sync` blocking mutex on a critical section, so the
//!   node can be changed from any task or interrupt;
//! - [`AppWake`]: the core's `Wake` over an `embassy-sync` `Signal`: a task that changed the node signals it,
//!   and the driver sends what was queued without waiting for the next deadline.
#![no_std]

use core::cell::RefCell;
use core::future::Future;

use canopen_core::driver::{CanRx, CanTx, Shared, Timer, Wake};
use canopen_core::{CanFrame, Instant};
use embassy_stm32::can;
use embassy_sync::blocking_mutex::raw::CriticalSectionRawMutex;
use embassy_sync::blocking_mutex::Mutex;
use embassy_sync::signal::Signal;

/// The transmit half of a bxCAN peripheral.
pub struct BxCanTx<'d>(pub can::CanTx<'d>);

impl CanTx for BxCanTx<'_> {
    type Error = core::convert::Infallible;

    /// Waits for a free mailbox. A frame that the HAL refuses to build cannot occur: the core only
    /// produces 11-bit identifiers and at most 8 bytes.
    async fn transmit(&mut self, frame: &CanFrame) -> Result<(), Self::Error> {
        if let Some(f) = frame.to_frame::<can::Frame>() {
            self.0.write(&f).await;
        }
        Ok(())
    }
}

/// The receive half of a bxCAN peripheral.
pub struct BxCanRx<'d>(pub can::CanRx<'d>);

impl CanRx for BxCanRx<'_> {
    /// A bus error (stuff, form, bit, CRC, ACK errors, bus-off) reported by the controller.
    type Error = can::enums::BusError;

    async fn receive(&mut self) -> Result<CanFrame, Self::Error> {
        loop {
            let envelope = self.0.read().await?;
            // 29-bit frames are not CANopen (CAN-01): skip them. Each `read` is cancel-safe, so the loop is.
            if let Some(f) = CanFrame::from_frame(&envelope.frame) {
                return Ok(f);
            }
        }
    }
}

/// The node's clock on `embassy-time`.
#[derive(Debug, Clone, Copy, Default)]
pub struct EmbassyClock;

impl Timer for EmbassyClock {
    fn now(&self) -> Instant {
        Instant::from_micros(embassy_time::Instant::now().as_micros())
    }

    fn sleep_until(&mut self, deadline: Instant) -> impl Future<Output = ()> {
        embassy_time::Timer::at(embassy_time::Instant::from_micros(deadline.as_micros()))
    }
}

/// A node shared between the driver task and the application's tasks (or interrupts): a blocking mutex on
/// a critical section. The lock is held only while the node computes, never across an `.await`.
pub struct NodeCell<N>(Mutex<CriticalSectionRawMutex, RefCell<N>>);

impl<N> NodeCell<N> {
    /// Wraps `node`.
    pub const fn new(node: N) -> Self {
        NodeCell(Mutex::new(RefCell::new(node)))
    }
}

impl<N> Shared<N> for NodeCell<N> {
    fn lock<R>(&self, f: impl FnOnce(&mut N) -> R) -> R {
        self.0.lock(|cell| f(&mut cell.borrow_mut()))
    }
}

/// The application's wake-up for the driver: `signal()` after changing the node from another task.
pub struct AppWake(Signal<CriticalSectionRawMutex, ()>);

impl AppWake {
    /// A wake-up source nobody has signalled yet (usable in a `static`).
    pub const fn new() -> Self {
        AppWake(Signal::new())
    }

    /// Wakes the driver so it sends what the application queued (event-driven TPDOs, EMCY).
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
