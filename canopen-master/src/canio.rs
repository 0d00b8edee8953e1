//! What the master sends and receives through: [`CanIo`], implemented by [`SocketCan`] (one SocketCAN
//! socket on tokio) and by the in-memory [`SimBus`](crate::sim::SimBus) of the tests.

use std::future::Future;
use std::io;
use std::pin::Pin;

use canopen_core::CanFrame;
use canopen_socketcan::{AdapterEvent, Observed, TokioBus};
use tokio::sync::broadcast;

/// A boxed, `Send` I/O future (the [`CanIo`] methods return one so that the trait stays object-safe).
pub type IoFuture<'a, T> = Pin<Box<dyn Future<Output = io::Result<T>> + Send + 'a>>;

/// One CAN socket as the master uses it: sends from any task, receives from its receive task.
///
/// ```
/// use canopen_master::{CanIo, sim::SimBus};
/// fn takes_any(_: &dyn CanIo) {}
/// # let rt = tokio::runtime::Builder::new_current_thread().build().unwrap();
/// # rt.block_on(async {
/// takes_any(&SimBus::new().port());
/// # });
/// ```
pub trait CanIo: Send + Sync + 'static {
    /// Sends one frame (waits while the socket's queue is full).
    fn send<'a>(&'a self, frame: &'a CanFrame) -> IoFuture<'a, ()>;
    /// The next received 11-bit frame. Only the master's receive task calls it.
    fn recv(&self) -> IoFuture<'_, CanFrame>;
}

/// The master's SocketCAN socket: a [`TokioBus`] of `canopen-socketcan` (nonblocking `AsyncFd`, `ENOBUFS`
/// back-off, error frames decoded), whose adapter events (bus-off, error passive, a dropped frame) go to
/// [`SocketCan::adapter_events`].
///
/// ```no_run
/// # async fn demo() -> std::io::Result<()> {
/// let io = canopen_master::SocketCan::open("vcan0")?;
/// let mut events = io.adapter_events();
/// let master = canopen_master::Master::new(io);
/// # Ok(()) }
/// ```
pub struct SocketCan {
    bus: TokioBus,
    adapter: broadcast::Sender<AdapterEvent>,
}

impl SocketCan {
    /// Opens `iface` (inside a tokio runtime). The error says how to create a virtual interface when it is
    /// missing.
    pub fn open(iface: &str) -> io::Result<Self> {
        Ok(SocketCan { bus: TokioBus::open(iface)?, adapter: broadcast::channel(64).0 })
    }

    /// What the socket saw below CANopen (error frames, controller states, a full send buffer).
    ///
    /// ```no_run
    /// # async fn demo() -> std::io::Result<()> {
    /// let io = canopen_master::SocketCan::open("vcan0")?;
    /// let mut events = io.adapter_events();
    /// # Ok(()) }
    /// ```
    pub fn adapter_events(&self) -> broadcast::Receiver<AdapterEvent> {
        self.adapter.subscribe()
    }

    fn observe(&self) -> impl Fn(Observed<'_>) + Sync + '_ {
        |o| {
            if let Observed::Adapter(e) = o {
                // Nobody listening is fine.
                let _ = self.adapter.send(e.clone());
            }
        }
    }
}

impl CanIo for SocketCan {
    fn send<'a>(&'a self, frame: &'a CanFrame) -> IoFuture<'a, ()> {
        Box::pin(async move { self.bus.send(frame, &self.observe()).await })
    }

    fn recv(&self) -> IoFuture<'_, CanFrame> {
        Box::pin(async move { self.bus.recv(&self.observe()).await })
    }
}
