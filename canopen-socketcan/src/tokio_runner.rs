//! The tokio adapter: the node on a tokio `AsyncFd` CAN socket ([`run_tokio`]); the halves of
//! [`TokioBus`] also plug into the core's executor-agnostic [`driver`](canopen_core::driver).
//!
//! - [`TokioBus`] owns the socket; [`TokioBus::split`] gives a receive half ([`CanRx`], cancel-safe: a frame
//!   is only taken from the socket when the read completes) and a transmit half ([`CanTx`], waits and
//!   retries on `ENOBUFS`).
//! - [`TimerFd`] is the timer [`run_tokio`] sleeps on: a `timerfd` in tokio's reactor, so the runtime needs
//!   no time driver; [`TokioTimer`] is the node's clock on `tokio::time` for the core's driver.
//! - [`MutexShared`](crate::MutexShared) holds the node (a `std::sync::Mutex`: the driver never holds it across an `.await`)
//!   and [`NotifyWake`] (a `tokio::sync::Notify`) lets another task wake the driver after it changed the
//!   node.
//! - [`run_tokio`] runs the node in passes (one clock reading, batched socket calls, kernel filters) and,
//!   when the interface goes down, waits for it, reopens the socket and goes on with the same node.
//!
//! ```no_run
//! use std::sync::Arc;
//! use canopen_core::{profile::NodeConfig, node::{NoApplication, Node}, NodeId};
//! use canopen_socketcan::{run_tokio, MutexShared, NotifyWake};
//! # async fn demo() -> std::io::Result<()> {
//! let node: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
//! let shared = Arc::new(MutexShared::new(node));
//! let wake = Arc::new(NotifyWake::new());
//! // Another task changes the node, then wakes the driver:
//! let (s, w) = (shared.clone(), wake.clone());
//! tokio::spawn(async move {
//!     s.with(|n| n.enter_state(canopen_core::NmtState::Operational)); // local control (NMT-16)
//!     w.signal();
//! });
//! run_tokio(&*shared, "vcan0", &*wake, &|o| println!("{o:?}")).await?;
//! # Ok(()) }
//! ```

use std::convert::Infallible;
use std::future::Future;
use std::io;

use canopen_core::driver::{CanRx, CanTx, Shared, Timer, Wake};
use canopen_core::node::SansIo;
use canopen_core::{CanFrame, Instant};
use std::os::fd::AsRawFd;

use socketcan::{Socket, SocketOptions};
use tokio::io::unix::AsyncFd;
use tokio::io::Interest;
use tokio::sync::Notify;

use crate::pass::{count, kernel_filters, Counter, Pass, ReceiveFilters};
use crate::{classify, map_received, open_error, AdapterEvent, Clock, ErrorClass, Observed};

/// The observer the tokio runner reports to (shared by the receive half, the transmit half and the driver's
/// event callback).
pub type Observer<'a> = &'a (dyn Fn(Observed<'_>) + Sync);

/// A tokio CAN socket on one interface.
pub struct TokioBus {
    socket: AsyncFd<socketcan::CanSocket>,
    iface: String,
}

impl TokioBus {
    /// Opens `iface` and accepts every error frame class. Must be called inside a tokio runtime. The error
    /// says how to create a virtual interface when it is missing.
    pub fn open(iface: &str) -> io::Result<Self> {
        let socket = socketcan::CanSocket::open(iface).map_err(|e| open_error(iface, e))?;
        socket.set_error_filter_accept_all()?;
        socket.set_nonblocking(true)?;
        Ok(TokioBus { socket: crate::batch::register(socket)?, iface: iface.to_owned() })
    }

    /// The interface name.
    pub fn iface(&self) -> &str {
        &self.iface
    }

    /// Receive only frames matching one of `(id, mask)` (error frames still come through).
    pub fn set_filters(&self, filters: &[(u32, u32)]) -> io::Result<()> {
        crate::blocking::apply_filters(self.socket.get_ref(), filters)
    }

    /// The receive and transmit halves, both reporting to `observe`.
    pub fn split<'a>(&'a self, observe: Observer<'a>) -> (TokioRx<'a>, TokioTx<'a>) {
        (TokioRx { bus: self, observe }, TokioTx { bus: self, observe })
    }

    /// Sends one frame, waiting for room: `ENOBUFS` is retried every
    /// [`ENOBUFS_BACKOFF`](crate::ENOBUFS_BACKOFF) (reported once as [`AdapterEvent::TxBufferFull`]); after
    /// [`TX_STALL_LIMIT`](crate::TX_STALL_LIMIT) the frame is dropped and reported.
    ///
    /// ```no_run
    /// # async fn demo() -> std::io::Result<()> {
    /// let bus = canopen_socketcan::TokioBus::open("vcan0")?;
    /// bus.send(&canopen_core::CanFrame::new(0x80, &[]).unwrap(), &|_| {}).await?; // a SYNC
    /// # Ok(()) }
    /// ```
    pub async fn send(&self, frame: &CanFrame, observe: Observer<'_>) -> io::Result<()> {
        self.send_many(std::slice::from_ref(frame), observe).await
    }

    /// Sends `frames` in order, one `sendmmsg` per [`BATCH`](crate::BATCH) frames (an SDO block
    /// download's sub-block of 127 segments in two calls instead of 127), waiting for room as
    /// [`send`](Self::send) does: a full queue (`ENOBUFS`, `EAGAIN`) is retried every
    /// [`ENOBUFS_BACKOFF`](crate::ENOBUFS_BACKOFF) from the first unsent frame on (reported once per stall as
    /// [`AdapterEvent::TxBufferFull`]); a frame still not sent after [`TX_STALL_LIMIT`](crate::TX_STALL_LIMIT)
    /// is dropped and reported ([`AdapterEvent::TxDropped`]). Nothing is reordered. An interface that went
    /// down is an error (`ENETDOWN`); the frames before it went out.
    ///
    /// ```no_run
    /// # async fn demo() -> std::io::Result<()> {
    /// use canopen_core::CanFrame;
    /// let bus = canopen_socketcan::TokioBus::open("vcan0")?;
    /// let frames = [CanFrame::new(0x80, &[]).unwrap(), CanFrame::new(0x000, &[0x01, 0x00]).unwrap()];
    /// bus.send_many(&frames, &|_| {}).await?;
    /// # Ok(()) }
    /// ```
    pub async fn send_many(&self, frames: &[CanFrame], observe: Observer<'_>) -> io::Result<()> {
        let fd = self.socket.as_raw_fd();
        let mut next = 0;
        let mut stalled: Option<std::time::Instant> = None;
        let mut backoff: Option<TimerFd> = None;
        while next < frames.len() {
            let rest = &frames[next..];
            // The socket is registered for readability only (see `batch::register`): a full queue
            // (`ENOBUFS`, or `EAGAIN` from the socket's own buffer) is retried after a back-off.
            match crate::batch::send_frames(fd, rest.len(), |i| crate::pass::raw_frame(&rest[i])) {
                Ok(n) => {
                    next += n;
                    stalled = None;
                }
                Err(e) => match classify(&e) {
                    ErrorClass::NoBufs | ErrorClass::Timeout => {
                        let since = *stalled.get_or_insert_with(|| {
                            observe(Observed::Adapter(&AdapterEvent::TxBufferFull));
                            std::time::Instant::now()
                        });
                        if since.elapsed() >= crate::TX_STALL_LIMIT {
                            observe(Observed::Adapter(&AdapterEvent::TxDropped(frames[next])));
                            next += 1;
                            stalled = None;
                            continue;
                        }
                        let timer = match &mut backoff {
                            Some(t) => t,
                            None => backoff.insert(TimerFd::new(Clock::new())?),
                        };
                        timer.sleep(crate::ENOBUFS_BACKOFF).await?;
                    }
                    ErrorClass::Interrupted => {}
                    ErrorClass::Down | ErrorClass::Fatal => return Err(e),
                },
            }
        }
        Ok(())
    }

    /// Waits for the next 11-bit frame; error frames are reported to `observe` and skipped, 29-bit frames
    /// are skipped. Cancel-safe.
    ///
    /// ```no_run
    /// # async fn demo() -> std::io::Result<()> {
    /// let bus = canopen_socketcan::TokioBus::open("vcan0")?;
    /// let frame = bus.recv(&|_| {}).await?;
    /// # Ok(()) }
    /// ```
    pub async fn recv(&self, observe: Observer<'_>) -> io::Result<CanFrame> {
        loop {
            let read = self.socket.async_io(Interest::READABLE | Interest::ERROR, |s| s.read_frame()).await;
            match read {
                Ok(f) => match map_received(&f) {
                    Some(Ok(frame)) => return Ok(frame),
                    Some(Err(event)) => observe(Observed::Adapter(&event)),
                    None => {}
                },
                Err(e) if matches!(classify(&e), ErrorClass::Interrupted | ErrorClass::Timeout) => {}
                Err(e) => return Err(e),
            }
        }
    }

    /// Waits until frames are queued, then appends every queued 11-bit frame (up to
    /// [`BATCH`](crate::BATCH)) to `out` with one `recvmmsg` into `buffers`; returns how many it appended
    /// (at least one). Error frames are reported to `observe` and skipped, 29-bit frames are skipped; the
    /// socket's own error (the interface went down: `ENETDOWN`) ends the wait as an error. So a
    /// burst of frames (an SDO block upload's sub-block) costs one wake-up and one system call per
    /// [`BATCH`](crate::BATCH) frames instead of one each. Cancel-safe: frames are only taken from the
    /// socket in the call that returns them.
    ///
    /// ```no_run
    /// # async fn demo() -> std::io::Result<()> {
    /// let bus = canopen_socketcan::TokioBus::open("vcan0")?;
    /// let (mut buffers, mut frames) = (canopen_socketcan::BatchReceiver::new(), Vec::new());
    /// let n = bus.recv_many(&mut buffers, &mut frames, &|_| {}).await?;
    /// assert_eq!(frames.len(), n);
    /// # Ok(()) }
    /// ```
    pub async fn recv_many(
        &self,
        buffers: &mut crate::BatchReceiver,
        out: &mut Vec<CanFrame>,
        observe: Observer<'_>,
    ) -> io::Result<usize> {
        let before = out.len();
        loop {
            // ERROR too: an interface going down sets the socket's error (`ENETDOWN`) and wakes it with
            // EPOLLERR alone, which a wait for readability never sees.
            let mut guard = self.socket.ready(Interest::READABLE | Interest::ERROR).await?;
            let taken = buffers.recv_frames(self.socket.as_raw_fd(), |raw| {
                for r in raw {
                    match map_received(&socketcan::CanFrame::from(*r)) {
                        Some(Ok(frame)) => out.push(frame),
                        Some(Err(event)) => observe(Observed::Adapter(&event)),
                        None => {}
                    }
                }
            });
            match taken {
                Ok(n) => {
                    if n < crate::BATCH {
                        // The queue was empty at the end of this call: wait for the next edge.
                        guard.clear_ready();
                    }
                    if out.len() > before {
                        return Ok(out.len() - before);
                    }
                }
                Err(e) => {
                    guard.clear_ready();
                    if !matches!(classify(&e), ErrorClass::Interrupted | ErrorClass::Timeout) {
                        return Err(e);
                    }
                }
            }
        }
    }

    /// Sets the socket's receive buffer to at least `bytes` (`SO_RCVBUFFORCE` when privileged, else
    /// `SO_RCVBUF`, capped by `net.core.rmem_max`), so that a burst (a whole SDO block sub-block) is not
    /// dropped while the task is busy. Returns the size the kernel reports.
    ///
    /// ```no_run
    /// # async fn demo() -> std::io::Result<()> {
    /// let bus = canopen_socketcan::TokioBus::open("vcan0")?;
    /// bus.grow_receive_buffer(canopen_socketcan::RECEIVE_BUFFER)?;
    /// # Ok(()) }
    /// ```
    pub fn grow_receive_buffer(&self, bytes: usize) -> io::Result<usize> {
        crate::batch::grow_receive_buffer(self.socket.as_raw_fd(), bytes)
    }
}

/// The receive half of a [`TokioBus`]: reports every frame it hands to the node as [`Observed::Received`].
pub struct TokioRx<'a> {
    bus: &'a TokioBus,
    observe: Observer<'a>,
}

impl CanRx for TokioRx<'_> {
    type Error = io::Error;
    async fn receive(&mut self) -> io::Result<CanFrame> {
        let frame = self.bus.recv(self.observe).await?;
        (self.observe)(Observed::Received(&frame));
        Ok(frame)
    }
}

/// The transmit half of a [`TokioBus`]: reports every frame it sent as [`Observed::Sent`].
pub struct TokioTx<'a> {
    bus: &'a TokioBus,
    observe: Observer<'a>,
}

impl CanTx for TokioTx<'_> {
    type Error = io::Error;
    async fn transmit(&mut self, frame: &CanFrame) -> io::Result<()> {
        self.bus.send(frame, self.observe).await?;
        (self.observe)(Observed::Sent(frame));
        Ok(())
    }
}

/// The node's clock on `tokio::time` (so a paused tokio clock in tests pauses the node too), for the core's
/// [`driver`](canopen_core::driver). It needs the runtime's time driver (`enable_time`), which reads the
/// clock at every wake-up of the runtime; [`run_tokio`] uses a [`TimerFd`] instead.
///
/// ```
/// let t = canopen_socketcan::TokioTimer::new(canopen_socketcan::Clock::new());
/// use canopen_core::driver::Timer;
/// assert!(t.now() <= t.now());
/// ```
#[derive(Debug, Clone, Copy)]
pub struct TokioTimer {
    clock: Clock,
}

impl TokioTimer {
    /// A timer on `clock`.
    pub fn new(clock: Clock) -> Self {
        TokioTimer { clock }
    }
}

impl Timer for TokioTimer {
    fn now(&self) -> Instant {
        self.clock.now()
    }
    fn sleep_until(&mut self, deadline: Instant) -> impl Future<Output = ()> {
        tokio::time::sleep_until(tokio::time::Instant::from_std(self.clock.to_std(deadline)))
    }
}

/// A one-shot timer on a Linux `timerfd` (`CLOCK_MONOTONIC`) registered with tokio's reactor, on the node's
/// [`Clock`]: [`run_tokio`] sleeps on it, so a runtime built with `enable_io()` alone (no time driver)
/// runs the node. tokio's time driver reads the clock on every wake-up of the runtime (to fire its
/// timers); a `timerfd` is armed only when a deadline changes and costs nothing otherwise. Needs a tokio
/// runtime with I/O enabled.
///
/// ```no_run
/// use canopen_socketcan::{Clock, TimerFd};
/// # async fn demo() -> std::io::Result<()> {
/// let clock = Clock::new();
/// let mut timer = TimerFd::new(clock)?;
/// timer.sleep(std::time::Duration::from_millis(10)).await?;
/// timer.sleep_until(clock.now() + canopen_core::Duration::from_millis(10)).await?;
/// # Ok(()) }
/// ```
#[derive(Debug)]
pub struct TimerFd {
    fd: AsyncFd<std::os::fd::OwnedFd>,
    clock: Clock,
    /// The deadline the timer is armed for (`None`: disarmed, fired, or a relative sleep).
    armed: Option<Instant>,
}

impl TimerFd {
    /// A disarmed timer on `clock`. Must be called inside a tokio runtime with I/O enabled.
    pub fn new(clock: Clock) -> io::Result<Self> {
        let fd = crate::batch::register(crate::batch::timerfd()?)?;
        Ok(TimerFd { fd, clock, armed: None })
    }

    /// Waits until `deadline` on the node's clock (at once if it passed).
    pub async fn sleep_until(&mut self, deadline: Instant) -> io::Result<()> {
        self.arm(Some(deadline))?;
        self.fired().await
    }

    /// Waits `d` (no clock reading: the timer is armed relative to now).
    pub async fn sleep(&mut self, d: std::time::Duration) -> io::Result<()> {
        crate::batch::set_timerfd(self.fd.as_raw_fd(), crate::batch::Expiry::In(d.as_micros() as u64))?;
        self.armed = None;
        self.fired().await
    }

    /// Arms the timer for `deadline` (`None`: disarms it), unless it is armed for exactly that.
    fn arm(&mut self, deadline: Option<Instant>) -> io::Result<()> {
        if self.armed != deadline {
            let expiry = match deadline {
                Some(d) => crate::batch::Expiry::At(self.clock.to_monotonic_us(d)),
                None => crate::batch::Expiry::Never,
            };
            crate::batch::set_timerfd(self.fd.as_raw_fd(), expiry)?;
            self.armed = deadline;
        }
        Ok(())
    }

    /// Arms the timer for the node's next `deadline` at `now`, keeping an earlier expiry that is still
    /// ahead (also when there is no deadline any more): that one wakes the runner once early, and the pass
    /// then re-arms the timer for the new deadline. A deadline that moves later on every pass (an SDO
    /// time-out restarted by each frame of a block transfer) so costs one `timerfd_settime` per expiry,
    /// not one per pass.
    fn arm_lazily(&mut self, deadline: Option<Instant>, now: Instant) -> io::Result<()> {
        match (self.armed, deadline) {
            (Some(a), Some(d)) if a > now && a <= d => Ok(()),
            (Some(a), None) if a > now => Ok(()),
            _ => self.arm(deadline),
        }
    }

    /// Waits until the timer fires (a disarmed timer never does). Cancel-safe.
    async fn fired(&mut self) -> io::Result<()> {
        let mut guard = self.fd.readable().await?;
        // Not read: the next arming clears the expiry count (timerfd_settime), which saves a system call.
        guard.clear_ready();
        self.armed = None;
        Ok(())
    }
}

/// A wake-up the application signals after it changed the node from another task. A signal given while
/// the driver is busy is kept (one permit) and wakes the next wait.
///
/// ```
/// let w = canopen_socketcan::NotifyWake::new();
/// w.signal();
/// ```
#[derive(Debug, Default)]
pub struct NotifyWake(Notify);

impl NotifyWake {
    /// A wake-up source with no pending signal.
    pub fn new() -> Self {
        NotifyWake(Notify::new())
    }

    /// Wakes the driver.
    pub fn signal(&self) {
        self.0.notify_one();
    }
}

impl Wake for NotifyWake {
    fn wait(&self) -> impl Future<Output = ()> {
        self.0.notified()
    }
}

/// Runs the node in `shared` on `iface` with tokio until a socket error that is not an interface going
/// down (that is returned). Every frame, node event and [`AdapterEvent`] goes to `observe`. Stop it by
/// dropping the future (`tokio::select!` with a [`TimerFd`] sleep or a signal, `tokio::time::timeout`).
///
/// Each pass reads the clock once, hands the node every frame received since the last pass and the time,
/// sends what it produced (one `sendmmsg` per [`BATCH`](crate::BATCH) frames), installs the node's receive
/// set as kernel filters when it changed (`CAN_RAW_FILTER`: frames for other nodes never wake the task),
/// then waits for the first of: the socket readable (every queued frame is taken, one `recvmmsg` per
/// batch), the node's next deadline (a [`TimerFd`], armed only when the deadline moves earlier; none when
/// there is no deadline), a [`Wake`] signal.
///
/// **Runtime**: any tokio runtime with I/O enabled; the runner uses no `tokio::time`, so
/// `Builder::new_current_thread().enable_io()` is enough (the example node's runtime). What the runtime
/// itself costs per wake-up is the runtime's: measured with strace on tokio 1.54 in a VM without vDSO
/// (where every clock read is a system call), a current-thread runtime reads the clock twice per wake-up
/// for its busy-time metrics (`MetricsBatch::{start,end}_processing_scheduled_tasks`, not configurable),
/// and a runtime with the time driver (`enable_all`, `enable_time`) once more, to fire its timers. On a
/// kernel with vDSO (most) those reads are not system calls. A served SDO expedited read then costs
/// `epoll_wait`, `recvmmsg`, `sendmmsg` and the runner's one clock read.
pub async fn run_tokio<N: SansIo + ReceiveFilters, S: Shared<N>, W: Wake>(
    shared: &S,
    iface: &str,
    wake: &W,
    observe: Observer<'_>,
) -> io::Result<Infallible> {
    let clock = Clock::new();
    let mut timer = TimerFd::new(clock)?;
    let mut pass = Pass::default();
    let mut bus = TokioBus::open(iface)?;
    loop {
        let _ = bus.grow_receive_buffer(crate::RECEIVE_BUFFER);
        pass.reinstall();
        let e = match run_passes(shared, &bus, &mut pass, &clock, &mut timer, wake, observe).await {
            Ok(never) => match never {},
            Err(e) => e,
        };
        if classify(&e) != ErrorClass::Down {
            return Err(e);
        }
        observe(Observed::Adapter(&AdapterEvent::InterfaceDown { iface: iface.to_owned(), error: e.to_string() }));
        bus = loop {
            if crate::interface_is_up(iface) {
                if let Ok(b) = TokioBus::open(iface) {
                    break b;
                }
            }
            timer.sleep(crate::REOPEN_POLL).await?;
        };
        observe(Observed::Adapter(&AdapterEvent::Reopened { iface: iface.to_owned() }));
    }
}

async fn run_passes<N: SansIo + ReceiveFilters, S: Shared<N>, W: Wake>(
    shared: &S,
    bus: &TokioBus,
    pass: &mut Pass,
    clock: &Clock,
    timer: &mut TimerFd,
    wake: &W,
    observe: Observer<'_>,
) -> io::Result<Infallible> {
    let fd = bus.socket.as_raw_fd();
    let mut obs = |o: Observed<'_>| observe(o);
    loop {
        let now = clock.now(); // the pass's one clock reading
        let (deadline, filters) = pass.run(shared, now, &mut obs);
        if let Some(f) = filters {
            bus.set_filters(&kernel_filters(&f))?;
            count(Counter::FilterUpdates, 1);
            pass.installed(f);
        }
        send_all(bus, pass, clock, timer, &mut obs).await?;
        if deadline.is_some_and(|d| d <= now) {
            crate::blocking::receive_all(fd, pass, &mut obs)?; // due now: no wait
            continue;
        }
        timer.arm_lazily(deadline, now)?;
        let ready = tokio::select! {
            biased;
            // ERROR too: an interface going down wakes the socket with EPOLLERR alone (its `ENETDOWN`),
            // which a wait for readability never sees; the next receive then returns it.
            r = bus.socket.ready(Interest::READABLE | Interest::ERROR) => Some(r?),
            r = timer.fired() => {
                r?;
                None
            }
            _ = wake.wait() => None,
        };
        count(Counter::Wakeups, 1);
        if let Some(mut guard) = ready {
            loop {
                let n = pass.receive(fd, &mut obs)?;
                if n < crate::BATCH {
                    // The queue was empty at the end of this call: wait for the next edge.
                    guard.clear_ready();
                    break;
                }
            }
        }
    }
}

/// Sends `pass.tx` in order, in as few calls as the socket takes; a full queue (`ENOBUFS`, `EAGAIN`) is
/// retried every [`ENOBUFS_BACKOFF`](crate::ENOBUFS_BACKOFF), the first frame dropped and reported after
/// [`TX_STALL_LIMIT`](crate::TX_STALL_LIMIT); nothing is lost or reordered on a partial send.
async fn send_all(
    bus: &TokioBus,
    pass: &mut Pass,
    clock: &Clock,
    timer: &mut TimerFd,
    observe: &mut (dyn FnMut(Observed<'_>) + Send),
) -> io::Result<()> {
    let mut stall = crate::pass::TxStall::default();
    while !pass.tx.is_empty() {
        if crate::pass::send_attempt(bus.socket.as_raw_fd(), &mut pass.tx, &mut stall, || clock.now(), observe)? {
            timer.sleep(crate::ENOBUFS_BACKOFF).await?;
        }
    }
    Ok(())
}
