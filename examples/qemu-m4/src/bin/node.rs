//! The canopener node of `examples/firmware` (`node`: node-ID 5, the same dictionary, PDO defaults and
//! services: NMT, heartbeat producer 1017h = 1000 ms and 4 consumers, SDO server with block transfer, 4 RPDOs
//! and 4 TPDOs with dynamic mapping, SYNC, EMCY with the 1003h history, TIME) on QEMU's `mps2-an386`, its CAN
//! frames as slcan lines on UART0 (`canopen_qemu_m4::link`). What differs from the STM32 board:
//!
//! - parameters are stored in RAM (`RamStorage`): 1010h "save" survives NMT resets, not a power cycle;
//! - there is no button and no LED: output 6200h:01 is wired back to input 6000h:01 (a loopback), so an
//!   RPDO or SDO write to the output makes the input change and the event-driven TPDO 1 carry it, and 2101h
//!   counts the input's rising edges;
//! - two objects of ours: 2103h, the stack's high-water mark in bytes (painted at boot, read back every
//!   second), and 2104h, the slcan lines skipped as bad (plus 29-bit frames ignored).
#![no_std]
#![no_main]

use canopen_core::driver::{self, Shared};
use canopen_core::pdo::PdoDefault;
use canopen_core::profile::{Identity, NodeConfig};
use canopen_core::storage::RamStorage;
use canopen_core::Sizes;
use canopen_core::{Event, Node, NodeId};
use canopen_embassy::{AppWake, EmbassyClock, NodeCell};
use canopen_od_derive::ObjectDictionary;
use canopen_qemu_m4::link::{SlcanRx, SlcanTx};
use canopen_qemu_m4::{stack, time_driver, uart};
use embassy_executor::Spawner;
use embassy_time::{Duration, Ticker};
use static_cell::StaticCell;

/// The application's object dictionary: `examples/firmware`'s, plus 2103h and 2104h.
#[derive(ObjectDictionary)]
struct Device {
    /// 6000h: digital inputs, 8 bits per sub-index (here: the outputs, looped back).
    #[od(index = 0x6000, sub = 1..=1, access = "ro", pdo = "tpdo", name = "Read input 8-bit")]
    inputs: [u8; 1],
    /// 6200h: digital outputs.
    #[od(index = 0x6200, sub = 1..=1, access = "rw", pdo = "rpdo", default = 0, name = "Write output 8-bit")]
    outputs: [u8; 1],
    /// 2001h: a set-point with limits.
    #[od(index = 0x2001, access = "rw", pdo = "rpdo", min = -1000, max = 1000, default = 0)]
    setpoint: i16,
    /// 2002h: LED blink period in 10 ms ticks (kept for the same dictionary; there is no LED).
    #[od(index = 0x2002, access = "rw", pdo = "rpdo", default = 0, name = "Blink period")]
    blink_ticks: u16,
    /// 2100h: seconds since power-on, kept by the process task.
    #[od(index = 0x2100, access = "ro", pdo = "tpdo", name = "Uptime")]
    uptime_s: u32,
    /// 2101h: rising edges of input 0 since power-on.
    #[od(index = 0x2101, access = "ro", pdo = "tpdo", name = "Button presses")]
    presses: u16,
    /// 2102h: milliseconds after midnight of the last TIME message received (TIME consumer).
    #[od(index = 0x2102, access = "ro", pdo = "tpdo", name = "Time of day ms")]
    time_ms: u32,
    /// 2103h: the stack's high-water mark in bytes since boot.
    #[od(index = 0x2103, access = "ro", name = "Stack high-water mark")]
    stack_high_water: u32,
    /// 2104h: slcan lines skipped as bad (garbage, over-long, a lost CR) plus 29-bit frames ignored.
    #[od(index = 0x2104, access = "ro", name = "slcan lines skipped")]
    slcan_skipped: u32,
}

/// As `examples/firmware`: 4 heartbeat consumers, queues of 8, 4 RPDOs, 4 TPDOs.
type DeviceNode = Node<Device, Sizes<4, 8, 8, 4, 4>, RamStorage<2048>>;

const NODE_ID: u8 = 5;

const RPDO1: PdoDefault = PdoDefault { transmission_type: 255, mapping: &[0x6200_0108], ..PdoDefault::EVENT };
const RPDO2: PdoDefault = PdoDefault { transmission_type: 255, mapping: &[0x2001_0010], ..PdoDefault::EVENT };
const RPDO3: PdoDefault =
    PdoDefault { transmission_type: 1, mapping: &[0x6200_0108, 0x2001_0010, 0x2002_0010], ..PdoDefault::EVENT };
const RPDO4: PdoDefault = PdoDefault { mapping: &[0x2002_0010], ..PdoDefault::UNUSED };
const TPDO1: PdoDefault = PdoDefault { mapping: &[0x6000_0108], ..PdoDefault::EVENT };
const TPDO2: PdoDefault =
    PdoDefault { event_timer_ms: 1000, mapping: &[0x2100_0020, 0x2101_0010], ..PdoDefault::EVENT };
const TPDO3: PdoDefault =
    PdoDefault { transmission_type: 1, mapping: &[0x6000_0108, 0x2101_0010, 0x2001_0010], ..PdoDefault::EVENT };
const TPDO4: PdoDefault =
    PdoDefault { transmission_type: 10, mapping: &[0x2102_0020, 0x2100_0020], ..PdoDefault::EVENT };

const CONFIG: NodeConfig = NodeConfig {
    device_type: 0x0003_0191, // CiA 401, digital inputs and outputs
    identity: Identity { vendor_id: 0, product_code: 0x386, revision: 0x0001_0000, serial: 1 },
    device_name: "canopener QEMU AN386",
    hardware_version: "QEMU mps2-an386",
    software_version: env!("CARGO_PKG_VERSION"),
    heartbeat_time_ms: 1000,
    rpdo: &[RPDO1, RPDO2, RPDO3, RPDO4],
    tpdo: &[TPDO1, TPDO2, TPDO3, TPDO4],
    ..NodeConfig::DEFAULT
};

static NODE: StaticCell<NodeCell<DeviceNode>> = StaticCell::new();
static WAKE: AppWake = AppWake::new();

#[embassy_executor::main]
async fn main(spawner: Spawner) {
    stack::paint();
    let Some(core) = cortex_m::Peripherals::take() else { return };
    time_driver::init(core.SYST);
    uart::init();

    let device = Device {
        inputs: [0],
        outputs: [0],
        setpoint: 0,
        blink_ticks: 0,
        uptime_s: 0,
        presses: 0,
        time_ms: 0,
        stack_high_water: 0,
        slcan_skipped: 0,
    };
    let Some(id) = NodeId::new(NODE_ID) else { return };
    let node: &'static NodeCell<DeviceNode> =
        NODE.init_with(|| NodeCell::new(Node::with_storage(id, CONFIG, device, RamStorage::new())));
    spawner.spawn(process(node).unwrap());
    spawner.spawn(canopen(node).unwrap());
}

/// Runs the node on the slcan link (whose halves never fail).
#[embassy_executor::task]
async fn canopen(node: &'static NodeCell<DeviceNode>) {
    let (mut rx, mut tx, mut clock) = (SlcanRx::new(), SlcanTx, EmbassyClock);
    let Err(_never) = driver::run(node, &mut rx, &mut tx, &mut clock, &WAKE, |e| on_event(node, e)).await;
}

fn on_event(node: &NodeCell<DeviceNode>, event: Event) {
    if let Event::Time(t) = event {
        node.lock(|n| n.app_mut().time_ms = t.ms);
    }
}

/// Every 10 ms: the loopback from output to input (TPDO 1 on a change), uptime; every second the stack's
/// high-water mark and the slcan counter.
#[embassy_executor::task]
async fn process(node: &'static NodeCell<DeviceNode>) {
    let mut ticker = Ticker::every(Duration::from_millis(10));
    let mut ticks: u32 = 0;
    loop {
        ticker.next().await;
        ticks = ticks.wrapping_add(1);
        let second = ticks % 100 == 0;
        let high_water = if second { stack::high_water() } else { 0 };
        let sent = node.lock(|n| {
            let app = n.app_mut();
            let inputs = app.outputs[0];
            let changed = app.inputs[0] != inputs;
            if changed && inputs & !app.inputs[0] & 1 != 0 {
                app.presses = app.presses.wrapping_add(1);
            }
            app.inputs[0] = inputs;
            app.uptime_s = ticks / 100;
            if second {
                app.stack_high_water = high_water;
                app.slcan_skipped = canopen_qemu_m4::link::skipped();
            }
            changed && n.trigger_tpdo(0)
        });
        if sent {
            WAKE.signal();
        }
    }
}
