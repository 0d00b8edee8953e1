//! The embassy-time driver: SysTick on the 25 MHz processor clock, reloaded every millisecond. `now` is in
//! microseconds (embassy-time's 1 MHz tick): elapsed milliseconds (counted by the SysTick interrupt) plus the
//! counter's position in the current one. Wake-ups go through embassy-time-queue-utils' `Queue`; the SysTick
//! interrupt runs it every millisecond, so a timer fires within 1 ms of its instant (CANopen's times are
//! milliseconds). [`cycles`] gives the raw 25 MHz count for measurements.

use core::cell::{Cell, RefCell};
use core::task::Waker;

use cortex_m::peripheral::{syst::SystClkSource, SCB, SYST};
use critical_section::{CriticalSection, Mutex};
use embassy_time_driver::Driver;
use embassy_time_queue_utils::Queue;

const CYCLES_PER_MS: u32 = crate::SYSCLK_HZ / 1000;

struct SysTickDriver {
    ms: Mutex<Cell<u64>>,
    alarm: Mutex<Cell<u64>>,
    queue: Mutex<RefCell<Queue>>,
}

embassy_time_driver::time_driver_impl!(static DRIVER: SysTickDriver = SysTickDriver {
    ms: Mutex::new(Cell::new(0)),
    alarm: Mutex::new(Cell::new(u64::MAX)),
    queue: Mutex::new(RefCell::new(Queue::new())),
});

/// Starts SysTick: processor clock, 1 ms period, interrupt on.
pub fn init(mut syst: SYST) {
    syst.set_clock_source(SystClkSource::Core);
    syst.set_reload(CYCLES_PER_MS - 1);
    syst.clear_current();
    syst.enable_interrupt();
    syst.enable_counter();
    // The counter reads 0 until its first reload (which raises no interrupt): wait for it, so that `now`
    // never goes back from "the end of ms 0" to its start.
    while SYST::get_current() == 0 {}
}

/// Processor clock cycles since [`init`] (40 ns each).
pub fn cycles() -> u64 {
    critical_section::with(|cs| {
        let (ms, in_ms) = DRIVER.position(cs);
        ms * u64::from(CYCLES_PER_MS) + u64::from(in_ms)
    })
}

impl SysTickDriver {
    /// Elapsed whole milliseconds and cycles into the current one. A wrap whose interrupt is still pending
    /// (we are in a critical section) is counted, and the counter read again after it.
    fn position(&self, cs: CriticalSection) -> (u64, u32) {
        let ms = self.ms.borrow(cs).get();
        let current = SYST::get_current();
        if SCB::is_pendst_pending() {
            (ms + 1, CYCLES_PER_MS - 1 - SYST::get_current())
        } else {
            (ms, CYCLES_PER_MS - 1 - current)
        }
    }

    fn now_cs(&self, cs: CriticalSection) -> u64 {
        let (ms, in_ms) = self.position(cs);
        ms * 1000 + u64::from(in_ms / (CYCLES_PER_MS / 1000))
    }
}

impl Driver for SysTickDriver {
    fn now(&self) -> u64 {
        critical_section::with(|cs| self.now_cs(cs))
    }

    fn schedule_wake(&self, at: u64, waker: &Waker) {
        critical_section::with(|cs| {
            let mut queue = self.queue.borrow(cs).borrow_mut();
            if queue.schedule_wake(at, waker) {
                // Wakes what is due already and gives the next instant the SysTick interrupt checks.
                self.alarm.borrow(cs).set(queue.next_expiration(self.now_cs(cs)));
            }
        });
    }
}

#[cortex_m_rt::exception]
fn SysTick() {
    critical_section::with(|cs| {
        let ms = DRIVER.ms.borrow(cs);
        ms.set(ms.get() + 1);
        let now = DRIVER.now_cs(cs);
        let alarm = DRIVER.alarm.borrow(cs);
        if now >= alarm.get() {
            alarm.set(DRIVER.queue.borrow(cs).borrow_mut().next_expiration(now));
        }
    });
}
