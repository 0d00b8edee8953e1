//! The embassy-time driver. The clock is CMSDK APB TIMER0 (4000_0000h), a 32-bit down-counter on the 25 MHz
//! peripheral clock, free-running from FFFF_FFFFh; `now` extends it to 64 bits by counting its wraps in
//! software (one every 171 s, and `now` runs at least every millisecond) and divides to embassy-time's 1 MHz
//! tick. Wake-ups: embassy-time-queue-utils' `Queue`, run by the SysTick interrupt every millisecond, so a
//! timer fires within 1 ms of its instant (CANopen's times are milliseconds).
//!
//! Why not count SysTick interrupts for the clock: under a loaded host QEMU delivers a periodic timer late
//! and does not make up the lost periods, so a clock made of interrupts runs slow (seen: 200 ms heartbeats
//! 250-340 ms apart). A counter register is computed from QEMU's virtual clock at each read and is exact.
//! [`cycles`] gives the raw 25 MHz count for measurements.

use core::cell::{Cell, RefCell};
use core::ptr::{read_volatile, write_volatile};
use core::task::Waker;

use cortex_m::peripheral::{syst::SystClkSource, SYST};
use critical_section::{CriticalSection, Mutex};
use embassy_time_driver::Driver;
use embassy_time_queue_utils::Queue;

const CYCLES_PER_MS: u32 = crate::SYSCLK_HZ / 1000;
const CYCLES_PER_US: u64 = crate::SYSCLK_HZ as u64 / 1_000_000;

const TIMER0_CTRL: usize = 0x4000_0000;
const TIMER0_VALUE: usize = 0x4000_0004;
const TIMER0_RELOAD: usize = 0x4000_0008;
const CTRL_ENABLE: u32 = 1;

struct ClockDriver {
    /// Wraps of TIMER0 so far, and its last up-count, to detect the next.
    wraps: Mutex<Cell<(u32, u32)>>,
    alarm: Mutex<Cell<u64>>,
    queue: Mutex<RefCell<Queue>>,
}

embassy_time_driver::time_driver_impl!(static DRIVER: ClockDriver = ClockDriver {
    wraps: Mutex::new(Cell::new((0, 0))),
    alarm: Mutex::new(Cell::new(u64::MAX)),
    queue: Mutex::new(RefCell::new(Queue::new())),
});

/// Starts TIMER0 free-running and SysTick's 1 ms wake-up check (processor clock, interrupt on).
pub fn init(mut syst: SYST) {
    // SAFETY: TIMER0's registers, mapped by the board; nothing else uses the timer.
    unsafe {
        write_volatile(TIMER0_RELOAD as *mut u32, u32::MAX);
        write_volatile(TIMER0_VALUE as *mut u32, u32::MAX);
        write_volatile(TIMER0_CTRL as *mut u32, CTRL_ENABLE);
    }
    syst.set_clock_source(SystClkSource::Core);
    syst.set_reload(CYCLES_PER_MS - 1);
    syst.clear_current();
    syst.enable_interrupt();
    syst.enable_counter();
}

/// Peripheral clock cycles (40 ns each) since [`init`].
pub fn cycles() -> u64 {
    critical_section::with(|cs| DRIVER.cycles(cs))
}

impl ClockDriver {
    fn cycles(&self, cs: CriticalSection) -> u64 {
        // SAFETY: a read of TIMER0's counter.
        let up = u32::MAX - unsafe { read_volatile(TIMER0_VALUE as *const u32) };
        let cell = self.wraps.borrow(cs);
        let (mut wraps, last) = cell.get();
        if up < last {
            wraps = wraps.wrapping_add(1);
        }
        cell.set((wraps, up));
        (u64::from(wraps) << 32) | u64::from(up)
    }

    fn now_cs(&self, cs: CriticalSection) -> u64 {
        self.cycles(cs) / CYCLES_PER_US
    }
}

impl Driver for ClockDriver {
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
        let now = DRIVER.now_cs(cs);
        let alarm = DRIVER.alarm.borrow(cs);
        if now >= alarm.get() {
            alarm.set(DRIVER.queue.borrow(cs).borrow_mut().next_expiration(now));
        }
    });
}
