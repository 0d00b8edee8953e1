//! Type-checks canopen-embassy on an FDCAN part: the driver on `Stm32CanTx`/`Stm32CanRx` of
//! embassy-stm32's FDCAN halves, `EmbassyClock`, `NodeCell`, `AppWake`, and `FlashStorage` on the G4's
//! blocking flash (4 KB pages in single-bank mode, 8-byte program words).
#![no_std]

use canopen_core::driver::{self, DriverError};
use canopen_core::node::NoApplication;
use canopen_core::{Node, Sizes};
use canopen_embassy::bus_state::ReportState;
use canopen_embassy::flash::FlashStorage;
use canopen_embassy::stm32::{fdcan_error_mode, Stm32CanRx, Stm32CanTx};
use canopen_embassy::{AppWake, EmbassyClock, NodeCell};
use embassy_stm32::can::CanConfigurator;
use embassy_stm32::flash::{Blocking, Flash};

/// A node keeping its parameters in the last three 4 KB pages of the G474's 512 KB flash.
pub type FlashNode = Node<NoApplication, Sizes, FlashStorage<Flash<'static, Blocking>>>;

/// The storage layout: two pages for the A/B slots, one for the LSS configuration.
pub fn storage(flash: Flash<'static, Blocking>) -> Option<FlashStorage<Flash<'static, Blocking>>> {
    FlashStorage::new(flash, 0x7_D000..0x7_E000, 0x7_E000..0x7_F000).and_then(|s| s.with_lss(0x7_F000..0x8_0000)).ok()
}

/// Runs `node` on an FDCAN peripheral in classic mode; the controller's state reaches the node.
pub async fn run(
    can: CanConfigurator<'static>,
    node: &NodeCell<FlashNode>,
    wake: &AppWake,
) -> DriverError<embassy_stm32::can::enums::BusError, core::convert::Infallible> {
    let can = can.into_normal_mode();
    let (tx, rx, properties) = can.split();
    let (mut tx, mut rx) = (Stm32CanTx(tx), ReportState::new(Stm32CanRx(rx), move || fdcan_error_mode(&properties)));
    let Err(e) = driver::run(node, &mut rx, &mut tx, &mut EmbassyClock, wake, |_| {}).await;
    e
}
