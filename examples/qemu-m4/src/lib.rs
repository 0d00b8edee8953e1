//! Board support for QEMU's `mps2-an386` (ARM's AN386 FPGA image for the MPS2 board: a Cortex-M4 with
//! SysTick and CMSDK APB UARTs), enough to run the canopener node under embassy with its frames as slcan
//! lines on UART0. No PAC or HAL exists for this board in Rust; the few registers used are written here.
//!
//! Public descriptions relied on: QEMU's `docs/system/arm/mps2.rst` and `hw/arm/mps2.c` (memory map: image
//! at 0, RAM at 2000_0000h; UART0 at 4000_4000h with its RX interrupt on IRQ 0 and TX on IRQ 1; a 25 MHz
//! system clock), ARM's CMSDK APB UART description (DATA, STATE, CTRL, INTSTATUS/INTCLEAR, BAUDDIV at 0, 4, 8,
//! Ch, 10h) and APB timer (CTRL, VALUE, RELOAD at 0, 4, 8; TIMER0 at 4000_0000h), the ARMv7-M Architecture
//! Reference Manual for SysTick and the semihosting exit call, and
//! embassy-time-driver's documentation for the driver and its timer queue.
//!
//! - [`device`]: the node's dictionary and configuration (shared with the host example `qemu_m4_eds`);
//! - [`uart`]: UART0, receive on its interrupt into a pipe, transmit polled;
//! - [`time_driver`]: the embassy-time driver: TIMER0 as the clock, SysTick every 1 ms for the wake-ups;
//! - [`link`]: the node's `CanRx`/`CanTx` as slcan over the UART (`canopen-slcan`'s decoder and adapter);
//! - [`stack`]: the stack painted at boot and its high-water mark read back;
//! - [`semihosting`]: leave QEMU with an exit status (the bench binary).
#![no_std]

pub mod device;
pub mod link;
pub mod semihosting;
pub mod stack;
pub mod time_driver;
pub mod uart;

/// The system clock of QEMU's MPS2 boards (`SYSCLK_FRQ` in `hw/arm/mps2.c`), which SysTick and TIMER0 count.
pub const SYSCLK_HZ: u32 = 25_000_000;

/// The board's interrupts: all of them reach cortex-m-rt's `DefaultHandler` (no device crate), which
/// dispatches on the number.
#[cortex_m_rt::exception]
unsafe fn DefaultHandler(irqn: i16) {
    if irqn == uart::UART0_RX_IRQ as i16 {
        uart::on_rx_interrupt();
    }
}

/// An NVIC interrupt number of this board.
#[derive(Clone, Copy)]
pub struct Irq(pub u16);

// SAFETY: the numbers used are the board's (UART0 RX = 0), below the 32 its NVIC has.
unsafe impl cortex_m::interrupt::InterruptNumber for Irq {
    fn number(self) -> u16 {
        self.0
    }
}

/// A panic ends QEMU with status 1 after its source file on QEMU's standard error (the log CI prints).
/// No `core::fmt` here: it would add kilobytes of flash to every binary.
#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    semihosting::write("firmware panic in ");
    semihosting::write(info.location().map_or("?", |l| l.file()));
    semihosting::write("\n");
    semihosting::exit(false)
}

/// A fault ends QEMU with status 1 and the faulting PC on its standard error.
#[cortex_m_rt::exception]
unsafe fn HardFault(frame: &cortex_m_rt::ExceptionFrame) -> ! {
    let mut hex = *b"firmware hard fault at pc 0x00000000\n";
    let at = hex.len() - 9;
    for (i, d) in hex[at..at + 8].iter_mut().enumerate() {
        *d = b"0123456789abcdef"[(frame.pc() >> (28 - 4 * i)) as usize & 0xF];
    }
    semihosting::write(core::str::from_utf8(&hex).unwrap_or("firmware hard fault\n"));
    semihosting::exit(false)
}
