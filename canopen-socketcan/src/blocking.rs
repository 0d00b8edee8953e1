//! The blocking adapter: one raw CAN socket, waited on until the node's next deadline.
//!
//! [`run_blocking`] is the whole runner loop. The node lives in a [`Shared`] cell (a
//! [`MutexShared`](crate::MutexShared) when other threads change it, a `RefCell` otherwise). Another thread
//! that changed the node wakes the runner with a [`BusWaker`] ([`BlockingBus::waker`]); a runner whose bus
//! gave out no waker wakes at least every [`APP_POLL`] to send what another thread queued.

use std::io;
use std::time::Duration as StdDuration;

use std::os::fd::{AsRawFd, RawFd};
use std::os::unix::net::UnixDatagram;
use std::sync::Arc;

use canopen_core::driver::Shared;
use canopen_core::node::SansIo;
use canopen_core::{CanFrame, Instant};
use socketcan::{CanFilter, CanSocket, Socket, SocketOptions};

use crate::pass::{count, kernel_filters, Counter, Pass, ReceiveFilters};
use crate::{classify, map_received, open_error, to_socket_frame, AdapterEvent, Clock, ErrorClass, Observed};

/// The longest the blocking runner sleeps without looking at the node (changes made by other threads).
pub const APP_POLL: StdDuration = StdDuration::from_millis(20);

/// What [`BlockingBus::recv_until`] returns.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Rx {
    /// An 11-bit data or remote frame.
    Frame(CanFrame),
    /// The deadline passed.
    Timeout,
    /// The adapter saw something below the node (an error frame).
    Adapter(AdapterEvent),
}

/// A blocking CAN socket bound to one interface, with the node's clock.
///
/// ```no_run
/// use canopen_socketcan::BlockingBus;
/// let bus = BlockingBus::open("vcan0")?;
/// let now = bus.now();
/// # Ok::<(), std::io::Error>(())
/// ```
pub struct BlockingBus {
    socket: CanSocket,
    clock: Clock,
    iface: String,
    filters: Vec<(u32, u32)>,
    /// The runner's end and the [`BusWaker`]s' end of the wake-up socket pair, once taken.
    waker: Option<(UnixDatagram, Arc<UnixDatagram>)>,
}

impl BlockingBus {
    /// Opens `iface` (e.g. `vcan0`) and accepts every error frame class. The error says how to create a
    /// virtual interface when it is missing.
    pub fn open(iface: &str) -> io::Result<Self> {
        let socket = open_socket(iface, &[])?;
        Ok(BlockingBus { socket, clock: Clock::new(), iface: iface.to_owned(), filters: Vec::new(), waker: None })
    }

    /// Receive only frames whose `id & mask == filter_id & mask` for one of `filters` (error frames still
    /// come through). Kept across a reopen.
    pub fn set_filters(&mut self, filters: &[(u32, u32)]) -> io::Result<()> {
        apply_filters(&self.socket, filters)?;
        self.filters = filters.to_vec();
        Ok(())
    }

    /// A wake-up for [`run_blocking`]: another thread that changed the node calls [`BusWaker::signal`] and
    /// the runner sends what it queued at once. Once a waker is taken the runner no longer wakes every
    /// [`APP_POLL`]: it sleeps until a frame, the node's next deadline or a signal.
    pub fn waker(&mut self) -> io::Result<BusWaker> {
        if self.waker.is_none() {
            let (rx, tx) = UnixDatagram::pair()?;
            rx.set_nonblocking(true)?;
            tx.set_nonblocking(true)?;
            self.waker = Some((rx, Arc::new(tx)));
        }
        let tx = self.waker.as_ref().map(|(_, tx)| tx.clone()).ok_or_else(|| io::Error::other("no waker"))?;
        Ok(BusWaker(tx))
    }

    /// The interface name.
    pub fn iface(&self) -> &str {
        &self.iface
    }

    /// The current time on the node's clock.
    pub fn now(&self) -> Instant {
        self.clock.now()
    }

    /// The node's clock.
    pub fn clock(&self) -> Clock {
        self.clock
    }

    /// Sends one frame. While the socket buffer is full (`ENOBUFS`) it waits and retries, reporting
    /// [`AdapterEvent::TxBufferFull`] once; after [`TX_STALL_LIMIT`](crate::TX_STALL_LIMIT) it drops the
    /// frame and reports [`AdapterEvent::TxDropped`]. Other errors (interface down) are returned.
    pub fn send(&self, frame: &CanFrame, report: &mut dyn FnMut(AdapterEvent)) -> io::Result<()> {
        let out = to_socket_frame(frame)?;
        let mut stalled: Option<std::time::Instant> = None;
        loop {
            match self.socket.write_frame(&out) {
                Ok(()) => return Ok(()),
                Err(e) => match classify(&e) {
                    ErrorClass::NoBufs | ErrorClass::Timeout => {
                        let since = *stalled.get_or_insert_with(|| {
                            report(AdapterEvent::TxBufferFull);
                            std::time::Instant::now()
                        });
                        if since.elapsed() >= crate::TX_STALL_LIMIT {
                            report(AdapterEvent::TxDropped(*frame));
                            return Ok(());
                        }
                        std::thread::sleep(crate::ENOBUFS_BACKOFF);
                    }
                    ErrorClass::Interrupted => {}
                    ErrorClass::Down | ErrorClass::Fatal => return Err(e),
                },
            }
        }
    }

    /// Waits for a frame until `deadline` (forever if `None`). 29-bit frames are skipped (CAN-01).
    pub fn recv_until(&self, deadline: Option<Instant>) -> io::Result<Rx> {
        loop {
            let read = match deadline {
                Some(d) => {
                    let wait = d.as_micros().saturating_sub(self.now().as_micros());
                    if wait == 0 {
                        return Ok(Rx::Timeout);
                    }
                    self.socket.read_frame_timeout(StdDuration::from_micros(wait))
                }
                None => self.socket.read_frame(),
            };
            match read {
                Ok(f) => match map_received(&f) {
                    Some(Ok(frame)) => return Ok(Rx::Frame(frame)),
                    Some(Err(event)) => return Ok(Rx::Adapter(event)),
                    None => continue,
                },
                Err(e) => match classify(&e) {
                    ErrorClass::Timeout => return Ok(Rx::Timeout),
                    ErrorClass::Interrupted => continue,
                    ErrorClass::NoBufs | ErrorClass::Down | ErrorClass::Fatal => return Err(e),
                },
            }
        }
    }

    /// After an "interface down" error: waits until `iface` is up again (polling every
    /// [`REOPEN_POLL`](crate::REOPEN_POLL), for at most `limit` if given), then opens a fresh socket with
    /// the same filters and the same clock.
    pub fn reopen(&mut self, limit: Option<StdDuration>) -> io::Result<()> {
        let start = std::time::Instant::now();
        loop {
            if crate::interface_is_up(&self.iface) {
                if let Ok(socket) = open_socket(&self.iface, &self.filters) {
                    self.socket = socket;
                    return Ok(());
                }
            }
            if limit.is_some_and(|l| start.elapsed() >= l) {
                return Err(io::Error::new(io::ErrorKind::TimedOut, format!("{} did not come back up", self.iface)));
            }
            std::thread::sleep(crate::REOPEN_POLL);
        }
    }
}

pub(crate) fn apply_filters(socket: &impl SocketOptions, filters: &[(u32, u32)]) -> io::Result<()> {
    if filters.is_empty() {
        return socket.set_filter_accept_all();
    }
    let f: Vec<CanFilter> = filters.iter().map(|&(id, mask)| CanFilter::new(id, mask)).collect();
    socket.set_filters(&f)
}

fn open_socket(iface: &str, filters: &[(u32, u32)]) -> io::Result<CanSocket> {
    let socket = CanSocket::open(iface).map_err(|e| open_error(iface, e))?;
    socket.set_error_filter_accept_all()?;
    apply_filters(&socket, filters)?;
    Ok(socket)
}

/// A handle another thread uses to wake [`run_blocking`] after it changed the node (see
/// [`BlockingBus::waker`]). Cheap to clone; a signal given while the runner is busy is kept.
///
/// ```no_run
/// let mut bus = canopen_socketcan::BlockingBus::open("vcan0")?;
/// let waker = bus.waker()?;
/// std::thread::spawn(move || waker.signal());
/// # Ok::<(), std::io::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct BusWaker(Arc<UnixDatagram>);

impl BusWaker {
    /// Wakes the runner (one non-blocking send on a socket pair; a full pair means a wake-up is pending).
    pub fn signal(&self) {
        let _ = self.0.send(&[1]);
    }
}

/// Runs the node in `shared` on `bus` until `keep_running` returns false. Each pass reads the clock once,
/// hands the node every frame received since the last pass and the time, sends what it produced (one
/// `sendmmsg` per batch), installs the node's receive set as kernel filters when it changed, then waits in
/// one `ppoll` for a frame, the node's next deadline or a [`BusWaker`] signal, and takes every queued frame
/// (one `recvmmsg` per [`BATCH`](crate::BATCH) frames). Without a waker (none taken with
/// [`BlockingBus::waker`]) the wait is capped at [`APP_POLL`] so that changes made by other threads go out.
/// Every event, every frame on the wire and every [`AdapterEvent`] goes to `observe`. An interface that
/// goes down is waited for and reopened (the node keeps its state); other socket errors are returned.
///
/// ```no_run
/// use std::cell::RefCell;
/// use canopen_core::{profile::NodeConfig, node::{NoApplication, Node}, NodeId};
/// use canopen_socketcan::{run_blocking, BlockingBus, Observed};
/// let mut bus = BlockingBus::open("vcan0")?;
/// let node: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
/// run_blocking(&RefCell::new(node), &mut bus, |o| println!("{o:?}"), || true)?;
/// # Ok::<(), std::io::Error>(())
/// ```
pub fn run_blocking<N: SansIo + ReceiveFilters, S: Shared<N>>(
    shared: &S,
    bus: &mut BlockingBus,
    mut observe: impl FnMut(Observed<'_>),
    mut keep_running: impl FnMut() -> bool,
) -> io::Result<()> {
    let mut pass = Pass::default();
    let _ = crate::batch::grow_receive_buffer(bus.socket.as_raw_fd(), crate::RECEIVE_BUFFER);
    while keep_running() {
        match step(shared, bus, &mut pass, &mut observe) {
            Ok(()) => {}
            Err(e) if classify(&e) == ErrorClass::Down => {
                let iface = bus.iface().to_owned();
                observe(Observed::Adapter(&AdapterEvent::InterfaceDown { iface: iface.clone(), error: e.to_string() }));
                bus.reopen(None)?;
                let _ = crate::batch::grow_receive_buffer(bus.socket.as_raw_fd(), crate::RECEIVE_BUFFER);
                pass.reinstall(); // the new socket gets the node's current filters
                observe(Observed::Adapter(&AdapterEvent::Reopened { iface }));
            }
            Err(e) => return Err(e),
        }
    }
    Ok(())
}

fn step<N: SansIo + ReceiveFilters, S: Shared<N>>(
    shared: &S,
    bus: &mut BlockingBus,
    pass: &mut Pass,
    observe: &mut impl FnMut(Observed<'_>),
) -> io::Result<()> {
    let now = bus.now(); // the pass's one clock reading
    let (deadline, filters) = pass.run(shared, now, observe);
    if let Some(f) = filters {
        bus.set_filters(&kernel_filters(&f))?;
        count(Counter::FilterUpdates, 1);
        pass.installed(f);
    }
    send_all(bus, pass, observe)?;
    let mut wait = deadline.map(|d| d.as_micros().saturating_sub(now.as_micros()));
    if bus.waker.is_none() {
        let cap = APP_POLL.as_micros() as u64;
        wait = Some(wait.map_or(cap, |w| w.min(cap)));
    }
    let fd = bus.socket.as_raw_fd();
    let socket_ready = if wait == Some(0) {
        true // due now: take what is queued without waiting
    } else {
        let wake_fd = bus.waker.as_ref().map_or(-1, |(rx, _)| rx.as_raw_fd());
        let [ready, woken] = crate::batch::wait_readable([fd, wake_fd], wait)?;
        count(Counter::Wakeups, 1);
        if woken {
            if let Some((rx, _)) = &bus.waker {
                let mut b = [0u8; 16];
                while rx.recv(&mut b).is_ok() {}
            }
        }
        ready
    };
    if socket_ready {
        receive_all(fd, pass, observe)?;
    }
    Ok(())
}

/// Takes every queued frame, [`BATCH`](crate::BATCH) per call, so the socket's receive buffer is empty
/// after each pass.
pub(crate) fn receive_all(fd: RawFd, pass: &mut Pass, observe: &mut dyn FnMut(Observed<'_>)) -> io::Result<usize> {
    let mut total = 0;
    loop {
        let n = pass.receive(fd, observe)?;
        total += n;
        if n < crate::BATCH {
            return Ok(total);
        }
    }
}

/// Sends `pass.tx` in order, in as few calls as the socket takes; a full queue (`ENOBUFS`, `EAGAIN`) is
/// waited out as [`BlockingBus::send`] does, nothing is lost or reordered on a partial send.
fn send_all(bus: &BlockingBus, pass: &mut Pass, observe: &mut impl FnMut(Observed<'_>)) -> io::Result<()> {
    let mut stall = crate::pass::TxStall::default();
    while !pass.tx.is_empty() {
        if crate::pass::send_attempt(bus.socket.as_raw_fd(), &mut pass.tx, &mut stall, || bus.now(), observe)? {
            std::thread::sleep(crate::ENOBUFS_BACKOFF);
        }
    }
    Ok(())
}
