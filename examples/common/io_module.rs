//! The example node's dictionary: a CiA 401-style I/O module (device type 0x000F_0191: profile 401, digital
//! and analogue inputs and outputs), shared by `examples/node.rs`, `examples/master.rs` and the vcan tests
//! (`#[path]`-included).
//!
//! Objects (besides the communication profile the core provides: 1000h, 1001h, 1008h–100Ah, 100Ch, 100Dh,
//! 1016h with 4 consumer entries, 1017h = 1000 ms, 1018h, 1200h):
//!
//! | index | type | access | what |
//! |---|---|---|---|
//! | 2000h | UNSIGNED8 | rw | a configuration byte |
//! | 2001h | INTEGER16 | rw | a setpoint, limits -1000..=1000 |
//! | 2002h | UNSIGNED32 | rw | a parameter |
//! | 2003h | REAL32 | rw | a gain |
//! | 2004h | VISIBLE_STRING | rw | a label, capacity 32 |
//! | 2005h | DOMAIN | rw | a data block of up to 65,536 bytes ([`DataBlock`]) |
//! | 2006h | UNSIGNED64 | ro | uptime in ms, updated by another task while the node runs |
//! | 2100h | UNSIGNED16 | rw | error injection: the requested EMCY error code is recorded |
//! | 6000h | ARRAY 8 × UNSIGNED8 | ro, TPDO | digital inputs (the example changes them over time) |
//! | 6200h | ARRAY 8 × UNSIGNED8 | rw, RPDO | digital outputs |
//! | 6401h | ARRAY 4 × INTEGER16 | ro, TPDO | analogue inputs |
//! | 6411h | ARRAY 4 × INTEGER16 | rw, RPDO | analogue outputs |
#![allow(dead_code)]

use canopen_core::comm::{Identity, NodeConfig};
use canopen_core::od::eds::EdsInfo;
use canopen_core::od::{AbortCode, Domain, VisibleString};
use canopen_od_derive::ObjectDictionary;

/// Capacity of the 2005h DOMAIN.
pub const DATA_BLOCK_CAPACITY: usize = 65_536;

/// 2005h: a DOMAIN on the heap of up to [`DATA_BLOCK_CAPACITY`] bytes, committed when a download ends (a
/// refused or aborted download keeps the old content).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct DataBlock {
    data: Vec<u8>,
    staged: Vec<u8>,
}

impl DataBlock {
    /// The committed content.
    pub fn as_bytes(&self) -> &[u8] {
        &self.data
    }
}

impl Domain for DataBlock {
    fn size(&self) -> Option<usize> {
        Some(self.data.len())
    }

    fn read(&self, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        let src = self.data.get(offset..).unwrap_or(&[]);
        let n = src.len().min(buf.len());
        buf[..n].copy_from_slice(&src[..n]);
        Ok(n)
    }

    fn begin_write(&mut self, size: Option<usize>) -> Result<(), AbortCode> {
        if size.is_some_and(|s| s > DATA_BLOCK_CAPACITY) {
            return Err(AbortCode::LengthTooHigh);
        }
        self.staged.clear();
        Ok(())
    }

    fn write_chunk(&mut self, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        let end =
            offset.checked_add(data.len()).filter(|&e| e <= DATA_BLOCK_CAPACITY).ok_or(AbortCode::LengthTooHigh)?;
        if self.staged.len() < end {
            self.staged.resize(end, 0);
        }
        self.staged[offset..end].copy_from_slice(data);
        Ok(())
    }

    fn end_write(&mut self, total: usize) -> Result<(), AbortCode> {
        if total > DATA_BLOCK_CAPACITY {
            return Err(AbortCode::LengthTooHigh);
        }
        self.staged.resize(total, 0);
        self.data = std::mem::take(&mut self.staged);
        Ok(())
    }

    fn abort_write(&mut self) {
        self.staged.clear();
    }
}

/// The application dictionary of the I/O module.
#[derive(ObjectDictionary, Debug, Default)]
pub struct IoModule {
    #[od(index = 0x2000, name = "Configuration byte", access = "rw", default = 0)]
    pub config_byte: u8,
    #[od(index = 0x2001, name = "Setpoint", access = "rw", min = -1000, max = 1000, default = 0)]
    pub setpoint: i16,
    #[od(index = 0x2002, name = "Parameter", access = "rw", default = 0x12345678)]
    pub parameter: u32,
    #[od(index = 0x2003, name = "Gain", access = "rw", default = 1.5)]
    pub gain: f32,
    #[od(index = 0x2004, name = "Label", access = "rw", default = "io module")]
    pub label: VisibleString<32>,
    #[od(index = 0x2005, name = "Data block", domain)]
    pub data_block: DataBlock,
    #[od(index = 0x2006, name = "Uptime ms", access = "ro", pdo = "tpdo")]
    pub uptime_ms: u64,
    #[od(index = 0x2100, name = "Error injection", access = "rw", default = 0, on_write = "error_injected")]
    pub error_injection: u16,
    #[od(index = 0x6000, sub = 1..=8, name = "Digital inputs", access = "ro", pdo = "tpdo")]
    pub digital_inputs: [u8; 8],
    #[od(index = 0x6200, sub = 1..=8, name = "Digital outputs", access = "rw", pdo = "rpdo")]
    pub digital_outputs: [u8; 8],
    #[od(index = 0x6401, sub = 1..=4, name = "Analog inputs", access = "ro", pdo = "tpdo")]
    pub analog_inputs: [i16; 4],
    #[od(index = 0x6411, sub = 1..=4, name = "Analog outputs", access = "rw", pdo = "rpdo")]
    pub analog_outputs: [i16; 4],
    /// Error codes requested through 2100h, oldest first (not in the dictionary). Raising them as EMCY
    /// frames is wired after the EMCY producer merges into the node.
    pub injected: Vec<u16>,
}

impl IoModule {
    /// The power-on values (the defaults the EDS announces).
    pub fn with_defaults() -> Self {
        IoModule { parameter: 0x1234_5678, gain: 1.5, label: VisibleString::literal("io module"), ..Default::default() }
    }

    /// Reset Application (NMT-04): every value back to its power-on value. The derive does not generate
    /// this yet, so the example calls it on `Event::ResetApplication`; the uptime keeps counting (it is the
    /// process's uptime, not a parameter).
    pub fn restore_power_on_values(&mut self) {
        let uptime_ms = self.uptime_ms;
        *self = IoModule { uptime_ms, ..IoModule::with_defaults() };
    }

    fn error_injected(&mut self, _sub: u8) {
        self.injected.push(self.error_injection);
    }
}

/// The node configuration.
pub const CONFIG: NodeConfig = NodeConfig {
    device_type: 0x000F_0191,
    identity: Identity { vendor_id: 0, product_code: 0x0000_0401, revision: 0x0001_0000, serial: 1 },
    device_name: "canopen example node",
    hardware_version: "vcan",
    software_version: "0.1.0",
    heartbeat_time_ms: 1000,
    ..NodeConfig::DEFAULT
};

/// What the EDS says beyond the dictionary.
pub const EDS_INFO: EdsInfo = EdsInfo {
    file_name: "io_module.eds",
    description: "canopen-rs example node: CiA 401-style I/O module",
    vendor_name: "canopen-rs",
    product_name: "canopen example node",
    order_code: "IO-1",
    ..EdsInfo::DEFAULT
};

/// The example node type: 4 heartbeat consumers, transmit queue 32, event queue 32.
pub type IoNode = canopen_core::Node<IoModule, 4, 32, 32>;

/// A fresh node with `node_id` and `config`.
pub fn new_node(node_id: canopen_core::NodeId, config: NodeConfig) -> IoNode {
    canopen_core::Node::new(node_id, config, IoModule::with_defaults())
}

/// The EDS text of the node.
pub fn eds_text(config: NodeConfig) -> String {
    let od = canopen_core::od::Merged {
        comm: canopen_core::od::comm::CommProfile::<4>::new(config),
        app: IoModule::with_defaults(),
    };
    let mut text = String::new();
    canopen_core::od::eds::write_eds(&mut text, &EDS_INFO, &od).expect("formatting into a String cannot fail");
    text
}
