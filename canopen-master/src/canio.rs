//! What the master sends and receives through: [`CanIo`], implemented by [`SocketCan`] (one SocketCAN
//! socket on tokio) and by the in-memory [`SimBus`](crate::sim::SimBus) of the tests.

use std::future::Future;
use std::io;
use std::pin::Pin;

use canopen_core::CanFrame;
use canopen_socketcan::{AdapterEvent, BatchReceiver, Observed, TokioBus};
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

    /// Sends `frames` in order (a block download's sub-block at once). The default sends them one by one
    /// with [`send`](Self::send); [`SocketCan`] sends up to
    /// [`BATCH`](canopen_socketcan::BATCH) per system call (`sendmmsg`).
    ///
    /// ```
    /// use canopen_master::{CanIo, sim::SimBus};
    /// # let rt = tokio::runtime::Builder::new_current_thread().build().unwrap();
    /// # rt.block_on(async {
    /// let (bus, frames) = (SimBus::new(), [canopen_core::CanFrame::new(0x80, &[]).unwrap(); 3]);
    /// bus.port().send_many(&frames).await.unwrap();
    /// # });
    /// ```
    fn send_many<'a>(&'a self, frames: &'a [CanFrame]) -> IoFuture<'a, ()> {
        Box::pin(async move {
            for f in frames {
                self.send(f).await?;
            }
            Ok(())
        })
    }

    /// Waits for at least one received 11-bit frame and appends it, with every other one already queued, to
    /// `out`; returns how many it appended. Only the master's receive task calls it. The default takes one
    /// frame with [`recv`](Self::recv); [`SocketCan`] takes up to [`BATCH`](canopen_socketcan::BATCH) per
    /// system call (`recvmmsg`), so a burst of frames costs one wake-up.
    ///
    /// ```
    /// use canopen_master::{CanIo, sim::SimBus};
    /// # let rt = tokio::runtime::Builder::new_current_thread().build().unwrap();
    /// # rt.block_on(async {
    /// let bus = SimBus::new();
    /// let (a, b) = (bus.port(), bus.port());
    /// a.send(&canopen_core::CanFrame::new(0x80, &[]).unwrap()).await.unwrap();
    /// let mut out = Vec::new();
    /// assert_eq!(b.recv_many(&mut out).await.unwrap(), 1);
    /// # });
    /// ```
    fn recv_many<'a>(&'a self, out: &'a mut Vec<CanFrame>) -> IoFuture<'a, usize> {
        Box::pin(async move {
            out.push(self.recv().await?);
            Ok(1)
        })
    }
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
    /// The `recvmmsg` buffers of [`CanIo::recv_many`] (only the receive task takes them: never contended).
    buffers: tokio::sync::Mutex<BatchReceiver>,
}

impl SocketCan {
    /// Opens `iface` (inside a tokio runtime) with a receive buffer of
    /// [`RECEIVE_BUFFER`](canopen_socketcan::RECEIVE_BUFFER) where the system allows it (a node's block
    /// upload sends 127 segments at once). The error says how to create a virtual interface when it is
    /// missing.
    pub fn open(iface: &str) -> io::Result<Self> {
        let bus = TokioBus::open(iface)?;
        // A smaller buffer still works (a lost segment is repeated by the block protocol).
        let _ = bus.grow_receive_buffer(canopen_socketcan::RECEIVE_BUFFER);
        Ok(SocketCan { bus, adapter: broadcast::channel(64).0, buffers: tokio::sync::Mutex::new(BatchReceiver::new()) })
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

    fn send_many<'a>(&'a self, frames: &'a [CanFrame]) -> IoFuture<'a, ()> {
        Box::pin(async move { self.bus.send_many(frames, &self.observe()).await })
    }

    fn recv_many<'a>(&'a self, out: &'a mut Vec<CanFrame>) -> IoFuture<'a, usize> {
        Box::pin(async move {
            let mut buffers = self.buffers.lock().await;
            self.bus.recv_many(&mut buffers, out, &self.observe()).await
        })
    }
}
