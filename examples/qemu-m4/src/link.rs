//! The node's CAN interface as an slcan link on UART0: the board plays a serial CAN adapter (CANable, USBtin)
//! with the node on its bus. Lines from the host go through `canopen-slcan`'s [`Decoder`] and [`Adapter`]:
//! commands get their answers (`O`, `C`, `S`n, `V`, `F` ...), frames on an open channel go to the node; the
//! node's frames go to the host as `t` lines while the channel is open and are dropped (and counted) while
//! it is closed, as a real adapter's bus frames are.
//!
//! Bad input (garbage, over-long lines, a lost `\r`) is skipped and counted by the decoder; 29-bit frames
//! (not CANopen, CAN-01) are counted too. [`skipped`] sums both for the dictionary (2104h).

use core::convert::Infallible;
use core::sync::atomic::{AtomicBool, AtomicU32, Ordering};

use canopen_core::driver::{CanRx, CanTx};
use canopen_core::CanFrame;
use canopen_slcan::{encode_frame, Adapter, Decoder, MAX_LINE};

static OPEN: AtomicBool = AtomicBool::new(false);
static SKIPPED: AtomicU32 = AtomicU32::new(0);
static DROPPED_CLOSED: AtomicU32 = AtomicU32::new(0);

/// Lines skipped as bad plus 29-bit frames ignored, since boot.
pub fn skipped() -> u32 {
    SKIPPED.load(Ordering::Relaxed)
}

/// The node's frames dropped because the host had not opened the channel.
pub fn dropped_while_closed() -> u32 {
    DROPPED_CLOSED.load(Ordering::Relaxed)
}

/// The receive half: bytes from the UART, frames to the node, answers back to the host.
pub struct SlcanRx {
    decoder: Decoder,
    adapter: Adapter,
    extended: u32,
}

impl SlcanRx {
    /// A closed channel; `V` answers hardware 1.0, software 0.1; `N` answers 0044h (issue 44).
    pub const fn new() -> Self {
        SlcanRx { decoder: Decoder::new(), adapter: Adapter::new(0x10, 0x01, 0x0044), extended: 0 }
    }
}

impl Default for SlcanRx {
    fn default() -> Self {
        Self::new()
    }
}

impl CanRx for SlcanRx {
    type Error = Infallible;

    /// Cancel-safe: the decoder's state lives in `self`, and a byte is consumed only when `read_byte`
    /// completes; between that and the return there is no await.
    async fn receive(&mut self) -> Result<CanFrame, Infallible> {
        loop {
            let byte = crate::uart::read_byte().await;
            let Some(line) = self.decoder.push(byte) else { continue };
            let reply = self.adapter.handle(line);
            OPEN.store(self.adapter.is_open(), Ordering::Relaxed);
            if let Some(answer) = reply.answer {
                let mut out = [0u8; MAX_LINE];
                let n = answer.encode(&mut out);
                crate::uart::write_all(&out[..n]);
            }
            let frame = reply.to_bus.and_then(|f| {
                let frame = CanFrame::from_frame(&f);
                self.extended = self.extended.wrapping_add(u32::from(frame.is_none()));
                frame
            });
            SKIPPED.store(self.decoder.counters().skipped().wrapping_add(self.extended), Ordering::Relaxed);
            if let Some(frame) = frame {
                return Ok(frame);
            }
        }
    }
}

/// The transmit half: the node's frames as `t`/`r` lines.
pub struct SlcanTx;

impl CanTx for SlcanTx {
    type Error = Infallible;

    async fn transmit(&mut self, frame: &CanFrame) -> Result<(), Infallible> {
        if OPEN.load(Ordering::Relaxed) {
            let mut out = [0u8; MAX_LINE];
            let n = encode_frame(frame, &mut out);
            crate::uart::write_all(&out[..n]);
        } else {
            DROPPED_CLOSED.fetch_add(1, Ordering::Relaxed);
        }
        Ok(())
    }
}
