//! A dictionary that uses every CiA 301 data type, VAR/ARRAY/RECORD, every access type, limits, defaults,
//! hooks and a DOMAIN. Shared by `tests/od_all_types.rs` and `examples/write_eds.rs` (whose EDS the python
//! test loads).
#![allow(dead_code)]

use canopen_core::od::{
    AbortCode, DomainBuf, Merged, OctetString, TimeDifference, TimeOfDay, UnicodeString, VisibleString, I24, I40, I48,
    I56, U24, U40, U48, U56,
};
use canopen_core::pdo::PdoDefault;
use canopen_core::profile::CommProfile;
use canopen_core::profile::{Identity, NodeConfig};
use canopen_core::Sizes;
use canopen_od_derive::ObjectDictionary;

/// With the root package's test feature `od-compact-tests` the same dictionary is derived as data
/// (`#[od(compact)]`), and `tests/od_all_types.rs` runs its whole suite on that layout too (`.ci/run`).
#[derive(ObjectDictionary, Debug, Default)]
#[cfg_attr(feature = "od-compact-tests", od(compact))]
pub struct AllTypes {
    #[od(index = 0x2000, name = "Boolean", pdo = "both", default = true)]
    pub boolean: bool,
    #[od(index = 0x2001, name = "Integer8", pdo = "rpdo", min = -100, max = 100, default = -1)]
    pub int8: i8,
    #[od(index = 0x2002, name = "Integer16", access = "rww", pdo = "rpdo", min = -1000, max = 1000, default = 0,
         check = "check_int16", on_write = "wrote_int16")]
    pub int16: i16,
    #[od(index = 0x2003, name = "Integer24", access = "rwr", pdo = "tpdo", default = -5)]
    pub int24: I24,
    #[od(index = 0x2004, name = "Integer32", pdo = "both", min = -70000, default = -70000)]
    pub int32: i32,
    #[od(index = 0x2005, name = "Integer40", default = -1)]
    pub int40: I40,
    #[od(index = 0x2006, name = "Integer48")]
    pub int48: I48,
    #[od(index = 0x2007, name = "Integer56", pdo = "tpdo")]
    pub int56: I56,
    #[od(index = 0x2008, name = "Integer64", pdo = "both", default = -9000000000)]
    pub int64: i64,
    #[od(index = 0x2010, name = "Unsigned8", pdo = "both", max = 200, default = 200)]
    pub uint8: u8,
    #[od(index = 0x2011, name = "Unsigned16", pdo = "both", min = 10, max = 60000, default = 10)]
    pub uint16: u16,
    #[od(index = 0x2012, name = "Unsigned24", default = 0x123456)]
    pub uint24: U24,
    #[od(index = 0x2013, name = "Unsigned32", pdo = "both", default = 0xDEADBEEF)]
    pub uint32: u32,
    #[od(index = 0x2014, name = "Unsigned40")]
    pub uint40: U40,
    #[od(index = 0x2015, name = "Unsigned48")]
    pub uint48: U48,
    #[od(index = 0x2016, name = "Unsigned56")]
    pub uint56: U56,
    #[od(index = 0x2017, name = "Unsigned64", pdo = "tpdo", default = 18446744073709551615)]
    pub uint64: u64,
    #[od(index = 0x2018, name = "Real32", pdo = "both", min = -1.5, max = 2.5, default = 1.25)]
    pub real32: f32,
    #[od(index = 0x2019, name = "Real64", default = -0.5)]
    pub real64: f64,
    #[od(index = 0x2020, name = "Visible string", default = "hello")]
    pub visible: VisibleString<16>,
    #[od(index = 0x2021, name = "Octet string", default = "AB")]
    pub octets: OctetString<8>,
    #[od(index = 0x2022, name = "Unicode string", default = "hi")]
    pub unicode: UnicodeString<8>,
    #[od(index = 0x2023, name = "Time of day", pdo = "tpdo")]
    pub time_of_day: TimeOfDay,
    #[od(index = 0x2024, name = "Time difference")]
    pub time_diff: TimeDifference,
    #[od(index = 0x2025, name = "Firmware image", domain)]
    pub firmware: DomainBuf<64>,
    #[od(index = 0x2030, name = "Write only", access = "wo", pdo = "rpdo")]
    pub write_only: u32,
    #[od(index = 0x2031, name = "Read only", access = "ro", pdo = "tpdo")]
    pub read_only: u16,
    #[od(index = 0x2032, name = "Constant", access = "const", default = 7)]
    pub constant: u8,
    #[od(index = 0x2100, sub = 1, record = "PID controller", name = "Kp", pdo = "rpdo", default = 1.0)]
    pub kp: f32,
    #[od(index = 0x2100, sub = 2, name = "Ki", min = 0.0, max = 10.0)]
    pub ki: f32,
    #[od(index = 0x2100, sub = 3, name = "Mode", access = "rw", min = 1, max = 3, default = 1)]
    pub mode: u8,
    #[od(index = 0x2100, sub = 4, name = "Label", access = "ro")]
    pub label: VisibleString<8>,
    #[od(index = 0x6000, sub = 1..=8, access = "ro", pdo = "tpdo", name = "Digital inputs")]
    pub inputs: [u8; 8],
    #[od(index = 0x6200, name = "Outputs", access = "rw", pdo = "rpdo", min = -10, max = 10, default = 0)]
    pub outputs: [i16; 4],
    /// Not in the dictionary.
    pub scratch: u32,
    /// Counts accepted writes of 2002h (on_write hook).
    pub int16_writes: u32,
}

impl AllTypes {
    /// Refuses 13 with 0609 0030h (the check hook).
    fn check_int16(&self, _sub: u8, v: &i16) -> Result<(), AbortCode> {
        if *v == 13 {
            Err(AbortCode::InvalidValue)
        } else {
            Ok(())
        }
    }

    fn wrote_int16(&mut self, _sub: u8) {
        self.int16_writes += 1;
    }

    /// The values the EDS gives as defaults.
    pub fn with_defaults() -> Self {
        AllTypes {
            boolean: true,
            int8: -1,
            int24: I24::new(-5).unwrap_or_default(),
            int32: -70000,
            int40: I40::new(-1).unwrap_or_default(),
            int64: -9_000_000_000,
            uint8: 200,
            uint16: 10,
            uint24: U24::new(0x12_3456).unwrap_or_default(),
            uint32: 0xDEAD_BEEF,
            uint64: u64::MAX,
            real32: 1.25,
            real64: -0.5,
            visible: VisibleString::literal("hello"),
            octets: OctetString::from_bytes(b"AB").unwrap_or_default(),
            unicode: UnicodeString::from_str("hi").unwrap_or_default(),
            constant: 7,
            kp: 1.0,
            mode: 1,
            ..Default::default()
        }
    }
}

/// The node configuration used with it.
pub const CONFIG: NodeConfig = NodeConfig {
    device_type: 0x0001_0191,
    identity: Identity { vendor_id: 0x0000_02B6, product_code: 0x1234, revision: 0x0001_0002, serial: 42 },
    device_name: "canopener all types",
    hardware_version: "HW 1.0",
    software_version: "SW 0.1",
    heartbeat_time_ms: 1000,
    tpdo: &[PdoDefault { mapping: &[0x2010_0008, 0x2011_0010], ..PdoDefault::EVENT }],
    rpdo: &[PdoDefault { mapping: &[0x2002_0010], ..PdoDefault::EVENT }],
    ..NodeConfig::DEFAULT
};

/// The whole node dictionary: comm profile (4 heartbeat consumers, 4 RPDOs, 4 TPDOs) + application.
pub type NodeOd = Merged<CommProfile<Sizes>, AllTypes>;

/// A fresh node dictionary (node-ID 5).
pub fn node_od() -> NodeOd {
    Merged { comm: CommProfile::for_node(CONFIG, 5), app: AllTypes::with_defaults() }
}
