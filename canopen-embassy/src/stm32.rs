//! The driver's `CanTx`/`CanRx` on embassy-stm32's CAN peripherals (feature `stm32`).
//!
//! embassy-stm32 exposes the same split halves, `can::CanTx` and `can::CanRx`, for both of its CAN
//! drivers: bxCAN (STM32F0/F1/F2/F3/F4/F7/L4) and FDCAN (STM32G0/G4/H5/H7/U5, used here with classic
//! frames). One adapter serves both; the chip (and so the driver) is chosen by the application's
//! embassy-stm32 feature. CI builds it for an STM32F446 (bxCAN) and an STM32G474 (FDCAN).

#[cfg(feature = "stm32-fdcan")]
use canopen_core::bus::BusState;
#[cfg(feature = "stm32-fdcan")]
use canopen_core::driver::Received;
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

/// The receive half of an STM32 FDCAN peripheral that also reports the controller's state (feature
/// `stm32-fdcan`, for G0/G4/H5/H7/U5 parts): after every frame or bus error it reads the error mode
/// (`Properties::bus_error_mode`) and, when it changed, hands the driver a [`BusState`] first (EMCY 8120h on
/// error passive, bus-off as a communication error for 1029h:01, 8140h after the recovery: see
/// [`canopen_core::bus`]). A frame that came with the change is kept and delivered next, so nothing is lost,
/// and protocol errors without a change of state (a stuff or CRC error) do not end the driver: the controller
/// counts them, and the state shows when they matter.
#[cfg(feature = "stm32-fdcan")]
pub struct Stm32FdcanRx<'d> {
    rx: can::CanRx<'d>,
    properties: can::Properties,
    /// The last error mode seen: 0 error active, 1 error passive, 2 bus-off.
    mode: u8,
    held: Option<CanFrame>,
}

#[cfg(feature = "stm32-fdcan")]
impl<'d> Stm32FdcanRx<'d> {
    /// The receive half and the properties of `Can::split`.
    pub fn new(rx: can::CanRx<'d>, properties: can::Properties) -> Self {
        Stm32FdcanRx { rx, properties, mode: 0, held: None }
    }

    /// The controller's error mode, and the state to report when it changed.
    fn state(&mut self) -> Option<BusState> {
        let mode = match self.properties.bus_error_mode() {
            can::enums::BusErrorMode::ErrorActive => 0,
            can::enums::BusErrorMode::ErrorPassive => 1,
            can::enums::BusErrorMode::BusOff => 2,
        };
        let before = core::mem::replace(&mut self.mode, mode);
        match (before, mode) {
            (b, m) if b == m => None,
            (2, 0) => Some(BusState::Recovered),
            (_, 0) => Some(BusState::ErrorActive),
            (_, 1) => Some(BusState::ErrorPassive),
            _ => Some(BusState::BusOff),
        }
    }
}

#[cfg(feature = "stm32-fdcan")]
impl CanRx for Stm32FdcanRx<'_> {
    type Error = can::enums::BusError;

    /// Frames only (what [`Stm32CanRx`] does); the driver calls [`receive_event`](CanRx::receive_event).
    async fn receive(&mut self) -> Result<CanFrame, Self::Error> {
        loop {
            if let Some(f) = self.held.take() {
                return Ok(f);
            }
            let envelope = self.rx.read().await?;
            if let Some(f) = CanFrame::from_frame(&envelope.frame) {
                return Ok(f);
            }
        }
    }

    async fn receive_event(&mut self) -> Result<Received, Self::Error> {
        if let Some(f) = self.held.take() {
            return Ok(Received::Frame(f));
        }
        loop {
            // Cancel-safe: `read` is, and what it returned is stored before anything else can be dropped.
            let frame = match self.rx.read().await {
                Ok(envelope) => CanFrame::from_frame(&envelope.frame), // 29-bit: None (CAN-01)
                Err(_) => None,
            };
            if let Some(state) = self.state() {
                self.held = frame;
                return Ok(Received::Bus(state));
            }
            if let Some(f) = frame {
                return Ok(Received::Frame(f));
            }
        }
    }
}
