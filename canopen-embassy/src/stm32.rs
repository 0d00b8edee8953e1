//! The driver's `CanTx`/`CanRx` on embassy-stm32's CAN peripherals (feature `stm32`).
//!
//! The controller's state reaches the node through [`ReportState`](crate::bus_state::ReportState) around
//! [`Stm32CanRx`], with a probe of the status register: on bxCAN the ESR flags (`embassy_stm32::pac::CAN1.esr()`,
//! see `examples/firmware`), on FDCAN [`fdcan_error_mode`].
//!
//! embassy-stm32 exposes the same split halves, `can::CanTx` and `can::CanRx`, for both of its CAN
//! drivers: bxCAN (STM32F0/F1/F2/F3/F4/F7/L4) and FDCAN (STM32G0/G4/H5/H7/U5, used here with classic
//! frames). One adapter serves both; the chip (and so the driver) is chosen by the application's
//! embassy-stm32 feature. CI builds it for an STM32F446 (bxCAN) and an STM32G474 (FDCAN).

use canopen_core::driver::{CanRx, CanTx, Received};
use canopen_core::CanFrame;
use embassy_stm32::can;

#[cfg(feature = "stm32-fdcan")]
use crate::bus_state::ErrorMode;

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

    /// The frames alone, as the default does, but written out: the default is an `async` block around
    /// [`receive`](CanRx::receive), one state machine more in the driver's task (footprint.sh, minimal:
    /// 28 B). [`ReportState`](crate::bus_state::ReportState) calls `receive`, so the node build is unchanged.
    async fn receive_event(&mut self) -> Result<Received, Self::Error> {
        loop {
            // As `receive`: 29-bit frames skipped (CAN-01), cancel-safe like each `read`.
            if let Some(f) = CanFrame::from_frame(&self.0.read().await?.frame) {
                return Ok(Received::Frame(f));
            }
        }
    }
}

/// The FDCAN controller's error mode (feature `stm32-fdcan`, FDCAN parts only), for
/// [`ReportState`](crate::bus_state::ReportState): `ReportState::new(Stm32CanRx(rx), move ||
/// fdcan_error_mode(&properties))` with the properties of `Can::split`. FDCAN has no warning flag in this
/// API: the mode is active, passive or bus-off.
#[cfg(feature = "stm32-fdcan")]
pub fn fdcan_error_mode(properties: &can::Properties) -> ErrorMode {
    match properties.bus_error_mode() {
        can::enums::BusErrorMode::ErrorActive => ErrorMode::Active,
        can::enums::BusErrorMode::ErrorPassive => ErrorMode::Passive,
        can::enums::BusErrorMode::BusOff => ErrorMode::BusOff,
    }
}
