//! An in-memory CAN bus on tokio, for tests without SocketCAN: the master on a [`SimPort`], and any number of
//! `canopen-core` nodes on the same bus ([`SimBus::spawn_node`]) run by the core's async driver. Time is
//! tokio's, so a test on a paused clock (`#[tokio::test(start_paused = true)]`) runs in simulated time.
//!
//! Every frame reaches every other port, in the order sent (a broadcast channel); a port never receives its
//! own frames, like a CAN socket without `CAN_RAW_RECV_OWN_MSGS`.
//!
//! ```
//! use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
//! use canopen_master::{sim::SimBus, Master};
//! # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
//! # rt.block_on(async {
//! let bus = SimBus::new();
//! let node: Node<NoApplication> = Node::new(NodeId::new(3).unwrap(), NodeConfig::DEFAULT, NoApplication);
//! let _node = bus.spawn_node(node);
//! let master = Master::new(bus.port());
//! assert_eq!(master.read::<u32>(3, 0x1000, 0).await.unwrap(), NodeConfig::DEFAULT.device_type);
//! # });
//! ```

use std::future::Future;
use std::io;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

use canopen_core::driver::{self, CanRx, CanTx, Timer};
use canopen_core::driver::{Shared, Wake};
use canopen_core::node::SansIo;
use canopen_core::{CanFrame, Event, Instant};
use tokio::sync::{broadcast, Mutex};
use tokio::task::JoinHandle;

use crate::canio::{CanIo, IoFuture};

/// Frames the bus holds for a slow port before that port loses the oldest (and counts them as lost).
pub const SIM_CAPACITY: usize = 4096;

/// The in-memory bus. Cloning it gives another handle to the same bus.
///
/// ```
/// # let rt = tokio::runtime::Builder::new_current_thread().build().unwrap();
/// # rt.block_on(async {
/// let bus = canopen_master::sim::SimBus::new();
/// let (a, b) = (bus.port(), bus.port());
/// # });
/// ```
#[derive(Clone)]
pub struct SimBus {
    tx: broadcast::Sender<(usize, CanFrame)>,
    next: Arc<AtomicUsize>,
}

impl Default for SimBus {
    fn default() -> Self {
        SimBus::new()
    }
}

impl SimBus {
    /// An empty bus.
    ///
    /// ```
    /// let _ = canopen_master::sim::SimBus::new();
    /// ```
    pub fn new() -> Self {
        SimBus { tx: broadcast::channel(SIM_CAPACITY).0, next: Arc::new(AtomicUsize::new(0)) }
    }

    /// A new port: it receives every frame another port sends from now on.
    ///
    /// ```
    /// # let rt = tokio::runtime::Builder::new_current_thread().build().unwrap();
    /// # rt.block_on(async {
    /// use canopen_master::CanIo;
    /// let bus = canopen_master::sim::SimBus::new();
    /// let (a, b) = (bus.port(), bus.port());
    /// let f = canopen_core::CanFrame::new(0x123, &[1]).unwrap();
    /// a.send(&f).await.unwrap();
    /// assert_eq!(b.recv().await.unwrap(), f);
    /// # });
    /// ```
    pub fn port(&self) -> SimPort {
        let id = self.next.fetch_add(1, Ordering::Relaxed);
        SimPort { id, tx: self.tx.clone(), rx: Mutex::new(self.tx.subscribe()) }
    }

    /// Runs `node` on a new port of this bus (the core's [`driver::run`] on tokio time) until the returned
    /// [`SimNode`] is dropped.
    ///
    /// ```
    /// use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// let bus = canopen_master::sim::SimBus::new();
    /// let node: Node<NoApplication> = Node::new(NodeId::new(3).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// let sim = bus.spawn_node(node);
    /// sim.with(|n| assert_eq!(n.node_id().get(), 3));
    /// # });
    /// ```
    pub fn spawn_node<N: SansIo + Send + 'static>(&self, node: N) -> SimNode<N> {
        self.spawn_node_with(node, |_, _| {})
    }

    /// As [`spawn_node`](Self::spawn_node), with the node's application reacting to its events: `on_event`
    /// gets the node (locked) and each event the driver hands out (a drive taking its set-point at a SYNC,
    /// running its cycle after an RPDO).
    ///
    /// ```
    /// use canopen_core::{node::NoApplication, profile::NodeConfig, Event, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// let bus = canopen_master::sim::SimBus::new();
    /// let node: Node<NoApplication> = Node::new(NodeId::new(3).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// let sim = bus.spawn_node_with(node, |_node, event| {
    ///     if let Event::Sync { .. } = event { /* the application's SYNC work */ }
    /// });
    /// # });
    /// ```
    pub fn spawn_node_with<N: SansIo + Send + 'static>(
        &self,
        node: N,
        mut on_event: impl FnMut(&mut N, Event) + Send + 'static,
    ) -> SimNode<N> {
        let shared = Arc::new(MutexShared::new(node));
        let wake = Arc::new(NotifyWake::new());
        let port = self.port();
        let task = {
            let (shared, wake) = (shared.clone(), wake.clone());
            tokio::spawn(async move {
                let (mut rx, mut tx) = (NodeRx(&port), NodeTx(&port));
                let mut timer = TokioClock::new();
                // The bus never fails: the driver only ends when the task is aborted.
                let on = |e| shared.with(|n| on_event(n, e));
                let _ = driver::run(&*shared, &mut rx, &mut tx, &mut timer, &*wake, on).await;
            })
        };
        SimNode { shared, wake, task }
    }
}

/// The node's cell: a `std` mutex (the driver holds it only while the node computes, never across an await).
struct MutexShared<N>(std::sync::Mutex<N>);

impl<N> MutexShared<N> {
    fn new(node: N) -> Self {
        MutexShared(std::sync::Mutex::new(node))
    }
    fn with<R>(&self, f: impl FnOnce(&mut N) -> R) -> R {
        f(&mut self.0.lock().unwrap_or_else(|p| p.into_inner()))
    }
}

impl<N> Shared<N> for MutexShared<N> {
    fn lock<R>(&self, f: impl FnOnce(&mut N) -> R) -> R {
        self.with(f)
    }
}

/// The driver's wake-up on a tokio `Notify`.
struct NotifyWake(tokio::sync::Notify);

impl NotifyWake {
    fn new() -> Self {
        NotifyWake(tokio::sync::Notify::new())
    }
    fn signal(&self) {
        self.0.notify_one();
    }
}

impl Wake for NotifyWake {
    fn wait(&self) -> impl Future<Output = ()> {
        self.0.notified()
    }
}

/// A node running on a [`SimBus`]; dropping it removes the node from the bus.
pub struct SimNode<N> {
    shared: Arc<MutexShared<N>>,
    wake: Arc<NotifyWake>,
    task: JoinHandle<()>,
}

impl<N> SimNode<N> {
    /// Runs `f` on the node (to look at or change its state while it runs), then wakes its driver so that
    /// what `f` changed (an error raised, a TPDO triggered) goes out now.
    ///
    /// ```
    /// # use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
    /// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    /// # rt.block_on(async {
    /// # let bus = canopen_master::sim::SimBus::new();
    /// # let node: Node<NoApplication> = Node::new(NodeId::new(3).unwrap(), NodeConfig::DEFAULT, NoApplication);
    /// let sim = bus.spawn_node(node);
    /// let state = sim.with(|n| n.state());
    /// # });
    /// ```
    pub fn with<R>(&self, f: impl FnOnce(&mut N) -> R) -> R {
        let r = self.shared.with(f);
        self.wake.signal();
        r
    }
}

impl<N> Drop for SimNode<N> {
    fn drop(&mut self) {
        self.task.abort();
    }
}

/// One port of a [`SimBus`].
pub struct SimPort {
    id: usize,
    tx: broadcast::Sender<(usize, CanFrame)>,
    rx: Mutex<broadcast::Receiver<(usize, CanFrame)>>,
}

impl SimPort {
    fn send_now(&self, frame: &CanFrame) {
        // No receiver at all is a bus with nobody else on it: the frame is lost, as on a real bus.
        let _ = self.tx.send((self.id, *frame));
    }

    async fn next(rx: &mut broadcast::Receiver<(usize, CanFrame)>, me: usize) -> io::Result<CanFrame> {
        loop {
            match rx.recv().await {
                Ok((from, f)) if from != me => return Ok(f),
                Ok(_) | Err(broadcast::error::RecvError::Lagged(_)) => {}
                Err(broadcast::error::RecvError::Closed) => {
                    return Err(io::Error::new(io::ErrorKind::BrokenPipe, "simulated bus closed"))
                }
            }
        }
    }
}

impl CanIo for SimPort {
    fn send<'a>(&'a self, frame: &'a CanFrame) -> IoFuture<'a, ()> {
        self.send_now(frame);
        Box::pin(async { Ok(()) })
    }

    fn recv(&self) -> IoFuture<'_, CanFrame> {
        Box::pin(async move { SimPort::next(&mut *self.rx.lock().await, self.id).await })
    }
}

struct NodeRx<'a>(&'a SimPort);
struct NodeTx<'a>(&'a SimPort);

impl CanRx for NodeRx<'_> {
    type Error = io::Error;
    async fn receive(&mut self) -> io::Result<CanFrame> {
        let mut rx = self.0.rx.lock().await;
        SimPort::next(&mut rx, self.0.id).await
    }
}

impl CanTx for NodeTx<'_> {
    type Error = io::Error;
    async fn transmit(&mut self, frame: &CanFrame) -> io::Result<()> {
        self.0.send_now(frame);
        Ok(())
    }
}

/// The core's clock on tokio time (paused in simulated-time tests): microseconds since it was made.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TokioClock {
    epoch: tokio::time::Instant,
}

impl TokioClock {
    pub(crate) fn new() -> Self {
        TokioClock { epoch: tokio::time::Instant::now() }
    }

    pub(crate) fn now(&self) -> Instant {
        Instant::from_micros(self.epoch.elapsed().as_micros() as u64)
    }

    pub(crate) fn to_tokio(self, t: Instant) -> tokio::time::Instant {
        self.epoch + std::time::Duration::from_micros(t.as_micros())
    }
}

impl Timer for TokioClock {
    fn now(&self) -> Instant {
        TokioClock::now(self)
    }

    fn sleep_until(&mut self, deadline: Instant) -> impl Future<Output = ()> {
        tokio::time::sleep_until(self.to_tokio(deadline))
    }
}
