//! The driver's `CanTx`/`CanRx` on embassy-stm32's CAN peripherals (feature `stm32`).
//!
//! embassy-stm32 exposes the same split halves, `can::CanTx` and `can::CanRx`, for both of its CAN
//! drivers: bxCAN (STM32F0/F1/F2/F3/F4/F7/L4) and FDCAN (STM32G0/G4/H5/H7/U5, used here with classic
//! frames). One adapter serves both; the chip (and so the driver) is chosen by the application's
//! embassy-stm32 feature. CI builds it for an STM32F446 (bxCAN) and an STM32G474 (FDCAN).

use canopen_core::driver::{CanRx, CanTx};
use canopen_core::CanFrame;
use embassy_stm32::can;

/// The transmit half of an STM32 CAN peripheral (bxCAN or FDCAN).
pub struct Stm32CanTx<'d>(pub can::CanTx<'d>);

impl CanTx for Stm32CanTx<'_> {
    type Error = core::convert::Infallible;

    /// Waits for a free mailbox (bxCAN) or TX buffer (FDCAN). A frame the HAL refuses to build cannot
    /// occur: the core produces only 11-bit identifiers and at most 8 bytes (CAN-01).
    async fn transmit(&mut self, frame: &CanFrame) -> Result<(), Self::Error> {
        if let Some(f) = frame.to_frame::<can::Frame>() {
            // bxCAN reports which mailbox was used, FDCAN a frame it displaced from a full queue of lower
            // priority; the core's frames are all queued in priority order already, so neither matters.
            let _ = self.0.write(&f).await;
        }
        Ok(())
    }
}

/// The receive half of an STM32 CAN peripheral (bxCAN or FDCAN).
pub struct Stm32CanRx<'d>(pub can::CanRx<'d>);

impl CanRx for Stm32CanRx<'_> {
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
