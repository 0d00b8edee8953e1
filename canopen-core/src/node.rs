//! The node: one object that owns every service and is driven from outside (the quinn-proto shape).
//!
//! - [`Node::handle_frame`] feeds a received frame, [`Node::handle_timeout`] tells it the time passed;
//! - [`Node::poll_transmit`] drains frames to send, [`Node::poll_event`] drains events for the application;
//! - [`Node::poll_timeout`] says when the next deadline is, so a runner sleeps exactly until then.
//!
//! Both output queues are bounded (`Z::TXQ`, `Z::EVQ`, see [`NodeSizes`]). When one is full the newest item
//! is dropped and counted ([`Node::tx_dropped`], [`Node::events_dropped`]); a runner that drains the transmit
//! queue after every call never sees it full.
//!
//! Receive dispatch compares the CAN-ID with the few configurable single-object IDs (NMT 000h, SYNC 1005h,
//! TIME 1012h), then finds the RPDO: up to 8 RPDOs by comparing their CAN-IDs (at most 8 compares, no table
//! to keep), above that by a binary search of a sorted table of (CAN-ID → RPDO) rebuilt whenever a COB-ID
//! changes; then it decodes the function code once for the rest. No scan over services, and the work per
//! frame does not grow with the number of PDOs.
//!
//! The PDO, SYNC, TIME and EMCY wiring lives in `node/pdo.rs` and `node/errors.rs`, NMT node control and
//! error control (heartbeat, guarding, the reaction to a communication error) in `node/error_control.rs`;
//! the dictionary SDO sees (mapping checks, store/restore commands) in `node/dict.rs`.
//!
//! Requirements (`docs/CONFORMANCE.md`) carried out here: NMT-03 (power-on: Initialising → reset application → reset
//! communication → boot-up → Pre-operational, on the first call), NMT-04/NMT-05 (what the resets restore),
//! NMT-18 (services per state), NMT-23/NMT-24 (boot-up on 700h + node, once per Initialization →
//! Pre-operational), HB-03/HB-04, CAN-07 (frames malformed for their COB-ID are ignored), NMT-06 (power-on
//! and resets load the stored values, [`crate::storage`]), NMT-22 (EMCY pending in Stopped), NMT-27 (1F80h
//! bit 2 = 0: enter Operational by itself after boot-up; the bit meaning is CiA 302-2's, as the lely stack
//! reads it in `co_nmt_startup_slave`: "enter the operational state automatically if bit 2 of the NMT
//! startup value is 0"). In `node/error_control.rs`: NMT-08 (own node-ID or broadcast), NMT-14 (never
//! replies on 000h), HB-05 (guarding is answered only while the heartbeat producer is off), HB-13/GUARD-11
//! (time-outs are communication errors), NMT-26/ERR-12 (a communication error in Operational →
//! Pre-operational by default), ERR-10..13 (1029h sub 01h decides the reaction to a communication error).

/// Evaluates `$body` with `$od` bound to the dictionary the SDO servers see: the node's [`dict::NodeDict`],
/// wrapped in [`sdo_servers::WithRecords`] (the records 1200h–127Fh) only when the node has additional
/// servers; with none (a constant) the wrapper is not built at all, so `Sizes` nodes keep their code.
macro_rules! sdo_dict {
    ($node:ident, |$od:ident| $body:expr) => {{
        let node_id = $node.node_id;
        let mut nd = crate::node::dict::NodeDict::new(&mut $node.comm, &mut $node.app, &mut $node.storage, $node.save);
        if <Z::ExtraSdo as crate::sizes::Slots<crate::sdo::SdoServer>>::LEN == 0
            && <Z::SdoClients as crate::sizes::Slots<crate::node::SdoClientRecord>>::LEN == 0
        {
            let $od = &mut nd;
            $body
        } else {
            let records = crate::node::sdo_servers::SdoRecords {
                records: &mut $node.sdo_records,
                clients: &mut $node.sdo_clients,
                node_id,
            };
            let $od = &mut crate::node::sdo_servers::WithRecords { od: nd, sdo: records };
            $body
        }
    }};
}

mod dict;
mod error_control;
mod errors;
#[cfg(feature = "mpdo")]
mod mpdo;
mod optional;
mod pdo;
mod rx_filter;
mod sdo_servers;

pub use rx_filter::{RxFilter, RxFilters, RX_FILTER_CAPACITY};
pub use sdo_servers::{SdoClientRecord, SdoRecordsDesc, WithSdoServers};

use heapless::deque::DequeInner;
use heapless::vec::{OwnedVecStorage, VecInner, VecStorage};
use heapless::{Deque, Vec};

#[cfg(feature = "lss")]
mod with_lss;

use crate::bus::BusState;
use crate::cob::{FunctionCode, NodeId};
use crate::emcy::{codes, EmcyProducer};
use crate::event::Event;
use crate::frame::CanFrame;
#[cfg(feature = "guarding")]
use crate::guarding::Guarding;
use crate::heartbeat::{HeartbeatConsumer, HeartbeatProducer};
#[cfg(feature = "lss")]
use crate::lss::LssSlave;
use crate::nmt::{Nmt, NmtState, Service, Transition};
use crate::od::Merged;
pub use crate::od::NoApplication;
use crate::od::{AbortCode, ObjectDictionary, OdDescribe};
use crate::pdo::{mapping::ResolvedMap, rpdo::Rpdo, tpdo::Tpdo};
use crate::profile::ProfileSizes;
use crate::profile::{CommParams, NodeConfig};
use crate::profile::{CommProfile, Unchecked};
use crate::sdo::{Response, SdoEvent, SdoServer, SdoServerParams};
use crate::sizes::{Sizes, Slots};
use crate::storage::{self, Groups, NoStorage, Storage};
use crate::sync::Sync;
use crate::time::Instant;
use crate::wire::error_control::{Heartbeat, StateCode};
use dict::SaveFn;

/// A CANopen node with application dictionary `A`, the capacities `Z` ([`Sizes`]`<HB, TXQ, EVQ, RPDO,
/// TPDO>`: heartbeat consumer entries, transmit queue frames, event queue events, receive and transmit PDOs)
/// and non-volatile storage `S` ([`NoStorage`] unless built with [`Node::with_storage`]). The defaults keep
/// `Node<App>` a complete CiA 301 device with 4 + 4 PDOs; `Node<App, Sizes<4, 16, 32>>` has a 32-event
/// queue.
///
/// ```
/// use canopen_core::{profile::NodeConfig, node::{Node, NoApplication}, CanFrame, Instant, NodeId};
///
/// let cfg = NodeConfig { heartbeat_time_ms: 100, ..NodeConfig::DEFAULT };
/// let mut node: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), cfg, NoApplication);
///
/// // Power-on: the first call boots the node (boot-up frame, Pre-operational).
/// assert_eq!(node.poll_timeout(), Some(Instant::ZERO));
/// node.handle_timeout(Instant::ZERO);
/// assert_eq!(node.poll_transmit(), CanFrame::new(0x705, &[0x00]));
///
/// // NMT start, then the next heartbeat says Operational.
/// node.handle_frame(Instant::from_millis(10), &CanFrame::new(0x000, &[0x01, 0x05]).unwrap());
/// assert_eq!(node.poll_timeout(), Some(Instant::from_millis(100)));
/// node.handle_timeout(Instant::from_millis(100));
/// assert_eq!(node.poll_transmit(), CanFrame::new(0x705, &[0x05]));
/// ```
pub struct Node<A, Z: NodeSizes = Sizes, S = NoStorage> {
    node_id: NodeId,
    comm: CommProfile<Z>,
    sdo: SdoServer,
    /// The additional SDO servers 1201h+ (none for [`Sizes`]; `node/sdo_servers.rs`).
    sdo_extra: Z::ExtraSdo,
    /// Their records 1201h+ as SDO last wrote them.
    sdo_records: Z::ExtraSdoParams,
    /// The SDO client records 1280h+ (none for [`Sizes`]).
    sdo_clients: Z::SdoClients,
    /// The latest time passed in, for work that `poll_transmit` resumes (block upload segments).
    now: Instant,
    nmt: Nmt,
    boot_pending: bool,
    producer: HeartbeatProducer,
    consumer: HeartbeatConsumer<Z>,
    #[cfg(feature = "guarding")]
    guarding: Guarding,
    /// CiA 305 LSS slave (see `node/with_lss.rs`).
    #[cfg(feature = "lss")]
    lss: LssSlave,
    app: A,
    sync: Sync,
    emcy: EmcyProducer,
    rpdos: Z::Rpdos,
    tpdos: Z::Tpdos,
    /// (CAN-ID, RPDO number) of the valid RPDOs, sorted by CAN-ID; kept only above [`pdo::SCAN_MAX`] RPDOs
    /// (below, a frame is matched against the RPDOs themselves).
    rx_table: PdoTable<Z::RpdoTable>,
    /// (CAN-ID, TPDO number) of the TPDOs that answer a remote request, sorted by CAN-ID; kept only above
    /// [`pdo::SCAN_MAX`] TPDOs.
    rtr_table: PdoTable<Z::TpdoTable>,
    storage: S,
    save: SaveFn<S, CommProfile<Z>, A>,
    sync_length_error: bool,
    tx_overrun: bool,
    /// The stack raised 8110h for a transmit-queue overflow and has not cleared it yet (an 8110h the
    /// application raises itself is the application's to clear).
    tx_overrun_raised: bool,
    /// The controller's last reported state (see [`crate::bus`]).
    bus: BusState,
    /// 8140h is active and the next received frame clears it.
    bus_recovered: bool,
    tx: DequeInner<CanFrame, Z::TxQueue>,
    events: DequeInner<Event, Z::EventQueue>,
    tx_dropped: u32,
    events_dropped: u32,
    /// Bumped whenever the COB-IDs the node receives may have changed (see [`Node::rx_filters_generation`]).
    rx_generation: u32,
}

/// The sans-IO surface every runner drives (the async [`crate::driver`], the SocketCAN adapters, the test
/// bus): implemented by [`Node`], so a runner is written once whatever the node's capacities are.
///
/// ```
/// use canopen_core::{profile::NodeConfig, node::{NoApplication, Node, SansIo}, Instant, NodeId};
/// fn boot<N: SansIo>(n: &mut N) -> usize {
///     n.handle_timeout(Instant::ZERO);
///     core::iter::from_fn(|| n.poll_transmit()).count()
/// }
/// let mut node: Node<NoApplication> = Node::new(NodeId::new(1).unwrap(), NodeConfig::DEFAULT, NoApplication);
/// assert_eq!(boot(&mut node), 1); // the boot-up frame
/// ```
pub trait SansIo {
    /// Feeds one received frame.
    fn handle_frame(&mut self, now: Instant, frame: &CanFrame);
    /// Lets the node act on the time that has passed.
    fn handle_timeout(&mut self, now: Instant);
    /// The next deadline.
    fn poll_timeout(&self) -> Option<Instant>;
    /// The next frame to send.
    fn poll_transmit(&mut self) -> Option<CanFrame>;
    /// The next frame to send, left in the queue until [`transmitted`](SansIo::transmitted).
    fn peek_transmit(&self) -> Option<CanFrame>;
    /// `frame` (from [`peek_transmit`](SansIo::peek_transmit)) was sent.
    fn transmitted(&mut self, frame: &CanFrame);
    /// The next event for the application.
    fn poll_event(&mut self) -> Option<Event>;
    /// The CAN controller's state changed (see [`crate::bus`]).
    fn handle_bus_state(&mut self, now: Instant, state: BusState);
}

impl<A: ObjectDictionary, Z: NodeSizes, S: Storage> SansIo for Node<A, Z, S> {
    fn handle_frame(&mut self, now: Instant, frame: &CanFrame) {
        Node::handle_frame(self, now, frame)
    }
    fn handle_timeout(&mut self, now: Instant) {
        Node::handle_timeout(self, now)
    }
    fn poll_timeout(&self) -> Option<Instant> {
        Node::poll_timeout(self)
    }
    fn handle_bus_state(&mut self, now: Instant, state: BusState) {
        Node::set_bus_state(self, now, state)
    }
    fn poll_transmit(&mut self) -> Option<CanFrame> {
        Node::poll_transmit(self)
    }
    fn peek_transmit(&self) -> Option<CanFrame> {
        Node::peek_transmit(self)
    }
    fn transmitted(&mut self, frame: &CanFrame) {
        Node::transmitted(self, frame)
    }
    fn poll_event(&mut self) -> Option<Event> {
        Node::poll_event(self)
    }
}

/// The node's capacities as its storage types: the communication profile's and the heartbeat consumer's
/// ([`ProfileSizes`], [`ConsumerSizes`](crate::heartbeat::ConsumerSizes)) plus the node's own PDO state machines, receive tables and queues.
/// Implemented for [`Sizes`]; a node is generic over one `Z: NodeSizes` instead of five numbers (see
/// [`crate::sizes`]).
///
/// ```
/// use canopen_core::{node::NodeSizes, Sizes};
/// assert_eq!(<Sizes as NodeSizes>::TXQ, 16);
/// assert_eq!(<Sizes<2, 8, 32> as NodeSizes>::EVQ, 32);
/// ```
pub trait NodeSizes: ProfileSizes {
    /// Transmit queue length, frames.
    const TXQ: usize;
    /// Event queue length, events.
    const EVQ: usize;
    /// `[Rpdo; RPDO]`.
    type Rpdos: Slots<Rpdo>;
    /// `[Tpdo; TPDO]`.
    type Tpdos: Slots<Tpdo>;
    /// Storage of the (CAN-ID, RPDO) receive table: `RPDO` entries.
    type RpdoTable: VecStorage<(u16, u16)>;
    /// Storage of the (CAN-ID, TPDO) remote-request table: `TPDO` entries.
    type TpdoTable: VecStorage<(u16, u16)>;
    /// Storage of the transmit queue: `TXQ` frames.
    type TxQueue: VecStorage<CanFrame>;
    /// Storage of the event queue: `EVQ` events.
    type EventQueue: VecStorage<Event>;
    /// An empty receive table.
    const RPDO_TABLE: PdoTable<Self::RpdoTable>;
    /// An empty remote-request table.
    const TPDO_TABLE: PdoTable<Self::TpdoTable>;
    /// An empty transmit queue.
    const TX_QUEUE: DequeInner<CanFrame, Self::TxQueue>;
    /// An empty event queue.
    const EVENT_QUEUE: DequeInner<Event, Self::EventQueue>;
    /// The additional SDO servers 1201h+ (issue 17): `[SdoServer; N]`, none (`N` = 0) for [`Sizes`], `N` for
    /// [`WithSdoServers`]`<Z, N>`.
    type ExtraSdo: Slots<SdoServer>;
    /// Their parameter records 1201h+ as the dictionary holds them: `[SdoServerParams; N]`.
    type ExtraSdoParams: Slots<SdoServerParams>;
    /// The SDO client records 1280h+ (SDO-56): `[SdoClientRecord; M]`, none for [`Sizes`].
    type SdoClients: Slots<SdoClientRecord>;
}

/// A sorted (CAN-ID, PDO number) table in `S`'s storage (`heapless::Vec<(u16, u16), N>` for
/// `OwnedVecStorage<_, N>`).
pub type PdoTable<S> = VecInner<(u16, u16), usize, S>;

impl<const HB: usize, const TXQ: usize, const EVQ: usize, const RPDO: usize, const TPDO: usize> NodeSizes
    for Sizes<HB, TXQ, EVQ, RPDO, TPDO>
{
    const TXQ: usize = TXQ;
    const EVQ: usize = EVQ;
    type Rpdos = [Rpdo; RPDO];
    type Tpdos = [Tpdo; TPDO];
    type RpdoTable = OwnedVecStorage<(u16, u16), RPDO>;
    type TpdoTable = OwnedVecStorage<(u16, u16), TPDO>;
    type TxQueue = OwnedVecStorage<CanFrame, TXQ>;
    type EventQueue = OwnedVecStorage<Event, EVQ>;
    const RPDO_TABLE: Vec<(u16, u16), RPDO> = Vec::new();
    const TPDO_TABLE: Vec<(u16, u16), TPDO> = Vec::new();
    const TX_QUEUE: Deque<CanFrame, TXQ> = Deque::new();
    const EVENT_QUEUE: Deque<Event, EVQ> = Deque::new();
    type ExtraSdo = [SdoServer; 0];
    type ExtraSdoParams = [SdoServerParams; 0];
    type SdoClients = [SdoClientRecord; 0];
}

/// Transmit-queue slots that block-upload segments never take, so that a heartbeat, an EMCY or a PDO due
/// during a block upload is queued rather than dropped (a queue of `TXQ` frames gives block upload at least
/// one slot).
pub const TX_RESERVE: usize = 3;

impl<A: ObjectDictionary, Z: NodeSizes> Node<A, Z, NoStorage> {
    /// A node in Initialization; it boots on the first call that passes the time in (NMT-03). Booting runs
    /// Reset Application, so every application entry then holds its default (for a derived dictionary, its
    /// `default =` value — the value the EDS announces), exactly as after an NMT reset node. It has no
    /// storage: 1010h/1011h answer 0606 0000h.
    pub fn new(node_id: NodeId, config: NodeConfig, app: A) -> Self {
        Self::build(node_id, config, app, NoStorage, |st, g, d, c, _| storage::update(st, g, d, 0, c, &NoApplication))
    }
}

impl<A: ObjectDictionary + OdDescribe, Z: NodeSizes, S: Storage> Node<A, Z, S> {
    /// A node whose parameters can be stored in `storage` (1010h/1011h, NMT-06): communication parameters
    /// and every writable application entry the dictionary describes.
    ///
    /// ```
    /// # use canopen_core::Sizes;
    /// use canopen_core::{profile::NodeConfig, node::{Node, NoApplication}, storage::NoStorage, NodeId};
    /// let node: Node<NoApplication, Sizes<0, 8, 8, 1, 1>, NoStorage> =
    ///     Node::with_storage(NodeId::new(2).unwrap(), NodeConfig::DEFAULT, NoApplication, NoStorage);
    /// assert_eq!(node.node_id().get(), 2);
    /// ```
    pub fn with_storage(node_id: NodeId, config: NodeConfig, app: A, storage: S) -> Self {
        Self::build(node_id, config, app, storage, |st, g, d, c, a| storage::update(st, g, d, 0, c, a))
    }
}

impl<A: ObjectDictionary, Z: NodeSizes, S: Storage> Node<A, Z, S> {
    fn build(node_id: NodeId, config: NodeConfig, app: A, storage: S, save: SaveFn<S, CommProfile<Z>, A>) -> Self {
        let mut comm = CommProfile::for_node(config, node_id.get());
        comm.storage_supported = storage.capacity() > 0;
        let sync = Sync::new(comm.params.sync);
        Node {
            node_id,
            comm,
            sdo: SdoServer::new(SdoServerParams::default_server(node_id)),
            sdo_extra: Z::ExtraSdo::from_fn(|_| SdoServer::new(SdoServerParams::DISABLED)),
            sdo_records: Z::ExtraSdoParams::from_fn(|_| SdoServerParams::DISABLED),
            sdo_clients: Z::SdoClients::from_fn(|_| SdoClientRecord::DISABLED),
            now: Instant::ZERO,
            nmt: Nmt::new(),
            boot_pending: true,
            producer: HeartbeatProducer::new(),
            consumer: HeartbeatConsumer::new_in_place(),
            #[cfg(feature = "guarding")]
            guarding: Guarding::new(),
            #[cfg(feature = "lss")]
            lss: LssSlave::new(&config.identity, Some(node_id)),
            app,
            sync,
            emcy: EmcyProducer::new(),
            // Built in place, not copied from a constant: `[IDLE; N]` constants cost 992 B of .rodata.
            rpdos: Z::Rpdos::from_fn(|_| Rpdo::new(&Default::default(), ResolvedMap::EMPTY)),
            tpdos: Z::Tpdos::from_fn(|_| Tpdo::new(&Default::default(), ResolvedMap::EMPTY)),
            rx_table: Z::RPDO_TABLE,
            rtr_table: Z::TPDO_TABLE,
            storage,
            save,
            sync_length_error: false,
            tx_overrun: false,
            tx_overrun_raised: false,
            bus: BusState::ErrorActive,
            bus_recovered: false,
            tx: Z::TX_QUEUE,
            events: Z::EVENT_QUEUE,
            tx_dropped: 0,
            events_dropped: 0,
            rx_generation: 0,
        }
    }

    /// The node-ID.
    pub const fn node_id(&self) -> NodeId {
        self.node_id
    }

    /// The current NMT state.
    pub const fn state(&self) -> NmtState {
        self.nmt.state()
    }

    /// The node configuration.
    pub const fn config(&self) -> &NodeConfig {
        &self.comm.config
    }

    /// The current communication parameters.
    pub const fn params(&self) -> &CommParams<Z> {
        &self.comm.params
    }

    /// The whole object dictionary as SDO, PDO and the EDS see it: the communication profile (1000h–1FFFh)
    /// merged with the application's entries.
    pub fn dictionary(&mut self) -> Merged<&mut CommProfile<Z>, &mut A> {
        self.cob_ids_may_change(); // a direct write may change a COB-ID
        Merged { comm: &mut self.comm, app: &mut self.app }
    }

    /// The communication-profile dictionary (1000h–1FFFh).
    pub const fn comm_profile(&self) -> &CommProfile<Z> {
        &self.comm
    }

    /// The application dictionary.
    pub const fn app(&self) -> &A {
        &self.app
    }

    /// The application dictionary, to change process values while the node runs.
    pub fn app_mut(&mut self) -> &mut A {
        &mut self.app
    }

    /// The storage.
    pub const fn storage(&self) -> &S {
        &self.storage
    }

    /// The storage, e.g. to inspect or replace its content in tests.
    pub fn storage_mut(&mut self) -> &mut S {
        &mut self.storage
    }

    /// The heartbeat consumer (remote states, time-outs).
    pub const fn heartbeat_consumer(&self) -> &HeartbeatConsumer<Z> {
        &self.consumer
    }

    /// Frames dropped because the transmit queue was full.
    pub const fn tx_dropped(&self) -> u32 {
        self.tx_dropped
    }

    /// Events dropped because the event queue was full.
    pub const fn events_dropped(&self) -> u32 {
        self.events_dropped
    }

    /// The next frame to send.
    pub fn poll_transmit(&mut self) -> Option<CanFrame> {
        #[cfg(feature = "lss")]
        if self.lss.holds_transmit(self.now) {
            return None; // CiA 305: silent from the bit-rate switch to the end of the second switch delay
        }
        let frame = self.tx.pop_front();
        self.refill_transmit();
        frame
    }

    /// The frame [`poll_transmit`](Self::poll_transmit) would return next, left in the queue: a runner that
    /// may be cancelled while a frame is on its way (an `async` driver in a `select!`) takes it out only once
    /// it was sent, with [`transmitted`](Self::transmitted), so a cancelled send loses nothing.
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{NoApplication, Node}, CanFrame, Instant, NodeId};
    /// let mut node: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// node.handle_timeout(Instant::ZERO);
    /// let boot_up = CanFrame::new(0x705, &[0x00]);
    /// assert_eq!(node.peek_transmit(), boot_up);
    /// assert_eq!(node.peek_transmit(), boot_up); // still there: not sent yet
    /// node.transmitted(&boot_up.unwrap());
    /// assert_eq!(node.peek_transmit(), None);
    /// ```
    ///
    /// Inline everywhere: out of line on bare metal (with LSS, whose hold test makes it more than a queue
    /// read) the node firmware was 84 B smaller, but every frame took about 10 more Cortex-M4 instructions per
    /// peek (test-qemu.sh: expedited upload 503 -> 523, RPDO 427 -> 437 per frame).
    pub fn peek_transmit(&self) -> Option<CanFrame> {
        // The queue first: empty is the common answer, and the hold is then not computed.
        let frame = self.tx.front()?;
        #[cfg(feature = "lss")]
        if self.lss.holds_transmit(self.now) {
            return None;
        }
        Some(*frame)
    }

    /// `frame`, got from [`peek_transmit`](Self::peek_transmit), is on the bus: removes it from the front of
    /// the transmit queue (and lets the node queue what follows, as [`poll_transmit`](Self::poll_transmit)
    /// does). Does nothing when the front is another frame: the queue was emptied meanwhile (a reset).
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{NoApplication, Node}, CanFrame, Instant, NodeId};
    /// let mut node: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// node.handle_timeout(Instant::ZERO);
    /// node.transmitted(&CanFrame::new(0x123, &[]).unwrap()); // not the front frame: nothing happens
    /// assert_eq!(node.poll_transmit(), CanFrame::new(0x705, &[0x00]));
    /// ```
    pub fn transmitted(&mut self, frame: &CanFrame) {
        if self.tx.front() == Some(frame) {
            self.tx.pop_front();
            self.refill_transmit();
        }
    }

    /// After a frame left the queue: the transmit-overflow error's state, then the EMCY and SDO work that
    /// waits for room in the queue.
    fn refill_transmit(&mut self) {
        if self.tx_overrun | self.tx_overrun_raised {
            self.overrun_state();
        }
        self.pump_emcy(self.now);
        #[cfg(feature = "sdo-block")]
        self.pump_sdo();
    }

    /// EEC-10: frames were lost; 8110h is raised once there is room for the EMCY, and cleared when the cause is
    /// gone: every frame queued since the overflow (the 8110h EMCY included) went out. Cold and out of line:
    /// with this inline, `poll_transmit` was no longer inlined into a runner's loop (+43 instructions per
    /// frame in `scripts/bench-node.sh`; out of line it costs 180 B of firmware flash instead).
    #[cold]
    fn overrun_state(&mut self) {
        if self.tx_overrun {
            self.tx_overrun = false;
            self.tx_overrun_raised |= self.raise_error(codes::CAN_OVERRUN, [0; 5]);
        } else if self.tx.is_empty() {
            self.tx_overrun_raised = false;
            self.clear_error(codes::CAN_OVERRUN);
        }
    }

    /// The next event for the application.
    pub fn poll_event(&mut self) -> Option<Event> {
        self.events.pop_front()
    }

    /// The next instant at which [`handle_timeout`](Self::handle_timeout) has work to do.
    pub fn poll_timeout(&self) -> Option<Instant> {
        if self.boot_pending {
            return Some(Instant::ZERO);
        }
        // As time::Deadline values (u64::MAX = none): a u64 minimum per service, not a match on two options.
        // One statement per service, so a service behind a Cargo feature is one `#[cfg]` line.
        let mut t = self.producer.deadline();
        t = t.min(self.consumer.deadline());
        #[cfg(feature = "guarding")]
        {
            t = t.min(self.guarding.deadline());
        }
        #[cfg(feature = "lss")]
        {
            t = t.min(crate::time::Deadline::new(self.lss.poll_timeout()));
        }
        t = t.min(self.sdo.deadline());
        t = t.min(self.extra_sdo_deadline());
        t = t.min(self.sync.deadline());
        t = t.min(self.emcy_timeout());
        t = t.min(self.pdo_timeout());
        t.get()
    }

    /// Lets the node act on the time that has passed: boot, heartbeats, consumer and life-guarding time-outs.
    pub fn handle_timeout(&mut self, now: Instant) {
        self.ensure_booted(now);
        #[cfg(feature = "lss")]
        self.lss_timeout(now);
        let response = sdo_dict!(self, |od| self.sdo.handle_timeout(now, od)); // nothing unless its deadline passed
        if response.frame.is_some() || response.event.is_some() {
            self.sdo_response_out_of_line(response, now);
        }
        self.extra_sdo_timeout(now);
        if self.producer.due(now) {
            self.send_error_control(Heartbeat(self.nmt.state().state_code()).emit());
        }
        while let Some(ev) = self.consumer.handle_timeout(now) {
            self.error_control_lost(now, Event::Heartbeat(ev));
        }
        #[cfg(feature = "guarding")]
        if let Some(ev) = self.guarding.handle_timeout(now) {
            self.error_control_lost(now, Event::LifeGuarding(ev));
        }
        self.sync_timeout(now);
        self.pdo_handle_timeout(now);
        self.pump_emcy(now);
    }

    /// Feeds one received frame.
    ///
    /// Out of line on bare metal without block transfer, where the SDO request handling is inline in it: so
    /// the SDO server's dispatch is out of the driver's service loop in both builds (the minimal device's
    /// firmware: 20 B less, footprint.sh; with block transfer the SDO part alone is out of line, and this
    /// out of line too was 168 B more).
    #[cfg_attr(all(target_os = "none", not(feature = "sdo-block")), inline(never))]
    pub fn handle_frame(&mut self, now: Instant, frame: &CanFrame) {
        self.ensure_booted(now);
        if self.bus_recovered {
            self.bus_works_again();
        }
        let id = frame.cob_id();
        let has_node_id = self.has_node_id();
        if has_node_id && self.sdo.receives(id) {
            // First: the SDO CAN-ID is restricted (COB-13), no other service may use it (nor LSS's 7E5h, in
            // the restricted 780h–7FFh), and SDO is the per-frame-heaviest service.
            return self.handle_sdo(now, frame);
        }
        if has_node_id {
            if let Some(i) = self.extra_sdo_for(id) {
                return self.handle_extra_sdo(now, i, frame); // 1201h+ (none unless WithSdoServers)
            }
        }
        #[cfg(feature = "lss")]
        if id == crate::cob::LSS_MASTER_ID {
            return self.handle_lss(now, frame); // CiA 305: LSS in every NMT state
        }
        if !has_node_id {
            return; // CiA 305: no node-ID, LSS only
        }
        if id == self.sync.can_id() && id != 0 {
            return self.handle_sync(now, frame);
        }
        if let Some(k) = self.rpdo_for(id) {
            return self.handle_rpdo(k, frame, now);
        }
        if frame.is_rtr() {
            if let Some(k) = self.rtr_tpdo_for(id) {
                return self.handle_tpdo_rtr(k, now);
            }
        }
        #[cfg(feature = "time")]
        if id == self.time_can_id() {
            return self.handle_time(frame);
        }
        // EMCY-10: with 1028h, an EMCY is consumed on the CAN-ID of a valid entry only (`node/optional.rs`).
        #[cfg(feature = "emcy-consumer")]
        if let Some(node) = self.comm.optional.emcy_producer(id) {
            return self.handle_emcy(node, frame);
        }
        let Some((function, node)) = FunctionCode::of(id) else {
            return;
        };
        match function {
            FunctionCode::Nmt if node == 0 => self.handle_node_control(now, frame),
            FunctionCode::NmtErrorControl if node != 0 => self.handle_error_control(now, node, frame),
            #[cfg(not(feature = "emcy-consumer"))]
            FunctionCode::SyncEmcy if node != 0 => self.handle_emcy(node, frame),
            _ => {}
        }
    }

    /// SDO-01, NMT-18: requests are served in Pre-operational and Operational only (an upload of 1000h:00 to
    /// a Stopped node gets no reply). The server handles DLC and content (CAN-07: frames shorter than 8 bytes
    /// are ignored).
    ///
    /// Out of line on bare metal with block transfer: inlined, the server's whole request dispatch sat in
    /// the driver's service loop, where it shares the registers with the loop's state and LLVM hoisted part
    /// of it out of the loop; out of line, the firmware's node is 276 B smaller (footprint.sh, the driver's
    /// task 7,372 -> 4,430 B, handle_sdo 2,006 B), for about 10 more Cortex-M4 instructions per SDO frame
    /// (test-qemu.sh: expedited upload 493 -> 503, block download 417 -> 426). Not on the host (a call more
    /// per SDO frame in `bench-node.sh`), nor without block transfer (the minimal device: 12 B more).
    #[cfg_attr(all(target_os = "none", feature = "sdo-block"), inline(never))]
    fn handle_sdo(&mut self, now: Instant, frame: &CanFrame) {
        if frame.is_rtr() || !self.nmt.state().allows(Service::Sdo) {
            return;
        }
        let response = sdo_dict!(self, |od| self.sdo.handle_request(now, frame.data(), od));
        // The frame came in on the rx COB-ID, so the channel is valid (SdoServerParams::is_valid covers both
        // COB-IDs, and a request never changes the server's own parameters): no second validity test.
        self.sdo_response(now, response, Some(self.sdo.params().cob_tx.can_id()));
        #[cfg(feature = "sdo-block")]
        self.pump_sdo();
    }

    /// Queues the server's frame on `cob`, its tx CAN-ID when the channel is valid (SDO-02: 8 bytes), and
    /// hands its event on. Inline: most frames have no event, and then this is the push alone; an
    /// application write is one more push.
    #[inline]
    fn sdo_response(&mut self, now: Instant, response: Response, cob: Option<u16>) {
        if let (Some(data), Some(cob)) = (response.frame, cob) {
            self.transmit(CanFrame::from_parts(cob, data, 8));
        }
        match response.event {
            None => {}
            // An application object written (the expedited and segmented downloads' event): no side
            // effect here, the event alone, inline, unless the application wants none (a constant for a
            // derived dictionary).
            Some(SdoEvent::Written { index, .. }) if index >= 0x2000 && !self.app.write_events() => {}
            Some(SdoEvent::Written { index, sub }) if index >= 0x2000 => {
                self.push_event(Event::ObjectWritten { index, sub })
            }
            Some(event) => self.sdo_event(now, event),
        }
    }

    /// [`sdo_response`](Self::sdo_response) for the paths that are not one request frame (a time-out, the
    /// block-upload segments), out of line. Neither path completes a download (their events are aborts), so
    /// every event goes to [`sdo_event`](Self::sdo_event): no copy of the inline path's case for application
    /// writes. The frame goes out on the default server's tx COB-ID, the callers' server, through the
    /// out-of-line [`send`](Self::send): its parts in registers, no frame built here. Both paths run
    /// during a transfer only, which began on a frame received on a valid channel, and new parameters end a
    /// transfer (`SdoServer::set_params`): the channel is valid, no second validity test (as in `handle_sdo`).
    /// `now` last: on a 32-bit target a 64-bit argument takes an even register pair, so right after `self`
    /// it leaves r1 empty and pushes the next argument to the stack at every call (footprint.sh, see the
    /// commit); the node's other out-of-line functions put it after one word-sized argument alike.
    #[inline(never)]
    fn sdo_response_out_of_line(&mut self, response: Response, now: Instant) {
        if let Some(data) = response.frame {
            self.send(self.sdo.params().cob_tx.can_id(), data, 8);
        }
        if let Some(event) = response.event {
            self.sdo_event(now, event);
        }
    }

    #[inline(never)]
    fn sdo_event(&mut self, now: Instant, event: SdoEvent) {
        // one push for all three events the application sees
        let event = match event {
            SdoEvent::Written { index, sub } => {
                if <Z::ExtraSdo as Slots<SdoServer>>::LEN > 0 && sdo_servers::is_server_record(index) {
                    self.sdo_record_written(index); // a 1201h+ record: its server follows
                }
                if index < 0x2000 {
                    self.comm_written(now, index, sub); // only 1000h–1FFFh have side effects here
                }
                Event::ObjectWritten { index, sub }
            }
            SdoEvent::Aborted { index, sub, code } => {
                Event::SdoAborted { index, sub, code: code.code(), by_client: false }
            }
            SdoEvent::AbortReceived { index, sub, code } => Event::SdoAborted { index, sub, code, by_client: true },
            SdoEvent::Uploaded { .. } => return,
        };
        self.push_event(event);
    }

    /// Moves block-upload segments from the SDO server into the transmit queue while it has room, so a
    /// sub-block of up to 127 frames never needs a queue of that size. [`TX_RESERVE`] slots stay free for
    /// the node's own frames (heartbeat, EMCY, PDOs) that fall due while a sub-block is going out.
    #[cfg(feature = "sdo-block")]
    #[inline]
    fn pump_sdo(&mut self) {
        if self.sdo.wants_transmit() {
            self.pump_sdo_segments();
        }
        if <Z::ExtraSdo as Slots<SdoServer>>::LEN > 0 {
            self.pump_extra_sdo();
        }
    }

    #[cfg(feature = "sdo-block")]
    #[inline(never)]
    fn pump_sdo_segments(&mut self) {
        while self.sdo.wants_transmit() && self.tx.storage_len() + TX_RESERVE.min(Z::TXQ.saturating_sub(1)) < Z::TXQ {
            let now = self.now;
            let response = sdo_dict!(self, |od| self.sdo.next_segment(now, od)); // wants_transmit: there is one
            self.sdo_response_out_of_line(response, now);
        }
    }

    /// Local control of the NMT state (NMT-16, NMT-17): e.g. enter Operational without waiting for a
    /// master. Resets are requested with NMT commands or [`reset_node`](Self::reset_node).
    pub fn enter_state(&mut self, target: NmtState) {
        let from = self.nmt.state();
        if let Transition::Enter(to) = self.nmt.enter(target) {
            self.state_changed(from, to);
        }
    }

    /// A local Reset Node (as if NMT 81h had been received).
    pub fn reset_node(&mut self, now: Instant) {
        self.ensure_booted(now);
        self.nmt.handle_command(crate::wire::nmt::NmtCommand::ResetNode);
        self.reset(true, now);
    }

    /// Sets the SDO server's protocol time-out (SDO-31; the default is 1 s, zero disables it). A transfer
    /// that waits longer than this for the client's next frame is aborted with 0504 0000h.
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{NoApplication, Node}, Duration, NodeId};
    /// let mut node: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// node.set_sdo_timeout(Duration::from_millis(5_000));
    /// ```
    pub fn set_sdo_timeout(&mut self, timeout: crate::time::Duration) {
        self.sdo.set_timeout(timeout);
        for s in self.sdo_extra.as_mut() {
            s.set_timeout(timeout); // the additional servers 1201h+ alike
        }
    }

    /// Writes 1017h producer heartbeat time (HB-01, HB-04: effective at once).
    pub fn set_heartbeat_time(&mut self, now: Instant, ms: u16) {
        self.comm.params.heartbeat_time_ms = ms;
        self.comm_written(now, 0x1017, 0);
    }

    /// Writes 1016h sub-index `sub` (HB-06..HB-09).
    pub fn set_consumer_heartbeat(&mut self, now: Instant, sub: u8, raw: u32) -> Result<(), AbortCode> {
        self.comm.params.set_consumer(sub, raw)?;
        self.comm_written(now, 0x1016, sub);
        Ok(())
    }

    /// Writes 100Ch guard time and 100Dh life time factor (GUARD-02..GUARD-04).
    #[cfg(feature = "guarding")]
    pub fn set_life_guarding(&mut self, now: Instant, guard_time_ms: u16, life_time_factor: u8) {
        self.comm.params.guard_time_ms = guard_time_ms;
        self.comm.params.life_time_factor = life_time_factor;
        self.comm_written(now, 0x100C, 0);
    }

    /// Applies the side effects of a communication object written at `now` (by SDO or the local API).
    fn comm_written(&mut self, now: Instant, index: u16, sub: u8) {
        self.cob_ids_may_change();
        let p = &self.comm.params;
        match index {
            0x1005 | 0x1006 | 0x1007 | 0x1019 => self.sync.reconfigure(now, p.sync),
            0x1014 | 0x1015 => self.emcy.set_inhibit_100us(p.emcy_inhibit_100us),
            0x1400..=0x1BFF => self.configure_pdo(index >= 0x1800, usize::from(index & 0x1FF)),
            0x1017 => self.producer.set_period(now, p.heartbeat_time_ms),
            0x1016 => {
                if let Some(raw) = usize::from(sub).checked_sub(1).and_then(|i| p.heartbeat_consumers.as_ref().get(i)) {
                    self.consumer.set_entry(usize::from(sub) - 1, *raw);
                }
                self.error_control_recovered(); // the timed-out entry may be gone
            }
            #[cfg(feature = "guarding")]
            0x100C | 0x100D => {
                self.guarding.set_life_time(now, p.guard_time_ms, p.life_time_factor);
                self.error_control_recovered(); // life guarding switched off or restarted
            }
            #[cfg(feature = "verify-config")]
            0x1011 => self.boot_configuration_restored(), // STORE-12: 1020h set to 0
            _ => {}
        }
    }

    fn ensure_booted(&mut self, now: Instant) {
        self.now = self.now.max(now);
        self.comm.optional.set_now(self.now); // 1013h runs on the node's clock (nothing without the feature)
        if self.boot_pending {
            self.reset(true, now); // clears boot_pending: one store in `reset`, not one per inlined copy of this
        }
    }

    /// Reset Application (if `application`) then Reset Communication, boot-up, Pre-operational (NMT-03..05),
    /// each loading the stored values of its group after the defaults (NMT-06). `application` before `now`:
    /// see [`sdo_response_out_of_line`](Self::sdo_response_out_of_line).
    fn reset(&mut self, application: bool, now: Instant) {
        self.boot_pending = false; // the power-on boot is this reset (`ensure_booted`); later ones find it false
        self.cob_ids_may_change(); // reset communication, an LSS node-ID
        if application {
            self.app.restore_defaults();
            let _ = storage::load(&mut self.storage, Groups::APP, &mut self.app);
            self.push_event(Event::ResetApplication);
        }
        let configured = self.lss_reset_communication(); // CiA 305: a pending node-ID becomes active
        self.comm.reset_communication();
        self.comm.errors.reset();
        self.tx_overrun_raised = false;
        self.comm.params.error_register = 0;
        self.bus_recovered = false;
        let _ = storage::load(&mut self.storage, Groups::COMM, &mut Unchecked(&mut self.comm));
        self.apply_comm_params(now);
        self.push_event(Event::ResetCommunication);
        // HB-04: the boot-up below counts as the first heartbeat; without a node-ID the producer is off.
        self.producer.start(now, if configured { self.comm.params.heartbeat_time_ms } else { 0 });
        if !configured {
            return; // CiA 305: no node-ID, stay in Initialisation serving LSS only
        }
        self.send_error_control(Heartbeat(StateCode::BootUp).emit()); // NMT-23: boot-up
        self.nmt.boot_completed();
        self.state_changed(NmtState::Initialising, NmtState::PreOperational);
        if self.comm.params.nmt_startup & 0x04 == 0 {
            self.enter_state(NmtState::Operational); // NMT-17, NMT-27
        }
    }

    /// Sets every service up from the (reset or loaded) communication parameters.
    fn apply_comm_params(&mut self, now: Instant) {
        let p = &self.comm.params;
        self.consumer.configure(&p.heartbeat_consumers);
        #[cfg(feature = "guarding")]
        self.guarding.reset();
        self.sdo.set_params(SdoServerParams::default_server(self.node_id));
        self.reset_extra_sdo(); // SDO-54: 1201h+ invalid again
        let p = &self.comm.params;
        self.sync.take_params(now, p.sync, true); // the parameters, then a restart (SYNC-07, SYNC-11)
        self.emcy.set_inhibit_100us(p.emcy_inhibit_100us);
        self.sync_length_error = false;
        // Every RPDO, then every TPDO: one loop over both.
        for i in 0..Z::RPDO + Z::TPDO {
            let tx = i >= Z::RPDO;
            self.configure_pdo(tx, if tx { i - Z::RPDO } else { i });
        }
    }

    /// Out of line: an NMT state change is rare, and inlined into its callers it was 8 B (node) and 12 B
    /// (minimal) more of the firmware's flash.
    #[inline(never)]
    fn state_changed(&mut self, from: NmtState, to: NmtState) {
        self.push_event(Event::StateChanged { from, to });
        if from == NmtState::Operational {
            self.stop_pdos();
        }
        if to == NmtState::Operational {
            self.start_pdos(self.now);
        }
        if to == NmtState::Stopped {
            // NMT-18: no SDO in Stopped; a transfer under way is dropped, so no time-out abort follows.
            sdo_dict!(self, |od| self.sdo.cancel(od));
            self.cancel_extra_sdo();
        }
        if from == NmtState::Stopped {
            // Leaving Stopped: one test for SYNC-11 and NMT-22 (towards Pre-operational no PDO starts above,
            // so the counter restarts in the same order as before).
            if to == NmtState::PreOperational {
                self.sync.restart_counter(); // SYNC-11
            }
            self.pump_emcy(self.now); // NMT-22: the most recent pending EMCY goes out now
        }
    }

    /// Queues a frame; a full queue drops it, counts it and raises EMCY 8110h (CAN overrun, EEC-10) as soon
    /// as there is room again. The error stays active until the application clears it.
    ///
    /// Out of line on bare metal, as LTO had it there: with the full test first the smaller body was
    /// otherwise inlined into its callers (footprint.sh node +180 B, minimal +112 B).
    #[cfg_attr(target_os = "none", inline(never))]
    fn transmit(&mut self, frame: CanFrame) {
        // The full test first, as in push_event (no test of the returned frame's niche).
        if self.tx.is_full() {
            self.tx_dropped = self.tx_dropped.saturating_add(1);
            self.tx_overrun = true;
        } else {
            let _ = self.tx.push_back(frame);
        }
    }

    /// [`transmit`](Self::transmit) of a frame the node builds from its CAN-ID, payload and length: the
    /// parts go in registers, where a `CanFrame` argument is built on the stack at every caller.
    #[inline(never)]
    fn send(&mut self, id: u16, data: [u8; 8], len: u8) {
        self.transmit(CanFrame::from_parts(id, data, len));
    }

    /// Out of line on bare metal, as LTO had it there: with the full test first its body is smaller and
    /// was otherwise inlined into every caller (footprint.sh node +776 B). Not on the host, whose
    /// benchmarked paths (`bench-node.sh`) keep LLVM's choice.
    #[cfg_attr(target_os = "none", inline(never))]
    fn push_event(&mut self, event: Event) {
        // The full test first: `push_back(..).is_err()` read the returned event's tag to tell `Err` from
        // `Ok` (the niche), where a full queue is always `Err`.
        if self.events.is_full() {
            self.events_dropped = self.events_dropped.saturating_add(1);
        } else {
            let _ = self.events.push_back(event);
        }
    }
}

/// Without the `lss` feature a node always has its node-ID (`node/with_lss.rs` has the CiA 305 versions).
#[cfg(not(feature = "lss"))]
impl<A: ObjectDictionary, Z: NodeSizes, S: Storage> Node<A, Z, S> {
    const fn has_node_id(&self) -> bool {
        true
    }

    fn lss_reset_communication(&mut self) -> bool {
        true
    }
}
