//! The footprint baseline: the same chip, clocks, CAN set-up, executor, time driver and GPIO as
//! `node.rs`, with two tasks of the same shape, but no CANopen: it echoes every received frame and a
//! `process` task samples the same pins. `scripts/footprint.sh` subtracts this binary from the node binary,
//! so what remains is the stack's own cost (core + derived dictionary + glue + the node's RAM).
#![no_std]
#![no_main]

use embassy_executor::Spawner;
use embassy_stm32::bind_interrupts;
use embassy_stm32::can::filter::Mask32;
use embassy_stm32::can::{
    Can, Fifo, Rx0InterruptHandler, Rx1InterruptHandler, SceInterruptHandler, TxInterruptHandler,
};
use embassy_stm32::gpio::{Input, Level, Output, Pull, Speed};
use embassy_stm32::peripherals::CAN1;
use embassy_time::{Duration, Ticker, Timer};

bind_interrupts!(struct Irqs {
    CAN1_RX0 => Rx0InterruptHandler<CAN1>;
    CAN1_RX1 => Rx1InterruptHandler<CAN1>;
    CAN1_SCE => SceInterruptHandler<CAN1>;
    CAN1_TX => TxInterruptHandler<CAN1>;
});

const BITRATE: u32 = 250_000;

#[embassy_executor::main]
async fn main(spawner: Spawner) {
    let p = embassy_stm32::init(Default::default());

    let mut can = Can::new(p.CAN1, p.PA11, p.PA12, Irqs);
    can.modify_filters().enable_bank(0, Fifo::Fifo0, Mask32::accept_all());
    can.modify_config().set_bitrate(BITRATE).set_automatic_retransmit(true);
    can.enable().await;

    let button = Input::new(p.PC13, Pull::None);
    let led = Output::new(p.PA5, Level::Low, Speed::Low);
    spawner.spawn(process(button, led).unwrap());
    spawner.spawn(echo(can).unwrap());
}

/// Echoes every frame; after a bus error waits a little, as the node's driver task does.
#[embassy_executor::task]
async fn echo(mut can: Can<'static>) {
    let (mut tx, mut rx) = can.split();
    loop {
        match rx.read().await {
            Ok(envelope) => {
                tx.write(&envelope.frame).await;
            }
            Err(_) => Timer::after(Duration::from_millis(10)).await,
        }
    }
}

/// Samples the button every 10 ms and mirrors it on the LED.
#[embassy_executor::task]
async fn process(button: Input<'static>, mut led: Output<'static>) {
    let mut ticker = Ticker::every(Duration::from_millis(10));
    loop {
        ticker.next().await;
        led.set_level(Level::from(button.is_low()));
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    cortex_m::asm::udf()
}
