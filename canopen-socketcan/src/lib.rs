//! Linux SocketCAN adapter for `canopen-core`.
//!
//! [`BlockingBus`] wraps a raw CAN socket: it converts frames through `embedded-can`, keeps the node's clock
//! (a monotonic [`std::time::Instant`] mapped to the core's microsecond [`canopen_core::Instant`]), waits for a
//! frame *or* the node's next deadline (no fixed tick), and retries a send when the socket's buffer is full
//! (`ENOBUFS`) instead of dropping the frame. [`run_blocking`] is the whole runner loop for a [`Node`].
//!
//! The async (tokio) variant, error-frame and bus-off reporting, and store/restore to a file are built on
//! the same pieces (SocketCAN issue).

use std::io;
use std::time::Duration as StdDuration;

use canopen_core::od::ObjectDictionary;
use canopen_core::{CanFrame, Event, Instant, Node};
use socketcan::{CanSocket, EmbeddedFrame, Socket};

/// How long to wait before retrying a send that failed because the socket buffer was full.
const ENOBUFS_BACKOFF: StdDuration = StdDuration::from_micros(200);

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
    epoch: std::time::Instant,
    iface: String,
}

impl BlockingBus {
    /// Opens `iface` (e.g. `vcan0`). The error says how to create a virtual interface when it is missing.
    pub fn open(iface: &str) -> io::Result<Self> {
        let socket = CanSocket::open(iface).map_err(|e| {
            io::Error::new(
                e.kind(),
                format!(
                    "no SocketCAN interface '{iface}' ({e}); create one with: sudo modprobe vcan && sudo ip link add dev {iface} type vcan && sudo ip link set up {iface}"
                ),
            )
        })?;
        Ok(BlockingBus { socket, epoch: std::time::Instant::now(), iface: iface.to_owned() })
    }

    /// The interface name.
    pub fn iface(&self) -> &str {
        &self.iface
    }

    /// The current time on the node's clock.
    pub fn now(&self) -> Instant {
        Instant::from_micros(self.epoch.elapsed().as_micros() as u64)
    }

    /// Sends one frame, retrying while the socket buffer is full (`ENOBUFS`).
    pub fn send(&self, frame: &CanFrame) -> io::Result<()> {
        let out: socketcan::CanFrame =
            frame.to_frame().ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "frame not representable"))?;
        loop {
            match self.socket.write_frame(&out) {
                Err(e) if e.raw_os_error() == Some(libc_enobufs()) => std::thread::sleep(ENOBUFS_BACKOFF),
                other => return other,
            }
        }
    }

    /// Waits for a frame until `deadline` (forever if `None`). Returns `Ok(None)` when the deadline passed.
    /// 29-bit and error frames are skipped (CAN-01; error frames are reported by the full adapter).
    pub fn recv_until(&self, deadline: Option<Instant>) -> io::Result<Option<CanFrame>> {
        loop {
            let read = match deadline {
                Some(d) => {
                    let wait = d.as_micros().saturating_sub(self.now().as_micros());
                    if wait == 0 {
                        return Ok(None);
                    }
                    self.socket.read_frame_timeout(StdDuration::from_micros(wait))
                }
                None => self.socket.read_frame(),
            };
            match read {
                Ok(f) if f.is_extended() || matches!(f, socketcan::CanFrame::Error(_)) => continue,
                Ok(f) => {
                    if let Some(frame) = CanFrame::from_frame(&f) {
                        return Ok(Some(frame));
                    }
                }
                Err(e) if e.kind() == io::ErrorKind::TimedOut || e.kind() == io::ErrorKind::WouldBlock => {
                    return Ok(None)
                }
                Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(e),
            }
        }
    }
}

fn libc_enobufs() -> i32 {
    105 // ENOBUFS on Linux
}

/// Runs `node` on `bus` until `keep_running` returns false: waits for a frame or the next deadline, feeds
/// the node, sends what it produces, and hands every event and every frame on the wire to `observe`.
///
/// ```no_run
/// use canopen_core::{comm::NodeConfig, node::{NoApplication, Node}, NodeId};
/// use canopen_socketcan::{run_blocking, BlockingBus, Observed};
/// let bus = BlockingBus::open("vcan0")?;
/// let mut node: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
/// run_blocking(&mut node, &bus, |o| println!("{o:?}"), || true)?;
/// # Ok::<(), std::io::Error>(())
/// ```
pub fn run_blocking<A: ObjectDictionary, const HB: usize, const TXQ: usize, const EVQ: usize>(
    node: &mut Node<A, HB, TXQ, EVQ>,
    bus: &BlockingBus,
    mut observe: impl FnMut(Observed<'_>),
    mut keep_running: impl FnMut() -> bool,
) -> io::Result<()> {
    while keep_running() {
        node.handle_timeout(bus.now());
        flush(node, bus, &mut observe)?;
        // Wake at the next deadline, but at least every 100 ms so that `keep_running` is polled.
        let cap = Instant::from_micros(bus.now().as_micros() + 100_000);
        let deadline = node.poll_timeout().map_or(cap, |d| d.min(cap));
        if let Some(frame) = bus.recv_until(Some(deadline))? {
            observe(Observed::Received(&frame));
            node.handle_frame(bus.now(), &frame);
        }
        flush(node, bus, &mut observe)?;
    }
    Ok(())
}

fn flush<A: ObjectDictionary, const HB: usize, const TXQ: usize, const EVQ: usize>(
    node: &mut Node<A, HB, TXQ, EVQ>,
    bus: &BlockingBus,
    observe: &mut impl FnMut(Observed<'_>),
) -> io::Result<()> {
    while let Some(frame) = node.poll_transmit() {
        bus.send(&frame)?;
        observe(Observed::Sent(&frame));
    }
    while let Some(event) = node.poll_event() {
        observe(Observed::Event(&event));
    }
    Ok(())
}

/// What [`run_blocking`] reports to its observer.
///
/// ```
/// use canopen_socketcan::Observed;
/// let f = canopen_core::CanFrame::new(0x705, &[0]).unwrap();
/// assert!(matches!(Observed::Sent(&f), Observed::Sent(_)));
/// ```
#[derive(Debug)]
pub enum Observed<'a> {
    /// A frame the node received.
    Received(&'a CanFrame),
    /// A frame the node sent.
    Sent(&'a CanFrame),
    /// An event of the node.
    Event(&'a Event),
}
