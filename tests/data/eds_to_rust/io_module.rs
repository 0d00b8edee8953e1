//! Generated from io_module.eds (CiA 306) by canopen-eds (`canopenctl eds-to-rust` or a build script's
//! `canopen_eds::generate`): the application objects (2000h-FFFFh) as a derived object dictionary,
//! and the node configuration from 1000h-1FFFh.

#![allow(unused_imports, clippy::all)]

use canopen_core::od::{DomainBuf, OctetString, TimeDifference, TimeOfDay, UnicodeString, VisibleString};
use canopen_core::od::{I24, I40, I48, I56, U24, U40, U48, U56};
use canopen_core::pdo::PdoDefault;
use canopen_core::profile::{Identity, NodeConfig};
use canopen_od_derive::ObjectDictionary;

/// The application objects of io_module.eds.
#[derive(ObjectDictionary, Debug, Default)]
pub struct Device {
    #[od(index = 0x2000, name = "Configuration byte", access = "rw", default = 0)]
    pub configuration_byte_2000: u8,
    #[od(index = 0x2001, name = "Setpoint", access = "rw", min = -1000, max = 1000, default = 0)]
    pub setpoint_2001: i16,
    #[od(index = 0x2002, name = "Parameter", access = "rw", default = 305419896)]
    pub parameter_2002: u32,
    #[od(index = 0x2003, name = "Gain", access = "rw", default = 1.5)]
    pub gain_2003: f32,
    #[od(index = 0x2004, name = "Label", access = "rw", default = "io module")]
    pub label_2004: VisibleString<32>,
    #[od(index = 0x2005, name = "Data block", domain)]
    pub data_block_2005: DomainBuf<4096>,
    #[od(index = 0x2006, name = "Uptime ms", access = "ro", pdo = "tpdo", default = 0)]
    pub uptime_ms_2006: u64,
    #[od(index = 0x2100, name = "Error injection", access = "rw", default = 0)]
    pub error_injection_2100: u16,
    #[od(index = 0x6000, sub = 1..=8, name = "Digital inputs", access = "ro", pdo = "tpdo", default = 0)]
    pub digital_inputs_6000: [u8; 8],
    #[od(index = 0x6200, sub = 1..=8, name = "Digital outputs", access = "rw", pdo = "both", default = 0)]
    pub digital_outputs_6200: [u8; 8],
    #[od(index = 0x6401, sub = 1..=4, name = "Analog inputs", access = "ro", pdo = "tpdo", default = 0)]
    pub analog_inputs_6401: [i16; 4],
    #[od(index = 0x6411, sub = 1..=4, name = "Analog outputs", access = "rw", pdo = "both", default = 0)]
    pub analog_outputs_6411: [i16; 4],
}

/// The node configuration io_module.eds describes.
pub const CONFIG: NodeConfig = NodeConfig {
    device_type: 983441,
    identity: Identity { vendor_id: 0, product_code: 1025, revision: 65536, serial: 1 },
    device_name: "canopen example node",
    hardware_version: "vcan",
    software_version: "0.1.0",
    heartbeat_time_ms: 1000,
    rpdo: &[
        PdoDefault { valid: true, can_id: None, transmission_type: 255, inhibit_100us: 0, event_timer_ms: 0, mapping: &[0x62000108, 0x62000208, 0x62000308, 0x62000408, 0x62000508, 0x62000608, 0x62000708, 0x62000808], ..PdoDefault::EVENT },
        PdoDefault { valid: true, can_id: None, transmission_type: 255, inhibit_100us: 0, event_timer_ms: 0, mapping: &[0x64110110, 0x64110210, 0x64110310, 0x64110410], ..PdoDefault::EVENT },
        PdoDefault { valid: false, can_id: None, transmission_type: 254, inhibit_100us: 0, event_timer_ms: 0, mapping: &[], ..PdoDefault::EVENT },
        PdoDefault { valid: false, can_id: None, transmission_type: 254, inhibit_100us: 0, event_timer_ms: 0, mapping: &[], ..PdoDefault::EVENT },
    ],
    tpdo: &[
        PdoDefault { valid: true, can_id: None, transmission_type: 255, inhibit_100us: 100, event_timer_ms: 0, sync_start: 0, mapping: &[0x60000108, 0x60000208, 0x60000308, 0x60000408, 0x60000508, 0x60000608, 0x60000708, 0x60000808], ..PdoDefault::EVENT },
        PdoDefault { valid: true, can_id: None, transmission_type: 255, inhibit_100us: 100, event_timer_ms: 0, sync_start: 0, mapping: &[0x64010110, 0x64010210, 0x64010310, 0x64010410], ..PdoDefault::EVENT },
        PdoDefault { valid: false, can_id: None, transmission_type: 254, inhibit_100us: 0, event_timer_ms: 0, sync_start: 0, mapping: &[], ..PdoDefault::EVENT },
        PdoDefault { valid: false, can_id: None, transmission_type: 254, inhibit_100us: 0, event_timer_ms: 0, sync_start: 0, mapping: &[], ..PdoDefault::EVENT },
    ],
    ..NodeConfig::DEFAULT
};
