//! An async CANopen master on tokio: one CAN socket, many nodes at once.
//!
//! - **SDO** through `canopen-core`'s sans-IO client (expedited, segmented, block with CRC): typed
//!   [`Master::read`] / [`Master::write`], bytes and strings of any length ([`Master::upload`],
//!   [`Master::download`]), DOMAIN streaming from a reader / into a writer ([`Master::download_from`],
//!   [`Master::upload_to`]); aborts come back as [`Error::Aborted`] with the code and its meaning.
//! - **NMT** node control ([`Master::nmt`]), **heartbeat** and **EMCY** as broadcast streams
//!   ([`Master::heartbeats`], [`Master::emergencies`]), every received frame ([`Master::frames`]).
//! - Blocking calls for code without a runtime: [`blocking::BlockingMaster`].
//! - A **SYNC** producer ([`Master::start_sync`]), **PDO** remapping through SDO with the CiA 301
//!   disable/map/enable sequence ([`Master::configure_pdo`]), the core's **LSS** master ([`Master::lss`]).
//!
//! # How frames find their transfer
//!
//! One receive task reads the socket and hands each frame to whoever waits for its COB-ID: the SDO
//! transfer talking to that server (580h + node), the LSS service (7E4h), the heartbeat (700h + node) and
//! EMCY (80h + node) streams. So concurrent transfers to different nodes never see each other's frames,
//! and a transfer's time-out (the core client's own deadline, SDO-31) is never extended by frames from
//! other nodes: a read from a stopped node times out on time while that node's heartbeats arrive.
//! Transfers to the same server take turns (a server runs one transfer at a time).
//!
//! # Cancel safety
//!
//! Dropping a transfer's future (a `select!` or `timeout` around it) ends it: the master sends the server
//! an abort (0800 0000h, general error) from a spawned task, and the next transfer to that node can start.
//!
//! ```no_run
//! use canopen_master::{Master, NmtCommand};
//! # async fn demo() -> Result<(), canopen_master::Error> {
//! let master = Master::open("vcan0")?;
//! let device_type: u32 = master.read(5, 0x1000, 0).await?;
//! let name: String = master.read(5, 0x1008, 0).await?;
//! master.write(5, 0x2001, 0, -100i16).await?;
//! master.nmt(5, NmtCommand::Start).await?;
//! # Ok(()) }
//! ```

#![deny(unsafe_code)]
#![warn(missing_docs)]

use std::collections::HashMap;
use std::io;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use canopen_core::od::AbortCode;
use canopen_core::sdo::client::{Busy, SdoClient};
use canopen_core::sdo::SdoClientParams;
use canopen_core::wire::emcy::Emergency;
use canopen_core::wire::sdo::{abort_frame, Multiplexer};
use canopen_core::{CanFrame, NodeId};
use tokio::sync::{broadcast, mpsc, watch};
use tokio::task::JoinHandle;

pub mod blocking;
mod canio;
mod data;
mod error;
pub mod lss;
pub mod pdo;
pub mod sim;
mod value;

pub use canio::{CanIo, IoFuture, SocketCan};
pub use canopen_core::sdo::client::Mode;
pub use canopen_core::wire::error_control::StateCode;
pub use canopen_core::wire::nmt::NmtCommand;
/// EDS/DCF import (CiA 306) and EDS → Rust: the [`canopen_eds`] crate, which holds them (std only, for a
/// firmware's build.rs as well), under the name the master has always given them.
pub use canopen_eds as eds;
pub use data::Progress;
pub use error::{abort_meaning, Error};
pub use value::SdoValue;

use data::{Data, ReaderSource, SliceSource, VecSink, WriterSink};
use sim::TokioClock;

/// Block transfer with CRC, 127 segments per sub-block, no protocol switch: the fastest mode for large
/// values (SDO-35..SDO-51).
///
/// ```
/// assert!(matches!(canopen_master::BLOCK, canopen_master::Mode::Block { crc: true, blksize: 127, .. }));
/// ```
pub const BLOCK: Mode = Mode::Block { crc: true, blksize: 127, pst: 0 };

/// The SDO time-out of a new master: each step of a transfer must be answered within it (SDO-31).
pub const DEFAULT_SDO_TIMEOUT: Duration = Duration::from_millis(1000);

/// How long the server's line must stay quiet after a failed transfer before the next transfer to it starts
/// (what it still sends for the failed one, e.g. the rest of a sub-block, is discarded).
pub const QUIET: Duration = Duration::from_millis(50);

/// A heartbeat or boot-up message (700h + node, one byte; NMT-23, HB-02).
///
/// ```
/// use canopen_master::{Heartbeat, StateCode};
/// let hb = Heartbeat { node: 5, state: 0x7F };
/// assert_eq!(hb.state(), Some(StateCode::PreOperational));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Heartbeat {
    /// The node-ID.
    pub node: u8,
    /// The state byte (bit 7 is the toggle of a node-guarding reply, 0 in a heartbeat).
    pub state: u8,
}

impl Heartbeat {
    /// The NMT state it reports, `None` for an undefined code.
    ///
    /// ```
    /// assert_eq!(canopen_master::Heartbeat { node: 1, state: 0 }.state(), Some(canopen_master::StateCode::BootUp));
    /// ```
    pub fn state(&self) -> Option<StateCode> {
        StateCode::from_code(self.state & 0x7F)
    }
}

/// An emergency message of a node (80h + node, EMCY-04).
///
/// ```
/// use canopen_master::EmcyEvent;
/// use canopen_core::wire::emcy::Emergency;
/// let e = EmcyEvent { node: 5, emergency: Emergency { code: 0x8130, register: 0x11, manufacturer: [0; 5] } };
/// assert_eq!(e.emergency.code, 0x8130);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EmcyEvent {
    /// The node-ID (the COB-ID minus 80h).
    pub node: u8,
    /// The message.
    pub emergency: Emergency,
}

/// The node-ID for `node`, or an [`Error::InvalidArgument`].
pub(crate) fn node_id(node: u8) -> Result<NodeId, Error> {
    NodeId::new(node).ok_or_else(|| Error::InvalidArgument(format!("node-ID {node} is not in 1..=127")))
}

/// The frame routing table shared by the receive task and the transfers.
struct Router {
    /// Transfers waiting for a COB-ID (SDO responses, LSS 7E4h).
    routes: Mutex<HashMap<u16, mpsc::UnboundedSender<CanFrame>>>,
    /// One lock per COB-ID a transfer receives on: transfers to the same server take turns.
    locks: Mutex<HashMap<u16, Arc<tokio::sync::Mutex<()>>>>,
    heartbeat: broadcast::Sender<Heartbeat>,
    emcy: broadcast::Sender<EmcyEvent>,
    frames: broadcast::Sender<CanFrame>,
    /// Why the receive task stopped, once it has.
    closed: Mutex<Option<String>>,
    /// Why the transfers waiting for frames were last cut off (the socket failed and was reopened).
    interrupted: Mutex<Option<String>>,
    /// Whether the socket can be used: transfers cut off by an outage wait for it to abort their server.
    link: watch::Sender<Link>,
}

/// The state of the master's socket, as its receive task sees it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Link {
    Up,
    /// Failed; the receive task waits for it to come back ([`CanIo::reopen`]).
    Down,
    /// The receive task stopped.
    Closed,
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    // Nothing panics while holding these locks; a poisoned one still holds consistent maps.
    m.lock().unwrap_or_else(|p| p.into_inner())
}

impl Router {
    fn new() -> Self {
        Router {
            routes: Mutex::new(HashMap::new()),
            locks: Mutex::new(HashMap::new()),
            heartbeat: broadcast::channel(1024).0,
            emcy: broadcast::channel(256).0,
            frames: broadcast::channel(4096).0,
            closed: Mutex::new(None),
            interrupted: Mutex::new(None),
            link: watch::channel(Link::Up).0,
        }
    }

    fn dispatch(&self, f: CanFrame) {
        if self.frames.receiver_count() > 0 {
            let _ = self.frames.send(f);
        }
        if f.is_rtr() {
            return;
        }
        let id = f.cob_id();
        if let Some(tx) = lock(&self.routes).get(&id) {
            let _ = tx.send(f);
        }
        match (id, f.data()) {
            (0x701..=0x77F, &[state]) => {
                let _ = self.heartbeat.send(Heartbeat { node: (id - 0x700) as u8, state });
            }
            (0x081..=0x0FF, data) => {
                if let Ok(emergency) = Emergency::parse(data) {
                    let _ = self.emcy.send(EmcyEvent { node: (id - 0x80) as u8, emergency });
                }
            }
            _ => {}
        }
    }

    fn close(&self, why: String) {
        *lock(&self.closed) = Some(why);
        lock(&self.routes).clear();
        self.link.send_replace(Link::Closed);
    }

    /// The socket failed (`why`) while the receive task may go on: every transfer waiting for frames
    /// ends with [`Error::Interrupted`] (its route's sender is dropped).
    fn interrupt(&self, why: String) {
        *lock(&self.interrupted) = Some(why);
        self.link.send_replace(Link::Down);
        lock(&self.routes).clear();
    }

    /// Why a route stopped delivering: the master closed, or the socket failed under the transfer.
    fn closed_error(&self) -> Error {
        if let Some(why) = lock(&self.closed).clone() {
            return Error::Closed(why);
        }
        match lock(&self.interrupted).clone() {
            Some(why) => Error::Interrupted(why),
            None => Error::Closed("the master was dropped".into()),
        }
    }

    fn turn(&self, cob: u16) -> Arc<tokio::sync::Mutex<()>> {
        lock(&self.locks).entry(cob).or_default().clone()
    }

    /// Routes frames with `cob` to the returned receiver until it is dropped. The caller holds
    /// [`Router::turn`]`(cob)`, so no other route for `cob` exists.
    fn route(self: &Arc<Self>, cob: u16) -> Result<Route, Error> {
        let (tx, rx) = mpsc::unbounded_channel();
        {
            let closed = lock(&self.closed);
            if closed.is_some() {
                drop(closed);
                return Err(self.closed_error());
            }
            lock(&self.routes).insert(cob, tx);
        }
        Ok(Route { router: self.clone(), cob, rx })
    }
}

/// Frames of one COB-ID, while held.
pub(crate) struct Route {
    router: Arc<Router>,
    cob: u16,
    pub(crate) rx: mpsc::UnboundedReceiver<CanFrame>,
}

impl Drop for Route {
    fn drop(&mut self) {
        lock(&self.router.routes).remove(&self.cob);
    }
}

struct Inner {
    io: Arc<dyn CanIo>,
    router: Arc<Router>,
    clock: TokioClock,
    task: JoinHandle<()>,
}

impl Drop for Inner {
    fn drop(&mut self) {
        self.task.abort();
    }
}

/// The master: cheap to clone (every clone shares the socket and the receive task, which stops when the
/// last clone is dropped), usable from many tasks at once.
///
/// ```
/// use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
/// use canopen_master::{sim::SimBus, Master};
/// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
/// # rt.block_on(async {
/// let bus = SimBus::new();
/// let _nodes: Vec<_> = (1..=3)
///     .map(|id| bus.spawn_node(Node::<NoApplication>::new(NodeId::new(id).unwrap(), NodeConfig::DEFAULT, NoApplication)))
///     .collect();
/// let master = Master::new(bus.port());
/// let (a, b, c) = tokio::join!(master.read::<u32>(1, 0x1000, 0), master.read::<u32>(2, 0x1000, 0), master.read::<u32>(3, 0x1000, 0));
/// assert!(a.is_ok() && b.is_ok() && c.is_ok());
/// # });
/// ```
#[derive(Clone)]
pub struct Master {
    inner: Arc<Inner>,
    sdo_timeout: Duration,
}

impl Master {
    /// A master on `io`; spawns its receive task on the current tokio runtime.
    ///
    /// # Panics
    ///
    /// Outside a tokio runtime (as `tokio::spawn` does).
    ///
    /// # When the socket fails
    ///
    /// At a receive error every transfer waiting for frames fails at once with [`Error::Interrupted`] and
    /// the reason, then the receive task asks [`CanIo::reopen`] to wait for the socket: on [`SocketCan`],
    /// when the interface went down (`ip link set can0 down`) or away, until it is up again, then on a
    /// fresh socket. Meanwhile transfers fail when they send (`Network is down`); once it is back they work
    /// again on the same master. Any other receive error (or an `io` that cannot reopen) stops the task:
    /// every waiting and later transfer then fails with [`Error::Closed`] and the reason.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// let master = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// # });
    /// ```
    pub fn new(io: impl CanIo) -> Self {
        let io: Arc<dyn CanIo> = Arc::new(io);
        let router = Arc::new(Router::new());
        let task = {
            let (io, router) = (io.clone(), router.clone());
            tokio::spawn(async move {
                // Every frame queued at a wake-up is taken at once (one recvmmsg on SocketCAN) and routed
                // before the transfers run: a block upload's sub-block wakes each side once, not per frame.
                let mut batch = Vec::with_capacity(canopen_socketcan::BATCH);
                loop {
                    match io.recv_many(&mut batch).await {
                        Ok(_) => batch.drain(..).for_each(|f| router.dispatch(f)),
                        Err(e) => {
                            // Transfers in flight end now; the task waits for the socket to come back.
                            router.interrupt(e.to_string());
                            match io.reopen().await {
                                Ok(true) => {
                                    router.link.send_replace(Link::Up);
                                }
                                Ok(false) => return router.close(e.to_string()),
                                Err(again) => return router.close(format!("{e}; reopening failed: {again}")),
                            }
                        }
                    }
                }
            })
        };
        Master {
            inner: Arc::new(Inner { io, router, clock: TokioClock::new(), task }),
            sdo_timeout: DEFAULT_SDO_TIMEOUT,
        }
    }

    /// A master on the SocketCAN interface `iface` (inside a tokio runtime).
    ///
    /// ```no_run
    /// # async fn demo() -> Result<(), canopen_master::Error> {
    /// let master = canopen_master::Master::open("can0")?;
    /// # Ok(()) }
    /// ```
    pub fn open(iface: &str) -> Result<Self, Error> {
        Ok(Master::new(SocketCan::open(iface)?))
    }

    /// This master with another SDO time-out (per protocol step, SDO-31; zero waits for ever). Other clones
    /// keep theirs.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// use std::time::Duration;
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port()).with_sdo_timeout(Duration::from_millis(100));
    /// assert_eq!(m.sdo_timeout(), Duration::from_millis(100));
    /// # });
    /// ```
    pub fn with_sdo_timeout(mut self, timeout: Duration) -> Self {
        self.sdo_timeout = timeout;
        self
    }

    /// The SDO time-out.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// assert_eq!(m.sdo_timeout(), canopen_master::DEFAULT_SDO_TIMEOUT);
    /// # });
    /// ```
    pub fn sdo_timeout(&self) -> Duration {
        self.sdo_timeout
    }

    /// Sends one frame.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// m.send(&canopen_core::CanFrame::new(0x80, &[]).unwrap()).await.unwrap(); // a SYNC
    /// # });
    /// ```
    pub async fn send(&self, frame: &CanFrame) -> Result<(), Error> {
        Ok(self.inner.io.send(frame).await?)
    }

    /// Every frame received from now on (for a bus monitor). A receiver that falls more than 4096 frames
    /// behind loses the oldest (`RecvError::Lagged`).
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// let mut frames = m.frames();
    /// # });
    /// ```
    pub fn frames(&self) -> broadcast::Receiver<CanFrame> {
        self.inner.router.frames.subscribe()
    }

    /// Every heartbeat and boot-up message received from now on.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// let mut heartbeats = m.heartbeats();
    /// # });
    /// ```
    pub fn heartbeats(&self) -> broadcast::Receiver<Heartbeat> {
        self.inner.router.heartbeat.subscribe()
    }

    /// Every emergency message received from now on.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
    /// let mut emcy = m.emergencies();
    /// # });
    /// ```
    pub fn emergencies(&self) -> broadcast::Receiver<EmcyEvent> {
        self.inner.router.emcy.subscribe()
    }

    /// Sends an NMT node-control command (NMT-07..NMT-13) to `node`, or to every node with `node` 0.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// use canopen_master::{Master, NmtCommand};
    /// let m = Master::new(canopen_master::sim::SimBus::new().port());
    /// m.nmt(0, NmtCommand::Start).await.unwrap(); // all nodes
    /// assert!(m.nmt(128, NmtCommand::Start).await.is_err());
    /// # });
    /// ```
    pub async fn nmt(&self, node: u8, command: NmtCommand) -> Result<(), Error> {
        if node != 0 {
            node_id(node)?;
        }
        self.send(&CanFrame::from_parts(0, [command as u8, node, 0, 0, 0, 0, 0, 0], 2)).await
    }

    /// Waits up to `timeout` for a heartbeat of `node` reporting `state` (heartbeats with other states, sent
    /// before the node acted on a command, are skipped); [`Error::Timeout`] if none comes.
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// use std::time::Duration;
    /// use canopen_master::{Master, NmtCommand, StateCode};
    /// let bus = canopen_master::sim::SimBus::new();
    /// let config = NodeConfig { heartbeat_time_ms: 100, ..NodeConfig::DEFAULT };
    /// let _n = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(4).unwrap(), config, NoApplication));
    /// let m = Master::new(bus.port());
    /// m.nmt(4, NmtCommand::Start).await.unwrap();
    /// m.wait_for_state(4, StateCode::Operational, Duration::from_secs(1)).await.unwrap();
    /// # });
    /// ```
    pub async fn wait_for_state(&self, node: u8, state: StateCode, timeout: Duration) -> Result<(), Error> {
        let mut rx = self.heartbeats();
        let wait = async {
            loop {
                match rx.recv().await {
                    Ok(hb) if hb.node == node && hb.state() == Some(state) => return Ok(()),
                    Ok(_) | Err(broadcast::error::RecvError::Lagged(_)) => {}
                    Err(broadcast::error::RecvError::Closed) => return Err(self.inner.router.closed_error()),
                }
            }
        };
        tokio::time::timeout(timeout, wait).await.unwrap_or(Err(Error::Timeout))
    }

    /// Starts a SYNC producer (1005h/1006h/1019h on the master's side): a SYNC on 80h every `period`, with a
    /// counter 1..=`overflow` in one data byte when `overflow` is 2..=240 (SYNC-04), without data when it is
    /// 0. It runs until the returned handle is dropped.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// use std::time::Duration;
    /// let bus = canopen_master::sim::SimBus::new();
    /// let m = canopen_master::Master::new(bus.port());
    /// let watcher = canopen_master::Master::new(bus.port());
    /// let mut frames = watcher.frames();
    /// let sync = m.start_sync(Duration::from_millis(10), 3).unwrap();
    /// for counter in [1, 2, 3, 1] {
    ///     assert_eq!(frames.recv().await.unwrap().data(), &[counter]);
    /// }
    /// # });
    /// ```
    pub fn start_sync(&self, period: Duration, overflow: u8) -> Result<SyncProducer, Error> {
        if overflow == 1 || overflow > 240 {
            return Err(Error::InvalidArgument(format!("SYNC counter overflow {overflow} is not 0 or 2..=240")));
        }
        if period.is_zero() {
            return Err(Error::InvalidArgument("a SYNC period of 0".into()));
        }
        let io = self.inner.io.clone();
        let task = tokio::spawn(async move {
            let mut tick = tokio::time::interval(period);
            tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
            let mut counter = 0u8;
            loop {
                tick.tick().await;
                let frame = if overflow == 0 {
                    CanFrame::from_parts(0x80, [0; 8], 0)
                } else {
                    counter = if counter >= overflow { 1 } else { counter + 1 };
                    CanFrame::from_parts(0x80, [counter, 0, 0, 0, 0, 0, 0, 0], 1)
                };
                if io.send(&frame).await.is_err() {
                    return;
                }
            }
        });
        Ok(SyncProducer { task })
    }

    /// Reads a typed value (`u8`..`u64`, `i8`..`i64`, `f32`, `f64`, `bool`, `String`, `Vec<u8>`) from
    /// `index:sub` of `node`. A value of another size is [`Error::TypeMismatch`].
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let bus = canopen_master::sim::SimBus::new();
    /// let _n = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(2).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let m = canopen_master::Master::new(bus.port());
    /// let vendor: u32 = m.read(2, 0x1018, 1).await.unwrap();
    /// assert!(m.read::<u16>(2, 0x1018, 1).await.is_err()); // 4 bytes are no UNSIGNED16
    /// let e = m.read::<u32>(2, 0x1234, 0).await.unwrap_err();
    /// assert_eq!(e.abort_code(), Some(0x0602_0000));
    /// # });
    /// ```
    pub async fn read<T: SdoValue>(&self, node: u8, index: u16, sub: u8) -> Result<T, Error> {
        // A fixed-size type still takes a few bytes more, so that a wrong type is a type mismatch and not an
        // "out of memory" abort.
        let cap = T::SIZE.map_or(usize::MAX, |s| s.max(64));
        let mut sink = VecSink::upload(cap);
        let len = self.transfer(node, Multiplexer::new(index, sub), Start::Upload(Mode::Auto), &mut sink).await?;
        sink.buf.truncate(len);
        T::decode(&sink.buf)
    }

    /// Writes a typed value to `index:sub` of `node` (expedited up to 4 bytes, segmented above).
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let bus = canopen_master::sim::SimBus::new();
    /// let _n = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(2).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let m = canopen_master::Master::new(bus.port());
    /// m.write(2, 0x1017, 0, 250u16).await.unwrap(); // producer heartbeat time
    /// assert_eq!(m.read::<u16>(2, 0x1017, 0).await.unwrap(), 250);
    /// # });
    /// ```
    pub async fn write<T: SdoValue>(&self, node: u8, index: u16, sub: u8, value: T) -> Result<(), Error> {
        self.download(node, index, sub, &value.encode(), Mode::Auto).await
    }

    /// Reads the bytes of `index:sub` (any length) in `mode` ([`Mode::Auto`], or [`BLOCK`] for large values).
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let bus = canopen_master::sim::SimBus::new();
    /// let _n = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(2).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let m = canopen_master::Master::new(bus.port());
    /// let name = m.upload(2, 0x1008, 0, canopen_master::BLOCK).await.unwrap();
    /// assert_eq!(name, NodeConfig::DEFAULT.device_name.as_bytes());
    /// # });
    /// ```
    pub async fn upload(&self, node: u8, index: u16, sub: u8, mode: Mode) -> Result<Vec<u8>, Error> {
        let mut sink = VecSink::upload(usize::MAX);
        let len = self.transfer(node, Multiplexer::new(index, sub), Start::Upload(mode), &mut sink).await?;
        sink.buf.truncate(len);
        Ok(sink.buf)
    }

    /// Writes `data` (any length up to 4 GiB - 1) to `index:sub` in `mode`.
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let bus = canopen_master::sim::SimBus::new();
    /// let _n = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(2).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let m = canopen_master::Master::new(bus.port());
    /// let e = m.download(2, 0x1000, 0, &[1, 2, 3, 4], canopen_master::Mode::Auto).await.unwrap_err();
    /// assert_eq!(e.abort_code(), Some(0x0601_0002)); // 1000h is read-only
    /// # });
    /// ```
    pub async fn download(&self, node: u8, index: u16, sub: u8, data: &[u8], mode: Mode) -> Result<(), Error> {
        let mut src = SliceSource { src: data, progress: None };
        let start = Start::Download(data.len(), mode);
        self.transfer(node, Multiplexer::new(index, sub), start, &mut src).await.map(|_| ())
    }

    /// Streams `index:sub` (a DOMAIN, a firmware image...) into `out` as it arrives, calling `progress` with
    /// the bytes received so far; returns the length. `out` is written from the async task (a file or a
    /// buffer; wrap a slow sink in a channel).
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let bus = canopen_master::sim::SimBus::new();
    /// let _n = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(2).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let m = canopen_master::Master::new(bus.port());
    /// let mut out = Vec::new();
    /// let mut seen = 0;
    /// let len = m.upload_to(2, 0x1008, 0, canopen_master::BLOCK, &mut out, Some(&mut |n| seen = n)).await.unwrap();
    /// assert_eq!((len, seen), (out.len() as u64, len));
    /// # });
    /// ```
    pub async fn upload_to(
        &self,
        node: u8,
        index: u16,
        sub: u8,
        mode: Mode,
        out: &mut (dyn io::Write + Send),
        progress: Option<Progress<'_>>,
    ) -> Result<u64, Error> {
        let mut sink = WriterSink { writer: out, written: 0, progress, error: None };
        let len = self.transfer(node, Multiplexer::new(index, sub), Start::Upload(mode), &mut sink).await?;
        Ok(len as u64)
    }

    /// Streams `len` bytes from `source` into `index:sub`, keeping only a few KiB of it in memory, calling
    /// `progress` with the bytes handed to the transfer so far. A source that fails or ends early aborts the
    /// transfer (0800 0000h) and returns its I/O error.
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// let bus = canopen_master::sim::SimBus::new();
    /// let _n = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(2).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let m = canopen_master::Master::new(bus.port());
    /// let mut source: &[u8] = &[0xF4, 0x01]; // 500 ms
    /// m.download_from(2, 0x1017, 0, canopen_master::Mode::Segmented, &mut source, 2, None).await.unwrap();
    /// assert_eq!(m.read::<u16>(2, 0x1017, 0).await.unwrap(), 500);
    /// # });
    /// ```
    #[allow(clippy::too_many_arguments)]
    pub async fn download_from(
        &self,
        node: u8,
        index: u16,
        sub: u8,
        mode: Mode,
        source: &mut (dyn io::Read + Send),
        len: u64,
        progress: Option<Progress<'_>>,
    ) -> Result<(), Error> {
        let len = usize::try_from(len).map_err(|_| Error::InvalidArgument(format!("{len} bytes")))?;
        let mut src = ReaderSource::new(source, len, progress);
        self.transfer(node, Multiplexer::new(index, sub), Start::Download(len, mode), &mut src).await.map(|_| ())
    }

    /// Which of the nodes 1..=127 answer an SDO read of 1000h within `timeout` (all asked at once); a node
    /// that answers with an abort is there too.
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
    /// # rt.block_on(async {
    /// use std::time::Duration;
    /// let bus = canopen_master::sim::SimBus::new();
    /// let _a = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(2).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let _b = bus.spawn_node(Node::<NoApplication>::new(NodeId::new(90).unwrap(), NodeConfig::DEFAULT, NoApplication));
    /// let m = canopen_master::Master::new(bus.port());
    /// assert_eq!(m.scan(Duration::from_millis(100)).await.unwrap(), vec![2, 90]);
    /// # });
    /// ```
    pub async fn scan(&self, timeout: Duration) -> Result<Vec<u8>, Error> {
        let m = self.clone().with_sdo_timeout(timeout);
        let mut set = tokio::task::JoinSet::new();
        for node in 1..=127u8 {
            let m = m.clone();
            set.spawn(async move { (node, m.upload(node, 0x1000, 0, Mode::Auto).await) });
        }
        let mut found = Vec::new();
        while let Some(joined) = set.join_next().await {
            let (node, result) = joined.map_err(|e| Error::Io(io::Error::other(e)))?;
            match result {
                Ok(_) | Err(Error::Aborted { by_server: true, .. }) => found.push(node),
                Err(Error::Aborted { by_server: false, .. }) => {}
                Err(e) => return Err(e),
            }
        }
        found.sort_unstable();
        Ok(found)
    }

    /// One SDO transfer with `node`'s default server (600h/580h + node), driven to its end.
    async fn transfer(&self, node: u8, mux: Multiplexer, start: Start, data: &mut dyn Data) -> Result<usize, Error> {
        let params = SdoClientParams::for_server(node_id(node)?);
        let (tx_cob, rx_cob) = (params.tx_cob_id(), params.rx_cob_id());
        let router = &self.inner.router;
        if *router.link.borrow() == Link::Down {
            return Err(router.closed_error()); // at once, not after a time-out
        }
        let turn = router.turn(rx_cob).lock_owned().await;
        let mut route = router.route(rx_cob)?;
        let timeout = canopen_core::Duration::from_micros(self.sdo_timeout.as_micros() as u64);
        let mut client = SdoClient::new(params).with_timeout(timeout);
        let now = self.inner.clock.now();
        let started = match start {
            Start::Upload(mode) => client.start_upload(now, mux, mode),
            Start::Download(len, mode) if u32::try_from(len).is_ok() => client.start_download(now, mux, len, mode),
            Start::Download(len, _) => {
                return Err(Error::InvalidArgument(format!("{len} bytes: more than SDO's 4 GiB - 1")))
            }
        };
        started.map_err(|Busy| Error::InvalidArgument("the SDO client is busy".into()))?;
        let mut armed = AbortOnDrop { io: self.inner.io.clone(), cob: tx_cob, mux: Some(mux) };
        let result = self.drive(&mut client, &mut route, data, tx_cob).await;
        armed.mux = None;
        if let Err(e) = &result {
            // A transfer cut off by the socket (the interface went down) leaves the server in it: once the
            // socket is back, abort it (0800 0000h), so that the next transfer finds the server idle.
            let cut_off = matches!(e, Error::Interrupted(_) | Error::Io(_))
                .then(|| CanFrame::from_parts(tx_cob, abort_frame(mux, AbortCode::GeneralError.code()), 8));
            let (io, router) = (self.inner.io.clone(), self.inner.router.clone());
            // What the server still sends for this transfer must not be taken for the next one's answer: the
            // next transfer to this server waits until its line has been quiet for QUIET; this one returns now.
            tokio::spawn(async move {
                if let Some(abort) = cut_off {
                    drop(route); // dead after an outage: routed anew below
                    route = match abort_after_outage(&*io, &router, rx_cob, &abort).await {
                        Some(r) => r,
                        None => return, // the master closed
                    };
                }
                while let Ok(Some(_)) = tokio::time::timeout(QUIET, route.rx.recv()).await {}
                drop((route, turn));
            });
        }
        result
    }

    async fn drive(
        &self,
        client: &mut SdoClient,
        route: &mut Route,
        data: &mut dyn Data,
        tx_cob: u16,
    ) -> Result<usize, Error> {
        use canopen_core::sdo::client::ClientEvent;
        let clock = self.inner.clock;
        let mut out = Vec::new();
        let mut now = clock.now();
        loop {
            self.flush(client, data, tx_cob, now, &mut out).await?;
            if let Some(e) = data.take_error() {
                client.abort(AbortCode::GeneralError);
                self.flush(client, data, tx_cob, now, &mut out).await?;
                return Err(Error::Io(e));
            }
            let deadline = client.poll_timeout().map(|t| clock.to_tokio(t));
            let event = tokio::select! {
                frame = route.rx.recv() => match frame {
                    Some(f) => {
                        // One clock reading for every frame already routed to this transfer (a block
                        // upload's sub-block arrives as one batch); what the client answers in between
                        // is collected and sent in order after them.
                        now = clock.now();
                        let mut event = client.handle_response(now, f.data(), data);
                        while event.is_none() {
                            queue(client, data, tx_cob, now, &mut out);
                            match route.rx.try_recv() {
                                Ok(f) => event = client.handle_response(now, f.data(), data),
                                Err(_) => break,
                            }
                        }
                        event
                    }
                    None => return Err(self.inner.router.closed_error()),
                },
                _ = sleep_until(deadline) => {
                    now = clock.now();
                    client.handle_timeout(now)
                }
            };
            match event {
                None => {}
                Some(ClientEvent::Done { len }) => {
                    self.flush(client, data, tx_cob, now, &mut out).await?;
                    return match data.take_error() {
                        Some(e) => Err(Error::Io(e)),
                        None => Ok(len),
                    };
                }
                Some(ClientEvent::Failed(e)) => {
                    self.flush(client, data, tx_cob, now, &mut out).await?;
                    // A local write error (a file) is reported as itself, not only as its abort code.
                    return Err(data.take_error().map_or_else(|| e.into(), Error::Io));
                }
            }
        }
    }

    /// Sends what the client has to send (after what `out` already holds), in one
    /// [`CanIo::send_many`]: a block download's sub-block (up to 127 segments) goes out in two `sendmmsg`
    /// on one clock reading, `now` (the time of the frames just handled), so its time-out runs from there
    /// (scripts/bench-master.sh counts the system calls per frame).
    async fn flush(
        &self,
        client: &mut SdoClient,
        data: &mut dyn Data,
        tx_cob: u16,
        now: canopen_core::Instant,
        out: &mut Vec<CanFrame>,
    ) -> Result<(), Error> {
        queue(client, data, tx_cob, now, out);
        if !out.is_empty() {
            let sent = self.inner.io.send_many(out).await;
            out.clear();
            sent?;
        }
        Ok(())
    }
}

/// Appends what the client has to send at `now` to `out`.
fn queue(
    client: &mut SdoClient,
    data: &mut dyn Data,
    tx_cob: u16,
    now: canopen_core::Instant,
    out: &mut Vec<CanFrame>,
) {
    out.extend(std::iter::from_fn(|| client.poll_transmit(now, data)).map(|b| CanFrame::from_parts(tx_cob, b, 8)));
}

/// Sends `abort` for a transfer an outage cut off, once the socket is up again and
/// 2 × [`REOPEN_POLL`](canopen_socketcan::REOPEN_POLL) later (a send that fails because
/// the receive task has not seen the outage yet is retried after it has, up to three times), and returns
/// a route for the server's COB-ID `cob` to discard what it still sends; `None` when the master closed.
async fn abort_after_outage(io: &dyn CanIo, router: &Arc<Router>, cob: u16, abort: &CanFrame) -> Option<Route> {
    let mut link = router.link.subscribe();
    for _ in 0..3 {
        if !matches!(link.wait_for(|l| *l != Link::Down).await.map(|l| *l), Ok(Link::Up)) {
            return None;
        }
        // Nodes on the same interface (vcan) reopen their sockets too, polling as often as the master
        // (canopen-socketcan's runners): an abort sent before they did would be lost.
        tokio::time::sleep(2 * canopen_socketcan::REOPEN_POLL).await;
        if io.send(abort).await.is_ok() {
            break;
        }
        // Not an outage after all, or one the receive task has not seen yet: wait a little for it.
        let _ = tokio::time::timeout(Duration::from_secs(1), link.changed()).await;
    }
    router.route(cob).ok()
}

async fn sleep_until(deadline: Option<tokio::time::Instant>) {
    match deadline {
        Some(d) => tokio::time::sleep_until(d).await,
        None => std::future::pending().await,
    }
}

enum Start {
    Upload(Mode),
    Download(usize, Mode),
}

/// Sends the server an abort when a transfer's future is dropped before its end.
struct AbortOnDrop {
    io: Arc<dyn CanIo>,
    cob: u16,
    mux: Option<Multiplexer>,
}

impl Drop for AbortOnDrop {
    fn drop(&mut self) {
        if let (Some(mux), Ok(rt)) = (self.mux.take(), tokio::runtime::Handle::try_current()) {
            let io = self.io.clone();
            let frame = CanFrame::from_parts(self.cob, abort_frame(mux, AbortCode::GeneralError.code()), 8);
            rt.spawn(async move {
                let _ = io.send(&frame).await;
            });
        }
    }
}

/// A running SYNC producer ([`Master::start_sync`]); dropping it stops the SYNCs.
///
/// ```
/// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
/// # rt.block_on(async {
/// let m = canopen_master::Master::new(canopen_master::sim::SimBus::new().port());
/// let sync = m.start_sync(std::time::Duration::from_millis(10), 0).unwrap();
/// drop(sync); // stops
/// # });
/// ```
pub struct SyncProducer {
    task: JoinHandle<()>,
}

impl Drop for SyncProducer {
    fn drop(&mut self) {
        self.task.abort();
    }
}

/// The README's example, compiled (not run: it needs vcan0) as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctest;
