//! PDO configuration through SDO, in the CiA 301 order (PDO-35): invalidate the PDO (COB-ID bit 31 = 1),
//! clear the mapping count, write the entries, set the count, write the communication parameters, and
//! validate it again (bit 31 = 0). The communication parameters the node refuses while the PDO is valid
//! (inhibit time PDO-10/PDO-24, COB-ID PDO-17) are written while it is invalid.

use crate::{Error, Master};

/// Which PDO: receive (1400h/1600h + n - 1) or transmit (1800h/1A00h + n - 1).
///
/// ```
/// use canopen_master::pdo::Pdo;
/// assert_eq!(Pdo::Tpdo(1).comm_index().unwrap(), 0x1800);
/// assert_eq!(Pdo::Rpdo(2).mapping_index().unwrap(), 0x1601);
/// assert!(Pdo::Tpdo(0).comm_index().is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pdo {
    /// RPDO n (1..=512).
    Rpdo(u16),
    /// TPDO n (1..=512).
    Tpdo(u16),
}

impl Pdo {
    fn number(self) -> Result<u16, Error> {
        let n = match self {
            Pdo::Rpdo(n) | Pdo::Tpdo(n) => n,
        };
        if (1..=512).contains(&n) {
            Ok(n - 1)
        } else {
            Err(Error::InvalidArgument(format!("PDO number {n} is not in 1..=512")))
        }
    }

    /// The communication parameter index (1400h + n - 1 or 1800h + n - 1).
    pub fn comm_index(self) -> Result<u16, Error> {
        let base = if matches!(self, Pdo::Rpdo(_)) { 0x1400 } else { 0x1800 };
        Ok(base + self.number()?)
    }

    /// The mapping parameter index (1600h + n - 1 or 1A00h + n - 1).
    pub fn mapping_index(self) -> Result<u16, Error> {
        Ok(self.comm_index()? + 0x200)
    }
}

/// One mapped object (PDO-31): index, sub-index and length in bits.
///
/// ```
/// use canopen_master::pdo::MapEntry;
/// assert_eq!(MapEntry { index: 0x6000, sub: 1, bits: 8 }.raw(), 0x6000_0108);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MapEntry {
    /// Object index.
    pub index: u16,
    /// Sub-index.
    pub sub: u8,
    /// Length in bits.
    pub bits: u8,
}

impl MapEntry {
    /// The UNSIGNED32 written to the mapping record.
    pub fn raw(self) -> u32 {
        u32::from(self.index) << 16 | u32::from(self.sub) << 8 | u32::from(self.bits)
    }
}

/// What to configure. `None` fields keep the node's value.
///
/// ```
/// use canopen_master::pdo::{MapEntry, PdoConfig};
/// let c = PdoConfig { transmission_type: Some(1), ..PdoConfig::mapping(&[MapEntry { index: 0x6000, sub: 1, bits: 8 }]) };
/// assert_eq!(c.mapping.len(), 1);
/// ```
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct PdoConfig {
    /// The CAN-ID (bits 0..=10; bit 30 "no RTR" may be set too), `None` to keep the current one.
    pub cob_id: Option<u32>,
    /// Sub 02h transmission type.
    pub transmission_type: Option<u8>,
    /// Sub 03h inhibit time in 100 µs (TPDO; RPDOs may refuse it).
    pub inhibit_100us: Option<u16>,
    /// Sub 05h event timer in ms.
    pub event_timer_ms: Option<u16>,
    /// The new mapping (empty: the PDO stays disabled after the call).
    pub mapping: Vec<MapEntry>,
}

impl PdoConfig {
    /// A configuration that only remaps.
    pub fn mapping(entries: &[MapEntry]) -> Self {
        PdoConfig { mapping: entries.to_vec(), ..PdoConfig::default() }
    }
}

/// COB-ID bit 31: the PDO does not exist (PDO-07, PDO-15).
const INVALID: u32 = 0x8000_0000;

impl Master {
    /// Configures and remaps `pdo` of `node` in the CiA 301 order (PDO-35, see the [module docs](self)). An
    /// empty mapping leaves the PDO invalid. The node must accept it in its NMT state (Pre-operational
    /// always does).
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// use canopen_master::pdo::{MapEntry, Pdo, PdoConfig};
    /// let bus = canopen_master::sim::SimBus::new();
    /// let _n = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(2).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let m = canopen_master::Master::new(bus.port());
    /// // 1017h is not PDO-mappable: step 3 is refused with 0604 0041h (PDO-36), the PDO stays invalid.
    /// let map = [MapEntry { index: 0x1017, sub: 0, bits: 16 }];
    /// let e = m.configure_pdo(2, Pdo::Tpdo(1), &PdoConfig::mapping(&map)).await.unwrap_err();
    /// assert_eq!(e.abort_code(), Some(0x0604_0041));
    /// assert!(e.to_string().ends_with("object cannot be mapped to the PDO"));
    /// assert_ne!(m.read::<u32>(2, 0x1800, 1).await.unwrap() & 0x8000_0000, 0);
    /// # });
    /// ```
    pub async fn configure_pdo(&self, node: u8, pdo: Pdo, config: &PdoConfig) -> Result<(), Error> {
        let (comm, map) = (pdo.comm_index()?, pdo.mapping_index()?);
        if config.mapping.len() > 0x40 {
            return Err(Error::InvalidArgument(format!("{} mapping entries, at most 64", config.mapping.len())));
        }
        // 1. Invalidate.
        let current: u32 = self.read(node, comm, 1).await?;
        if current & INVALID == 0 {
            self.write(node, comm, 1, current | INVALID).await?;
        }
        // 2.-4. Remap.
        self.write(node, map, 0, 0u8).await?;
        for (sub, entry) in (1u8..).zip(&config.mapping) {
            self.write(node, map, sub, entry.raw()).await?;
        }
        self.write(node, map, 0, config.mapping.len() as u8).await?;
        // Communication parameters, while the PDO is invalid.
        if let Some(t) = config.transmission_type {
            self.write(node, comm, 2, t).await?;
        }
        if let Some(t) = config.inhibit_100us {
            self.write(node, comm, 3, t).await?;
        }
        if let Some(t) = config.event_timer_ms {
            self.write(node, comm, 5, t).await?;
        }
        let cob = config.cob_id.map_or(current & !INVALID, |id| id & !INVALID);
        if config.cob_id.is_some() {
            self.write(node, comm, 1, cob | INVALID).await?;
        }
        // 5. Validate (unless there is nothing mapped).
        if !config.mapping.is_empty() {
            self.write(node, comm, 1, cob).await?;
        }
        Ok(())
    }

    /// Invalidates `pdo` of `node` (COB-ID bit 31 = 1).
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let bus = canopen_master::sim::SimBus::new();
    /// let _n = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(2).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let m = canopen_master::Master::new(bus.port());
    /// m.disable_pdo(2, canopen_master::pdo::Pdo::Tpdo(1)).await.unwrap();
    /// assert_ne!(m.read::<u32>(2, 0x1800, 1).await.unwrap() & 0x8000_0000, 0);
    /// # });
    /// ```
    pub async fn disable_pdo(&self, node: u8, pdo: Pdo) -> Result<(), Error> {
        let comm = pdo.comm_index()?;
        let current: u32 = self.read(node, comm, 1).await?;
        if current & INVALID == 0 {
            self.write(node, comm, 1, current | INVALID).await?;
        }
        Ok(())
    }
}
