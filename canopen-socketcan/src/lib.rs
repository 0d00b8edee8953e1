//! Linux SocketCAN adapter for `canopen-core`: the node on a real (or virtual) CAN interface, driven by
//! tokio ([`tokio_runner`]) or by a plain blocking loop ([`blocking`]), plus a blocking SDO/NMT master
//! ([`master`]) on the core's sans-IO SDO client.
//!
//! Both runners are thin: the core's [`Node`](canopen_core::Node) does the protocol work, the adapter moves
//! frames (through `embedded-can`, so [`canopen_core::CanFrame`] never sees a socket type), keeps the
//! node's clock (a monotonic [`std::time::Instant`] mapped to the core's microsecond
//! [`canopen_core::Instant`]) and sleeps exactly until the node's next deadline.
//!
//! # What the adapter reports and recovers from
//!
//! Everything that happens below the node is reported to the observer as an [`AdapterEvent`]
//! ([`Observed::Adapter`]), never swallowed:
//!
//! - **Error frames** (the socket accepts all error classes): [`AdapterEvent::ErrorFrame`]; those that
//!   report the controller's state are decoded as [`AdapterEvent::BusOff`] (`CAN_ERR_BUSOFF`),
//!   [`AdapterEvent::Restarted`] (`CAN_ERR_RESTARTED`) and [`AdapterEvent::Controller`] (`CAN_ERR_CRTL`:
//!   warning, error passive, back to error active), and the runners feed each to the node
//!   ([`AdapterEvent::bus_state`], `Node::set_bus_state`) in order with the frames: it raises 8120h on error
//!   passive, treats bus-off as a communication error for 1029h:01 (ERR-13) and sends 8140h after the
//!   restart. The controller restarts itself (`ip link set canX type can restart-ms N`); the runner keeps
//!   going.
//! - **Interface down or removed** (`ENETDOWN`, `ENODEV`, `ENXIO` on a read or write):
//!   [`AdapterEvent::InterfaceDown`]; the runner waits until the interface is up again (it polls
//!   `/sys/class/net/<iface>/flags` every 100 ms), opens a fresh socket (the interface index may have
//!   changed) and reports [`AdapterEvent::Reopened`]. The node lives outside the socket (in a
//!   [`Shared`](canopen_core::driver::Shared) cell), so its state (NMT state, parameters, an SDO transfer)
//!   survives; its deadlines that passed meanwhile fire on the first call after the reopen.
//! - **Full socket send buffer** (`ENOBUFS`, the interface's queue is full): the send waits
//!   [`ENOBUFS_BACKOFF`] and retries, reporting [`AdapterEvent::TxBufferFull`] once per stall. A frame that
//!   still cannot be sent after [`TX_STALL_LIMIT`] (no other node acknowledges, the controller is stuck) is
//!   dropped and reported as [`AdapterEvent::TxDropped`], so a dead bus cannot freeze the receive side.
//!
//! 29-bit (extended) frames are ignored (CAN-01: CANopen uses 11-bit identifiers).
//!
//! ```no_run
//! use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
//! use canopen_socketcan::{run_blocking, BlockingBus};
//!
//! // sudo modprobe vcan && sudo ip link add dev vcan0 type vcan && sudo ip link set up vcan0
//! let node: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
//! let shared = core::cell::RefCell::new(node);
//! let mut bus = BlockingBus::open("vcan0")?;
//! run_blocking(&shared, &mut bus, |seen| println!("{seen:?}"), || true)?;
//! # Ok::<(), std::io::Error>(())
//! ```

#![deny(unsafe_code)]
#![warn(missing_docs)]

use std::io;
use std::time::Duration as StdDuration;

use canopen_core::bus::BusState;
use canopen_core::{CanFrame, Event, Instant};

/// The `socketcan` crate this adapter is built on (for raw sockets in tests and tools).
pub use socketcan;

mod batch;
pub mod blocking;
pub mod file_storage;
pub mod master;
mod pass;
mod shared;
#[cfg(feature = "tokio")]
pub mod tokio_runner;

pub use batch::{send_frames, BatchReceiver, BATCH};
pub use blocking::{run_blocking, BlockingBus, BusWaker, Rx};
pub use file_storage::FileStorage;
pub use master::{Master, MasterError, MasterStats};
pub use pass::{runner_stats, ReceiveFilters, RunnerStats};
pub use shared::MutexShared;
#[cfg(feature = "tokio")]
pub use tokio_runner::{run_tokio, NotifyWake, TimerFd, TokioBus, TokioTimer};

/// How long a send waits before retrying when the socket buffer is full (`ENOBUFS`).
pub const ENOBUFS_BACKOFF: StdDuration = StdDuration::from_micros(200);

/// How long a send keeps retrying on `ENOBUFS` before the frame is dropped and reported.
pub const TX_STALL_LIMIT: StdDuration = StdDuration::from_secs(1);

/// The receive buffer the runners ask for on the node's socket (`SO_RCVBUFFORCE`, else `SO_RCVBUF` capped
/// by `net.core.rmem_max`): a whole 127-segment sub-block plus a burst of other traffic while the node
/// computes (the default of about 200 KiB holds far fewer frames than it seems, each costing a whole skb).
pub const RECEIVE_BUFFER: usize = 4 << 20;

/// How often a runner looks whether a downed interface is up again.
pub const REOPEN_POLL: StdDuration = StdDuration::from_millis(100);

/// Something the adapter saw below the node (see the [crate docs](crate)).
///
/// ```
/// use canopen_socketcan::AdapterEvent;
/// let e = AdapterEvent::InterfaceDown { iface: "vcan0".into(), error: "Network is down".into() };
/// assert!(e.to_string().contains("vcan0"));
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum AdapterEvent {
    /// An error frame from the controller, decoded by `socketcan`.
    ErrorFrame(String),
    /// The controller went bus-off (an error frame with `CAN_ERR_BUSOFF`).
    BusOff,
    /// The controller restarted after bus-off (`CAN_ERR_RESTARTED`).
    Restarted,
    /// The controller changed its error state (`CAN_ERR_CRTL`: rx/tx warning, rx/tx error passive, back to
    /// error active): [`BusState::Warning`], [`BusState::ErrorPassive`] or [`BusState::ErrorActive`].
    Controller(BusState),
    /// The interface went down or disappeared; the runner waits for it.
    InterfaceDown {
        /// Interface name.
        iface: String,
        /// The error the socket returned.
        error: String,
    },
    /// A fresh socket is open on the interface again; the node resumes.
    Reopened {
        /// Interface name.
        iface: String,
    },
    /// The socket's send buffer was full (`ENOBUFS`); the send waits and retries.
    TxBufferFull,
    /// A frame could not be sent within [`TX_STALL_LIMIT`] and was dropped.
    TxDropped(CanFrame),
}

impl std::fmt::Display for AdapterEvent {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            AdapterEvent::ErrorFrame(e) => write!(f, "error frame: {e}"),
            AdapterEvent::BusOff => write!(f, "bus-off"),
            AdapterEvent::Restarted => write!(f, "controller restarted after bus-off"),
            AdapterEvent::Controller(state) => write!(f, "controller {state}"),
            AdapterEvent::InterfaceDown { iface, error } => {
                write!(f, "interface {iface} down ({error}); waiting for it to come back")
            }
            AdapterEvent::Reopened { iface } => write!(f, "interface {iface} up again; socket reopened, node resumes"),
            AdapterEvent::TxBufferFull => write!(f, "socket send buffer full (ENOBUFS); retrying"),
            AdapterEvent::TxDropped(frame) => {
                write!(f, "frame {frame} dropped: not sent within {} ms", TX_STALL_LIMIT.as_millis())
            }
        }
    }
}

impl AdapterEvent {
    /// The controller state this event reports, which the runners feed to the node
    /// ([`canopen_core::Node::set_bus_state`]): bus-off, the restart after it, and the `CAN_ERR_CRTL` states.
    ///
    /// ```
    /// use canopen_core::bus::BusState;
    /// use canopen_socketcan::AdapterEvent;
    /// assert_eq!(AdapterEvent::Restarted.bus_state(), Some(BusState::Recovered));
    /// assert_eq!(AdapterEvent::TxBufferFull.bus_state(), None);
    /// ```
    pub fn bus_state(&self) -> Option<BusState> {
        match self {
            AdapterEvent::BusOff => Some(BusState::BusOff),
            AdapterEvent::Restarted => Some(BusState::Recovered),
            AdapterEvent::Controller(state) => Some(*state),
            _ => None,
        }
    }
}

/// What a runner reports to its observer.
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
    /// Something the adapter saw below the node.
    Adapter(&'a AdapterEvent),
}

/// The node's monotonic clock: microseconds since the first `Clock` of the process was made. Every clock of
/// the process shares that zero, so a runner that is restarted (a new `run_tokio` after an error, a new
/// [`BlockingBus`]) carries on the node's timeline instead of sending it back to zero: the node's deadlines
/// (heartbeat, SDO time-out, inhibit times) stay right.
///
/// ```
/// let c = canopen_socketcan::Clock::new();
/// let before = c.now();
/// assert!(before <= c.now());
/// let later = canopen_socketcan::Clock::new(); // a restarted runner's clock
/// assert!(later.now() >= before); // read after `before`, on the same timeline
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Clock {
    /// The zero as a standard-library instant and as a `CLOCK_MONOTONIC` reading (µs), taken together.
    epoch: std::time::Instant,
    epoch_us: u64,
}

impl Clock {
    /// The process's node clock (its zero is when the first one was made).
    pub fn new() -> Self {
        static EPOCH: std::sync::OnceLock<(std::time::Instant, u64)> = std::sync::OnceLock::new();
        let &(epoch, epoch_us) = EPOCH.get_or_init(|| (std::time::Instant::now(), batch::monotonic_us()));
        Clock { epoch, epoch_us }
    }

    /// The current instant (one `clock_gettime(CLOCK_MONOTONIC)`).
    pub fn now(&self) -> Instant {
        Instant::from_micros(batch::monotonic_us().saturating_sub(self.epoch_us))
    }

    /// The standard-library instant of `t`.
    pub fn to_std(&self, t: Instant) -> std::time::Instant {
        self.epoch + StdDuration::from_micros(t.as_micros())
    }

    /// `t` on `CLOCK_MONOTONIC`, in µs (what a `timerfd` is armed with).
    #[cfg(feature = "tokio")]
    pub(crate) fn to_monotonic_us(self, t: Instant) -> u64 {
        self.epoch_us.saturating_add(t.as_micros())
    }
}

impl Default for Clock {
    fn default() -> Self {
        Clock::new()
    }
}

/// How a socket error is handled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ErrorClass {
    /// The interface is down or gone: wait, reopen, resume.
    Down,
    /// The send buffer is full: wait and retry.
    NoBufs,
    /// A read timed out or would block.
    Timeout,
    /// A signal interrupted the call: retry.
    Interrupted,
    /// Anything else: the runner stops with it.
    Fatal,
}

/// Whether a socket error means the interface went down or away (`ENETDOWN`, `ENODEV`, `ENXIO`,
/// `ENETUNREACH`): what the runners wait out and reopen after ([`AdapterEvent::InterfaceDown`]), and what
/// `canopen-master` reopens its socket after.
///
/// ```
/// use std::io::Error;
/// assert!(canopen_socketcan::is_interface_down(&Error::from_raw_os_error(libc::ENETDOWN)));
/// assert!(!canopen_socketcan::is_interface_down(&Error::from_raw_os_error(libc::ENOBUFS)));
/// ```
pub fn is_interface_down(e: &io::Error) -> bool {
    classify(e) == ErrorClass::Down
}

pub(crate) fn classify(e: &io::Error) -> ErrorClass {
    match e.raw_os_error() {
        Some(libc::ENETDOWN) | Some(libc::ENODEV) | Some(libc::ENXIO) | Some(libc::ENETUNREACH) => ErrorClass::Down,
        Some(libc::ENOBUFS) => ErrorClass::NoBufs,
        _ => match e.kind() {
            io::ErrorKind::TimedOut | io::ErrorKind::WouldBlock => ErrorClass::Timeout,
            io::ErrorKind::Interrupted => ErrorClass::Interrupted,
            _ => ErrorClass::Fatal,
        },
    }
}

/// Whether `iface` exists and is administratively up (`IFF_UP` in `/sys/class/net/<iface>/flags`).
///
/// ```
/// assert!(!canopen_socketcan::interface_is_up("no-such-if0"));
/// ```
pub fn interface_is_up(iface: &str) -> bool {
    std::fs::read_to_string(format!("/sys/class/net/{iface}/flags"))
        .ok()
        .and_then(|s| u32::from_str_radix(s.trim().trim_start_matches("0x"), 16).ok())
        .is_some_and(|flags| flags & 0x1 != 0)
}

/// The error [`BlockingBus::open`] and [`TokioBus::open`] return for a missing interface: one line that says
/// how to create a virtual one.
pub(crate) fn open_error(iface: &str, e: io::Error) -> io::Error {
    io::Error::new(
        e.kind(),
        format!(
            "no SocketCAN interface '{iface}' ({e}); create one with: sudo modprobe vcan && sudo ip link add dev {iface} type vcan && sudo ip link set up {iface}"
        ),
    )
}

/// Maps a received socket frame: data and remote frames with an 11-bit identifier become a core frame;
/// 29-bit frames are ignored (`None`); error frames become an [`AdapterEvent`].
pub(crate) fn map_received(frame: &socketcan::CanFrame) -> Option<Result<CanFrame, AdapterEvent>> {
    use socketcan::EmbeddedFrame;
    match frame {
        socketcan::CanFrame::Error(err) => Some(Err(match controller_state(err.error_bits(), err.data()) {
            Some(BusState::BusOff) => AdapterEvent::BusOff,
            Some(BusState::Recovered) => AdapterEvent::Restarted,
            Some(state) => AdapterEvent::Controller(state),
            None => AdapterEvent::ErrorFrame(err.into_error().to_string()),
        })),
        f if f.is_extended() => None,
        f => CanFrame::from_frame(f).map(Ok),
    }
}

/// The controller state an error frame reports (`linux/can/error.h`), read from the class bits and
/// `data[1]` directly: drivers combine classes (`CAN_ERR_CRTL | CAN_ERR_CNT` with the counters in
/// `data[6..8]`), which `socketcan`'s one-class decoding reports as unknown. Bus-off wins over a restart,
/// which wins over `CAN_ERR_CRTL`; there the worst state named wins (passive over warning over active).
/// Buffer overflows and other classes are no state (`None`).
fn controller_state(class: u32, data: &[u8]) -> Option<BusState> {
    const CRTL: u32 = 0x004;
    const BUSOFF: u32 = 0x040;
    const RESTARTED: u32 = 0x100;
    const RX_WARNING: u8 = 0x04;
    const TX_WARNING: u8 = 0x08;
    const RX_PASSIVE: u8 = 0x10;
    const TX_PASSIVE: u8 = 0x20;
    const ACTIVE: u8 = 0x40;
    if class & BUSOFF != 0 {
        return Some(BusState::BusOff);
    }
    if class & RESTARTED != 0 {
        return Some(BusState::Recovered);
    }
    if class & CRTL == 0 {
        return None;
    }
    let d1 = data.get(1).copied().unwrap_or(0);
    match () {
        _ if d1 & (RX_PASSIVE | TX_PASSIVE) != 0 => Some(BusState::ErrorPassive),
        _ if d1 & (RX_WARNING | TX_WARNING) != 0 => Some(BusState::Warning),
        _ if d1 & ACTIVE != 0 => Some(BusState::ErrorActive),
        _ => None,
    }
}

/// Maps a core frame to a socket frame.
pub(crate) fn to_socket_frame(frame: &CanFrame) -> io::Result<socketcan::CanFrame> {
    frame.to_frame().ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "frame not representable"))
}

#[cfg(test)]
mod tests {

    /// Issue "cancel safety / restart": a runner restarted after an error makes a new `Clock`; the node's time
    /// must carry on, never jump back to zero (its deadlines would all lie in the future again).
    #[test]
    fn a_restarted_runners_clock_never_goes_backwards() {
        let first = Clock::new();
        std::thread::sleep(StdDuration::from_millis(5));
        let before = first.now();
        assert!(before.as_micros() >= 5_000);
        let restarted = Clock::new();
        assert!(restarted.now() >= before, "{:?} < {before:?}", restarted.now());
    }
    use super::*;
    use socketcan::{EmbeddedFrame, ExtendedId, Frame, StandardId};

    #[test]
    fn frames_map_through_embedded_can() {
        let data = socketcan::CanFrame::new(StandardId::new(0x605).unwrap(), &[0x40, 0x00, 0x10, 0x00]).unwrap();
        assert_eq!(map_received(&data), Some(Ok(CanFrame::new(0x605, &[0x40, 0x00, 0x10, 0x00]).unwrap())));
        let rtr = socketcan::CanFrame::new_remote(StandardId::new(0x705).unwrap(), 1).unwrap();
        assert_eq!(map_received(&rtr), Some(Ok(CanFrame::new_rtr(0x705, 1).unwrap())));
        let ext = socketcan::CanFrame::new(ExtendedId::new(0x605).unwrap(), &[1]).unwrap();
        assert_eq!(map_received(&ext), None);
        let busoff = socketcan::CanFrame::Error(socketcan::CanErrorFrame::new_error(0x40, &[]).unwrap());
        assert_eq!(map_received(&busoff), Some(Err(AdapterEvent::BusOff)));
    }

    /// CAN_ERR_CRTL as drivers send it (with CAN_ERR_CNT and the counters), bus-off and restart, each to the
    /// state the node is given (EEC-11, EEC-13, ERR-13); an overflow is no state.
    #[test]
    fn controller_errors_map_to_bus_states() {
        let err = |class: u32, d1: u8| {
            let f = socketcan::CanErrorFrame::new_error(class, &[0, d1, 0, 0, 0, 0, 0x80, 0x10]).unwrap();
            map_received(&socketcan::CanFrame::Error(f))
        };
        let state = |class: u32, d1: u8| match err(class, d1) {
            Some(Err(e)) => e.bus_state(),
            other => panic!("not an adapter event: {other:?}"),
        };
        assert_eq!(state(0x204, 0x08), Some(BusState::Warning)); // tx warning
        assert_eq!(state(0x204, 0x04), Some(BusState::Warning)); // rx warning
        assert_eq!(state(0x204, 0x20), Some(BusState::ErrorPassive)); // tx passive
        assert_eq!(state(0x004, 0x10), Some(BusState::ErrorPassive)); // rx passive
        assert_eq!(state(0x004, 0x30), Some(BusState::ErrorPassive));
        assert_eq!(state(0x204, 0x40), Some(BusState::ErrorActive));
        assert_eq!(state(0x040, 0x00), Some(BusState::BusOff));
        assert_eq!(state(0x044, 0x20), Some(BusState::BusOff)); // bus-off wins
        assert_eq!(state(0x100, 0x00), Some(BusState::Recovered));
        assert_eq!(err(0x004, 0x40), Some(Err(AdapterEvent::Controller(BusState::ErrorActive))));
        assert_eq!(state(0x004, 0x01), None); // rx overflow: reported as an error frame, no state
        assert!(matches!(err(0x004, 0x01), Some(Err(AdapterEvent::ErrorFrame(_)))));
        assert_eq!(state(0x020, 0x00), None); // no ACK
    }

    #[test]
    fn core_frames_map_to_socket_frames() {
        let out = to_socket_frame(&CanFrame::new(0x185, &[1, 2, 3]).unwrap()).unwrap();
        assert_eq!((out.raw_id(), out.data()), (0x185, &[1u8, 2, 3][..]));
    }

    #[test]
    fn errors_are_classified() {
        assert_eq!(classify(&io::Error::from_raw_os_error(libc::ENETDOWN)), ErrorClass::Down);
        assert_eq!(classify(&io::Error::from_raw_os_error(libc::ENODEV)), ErrorClass::Down);
        assert_eq!(classify(&io::Error::from_raw_os_error(libc::ENOBUFS)), ErrorClass::NoBufs);
        assert_eq!(classify(&io::Error::from_raw_os_error(libc::EAGAIN)), ErrorClass::Timeout);
        assert_eq!(classify(&io::Error::from_raw_os_error(libc::EACCES)), ErrorClass::Fatal);
    }
}

/// The README's example, compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctest;
