//! The CAN-IDs the node listens to, as acceptance filters for a CAN controller or a SocketCAN socket
//! (`CAN_RAW_FILTER`): a frame no filter accepts is one [`Node::handle_frame`] would ignore, so a runner that
//! installs them pays nothing for the other nodes' traffic (CAN-02: a node receives what its COB-IDs say).
//!
//! The list is a pure function of the node's current parameters (NMT, SYNC 1005h, TIME 1012h, the valid
//! RPDOs 1400h+, the TPDOs that answer a remote request, the SDO servers 1200h+, the server → client COB-IDs
//! of the valid SDO client records 1280h+, the heartbeat consumers 1016h,
//! the EMCY consumer, LSS, the node guarding request). Computing it is not free, so the node counts the
//! changes that may move it ([`Node::rx_filters_generation`]: a communication object written by SDO or the
//! local API, the dictionary handed out for writing, an NMT reset communication or reset node, which is
//! also where an LSS node-ID takes effect): a runner recomputes the list only when that number moved, and
//! re-installs it when it differs from the one installed.

use heapless::Vec;

use super::{Node, NodeSizes};
use crate::cob::{FunctionCode, LSS_MASTER_ID};
use crate::od::ObjectDictionary;
use crate::storage::Storage;

/// One acceptance filter: a frame with 11-bit CAN-ID `c` is accepted when `c & mask == id & mask`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RxFilter {
    /// The CAN-ID to compare.
    pub id: u16,
    /// The bits compared (7FFh: exactly `id`; 0: every frame).
    pub mask: u16,
}

/// How many filters [`Node::rx_filters`] returns at most; a node that would need more gets one filter that
/// accepts every frame (correct, only not cheaper).
pub const RX_FILTER_CAPACITY: usize = 32;

/// The filters of one node, in a fixed order (two calls on an unchanged node compare equal).
pub type RxFilters = Vec<RxFilter, RX_FILTER_CAPACITY>;

impl<A: ObjectDictionary, Z: NodeSizes, S: Storage> Node<A, Z, S> {
    /// A number that changes whenever [`rx_filters`](Self::rx_filters) may have changed: bumped on every
    /// communication object written (1000h–1FFFh, by SDO or by the local setters), whenever
    /// [`dictionary`](Self::dictionary) hands out the dictionary for writing, and on every reset
    /// communication or reset node (which is also where a node-ID configured by LSS takes effect). A runner
    /// keeps the generation its filters were computed at and skips the computation while it is unchanged.
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{NoApplication, Node}, Instant, NodeId};
    /// let mut node: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// let g = node.rx_filters_generation();
    /// node.handle_timeout(Instant::ZERO); // boots: reset communication
    /// assert_ne!(node.rx_filters_generation(), g);
    /// let g = node.rx_filters_generation();
    /// node.handle_timeout(Instant::from_millis(1)); // nothing changed
    /// assert_eq!(node.rx_filters_generation(), g);
    /// ```
    pub const fn rx_filters_generation(&self) -> u32 {
        self.rx_generation
    }

    /// Something that may change a receive COB-ID happened (see [`Node::rx_filters_generation`]).
    pub(crate) fn cob_ids_may_change(&mut self) {
        self.rx_generation = self.rx_generation.wrapping_add(1);
    }

    /// The acceptance filters covering every frame the node handles now: NMT, SYNC (1005h), TIME (1012h,
    /// when consumed), the valid RPDOs, the TPDOs that answer a remote request, the SDO servers (1200h and
    /// the valid 1201h+), the server → client COB-ID of each valid SDO client record (1280h+: what the
    /// application's client receives), the heartbeat consumers (1016h), the EMCY consumer (081h–0FFh), LSS (7E5h) and the node guarding request.
    /// A pure function of the node's parameters: a runner recomputes it when
    /// [`rx_filters_generation`](Self::rx_filters_generation) moved and re-installs it when it differs from
    /// the filters it installed (a COB-ID written by SDO, a reset communication).
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{NoApplication, Node, RxFilter}, NodeId};
    /// let node: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// let f = node.rx_filters();
    /// let accepts = |c: u16| f.iter().any(|x| c & x.mask == x.id & x.mask);
    /// assert!(accepts(0x000) && accepts(0x605) && accepts(0x705)); // NMT, SDO, guarding
    /// assert!(accepts(0x080)); // SYNC
    /// assert!(!accepts(0x606) && !accepts(0x586)); // another node's SDO server, our own SDO replies
    /// ```
    pub fn rx_filters(&self) -> RxFilters {
        let exact = |id: u16| RxFilter { id, mask: 0x7FF };
        let mut out = RxFilters::new();
        let mut push = |f: RxFilter| {
            if !out.contains(&f) && out.push(f).is_err() {
                return false;
            }
            true
        };
        let mut ok = cfg!(not(feature = "lss")) || push(exact(LSS_MASTER_ID));
        if self.has_node_id() {
            let own = FunctionCode::NmtErrorControl.cob_id(self.node_id);
            // NMT 000h; the EMCY consumer (every node's 081h–0FFh, which covers SYNC 080h); guarding on
            // 700h + own node-ID.
            ok &= push(exact(0x000)) && push(RxFilter { id: 0x080, mask: 0x780 }) && push(exact(own));
            // EMCY-10: the valid 1028h entries outside 081h–0FFh (none without the feature).
            for id in self.comm.optional.emcy_ids_outside_range() {
                ok &= push(exact(id));
            }
            let sync = self.sync.can_id();
            if sync != 0 {
                ok &= push(exact(sync));
            }
            #[cfg(feature = "time")]
            if crate::cob::CobIdEntry::from_raw(self.comm.params.time_cob_id).bit31() {
                ok &= push(exact(self.time_can_id()));
            }
            if let Some(sdo) = self.sdo.rx_cob_id() {
                ok &= push(exact(sdo));
            }
            for sdo in self.sdo_extra.as_ref().iter().filter_map(|s| s.rx_cob_id()) {
                ok &= push(exact(sdo)); // the valid additional servers 1201h+
            }
            for c in self.sdo_clients.as_ref().iter().filter(|c| c.is_valid()) {
                ok &= push(exact(c.cob_rx.can_id())); // SDO-56: the server's responses to a 1280h+ client
            }
            let rpdos = self.rpdos.as_ref().iter().filter_map(super::pdo::rx_id);
            for id in rpdos.chain(self.tpdos.as_ref().iter().filter_map(super::pdo::rtr_id)) {
                ok &= push(exact(id));
            }
            for &raw in self.comm.params.heartbeat_consumers.as_ref() {
                let entry = crate::heartbeat::ConsumerEntry::from_raw(raw);
                if entry.is_active() {
                    ok &= push(exact(0x700 | u16::from(entry.node_id & 0x7F)));
                }
            }
        }
        if !ok {
            out.clear();
            let _ = out.push(RxFilter { id: 0, mask: 0 });
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use crate::node::{NoApplication, Node};
    use crate::profile::NodeConfig;
    use crate::{CanFrame, Instant, NodeId};

    type N = Node<NoApplication>;

    fn accepts(node: &N, id: u16) -> bool {
        node.rx_filters().iter().any(|f| id & f.mask == f.id & f.mask)
    }

    fn sdo_write(node: &mut N, index: u16, sub: u8, value: u32) {
        let v = value.to_le_bytes();
        let req = [0x23, index as u8, (index >> 8) as u8, sub, v[0], v[1], v[2], v[3]];
        node.handle_frame(Instant::ZERO, &CanFrame::new(0x605, &req).unwrap());
        let reply = core::iter::from_fn(|| node.poll_transmit()).last().unwrap();
        assert_eq!(reply.data()[0], 0x60, "write {index:04X}h:{sub} answered {reply}");
    }

    /// CAN-02, SDO-05, PDO-04, HB-09: the filters follow a COB-ID written by SDO (1016h consumer, 1400h
    /// RPDO, 1012h TIME), and an NMT reset communication brings the power-on set back.
    #[test]
    fn filters_follow_cob_id_changes() {
        let mut node: N = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
        node.handle_timeout(Instant::ZERO);
        while node.poll_transmit().is_some() {}
        let before = node.rx_filters();
        let mut generation = node.rx_filters_generation();
        // Every change below moves the generation, so a runner that skips unchanged generations misses none.
        let mut moved = |node: &N| {
            let g = node.rx_filters_generation();
            let moved = g != generation;
            generation = g;
            moved
        };
        // TIME (100h) and LSS (7E5h) only in a build that has them.
        let built = |id: u16| (id != 0x100 || cfg!(feature = "time")) && (id != 0x7E5 || cfg!(feature = "lss"));
        for id in [0x000, 0x080, 0x081, 0x0FF, 0x100, 0x605, 0x705, 0x7E5] {
            assert_eq!(accepts(&node, id), built(id), "{id:03X}h");
        }
        for id in [0x185, 0x205, 0x585, 0x606, 0x706, 0x7E4] {
            assert!(!accepts(&node, id), "{id:03X}h");
        }
        node.handle_frame(Instant::ZERO, &CanFrame::new(0x605, &[0x40, 0x00, 0x10, 0, 0, 0, 0, 0]).unwrap());
        while node.poll_transmit().is_some() {}
        assert!(!moved(&node), "an SDO read changes no COB-ID");
        sdo_write(&mut node, 0x1016, 1, 0x0003_0100); // consume node 3's heartbeat, 256 ms
        assert!(accepts(&node, 0x703));
        assert!(moved(&node));
        #[cfg(feature = "time")]
        {
            sdo_write(&mut node, 0x1012, 0, 0x0000_0100); // stop consuming TIME
            assert!(!accepts(&node, 0x100));
            assert!(moved(&node));
        }
        sdo_write(&mut node, 0x1400, 1, 0x0000_0205); // RPDO1 valid on 205h
        assert!(accepts(&node, 0x205));
        assert!(moved(&node));
        assert_ne!(node.rx_filters(), before);
        node.handle_frame(Instant::ZERO, &CanFrame::new(0x000, &[0x82, 0x05]).unwrap()); // reset communication
        node.handle_timeout(Instant::ZERO);
        assert!(moved(&node));
        assert_eq!(node.rx_filters(), before);
    }

    /// CiA 305: a node without a node-ID listens to LSS only.
    #[test]
    #[cfg(feature = "lss")]
    fn unconfigured_node_listens_to_lss_only() {
        let node: N = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication).without_node_id();
        let f = node.rx_filters();
        assert_eq!(f.as_slice(), &[super::RxFilter { id: 0x7E5, mask: 0x7FF }]);
    }
}
