//! The master for code without an async runtime: [`BlockingMaster`] owns a single-threaded tokio runtime and
//! runs each call of the async [`Master`] to its end on it. The receive task and any SYNC producer run while
//! a call runs (between calls nothing is received; the streams keep what came, up to their capacity).
//!
//! ```
//! use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
//! use canopen_master::{blocking::BlockingMaster, sim::SimBus, NmtCommand};
//! let bus = SimBus::new();
//! let master = BlockingMaster::new(|| Ok(bus.port())).unwrap();
//! // Simulated nodes run on the master's runtime.
//! let node: Node<NoApplication> = Node::new(NodeId::new(3).unwrap(), NodeConfig::DEFAULT, NoApplication);
//! let _node = master.runtime().block_on(async { bus.spawn_node(node) });
//! assert_eq!(master.read::<u32>(3, 0x1000, 0).unwrap(), NodeConfig::DEFAULT.device_type);
//! master.write(3, 0x1017, 0, 100u16).unwrap();
//! master.nmt(3, NmtCommand::Start).unwrap();
//! ```

use std::io;

use tokio::runtime::Runtime;

use crate::{CanIo, Error, Master, Mode, NmtCommand, SdoValue};

/// A [`Master`] with blocking calls (see the [module docs](self)).
pub struct BlockingMaster {
    // Dropped before the runtime: its receive task is aborted while the runtime still exists.
    master: Master,
    runtime: Runtime,
}

impl BlockingMaster {
    /// A master on the CAN socket `open` makes (called inside the master's runtime).
    ///
    /// ```no_run
    /// let m = canopen_master::blocking::BlockingMaster::new(|| canopen_master::SocketCan::open("vcan0"))?;
    /// # Ok::<(), canopen_master::Error>(())
    /// ```
    pub fn new<I: CanIo>(open: impl FnOnce() -> io::Result<I>) -> Result<Self, Error> {
        let runtime = tokio::runtime::Builder::new_current_thread().enable_all().build()?;
        let master = {
            let _inside = runtime.enter();
            Master::new(open()?)
        };
        Ok(BlockingMaster { master, runtime })
    }

    /// A master on the SocketCAN interface `iface`.
    ///
    /// ```no_run
    /// let m = canopen_master::blocking::BlockingMaster::open("can0")?;
    /// let name: String = m.read(5, 0x1008, 0)?;
    /// # Ok::<(), canopen_master::Error>(())
    /// ```
    #[cfg(target_os = "linux")]
    pub fn open(iface: &str) -> Result<Self, Error> {
        BlockingMaster::new(|| crate::SocketCan::open(iface))
    }

    /// The async master (clone it into tasks of [`BlockingMaster::runtime`]).
    ///
    /// ```
    /// # let bus = canopen_master::sim::SimBus::new();
    /// let m = canopen_master::blocking::BlockingMaster::new(|| Ok(bus.port())).unwrap();
    /// assert_eq!(m.master().sdo_timeout(), canopen_master::DEFAULT_SDO_TIMEOUT);
    /// ```
    pub fn master(&self) -> &Master {
        &self.master
    }

    /// The runtime the calls run on.
    ///
    /// ```
    /// # let bus = canopen_master::sim::SimBus::new();
    /// let m = canopen_master::blocking::BlockingMaster::new(|| Ok(bus.port())).unwrap();
    /// assert_eq!(m.runtime().block_on(async { 1 + 1 }), 2);
    /// ```
    pub fn runtime(&self) -> &Runtime {
        &self.runtime
    }

    /// [`Master::read`], blocking.
    ///
    /// ```
    /// # let bus = canopen_master::sim::SimBus::new();
    /// let m = canopen_master::blocking::BlockingMaster::new(|| Ok(bus.port())).unwrap();
    /// let m = m.with_sdo_timeout(std::time::Duration::from_millis(10));
    /// assert!(m.read::<u32>(9, 0x1000, 0).unwrap_err().is_timeout()); // nobody there
    /// ```
    pub fn read<T: SdoValue>(&self, node: u8, index: u16, sub: u8) -> Result<T, Error> {
        self.runtime.block_on(self.master.read(node, index, sub))
    }

    /// [`Master::write`], blocking.
    ///
    /// ```
    /// # let bus = canopen_master::sim::SimBus::new();
    /// let m = canopen_master::blocking::BlockingMaster::new(|| Ok(bus.port())).unwrap();
    /// assert!(m.write(0, 0x2000, 0, 1u8).is_err()); // node-ID 0
    /// ```
    pub fn write<T: SdoValue>(&self, node: u8, index: u16, sub: u8, value: T) -> Result<(), Error> {
        self.runtime.block_on(self.master.write(node, index, sub, value))
    }

    /// [`Master::upload`], blocking.
    ///
    /// ```
    /// # let bus = canopen_master::sim::SimBus::new();
    /// let m = canopen_master::blocking::BlockingMaster::new(|| Ok(bus.port())).unwrap();
    /// assert!(m.upload(200, 0x1008, 0, canopen_master::BLOCK).is_err());
    /// ```
    pub fn upload(&self, node: u8, index: u16, sub: u8, mode: Mode) -> Result<Vec<u8>, Error> {
        self.runtime.block_on(self.master.upload(node, index, sub, mode))
    }

    /// [`Master::download`], blocking.
    ///
    /// ```
    /// # let bus = canopen_master::sim::SimBus::new();
    /// let m = canopen_master::blocking::BlockingMaster::new(|| Ok(bus.port())).unwrap();
    /// assert!(m.download(200, 0x2005, 0, &[1, 2, 3], canopen_master::BLOCK).is_err());
    /// ```
    pub fn download(&self, node: u8, index: u16, sub: u8, data: &[u8], mode: Mode) -> Result<(), Error> {
        self.runtime.block_on(self.master.download(node, index, sub, data, mode))
    }

    /// [`Master::nmt`], blocking.
    ///
    /// ```
    /// # let bus = canopen_master::sim::SimBus::new();
    /// let m = canopen_master::blocking::BlockingMaster::new(|| Ok(bus.port())).unwrap();
    /// m.nmt(0, canopen_master::NmtCommand::ResetCommunication).unwrap();
    /// ```
    pub fn nmt(&self, node: u8, command: NmtCommand) -> Result<(), Error> {
        self.runtime.block_on(self.master.nmt(node, command))
    }

    /// [`Master::scan`], blocking.
    ///
    /// ```
    /// # let bus = canopen_master::sim::SimBus::new();
    /// let m = canopen_master::blocking::BlockingMaster::new(|| Ok(bus.port())).unwrap();
    /// assert!(m.scan(std::time::Duration::from_millis(5)).unwrap().is_empty());
    /// ```
    pub fn scan(&self, timeout: std::time::Duration) -> Result<Vec<u8>, Error> {
        self.runtime.block_on(self.master.scan(timeout))
    }

    /// This master with another SDO time-out ([`Master::with_sdo_timeout`]).
    ///
    /// ```
    /// # let bus = canopen_master::sim::SimBus::new();
    /// let m = canopen_master::blocking::BlockingMaster::new(|| Ok(bus.port())).unwrap();
    /// let m = m.with_sdo_timeout(std::time::Duration::from_millis(50));
    /// assert_eq!(m.master().sdo_timeout().as_millis(), 50);
    /// ```
    pub fn with_sdo_timeout(self, timeout: std::time::Duration) -> Self {
        BlockingMaster { master: self.master.with_sdo_timeout(timeout), runtime: self.runtime }
    }
}
