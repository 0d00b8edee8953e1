//! The node's dictionary and configuration: `examples/firmware`'s `node` (the same objects, PDO defaults and
//! identity layout), plus three objects of this board: 2103h (stack high-water mark), 2104h (slcan lines
//! skipped) and 2105h (256 bytes of scratch for SDO transfers). Plain `canopen_core` + derive code, so that the host example `qemu_m4_eds` includes this file
//! too and writes the EDS python canopen loads (`scripts/test-qemu.sh`).

use canopen_core::od::OctetString;
use canopen_core::profile::{Identity, NodeConfig};
use canopen_core::Sizes;
use canopen_od_derive::ObjectDictionary;

#[path = "../../firmware/src/pdo_defaults.rs"]
mod pdo_defaults;
use pdo_defaults::{RPDO1, RPDO2, RPDO3, RPDO4, TPDO1, TPDO2, TPDO3, TPDO4};

/// As `examples/firmware`: 4 heartbeat consumers, queues of 8, 4 RPDOs, 4 TPDOs.
pub type NodeSizes = Sizes<4, 8, 8, 4, 4>;

/// The node-ID.
pub const NODE_ID: u8 = 5;

/// The application's object dictionary: `examples/firmware`'s, plus 2103h, 2104h and 2105h.
#[derive(ObjectDictionary)]
pub struct Device {
    /// 6000h: digital inputs, 8 bits per sub-index (here: the outputs, looped back).
    #[od(index = 0x6000, sub = 1..=1, access = "ro", pdo = "tpdo", name = "Read input 8-bit")]
    pub inputs: [u8; 1],
    /// 6200h: digital outputs.
    #[od(index = 0x6200, sub = 1..=1, access = "rw", pdo = "rpdo", default = 0, name = "Write output 8-bit")]
    pub outputs: [u8; 1],
    /// 2001h: a set-point with limits.
    #[od(index = 0x2001, access = "rw", pdo = "rpdo", min = -1000, max = 1000, default = 0)]
    pub setpoint: i16,
    /// 2002h: LED blink period in 10 ms ticks (kept for the same dictionary; there is no LED).
    #[od(index = 0x2002, access = "rw", pdo = "rpdo", default = 0, name = "Blink period")]
    pub blink_ticks: u16,
    /// 2100h: seconds since power-on, kept by the process task.
    #[od(index = 0x2100, access = "ro", pdo = "tpdo", name = "Uptime")]
    pub uptime_s: u32,
    /// 2101h: rising edges of input 0 since power-on.
    #[od(index = 0x2101, access = "ro", pdo = "tpdo", name = "Button presses")]
    pub presses: u16,
    /// 2102h: milliseconds after midnight of the last TIME message received (TIME consumer).
    #[od(index = 0x2102, access = "ro", pdo = "tpdo", name = "Time of day ms")]
    pub time_ms: u32,
    /// 2103h: the stack's high-water mark in bytes: sub 01h since boot (building the node included), sub 02h
    /// since the node runs (the stack painted again after `main` built it), sub 03h in the steady state (painted
    /// again one second after that, when every task has run and the futures are in place).
    #[od(index = 0x2103, sub = 1..=3, access = "ro", name = "Stack high-water mark")]
    pub stack_high_water: [u32; 3],
    /// 2104h: slcan lines skipped as bad (garbage, over-long, a lost CR) plus 29-bit frames ignored.
    #[od(index = 0x2104, access = "ro", name = "slcan lines skipped")]
    pub slcan_skipped: u32,
    /// 2105h: 256 bytes of scratch for SDO transfers (segmented and block, with CRC) of a real size.
    #[od(index = 0x2105, access = "rw", name = "Scratch")]
    pub scratch: OctetString<256>,
}

impl Device {
    /// All zero; the node's power-on (Reset Application) then gives each entry its `default =` value.
    pub const fn new() -> Self {
        Device {
            inputs: [0],
            outputs: [0],
            setpoint: 0,
            blink_ticks: 0,
            uptime_s: 0,
            presses: 0,
            time_ms: 0,
            stack_high_water: [0; 3],
            slcan_skipped: 0,
            scratch: OctetString::new(),
        }
    }
}

impl Default for Device {
    fn default() -> Self {
        Self::new()
    }
}

/// The node configuration: identity, heartbeat, PDO defaults.
pub const CONFIG: NodeConfig = NodeConfig {
    device_type: 0x0003_0191, // CiA 401, digital inputs and outputs
    identity: Identity { vendor_id: 0, product_code: 0x386, revision: 0x0001_0000, serial: 1 },
    device_name: "canopener QEMU AN386",
    hardware_version: "QEMU mps2-an386",
    software_version: "0.1.0",
    heartbeat_time_ms: 1000,
    rpdo: &[RPDO1, RPDO2, RPDO3, RPDO4],
    tpdo: &[TPDO1, TPDO2, TPDO3, TPDO4],
    ..NodeConfig::DEFAULT
};
