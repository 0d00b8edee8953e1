//! The blocking adapter: one raw CAN socket, read with a timeout equal to the node's next deadline.
//!
//! [`run_blocking`] is the whole runner loop. The node lives in a [`Shared`] cell (a
//! [`MutexShared`](crate::MutexShared) when other threads change it, a `RefCell` otherwise). A blocking read
//! cannot be woken by another thread, so the runner wakes at least every [`APP_POLL`] to send what another
//! thread queued; the tokio runner has no such delay (it awaits a [`Wake`](canopen_core::driver::Wake)).

use std::io;
use std::time::Duration as StdDuration;

use canopen_core::driver::Shared;
use canopen_core::node::SansIo;
use canopen_core::{CanFrame, Instant};
use socketcan::{CanFilter, CanSocket, Socket, SocketOptions};

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
}

impl BlockingBus {
    /// Opens `iface` (e.g. `vcan0`) and accepts every error frame class. The error says how to create a
    /// virtual interface when it is missing.
    pub fn open(iface: &str) -> io::Result<Self> {
        let socket = open_socket(iface, &[])?;
        Ok(BlockingBus { socket, clock: Clock::new(), iface: iface.to_owned(), filters: Vec::new() })
    }

    /// Receive only frames whose `id & mask == filter_id & mask` for one of `filters` (error frames still
    /// come through). Kept across a reopen.
    pub fn set_filters(&mut self, filters: &[(u32, u32)]) -> io::Result<()> {
        apply_filters(&self.socket, filters)?;
        self.filters = filters.to_vec();
        Ok(())
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

/// Runs the node in `shared` on `bus` until `keep_running` returns false: waits for a frame or the next
/// deadline (at most [`APP_POLL`]), feeds the node, sends what it produces, and hands every event, every
/// frame on the wire and every [`AdapterEvent`] to `observe`. An interface that goes down is waited for
/// and reopened (the node keeps its state); other socket errors are returned.
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
pub fn run_blocking<N: SansIo, S: Shared<N>>(
    shared: &S,
    bus: &mut BlockingBus,
    mut observe: impl FnMut(Observed<'_>),
    mut keep_running: impl FnMut() -> bool,
) -> io::Result<()> {
    while keep_running() {
        match step(shared, bus, &mut observe) {
            Ok(()) => {}
            Err(e) if classify(&e) == ErrorClass::Down => {
                let iface = bus.iface().to_owned();
                observe(Observed::Adapter(&AdapterEvent::InterfaceDown { iface: iface.clone(), error: e.to_string() }));
                bus.reopen(None)?;
                observe(Observed::Adapter(&AdapterEvent::Reopened { iface }));
            }
            Err(e) => return Err(e),
        }
    }
    Ok(())
}

fn step<N: SansIo, S: Shared<N>>(
    shared: &S,
    bus: &BlockingBus,
    observe: &mut impl FnMut(Observed<'_>),
) -> io::Result<()> {
    let now = bus.now();
    shared.lock(|n| n.handle_timeout(now));
    flush(shared, bus, observe)?;
    let cap = Instant::from_micros(bus.now().as_micros() + APP_POLL.as_micros() as u64);
    let deadline = shared.lock(|n| n.poll_timeout()).map_or(cap, |d| d.min(cap));
    match bus.recv_until(Some(deadline))? {
        Rx::Frame(frame) => {
            observe(Observed::Received(&frame));
            let now = bus.now();
            shared.lock(|n| n.handle_frame(now, &frame));
        }
        Rx::Adapter(event) => observe(Observed::Adapter(&event)),
        Rx::Timeout => {}
    }
    flush(shared, bus, observe)
}

fn flush<N: SansIo, S: Shared<N>>(
    shared: &S,
    bus: &BlockingBus,
    observe: &mut impl FnMut(Observed<'_>),
) -> io::Result<()> {
    loop {
        let (frame, event) = shared.lock(|n| (n.poll_transmit(), n.poll_event()));
        if frame.is_none() && event.is_none() {
            return Ok(());
        }
        if let Some(event) = event {
            observe(Observed::Event(&event));
        }
        if let Some(frame) = frame {
            bus.send(&frame, &mut |e| observe(Observed::Adapter(&e)))?;
            observe(Observed::Sent(&frame));
        }
    }
}
