//! A CANopen node on an STM32F446RE (bxCAN CAN1 on PA11/PA12, 250 kbit/s) with embassy: node-ID 5, NMT,
//! heartbeat producer (1017h, 1000 ms) and a 4-entry heartbeat consumer (1016h, configured by SDO), an SDO
//! server with block transfer, and the application dictionary as a derived struct.
//!
//! Two tasks share the node (see the crate docs for the glue types):
//!
//! - `canopen` runs `canopen_core::driver::run` on the CAN halves and `embassy-time`;
//! - `process` samples the inputs every 10 ms, writes them into the dictionary struct under the node's lock,
//!   drives the output from what the bus wrote (SDO today, RPDO later), and signals the driver when an input
//!   changed, which is where an event-driven TPDO will be triggered.
//!
//! The node lives in a `static` (`StaticCell`), so its RAM is in `.bss` and counted by
//! `scripts/footprint.sh`. The PDO, SYNC, EMCY-history and TIME parts of the reference feature set land in
//! the core separately; the places they plug in are marked `PDO:` below.
#![no_std]
#![no_main]

use canopen_core::comm::{Identity, NodeConfig};
use canopen_core::driver::{self, Shared};
use canopen_core::{Event, NmtState, Node, NodeId};
use canopen_firmware::{AppWake, BxCanRx, BxCanTx, EmbassyClock, NodeCell};
use canopen_od_derive::ObjectDictionary;
use embassy_executor::Spawner;
use embassy_stm32::bind_interrupts;
use embassy_stm32::can::filter::Mask32;
use embassy_stm32::can::{
    Can, Fifo, Rx0InterruptHandler, Rx1InterruptHandler, SceInterruptHandler, TxInterruptHandler,
};
use embassy_stm32::gpio::{Input, Level, Output, Pull, Speed};
use embassy_stm32::peripherals::CAN1;
use embassy_time::{Duration, Ticker, Timer};
use static_cell::StaticCell;

bind_interrupts!(struct Irqs {
    CAN1_RX0 => Rx0InterruptHandler<CAN1>;
    CAN1_RX1 => Rx1InterruptHandler<CAN1>;
    CAN1_SCE => SceInterruptHandler<CAN1>;
    CAN1_TX => TxInterruptHandler<CAN1>;
});

/// The application's object dictionary: the process values live here, the node serves them by SDO (and by
/// PDO once the core has it: the `pdo =` keys already mark what is mappable).
#[derive(ObjectDictionary)]
struct Device {
    /// 6000h: digital inputs, 8 bits per sub-index.
    #[od(index = 0x6000, sub = 1..=1, access = "ro", pdo = "tpdo", name = "Read input 8-bit")]
    inputs: [u8; 1],
    /// 6200h: digital outputs.
    #[od(index = 0x6200, sub = 1..=1, access = "rw", pdo = "rpdo", default = 0, name = "Write output 8-bit")]
    outputs: [u8; 1],
    /// 2001h: a set-point with limits.
    #[od(index = 0x2001, access = "rw", pdo = "rpdo", min = -1000, max = 1000, default = 0)]
    setpoint: i16,
    /// 2100h: seconds since power-on, kept by the process task.
    #[od(index = 0x2100, access = "ro", pdo = "tpdo", name = "Uptime")]
    uptime_s: u32,
}

/// NMT + heartbeat producer + 4 heartbeat consumers + SDO server (with block transfer), queues of 16.
/// PDO: the RPDO/TPDO counts become const generics here.
type DeviceNode = Node<Device, 4, 16, 16>;

const NODE_ID: u8 = 5;
const BITRATE: u32 = 250_000;
const CONFIG: NodeConfig = NodeConfig {
    device_type: 0x0003_0191, // CiA 401, digital inputs and outputs
    identity: Identity { vendor_id: 0, product_code: 0x446, revision: 0x0001_0000, serial: 1 },
    device_name: "canopen-rs F446",
    hardware_version: "NUCLEO-F446RE",
    software_version: env!("CARGO_PKG_VERSION"),
    heartbeat_time_ms: 1000,
    ..NodeConfig::DEFAULT
};

static NODE: StaticCell<NodeCell<DeviceNode>> = StaticCell::new();
static WAKE: AppWake = AppWake::new();

#[embassy_executor::main]
async fn main(spawner: Spawner) {
    let p = embassy_stm32::init(Default::default());

    let mut can = Can::new(p.CAN1, p.PA11, p.PA12, Irqs);
    can.modify_filters().enable_bank(0, Fifo::Fifo0, Mask32::accept_all());
    can.modify_config().set_bitrate(BITRATE).set_automatic_retransmit(true);
    can.enable().await;

    let Some(id) = NodeId::new(NODE_ID) else { return };
    let device = Device { inputs: [0], outputs: [0], setpoint: 0, uptime_s: 0 };
    let node: &'static NodeCell<DeviceNode> = NODE.init(NodeCell::new(Node::new(id, CONFIG, device)));

    let button = Input::new(p.PC13, Pull::None);
    let led = Output::new(p.PA5, Level::Low, Speed::Low);
    spawner.spawn(process(node, button, led).unwrap());
    spawner.spawn(canopen(can, node).unwrap());
}

/// Runs the node. A receive error (a bus error reported by the controller) returns from `driver::run`
/// with the node intact in `NODE`; the task waits a little and runs it again.
#[embassy_executor::task]
async fn canopen(mut can: Can<'static>, node: &'static NodeCell<DeviceNode>) {
    let (tx, rx) = can.split();
    let (mut tx, mut rx, mut clock) = (BxCanTx(tx), BxCanRx(rx), EmbassyClock);
    loop {
        let Err(_error) = driver::run(node, &mut rx, &mut tx, &mut clock, &WAKE, on_event).await;
        Timer::after(Duration::from_millis(10)).await;
    }
}

/// The node's events, outside the lock. PDO: an RPDO-written event lands here too.
fn on_event(event: Event) {
    match event {
        Event::StateChanged { to: NmtState::Operational, .. } => {}
        Event::Heartbeat(_) | Event::SdoAborted { .. } | Event::ObjectWritten { .. } => {}
        _ => {}
    }
}

/// The application: samples the inputs into the dictionary, applies the outputs the bus wrote.
#[embassy_executor::task]
async fn process(node: &'static NodeCell<DeviceNode>, button: Input<'static>, mut led: Output<'static>) {
    let mut ticker = Ticker::every(Duration::from_millis(10));
    // Uptime counted in ticks: `Instant::elapsed().as_secs()` would link a 64-bit division (~1 KB of flash).
    let mut ticks: u32 = 0;
    loop {
        ticker.next().await;
        ticks = ticks.wrapping_add(1);
        let inputs = u8::from(button.is_low());
        let uptime_s = ticks / 100;
        let (changed, outputs) = node.lock(|n| {
            let app = n.app_mut();
            let changed = app.inputs[0] != inputs;
            app.inputs[0] = inputs;
            app.uptime_s = uptime_s;
            // PDO: `if changed { n.trigger_tpdo(0) }` (event-driven TPDO 1 mapping 6000h:01).
            (changed, app.outputs[0])
        });
        if changed {
            WAKE.signal(); // the driver sends what was queued now, not at the next deadline
        }
        led.set_level(Level::from(outputs & 1 != 0));
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    cortex_m::asm::udf()
}
