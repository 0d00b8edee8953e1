//! The node's side of the optional objects of [`crate::profile::optional`]: the application's access to
//! 1002h and 1013h, and 1020h reset when a 1011h restore changed the boot-up configuration (STORE-12). The
//! EMCY consumer (1028h) is the one test in `Node::handle_frame`, the receive filters' loop in
//! `rx_filter.rs`; TIME sets 1013h in `pdo.rs` (`handle_time`, `produce_time`).

use super::{Node, NodeSizes};
use crate::od::ObjectDictionary;
use crate::storage::Storage;

impl<A: ObjectDictionary, Z: NodeSizes, S: Storage> Node<A, Z, S> {
    /// Sets 1002h manufacturer status register (ERR-03: ro on the bus, TPDO-mappable; the stack never
    /// changes it).
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{Node, NoApplication}, od::ObjectDictionary, NodeId};
    /// let mut node: Node<NoApplication> = Node::new(NodeId::new(3).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// node.set_manufacturer_status(0x0102_0304);
    /// let mut b = [0u8; 4];
    /// assert_eq!(node.dictionary().read(0x1002, 0, 0, &mut b), Ok(4));
    /// assert_eq!(b, [0x04, 0x03, 0x02, 0x01]);
    /// ```
    #[cfg(feature = "manufacturer-status")]
    pub fn set_manufacturer_status(&mut self, status: u32) {
        self.comm.optional.manufacturer_status = status;
    }

    /// 1002h manufacturer status register.
    #[cfg(feature = "manufacturer-status")]
    pub const fn manufacturer_status(&self) -> u32 {
        self.comm.optional.manufacturer_status
    }

    /// 1013h high-resolution time stamp at the latest instant passed in, µs modulo 2³² (TIME-06).
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{Node, NoApplication}, CanFrame, Instant, NodeId};
    /// let mut node: Node<NoApplication> = Node::new(NodeId::new(3).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// node.handle_timeout(Instant::ZERO);
    /// // TIME 100h (consumed by default): 1 ms after midnight, day 0.
    /// node.handle_frame(Instant::from_millis(10), &CanFrame::new(0x100, &[0x01, 0, 0, 0, 0, 0]).unwrap());
    /// assert_eq!(node.high_res_time(), 1_000);
    /// node.handle_timeout(Instant::from_micros(10_250));
    /// assert_eq!(node.high_res_time(), 1_250);
    /// ```
    #[cfg(feature = "high-res-time")]
    pub fn high_res_time(&self) -> u32 {
        self.comm.optional.high_res_time()
    }

    /// STORE-12: a 1011h restore changed the boot-up configuration, so 1020h is set to 0, live and in the
    /// stored record (which then holds no 1020h: the default 0 loads after the next reset).
    #[cfg(feature = "verify-config")]
    pub(super) fn boot_configuration_restored(&mut self) {
        self.comm.optional.configuration_changed();
        // A failure leaves the old record; the restore itself succeeded and was answered.
        let _ = crate::storage::forget(&mut self.storage, 0x1020);
    }
}
