//! UART0 of the board, a CMSDK APB UART at 4000_4000h. Receive: the RX interrupt (IRQ 0) moves each byte
//! into a 256-byte [`Pipe`] that the link task awaits; a byte that finds the pipe full, or that the UART
//! flags as overrun, is dropped and counted ([`rx_dropped`]). Transmit: polled on STATE.TXFULL (QEMU sends a
//! byte at once; a real board would use the TX interrupt for long writes).
//!
//! The interrupt clears INTCLEAR.RX *before* it drains DATA, so a byte that arrives while it runs raises
//! the interrupt again instead of being left behind.

use core::ptr::{read_volatile, write_volatile};
use core::sync::atomic::{AtomicU32, Ordering};

use embassy_sync::blocking_mutex::raw::CriticalSectionRawMutex;
use embassy_sync::pipe::Pipe;

/// NVIC number of UART0's receive interrupt (`uartirq[0]` in QEMU's `hw/arm/mps2.c`).
pub const UART0_RX_IRQ: u16 = 0;

const BASE: usize = 0x4000_4000;
const DATA: usize = BASE;
const STATE: usize = BASE + 0x04;
const CTRL: usize = BASE + 0x08;
const INTCLEAR: usize = BASE + 0x0C;
const BAUDDIV: usize = BASE + 0x10;

const STATE_TXFULL: u32 = 1 << 0;
const STATE_RXFULL: u32 = 1 << 1;
const STATE_RXOVERRUN: u32 = 1 << 3;
const CTRL_TX_EN: u32 = 1 << 0;
const CTRL_RX_EN: u32 = 1 << 1;
const CTRL_RX_INTEN: u32 = 1 << 3;
const INT_RX: u32 = 1 << 1;

static RX: Pipe<CriticalSectionRawMutex, 256> = Pipe::new();
static RX_DROPPED: AtomicU32 = AtomicU32::new(0);

fn read(reg: usize) -> u32 {
    // SAFETY: a register of UART0, mapped by the board.
    unsafe { read_volatile(reg as *const u32) }
}

fn write(reg: usize, value: u32) {
    // SAFETY: a register of UART0, mapped by the board.
    unsafe { write_volatile(reg as *mut u32, value) }
}

/// Enables UART0 at 115,200 baud (QEMU ignores the rate but sends nothing while BAUDDIV < 16) with its
/// receive interrupt.
pub fn init() {
    write(BAUDDIV, crate::SYSCLK_HZ / 115_200);
    write(CTRL, CTRL_TX_EN | CTRL_RX_EN | CTRL_RX_INTEN);
    // SAFETY: the handler (`on_rx_interrupt`) shares only the pipe and an atomic with the tasks.
    unsafe { cortex_m::peripheral::NVIC::unmask(crate::Irq(UART0_RX_IRQ)) };
}

/// The RX interrupt's work (called from the board's `DefaultHandler`).
pub fn on_rx_interrupt() {
    write(INTCLEAR, INT_RX);
    loop {
        let state = read(STATE);
        if state & STATE_RXOVERRUN != 0 {
            write(STATE, STATE_RXOVERRUN); // write-one-to-clear
            RX_DROPPED.fetch_add(1, Ordering::Relaxed);
        }
        if state & STATE_RXFULL == 0 {
            break;
        }
        let byte = read(DATA) as u8;
        if RX.try_write(&[byte]).is_err() {
            RX_DROPPED.fetch_add(1, Ordering::Relaxed);
        }
    }
}

/// Waits for the next received byte. Cancel-safe: a byte is taken from the pipe only when this completes.
pub async fn read_byte() -> u8 {
    let mut b = [0u8; 1];
    RX.read(&mut b).await;
    b[0]
}

/// Writes `bytes`, waiting while the transmitter is full.
pub fn write_all(bytes: &[u8]) {
    for &b in bytes {
        while read(STATE) & STATE_TXFULL != 0 {}
        write(DATA, u32::from(b));
    }
}

/// Bytes dropped on receive so far (pipe full or UART overrun).
pub fn rx_dropped() -> u32 {
    RX_DROPPED.load(Ordering::Relaxed)
}

/// `core::fmt` on UART0, for the bench's report.
pub struct Writer;

impl core::fmt::Write for Writer {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        write_all(s.as_bytes());
        Ok(())
    }
}
