//! The example node's dictionary: a CiA 401-style I/O module (device type 0x000F_0191: profile 401, digital
//! and analogue inputs and outputs), shared by `examples/node.rs` and the vcan tests
//! (`#[path]`-included).
//!
//! Objects (besides the communication profile the core provides: 1000h, 1001h, 1008h–100Ah, 100Ch, 100Dh,
//! 1003h, 1010h/1011h (with a store), 1014h/1015h, 1016h with 4 consumer entries, 1017h = 1000 ms, 1018h, 1200h,
//! an additional SDO server 1201h, an SDO client record 1280h, RPDO/TPDO 1..4 at 1400h–1403h/1600h–1603h and
//! 1800h–1803h/1A00h–1A03h, up to 8 mapping entries each, 64 built with `--features pdo-mapping-64`):
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
//! | 2100h | UNSIGNED16 | rw | error injection: a non-zero EMCY error code is raised, 0 clears it ([`apply_error_injection`]) |
//! | 6000h | ARRAY 8 × UNSIGNED8 | ro, TPDO | digital inputs (the example changes them over time) |
//! | 6200h | ARRAY 8 × UNSIGNED8 | rw, RPDO | digital outputs |
//! | 6401h | ARRAY 4 × INTEGER16 | ro, TPDO | analogue inputs |
//! | 6411h | ARRAY 4 × INTEGER16 | rw, RPDO | analogue outputs |
//!
//! Default PDOs (CiA 401 style, pre-defined COB-IDs, event-driven type 255 with a 10 ms inhibit time on the
//! TPDOs): TPDO1 ← 6000h:01..08, TPDO2 ← 6401h:01..04, RPDO1 → 6200h:01..08, RPDO2 → 6411h:01..04.
//!
//! The additional SDO server 1201h starts invalid (COB-IDs 8000_0000h, as after every reset communication):
//! a master configures its COB-IDs through the default server 1200h (sub 02h, then sub 01h), then talks to
//! both servers at once (SDO-54, SDO-55; `tests/python/test_interop.py`). The SDO client record 1280h
//! (SDO-56) is there for a master to configure (COB-IDs and the server's node-ID); the example's
//! application runs no client on it.
//!
//! Built with the feature `pdo-mapping-64` (`cargo run --example node --features pdo-mapping-64`), every
//! PDO mapping takes 64 entries (sub 01h–40h, CiA 301's maximum, PDO-30), so that foreign masters can test
//! long mappings of bit-sized entries against this node; scripts/test-interop.sh runs python canopen
//! against that build. It is not the default: a Cargo feature is one per build, and the root package's
//! tests (store sizes, vectors) and benches are about the default 8; the firmware example never turns it
//! on (about 670 B of RAM per PDO).
//!
//! Parameters are stored (1010h/1011h) in a [`Store`]: a [`FileStorage`] with `--store FILE`, else none.
//!
//! Program download (CiA 302-3, `canopen_core::program`): the node's application is the [`IoModule`]
//! behind a [`ProgramDownload`] whose sink is an [`ImageFile`]: 1F50h:01 streams the image into a file
//! (`--program FILE` of the node example; without it a download is refused with 0800 0020h), 1F51h program
//! control, 1F56h = the CRC-32 of the last complete image, 1F57h flash status.
#![allow(dead_code)]

use canopen_core::node::{SdoRecordsDesc, WithSdoServers};
use canopen_core::od::{AbortCode, Domain, VisibleString};
use canopen_core::pdo::PdoDefault;
use canopen_core::profile::eds::EdsInfo;
use canopen_core::profile::{Identity, NodeConfig};
use canopen_core::program::{ProgramDownload, ProgramSink};
use canopen_core::storage::{Storage, StorageError};
use canopen_core::Sizes;
use canopen_od_derive::ObjectDictionary;
use canopen_socketcan::FileStorage;

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
    #[od(index = 0x2100, name = "Error injection", access = "rw", default = 0)]
    pub error_injection: u16,
    #[od(index = 0x6000, sub = 1..=8, name = "Digital inputs", access = "ro", pdo = "tpdo")]
    pub digital_inputs: [u8; 8],
    #[od(index = 0x6200, sub = 1..=8, name = "Digital outputs", access = "rw", pdo = "rpdo")]
    pub digital_outputs: [u8; 8],
    #[od(index = 0x6401, sub = 1..=4, name = "Analog inputs", access = "ro", pdo = "tpdo")]
    pub analog_inputs: [i16; 4],
    #[od(index = 0x6411, sub = 1..=4, name = "Analog outputs", access = "rw", pdo = "rpdo")]
    pub analog_outputs: [i16; 4],
    /// The error code raised for 2100h (not in the dictionary; 0 = none).
    pub raised: u16,
}

impl IoModule {
    /// The power-on values (the defaults the EDS announces).
    pub fn with_defaults() -> Self {
        IoModule { parameter: 0x1234_5678, gain: 1.5, label: VisibleString::literal("io module"), ..Default::default() }
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
    rpdo: &[
        PdoDefault { mapping: &DIGITAL_OUTPUTS_MAP, transmission_type: 255, ..PdoDefault::EVENT },
        PdoDefault { mapping: &ANALOG_OUTPUTS_MAP, transmission_type: 255, ..PdoDefault::EVENT },
    ],
    tpdo: &[
        PdoDefault { mapping: &DIGITAL_INPUTS_MAP, transmission_type: 255, inhibit_100us: 100, ..PdoDefault::EVENT },
        PdoDefault { mapping: &ANALOG_INPUTS_MAP, transmission_type: 255, inhibit_100us: 100, ..PdoDefault::EVENT },
    ],
    ..NodeConfig::DEFAULT
};

/// Mapping entries `index:01..=N`, each `bits` wide (raw UNSIGNED32: index, sub, length in bits).
const fn map<const N: usize>(index: u16, bits: u8) -> [u32; N] {
    let mut m = [0u32; N];
    let mut i = 0;
    while i < N {
        m[i] = (index as u32) << 16 | ((i as u32 + 1) << 8) | bits as u32;
        i += 1;
    }
    m
}

const DIGITAL_INPUTS_MAP: [u32; 8] = map(0x6000, 8);
const DIGITAL_OUTPUTS_MAP: [u32; 8] = map(0x6200, 8);
const ANALOG_INPUTS_MAP: [u32; 4] = map(0x6401, 16);
const ANALOG_OUTPUTS_MAP: [u32; 4] = map(0x6411, 16);

/// What the EDS says beyond the dictionary.
pub const EDS_INFO: EdsInfo = EdsInfo {
    file_name: "io_module.eds",
    description: "canopener example node: CiA 401-style I/O module",
    vendor_name: "canopener",
    product_name: "canopen example node",
    order_code: "IO-1",
    ..EdsInfo::DEFAULT
};

/// The example node's capacities: 4 heartbeat consumers, transmit queue 32, event queue 32, 4 RPDOs, 4
/// TPDOs, one additional SDO server 1201h and one SDO client record 1280h.
pub type IoSizes = WithSdoServers<Sizes<4, 32, 32, 4, 4>, 1, 1>;

/// The example node type: [`IoSizes`], parameters in a [`Store`].
pub type IoNode = canopen_core::Node<IoApp, IoSizes, Store>;

/// The node's application dictionary: the [`IoModule`] with the program download objects in front
/// (`node.app().setpoint` reaches the module through `Deref`).
pub type IoApp = ProgramDownload<ImageFile, IoModule>;

/// CRC-32 (ISO-HDLC, the one of zlib and `zlib.crc32` in python) of `data` continued from `crc` (0 to
/// start): `crc32(crc32(0, a), b) == crc32(0, a ++ b)`.
pub fn crc32(crc: u32, data: &[u8]) -> u32 {
    let mut c = !crc;
    for &b in data {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 != 0 { (c >> 1) ^ 0xEDB8_8320 } else { c >> 1 };
        }
    }
    !c
}

/// The program area of the example node: the image goes to `FILE.part` chunk by chunk (never held in
/// memory) and becomes `FILE` when the download completes; an aborted download removes `FILE.part`.
#[derive(Debug, Default)]
pub struct ImageFile {
    path: Option<std::path::PathBuf>,
    file: Option<std::fs::File>,
    crc: u32,
    /// Length and CRC-32 of the last complete image.
    pub last: Option<(usize, u32)>,
}

impl ImageFile {
    /// A program area writing to `path` (`None`: downloads are refused with 0800 0020h).
    pub fn new(path: Option<std::path::PathBuf>) -> Self {
        ImageFile { path, ..ImageFile::default() }
    }

    /// Where images go.
    pub fn path(&self) -> Option<&std::path::Path> {
        self.path.as_deref()
    }

    fn part(&self) -> Option<std::path::PathBuf> {
        self.path.as_ref().map(|p| p.with_extension("part"))
    }
}

impl ProgramSink for ImageFile {
    fn begin(&mut self, _size: Option<usize>) -> Result<(), AbortCode> {
        let part = self.part().ok_or(AbortCode::CannotStore)?;
        self.file = Some(std::fs::File::create(part).map_err(|_| AbortCode::CannotStore)?);
        self.crc = 0;
        Ok(())
    }

    fn write_chunk(&mut self, _offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        use std::io::Write;
        let file = self.file.as_mut().ok_or(AbortCode::GeneralError)?;
        file.write_all(data).map_err(|_| AbortCode::CannotStore)?;
        self.crc = crc32(self.crc, data);
        Ok(())
    }

    fn end(&mut self, total: usize) -> Result<(), AbortCode> {
        let file = self.file.take().ok_or(AbortCode::GeneralError)?;
        file.sync_all().map_err(|_| AbortCode::CannotStore)?;
        drop(file);
        if let (Some(part), Some(path)) = (self.part(), self.path.as_ref()) {
            std::fs::rename(part, path).map_err(|_| AbortCode::CannotStore)?;
        }
        self.last = Some((total, self.crc));
        Ok(())
    }

    fn abort(&mut self) {
        self.file = None;
        if let Some(part) = self.part() {
            let _ = std::fs::remove_file(part);
        }
    }

    fn software_id(&self) -> u32 {
        self.last.map_or(0, |(_, crc)| crc)
    }
}

/// Where the node stores its parameters (1010h/1011h).
#[derive(Debug)]
pub enum Store {
    /// No storage: 1010h/1011h answer 0606 0000h.
    None,
    /// `--store FILE`: two slot files, see [`FileStorage`].
    File(FileStorage),
}

impl Storage for Store {
    fn capacity(&self) -> usize {
        match self {
            Store::None => 0,
            Store::File(f) => f.capacity(),
        }
    }
    fn erase(&mut self, slot: u8) -> Result<(), StorageError> {
        match self {
            Store::None => Err(StorageError::Unsupported),
            Store::File(f) => f.erase(slot),
        }
    }
    fn write(&mut self, slot: u8, offset: usize, data: &[u8]) -> Result<(), StorageError> {
        match self {
            Store::None => Err(StorageError::Unsupported),
            Store::File(f) => f.write(slot, offset, data),
        }
    }
    fn read(&mut self, slot: u8, offset: usize, buf: &mut [u8]) -> Result<(), StorageError> {
        match self {
            Store::None => Err(StorageError::Unsupported),
            Store::File(f) => f.read(slot, offset, buf),
        }
    }
}

/// A fresh node with `node_id` and `config`, without storage.
pub fn new_node(node_id: canopen_core::NodeId, config: NodeConfig) -> IoNode {
    new_node_with_store(node_id, config, Store::None)
}

/// A fresh node storing its parameters in `store`; stored values are loaded when it boots.
pub fn new_node_with_store(node_id: canopen_core::NodeId, config: NodeConfig, store: Store) -> IoNode {
    new_node_with_program(node_id, config, store, None)
}

/// A fresh node storing its parameters in `store` and downloaded programs (1F50h) in `program`.
pub fn new_node_with_program(
    node_id: canopen_core::NodeId,
    config: NodeConfig,
    store: Store,
    program: Option<std::path::PathBuf>,
) -> IoNode {
    let app = ProgramDownload::new(ImageFile::new(program), IoModule::with_defaults());
    canopen_core::Node::with_storage(node_id, config, app, store)
}

/// 2100h error injection, called after 2100h was written (`Event::ObjectWritten`) and after a reset: the
/// code written is raised as an error (1001h, 1003h, an EMCY frame), the previously raised one is cleared;
/// 0 clears. Returns `(cleared, raised)` codes, 0 for none.
pub fn apply_error_injection(node: &mut IoNode) -> (u16, u16) {
    let (wanted, old) = (node.app().error_injection, node.app().raised);
    if wanted == old {
        return (0, 0);
    }
    if old != 0 {
        node.clear_error(old);
    }
    if wanted != 0 {
        node.raise_error(wanted, [0; 5]);
    }
    node.app_mut().raised = wanted;
    (old, wanted)
}

/// After a reset: Reset Communication cleared every error (1003h, 1001h), so nothing is raised any more;
/// 2100h may hold a default or a stored value that is raised again.
pub fn error_injection_after_reset(node: &mut IoNode) -> (u16, u16) {
    node.app_mut().raised = 0;
    apply_error_injection(node)
}

/// The EDS text of the node (`storage`: whether 1010h/1011h announce that saving is supported): the
/// dictionary the node serves, program download (1F50h–1F57h) and the SDO records 1200h/1201h/1280h included,
/// every object in index order.
pub fn eds_text(config: NodeConfig, storage: bool) -> String {
    let mut comm = canopen_core::profile::CommProfile::<IoSizes>::new(config);
    comm.storage_supported = storage;
    let app: IoApp = ProgramDownload::new(ImageFile::new(None), IoModule::with_defaults());
    let od = SdoRecordsDesc::of::<IoSizes>(canopen_core::od::Merged { comm, app });
    let mut text = String::new();
    canopen_core::profile::eds::write_eds(&mut text, &EDS_INFO, &od).expect("formatting into a String cannot fail");
    text
}
