//! The stack's high-water mark: [`paint`] fills the unused stack with a pattern at boot, [`high_water`] finds
//! the deepest word that no longer holds it. The stack is cortex-m-rt's: from `_stack_start` (the initial SP,
//! the top of RAM) down to `_stack_end` (the end of `.bss`/`.uninit`).
//!
//! Under embassy the tasks' futures live in statics, so the stack holds only the call chain of the poll
//! being run plus the interrupt frames stacked on it: the figure is what a device must reserve beyond
//! `.data`/`.bss`.

use core::ptr::{addr_of, read_volatile, write_volatile};

const PAINT: u32 = 0x5AA5_C33C;

unsafe extern "C" {
    static _stack_start: u32;
    static _stack_end: u32;
}

fn bounds() -> (usize, usize) {
    (addr_of!(_stack_end) as usize, addr_of!(_stack_start) as usize)
}

/// The stack's size in bytes.
pub fn size() -> u32 {
    let (bottom, top) = bounds();
    (top - bottom) as u32
}

/// Paints the stack below the current frame (less a margin for this function's own). Call it first in
/// `main`. Returns how deep the stack already is (bytes from its top to the painted part), so that a later
/// [`high_water`] less it is what the code run in between took.
pub fn paint() -> u32 {
    let (bottom, top) = bounds();
    let below = cortex_m::register::msp::read() as usize - 64;
    let mut at = (bottom + 3) & !3;
    while at < below {
        // SAFETY: [bottom, SP - 64) is RAM no one uses yet: below the live stack, above .bss/.uninit.
        unsafe { write_volatile(at as *mut u32, PAINT) };
        at += 4;
    }
    (top - below) as u32
}

/// The deepest the stack has been since [`paint`], in bytes from its top.
pub fn high_water() -> u32 {
    let (bottom, top) = bounds();
    let mut at = (bottom + 3) & !3;
    // SAFETY: reads of the stack region, which is RAM.
    while at < top && unsafe { read_volatile(at as *const u32) } == PAINT {
        at += 4;
    }
    (top - at) as u32
}
