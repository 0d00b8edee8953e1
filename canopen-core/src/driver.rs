//! Executor-agnostic async driver: one `run` future that waits for a received frame, the node's next
//! deadline, or a wake-up from the application, feeds the node, and sends what it produces. No fixed tick,
//! no executor dependency: it runs on tokio (through `canopen-socketcan`), on embassy, or on any `block_on`.
//!
//! The node lives in a [`Shared`] cell so that other tasks or interrupts can change process values and
//! trigger event-driven TPDOs while the driver runs; they then call the [`Wake`] source so that the driver
//! sends what they queued without waiting for the next deadline:
//!
//! ```text
//! // application task                          // driver task
//! shared.lock(|node| {                         run(&shared, &mut rx, &mut tx, &mut timer, &wake, |ev| ...)
//!     node.app_mut().inputs[0] = read_pins();
//!     // node.trigger_tpdo(0) once PDOs exist
//! });
//! wake.signal();
//! ```
//!
//! The lock is held only while the node computes, never across an `.await`: a frame is copied out under the
//! lock, sent after it is released, and removed from the node's queue under the next lock once it is on the
//! bus. So `run` is cancel-safe: dropping its future between any two polls (a `select!` that picks another
//! branch, a task that is aborted) loses no frame and no event; the next `run` carries on where it stopped.

use core::convert::Infallible;
use core::future::{poll_fn, Future};
use core::pin::pin;
use core::task::Poll;

use crate::bus::BusState;
use crate::event::Event;
use crate::frame::CanFrame;
use crate::node::SansIo;
use crate::time::Instant;

/// Sends one frame (a CAN driver's transmit).
pub trait CanTx {
    /// The driver's error.
    type Error;
    /// Sends `frame`, waiting for room in the controller or socket.
    fn transmit(&mut self, frame: &CanFrame) -> impl Future<Output = Result<(), Self::Error>>;
}

/// Receives one frame. The future must be cancel-safe: dropping it before it completes loses no frame
/// (tokio's and embassy's CAN receive futures are).
pub trait CanRx {
    /// The driver's error.
    type Error;
    /// Waits for the next frame.
    fn receive(&mut self) -> impl Future<Output = Result<CanFrame, Self::Error>>;
    /// Waits for the next frame or change of the controller's state ([`BusState`]: error passive, bus-off,
    /// recovered, ...), which the driver hands to the node (EMCY 8120h/8140h, 1029h:01 on bus-off; see
    /// [`crate::bus`]). The default reports frames only; an adapter that sees the controller's state
    /// overrides it. Must be cancel-safe like [`receive`](CanRx::receive).
    ///
    /// ```
    /// use canopen_core::{bus::BusState, driver::{CanRx, Received}, CanFrame};
    /// struct Passive;
    /// impl CanRx for Passive {
    ///     type Error = ();
    ///     async fn receive(&mut self) -> Result<CanFrame, ()> { core::future::pending().await }
    ///     async fn receive_event(&mut self) -> Result<Received, ()> { Ok(Received::Bus(BusState::ErrorPassive)) }
    /// }
    /// ```
    fn receive_event(&mut self) -> impl Future<Output = Result<Received, Self::Error>> {
        async { self.receive().await.map(Received::Frame) }
    }
}

/// What [`CanRx::receive_event`] delivers.
///
/// ```
/// use canopen_core::{bus::BusState, driver::Received};
/// assert_ne!(Received::Bus(BusState::BusOff), Received::Bus(BusState::Recovered));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Received {
    /// A frame from the bus.
    Frame(CanFrame),
    /// The controller's state changed.
    Bus(BusState),
}

/// The node's clock.
pub trait Timer {
    /// The current instant on a monotonic clock.
    fn now(&self) -> Instant;
    /// Completes at `deadline` (at once if it has passed).
    fn sleep_until(&mut self, deadline: Instant) -> impl Future<Output = ()>;
}

/// Short, blocking, exclusive access to the node from several tasks (a mutex, a critical section, or a
/// `RefCell` on a single-threaded executor).
pub trait Shared<N> {
    /// Runs `f` with exclusive access to the node.
    fn lock<R>(&self, f: impl FnOnce(&mut N) -> R) -> R;
}

impl<N> Shared<N> for core::cell::RefCell<N> {
    fn lock<R>(&self, f: impl FnOnce(&mut N) -> R) -> R {
        f(&mut self.borrow_mut())
    }
}

/// A wake-up source the application signals after it changed the node from another task.
pub trait Wake {
    /// Completes when the application signalled.
    fn wait(&self) -> impl Future<Output = ()>;
}

/// A wake-up source that never fires, for applications that only change the node from the driver's own
/// event callback.
///
/// ```
/// use canopen_core::driver::NoWake;
/// let _w = NoWake;
/// ```
#[derive(Debug, Clone, Copy, Default)]
pub struct NoWake;

impl Wake for NoWake {
    fn wait(&self) -> impl Future<Output = ()> {
        core::future::pending()
    }
}

/// Why [`run`] stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum DriverError<R, T> {
    /// Receiving failed.
    Receive(R),
    /// Sending failed.
    Transmit(T),
}

/// ```
/// use canopen_core::driver::DriverError;
/// let e: DriverError<&str, &str> = DriverError::Receive("bus off");
/// assert_eq!(e.to_string(), "CAN receive failed: bus off");
/// ```
impl<R: core::fmt::Display, T: core::fmt::Display> core::fmt::Display for DriverError<R, T> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            DriverError::Receive(e) => write!(f, "CAN receive failed: {e}"),
            DriverError::Transmit(e) => write!(f, "CAN transmit failed: {e}"),
        }
    }
}

/// The CAN driver's own error is the [`source`](core::error::Error::source).
///
/// ```
/// use canopen_core::{abort::AbortCode, driver::DriverError};
/// use core::error::Error;
/// let e: DriverError<AbortCode, core::convert::Infallible> = DriverError::Receive(AbortCode::SdoTimeout);
/// assert!(e.source().is_some());
/// ```
impl<R, T> core::error::Error for DriverError<R, T>
where
    R: core::error::Error + 'static,
    T: core::error::Error + 'static,
{
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            DriverError::Receive(e) => Some(e),
            DriverError::Transmit(e) => Some(e),
        }
    }
}

/// Runs the node until the CAN driver fails. Every event goes to `on_event` (outside the lock). The node's
/// state is in `shared`, so after an error the caller can recover the interface and call `run` again
/// without losing anything.
///
/// ```
/// use core::{cell::RefCell, future::Future};
/// use canopen_core::{profile::NodeConfig, driver::*, node::{NoApplication, Node}, CanFrame, Instant, NodeId};
///
/// struct Wire(std::vec::Vec<CanFrame>);
/// impl CanTx for Wire {
///     type Error = ();
///     async fn transmit(&mut self, f: &CanFrame) -> Result<(), ()> { self.0.push(*f); Ok(()) }
/// }
/// struct Silent;
/// impl CanRx for Silent {
///     type Error = ();
///     async fn receive(&mut self) -> Result<CanFrame, ()> { core::future::pending().await }
/// }
/// /// Simulated time: a sleep jumps the clock to its deadline and yields once, as a real timer would.
/// struct Sim(Instant);
/// impl Timer for Sim {
///     fn now(&self) -> Instant { self.0 }
///     fn sleep_until(&mut self, t: Instant) -> impl core::future::Future<Output = ()> {
///         let mut slept = false;
///         core::future::poll_fn(move |_| {
///             if slept { return core::task::Poll::Ready(()) }
///             slept = true;
///             self.0 = self.0.max(t);
///             core::task::Poll::Pending
///         })
///     }
/// }
///
/// let node: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), NodeConfig { heartbeat_time_ms: 10, ..NodeConfig::DEFAULT }, NoApplication);
/// let shared = RefCell::new(node);
/// let (mut rx, mut tx, mut timer) = (Silent, Wire(vec![]), Sim(Instant::ZERO));
/// {
///     let mut fut = core::pin::pin!(run(&shared, &mut rx, &mut tx, &mut timer, &NoWake, |_| {}));
///     let mut cx = core::task::Context::from_waker(core::task::Waker::noop());
///     for _ in 0..4 { let _ = fut.as_mut().poll(&mut cx); }
/// }
/// assert_eq!(tx.0[0], CanFrame::new(0x705, &[0]).unwrap()); // boot-up, then heartbeats every 10 ms
/// assert_eq!(tx.0[1], CanFrame::new(0x705, &[0x7F]).unwrap());
/// ```
pub async fn run<N, S, R, T, C, W>(
    shared: &S,
    rx: &mut R,
    tx: &mut T,
    timer: &mut C,
    wake: &W,
    mut on_event: impl FnMut(Event),
) -> Result<Infallible, DriverError<R::Error, T::Error>>
where
    N: SansIo,
    S: Shared<N>,
    R: CanRx,
    T: CanTx,
    C: Timer,
    W: Wake,
{
    loop {
        // Service: the node acts on the time, then hands out its events and sends its frames. Cancel-safe: a
        // frame leaves the node's queue only once `transmit` returned it sent ([`SansIo::peek_transmit`], then
        // [`SansIo::transmitted`] under the next lock), and events are handed out in the same poll that takes
        // them, with no `.await` between; a frame whose `transmit` failed stays first in the queue. Inline
        // here rather than an `async fn` of its own, as is the wait below: each nested future is a state
        // machine of its own in the task (footprint.sh: see the commit).
        let (mut timeout, mut sent) = (Some(timer.now()), None);
        let deadline = loop {
            match shared.lock(|n| next_work(n, timeout.take(), sent.take())) {
                Work::Event(e) => {
                    crate::trace::event(&e);
                    on_event(e);
                }
                Work::Frame(f) => {
                    #[cfg(any(feature = "defmt", feature = "log"))]
                    crate::trace::frame("tx", &f);
                    if let Err(e) = tx.transmit(&f).await {
                        crate::trace::driver_error(false);
                        return Err(DriverError::Transmit(e));
                    }
                    sent = Some(f);
                }
                Work::Idle(deadline) => break deadline,
            }
        };
        // Wait for the first of a frame, the deadline and an application wake-up. No deadline, no sleep (an
        // Option, not an async block around `pending()`: one state machine less).
        let woken = {
            let mut frame = pin!(rx.receive_event());
            let mut sleep = pin!(deadline.map(|t| timer.sleep_until(t)));
            let mut app = pin!(wake.wait());
            poll_fn(|cx| poll_woken(cx, frame.as_mut(), sleep.as_mut(), app.as_mut())).await
        };
        // A frame and a controller state share one clock read and one lock: they differ only in the call.
        match woken {
            Some(Ok(received)) => {
                #[cfg(any(feature = "defmt", feature = "log"))]
                if let Received::Frame(frame) = &received {
                    crate::trace::frame("rx", frame);
                }
                let now = timer.now();
                shared.lock(|n| match received {
                    Received::Frame(frame) => n.handle_frame(now, &frame),
                    Received::Bus(state) => n.handle_bus_state(now, state),
                });
            }
            Some(Err(e)) => {
                crate::trace::driver_error(true);
                return Err(DriverError::Receive(e));
            }
            None => {} // the deadline or an application wake-up
        }
    }
}

/// What the node has for the driver, one item per lock: nothing is batched in the future, so its state
/// stays small (a batch of 8 events was 192 B of task storage on a Cortex-M), and events come before frames.
enum Work {
    Event(Event),
    Frame(CanFrame),
    /// Nothing to hand out or send: the node's next deadline, what the driver sleeps until.
    Idle(Option<Instant>),
}

/// One step of the service, under the lock: the time passes in first (`timeout`, once per service), the
/// frame `sent` last is taken out of the queue, then the next event or frame. The deadline only once
/// nothing is left to send: computing it per frame sent was the minimum over every service each time
/// (about 70 instructions).
fn next_work<N: SansIo>(n: &mut N, timeout: Option<Instant>, sent: Option<CanFrame>) -> Work {
    if let Some(now) = timeout {
        n.handle_timeout(now);
    }
    if let Some(f) = sent {
        n.transmitted(&f);
    }
    // Both asked every time (the peek reads the queue head, no side effect): one branch less than asking
    // for the frame only when there is no event (footprint.sh, node: 72 B).
    match (n.poll_event(), n.peek_transmit()) {
        (Some(e), _) => Work::Event(e),
        (None, Some(f)) => Work::Frame(f),
        (None, None) => Work::Idle(n.poll_timeout()),
    }
}

/// Polls a frame, the deadline and an application wake-up, in that order: the receive's result, or `None` for
/// the other two (the driver does the same after either: a service step; an enum of three cases was 32 B more
/// of the node firmware's flash).
fn poll_woken<F: Future, D: Future, A: Future>(
    cx: &mut core::task::Context<'_>,
    frame: core::pin::Pin<&mut F>,
    sleep: core::pin::Pin<&mut Option<D>>,
    app: core::pin::Pin<&mut A>,
) -> Poll<Option<F::Output>> {
    if let Poll::Ready(r) = frame.poll(cx) {
        return Poll::Ready(Some(r));
    }
    if sleep.as_pin_mut().is_some_and(|s| s.poll(cx).is_ready()) {
        return Poll::Ready(None);
    }
    if app.poll(cx).is_ready() {
        return Poll::Ready(None);
    }
    Poll::Pending
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::node::{NoApplication, Node};
    use crate::profile::NodeConfig;
    use crate::NodeId;
    use core::cell::{Cell, RefCell};
    use core::task::{Context, Waker};
    use std::collections::VecDeque;
    use std::vec::Vec as StdVec;

    struct Wire<'a>(&'a RefCell<StdVec<(Instant, CanFrame)>>, &'a Cell<Instant>);
    impl CanTx for Wire<'_> {
        type Error = ();
        async fn transmit(&mut self, f: &CanFrame) -> Result<(), ()> {
            self.0.borrow_mut().push((self.1.get(), *f));
            Ok(())
        }
    }
    struct Inbox<'a>(&'a RefCell<VecDeque<CanFrame>>);
    impl CanRx for Inbox<'_> {
        type Error = &'static str;
        fn receive(&mut self) -> impl Future<Output = Result<CanFrame, &'static str>> {
            poll_fn(|_| match self.0.borrow_mut().pop_front() {
                Some(f) if f.cob_id() == 0x7FF => Poll::Ready(Err("bus off")),
                Some(f) => Poll::Ready(Ok(f)),
                None => Poll::Pending,
            })
        }
    }
    /// Simulated time: a sleep jumps the clock to its deadline and yields once, as a real timer would.
    struct Sim<'a>(&'a Cell<Instant>);
    impl Timer for Sim<'_> {
        fn now(&self) -> Instant {
            self.0.get()
        }
        fn sleep_until(&mut self, t: Instant) -> impl Future<Output = ()> {
            let clock = self.0;
            let mut slept = false;
            poll_fn(move |_| {
                if slept {
                    return Poll::Ready(());
                }
                slept = true;
                clock.set(clock.get().max(t));
                Poll::Pending
            })
        }
    }
    struct Flag<'a>(&'a Cell<bool>);
    impl Wake for Flag<'_> {
        fn wait(&self) -> impl Future<Output = ()> {
            poll_fn(|_| if self.0.replace(false) { Poll::Ready(()) } else { Poll::Pending })
        }
    }

    /// A transmitter whose mailbox is busy at every other attempt (the attempt returns `Pending` once), so that
    /// a send is an await point where the driver can be dropped. The state is the wire's, not the future's: a
    /// send attempted again after a drop finds the mailbox free, as real hardware would.
    struct SlowWire<'a>(&'a RefCell<StdVec<(Instant, CanFrame)>>, &'a Cell<Instant>, Cell<bool>);
    impl CanTx for SlowWire<'_> {
        type Error = ();
        fn transmit(&mut self, f: &CanFrame) -> impl Future<Output = Result<(), ()>> {
            let (log, clock, busy, f) = (self.0, self.1, &self.2, *f);
            poll_fn(move |_| {
                if !busy.replace(false) {
                    busy.set(true); // the next frame finds it busy
                    log.borrow_mut().push((clock.get(), f));
                    return Poll::Ready(Ok(()));
                }
                Poll::Pending
            })
        }
    }
    /// Frames that arrive at given times: `receive` is ready once the simulated clock has reached them.
    struct Timed<'a>(&'a RefCell<VecDeque<(Instant, CanFrame)>>, &'a Cell<Instant>);
    impl CanRx for Timed<'_> {
        type Error = ();
        fn receive(&mut self) -> impl Future<Output = Result<CanFrame, ()>> {
            poll_fn(|_| {
                let mut q = self.0.borrow_mut();
                match q.front() {
                    Some((t, _)) if *t <= self.1.get() => Poll::Ready(Ok(q.pop_front().unwrap().1)),
                    _ => Poll::Pending,
                }
            })
        }
    }

    /// Simulated time that stops at the next frame's arrival: a sleep moves the clock to its deadline or to
    /// the arrival of the next frame of `Timed`, whichever is first, so every frame is handled at its own time
    /// whatever the polls look like.
    struct SimTo<'a>(&'a Cell<Instant>, &'a RefCell<VecDeque<(Instant, CanFrame)>>);
    impl Timer for SimTo<'_> {
        fn now(&self) -> Instant {
            self.0.get()
        }
        fn sleep_until(&mut self, t: Instant) -> impl Future<Output = ()> {
            let (clock, inbox) = (self.0, self.1);
            poll_fn(move |_| {
                if clock.get() >= t {
                    return Poll::Ready(());
                }
                let arrival = inbox.borrow().front().map_or(t, |(a, _)| *a);
                clock.set(clock.get().max(t.min(arrival)));
                Poll::Pending
            })
        }
    }

    /// What a run sent (with the times) and handed out, driving a fresh `run` future that is dropped after
    /// every `polls` polls (`usize::MAX`: never dropped), until the simulated clock reaches 1 s.
    fn session(polls: usize) -> (StdVec<(Instant, CanFrame)>, StdVec<Event>) {
        let clock = Cell::new(Instant::ZERO);
        let sent = RefCell::new(StdVec::new());
        let at = |ms, id, data: &[u8]| (Instant::from_millis(ms), CanFrame::new(id, data).unwrap());
        let inbox = RefCell::new(VecDeque::from([
            at(150, 0x000, &[0x01, 0x05]),                               // NMT start
            at(250, 0x605, &[0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0]),       // SDO upload 1000h
            at(260, 0x605, &[0x2B, 0x17, 0x10, 0x00, 0x32, 0x00, 0, 0]), // 1017h = 50 ms
            at(270, 0x605, &[0x40, 0x08, 0x10, 0x00, 0, 0, 0, 0]),       // segmented upload 1008h
            at(280, 0x605, &[0x60, 0, 0, 0, 0, 0, 0, 0]),                // its first segment
            at(600, 0x000, &[0x80, 0x05]),                               // NMT enter pre-operational
        ]));
        let cfg = NodeConfig { heartbeat_time_ms: 100, ..NodeConfig::DEFAULT };
        let shared = RefCell::new(Node::<NoApplication>::new(NodeId::new(5).unwrap(), cfg, NoApplication));
        let mut events = StdVec::new();
        let (mut rx, mut tx, mut timer) =
            (Timed(&inbox, &clock), SlowWire(&sent, &clock, Cell::new(true)), SimTo(&clock, &inbox));
        let mut cx = Context::from_waker(Waker::noop());
        while clock.get() < Instant::from_millis(1000) {
            let mut fut = pin!(run(&shared, &mut rx, &mut tx, &mut timer, &NoWake, |e| events.push(e)));
            for _ in 0..polls {
                assert!(fut.as_mut().poll(&mut cx).is_pending());
                if clock.get() >= Instant::from_millis(1000) {
                    break;
                }
            }
        }
        (sent.into_inner(), events)
    }

    /// Issue "cancel safety": dropping the driver's future between any two polls loses no frame and no event,
    /// and sends none twice: the frames (with their times) and events equal those of a run never dropped,
    /// whether it is dropped after every poll, every 2nd, ... every 7th.
    #[test]
    fn dropping_run_between_any_two_polls_loses_nothing() {
        let (frames, events) = session(usize::MAX);
        // The reference did work: boot-up, heartbeats (100 ms, then 50 ms), 3 SDO answers, state changes.
        assert!(frames.len() > 15, "{frames:?}");
        assert_eq!(frames.iter().filter(|(_, f)| f.cob_id() == 0x585).count(), 4);
        assert!(events.len() >= 3, "{events:?}");
        for polls in 1..=7 {
            let (f, e) = session(polls);
            assert_eq!(f, frames, "frames, dropped after every {polls} polls");
            assert_eq!(e, events, "events, dropped after every {polls} polls");
        }
    }

    /// A controller that reports error passive once (an adapter overriding `receive_event`).
    struct GoesPassive(bool);
    impl CanRx for GoesPassive {
        type Error = ();
        fn receive(&mut self) -> impl Future<Output = Result<CanFrame, ()>> {
            core::future::pending()
        }
        fn receive_event(&mut self) -> impl Future<Output = Result<Received, ()>> {
            let first = core::mem::take(&mut self.0);
            poll_fn(move |_| if first { Poll::Ready(Ok(Received::Bus(BusState::ErrorPassive))) } else { Poll::Pending })
        }
    }

    /// EEC-11 through the driver: a controller state an adapter reports reaches the node, which sends EMCY
    /// 8120h (error passive) with 1001h bit 4 (communication error) set.
    #[test]
    fn a_bus_state_from_the_adapter_reaches_the_node_eec_11() {
        let clock = Cell::new(Instant::ZERO);
        let sent = RefCell::new(StdVec::new());
        let shared =
            RefCell::new(Node::<NoApplication>::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication));
        let (mut rx, mut tx, mut timer) = (GoesPassive(true), Wire(&sent, &clock), Sim(&clock));
        {
            let mut fut = pin!(run(&shared, &mut rx, &mut tx, &mut timer, &NoWake, |_| {}));
            let mut cx = Context::from_waker(Waker::noop());
            for _ in 0..3 {
                assert!(fut.as_mut().poll(&mut cx).is_pending());
            }
        }
        let frames: StdVec<CanFrame> = sent.borrow().iter().map(|(_, f)| *f).collect();
        assert_eq!(
            frames,
            [CanFrame::new(0x705, &[0]).unwrap(), CanFrame::new(0x085, &[0x20, 0x81, 0x11, 0, 0, 0, 0, 0]).unwrap()]
        );
    }

    /// The driver sleeps exactly until each deadline, handles received frames at once, sends what an
    /// application queued after a wake-up, and returns the receive error with the node intact.
    #[test]
    fn runs_the_node_on_simulated_time() {
        let clock = Cell::new(Instant::ZERO);
        let sent = RefCell::new(StdVec::new());
        let inbox = RefCell::new(VecDeque::new());
        let woke = Cell::new(false);
        let cfg = NodeConfig { heartbeat_time_ms: 100, ..NodeConfig::DEFAULT };
        let node: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), cfg, NoApplication);
        let shared = RefCell::new(node);
        let mut events = StdVec::new();
        let (mut rx, mut tx, mut timer, wake) = (Inbox(&inbox), Wire(&sent, &clock), Sim(&clock), Flag(&woke));
        let result = {
            let mut fut = pin!(run(&shared, &mut rx, &mut tx, &mut timer, &wake, |e| events.push(e)));
            let mut cx = Context::from_waker(Waker::noop());
            macro_rules! poll_n {
                ($fut:expr, $n:expr) => {{
                    let mut out = None;
                    for _ in 0..$n {
                        if let Poll::Ready(r) = $fut.as_mut().poll(&mut cx) {
                            out = Some(r);
                            break;
                        }
                    }
                    out
                }};
            }
            assert!(poll_n!(fut, 3).is_none()); // boot-up at 0, heartbeats at 100, 200
            inbox.borrow_mut().push_back(CanFrame::new(0x000, &[0x01, 0x05]).unwrap()); // NMT start
            assert!(poll_n!(fut, 2).is_none());
            // Another task changes the node and wakes the driver.
            shared.lock(|n: &mut Node<NoApplication>| n.set_heartbeat_time(clock.get(), 0));
            woke.set(true);
            assert!(poll_n!(fut, 2).is_none());
            inbox.borrow_mut().push_back(CanFrame::new(0x7FF, &[]).unwrap()); // the test's "bus off"
            poll_n!(fut, 2)
        };
        assert_eq!(result, Some(Err(DriverError::Receive("bus off"))));
        let log: StdVec<(u64, u8)> = sent.borrow().iter().map(|(t, f)| (t.as_micros() / 1000, f.data()[0])).collect();
        // Boot-up, two Pre-operational heartbeats; the start arrives while the clock sleeps towards 300 ms, so
        // the 300 ms heartbeat already says Operational; after 1017h = 0 nothing more is sent.
        assert_eq!(log, [(0, 0x00), (100, 0x7F), (200, 0x7F), (300, 0x05), (400, 0x05)]);
        assert_eq!(shared.borrow().state(), crate::NmtState::Operational);
        assert!(events.contains(&Event::StateChanged {
            from: crate::NmtState::PreOperational,
            to: crate::NmtState::Operational
        }));
    }
}
