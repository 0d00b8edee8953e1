//! One pass of a runner, shared by [`run_blocking`](crate::run_blocking) and [`run_tokio`](crate::run_tokio):
//! the frames received since the last pass and the time that passed go to the node with ONE clock reading,
//! everything the node produced comes out in one batch, and the node's receive filters are compared with the
//! installed ones. The runners only differ in how they wait and how they sleep on a full send queue.

use std::sync::atomic::{AtomicU64, Ordering};

use canopen_core::bus::BusState;
use canopen_core::driver::Shared;
use canopen_core::node::{RxFilters, SansIo};
use canopen_core::{CanFrame, Event, Instant};

use crate::{map_received, AdapterEvent, Observed};

/// A node whose receive set the runners install as kernel filters (`CAN_RAW_FILTER`), so that frames for
/// other nodes never wake the process. Implemented by [`canopen_core::Node`].
///
/// ```
/// use canopen_core::{profile::NodeConfig, node::{NoApplication, Node}, NodeId};
/// use canopen_socketcan::ReceiveFilters;
/// let node: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
/// assert!(ReceiveFilters::rx_filters(&node).iter().any(|f| f.id == 0x605));
/// ```
pub trait ReceiveFilters {
    /// The acceptance filters of the frames the node handles now.
    fn rx_filters(&self) -> RxFilters;
    /// A number that changes whenever [`rx_filters`](Self::rx_filters) may have changed; the runners
    /// recompute the filters only when it moved.
    fn rx_filters_generation(&self) -> u32;
}

impl<A: canopen_core::od::ObjectDictionary, Z: canopen_core::node::NodeSizes, S: canopen_core::storage::Storage>
    ReceiveFilters for canopen_core::Node<A, Z, S>
{
    fn rx_filters(&self) -> RxFilters {
        canopen_core::Node::rx_filters(self)
    }
    fn rx_filters_generation(&self) -> u32 {
        canopen_core::Node::rx_filters_generation(self)
    }
}

/// What the runners did, counted process-wide (all runners in the process together), for tests and
/// benchmarks: a frame for another node must not move any of these.
///
/// ```
/// let s = canopen_socketcan::runner_stats();
/// assert!(s.frames_received <= s.frames_received + s.wakeups);
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RunnerStats {
    /// Returns from a wait (a frame, a deadline, an application wake-up, a signal).
    pub wakeups: u64,
    /// Passes through the node (one clock reading each).
    pub passes: u64,
    /// Receive system calls that returned frames.
    pub receive_calls: u64,
    /// Frames received (11-bit, 29-bit and error frames).
    pub frames_received: u64,
    /// Send system calls.
    pub send_calls: u64,
    /// Frames sent.
    pub frames_sent: u64,
    /// Kernel filter installations (at open and whenever the node's receive set changed).
    pub filter_updates: u64,
}

static COUNTERS: [AtomicU64; 7] = [const { AtomicU64::new(0) }; 7];

pub(crate) enum Counter {
    Wakeups,
    Passes,
    ReceiveCalls,
    FramesReceived,
    SendCalls,
    FramesSent,
    FilterUpdates,
}

pub(crate) fn count(c: Counter, n: u64) {
    COUNTERS[c as usize].fetch_add(n, Ordering::Relaxed);
}

/// The runners' counters since the process started (see [`RunnerStats`]).
pub fn runner_stats() -> RunnerStats {
    let c = |i: usize| COUNTERS[i].load(Ordering::Relaxed);
    RunnerStats {
        wakeups: c(0),
        passes: c(1),
        receive_calls: c(2),
        frames_received: c(3),
        send_calls: c(4),
        frames_sent: c(5),
        filter_updates: c(6),
    }
}

/// One thing received from the socket for the node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Input {
    /// A data or remote frame.
    Frame(CanFrame),
    /// An error frame that reports the controller's state.
    Bus(BusState),
}

/// The buffers one runner reuses from pass to pass.
#[derive(Default)]
pub(crate) struct Pass {
    /// Frames and controller states received since the last pass, in order.
    pub rx: Vec<Input>,
    /// Frames the node produced, in order, not yet sent.
    pub tx: Vec<CanFrame>,
    events: Vec<Event>,
    /// The filters installed on the socket (`None`: accept all).
    installed: Option<RxFilters>,
    /// The node's [`ReceiveFilters::rx_filters_generation`] when its filters were last computed.
    generation: Option<u32>,
    /// The `recvmmsg` buffers, set up once.
    receiver: crate::batch::BatchReceiver,
}

impl Pass {
    /// The socket carries `filters` now (the runner installed what [`run`](Self::run) returned).
    pub fn installed(&mut self, filters: RxFilters) {
        self.installed = Some(filters);
    }

    /// A fresh socket accepts every frame: the next pass computes and returns the node's filters.
    pub fn reinstall(&mut self) {
        self.installed = None;
        self.generation = None;
    }

    /// Takes up to [`BATCH`](crate::BATCH) queued frames from the socket `fd` without waiting (one
    /// `recvmmsg`) into `rx`. Returns how many.
    pub fn receive(&mut self, fd: std::os::fd::RawFd, observe: &mut dyn FnMut(Observed<'_>)) -> std::io::Result<usize> {
        let rx = &mut self.rx;
        self.receiver.recv_frames(fd, |raw| take_raw(rx, raw, observe))
    }

    /// Maps raw frames from the socket into `rx` (reporting error frames, skipping 29-bit ones).
    #[cfg(test)]
    pub fn take_raw(&mut self, raw: &[libc::can_frame], observe: &mut dyn FnMut(Observed<'_>)) {
        take_raw(&mut self.rx, raw, observe)
    }

    /// Runs the node at `now`: the received frames, then the time, then drains its frames into `tx` and
    /// its events into `observe` (outside the lock: an observer may change the node, whose frames are
    /// drained too). Returns the next deadline and the node's filters when they differ from the installed
    /// ones; they are computed only when the node's generation moved since the last computation.
    pub fn run<N: SansIo + ReceiveFilters, S: Shared<N>>(
        &mut self,
        shared: &S,
        now: Instant,
        observe: &mut dyn FnMut(Observed<'_>),
    ) -> (Option<Instant>, Option<RxFilters>) {
        count(Counter::Passes, 1);
        for i in &self.rx {
            if let Input::Frame(f) = i {
                observe(Observed::Received(f));
            }
        }
        let mut first = true;
        let mut changed = None;
        loop {
            let (rx, tx, events, generation) = (&mut self.rx, &mut self.tx, &mut self.events, &mut self.generation);
            let (deadline, filters) = shared.lock(|n| {
                if std::mem::take(&mut first) {
                    for i in rx.drain(..) {
                        match i {
                            Input::Frame(f) => n.handle_frame(now, &f),
                            Input::Bus(state) => n.handle_bus_state(now, state),
                        }
                    }
                    n.handle_timeout(now);
                }
                tx.extend(std::iter::from_fn(|| n.poll_transmit()));
                events.extend(std::iter::from_fn(|| n.poll_event()));
                let g = n.rx_filters_generation();
                let filters = (*generation != Some(g)).then(|| {
                    *generation = Some(g);
                    n.rx_filters()
                });
                (n.poll_timeout(), filters)
            });
            if let Some(f) = filters {
                // The latest computation wins (an observer below may change the node again).
                changed = (self.installed.as_ref() != Some(&f)).then_some(f);
            }
            if self.events.is_empty() {
                return (deadline, changed);
            }
            for e in self.events.drain(..) {
                observe(Observed::Event(&e));
            }
        }
    }
}

/// Maps raw frames from the socket into `rx` (reporting error frames, skipping 29-bit ones).
fn take_raw(rx: &mut Vec<Input>, raw: &[libc::can_frame], observe: &mut dyn FnMut(Observed<'_>)) {
    count(Counter::ReceiveCalls, 1);
    count(Counter::FramesReceived, raw.len() as u64);
    for r in raw {
        match map_received(&socketcan::CanFrame::from(*r)) {
            Some(Ok(frame)) => rx.push(Input::Frame(frame)),
            Some(Err(event)) => {
                observe(Observed::Adapter(&event));
                rx.extend(event.bus_state().map(Input::Bus));
            }
            None => {}
        }
    }
}

/// The kernel filter list for `filters`: 11-bit data and remote frames only (29-bit frames never match,
/// CAN-01).
pub(crate) fn kernel_filters(filters: &[canopen_core::node::RxFilter]) -> Vec<(u32, u32)> {
    filters.iter().map(|f| (u32::from(f.id), u32::from(f.mask) | libc::CAN_EFF_FLAG)).collect()
}

/// A core frame as the kernel's `can_frame`.
pub(crate) fn raw_frame(frame: &CanFrame) -> std::io::Result<libc::can_frame> {
    let f = crate::to_socket_frame(frame)?;
    Ok(*AsRef::<libc::can_frame>::as_ref(&f))
}

/// Reports the frames `tx[..n]` as sent and removes them.
pub(crate) fn sent(tx: &mut Vec<CanFrame>, n: usize, observe: &mut dyn FnMut(Observed<'_>)) {
    count(Counter::SendCalls, 1);
    count(Counter::FramesSent, n as u64);
    for f in tx.drain(..n) {
        observe(Observed::Sent(&f));
    }
}

/// After a full send queue lasted [`TX_STALL_LIMIT`](crate::TX_STALL_LIMIT): the first unsent frame is
/// dropped and reported.
fn drop_first(tx: &mut Vec<CanFrame>, observe: &mut dyn FnMut(Observed<'_>)) {
    if !tx.is_empty() {
        let f = tx.remove(0);
        observe(Observed::Adapter(&AdapterEvent::TxDropped(f)));
    }
}

/// The transmit-stall rule both runners follow when the socket's queue is full (`ENOBUFS`, `EAGAIN`): the
/// first full answer is reported as [`AdapterEvent::TxBufferFull`]; once the stall has lasted
/// [`TX_STALL_LIMIT`](crate::TX_STALL_LIMIT), the first unsent frame is dropped and reported and the wait
/// starts again. Only a stall reads the clock.
#[derive(Default)]
pub(crate) struct TxStall(Option<Instant>);

impl TxStall {
    /// A send call went through.
    pub fn clear(&mut self) {
        self.0 = None;
    }

    /// The queue was full at `now`. Returns `true` when the caller should back off and retry, `false` when a
    /// frame was dropped (retry at once).
    pub fn full(&mut self, now: Instant, tx: &mut Vec<CanFrame>, observe: &mut dyn FnMut(Observed<'_>)) -> bool {
        let since = *self.0.get_or_insert_with(|| {
            observe(Observed::Adapter(&AdapterEvent::TxBufferFull));
            now
        });
        if now.as_micros().saturating_sub(since.as_micros()) >= crate::TX_STALL_LIMIT.as_micros() as u64 {
            drop_first(tx, observe);
            self.0 = None;
            false
        } else {
            true
        }
    }
}

/// One attempt of a runner's `send_all`: sends `tx` in order, as many frames as the socket takes in one
/// call, and applies the [`TxStall`] rule when its queue is full. Returns `Ok(true)` when the caller should
/// wait [`ENOBUFS_BACKOFF`](crate::ENOBUFS_BACKOFF) before the next attempt; the clock (`now`) is read only
/// in a stall. The two runners differ only in how they wait.
pub(crate) fn send_attempt(
    fd: std::os::fd::RawFd,
    tx: &mut Vec<CanFrame>,
    stall: &mut TxStall,
    now: impl FnOnce() -> Instant,
    observe: &mut dyn FnMut(Observed<'_>),
) -> std::io::Result<bool> {
    // The frames go to the kernel's structs on the stack, one batch at a time: no allocation per pass.
    let frames = &tx[..];
    match crate::batch::send_frames(fd, frames.len(), |i| raw_frame(&frames[i])) {
        Ok(n) => {
            sent(tx, n, observe);
            stall.clear();
            Ok(false)
        }
        Err(e) => match crate::classify(&e) {
            crate::ErrorClass::NoBufs | crate::ErrorClass::Timeout => Ok(stall.full(now(), tx, observe)),
            crate::ErrorClass::Interrupted => Ok(false),
            crate::ErrorClass::Down | crate::ErrorClass::Fatal => Err(e),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use canopen_core::node::{NoApplication, Node};
    use canopen_core::profile::NodeConfig;
    use canopen_core::NodeId;
    use std::cell::RefCell;

    /// One pass: the frames in order at the one instant given, then the time; every frame the node
    /// produced (including those an event observer queued) in order; the filters reported only when they
    /// differ from the installed ones (issue 19; SDO-05: the reply to a request in the same pass).
    #[test]
    fn a_pass_handles_frames_in_order_and_reports_filter_changes() {
        let node: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
        let shared = RefCell::new(node);
        let mut pass = Pass::default();
        let mut seen = Vec::new();
        let (deadline, filters) = pass.run(&shared, Instant::ZERO, &mut |o| seen.push(format!("{o:?}")));
        assert_eq!(pass.tx, [CanFrame::new(0x705, &[0]).unwrap()]); // boot-up
        assert_eq!(deadline, None);
        pass.installed(filters.expect("first pass: filters to install"));
        pass.tx.clear();
        // Two reads of 1000h, then a write of 1016h:01 (a heartbeat consumer of node 3): three replies in
        // order, and the receive set changed (703h).
        for req in [[0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0], [0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0]] {
            pass.rx.push(Input::Frame(CanFrame::new(0x605, &req).unwrap()));
        }
        pass.rx.push(Input::Frame(CanFrame::new(0x605, &[0x23, 0x16, 0x10, 0x01, 0xF4, 0x01, 0x03, 0x00]).unwrap()));
        let mut observed = 0;
        let (_, filters) = pass.run(&shared, Instant::from_millis(1), &mut |o| {
            if matches!(o, Observed::Received(_)) {
                observed += 1;
            }
        });
        assert_eq!(observed, 3);
        assert!(pass.rx.is_empty());
        let cmds: Vec<u8> = pass.tx.iter().map(|f| f.data()[0]).collect();
        assert_eq!(cmds, [0x43, 0x43, 0x60]);
        let filters = filters.expect("1016h changed the receive set");
        assert!(filters.iter().any(|f| f.id == 0x703));
        pass.installed(filters);
        pass.tx.clear();
        // Nothing changed: no filters to install.
        let (_, filters) = pass.run(&shared, Instant::from_millis(2), &mut |_| {});
        assert!(filters.is_none() && pass.tx.is_empty());
        // An observer that queues a frame while handling an event (an EMCY on the state change): the
        // pass drains the node again, so the EMCY goes out in the same pass (EMCY-01: 080h + node-ID).
        pass.rx.push(Input::Frame(CanFrame::new(0x000, &[0x01, 0x05]).unwrap())); // NMT start: an event
        let (_, _) = pass.run(&shared, Instant::from_millis(3), &mut |o| {
            if let Observed::Event(canopen_core::Event::StateChanged { .. }) = o {
                shared.borrow_mut().raise_error(0x1000, [0; 5]);
            }
        });
        assert_eq!(pass.tx.iter().map(|f| f.cob_id()).collect::<Vec<_>>(), [0x085]);
        assert!(seen.iter().any(|s| s.contains("Event")), "{seen:?}");
    }

    /// A node that counts how often its filters are computed.
    struct Counting(Node<NoApplication>, std::cell::Cell<u32>);

    impl SansIo for Counting {
        fn handle_frame(&mut self, now: Instant, frame: &CanFrame) {
            self.0.handle_frame(now, frame)
        }
        fn handle_timeout(&mut self, now: Instant) {
            self.0.handle_timeout(now)
        }
        fn poll_timeout(&self) -> Option<Instant> {
            self.0.poll_timeout()
        }
        fn poll_transmit(&mut self) -> Option<CanFrame> {
            self.0.poll_transmit()
        }
        fn peek_transmit(&self) -> Option<CanFrame> {
            self.0.peek_transmit()
        }
        fn transmitted(&mut self, frame: &CanFrame) {
            self.0.transmitted(frame)
        }
        fn poll_event(&mut self) -> Option<Event> {
            self.0.poll_event()
        }
        fn handle_bus_state(&mut self, now: Instant, state: BusState) {
            self.0.handle_bus_state(now, state)
        }
    }

    impl ReceiveFilters for Counting {
        fn rx_filters(&self) -> RxFilters {
            self.1.set(self.1.get() + 1);
            self.0.rx_filters()
        }
        fn rx_filters_generation(&self) -> u32 {
            self.0.rx_filters_generation()
        }
    }

    /// Issue 19: the filters are computed only when the node's generation moved (boot, a COB-ID written,
    /// a reset communication), not on every pass: 200 SDO reads compute them never.
    #[test]
    fn filters_are_computed_only_when_the_generation_moves() {
        let node = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
        let shared = RefCell::new(Counting(node, std::cell::Cell::new(0)));
        let mut pass = Pass::default();
        let computed = || shared.borrow().1.get();
        let (_, f) = pass.run(&shared, Instant::ZERO, &mut |_| {});
        pass.installed(f.expect("boot: filters to install"));
        assert_eq!(computed(), 1);
        for i in 0..200 {
            pass.rx.push(Input::Frame(CanFrame::new(0x605, &[0x40, 0x18, 0x10, 0x01, 0, 0, 0, 0]).unwrap()));
            let (_, f) = pass.run(&shared, Instant::from_millis(1 + i), &mut |_| {});
            assert!(f.is_none());
        }
        assert_eq!(computed(), 1, "SDO reads change no COB-ID");
        assert_eq!(pass.tx.len(), 201);
        // 1016h:01 written: computed again (after the ObjectWritten event's observer ran), and returned.
        pass.rx.push(Input::Frame(CanFrame::new(0x605, &[0x23, 0x16, 0x10, 0x01, 0xF4, 0x01, 0x03, 0x00]).unwrap()));
        let (_, f) = pass.run(&shared, Instant::from_millis(300), &mut |_| {});
        assert!(f.is_some_and(|f| f.iter().any(|x| x.id == 0x703)));
        assert_eq!(computed(), 2);
        // A reopened socket: computed and returned again although nothing changed.
        pass.reinstall();
        let (_, f) = pass.run(&shared, Instant::from_millis(301), &mut |_| {});
        assert!(f.is_some());
        assert_eq!(computed(), 3);
    }

    /// Error frames from the socket reach the node in order with the data frames (issue 22): a tx error
    /// passive (`CAN_ERR_CRTL`) raises 8120h (EEC-11), a bus-off in Operational is a communication error
    /// (ERR-13: Pre-operational), the restart sends 8140h (EEC-13) and the next frame clears it (EMCY-07).
    #[test]
    fn error_frames_from_the_socket_reach_the_node_in_order() {
        let node: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
        let shared = RefCell::new(node);
        let mut pass = Pass::default();
        pass.run(&shared, Instant::ZERO, &mut |_| {});
        pass.tx.clear();
        let error = |class: u32, d1: u8| {
            let f = socketcan::CanErrorFrame::new_error(class, &[0, d1, 0, 0, 0, 0, 0x80, 0]).unwrap();
            *AsRef::<libc::can_frame>::as_ref(&socketcan::CanFrame::Error(f))
        };
        let data = |id: u16, d: &[u8]| raw_frame(&CanFrame::new(id, d).unwrap()).unwrap();
        let mut adapter = Vec::new();
        let raw = [data(0x000, &[0x01, 0x05]), error(0x204, 0x20), error(0x040, 0)];
        pass.take_raw(&raw, &mut |o| adapter.push(format!("{o:?}")));
        assert_eq!(adapter, ["Adapter(Controller(ErrorPassive))", "Adapter(BusOff)"]);
        pass.run(&shared, Instant::from_millis(1), &mut |_| {});
        let emcys: Vec<[u8; 8]> = pass.tx.drain(..).filter(|f| f.cob_id() == 0x085).map(|f| f.padded()).collect();
        assert_eq!(emcys, [[0x20, 0x81, 0x11, 0, 0, 0, 0, 0]]);
        assert_eq!(shared.borrow().state(), canopen_core::NmtState::PreOperational);
        pass.take_raw(&[error(0x100, 0), data(0x701, &[0x05])], &mut |_| {});
        pass.run(&shared, Instant::from_millis(2), &mut |_| {});
        let emcys: Vec<[u8; 8]> = pass.tx.drain(..).map(|f| f.padded()).collect();
        assert_eq!(
            emcys,
            [[0x40, 0x81, 0x11, 0, 0, 0, 0, 0], [0, 0, 0x11, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0, 0, 0]],
            "8140h, 8120h cleared, 8140h cleared by the frame after the restart"
        );
        assert_eq!(shared.borrow().error_register(), 0);
    }
}
