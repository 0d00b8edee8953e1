//! The minimal device of issue 13 on the same board as `node.rs`: NMT, heartbeat producer (1017h, 1000 ms),
//! the SDO server with expedited and segmented transfer (no block transfer), 4 RPDOs and 4 TPDOs with the
//! fixed mapping of `src/pdo_defaults.rs` but TPDO 4 (1600h+/1A00h+ are const, PDO-30), the SYNC consumer,
//! and EMCY (1014h) with the error register 1001h. No heartbeat consumer
//! (1016h has no entries), no SYNC producer, no TPDO remote requests, no LSS, TIME, node guarding, SDO client
//! or SDO block transfer, PDO mapping of whole objects of whole bytes only (the EDS's Granularity=8, no
//! bit-granular entries), and none of the objects CiA 301 makes optional for these services: no 1003h error
//! history, 1007h SYNC window, 1008h–100Ah strings, 1015h EMCY inhibit time, 1019h SYNC counter or 1029h
//! error behaviour (a communication error in Operational leads to Pre-operational, 1029h's default), and no
//! 1010h/1011h store/restore (the device has no parameter storage).
//! canopen-core is built without its optional features (`cargo build --release --no-default-features
//! --features minimal --bin minimal`, which `scripts/footprint.sh` runs), so none of them is in the image.
//!
//! The application is `node.rs`'s without the TIME object: the same tasks, glue and process values.
#![no_std]
#![no_main]

use canopen_core::driver::{self, Shared};
use canopen_core::pdo::PdoDefault;
use canopen_core::profile::{Identity, NodeConfig};
use canopen_core::Sizes;
use canopen_core::{Event, NmtState, Node, NodeId};
use canopen_embassy::stm32::{Stm32CanRx, Stm32CanTx};
use canopen_embassy::{AppWake, EmbassyClock, NodeCell};
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

#[path = "../pdo_defaults.rs"]
#[allow(dead_code)] // TPDO4 is `node`'s: this build has no TIME consumer and its own TPDO 4
mod pdo_defaults;
use pdo_defaults::{RPDO1, RPDO2, RPDO3, RPDO4, TPDO1, TPDO2, TPDO3};

bind_interrupts!(struct Irqs {
    CAN1_RX0 => Rx0InterruptHandler<CAN1>;
    CAN1_RX1 => Rx1InterruptHandler<CAN1>;
    CAN1_SCE => SceInterruptHandler<CAN1>;
    CAN1_TX => TxInterruptHandler<CAN1>;
});

/// The application's object dictionary: the process values live here, the node serves them by SDO and PDO
/// (the `pdo =` keys say what may be mapped).
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
    /// 2002h: LED blink period in 10 ms ticks (0 = the LED follows 6200h:01 bit 0).
    #[od(index = 0x2002, access = "rw", pdo = "rpdo", default = 0, name = "Blink period")]
    blink_ticks: u16,
    /// 2100h: seconds since power-on, kept by the process task.
    #[od(index = 0x2100, access = "ro", pdo = "tpdo", name = "Uptime")]
    uptime_s: u32,
    /// 2101h: button presses since power-on.
    #[od(index = 0x2101, access = "ro", pdo = "tpdo", name = "Button presses")]
    presses: u16,
}

/// NMT + heartbeat producer + SDO server + 4 RPDOs + 4 TPDOs, no heartbeat consumer, transmit and event
/// queues of 8 (as `node.rs`).
type DeviceNode = Node<Device, Sizes<0, 8, 8, 4, 4>>;

const NODE_ID: u8 = 5;
const BITRATE: u32 = 250_000;

/// TPDO 4: uptime, every 10th SYNC.
const TPDO4: PdoDefault = PdoDefault { transmission_type: 10, mapping: &[0x2100_0020], ..PdoDefault::EVENT };

/// No device name or versions: they feed 1008h–100Ah, which this build leaves out. (Strings set here would
/// still be in the image, 36 B: the node keeps its `NodeConfig`, which `Node::config` returns.)
const CONFIG: NodeConfig = NodeConfig {
    device_type: 0x0003_0191, // CiA 401, digital inputs and outputs
    identity: Identity { vendor_id: 0, product_code: 0x446, revision: 0x0001_0000, serial: 1 },
    heartbeat_time_ms: 1000,
    rpdo: &[RPDO1, RPDO2, RPDO3, RPDO4],
    tpdo: &[TPDO1, TPDO2, TPDO3, TPDO4],
    ..NodeConfig::DEFAULT // SYNC consumer on 80h, EMCY on 80h + node
};

/// EMCY 8100h: communication, generic (a bus error reported by the controller).
const EMCY_BUS_ERROR: u16 = 0x8100;

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
    let device = Device { inputs: [0], outputs: [0], setpoint: 0, blink_ticks: 0, uptime_s: 0, presses: 0 };
    // Built inside `init_with`, as in node.rs: fewer copies through the stack (56 B of flash).
    let node: &'static NodeCell<DeviceNode> = NODE.init_with(|| NodeCell::new(Node::new(id, CONFIG, device)));

    let button = Input::new(p.PC13, Pull::None);
    let led = Output::new(p.PA5, Level::Low, Speed::Low);
    spawner.spawn(process(node, button, led).unwrap());
    spawner.spawn(canopen(can, node).unwrap());
}

/// Runs the node. A receive error (a bus error reported by the controller) returns from `driver::run`
/// with the node intact in `NODE`: the task raises EMCY 8100h (queued, with its 1003h history entry), waits a
/// little and runs the driver again, which sends the EMCY; the error is cleared once the bus works again.
#[embassy_executor::task]
async fn canopen(mut can: Can<'static>, node: &'static NodeCell<DeviceNode>) {
    let (tx, rx) = can.split();
    let (mut tx, mut rx, mut clock) = (Stm32CanTx(tx), Stm32CanRx(rx), EmbassyClock);
    loop {
        let Err(_error) = driver::run(node, &mut rx, &mut tx, &mut clock, &WAKE, |e| on_event(node, e)).await;
        node.lock(|n| n.raise_error(EMCY_BUS_ERROR, [0; 5]));
        Timer::after(Duration::from_millis(10)).await;
    }
}

/// The node's events, outside the lock.
fn on_event(node: &NodeCell<DeviceNode>, event: Event) {
    match event {
        // A frame was received and handled: the bus works, so a bus error is over (EMCY 0000h if it was the
        // last active error).
        Event::RpdoReceived { .. } | Event::Sync { .. } => {
            node.lock(|n| n.clear_error(EMCY_BUS_ERROR));
        }
        // The outputs are applied by the process task on its next tick, whatever wrote them (SDO or RPDO);
        // another node's EMCY and an RPDO timeout need no local reaction here.
        Event::StateChanged { to: NmtState::Operational, .. } => {}
        Event::SdoAborted { .. } | Event::ObjectWritten { .. } => {}
        Event::Emergency { .. } | Event::RpdoTimeout { .. } => {}
        _ => {}
    }
}

/// The application: samples the inputs into the dictionary, applies the outputs the bus wrote, triggers the
/// event-driven TPDO 1 when the inputs changed.
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
        let (sent, level) = node.lock(|n| {
            let app = n.app_mut();
            let changed = app.inputs[0] != inputs;
            if changed && inputs != 0 {
                app.presses = app.presses.wrapping_add(1);
            }
            app.inputs[0] = inputs;
            app.uptime_s = uptime_s;
            let level = match app.blink_ticks {
                0 => app.outputs[0] & 1 != 0,
                p => (ticks / u32::from(p)) & 1 != 0,
            };
            // Event-driven TPDO 1 (6000h:01): sampled and queued now, or when its inhibit time ends.
            (changed && n.trigger_tpdo(0), level)
        });
        if sent {
            WAKE.signal(); // the driver sends what was queued now, not at the next deadline
        }
        led.set_level(Level::from(level));
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    cortex_m::asm::udf()
}
