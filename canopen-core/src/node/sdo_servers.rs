//! Additional SDO servers 1201h–127Fh (issue 17, SDO-54, SDO-55, SDO-57): [`WithSdoServers`]`<Z, N>` gives a
//! node `N` of them beside the default server 1200h; [`Sizes`](crate::Sizes) gives none, and then none of
//! this code is built into a firmware (every path below is behind `N > 0`, a constant).
//!
//! - The records 1201h+ live in the node (`sdo_records`) and are read and written by SDO through
//!   [`WithRecords`] over the node's dictionary (only when `N > 0` or `M > 0`: with none, the servers see the node's
//!   dictionary as before, the same code and bytes): sub 00h = 3 (const), sub 01h COB-ID
//!   client → server and sub 02h COB-ID server → client (rw, UNSIGNED32), sub 03h the client's node-ID
//!   (rw, UNSIGNED8 01h–7Fh, 0 until written; information only). Power-on and every reset
//!   communication set both COB-IDs to 8000_0000h: invalid, the server does not exist (SDO-54).
//! - A write follows COB-14/COB-15/COB-16/COB-13: the frame bit (29-bit) or bits 28–11 set → 0609 0030h; a
//!   CAN-ID change while the entry is valid (bit 31 = 0) → 0609 0030h (invalidate, change, re-validate); a
//!   valid entry on a restricted CAN-ID → 0609 0030h. Bit 30 (dyn) is kept as written.
//! - A server exists while bit 31 = 0 in both entries (SDO-55); it then receives on sub 01h and answers on
//!   sub 02h, and each server keeps its own transfer, so transfers on different servers run at once.
//! - A record written by SDO takes effect when the write's response is queued (on the old COB-ID): a server
//!   whose parameters changed drops its transfer without a frame, and the receive filters follow
//!   ([`Node::rx_filters`]).
//! - With `N > 0` the default server's record 1200h is readable too (SDO-53): sub 00h = 2, sub 01h = 600h +
//!   node-ID, sub 02h = 580h + node-ID, all read-only.
//!
//! - The EDS lists the records the node serves ([`SdoRecordsDesc`], [`Node::describe`]): 1200h and
//!   1201h+ (when `N > 0`) and 1280h+ as CiA 306 RECORDs (`ObjectType=0x9`), each sub-entry with the data
//!   type, access and power-on value SDO answers with.
//! - The valid client records' server → client COB-IDs are in the receive filters ([`Node::rx_filters`]), so
//!   a runner that installs them lets the application's [`SdoClient`](crate::sdo::SdoClient) hear its server.
//!
//! Not built: storing the records (1010h; STORE-13 holds: never stored).

use super::{Node, NodeSizes, PdoTable};
use crate::cob::{is_restricted, CobIdEntry, NodeId};
use crate::event::Event;
use crate::frame::CanFrame;
use crate::heartbeat::ConsumerSizes;
use crate::nmt::Service;
use crate::od::{count_entry, EntryDesc, Merged, ObjectCode, ObjectDesc, OdDescribe, Value};
use crate::od::{AbortCode, Access, DataType, ObjectDictionary, OdValue, PdoDir, PdoHandle, PdoMapping, SubInfo};
use crate::profile::CommProfile;
use crate::profile::ProfileSizes;
use crate::sdo::{SdoServer, SdoServerParams};
use crate::sizes::Slots;
use crate::storage::Storage;
use crate::time::{Deadline, Instant};
use core::marker::PhantomData;
use heapless::deque::DequeInner;

/// The capacities `Z` plus `N` additional SDO servers 1201h..=1200h + `N` (`N` ≤ 127) and `M` SDO client
/// records 1280h..1280h + `M` - 1 (`M` ≤ 128, SDO-56: for the application's clients, see
/// [`Node::sdo_client_record`]).
///
/// ```
/// use canopen_core::{node::{NoApplication, Node, WithSdoServers}, profile::NodeConfig, CanFrame, Instant, NodeId};
/// // The default sizes and one more server, 1201h.
/// let mut node: Node<NoApplication, WithSdoServers> =
///     Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
/// node.handle_timeout(Instant::ZERO);
/// while node.poll_transmit().is_some() {}
/// // 1201h sub 01h, read through the default server: invalid until configured (SDO-54).
/// node.handle_frame(Instant::ZERO, &CanFrame::new(0x605, &[0x40, 0x01, 0x12, 0x01, 0, 0, 0, 0]).unwrap());
/// assert_eq!(node.poll_transmit().unwrap().data(), &[0x43, 0x01, 0x12, 0x01, 0, 0, 0, 0x80]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct WithSdoServers<Z = crate::Sizes, const N: usize = 1, const M: usize = 0>(PhantomData<Z>);

impl<Z: ConsumerSizes, const N: usize, const M: usize> ConsumerSizes for WithSdoServers<Z, N, M> {
    const HB: usize = Z::HB;
    type Consumers = Z::Consumers;
    type ConsumerTimes = Z::ConsumerTimes;
    const NO_CONSUMERS: Self::Consumers = Z::NO_CONSUMERS;
    const ZERO_TIMES: Self::ConsumerTimes = Z::ZERO_TIMES;
}

impl<Z: ProfileSizes, const N: usize, const M: usize> ProfileSizes for WithSdoServers<Z, N, M> {
    const RPDO: usize = Z::RPDO;
    const TPDO: usize = Z::TPDO;
    type RpdoComm = Z::RpdoComm;
    type RpdoMap = Z::RpdoMap;
    type TpdoComm = Z::TpdoComm;
    type TpdoMap = Z::TpdoMap;
    const RPDO_COMM: Self::RpdoComm = Z::RPDO_COMM;
    const RPDO_MAP: Self::RpdoMap = Z::RPDO_MAP;
    const TPDO_COMM: Self::TpdoComm = Z::TPDO_COMM;
    const TPDO_MAP: Self::TpdoMap = Z::TPDO_MAP;
}

impl<Z: NodeSizes, const N: usize, const M: usize> NodeSizes for WithSdoServers<Z, N, M> {
    const TXQ: usize = Z::TXQ;
    const EVQ: usize = Z::EVQ;
    type Rpdos = Z::Rpdos;
    type Tpdos = Z::Tpdos;
    type RpdoTable = Z::RpdoTable;
    type TpdoTable = Z::TpdoTable;
    type TxQueue = Z::TxQueue;
    type EventQueue = Z::EventQueue;
    const RPDO_TABLE: PdoTable<Self::RpdoTable> = Z::RPDO_TABLE;
    const TPDO_TABLE: PdoTable<Self::TpdoTable> = Z::TPDO_TABLE;
    const TX_QUEUE: DequeInner<CanFrame, Self::TxQueue> = Z::TX_QUEUE;
    const EVENT_QUEUE: DequeInner<Event, Self::EventQueue> = Z::EVENT_QUEUE;
    type ExtraSdo = [SdoServer; N];
    type ExtraSdoParams = [SdoServerParams; N];
    type SdoClients = [SdoClientRecord; M];
}

/// Whether `index` is an SDO server record, 1200h–127Fh.
#[inline]
pub(crate) const fn is_server_record(index: u16) -> bool {
    index >> 7 == 0x1200 >> 7
}

/// Whether `index` is an SDO server or client record, 1200h–12FFh.
#[inline]
const fn is_sdo_record(index: u16) -> bool {
    index >> 8 == 0x12
}

/// An SDO client parameter record 1280h+ (SDO-56): what the application's [`SdoClient`] of that channel
/// uses, configured locally ([`Node::set_sdo_client_record`]) or by SDO (a configuration tool or a
/// master writing the node's dictionary).
///
/// [`SdoClient`]: crate::sdo::SdoClient
///
/// ```
/// use canopen_core::node::SdoClientRecord;
/// let r = SdoClientRecord::DISABLED;
/// assert!(r.cob_tx.bit31() && r.cob_rx.bit31() && r.server_node == 0);
/// assert!(!r.is_valid());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SdoClientRecord {
    /// Sub 01h: COB-ID client → server (the client sends on it).
    pub cob_tx: CobIdEntry,
    /// Sub 02h: COB-ID server → client (the client receives on it).
    pub cob_rx: CobIdEntry,
    /// Sub 03h: node-ID of the server (01h–7Fh; 0 until configured).
    pub server_node: u8,
}

impl SdoClientRecord {
    /// Power-on and reset communication value: both COB-IDs invalid (bit 31 = 1), no server node-ID.
    ///
    /// ```
    /// # use canopen_core::node::SdoClientRecord;
    /// assert_eq!(SdoClientRecord::DISABLED.cob_tx.raw(), 0x8000_0000);
    /// ```
    pub const DISABLED: SdoClientRecord = SdoClientRecord {
        cob_tx: CobIdEntry::from_raw(CobIdEntry::BIT31),
        cob_rx: CobIdEntry::from_raw(CobIdEntry::BIT31),
        server_node: 0,
    };

    /// Whether the channel exists: bit 31 clear in both COB-IDs (SDO-55's rule, as for a server).
    ///
    /// ```
    /// # use canopen_core::node::SdoClientRecord;
    /// # use canopen_core::cob::CobIdEntry;
    /// let r = SdoClientRecord { cob_tx: CobIdEntry::from_raw(0x603), cob_rx: CobIdEntry::from_raw(0x583), server_node: 3 };
    /// assert!(r.is_valid());
    /// ```
    pub const fn is_valid(&self) -> bool {
        (self.cob_tx.raw() | self.cob_rx.raw()) & (CobIdEntry::BIT31 | CobIdEntry::FRAME) == 0
    }

    /// The parameters for an [`SdoClient`](crate::sdo::SdoClient), when the channel is valid.
    ///
    /// ```
    /// # use canopen_core::node::SdoClientRecord;
    /// # use canopen_core::cob::CobIdEntry;
    /// let r = SdoClientRecord { cob_tx: CobIdEntry::from_raw(0x603), cob_rx: CobIdEntry::from_raw(0x583), server_node: 3 };
    /// assert_eq!(r.client_params().map(|p| (p.tx_cob_id(), p.rx_cob_id())), Some((0x603, 0x583)));
    /// assert!(SdoClientRecord::DISABLED.client_params().is_none());
    /// ```
    #[cfg(feature = "sdo-client")]
    pub const fn client_params(&self) -> Option<crate::sdo::SdoClientParams> {
        if !self.is_valid() {
            return None;
        }
        Some(crate::sdo::SdoClientParams { cob_tx: self.cob_tx, cob_rx: self.cob_rx, server_node: self.server_node })
    }
}

/// The dictionary SDO sees on a node with additional servers: the SDO server records 1200h–127Fh from
/// [`SdoRecords`], everything else from the node's dictionary `od`.
pub(crate) struct WithRecords<'a, D, P, C> {
    pub(crate) od: D,
    pub(crate) sdo: SdoRecords<'a, P, C>,
}

impl<D: ObjectDictionary, P: Slots<SdoServerParams>, C: Slots<SdoClientRecord>> ObjectDictionary
    for WithRecords<'_, D, P, C>
{
    /// The records are numeric: streams are the wrapped dictionary's.
    const STREAMS: bool = D::STREAMS;
    const SEGMENTED_UPLOADS: bool = D::SEGMENTED_UPLOADS;

    fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
        if is_sdo_record(index) {
            return self.sdo.info(index, sub);
        }
        self.od.info(index, sub)
    }
    fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        if is_sdo_record(index) {
            return self.sdo.read(index, sub, offset, buf);
        }
        self.od.read(index, sub, offset, buf)
    }
    fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        if is_sdo_record(index) {
            return self.sdo.write(index, sub, data);
        }
        self.od.write(index, sub, data)
    }
    fn begin_write(&mut self, index: u16, sub: u8, size: Option<usize>) -> Result<(), AbortCode> {
        if is_sdo_record(index) {
            return self.sdo.begin_write(index, sub, size);
        }
        self.od.begin_write(index, sub, size)
    }
    fn write_chunk(&mut self, index: u16, sub: u8, offset: usize, data: &[u8]) -> Result<(), AbortCode> {
        if is_sdo_record(index) {
            return self.sdo.write_chunk(index, sub, offset, data);
        }
        self.od.write_chunk(index, sub, offset, data)
    }
    fn end_write(&mut self, index: u16, sub: u8, total: usize) -> Result<(), AbortCode> {
        if is_sdo_record(index) {
            return self.sdo.end_write(index, sub, total);
        }
        self.od.end_write(index, sub, total)
    }
    fn abort_write(&mut self, index: u16, sub: u8) {
        if !is_sdo_record(index) {
            self.od.abort_write(index, sub)
        }
    }
    fn restore_defaults(&mut self) {
        self.od.restore_defaults()
    }
    fn write_events(&self) -> bool {
        self.od.write_events()
    }
    fn read_expedited(&self, index: u16, sub: u8, buf: &mut [u8; 4]) -> Result<(usize, usize), AbortCode> {
        if is_sdo_record(index) {
            return self.sdo.read_expedited(index, sub, buf);
        }
        self.od.read_expedited(index, sub, buf)
    }
    fn write_expedited(&mut self, index: u16, sub: u8, data: &[u8; 4], len: Option<usize>) -> Result<(), AbortCode> {
        if is_sdo_record(index) {
            return self.sdo.write_expedited(index, sub, data, len);
        }
        self.od.write_expedited(index, sub, data, len)
    }
    fn slot(&self, index: u16, sub: u8) -> u16 {
        if is_sdo_record(index) {
            return self.sdo.slot(index, sub);
        }
        self.od.slot(index, sub)
    }
    fn read_slot(&self, index: u16, sub: u8, slot: u16, offset: usize, buf: &mut [u8]) -> Result<(), AbortCode> {
        if is_sdo_record(index) {
            return self.sdo.read_slot(index, sub, slot, offset, buf);
        }
        self.od.read_slot(index, sub, slot, offset, buf)
    }
    fn pdo_resolve(&self, index: u16, sub: u8, dir: PdoDir) -> Result<PdoHandle, AbortCode> {
        if is_sdo_record(index) {
            return self.sdo.pdo_resolve(index, sub, dir); // not mappable: 0604 0041h
        }
        self.od.pdo_resolve(index, sub, dir)
    }
    fn pdo_read(&self, handle: &PdoHandle, buf: &mut [u8]) -> Result<usize, AbortCode> {
        self.od.pdo_read(handle, buf)
    }
    fn pdo_write(&mut self, handle: &PdoHandle, data: &[u8]) -> Result<(), AbortCode> {
        self.od.pdo_write(handle, data)
    }
}

/// A node-ID written to sub 03h of a server or client record: 01h–7Fh (0609 0032h below, 0609 0031h above).
fn node_id_value(data: &[u8]) -> Result<u8, AbortCode> {
    match u8::decode(data)? {
        0 => Err(AbortCode::ValueTooLow),
        n if n > 0x7F => Err(AbortCode::ValueTooHigh),
        n => Ok(n),
    }
}

/// The SDO records as a dictionary: 1200h from the node-ID, 1201h + k from `records[k]`, 1280h + k from
/// `clients[k]`.
pub(crate) struct SdoRecords<'a, P, C> {
    pub(crate) records: &'a mut P,
    pub(crate) clients: &'a mut C,
    pub(crate) node_id: NodeId,
}

const U8_CONST: SubInfo =
    SubInfo { data_type: DataType::Unsigned8, access: Access::Const, pdo: PdoMapping::No, size: 1 };

const fn u32_entry(access: Access) -> SubInfo {
    SubInfo { data_type: DataType::Unsigned32, access, pdo: PdoMapping::No, size: 4 }
}

impl<P: Slots<SdoServerParams>, C: Slots<SdoClientRecord>> SdoRecords<'_, P, C> {
    /// The client record of `index` (1280h+).
    fn client(&self, index: u16) -> Result<SdoClientRecord, AbortCode> {
        self.clients.as_ref().get(usize::from(index & 0x7F)).copied().ok_or(AbortCode::ObjectDoesNotExist)
    }

    /// A client record's sub-entry (SDO-56: sub 00h = 3; 01h/02h COB-IDs; 03h server node-ID).
    fn client_value(&self, index: u16, sub: u8) -> Result<([u8; 4], usize), AbortCode> {
        let c = self.client(index)?;
        match sub {
            0 => Ok(([3, 0, 0, 0], 1)),
            1 => Ok((c.cob_tx.raw().to_le_bytes(), 4)),
            2 => Ok((c.cob_rx.raw().to_le_bytes(), 4)),
            3 => Ok(([c.server_node, 0, 0, 0], 1)),
            _ => Err(AbortCode::SubIndexDoesNotExist),
        }
    }

    /// Writes a client record's sub 01h–03h: the COB-ID rules of COB-14..16 (the IDs are the server's,
    /// often a default server's 600h/580h + node-ID, so the restricted set does not apply), the node-ID
    /// 01h–7Fh (0609 0032h below, 0609 0031h above).
    fn write_client(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        self.client(index)?;
        let Some(c) = self.clients.as_mut().get_mut(usize::from(index & 0x7F)) else {
            return Err(AbortCode::ObjectDoesNotExist);
        };
        match sub {
            0 => Err(AbortCode::WriteOfReadOnly),
            1 | 2 => {
                let v = u32::decode(data)?;
                let entry = if sub == 1 { &mut c.cob_tx } else { &mut c.cob_rx };
                *entry = entry.check_change(v, |e: CobIdEntry| !e.bit31())?;
                Ok(())
            }
            3 => {
                c.server_node = node_id_value(data)?;
                Ok(())
            }
            _ => Err(AbortCode::SubIndexDoesNotExist),
        }
    }

    /// The record of `index` (1200h: the default server).
    fn params(&self, index: u16) -> Result<SdoServerParams, AbortCode> {
        match usize::from(index & 0x7F).checked_sub(1) {
            None => Ok(SdoServerParams::default_server(self.node_id)),
            Some(k) => self.records.as_ref().get(k).copied().ok_or(AbortCode::ObjectDoesNotExist),
        }
    }

    /// The value of a sub-entry as little-endian bytes and its size.
    fn value(&self, index: u16, sub: u8) -> Result<([u8; 4], usize), AbortCode> {
        if !is_server_record(index) {
            return self.client_value(index, sub);
        }
        let p = self.params(index)?;
        let default = index & 0x7F == 0;
        match sub {
            0 => Ok(([if default { 2 } else { 3 }, 0, 0, 0], 1)),
            1 => Ok((p.cob_rx.raw().to_le_bytes(), 4)),
            2 => Ok((p.cob_tx.raw().to_le_bytes(), 4)),
            3 if !default => Ok(([p.client_node.map_or(0, NodeId::get), 0, 0, 0], 1)),
            _ => Err(AbortCode::SubIndexDoesNotExist),
        }
    }
}

impl<P: Slots<SdoServerParams>, C: Slots<SdoClientRecord>> ObjectDictionary for SdoRecords<'_, P, C> {
    const STREAMS: bool = false;
    const SEGMENTED_UPLOADS: bool = false;

    fn info(&self, index: u16, sub: u8) -> Result<SubInfo, AbortCode> {
        if !is_server_record(index) {
            self.client(index)?;
            return match sub {
                0 => Ok(U8_CONST),
                1 | 2 => Ok(u32_entry(Access::Rw)),
                3 => Ok(SubInfo { access: Access::Rw, ..U8_CONST }),
                _ => Err(AbortCode::SubIndexDoesNotExist),
            };
        }
        self.params(index)?;
        match (index & 0x7F, sub) {
            (_, 0) => Ok(U8_CONST),
            (0, 1) => Ok(u32_entry(Access::Const)), // SDO-53
            (0, 2) => Ok(u32_entry(Access::Ro)),
            (_, 1 | 2) => Ok(u32_entry(Access::Rw)),                    // SDO-54
            (1.., 3) => Ok(SubInfo { access: Access::Rw, ..U8_CONST }), // SDO-54: the client's node-ID
            _ => Err(AbortCode::SubIndexDoesNotExist),
        }
    }

    fn read(&self, index: u16, sub: u8, offset: usize, buf: &mut [u8]) -> Result<usize, AbortCode> {
        let (bytes, len) = self.value(index, sub)?;
        let src = bytes.get(offset..len).unwrap_or(&[]);
        let n = src.len().min(buf.len());
        buf[..n].copy_from_slice(&src[..n]);
        Ok(n)
    }

    fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        if !self.info(index, sub)?.access.writable() {
            return Err(AbortCode::WriteOfReadOnly);
        }
        if !is_server_record(index) {
            return self.write_client(index, sub, data);
        }
        let k = usize::from(index & 0x7F) - 1; // 1200h is read-only: k >= 0
        let Some(p) = self.records.as_mut().get_mut(k) else {
            return Err(AbortCode::ObjectDoesNotExist);
        };
        if sub == 3 {
            p.client_node = NodeId::new(node_id_value(data)?);
            return Ok(());
        }
        let v = u32::decode(data)?; // SDO-18
        let entry = if sub == 1 { &mut p.cob_rx } else { &mut p.cob_tx };
        // COB-15 (frame bit), COB-14 (bits 28-11), COB-16 (no ID change while valid).
        let new = entry.check_change(v, |e: CobIdEntry| !e.bit31())?;
        if !new.bit31() && is_restricted(new.can_id()) {
            return Err(AbortCode::InvalidValue); // COB-13
        }
        *entry = new;
        Ok(())
    }
}

impl<A: ObjectDictionary, Z: NodeSizes, S: Storage> Node<A, Z, S> {
    /// The additional server that receives on `id`, if any (never when `N` = 0).
    #[inline]
    pub(super) fn extra_sdo_for(&self, id: u16) -> Option<usize> {
        if <Z::ExtraSdo as Slots<SdoServer>>::LEN == 0 {
            return None;
        }
        self.sdo_extra.as_ref().iter().position(|s| s.receives(id))
    }

    /// A request to additional server `i` (SDO-01's rules: Pre-operational and Operational only, NMT-18).
    #[inline(never)]
    pub(super) fn handle_extra_sdo(&mut self, now: Instant, i: usize, frame: &CanFrame) {
        if frame.is_rtr() || !self.nmt.state().allows(Service::Sdo) {
            return;
        }
        let Some(cob) = self.sdo_extra.as_ref().get(i).map(SdoServer::tx_cob_id) else { return };
        let response = sdo_dict!(self, |od| self.sdo_extra[i].handle_request(now, frame.data(), od));
        self.sdo_response(now, response, cob);
        #[cfg(feature = "sdo-block")]
        self.pump_extra_sdo();
    }

    /// The earliest time-out of the additional servers.
    #[inline]
    pub(super) fn extra_sdo_deadline(&self) -> Deadline {
        let mut t = Deadline::NONE;
        for s in self.sdo_extra.as_ref() {
            t = t.min(s.deadline());
        }
        t
    }

    /// SDO-31 on the additional servers.
    #[inline]
    pub(super) fn extra_sdo_timeout(&mut self, now: Instant) {
        for i in 0..<Z::ExtraSdo as Slots<SdoServer>>::LEN {
            let cob = self.sdo_extra[i].tx_cob_id();
            let response = sdo_dict!(self, |od| self.sdo_extra[i].handle_timeout(now, od));
            self.sdo_response(now, response, cob);
        }
    }

    /// Block-upload segments of the additional servers, while the transmit queue has room (as the
    /// default server's, `pump_sdo_segments`).
    #[cfg(feature = "sdo-block")]
    pub(super) fn pump_extra_sdo(&mut self) {
        for i in 0..<Z::ExtraSdo as Slots<SdoServer>>::LEN {
            while self.sdo_extra[i].wants_transmit()
                && self.tx.storage_len() + super::TX_RESERVE.min(Z::TXQ.saturating_sub(1)) < Z::TXQ
            {
                let cob = self.sdo_extra[i].tx_cob_id();
                let now = self.now;
                let Some(response) = sdo_dict!(self, |od| self.sdo_extra[i].poll_transmit(now, od)) else {
                    break;
                };
                self.sdo_response(self.now, response, cob);
            }
        }
    }

    /// Drops every additional server's transfer without a frame (NMT-18: Stopped).
    pub(super) fn cancel_extra_sdo(&mut self) {
        for i in 0..<Z::ExtraSdo as Slots<SdoServer>>::LEN {
            sdo_dict!(self, |od| self.sdo_extra[i].cancel(od));
        }
    }

    /// Reset communication: every record 1201h+ back to 8000_0000h (SDO-54), every server idle.
    pub(super) fn reset_extra_sdo(&mut self) {
        self.cancel_extra_sdo();
        for i in 0..<Z::ExtraSdo as Slots<SdoServer>>::LEN {
            self.sdo_records[i] = SdoServerParams::DISABLED;
            self.sdo_extra[i].set_params(SdoServerParams::DISABLED);
        }
        for c in self.sdo_clients.as_mut() {
            *c = SdoClientRecord::DISABLED; // 1280h+ too
        }
    }

    /// The record of additional server 1201h + `k` (SDO-54), as last written; `None` when the node has no
    /// such server (`N` of [`WithSdoServers`]).
    ///
    /// ```
    /// use canopen_core::{node::{NoApplication, Node, WithSdoServers}, profile::NodeConfig, sdo::SdoServerParams, NodeId};
    /// let node: Node<NoApplication, WithSdoServers> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// assert_eq!(node.sdo_server_params(0), Some(SdoServerParams::DISABLED));
    /// assert_eq!(node.sdo_server_params(1), None);
    /// ```
    pub fn sdo_server_params(&self, k: usize) -> Option<SdoServerParams> {
        self.sdo_records.as_ref().get(k).copied()
    }

    /// Sets the record of additional server 1201h + `k` locally (the application's own configuration,
    /// e.g. after boot or a reset communication, which sets every record invalid; without the SDO change
    /// rules): the server takes it at once, dropping a transfer under way when it changed, and the receive
    /// filters follow. `false` when the node has no such server.
    ///
    /// ```
    /// use canopen_core::{node::{NoApplication, Node, WithSdoServers}, profile::NodeConfig, NodeId};
    /// use canopen_core::{cob::CobIdEntry, sdo::SdoServerParams};
    /// let mut node: Node<NoApplication, WithSdoServers> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// let p = SdoServerParams { cob_rx: CobIdEntry::from_raw(0x6C5), cob_tx: CobIdEntry::from_raw(0x6D5), client_node: None };
    /// assert!(node.set_sdo_server_params(0, p));
    /// assert!(node.rx_filters().iter().any(|f| f.id == 0x6C5));
    /// assert!(!node.set_sdo_server_params(1, p));
    /// ```
    pub fn set_sdo_server_params(&mut self, k: usize, params: SdoServerParams) -> bool {
        let Some(r) = self.sdo_records.as_mut().get_mut(k) else {
            return false;
        };
        *r = params;
        self.apply_server_record(k);
        self.cob_ids_may_change();
        true
    }

    /// SDO client record 1280h + `k` (SDO-56), as configured locally or by SDO; `None` when the node has
    /// no such record (`M` of [`WithSdoServers`]). An application builds its [`SdoClient`] from it
    /// ([`SdoClientRecord::client_params`]) and watches [`Event::ObjectWritten`] for 1280h + `k` to follow a
    /// change made by SDO. Reset communication sets every record back to [`SdoClientRecord::DISABLED`].
    ///
    /// [`SdoClient`]: crate::sdo::SdoClient
    ///
    /// ```
    /// use canopen_core::{node::{NoApplication, Node, SdoClientRecord, WithSdoServers}, profile::NodeConfig, NodeId, Sizes};
    /// // No additional server, two client records 1280h/1281h.
    /// let node: Node<NoApplication, WithSdoServers<Sizes, 0, 2>> =
    ///     Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// assert_eq!(node.sdo_client_record(1), Some(SdoClientRecord::DISABLED));
    /// assert_eq!(node.sdo_client_record(2), None);
    /// ```
    pub fn sdo_client_record(&self, k: usize) -> Option<SdoClientRecord> {
        self.sdo_clients.as_ref().get(k).copied()
    }

    /// Sets SDO client record 1280h + `k` locally (the application's own configuration, without the SDO
    /// change rules); `false` when the node has no such record. The receive filters follow (a valid record's
    /// server → client COB-ID is in [`Node::rx_filters`]).
    ///
    /// ```
    /// use canopen_core::{node::{NoApplication, Node, SdoClientRecord, WithSdoServers}, profile::NodeConfig, NodeId, Sizes};
    /// use canopen_core::cob::CobIdEntry;
    /// let mut node: Node<NoApplication, WithSdoServers<Sizes, 0, 1>> =
    ///     Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// let r = SdoClientRecord { cob_tx: CobIdEntry::from_raw(0x603), cob_rx: CobIdEntry::from_raw(0x583), server_node: 3 };
    /// assert!(node.set_sdo_client_record(0, r));
    /// assert_eq!(node.sdo_client_record(0), Some(r));
    /// assert!(!node.set_sdo_client_record(1, r));
    /// ```
    pub fn set_sdo_client_record(&mut self, k: usize, record: SdoClientRecord) -> bool {
        match self.sdo_clients.as_mut().get_mut(k) {
            Some(c) => {
                *c = record;
                self.cob_ids_may_change();
                true
            }
            None => false,
        }
    }

    /// Record `index` (1201h+) was written by SDO: its server takes the new COB-IDs, dropping a transfer
    /// under way when they changed.
    pub(super) fn sdo_record_written(&mut self, index: u16) {
        if let Some(i) = usize::from(index & 0x7F).checked_sub(1) {
            self.apply_server_record(i);
        }
    }

    /// Additional server `i` takes its record, dropping a transfer under way when the COB-IDs changed.
    fn apply_server_record(&mut self, i: usize) {
        let (Some(server), Some(&p)) = (self.sdo_extra.as_ref().get(i), self.sdo_records.as_ref().get(i)) else {
            return;
        };
        let old = server.params();
        if (old.cob_rx, old.cob_tx) != (p.cob_rx, p.cob_tx) {
            sdo_dict!(self, |od| self.sdo_extra[i].cancel(od));
            self.sdo_extra[i].set_params(p);
        }
    }
}

/// A description `od` plus the SDO parameter records of a node with [`WithSdoServers`]`<Z, N, M>`, in index
/// order: 1200h and 1201h..=1200h + `N` (only when `N` > 0: without additional servers the node does not
/// serve 1200h, SDO-53), 1280h..1280h + `M` (SDO-56). What the EDS of such a node lists (OD-11), each record a
/// CiA 306 RECORD described as SDO answers it: sub 00h the highest sub-index (const; 2 for 1200h, 3
/// otherwise), sub 01h/02h the COB-IDs (UNSIGNED32; 1200h const $NODEID+0x600 and ro $NODEID+0x580, SDO-53;
/// the others rw 8000_0000h, SDO-54/SDO-55), sub 03h the peer's node-ID (UNSIGNED8 rw, 0 until written).
///
/// ```
/// use canopen_core::node::{NoApplication, Node, SdoRecordsDesc, WithSdoServers};
/// use canopen_core::od::{Access, Merged, OdDescribe, Value};
/// use canopen_core::profile::{eds::{write_eds, EdsInfo}, CommProfile, NodeConfig};
/// use canopen_core::{NodeId, Sizes};
/// type Z = WithSdoServers<Sizes, 1, 1>;
/// // Without a node: the profile and the application, as a device maker writes its EDS file.
/// let od = Merged { comm: CommProfile::<Z>::new(NodeConfig::DEFAULT), app: NoApplication };
/// let desc = SdoRecordsDesc::of::<Z>(od);
/// assert_eq!(desc.entry(0x1201, 1).map(|e| (e.access, e.default)), Some((Access::Rw, Some(Value::Uint(0x8000_0000)))));
/// let mut eds = String::new();
/// write_eds(&mut eds, &EdsInfo::DEFAULT, &desc).unwrap();
/// assert!(eds.contains("[1200sub1]\nParameterName=COB-ID client to server (rx)\nObjectType=0x7\nDataType=0x0007\nAccessType=const\nDefaultValue=$NODEID+0x600\n"));
/// assert!(eds.contains("[1280]\nParameterName=SDO client parameter\nObjectType=0x9\nSubNumber=0x4\n"));
/// // The same from a node.
/// let node: Node<NoApplication, Z> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
/// assert_eq!(node.describe().object_count(), desc.object_count());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SdoRecordsDesc<D> {
    /// The rest of the dictionary (the profile and the application, [`Merged`]).
    pub od: D,
    /// Additional servers 1201h+ (`N`).
    servers: u8,
    /// Client records 1280h+ (`M`).
    clients: u8,
}

impl<D> SdoRecordsDesc<D> {
    /// `od` with the records of a node of sizes `Z` (none for [`Sizes`](crate::Sizes): then this is `od`).
    ///
    /// ```
    /// use canopen_core::node::{NoApplication, SdoRecordsDesc};
    /// use canopen_core::od::OdDescribe;
    /// assert_eq!(SdoRecordsDesc::of::<canopen_core::Sizes>(NoApplication).object_count(), 0);
    /// ```
    pub fn of<Z: NodeSizes>(od: D) -> Self {
        // SDO-57: at most 127 additional servers and 128 client records (a `WithSdoServers` with more
        // describes what the node serves: the dictionary answers 1200h–127Fh and 1280h–12FFh only).
        let servers = <Z::ExtraSdo as Slots<SdoServer>>::LEN.min(0x7F) as u8;
        let clients = <Z::SdoClients as Slots<SdoClientRecord>>::LEN.min(0x80) as u8;
        SdoRecordsDesc { od, servers, clients }
    }

    /// The number of server record objects: 1200h..=1200h + N when N > 0, else none (SDO-53).
    fn server_count(&self) -> usize {
        if self.servers > 0 {
            usize::from(self.servers) + 1
        } else {
            0
        }
    }

    /// The number of record objects: the servers', then 1280h+.
    fn own_count(&self) -> usize {
        self.server_count() + usize::from(self.clients)
    }

    /// The index of the `i`-th record object.
    fn own_index(&self, i: usize) -> u16 {
        match i.checked_sub(self.server_count()) {
            None => 0x1200 + i as u16,
            Some(k) => 0x1280 + k as u16,
        }
    }

    /// Whether `index` is one of the records described here.
    fn has(&self, index: u16) -> bool {
        match index {
            0x1200..=0x127F => self.servers > 0 && index - 0x1200 <= u16::from(self.servers),
            0x1280..=0x12FF => index - 0x1280 < u16::from(self.clients),
            _ => false,
        }
    }
}

/// COB-ID 8000_0000h: the power-on value of every record 1201h+ and 1280h+ (SDO-54, SDO-55).
const INVALID_COB_ID: Value = Value::Uint(CobIdEntry::BIT31 as u64);

/// Sub-entry `sub` of record `index` (which exists), as [`SdoRecords`] answers it.
fn record_entry(index: u16, sub: u8) -> Option<EntryDesc> {
    let cob =
        |name, access, default| EntryDesc::var(index, sub, name, DataType::Unsigned32, access).with_default(default);
    let node = |name| EntryDesc::var(index, sub, name, DataType::Unsigned8, Access::Rw).with_default(Value::Uint(0));
    Some(match (index, sub) {
        (0x1200, 0) => count_entry(index, 2),
        (0x1200, 1) => cob("COB-ID client to server (rx)", Access::Const, Value::NodeIdPlus(0x600)),
        (0x1200, 2) => cob("COB-ID server to client (tx)", Access::Ro, Value::NodeIdPlus(0x580)),
        (0x1200, _) => return None,
        (_, 0) => count_entry(index, 3),
        (0x1201..=0x127F, 1) => cob("COB-ID client to server (rx)", Access::Rw, INVALID_COB_ID),
        (0x1201..=0x127F, 2) => cob("COB-ID server to client (tx)", Access::Rw, INVALID_COB_ID),
        (0x1201..=0x127F, 3) => node("Node-ID of the SDO client"),
        (_, 1) => cob("COB-ID client to server (tx)", Access::Rw, INVALID_COB_ID),
        (_, 2) => cob("COB-ID server to client (rx)", Access::Rw, INVALID_COB_ID),
        (_, 3) => node("Node-ID of the SDO server"),
        _ => return None,
    })
}

impl<D: OdDescribe> SdoRecordsDesc<D> {
    /// Where the `n`-th object of the merged order is: (true, own record `i`) or (false, `od`'s `j`).
    fn locate(&self, n: usize) -> Option<(bool, usize)> {
        let other = |j| self.od.object_index(j).unwrap_or(u16::MAX);
        crate::od::merge_nth(n, self.own_count(), |i| self.own_index(i), self.od.object_count(), other)
    }
}

impl<D: OdDescribe> OdDescribe for SdoRecordsDesc<D> {
    fn object_count(&self) -> usize {
        self.od.object_count() + self.own_count()
    }

    fn object(&self, n: usize) -> Option<ObjectDesc> {
        match self.locate(n)? {
            (true, i) => {
                let index = self.own_index(i);
                let (name, subs) = match index {
                    0x1200 => ("SDO server parameter", 3),
                    ..=0x127F => ("SDO server parameter", 4),
                    _ => ("SDO client parameter", 4),
                };
                Some(ObjectDesc { index, name, code: ObjectCode::Record, first: 0, subs })
            }
            (false, j) => self.od.object(j),
        }
    }

    fn object_index(&self, n: usize) -> Option<u16> {
        match self.locate(n)? {
            (true, i) => Some(self.own_index(i)),
            (false, j) => self.od.object_index(j),
        }
    }

    fn entry(&self, index: u16, sub: u8) -> Option<EntryDesc> {
        if is_sdo_record(index) {
            return if self.has(index) { record_entry(index, sub) } else { None };
        }
        self.od.entry(index, sub)
    }
}

impl<A: ObjectDictionary + OdDescribe, Z: NodeSizes, S: Storage> Node<A, Z, S> {
    /// The node's dictionary as its EDS describes it ([`write_eds`](crate::profile::eds::write_eds)): the
    /// communication profile, the application and the SDO records of [`WithSdoServers`] ([`SdoRecordsDesc`]).
    ///
    /// ```
    /// use canopen_core::node::{NoApplication, Node, WithSdoServers};
    /// use canopen_core::profile::{eds::{write_eds, EdsInfo}, NodeConfig};
    /// use canopen_core::NodeId;
    /// let node: Node<NoApplication, WithSdoServers> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// let mut eds = String::new();
    /// write_eds(&mut eds, &EdsInfo::DEFAULT, &node.describe()).unwrap();
    /// assert!(eds.contains("[1201sub3]\nParameterName=Node-ID of the SDO client\n"));
    /// ```
    pub fn describe(&self) -> SdoRecordsDesc<Merged<&CommProfile<Z>, &A>> {
        SdoRecordsDesc::of::<Z>(Merged { comm: &self.comm, app: &self.app })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// OD-11, SDO-53, SDO-54, SDO-56: the EDS description of the records (what a tool reads) and the
    /// dictionary SDO serves (what the node answers) agree on every index 1200h–12FFh and sub-index:
    /// the same entries exist, with the same data type, access and PDO mapping, and a default equal to the
    /// value read after power-on.
    #[test]
    fn description_agrees_with_the_records() {
        let node_id = NodeId::new(5).unwrap();
        let mut records = [SdoServerParams::DISABLED; 3];
        let mut clients = [SdoClientRecord::DISABLED; 2];
        let sdo = SdoRecords { records: &mut records, clients: &mut clients, node_id };
        let desc = SdoRecordsDesc { od: crate::od::NoApplication, servers: 3, clients: 2 };
        let mut checked = 0;
        for index in 0x1200..=0x12FFu16 {
            for sub in 0..=255u8 {
                let info = sdo.info(index, sub);
                let entry = desc.entry(index, sub);
                assert_eq!(info.is_ok(), entry.is_some(), "{index:04X}h sub {sub}");
                let (Ok(info), Some(e)) = (info, entry) else { continue };
                assert_eq!(
                    (info.data_type, info.access, info.pdo),
                    (e.data_type, e.access, e.pdo),
                    "{index:04X}h:{sub}"
                );
                let mut buf = [0u8; 4];
                let n = sdo.read(index, sub, 0, &mut buf).unwrap();
                let read = u32::from_le_bytes(buf) as u64;
                let default = match e.default {
                    Some(Value::Uint(v)) => v,
                    Some(Value::NodeIdPlus(v)) => u64::from(v) + 5,
                    other => panic!("{index:04X}h:{sub} default {other:?}"),
                };
                assert_eq!((n, read), (info.size, default), "{index:04X}h:{sub}");
                checked += 1;
            }
        }
        assert_eq!(checked, 3 + 3 * 4 + 2 * 4);
        let listed: heapless::Vec<u16, 8> =
            (0..desc.object_count()).filter_map(|n| desc.object(n)).map(|o| o.index).collect();
        assert_eq!(listed, [0x1200, 0x1201, 0x1202, 0x1203, 0x1280, 0x1281]);
        // No additional server: no 1200h either (the node does not serve it then), the clients alone.
        let clients_only = SdoRecordsDesc { od: crate::od::NoApplication, servers: 0, clients: 1 };
        assert_eq!((clients_only.object_count(), clients_only.object(0).map(|o| o.index)), (1, Some(0x1280)));
        assert!(clients_only.entry(0x1200, 0).is_none() && clients_only.entry(0x1281, 0).is_none());
    }
}
