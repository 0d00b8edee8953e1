//! The node's LSS side (CiA 305), kept apart from `node.rs`: constructors for nodes without a node-ID,
//! the 7E5h handler, the switch-delay timer, store completion, and the node-ID change at reset
//! communication. See [`crate::lss`] for the protocol and what it relies on.
//!
//! A node without a node-ID (FFh) stays in NMT Initialisation and serves LSS only: no boot-up, no
//! heartbeat, no NMT, SDO or guarding. When a master gives it a node-ID and switches it back to LSS
//! waiting, it runs reset communication and boots (boot-up frame, Pre-operational). A node-ID configured
//! while the node has one stays pending until the next NMT reset communication (or reset node).

use super::{Node, NodeSizes};
use crate::cob::{NodeId, LSS_SLAVE_ID};
use crate::event::Event;
use crate::frame::CanFrame;
use crate::lss::{LssSlave, LssStore, StoreError, PLACEHOLDER_NODE_ID};
use crate::od::ObjectDictionary;
use crate::profile::NodeConfig;
use crate::storage::{NoStorage, Storage};
use crate::time::Instant;
use crate::wire::lss::{frame_u32, LssResponse, UNCONFIGURED_NODE_ID};

impl<A: ObjectDictionary, Z: NodeSizes> Node<A, Z, NoStorage> {
    /// A node without a node-ID (FFh): after power-on it waits in Initialisation, serving LSS only, until
    /// an LSS master assigns one.
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{NoApplication, Node}, CanFrame, Instant, NmtState};
    /// let mut node: Node<NoApplication> = Node::new_unconfigured(NodeConfig::DEFAULT, NoApplication);
    /// node.handle_timeout(Instant::ZERO);
    /// assert_eq!(node.poll_transmit(), None); // no boot-up
    /// assert_eq!(node.state(), NmtState::Initialising);
    /// assert_eq!(node.lss_node_id(), None);
    /// ```
    pub fn new_unconfigured(config: NodeConfig, app: A) -> Self {
        Node::new(PLACEHOLDER_NODE_ID, config, app).without_node_id()
    }

    /// A node from a raw (for example stored) node-ID: 1–127 as [`Node::new`], FFh as
    /// [`Node::new_unconfigured`]; `None` for any other value.
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{NoApplication, Node}};
    /// let n: Node<NoApplication> = Node::from_raw_node_id(0x22, NodeConfig::DEFAULT, NoApplication).unwrap();
    /// assert_eq!(n.lss_node_id().map(|id| id.get()), Some(0x22));
    /// let u: Node<NoApplication> = Node::from_raw_node_id(0xFF, NodeConfig::DEFAULT, NoApplication).unwrap();
    /// assert_eq!(u.lss_node_id(), None);
    /// assert!(Node::<NoApplication>::from_raw_node_id(0, NodeConfig::DEFAULT, NoApplication).is_none());
    /// ```
    pub fn from_raw_node_id(raw: u8, config: NodeConfig, app: A) -> Option<Self> {
        match NodeId::new(raw) {
            Some(id) => Some(Node::new(id, config, app)),
            None if raw == UNCONFIGURED_NODE_ID => Some(Node::new_unconfigured(config, app)),
            None => None,
        }
    }
}

impl<A: ObjectDictionary, Z: NodeSizes, S: Storage> Node<A, Z, S> {
    /// The same node without a node-ID, waiting for an LSS master (for nodes built with
    /// [`Node::with_storage`]; [`Node::new_unconfigured`] is the short form without storage).
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{NoApplication, Node}, storage::NoStorage, NodeId};
    /// let node: Node<NoApplication> =
    ///     Node::with_storage(NodeId::new(1).unwrap(), NodeConfig::DEFAULT, NoApplication, NoStorage).without_node_id();
    /// assert_eq!(node.lss_node_id(), None);
    /// ```
    pub fn without_node_id(mut self) -> Self {
        self.lss = LssSlave::new(&self.comm.config.identity, None);
        self.cob_ids_may_change();
        self
    }

    /// The active node-ID, `None` while the node has none (then [`Node::node_id`] is a placeholder).
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{NoApplication, Node}, NodeId};
    /// let n: Node<NoApplication> = Node::new(NodeId::new(9).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// assert_eq!(n.lss_node_id(), NodeId::new(9));
    /// ```
    pub const fn lss_node_id(&self) -> Option<NodeId> {
        self.lss.active_node_id()
    }

    /// The LSS slave (state, pending node-ID and bit rate).
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{NoApplication, Node}, wire::lss::LssMode};
    /// let n: Node<NoApplication> = Node::new_unconfigured(NodeConfig::DEFAULT, NoApplication);
    /// assert_eq!(n.lss().mode(), LssMode::Waiting);
    /// ```
    pub const fn lss(&self) -> &LssSlave {
        &self.lss
    }

    /// The LSS slave, to declare the bit rate, the supported rates and store support.
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{NoApplication, Node}, wire::lss::BitRate};
    /// let mut n: Node<NoApplication> = Node::new_unconfigured(NodeConfig::DEFAULT, NoApplication);
    /// n.lss_mut().set_bit_rate(BitRate::K250);
    /// n.lss_mut().set_store_supported(true);
    /// ```
    pub fn lss_mut(&mut self) -> &mut LssSlave {
        &mut self.lss
    }

    /// Answers a pending LSS store configuration request ([`crate::lss::LssEvent::StoreRequested`]) by
    /// storing through `store`. Does nothing when no store is pending, so a runner may call it after every
    /// batch of events.
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, lss::{LssStore, StoreError}, node::{NoApplication, Node}};
    /// use canopen_core::{wire::lss::BitRate, CanFrame, Instant};
    /// struct Ram(Option<u8>);
    /// impl LssStore for Ram {
    ///     fn store(&mut self, node_id: u8, _: BitRate) -> Result<(), StoreError> {
    ///         self.0 = Some(node_id);
    ///         Ok(())
    ///     }
    /// }
    /// let mut node: Node<NoApplication> = Node::new_unconfigured(NodeConfig::DEFAULT, NoApplication);
    /// node.lss_mut().set_store_supported(true);
    /// let t = Instant::ZERO;
    /// for data in [[0x04, 1, 0, 0, 0, 0, 0, 0], [0x11, 0x22, 0, 0, 0, 0, 0, 0], [0x17, 0, 0, 0, 0, 0, 0, 0]] {
    ///     node.handle_frame(t, &CanFrame::new(0x7E5, &data).unwrap());
    /// }
    /// assert_eq!(node.poll_transmit(), CanFrame::new(0x7E4, &[0x11, 0, 0, 0, 0, 0, 0, 0])); // node-ID ok
    /// assert_eq!(node.poll_transmit(), None); // store waits for the application
    /// let mut ram = Ram(None);
    /// node.complete_lss_store(&mut ram);
    /// assert_eq!(ram.0, Some(0x22));
    /// assert_eq!(node.poll_transmit(), CanFrame::new(0x7E4, &[0x17, 0, 0, 0, 0, 0, 0, 0]));
    /// ```
    pub fn complete_lss_store(&mut self, store: &mut impl LssStore) {
        if !self.lss.store_pending() {
            return;
        }
        let result = store.store(self.lss.pending_node_id(), self.lss.pending_bit_rate());
        self.lss_store_result(result);
    }

    /// [`complete_lss_store`](Node::complete_lss_store) through the node's own storage, for a storage that
    /// also keeps the LSS configuration (a flash backend that owns the whole flash, for example).
    ///
    /// ```
    /// use canopen_core::{lss::{LssStore, StoreError}, node::{NoApplication, Node}, profile::NodeConfig};
    /// use canopen_core::{storage::{Storage, StorageError}, wire::lss::BitRate, CanFrame, Instant, NodeId};
    /// #[derive(Default)]
    /// struct Nv(Option<u8>);
    /// impl Storage for Nv {
    ///     fn capacity(&self) -> usize { 0 }
    ///     fn erase(&mut self, _: u8) -> Result<(), StorageError> { Err(StorageError::Unsupported) }
    ///     fn write(&mut self, _: u8, _: usize, _: &[u8]) -> Result<(), StorageError> { Err(StorageError::Unsupported) }
    ///     fn read(&mut self, _: u8, _: usize, _: &mut [u8]) -> Result<(), StorageError> { Err(StorageError::Unsupported) }
    /// }
    /// impl LssStore for Nv {
    ///     fn store(&mut self, node_id: u8, _: BitRate) -> Result<(), StoreError> {
    ///         self.0 = Some(node_id);
    ///         Ok(())
    ///     }
    /// }
    /// let id = NodeId::new(1).unwrap();
    /// let mut node: Node<NoApplication, canopen_core::Sizes, Nv> =
    ///     Node::with_storage(id, NodeConfig::DEFAULT, NoApplication, Nv::default()).without_node_id();
    /// node.lss_mut().set_store_supported(true);
    /// for data in [[0x04, 1, 0, 0, 0, 0, 0, 0], [0x11, 0x22, 0, 0, 0, 0, 0, 0], [0x17, 0, 0, 0, 0, 0, 0, 0]] {
    ///     node.handle_frame(Instant::ZERO, &CanFrame::new(0x7E5, &data).unwrap());
    /// }
    /// assert_eq!(node.poll_transmit(), CanFrame::new(0x7E4, &[0x11, 0, 0, 0, 0, 0, 0, 0]));
    /// node.complete_lss_store_in_storage();
    /// assert_eq!(node.storage_mut().0, Some(0x22));
    /// assert_eq!(node.poll_transmit(), CanFrame::new(0x7E4, &[0x17, 0, 0, 0, 0, 0, 0, 0]));
    /// ```
    pub fn complete_lss_store_in_storage(&mut self)
    where
        S: LssStore,
    {
        if !self.lss.store_pending() {
            return;
        }
        let result = self.storage.store(self.lss.pending_node_id(), self.lss.pending_bit_rate());
        self.lss_store_result(result);
    }

    /// Answers a pending LSS store request with a result the application got by other means.
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, lss::StoreError, node::{NoApplication, Node}};
    /// let mut node: Node<NoApplication> = Node::new_unconfigured(NodeConfig::DEFAULT, NoApplication);
    /// node.lss_store_result(Err(StoreError::MediaAccess)); // nothing pending: no frame
    /// assert_eq!(node.poll_transmit(), None);
    /// ```
    pub fn lss_store_result(&mut self, result: Result<(), StoreError>) {
        if let Some(r) = self.lss.complete_store(result) {
            self.lss_transmit(r);
        }
    }

    /// Whether the node has a node-ID (CiA 305: without one it serves LSS only).
    pub(super) const fn has_node_id(&self) -> bool {
        self.lss.active_node_id().is_some()
    }

    /// A frame on 7E5h, in any NMT state. Out of line (LSS frames are rare; inlined into the frame dispatch it
    /// was 12 B more of the node firmware's flash).
    #[inline(never)]
    pub(super) fn handle_lss(&mut self, now: Instant, frame: &CanFrame) {
        // An RTR has no data: `serve` ignores it with every other frame that is not 8 bytes (CAN-07).
        let out = self.lss.serve(now, frame.data());
        if out.cs != 0 {
            self.send(LSS_SLAVE_ID, frame_u32(out.cs, out.value), 8);
        }
        if let Some(e) = out.event {
            self.push_event(Event::Lss(e));
            if self.lss.resets_communication(e) {
                self.reset(false, now);
            }
        }
    }

    /// The switch-delay timer.
    pub(super) fn lss_timeout(&mut self, now: Instant) {
        if let Some(e) = self.lss.handle_timeout(now) {
            self.push_event(Event::Lss(e));
        }
    }

    /// Reset communication: the pending node-ID becomes active. Returns false when the node has no
    /// node-ID: it then stays in Initialisation with its heartbeat producer off (`Node::reset`).
    pub(super) fn lss_reset_communication(&mut self) -> bool {
        match self.lss.apply_pending() {
            Some(id) => {
                self.node_id = id;
                true
            }
            None => false,
        }
    }

    fn lss_transmit(&mut self, r: LssResponse) {
        self.send(LSS_SLAVE_ID, r.emit(), 8);
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use crate::node::{NoApplication, Node};
    use crate::profile::NodeConfig;
    use crate::{CanFrame, Instant};

    /// CAN-07: a remote frame on 7E5h is no LSS request (it has no data), whatever its DLC and the LSS
    /// state: no answer, no event, no state change; the same requests as data frames are answered.
    #[test]
    fn lss_remote_frames_are_ignored_can_07() {
        let mut n: Node<NoApplication> = Node::new_unconfigured(NodeConfig::DEFAULT, NoApplication);
        let t = Instant::ZERO;
        n.handle_timeout(t);
        assert_eq!(n.poll_transmit(), None);
        while n.poll_event().is_some() {}
        for dlc in [0, 1, 8] {
            n.handle_frame(t, &CanFrame::new_rtr(0x7E5, dlc).unwrap());
        }
        assert_eq!((n.poll_transmit(), n.poll_event()), (None, None));
        // Identify non-configured remote slave (4Ch) as a data frame: answered 50h.
        n.handle_frame(t, &CanFrame::new(0x7E5, &[0x4C, 0, 0, 0, 0, 0, 0, 0]).unwrap());
        assert_eq!(n.poll_transmit(), CanFrame::new(0x7E4, &[0x50, 0, 0, 0, 0, 0, 0, 0]));
        // In LSS configuration too, an RTR is ignored.
        n.handle_frame(t, &CanFrame::new(0x7E5, &[0x04, 1, 0, 0, 0, 0, 0, 0]).unwrap());
        while n.poll_event().is_some() {}
        for dlc in [0, 2, 8] {
            n.handle_frame(t, &CanFrame::new_rtr(0x7E5, dlc).unwrap());
        }
        assert_eq!((n.poll_transmit(), n.poll_event()), (None, None));
        assert_eq!(n.lss().mode(), crate::wire::lss::LssMode::Configuration);
    }
}
