//! A CANopen node on an STM32F446RE (bxCAN CAN1 on PA11/PA12, 250 kbit/s) with embassy: node-ID 5, the
//! reference feature set of DESIGN.md "Performance": NMT, heartbeat producer (1017h, 1000 ms) and a 4-entry
//! heartbeat consumer (1016h, configured by SDO), an SDO server with block transfer, 4 RPDOs and 4 TPDOs with
//! dynamic mapping (defaults in `src/pdo_defaults.rs`, remappable by SDO through 1600h/1A00h), the SYNC
//! consumer (1005h = 80h), EMCY with the 1003h error history, the TIME consumer (1012h = 8000_0100h), and the
//! application dictionary as a derived struct.
//!
//! Two tasks share the node (the glue types come from `canopen-embassy`):
//!
//! - `canopen` runs `canopen_core::driver::run` on the CAN halves and `embassy-time`; the receive half is
//!   wrapped in `canopen_embassy::bus_state::ReportState` with a probe of bxCAN's error status register
//!   (ESR), so the node hears the controller's state: EMCY 8120h on error passive (cleared on error active),
//!   bus-off as a communication error for 1029h:01, 8140h after the recovery;
//! - `process` samples the inputs every 10 ms, writes them into the dictionary struct under the node's lock,
//!   drives the output from what the bus wrote (SDO or RPDO), triggers the event-driven TPDO 1 when an input
//!   changed and signals the driver, which sends it at once.
//!
//! Parameters persist in flash (`canopen_embassy::flash::FlashStorage` on embassy-stm32's blocking `Flash`):
//! 1010h "save" writes them to the A/B pair of 128 KB sectors 6 and 7, 1011h "load" restores the defaults at
//! the next reset, and the LSS "store configuration" keeps the node-ID and bit rate in sector 5. At power-on
//! a stored LSS node-ID wins over `NODE_ID`, the factory default (CiA 305), and a stored bit rate over
//! `BITRATE`. The program itself must stay below sector 5 (0x0802_0000, 128 KB; it is about 40 KB).
//!
//! The node lives in a `static` (`StaticCell`), so its RAM is in `.bss` and counted by
//! `scripts/footprint.sh`.
#![no_std]
#![no_main]

use canopen_core::driver::{self, Shared};
#[cfg(feature = "store")]
use canopen_core::lss::LssEvent;
use canopen_core::profile::{Identity, NodeConfig};
use canopen_core::wire::lss::BitRate;
use canopen_core::Sizes;
use canopen_core::{Event, NmtState, Node, NodeId};
use canopen_embassy::bus_state::{ErrorMode, ReportState};
#[cfg(feature = "store")]
use canopen_embassy::flash::FlashStorage;
use canopen_embassy::stm32::{Stm32CanRx, Stm32CanTx};
use canopen_embassy::{AppWake, EmbassyClock, NodeCell};
use canopen_od_derive::ObjectDictionary;
use embassy_executor::Spawner;
use embassy_stm32::bind_interrupts;
use embassy_stm32::can::filter::Mask32;
use embassy_stm32::can::{
    Can, Fifo, Rx0InterruptHandler, Rx1InterruptHandler, SceInterruptHandler, TxInterruptHandler,
};
#[cfg(feature = "store")]
use embassy_stm32::flash::{Blocking, Flash};
use embassy_stm32::gpio::{Input, Level, Output, Pull, Speed};
use embassy_stm32::peripherals::CAN1;
use embassy_time::{Duration, Ticker, Timer};
use static_cell::StaticCell;

#[path = "../pdo_defaults.rs"]
mod pdo_defaults;
use pdo_defaults::{RPDO1, RPDO2, RPDO3, RPDO4, TPDO1, TPDO2, TPDO3, TPDO4};

bind_interrupts!(struct Irqs {
    CAN1_RX0 => Rx0InterruptHandler<CAN1>;
    CAN1_RX1 => Rx1InterruptHandler<CAN1>;
    CAN1_SCE => SceInterruptHandler<CAN1>;
    CAN1_TX => TxInterruptHandler<CAN1>;
});

/// The application's object dictionary: the process values live here, the node serves them by SDO and PDO
/// (the `pdo =` keys say what may be mapped).
///
/// With the feature `od-data` the derive emits it as data served by the core's one generic path
/// (`#[od(compact, zerocopy)]`: tables of rows, each value reached by its offset in the struct's bytes), so
/// `scripts/footprint.sh` measures that path's fixed cost as `node-data`. The fields are in an order without
/// padding for that (`#[repr(C)]`, zerocopy's `IntoBytes`); the default build's layout does not depend on it.
#[derive(ObjectDictionary)]
#[cfg_attr(feature = "od-data", derive(zerocopy::IntoBytes, zerocopy::FromBytes, zerocopy::Immutable))]
#[cfg_attr(feature = "od-data", od(compact, zerocopy), repr(C))]
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
    /// 2101h: button presses since power-on.
    #[od(index = 0x2101, access = "ro", pdo = "tpdo", name = "Button presses")]
    presses: u16,
    /// 2100h: seconds since power-on, kept by the process task.
    #[od(index = 0x2100, access = "ro", pdo = "tpdo", name = "Uptime")]
    uptime_s: u32,
    /// 2102h: milliseconds after midnight of the last TIME message received (TIME consumer).
    #[od(index = 0x2102, access = "ro", pdo = "tpdo", name = "Time of day ms")]
    time_ms: u32,
}

/// NMT + heartbeat producer + 4 heartbeat consumers + SDO server (with block transfer) + 4 RPDOs + 4 TPDOs,
/// transmit and event queues of 8: the driver drains both after every frame and every deadline, and the
/// largest burst one step makes is entering Operational or a SYNC (4 TPDOs, plus an EMCY or an SDO
/// response), so 16 only cost RAM (8 × 12 B of frames + 8 × 12 B of events).
type DeviceNode = Node<App, Sizes<4, 8, 8, 4, 4>, Store>;

/// The node's application dictionary: the device's objects, and with the feature `cia402` the CiA 402
/// drive's objects composed with them (6000h-67FFh served by `canopen_cia402::Drive`; the device's 6000h and
/// 6200h are then shadowed, which is fine for measuring what the drive part costs).
#[cfg(not(feature = "cia402"))]
type App = Device;
#[cfg(feature = "cia402")]
type App = canopen_cia402::Drive<Device>;

/// The device's own objects inside the application.
#[cfg(not(feature = "cia402"))]
fn device(app: &mut App) -> &mut Device {
    app
}
#[cfg(feature = "cia402")]
fn device(app: &mut App) -> &mut Device {
    &mut app.app
}

/// An open-loop stepper: the position is the demand (feature `cia402`).
#[cfg(feature = "cia402")]
#[derive(Default)]
struct Stepper {
    position: i32,
    velocity: i32,
    powered: bool,
}

#[cfg(feature = "cia402")]
impl canopen_cia402::Motor for Stepper {
    fn set_power(&mut self, on: bool) {
        self.powered = on;
    }
    fn follow(&mut self, demand: canopen_cia402::Demand, dt_us: u32) {
        use canopen_cia402::Demand;
        match demand {
            Demand::Off => self.velocity = 0,
            Demand::Position { position, velocity } => (self.position, self.velocity) = (position, velocity),
            Demand::Velocity(v) => {
                self.velocity = v;
                self.position = self.position.wrapping_add(((i64::from(v) * i64::from(dt_us)) / 1_000_000) as i32);
            }
        }
    }
    fn position(&self) -> i32 {
        self.position
    }
    fn velocity(&self) -> i32 {
        self.velocity
    }
}

/// Parameters and LSS configuration in the on-chip flash (feature `store`, on by default).
#[cfg(feature = "store")]
type Store = FlashStorage<Flash<'static, Blocking>>;
/// Without the feature `store`: the footprint reference set of DESIGN.md, which stores nothing.
#[cfg(not(feature = "store"))]
type Store = canopen_core::storage::NoStorage;

/// Flash sectors (offsets from the flash base) of the STM32F446RE: 5 for the LSS configuration, 6 and 7
/// for the two slots of the parameters (all 128 KB; embassy's blocking `Flash` erases in its largest
/// sector size).
#[cfg(feature = "store")]
const LSS_SECTOR: core::ops::Range<u32> = 0x2_0000..0x4_0000;
#[cfg(feature = "store")]
const SLOT_A: core::ops::Range<u32> = 0x4_0000..0x6_0000;
#[cfg(feature = "store")]
const SLOT_B: core::ops::Range<u32> = 0x6_0000..0x8_0000;

const NODE_ID: u8 = 5;
const BITRATE: u32 = 250_000;

const CONFIG: NodeConfig = NodeConfig {
    device_type: 0x0003_0191, // CiA 401, digital inputs and outputs
    identity: Identity { vendor_id: 0, product_code: 0x446, revision: 0x0001_0000, serial: 1 },
    device_name: "canopener F446",
    hardware_version: "NUCLEO-F446RE",
    software_version: env!("CARGO_PKG_VERSION"),
    heartbeat_time_ms: 1000,
    rpdo: &[RPDO1, RPDO2, RPDO3, RPDO4],
    tpdo: &[TPDO1, TPDO2, TPDO3, TPDO4],
    ..NodeConfig::DEFAULT // SYNC consumer on 80h, TIME consumer on 100h, EMCY on 80h + node
};

static NODE: StaticCell<NodeCell<DeviceNode>> = StaticCell::new();
static WAKE: AppWake = AppWake::new();

#[embassy_executor::main]
async fn main(spawner: Spawner) {
    let p = embassy_stm32::init(Default::default());

    #[cfg(feature = "store")]
    let Ok(mut store) =
        FlashStorage::new(Flash::new_blocking(p.FLASH), SLOT_A, SLOT_B).and_then(|s| s.with_lss(LSS_SECTOR))
    else {
        return; // the sector constants above do not fit this chip
    };
    // CiA 305: a stored LSS configuration wins over the factory defaults.
    #[cfg(feature = "store")]
    let stored = store.lss_config();
    #[cfg(not(feature = "store"))]
    let (store, stored) = (canopen_core::storage::NoStorage, None::<(u8, BitRate)>);
    let bitrate = stored.and_then(|(_, rate)| rate.kbit_per_s()).map_or(BITRATE, |k| u32::from(k) * 1000);

    let mut can = Can::new(p.CAN1, p.PA11, p.PA12, Irqs);
    can.modify_filters().enable_bank(0, Fifo::Fifo0, Mask32::accept_all());
    can.modify_config().set_bitrate(bitrate).set_automatic_retransmit(true);
    can.enable().await;

    let device = Device { inputs: [0], outputs: [0], setpoint: 0, blink_ticks: 0, uptime_s: 0, presses: 0, time_ms: 0 };
    // The node-ID: the stored LSS one (FFh: unconfigured, wait for an LSS master), else the factory one.
    let raw = stored.map_or(NODE_ID, |(raw, _)| raw);
    let Some(factory) = NodeId::new(NODE_ID) else { return };
    // Built inside `init_with`: the compiler then moves fewer of the node's parts through the stack on their way
    // into the static (52 B less flash than building it first and calling `init`).
    let node: &'static NodeCell<DeviceNode> = NODE.init_with(|| {
        #[cfg(feature = "cia402")]
        let device = canopen_cia402::Drive::new(device);
        let mut node = Node::with_storage(NodeId::new(raw).unwrap_or(factory), CONFIG, device, store);
        if NodeId::new(raw).is_none() {
            node = node.without_node_id();
        }
        #[cfg(feature = "store")]
        {
            node.lss_mut().set_store_supported(true);
            node.lss_mut().set_bit_rate(stored.map_or(BitRate::K250, |(_, rate)| rate));
        }
        NodeCell::new(node)
    });

    let button = Input::new(p.PC13, Pull::None);
    let led = Output::new(p.PA5, Level::Low, Speed::Low);
    spawner.spawn(process(node, button, led).unwrap());
    spawner.spawn(canopen(can, node).unwrap());
}

/// Runs the node. The controller's state goes to the node (`ReportState`); should `driver::run` ever
/// return (it does not with these halves: protocol errors show as the controller's state), the node is intact
/// in `NODE` and the driver runs again.
#[embassy_executor::task]
async fn canopen(mut can: Can<'static>, node: &'static NodeCell<DeviceNode>) {
    let (tx, rx) = can.split();
    // bxCAN's error status register: bus-off, error passive, error warning (the most severe wins).
    let esr = || {
        let esr = embassy_stm32::pac::CAN1.esr().read();
        ErrorMode::from_flags(esr.boff(), esr.epvf(), esr.ewgf())
    };
    let (mut tx, mut rx, mut clock) = (Stm32CanTx(tx), ReportState::new(Stm32CanRx(rx), esr), EmbassyClock);
    loop {
        let Err(_error) = driver::run(node, &mut rx, &mut tx, &mut clock, &WAKE, |e| on_event(node, e)).await;
        Timer::after(Duration::from_millis(10)).await;
    }
}

/// The node's events, outside the lock.
fn on_event(node: &NodeCell<DeviceNode>, event: Event) {
    match event {
        // TIME consumer: the application keeps the time of day (2102h, mappable into TPDO 4).
        Event::Time(t) => node.lock(|n| device(n.app_mut()).time_ms = t.ms),
        // A drive takes its cyclic synchronous set-point at the SYNC.
        #[cfg(feature = "cia402")]
        Event::Sync { .. } => node.lock(|n| n.app_mut().sync()),
        // LSS "store configuration": node-ID and bit rate to flash, then the answer to the master.
        #[cfg(feature = "store")]
        Event::Lss(LssEvent::StoreRequested { .. }) => node.lock(|n| n.complete_lss_store_in_storage()),
        // The outputs are applied by the process task on its next tick, whatever wrote them (SDO or RPDO);
        // another node's EMCY, an RPDO timeout and heartbeat observations need no local reaction here.
        Event::StateChanged { to: NmtState::Operational, .. } => {}
        Event::Heartbeat(_) | Event::SdoAborted { .. } | Event::ObjectWritten { .. } => {}
        Event::Emergency { .. } | Event::RpdoTimeout { .. } | Event::RpdoReceived { .. } => {}
        #[cfg(not(feature = "cia402"))]
        Event::Sync { .. } => {}
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
    #[cfg(feature = "cia402")]
    let mut stepper = Stepper::default();
    loop {
        ticker.next().await;
        ticks = ticks.wrapping_add(1);
        let inputs = u8::from(button.is_low());
        let uptime_s = ticks / 100;
        let (sent, level) = node.lock(|n| {
            #[cfg(feature = "cia402")]
            canopen_cia402::cycle_node(n, &mut stepper, 10_000);
            let app = device(n.app_mut());
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
