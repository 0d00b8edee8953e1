//! The bus task: the one socket a [`Master`] and its clones share, and the receive task that reads it and
//! routes each frame by COB-ID to whoever waits for it (an SDO transfer, the LSS handle, the heartbeat, EMCY
//! and all-frames streams). It also takes the socket's failures: the transfers in flight are cut off at once
//! and the task waits for the socket to come back ([`CanIo::reopen`]).

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use canopen_core::wire::emcy::Emergency;
use canopen_core::CanFrame;
use tokio::sync::{broadcast, mpsc, watch};
use tokio::task::JoinHandle;

use crate::sim::TokioClock;
#[cfg(target_os = "linux")]
use crate::SocketCan;
use crate::{CanIo, EmcyEvent, Error, Heartbeat, Master, DEFAULT_SDO_TIMEOUT};

/// The frame routing table shared by the receive task and the transfers.
pub(crate) struct Router {
    /// Transfers waiting for a COB-ID (SDO responses, LSS 7E4h).
    routes: Mutex<HashMap<u16, mpsc::UnboundedSender<CanFrame>>>,
    /// One lock per COB-ID a transfer receives on: transfers to the same server take turns.
    locks: Mutex<HashMap<u16, Arc<tokio::sync::Mutex<()>>>>,
    pub(crate) heartbeat: broadcast::Sender<Heartbeat>,
    pub(crate) emcy: broadcast::Sender<EmcyEvent>,
    pub(crate) frames: broadcast::Sender<CanFrame>,
    /// Why the receive task stopped, once it has.
    closed: Mutex<Option<String>>,
    /// Why the transfers waiting for frames were last cut off (the socket failed and was reopened).
    interrupted: Mutex<Option<String>>,
    /// Whether the socket can be used: transfers cut off by an outage wait for it to abort their server.
    pub(crate) link: watch::Sender<Link>,
}

/// The state of the master's socket, as its receive task sees it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Link {
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
    pub(crate) fn closed_error(&self) -> Error {
        if let Some(why) = lock(&self.closed).clone() {
            return Error::Closed(why);
        }
        match lock(&self.interrupted).clone() {
            Some(why) => Error::Interrupted(why),
            None => Error::Closed("the master was dropped".into()),
        }
    }

    pub(crate) fn turn(&self, cob: u16) -> Arc<tokio::sync::Mutex<()>> {
        lock(&self.locks).entry(cob).or_default().clone()
    }

    /// Routes frames with `cob` to the returned receiver until it is dropped. The caller holds
    /// [`Router::turn`]`(cob)`, so no other route for `cob` exists.
    pub(crate) fn route(self: &Arc<Self>, cob: u16) -> Result<Route, Error> {
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

pub(crate) struct Inner {
    pub(crate) io: Arc<dyn CanIo>,
    pub(crate) router: Arc<Router>,
    pub(crate) clock: TokioClock,
    task: JoinHandle<()>,
}

impl Drop for Inner {
    fn drop(&mut self) {
        self.task.abort();
    }
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
                let mut batch = Vec::with_capacity(crate::canio::BATCH);
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
    #[cfg(target_os = "linux")]
    pub fn open(iface: &str) -> Result<Self, Error> {
        Ok(Master::new(SocketCan::open(iface)?))
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
}

pub(crate) async fn sleep_until(deadline: Option<tokio::time::Instant>) {
    match deadline {
        Some(d) => tokio::time::sleep_until(d).await,
        None => std::future::pending().await,
    }
}
