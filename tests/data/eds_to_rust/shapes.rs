//! Generated from shapes.eds (CiA 306) by canopen-eds (`canopenctl eds-to-rust` or a build script's
//! `canopen_eds::generate`): the application objects (2000h-FFFFh) as a derived object dictionary,
//! and the node configuration from 1000h-1FFFh.

#![allow(unused_imports, clippy::all)]

use canopen_core::od::{DomainBuf, OctetString, TimeDifference, TimeOfDay, UnicodeString, VisibleString};
use canopen_core::od::{I24, I40, I48, I56, U24, U40, U48, U56};
use canopen_core::pdo::PdoDefault;
use canopen_core::profile::{Identity, NodeConfig};
use canopen_od_derive::ObjectDictionary;

/// The application objects of shapes.eds.
#[derive(ObjectDictionary, Debug, Default)]
pub struct Device {
    #[od(index = 0x2010, name = "Enable", access = "rw", pdo = "both", default = true)]
    pub enable_2010: bool,
    #[od(index = 0x2011, name = "Offset", access = "rw", min = -100000, max = 100000, default = -16)]
    pub offset_2011: i32,
    #[od(index = 0x2012, name = "Serial text", access = "const", default = "SN-0042")]
    pub serial_text_2012: VisibleString<32>,
    #[od(index = 0x2020, sub = 1, record = "PID", name = "Kp", access = "rw", default = 0.5)]
    pub kp_2020_1: f32,
    #[od(index = 0x2020, sub = 2, name = "Ki", access = "rw", min = 0.0, max = 10.0, default = 0.125)]
    pub ki_2020_2: f32,
    #[od(index = 0x2020, sub = 3, name = "Limit", access = "ro", pdo = "tpdo", default = 1000)]
    pub limit_2020_3: u16,
    #[od(index = 0x2030, sub = 1..=3, name = "Gains", access = "rw", default = 2.5, count_access = "ro")]
    pub gains_2030: [f64; 3],
    // 2040h Complex: data type 0040h is not supported; left out.
}

/// The node configuration shapes.eds describes.
pub const CONFIG: NodeConfig = NodeConfig {
    device_type: 131474,
    heartbeat_time_ms: 250,
    ..NodeConfig::DEFAULT
};
