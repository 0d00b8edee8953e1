//! Heartbeat producer (1017h) and consumer (1016h) (HB-01..HB-14).
//!
//! Implemented: HB-02 (frame), HB-03 (cyclic in Pre-operational, Operational and Stopped), HB-04 (the boot-up
//! counts as the first heartbeat; a written period takes effect at once: the next heartbeat is one new
//! period after the write), HB-07/HB-08 (entry layout and inactive entries), HB-10 (monitoring starts with
//! the first heartbeat), HB-11 (one missed consumer time is a time-out; resolved when heartbeats resume or the
//! entry is disabled; state changes and a re-boot of the producer are reported). HB-05 (never heartbeat and
//! guarding at once) and HB-13 (time-out is a communication error handled per 1029h) are enforced by `Node`.
//! HB-09 (duplicate node) is enforced by `profile::CommParams::set_consumer`. HB-12/HB-14 are advice.

use crate::sizes::{Sizes, Slots};
use crate::time::{Deadline, Duration, Instant};
use crate::wire::error_control::StateCode;

/// Decoded 1016h consumer heartbeat entry (HB-07: bits 23–16 node-ID, bits 15–0 time in ms).
///
/// ```
/// use canopen_core::heartbeat::ConsumerEntry;
/// let e = ConsumerEntry::from_raw(0x0002_0064);
/// assert_eq!((e.node_id, e.time_ms), (2, 100));
/// assert!(e.is_active());
/// assert!(!ConsumerEntry::from_raw(0x0080_0064).is_active()); // node 128: inactive (HB-08)
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ConsumerEntry {
    /// Monitored node-ID.
    pub node_id: u8,
    /// Consumer time in ms.
    pub time_ms: u16,
}

impl ConsumerEntry {
    /// Decodes the UNSIGNED32 of a 1016h sub-entry (bits 31–24 are reserved and ignored).
    pub const fn from_raw(raw: u32) -> Self {
        ConsumerEntry { node_id: (raw >> 16) as u8, time_ms: raw as u16 }
    }

    /// Encodes as the UNSIGNED32 of a 1016h sub-entry.
    ///
    /// ```
    /// # use canopen_core::heartbeat::ConsumerEntry;
    /// assert_eq!(ConsumerEntry { node_id: 7, time_ms: 4000 }.raw(), 0x0007_0FA0);
    /// ```
    pub const fn raw(self) -> u32 {
        ((self.node_id as u32) << 16) | self.time_ms as u32
    }

    /// Active unless the time is 0 or the node-ID is 0 or above 127 (HB-08).
    pub const fn is_active(self) -> bool {
        self.time_ms != 0 && self.node_id >= 1 && self.node_id <= 127
    }
}

/// The heartbeat producer: when the next heartbeat is due.
///
/// ```
/// use canopen_core::{heartbeat::HeartbeatProducer, Instant};
/// let mut p = HeartbeatProducer::new();
/// p.start(Instant::ZERO, 100); // boot-up sent at 0 counts as the first heartbeat
/// assert_eq!(p.poll_timeout(), Some(Instant::from_millis(100)));
/// assert!(!p.due(Instant::from_millis(99)));
/// assert!(p.due(Instant::from_millis(100)));
/// assert_eq!(p.poll_timeout(), Some(Instant::from_millis(200)));
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct HeartbeatProducer {
    /// 1017h, ms (2 bytes kept instead of an 8-byte `Duration`).
    period_ms: u16,
    next: Deadline,
}

impl HeartbeatProducer {
    /// A producer that is off.
    pub const fn new() -> Self {
        HeartbeatProducer { period_ms: 0, next: Deadline::NONE }
    }

    /// Starts (or stops, for 0) the producer at the boot-up sent at `now` (HB-04).
    pub fn start(&mut self, now: Instant, period_ms: u16) {
        self.set_period(now, period_ms);
    }

    /// Applies a new 1017h value written at `now`: takes effect at once (HB-04), 0 stops the producer.
    pub fn set_period(&mut self, now: Instant, period_ms: u16) {
        self.period_ms = period_ms;
        self.next.set((period_ms != 0).then(|| now + self.period()));
    }

    fn period(&self) -> Duration {
        Duration::from_millis(u64::from(self.period_ms))
    }

    /// Whether the producer is running.
    pub const fn is_active(&self) -> bool {
        self.next.get().is_some()
    }

    /// The instant the next heartbeat is due.
    pub const fn poll_timeout(&self) -> Option<Instant> {
        self.next.get()
    }

    /// [`poll_timeout`](Self::poll_timeout) as a [`Deadline`], for the node's minimum over its services.
    pub(crate) const fn deadline(&self) -> Deadline {
        self.next
    }

    /// Whether a heartbeat is due at `now`; if so, schedules the next one. A runner that fell behind by more
    /// than a period sends one heartbeat, not a burst.
    pub fn due(&mut self, now: Instant) -> bool {
        if !self.next.passed(now) {
            return false;
        }
        let following = self.next.instant() + self.period();
        self.next = Deadline::at(if following <= now { now + self.period() } else { following });
        true
    }
}

/// What the consumer knows about one monitored producer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Monitor {
    /// No heartbeat seen yet: no time-out (HB-10).
    Waiting,
    /// Heartbeats arriving; the next one is due by the slot's deadline.
    Alive { state: StateCode },
    /// The consumer time elapsed without a heartbeat (HB-11).
    TimedOut { state: StateCode },
}

/// One 1016h entry and its monitoring state (opaque: what a [`HeartbeatConsumer`] keeps per entry).
///
/// ```
/// use canopen_core::heartbeat::ConsumerSlot;
/// let slots = [ConsumerSlot::OFF; 2]; // what `ConsumerSizes::NO_CONSUMERS` holds for two entries
/// assert_eq!(slots[0], ConsumerSlot::OFF);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ConsumerSlot {
    entry: ConsumerEntry,
    monitor: Monitor,
    /// While [`Monitor::Alive`]: when the next heartbeat is due (beside the enum, not in it, so a slot is
    /// 16 bytes rather than 24). [`Deadline::NONE`] in every other state (a slot leaves `Alive` only by
    /// [`HeartbeatConsumer::handle_timeout`], which clears it, or by becoming a new waiting slot), so the
    /// time-out search needs no test of the state. The earliest deadline keeps its test: without it LLVM
    /// unrolls the fold over the slots (footprint.sh node +284 B).
    deadline: Deadline,
}

impl ConsumerSlot {
    /// An entry that monitors nothing.
    pub const OFF: ConsumerSlot = ConsumerSlot::waiting(ConsumerEntry { node_id: 0, time_ms: 0 });

    const fn waiting(entry: ConsumerEntry) -> Self {
        ConsumerSlot { entry, monitor: Monitor::Waiting, deadline: Deadline::NONE }
    }
}

/// How many 1016h consumer entries a node has, as the consumer's storage type (see [`crate::sizes`]);
/// implemented for [`Sizes`].
///
/// ```
/// use canopen_core::{heartbeat::ConsumerSizes, Sizes};
/// assert_eq!(<Sizes<3> as ConsumerSizes>::HB, 3);
/// ```
pub trait ConsumerSizes {
    /// The number of consumer entries, `HB`.
    const HB: usize;
    /// `[ConsumerSlot; HB]`.
    type Consumers: Slots<ConsumerSlot> + Clone + core::fmt::Debug + PartialEq + Eq;
    /// `[u32; HB]`: the raw 1016h values.
    type ConsumerTimes: Slots<u32> + Copy + core::fmt::Debug + PartialEq + Eq;
    /// Every entry off.
    const NO_CONSUMERS: Self::Consumers;
    /// Every raw value 0 (entry unused).
    const ZERO_TIMES: Self::ConsumerTimes;
}

impl<const HB: usize, const TXQ: usize, const EVQ: usize, const RPDO: usize, const TPDO: usize> ConsumerSizes
    for Sizes<HB, TXQ, EVQ, RPDO, TPDO>
{
    const HB: usize = HB;
    type Consumers = [ConsumerSlot; HB];
    type ConsumerTimes = [u32; HB];
    const NO_CONSUMERS: [ConsumerSlot; HB] = [ConsumerSlot::OFF; HB];
    const ZERO_TIMES: [u32; HB] = [0; HB];
}

/// A heartbeat consumer observation, reported to the application (HB-11).
///
/// ```
/// use canopen_core::heartbeat::ConsumerEvent;
/// let e = ConsumerEvent::Timeout { node: 2 };
/// assert!(matches!(e, ConsumerEvent::Timeout { node: 2 }));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ConsumerEvent {
    /// The first heartbeat of a monitored node arrived: monitoring started (HB-10).
    Started {
        /// The producer's node-ID.
        node: u8,
        /// Its reported state.
        state: StateCode,
    },
    /// A monitored node reported a new NMT state.
    StateChanged {
        /// The producer's node-ID.
        node: u8,
        /// The previous state.
        from: StateCode,
        /// The new state.
        to: StateCode,
    },
    /// A monitored node sent its boot-up message again: it was reset or power-cycled.
    Rebooted {
        /// The producer's node-ID.
        node: u8,
    },
    /// Heartbeat event "occurred / time-out": no heartbeat within the consumer time (HB-11).
    Timeout {
        /// The producer's node-ID.
        node: u8,
    },
    /// Heartbeat event "resolved": heartbeats arrived again after a time-out (HB-11).
    Resumed {
        /// The producer's node-ID.
        node: u8,
        /// Its reported state.
        state: StateCode,
    },
}

/// The heartbeat consumer with `Z::HB` entries (1016h:01..HB).
///
/// ```
/// # use canopen_core::Sizes;
/// use canopen_core::{heartbeat::{ConsumerEvent, HeartbeatConsumer}, Instant};
/// use canopen_core::wire::error_control::StateCode;
/// let mut c: HeartbeatConsumer<canopen_core::Sizes<4>> = HeartbeatConsumer::new();
/// c.configure(&[0x0002_0064, 0, 0, 0]); // node 2, 100 ms
/// assert_eq!(c.poll_timeout(), None); // nothing until the first heartbeat (HB-10)
/// let ev = c.handle_heartbeat(Instant::ZERO, 2, StateCode::PreOperational);
/// assert_eq!(ev, Some(ConsumerEvent::Started { node: 2, state: StateCode::PreOperational }));
/// assert_eq!(c.poll_timeout(), Some(Instant::from_millis(100)));
/// assert_eq!(c.handle_timeout(Instant::from_millis(100)), Some(ConsumerEvent::Timeout { node: 2 }));
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct HeartbeatConsumer<Z: ConsumerSizes = Sizes> {
    slots: Z::Consumers,
}

impl<Z: ConsumerSizes> Default for HeartbeatConsumer<Z> {
    fn default() -> Self {
        HeartbeatConsumer::new()
    }
}

impl<Z: ConsumerSizes> HeartbeatConsumer<Z> {
    /// A consumer with every entry off.
    pub const fn new() -> Self {
        HeartbeatConsumer { slots: Z::NO_CONSUMERS }
    }

    /// [`new`](Self::new) built slot by slot: the node's construction stores the slots in place, where the
    /// `const` array was a `.rodata` copy (16 B a slot) copied twice on its way into a `static` node.
    pub(crate) fn new_in_place() -> Self {
        HeartbeatConsumer { slots: Z::Consumers::from_fn(|_| ConsumerSlot::OFF) }
    }

    /// Loads every entry from the raw 1016h values (after reset communication).
    pub fn configure(&mut self, raw: &Z::ConsumerTimes) {
        for (slot, &r) in self.slots.as_mut().iter_mut().zip(raw.as_ref()) {
            *slot = ConsumerSlot::waiting(ConsumerEntry::from_raw(r));
        }
    }

    /// Applies a written entry (0-based `i`). A changed entry restarts monitoring: it waits for the next
    /// heartbeat of its node (HB-10); disabling it resolves a pending time-out (HB-11).
    pub fn set_entry(&mut self, i: usize, raw: u32) {
        if let Some(slot) = self.slots.as_mut().get_mut(i) {
            let entry = ConsumerEntry::from_raw(raw);
            if slot.entry != entry {
                *slot = ConsumerSlot::waiting(entry);
            }
        }
    }

    /// The last reported state of a monitored node, `None` while waiting for its first heartbeat or when the
    /// node is not monitored.
    ///
    /// ```
    /// # use canopen_core::Sizes;
    /// # use canopen_core::heartbeat::HeartbeatConsumer;
    /// let c: HeartbeatConsumer<canopen_core::Sizes<1>> = HeartbeatConsumer::new();
    /// assert_eq!(c.remote_state(3), None);
    /// ```
    pub fn remote_state(&self, node: u8) -> Option<StateCode> {
        self.slot(node).and_then(|s| match s.monitor {
            Monitor::Waiting => None,
            Monitor::Alive { state } | Monitor::TimedOut { state } => Some(state),
        })
    }

    /// Whether a monitored node is currently timed out.
    pub fn is_timed_out(&self, node: u8) -> bool {
        self.slot(node).is_some_and(|s| matches!(s.monitor, Monitor::TimedOut { .. }))
    }

    /// Whether any monitored node is currently timed out (the cause of EMCY 8130h from the consumer side).
    ///
    /// ```
    /// use canopen_core::{heartbeat::HeartbeatConsumer, Instant, Sizes};
    /// use canopen_core::wire::error_control::StateCode;
    /// let mut c: HeartbeatConsumer<Sizes<2>> = HeartbeatConsumer::new();
    /// c.configure(&[0x0002_0064, 0x0003_0064]);
    /// c.handle_heartbeat(Instant::ZERO, 2, StateCode::Operational);
    /// assert!(!c.any_timed_out());
    /// c.handle_timeout(Instant::from_millis(100));
    /// assert!(c.any_timed_out());
    /// c.handle_heartbeat(Instant::from_millis(150), 2, StateCode::Operational);
    /// assert!(!c.any_timed_out());
    /// ```
    pub fn any_timed_out(&self) -> bool {
        self.slots.as_ref().iter().any(|s| s.entry.is_active() && matches!(s.monitor, Monitor::TimedOut { .. }))
    }

    fn slot(&self, node: u8) -> Option<&ConsumerSlot> {
        self.slots.as_ref().iter().find(|s| s.entry.is_active() && s.entry.node_id == node)
    }

    /// A heartbeat (or boot-up) of `node` arrived at `now`. Returns what the application should hear, if
    /// anything. Heartbeats of nodes that no active entry monitors are ignored.
    pub fn handle_heartbeat(&mut self, now: Instant, node: u8, state: StateCode) -> Option<ConsumerEvent> {
        let slot = self.slots.as_mut().iter_mut().find(|s| s.entry.is_active() && s.entry.node_id == node)?;
        slot.deadline.set(Some(now + Duration::from_millis(u64::from(slot.entry.time_ms))));
        let previous = slot.monitor;
        slot.monitor = Monitor::Alive { state };
        match previous {
            Monitor::Waiting => Some(ConsumerEvent::Started { node, state }),
            Monitor::TimedOut { .. } => Some(ConsumerEvent::Resumed { node, state }),
            Monitor::Alive { state: from } if from == state => None,
            Monitor::Alive { .. } if state == StateCode::BootUp => Some(ConsumerEvent::Rebooted { node }),
            Monitor::Alive { state: from } => Some(ConsumerEvent::StateChanged { node, from, to: state }),
        }
    }

    /// The earliest consumer deadline.
    pub fn poll_timeout(&self) -> Option<Instant> {
        self.deadline().get()
    }

    /// [`poll_timeout`](Self::poll_timeout) as a [`Deadline`] (the minimum of the monitored entries'), for
    /// the node's minimum over its services.
    pub(crate) fn deadline(&self) -> Deadline {
        self.slots.as_ref().iter().fold(Deadline::NONE, |t, s| match s.monitor {
            Monitor::Alive { .. } => t.min(s.deadline),
            _ => t,
        })
    }

    /// Reports the first entry whose consumer time has elapsed at `now` (HB-11: one missed period is a
    /// time-out); call again until it returns `None`.
    pub fn handle_timeout(&mut self, now: Instant) -> Option<ConsumerEvent> {
        let slot = self.slots.as_mut().iter_mut().find(|s| s.deadline.passed(now))?; // only an `Alive` slot has a deadline
        if let Monitor::Alive { state } = slot.monitor {
            slot.monitor = Monitor::TimedOut { state };
            slot.deadline = Deadline::NONE;
        }
        Some(ConsumerEvent::Timeout { node: slot.entry.node_id })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::time::ms;

    /// HB-04: the boot-up is the first heartbeat; a written period takes effect at once; 0 stops.
    #[test]
    fn producer_period_change() {
        let mut p = HeartbeatProducer::new();
        p.start(ms(0), 0);
        assert!(!p.is_active());
        p.set_period(ms(30), 100);
        assert_eq!(p.poll_timeout(), Some(ms(130)));
        assert!(p.due(ms(130)));
        p.set_period(ms(150), 20);
        assert_eq!(p.poll_timeout(), Some(ms(170)));
        p.set_period(ms(160), 0);
        assert_eq!(p.poll_timeout(), None);
        assert!(!p.due(ms(1000)));
    }

    #[test]
    fn producer_does_not_burst_after_a_stall() {
        let mut p = HeartbeatProducer::new();
        p.start(ms(0), 10);
        assert!(p.due(ms(55)));
        assert!(!p.due(ms(55)));
        assert_eq!(p.poll_timeout(), Some(ms(65)));
    }

    /// HB-10, HB-11: start, state change, reboot, time-out, resume.
    #[test]
    fn consumer_lifecycle() {
        let mut c: HeartbeatConsumer<Sizes<2>> = HeartbeatConsumer::new();
        c.configure(&[0x0002_0064, 0x0007_0FA0]);
        assert_eq!(c.poll_timeout(), None);
        assert_eq!(c.handle_timeout(ms(10_000)), None); // node 7 never seen: no time-out (HB-10)
        let s = |st| c_state(st);
        assert_eq!(
            c.handle_heartbeat(ms(0), 2, StateCode::PreOperational),
            Some(ConsumerEvent::Started { node: 2, state: s(0x7F) })
        );
        assert_eq!(c.handle_heartbeat(ms(90), 2, StateCode::PreOperational), None);
        assert_eq!(
            c.handle_heartbeat(ms(180), 2, StateCode::Operational),
            Some(ConsumerEvent::StateChanged { node: 2, from: s(0x7F), to: s(0x05) })
        );
        assert_eq!(c.handle_timeout(ms(279)), None);
        assert_eq!(c.handle_timeout(ms(280)), Some(ConsumerEvent::Timeout { node: 2 }));
        assert!(c.is_timed_out(2));
        assert_eq!(c.handle_timeout(ms(1000)), None); // reported once
        assert_eq!(
            c.handle_heartbeat(ms(1000), 2, StateCode::Operational),
            Some(ConsumerEvent::Resumed { node: 2, state: s(0x05) })
        );
        assert_eq!(c.handle_heartbeat(ms(1010), 2, StateCode::BootUp), Some(ConsumerEvent::Rebooted { node: 2 }));
        assert_eq!(c.handle_heartbeat(ms(1010), 9, StateCode::BootUp), None); // not monitored
    }

    /// HB-08, HB-11: disabling an entry resolves and stops monitoring; re-enabling waits again.
    #[test]
    fn consumer_entry_changes() {
        let mut c: HeartbeatConsumer<Sizes<1>> = HeartbeatConsumer::new();
        c.set_entry(0, 0x0002_0064);
        c.handle_heartbeat(ms(0), 2, StateCode::Stopped);
        assert_eq!(c.handle_timeout(ms(100)), Some(ConsumerEvent::Timeout { node: 2 }));
        c.set_entry(0, 0);
        assert!(!c.is_timed_out(2));
        assert_eq!(c.poll_timeout(), None);
        c.set_entry(0, 0x0080_0064); // node 128: inactive
        assert_eq!(c.handle_heartbeat(ms(0), 0x80, StateCode::Stopped), None);
        c.set_entry(5, 1); // no such entry: ignored, no panic
    }

    fn c_state(code: u8) -> StateCode {
        StateCode::from_code(code).unwrap()
    }
}
