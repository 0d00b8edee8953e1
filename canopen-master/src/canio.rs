//! What the master sends and receives through: [`CanIo`], implemented by [`SocketCan`] (one SocketCAN
//! socket on tokio) and by the in-memory [`SimBus`](crate::sim::SimBus) of the tests.

use std::future::Future;
use std::io;
use std::pin::Pin;
#[cfg(target_os = "linux")]
use std::sync::atomic::{AtomicBool, Ordering};
#[cfg(target_os = "linux")]
use std::sync::{Arc, Mutex, RwLock};

use canopen_core::CanFrame;
#[cfg(target_os = "linux")]
use canopen_socketcan::{AdapterEvent, BatchReceiver, Observed, TokioBus};
#[cfg(target_os = "linux")]
use tokio::sync::{broadcast, Notify};

/// How often a closed SocketCAN interface is polled to reopen it (canopen-socketcan's runners poll as often).
#[cfg(target_os = "linux")]
pub(crate) use canopen_socketcan::REOPEN_POLL;
/// The same pause off Linux, where nothing reopens (the abort after an outage waits it).
#[cfg(not(target_os = "linux"))]
pub(crate) const REOPEN_POLL: std::time::Duration = std::time::Duration::from_millis(100);
/// Frames taken per receive call.
#[cfg(target_os = "linux")]
pub(crate) use canopen_socketcan::BATCH;
/// Frames taken per receive call (what canopen-socketcan's `recvmmsg` takes on Linux).
#[cfg(not(target_os = "linux"))]
pub(crate) const BATCH: usize = 64;

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

    /// After a receive error: waits until the socket can be used again and returns `Ok(true)`, or returns
    /// `Ok(false)` when it never can (the master then stops: [`Error::Closed`](crate::Error::Closed)). The
    /// default never reopens; [`SocketCan`] waits for an interface that went down to come back up and
    /// opens a fresh socket on it.
    ///
    /// ```
    /// use canopen_master::{CanIo, sim::SimBus};
    /// # let rt = tokio::runtime::Builder::new_current_thread().build().unwrap();
    /// # rt.block_on(async {
    /// assert!(!SimBus::new().port().reopen().await.unwrap());
    /// # });
    /// ```
    fn reopen(&self) -> IoFuture<'_, bool> {
        Box::pin(async { Ok(false) })
    }
}

/// The master's SocketCAN socket: a [`TokioBus`] of `canopen-socketcan` (nonblocking `AsyncFd`, batched
/// `recvmmsg`/`sendmmsg`, `ENOBUFS` back-off, error frames decoded), whose adapter events (bus-off, error
/// passive, a dropped frame, the interface going down and coming back) go to [`SocketCan::adapter_events`].
///
/// When the interface goes down (or away), the receive error is reported as
/// [`AdapterEvent::InterfaceDown`] and [`CanIo::reopen`] waits until it is up again (polled every
/// [`REOPEN_POLL`](canopen_socketcan::REOPEN_POLL)), opens a fresh socket (the interface index may have
/// changed) and reports [`AdapterEvent::Reopened`]: the master goes on without being made anew.
///
/// ```no_run
/// # async fn demo() -> std::io::Result<()> {
/// let io = canopen_master::SocketCan::open("vcan0")?;
/// let mut events = io.adapter_events();
/// let master = canopen_master::Master::new(io);
/// # Ok(()) }
/// ```
#[cfg(target_os = "linux")]
pub struct SocketCan {
    iface: String,
    /// The socket; replaced by [`CanIo::reopen`] (senders take a clone of the `Arc` for one send).
    bus: RwLock<Arc<TokioBus>>,
    adapter: broadcast::Sender<AdapterEvent>,
    /// The `recvmmsg` buffers of [`CanIo::recv_many`] (only the receive task takes them: never contended).
    buffers: tokio::sync::Mutex<BatchReceiver>,
    /// The interface went down (seen by a receive or a send) and the socket was not reopened yet.
    down: AtomicBool,
    /// Why, for the receive task's error.
    down_error: Mutex<String>,
    /// Wakes the receive task when a send saw the interface go down: the socket's pending error
    /// (`ENETDOWN`) is reported to whichever call comes first, so the receive side may never see it.
    down_seen: Notify,
}

#[cfg(target_os = "linux")]
impl SocketCan {
    /// Opens `iface` (inside a tokio runtime) with a receive buffer of
    /// [`RECEIVE_BUFFER`](canopen_socketcan::RECEIVE_BUFFER) where the system allows it (a node's block
    /// upload sends 127 segments at once). The error says how to create a virtual interface when it is
    /// missing.
    pub fn open(iface: &str) -> io::Result<Self> {
        Ok(SocketCan {
            iface: iface.to_owned(),
            bus: RwLock::new(Arc::new(Self::open_bus(iface)?)),
            adapter: broadcast::channel(64).0,
            buffers: tokio::sync::Mutex::new(BatchReceiver::new()),
            down: AtomicBool::new(false),
            down_error: Mutex::new(String::new()),
            down_seen: Notify::new(),
        })
    }

    fn open_bus(iface: &str) -> io::Result<TokioBus> {
        let bus = TokioBus::open(iface)?;
        // A smaller buffer still works (a lost segment is repeated by the block protocol).
        let _ = bus.grow_receive_buffer(canopen_socketcan::RECEIVE_BUFFER);
        Ok(bus)
    }

    /// The socket now.
    fn bus(&self) -> Arc<TokioBus> {
        self.bus.read().unwrap_or_else(|p| p.into_inner()).clone()
    }

    /// What the socket saw below CANopen (error frames, controller states, a full send buffer, the
    /// interface going down and the socket reopened).
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

    /// The interface went down (`e`, from a receive or a send): reported once per outage as
    /// [`AdapterEvent::InterfaceDown`], and the receive task is woken to cut off the transfers waiting.
    fn went_down(&self, e: &io::Error) {
        if !self.down.swap(true, Ordering::SeqCst) {
            let error = e.to_string();
            *self.down_error.lock().unwrap_or_else(|p| p.into_inner()) = error.clone();
            self.report(AdapterEvent::InterfaceDown { iface: self.iface.clone(), error });
            self.down_seen.notify_one();
        }
    }

    /// A send's result, noting an interface that went down.
    fn sent(&self, r: io::Result<()>) -> io::Result<()> {
        if let Err(e) = &r {
            if canopen_socketcan::is_interface_down(e) {
                self.went_down(e);
            }
        }
        r
    }

    fn report(&self, e: AdapterEvent) {
        // Nobody listening is fine.
        let _ = self.adapter.send(e);
    }

    fn observe(&self) -> impl Fn(Observed<'_>) + Sync + '_ {
        |o| {
            if let Observed::Adapter(e) = o {
                self.report(e.clone());
            }
        }
    }
}

#[cfg(target_os = "linux")]
impl CanIo for SocketCan {
    fn send<'a>(&'a self, frame: &'a CanFrame) -> IoFuture<'a, ()> {
        Box::pin(async move { self.sent(self.bus().send(frame, &self.observe()).await) })
    }

    fn recv(&self) -> IoFuture<'_, CanFrame> {
        Box::pin(async move { self.bus().recv(&self.observe()).await })
    }

    fn send_many<'a>(&'a self, frames: &'a [CanFrame]) -> IoFuture<'a, ()> {
        Box::pin(async move { self.sent(self.bus().send_many(frames, &self.observe()).await) })
    }

    fn recv_many<'a>(&'a self, out: &'a mut Vec<CanFrame>) -> IoFuture<'a, usize> {
        Box::pin(async move {
            let mut buffers = self.buffers.lock().await;
            let (bus, observe) = (self.bus(), self.observe());
            // `None`: a send saw the interface go down.
            let result = loop {
                tokio::select! {
                    r = bus.recv_many(&mut buffers, out, &observe) => break r.map_err(Some),
                    // A wake-up left from an outage already reopened is stale: go on receiving.
                    _ = self.down_seen.notified() => if self.down.load(Ordering::SeqCst) {
                        break Err(None);
                    },
                }
            };
            match result {
                Ok(n) => Ok(n),
                Err(Some(e)) if !canopen_socketcan::is_interface_down(&e) => Err(e),
                Err(e) => {
                    if let Some(e) = &e {
                        self.went_down(e);
                    }
                    let why = self.down_error.lock().unwrap_or_else(|p| p.into_inner()).clone();
                    Err(io::Error::new(
                        io::ErrorKind::NotConnected,
                        format!("interface {} went down ({why})", self.iface),
                    ))
                }
            }
        })
    }

    fn reopen(&self) -> IoFuture<'_, bool> {
        Box::pin(async move {
            if !self.down.load(Ordering::SeqCst) {
                return Ok(false);
            }
            let bus = loop {
                if canopen_socketcan::interface_is_up(&self.iface) {
                    if let Ok(b) = Self::open_bus(&self.iface) {
                        break b;
                    }
                }
                tokio::time::sleep(canopen_socketcan::REOPEN_POLL).await;
            };
            *self.bus.write().unwrap_or_else(|p| p.into_inner()) = Arc::new(bus);
            self.down.store(false, Ordering::SeqCst);
            self.report(AdapterEvent::Reopened { iface: self.iface.clone() });
            Ok(true)
        })
    }
}
