//! The canopener node of `examples/firmware` (`node`: node-ID 5, the same dictionary, PDO defaults and
//! services: NMT, heartbeat producer 1017h = 1000 ms and 4 consumers, SDO server with block transfer, 4 RPDOs
//! and 4 TPDOs with dynamic mapping, SYNC, EMCY with the 1003h history, TIME) on QEMU's `mps2-an386`, its CAN
//! frames as slcan lines on UART0 (`canopen_qemu_m4::link`). What differs from the STM32 board:
//!
//! - parameters are stored in RAM (`RamStorage`): 1010h "save" survives NMT resets, not a power cycle;
//! - there is no button and no LED: output 6200h:01 is wired back to input 6000h:01 (a loopback), so an
//!   RPDO or SDO write to the output makes the input change and the event-driven TPDO 1 carry it, and 2101h
//!   counts the input's rising edges;
//! - objects of ours: 2103h, the stack's high-water mark in bytes (painted at boot, read back every second;
//!   sub 01h since boot, sub 02h since the node runs, sub 03h in the steady state), 2104h, the slcan lines skipped as bad (plus 29-bit
//!   frames ignored), and 2105h, 256 bytes of scratch for SDO transfers.
#![no_std]
#![no_main]

use core::sync::atomic::{AtomicU32, Ordering};

use canopen_core::driver::{self, Shared};
use canopen_core::storage::RamStorage;
use canopen_core::{Event, Node, NodeId};
use canopen_embassy::{AppWake, EmbassyClock, NodeCell};
use canopen_qemu_m4::device::{Device, NodeSizes, CONFIG, NODE_ID};
use canopen_qemu_m4::link::{SlcanRx, SlcanTx};
use canopen_qemu_m4::{stack, time_driver, uart};
use embassy_executor::Spawner;
use embassy_time::{Duration, Ticker};
use static_cell::{ConstStaticCell, StaticCell};

/// Parameters saved by 1010h go to RAM (2 slots of 2 KB, in `.data`: erased RAM reads 0xFF as erased flash).
type DeviceNode = Node<Device, NodeSizes, &'static mut RamStorage<2048>>;

/// A `static` of its own rather than a value moved into the node: built in place, never on the stack.
static STORE: ConstStaticCell<RamStorage<2048>> = ConstStaticCell::new(RamStorage::new());

static NODE: StaticCell<NodeCell<DeviceNode>> = StaticCell::new();
static WAKE: AppWake = AppWake::new();
static BOOT_STACK: AtomicU32 = AtomicU32::new(0);
static START_STACK: AtomicU32 = AtomicU32::new(0);

#[embassy_executor::main]
async fn main(spawner: Spawner) {
    let _ = stack::paint();
    let Some(core) = cortex_m::Peripherals::take() else { return };
    time_driver::init(core.SYST);
    uart::init();

    let device = Device::new();
    let Some(id) = NodeId::new(NODE_ID) else { return };
    let node: &'static NodeCell<DeviceNode> =
        NODE.init_with(|| NodeCell::new(Node::with_storage(id, CONFIG, device, STORE.take())));
    // What building the node took, then a fresh coat for what running it takes (2103h:01 / 02).
    BOOT_STACK.store(stack::high_water(), Ordering::Relaxed);
    let _ = stack::paint();
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
        let second = ticks.is_multiple_of(100);
        let high_water = if second { stack::high_water() } else { 0 };
        if ticks == 100 {
            // The first second (the tasks' first polls) is in sub 02h; from here on, the steady state.
            START_STACK.store(high_water, Ordering::Relaxed);
            let _ = stack::paint();
        }
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
                let running = START_STACK.load(Ordering::Relaxed).max(high_water);
                app.stack_high_water = [BOOT_STACK.load(Ordering::Relaxed).max(running), running, high_water];
                app.slcan_skipped = canopen_qemu_m4::link::skipped();
            }
            changed && n.trigger_tpdo(0)
        });
        if sent {
            WAKE.signal();
        }
    }
}
