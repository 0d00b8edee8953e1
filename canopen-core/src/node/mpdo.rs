//! The node's MPDO wiring (feature `mpdo`; the frame and list formats are [`crate::pdo::mpdo`]).
//!
//! A PDO whose mapping sub 00h is FEh (SAM) or FFh (DAM) is an MPDO (MPDO-05); its COB-ID, transmission
//! type and inhibit time are its communication record's, as for any PDO.
//!
//! - **DAM consumer** (RPDO, FFh; MPDO-02): a DAM frame addressed to this node's ID or to 0 writes its 1–4
//!   data bytes into the object the multiplexer names, which must be RPDO-mappable (the write a one-entry
//!   mapping of it would make: its size, its limits and hooks). No confirmation. An object that does not
//!   exist (0602 0000h / 0609 0011h) raises EMCY 8230h (EEC-18, manufacturer bytes: RPDO number, index LE,
//!   sub-index), cleared by the next DAM-MPDO that is written; any other refusal (not mappable, read-only,
//!   larger than 4 bytes, out of range) drops the frame silently: the seed names no reaction, and there is
//!   no SDO to abort.
//! - **SAM consumer** (RPDO, FEh; MPDO-03): a SAM frame whose (producer node, index, sub-index) one entry of
//!   the object dispatching list 1FD0h maps is written into the local object it maps to, as above; no
//!   entry, or a refused write, drops it (8230h is DAM's).
//! - A consumer processes each frame at reception whatever its transmission type (MPDOs are event-driven,
//!   MPDO-04), and runs no event timer (deadline monitoring of a multiplexed stream has no one object
//!   to watch).
//! - Each write is reported as [`Event::MpdoWritten`]. A frame of the other address type, of another
//!   length than 8, or a SAM frame from node-ID 0 is ignored (CAN-07). Only in Operational (PDO-04).
//! - **DAM producer** (TPDO, FFh): [`Node::send_dam_mpdo`] sends the application's value for the object
//!   (index, sub-index) of a destination node (0 = all). The seed translation gives no rule for the DAM
//!   producer's mapping entries, so, as the lely stack does (`co_dam_mpdo_event`), they are not used and
//!   the application names the destination's object itself.
//! - **SAM producer** (TPDO, FEh): [`Node::send_sam_mpdo`] sends this node's object (index, sub-index) with
//!   its own node-ID, if an entry of the object scanner list 1FA0h covers it and it is TPDO-mappable and at
//!   most 4 bytes.
//! - Both producers (MPDO-04): only event-driven TPDOs (transmission type FEh/FFh), no SYNC, RTR, event
//!   timer or send on entering Operational; the inhibit time (sub 03h) refuses a second MPDO until it has
//!   passed ([`MpdoRefused::Inhibited`]): an MPDO names one object, so there is no "latest value" to send
//!   later as a plain TPDO does.
//!
//! One SAM producer per device (MPDO-03): writing FEh to a second TPDO's mapping by SDO is refused with
//! 0604 0043h (the seed names no code; general parameter incompatibility: it conflicts with the other
//! TPDO); defaults (`PdoDefault::count`) are the integrator's and are not checked.
//!
//! Not done: one scanner list (1FA0h) and one dispatching list (1FD0h) of 16 entries each, not the 48 of
//! each kind CiA 301 allows.

use super::{Node, NodeSizes};
use crate::emcy::codes;
use crate::event::Event;
use crate::frame::CanFrame;
use crate::nmt::NmtState;
use crate::od::{AbortCode, Merged, ObjectDictionary, PdoDir};
use crate::pdo::mpdo::{AddressMode, Mpdo, MpdoRefused};
use crate::storage::Storage;

impl<A: ObjectDictionary, Z: NodeSizes, S: Storage> Node<A, Z, S> {
    /// A frame for RPDO `k`, an MPDO consumer of kind `mode` (the module docs).
    pub(super) fn handle_mpdo(&mut self, k: usize, mode: AddressMode, frame: &CanFrame) {
        let Ok(m) = Mpdo::parse(frame.data()) else { return }; // CAN-07
        if m.mode != mode {
            return;
        }
        let (index, sub) = match mode {
            AddressMode::Destination if m.addresses(self.node_id.get()) => (m.index, m.sub),
            AddressMode::Destination => return,
            AddressMode::Source => match self.comm.optional.mpdo_dispatch(m.node, m.index, m.sub) {
                Some(target) => target,
                None => return,
            },
        };
        let mut od = Merged { comm: &mut self.comm, app: &mut self.app };
        let written = od.pdo_resolve(index, sub, PdoDir::Rpdo).and_then(|h| {
            let data = m.data.get(..usize::from(h.size)).ok_or(AbortCode::NotMappable)?;
            od.pdo_write(&h, data)
        });
        let dam = mode == AddressMode::Destination;
        match written {
            Ok(()) => {
                if dam && self.comm.errors.is_active(codes::MPDO_NOT_PROCESSED) {
                    self.clear_error(codes::MPDO_NOT_PROCESSED);
                }
                self.push_event(Event::MpdoWritten { pdo: k as u16, index, sub });
            }
            Err(AbortCode::ObjectDoesNotExist | AbortCode::SubIndexDoesNotExist) if dam => {
                let [lo, hi] = index.to_le_bytes();
                self.raise_error(codes::MPDO_NOT_PROCESSED, [super::pdo::rpdo_number(k), lo, hi, sub, 0]);
                // MPDO-02, EEC-18
            }
            Err(_) => {}
        }
    }

    /// Sends a DAM-MPDO on TPDO `k` (0-based; its mapping sub 00h is FFh): `data` (1–4 bytes, LE) for the
    /// object (`index`, `sub`) of node `node`, 0 = every DAM consumer (MPDO-01/02/04). Only in
    /// Operational, on an event-driven TPDO, once its inhibit time has passed.
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{Node, NoApplication}, pdo::PdoDefault, Instant, NmtState, NodeId};
    /// const CFG: NodeConfig = NodeConfig { tpdo: &[PdoDefault { count: Some(0xFF), ..PdoDefault::EVENT }], ..NodeConfig::DEFAULT };
    /// let mut node: Node<NoApplication> = Node::new(NodeId::new(1).unwrap(), CFG, NoApplication);
    /// node.handle_timeout(Instant::ZERO);
    /// node.enter_state(NmtState::Operational);
    /// while node.poll_transmit().is_some() {}
    /// node.send_dam_mpdo(0, 5, 0x2000, 1, &[0x34, 0x12]).unwrap();
    /// let f = node.poll_transmit().unwrap();
    /// assert_eq!((f.cob_id(), f.data()), (0x181, &[0x85, 0x00, 0x20, 0x01, 0x34, 0x12, 0x00, 0x00][..]));
    /// ```
    pub fn send_dam_mpdo(&mut self, k: usize, node: u8, index: u16, sub: u8, data: &[u8]) -> Result<(), MpdoRefused> {
        if node > 127 {
            return Err(MpdoRefused::InvalidNode);
        }
        let mut value = [0u8; 4];
        value.get_mut(..data.len()).ok_or(MpdoRefused::TooLong)?.copy_from_slice(data);
        self.mpdo_ready(k, AddressMode::Destination)?;
        self.emit_mpdo(k, Mpdo { mode: AddressMode::Destination, node, index, sub, data: value });
        Ok(())
    }

    /// Sends a SAM-MPDO on TPDO `k` (0-based; its mapping sub 00h is FEh): this node's object (`index`,
    /// `sub`) with its own node-ID, when an entry of the object scanner list 1FA0h covers it (MPDO-01/03/04).
    /// The object must be TPDO-mappable and at most 4 bytes. Only in Operational, on an event-driven TPDO,
    /// once its inhibit time has passed.
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{Node, NoApplication}, od::ObjectDictionary, pdo::{PdoDefault, mpdo::MpdoRefused}, Instant, NmtState, NodeId};
    /// const CFG: NodeConfig = NodeConfig { tpdo: &[PdoDefault { count: Some(0xFE), ..PdoDefault::EVENT }], ..NodeConfig::DEFAULT };
    /// let mut node: Node<NoApplication> = Node::new(NodeId::new(3).unwrap(), CFG, NoApplication);
    /// node.handle_timeout(Instant::ZERO);
    /// node.enter_state(NmtState::Operational);
    /// while node.poll_transmit().is_some() {}
    /// assert_eq!(node.send_sam_mpdo(0, 0x1001, 0), Err(MpdoRefused::NotScanned));
    /// node.dictionary().write(0x1FA0, 1, &0x0010_0100u32.to_le_bytes()).unwrap(); // scan 1001h:00
    /// node.send_sam_mpdo(0, 0x1001, 0).unwrap();
    /// assert_eq!(node.poll_transmit().unwrap().data(), &[0x03, 0x01, 0x10, 0x00, 0x00, 0x00, 0x00, 0x00]);
    /// ```
    pub fn send_sam_mpdo(&mut self, k: usize, index: u16, sub: u8) -> Result<(), MpdoRefused> {
        self.mpdo_ready(k, AddressMode::Source)?;
        if !self.comm.optional.mpdo_scanned(index, sub) {
            return Err(MpdoRefused::NotScanned);
        }
        let od = Merged { comm: &mut self.comm, app: &mut self.app };
        let h = od.pdo_resolve(index, sub, PdoDir::Tpdo).map_err(MpdoRefused::Object)?;
        let mut data = [0u8; 4];
        let buf = data.get_mut(..usize::from(h.size)).ok_or(MpdoRefused::TooLong)?;
        od.pdo_read(&h, buf).map_err(MpdoRefused::Object)?;
        self.emit_mpdo(k, Mpdo { mode: AddressMode::Source, node: self.node_id.get(), index, sub, data });
        Ok(())
    }

    /// Both producers: Operational, and TPDO `k` an event-driven MPDO of kind `mode` out of its inhibit time.
    fn mpdo_ready(&self, k: usize, mode: AddressMode) -> Result<(), MpdoRefused> {
        if self.nmt.state() != NmtState::Operational {
            return Err(MpdoRefused::NotOperational);
        }
        self.tpdos.as_ref().get(k).ok_or(MpdoRefused::NotMpdo)?.mpdo_ready(self.now, mode)
    }

    /// Queues `m` on TPDO `k`'s COB-ID; its inhibit time starts.
    fn emit_mpdo(&mut self, k: usize, m: Mpdo) {
        let now = self.now;
        let Some(t) = self.tpdos.as_mut().get_mut(k) else { return };
        t.mpdo_sent(now);
        let frame = CanFrame::from_parts(t.can_id(), m.emit(), 8);
        self.transmit(frame);
    }
}
