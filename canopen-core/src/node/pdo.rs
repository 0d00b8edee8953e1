//! The node's PDO, SYNC and TIME wiring: configuring the state machines from the communication parameters,
//! the receive paths and the SYNC/TPDO transmit paths.

use super::{Node, NodeSizes, PdoTable};
use crate::cob::CobIdEntry;
use crate::emcy::codes;
use crate::event::Event;
use crate::frame::CanFrame;
use crate::nmt::{NmtState, Service};
#[cfg(feature = "time")]
use crate::od::TimeOfDay;
use crate::od::{Merged, ObjectDictionary, PdoDir};
use crate::pdo::mapping::ResolvedMap;
#[cfg(feature = "mpdo")]
use crate::pdo::mpdo::AddressMode;
use crate::pdo::rpdo::{Rpdo, RxOutcome};
use crate::pdo::tpdo::{SyncAction, Tpdo};
use crate::profile::CommProfile;
use crate::storage::Storage;
use crate::sync::SyncInput;
use crate::time::{Deadline, Instant};
#[cfg(feature = "time")]
use crate::wire::time_stamp::TimeStamp;
use heapless::vec::VecStorage;

impl<A: ObjectDictionary, Z: NodeSizes, S: Storage> Node<A, Z, S> {
    /// Rebuilds TPDO `k` (`tx`, from 1800h+k / 1A00h+k) or RPDO `k` (1400h+k / 1600h+k) and the CAN-ID
    /// table of its direction: the mapping is resolved once here; a mapping that no longer resolves (e.g.
    /// loaded from storage for another firmware) leaves the PDO not valid. One function for both directions:
    /// the parameters' copy and the resolution are shared.
    pub(super) fn configure_pdo(&mut self, tx: bool, k: usize) {
        let p = &self.comm.params;
        let (comm, map, dir) = if tx {
            (p.tpdo_comm.as_ref().get(k), p.tpdo_map.as_ref().get(k), PdoDir::Tpdo)
        } else {
            (p.rpdo_comm.as_ref().get(k), p.rpdo_map.as_ref().get(k), PdoDir::Rpdo)
        };
        let (Some(&(mut comm)), Some(&map)) = (comm, map) else {
            return;
        };
        let od = Merged { comm: &mut self.comm, app: &mut self.app };
        let mut resolved = ResolvedMap::EMPTY;
        if resolved.resolve_in(&od, map.active(), dir).is_err() {
            comm.cob_id |= CobIdEntry::BIT31; // the map is left empty
        }
        if tx {
            if let Some(t) = self.tpdos.as_mut().get_mut(k) {
                let new = Tpdo::new(&comm, resolved);
                #[cfg(feature = "mpdo")]
                let new = new.with_mpdo(AddressMode::of_mapping(map.count)); // MPDO-05
                *t = new;
            }
            if Z::TPDO > SCAN_MAX {
                rebuild(&mut self.rtr_table, self.tpdos.as_ref().iter().map(rtr_id));
            }
        } else {
            if let Some(r) = self.rpdos.as_mut().get_mut(k) {
                let new = Rpdo::new(&comm, resolved);
                #[cfg(feature = "mpdo")]
                let new = new.with_mpdo(AddressMode::of_mapping(map.count)); // MPDO-05
                *r = new;
            }
            if Z::RPDO > SCAN_MAX {
                rebuild(&mut self.rx_table, self.rpdos.as_ref().iter().map(rx_id));
            }
        }
    }

    /// The valid RPDO that receives CAN-ID `id`, the lowest-numbered if several do.
    #[inline]
    pub(super) fn rpdo_for(&self, id: u16) -> Option<usize> {
        find(Z::RPDO, self.rpdos.as_ref().iter().map(rx_id), &self.rx_table, id)
    }

    /// The TPDO that answers a remote request on CAN-ID `id` (PDO-29), the lowest-numbered if several do.
    #[inline]
    pub(super) fn rtr_tpdo_for(&self, id: u16) -> Option<usize> {
        find(Z::TPDO, self.tpdos.as_ref().iter().map(rtr_id), &self.rtr_table, id)
    }

    /// Entering Operational: event-driven TPDOs go out at once (PDO-28, types FEh/FFh).
    pub(super) fn start_pdos(&mut self, now: Instant) {
        for k in 0..Z::TPDO {
            if self.tpdos[k].start() {
                self.send_tpdo(now, k);
            }
        }
    }

    /// Leaving Operational: PDO timers stop, buffered RPDO data is dropped (PDO-04).
    pub(super) fn stop_pdos(&mut self) {
        self.rpdos.as_mut().iter_mut().for_each(Rpdo::stop);
        self.tpdos.as_mut().iter_mut().for_each(Tpdo::stop);
    }

    /// The earliest PDO deadline (inhibit times, event timers), in Operational only.
    pub(super) fn pdo_timeout(&self) -> Deadline {
        if self.nmt.state() != NmtState::Operational {
            return Deadline::NONE;
        }
        let t = self.tpdos.as_ref().iter().fold(Deadline::NONE, |t, p| t.min(p.deadline()));
        self.rpdos.as_ref().iter().fold(t, |t, p| t.min(p.deadline()))
    }

    /// The PDO timers that fell due (event timers, inhibit ends, RPDO time-outs). Out of line: inlined into
    /// `handle_timeout` it was 16 B (node) and 4 B (minimal) more of the firmware's flash.
    #[inline(never)]
    pub(super) fn pdo_handle_timeout(&mut self, now: Instant) {
        if self.nmt.state() != NmtState::Operational {
            return;
        }
        for k in 0..Z::TPDO {
            if self.tpdos[k].handle_timeout(now) {
                self.send_tpdo(now, k);
            }
        }
        for k in 0..Z::RPDO {
            if self.rpdos[k].handle_timeout(now) {
                self.push_event(Event::RpdoTimeout { pdo: k as u16 });
                self.raise_error(codes::RPDO_TIMEOUT, [rpdo_number(k), 0, 0, 0, 0]);
                // PDO-12, EEC-20
            }
        }
    }

    /// Samples TPDO `k` and queues it.
    #[inline]
    pub(super) fn send_tpdo(&mut self, now: Instant, k: usize) {
        self.sample_tpdo(k, true, now);
    }

    /// Samples TPDO `k` and queues it (`send`), or keeps the sample for the next remote request (type FCh at a
    /// SYNC, PDO-21): one path for both, so that the SYNC does not inline a second sampling. `now` last: `k`
    /// and `send` in r1 and r2, the 64-bit `now` in one stacked pair (see `Node::sdo_response_out_of_line`).
    fn sample_tpdo(&mut self, k: usize, send: bool, now: Instant) {
        let Some(t) = self.tpdos.as_mut().get_mut(k) else { return };
        let (data, len) = sample(&t.map, &mut self.comm, &mut self.app);
        if !send {
            t.sampled((data, len));
            return;
        }
        t.sent(now, (data, len));
        let id = t.can_id();
        self.transmit(CanFrame::from_parts(id, data, len));
    }

    /// A frame for RPDO `k` (PDO-04: Operational only; PDO-38/39 lengths; PDO-40 window). Out of line: inlined
    /// into the driver's task (`handle_frame`) it was 48 B (node) and 72 B (minimal) more of the firmware's
    /// flash, and on x86-64 11 instructions more per RPDO frame (`scripts/bench-node.sh`). `k` and
    /// `frame` before `now` (in r1 and r2, `now` stacked): see `Node::sdo_response_out_of_line`.
    #[inline(never)]
    pub(super) fn handle_rpdo(&mut self, k: usize, frame: &CanFrame, now: Instant) {
        if frame.is_rtr() || self.nmt.state() != NmtState::Operational {
            return;
        }
        let Some(r) = self.rpdos.as_mut().get_mut(k) else { return };
        // An MPDO consumer (MPDO-02/03/05): its mapping sub 00h, FEh/FFh, made it one when it was configured
        // (the RPDO itself maps nothing); each frame is decoded and written at once.
        #[cfg(feature = "mpdo")]
        if let Some(mode) = r.mpdo() {
            self.handle_mpdo(k, mode, frame);
            return;
        }
        let outcome = r.receive(now, frame);
        // A frame too short to apply is not a reception: the RPDO stays timed out (PDO-12, PDO-39).
        let recovered = outcome != RxOutcome::TooShort && core::mem::take(&mut r.timed_out);
        let length_error = match outcome {
            RxOutcome::TooShort => Some(codes::PDO_LENGTH),
            RxOutcome::Apply { exceeded } => {
                self.apply_rpdo(k, frame.padded_ref());
                exceeded.then_some(codes::PDO_LENGTH_EXCEEDED)
            }
            RxOutcome::Buffered { exceeded } => {
                if !self.sync.in_window(now) {
                    r.discard(); // SYNC-09: after the window, discarded until the next SYNC
                }
                exceeded.then_some(codes::PDO_LENGTH_EXCEEDED)
            }
        };
        // The cause of 8250h is gone when no RPDO is timed out any more (one code for every RPDO).
        if recovered && !self.rpdos.as_ref().iter().any(|r| r.timed_out) {
            self.clear_error(codes::RPDO_TIMEOUT);
        }
        self.rpdo_length_state(k, length_error);
    }

    /// Writes `data`, the padded data of a frame of RPDO `k` at least as long as its mapping, into the mapped
    /// objects (the leading bytes, PDO-39) and reports it: the one path of an event-driven RPDO's frame and
    /// of a synchronous one's at the SYNC. A [`direct`](ResolvedMap::direct) mapping goes to the application
    /// dictionary alone, byte-aligned; any other through the merged view. The 8 padded bytes, not the
    /// frame's length: no entry reads past [`bytes`](ResolvedMap::bytes), and the bit-granular path needs
    /// no copy of a slice into a zeroed payload.
    fn apply_rpdo(&mut self, k: usize, data: &[u8; 8]) {
        let Some(r) = self.rpdos.as_ref().get(k) else { return };
        if r.map.direct() {
            r.map.unpack_bytes(&mut self.app, data);
        } else {
            r.map.unpack_padded(&mut Merged { comm: &mut self.comm, app: &mut self.app }, *data);
        }
        self.push_event(Event::RpdoReceived { pdo: k as u16 });
    }

    /// EMCY 8210h for a short RPDO, 8220h for a long one (`error`: the code, PDO-38/39); both clear with the
    /// next frame of the right length.
    fn rpdo_length_state(&mut self, k: usize, error: Option<u16>) {
        let Some(r) = self.rpdos.as_mut().get_mut(k) else { return };
        if let Some(code) = error {
            r.length_error = true;
            self.raise_error(code, [rpdo_number(k), 0, 0, 0, 0]);
        } else if core::mem::take(&mut r.length_error) && !self.rpdos.as_ref().iter().any(|r| r.length_error) {
            // The cause is gone when no RPDO's last frame had a wrong length (one code for every RPDO).
            self.clear_error(codes::PDO_LENGTH);
            self.clear_error(codes::PDO_LENGTH_EXCEEDED);
        }
    }

    /// A remote request for TPDO `k` (PDO-21, PDO-22, PDO-29). `k` before `now`: see
    /// `Node::sdo_response_out_of_line`.
    pub(super) fn handle_tpdo_rtr(&mut self, k: usize, now: Instant) {
        if !crate::pdo::RTR || self.nmt.state() != NmtState::Operational {
            return;
        }
        let Some(t) = self.tpdos.as_mut().get_mut(k) else { return };
        if t.transmission_type() == 252 {
            if let Some((data, len)) = t.last() {
                let id = t.can_id();
                self.send(id, data, len);
            }
            return;
        }
        self.send_tpdo(now, k);
    }

    /// A frame on the SYNC COB-ID (SYNC-04, SYNC-05, SYNC-14).
    pub(super) fn handle_sync(&mut self, now: Instant, frame: &CanFrame) {
        if frame.is_rtr() || !self.nmt.state().allows(Service::Sync) {
            return;
        }
        match self.sync.consume(now, frame.data()) {
            SyncInput::WrongLength => {
                self.sync_length_error = true;
                self.raise_error(codes::SYNC_LENGTH, [frame.dlc(), 0, 0, 0, 0]);
            }
            SyncInput::Sync { counter } => {
                if core::mem::take(&mut self.sync_length_error) {
                    self.clear_error(codes::SYNC_LENGTH);
                }
                self.process_sync(now, counter);
            }
        }
    }

    /// The SYNC producer (SYNC-06/07): produced in Pre-operational and Operational, and acted on by this node
    /// as by every consumer.
    pub(super) fn sync_timeout(&mut self, now: Instant) {
        if !self.sync.deadline().passed(now) {
            return;
        }
        let Some(frame) = self.sync.produce(now) else { return };
        if self.nmt.state().allows(Service::Sync) {
            self.transmit(frame);
            self.process_sync(now, frame.data().first().copied());
        }
    }

    /// What a SYNC does: synchronous RPDO data is applied, synchronous TPDOs are sampled and sent.
    pub(super) fn process_sync(&mut self, now: Instant, counter: Option<u8>) {
        self.push_event(Event::Sync { counter });
        if self.nmt.state() != NmtState::Operational {
            return;
        }
        for k in 0..Z::RPDO {
            if let Some(data) = self.rpdos[k].take_pending() {
                self.apply_rpdo(k, &data);
            }
        }
        for k in 0..Z::TPDO {
            let action = self.tpdos[k].on_sync(counter);
            if action != SyncAction::None {
                // Sample (type FCh) only with remote requests in the build (`Tpdo::on_sync`).
                self.sample_tpdo(k, !crate::pdo::RTR || action == SyncAction::Send, now);
            }
        }
    }

    /// An application event for TPDO `k` (0-based; PDO-19, PDO-23): an event-driven TPDO is sampled and
    /// sent now (at the time last passed in), or when its inhibit time ends; a type-00h TPDO goes out at the
    /// next SYNC. Returns whether a frame was queued now. Only in Operational (PDO-04).
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{Node, NoApplication}, pdo::PdoDefault, Instant, NmtState, NodeId};
    /// const CFG: NodeConfig = NodeConfig { tpdo: &[PdoDefault { mapping: &[0x1001_0008], ..PdoDefault::EVENT }], ..NodeConfig::DEFAULT };
    /// let mut node: Node<NoApplication> = Node::new(NodeId::new(1).unwrap(), CFG, NoApplication);
    /// node.handle_timeout(Instant::ZERO);
    /// node.enter_state(NmtState::Operational); // sends TPDO1 once (PDO-28)
    /// while node.poll_transmit().is_some() {}
    /// assert!(node.trigger_tpdo(0));
    /// assert_eq!(node.poll_transmit().map(|f| (f.cob_id(), f.dlc())), Some((0x181, 1)));
    /// ```
    pub fn trigger_tpdo(&mut self, k: usize) -> bool {
        let now = self.now;
        if self.nmt.state() != NmtState::Operational || !self.tpdos.as_mut().get_mut(k).is_some_and(|t| t.trigger(now))
        {
            return false;
        }
        self.send_tpdo(now, k);
        true
    }

    /// Change-of-value detection (PDO-23): samples every valid event-driven TPDO and triggers those whose
    /// data differs from what they last sent. Call it after changing process values (or periodically);
    /// returns how many TPDOs were queued now.
    pub fn trigger_changed_tpdos(&mut self) -> usize {
        let mut sent = 0;
        for k in 0..Z::TPDO {
            let t = &self.tpdos[k];
            if t.transmission_type() < 254 {
                // not event-driven, or not valid (FDh in effect)
                continue;
            }
            if t.last() != Some(sample(&t.map, &mut self.comm, &mut self.app)) && self.trigger_tpdo(k) {
                sent += 1;
            }
        }
        sent
    }

    /// The CAN-ID the TIME object uses while this node consumes or produces it, else an impossible ID.
    #[cfg(feature = "time")]
    pub(super) fn time_can_id(&self) -> u16 {
        let cob = CobIdEntry::from_raw(self.comm.params.time_cob_id);
        if cob.bit31() || cob.bit30() {
            cob.can_id()
        } else {
            u16::MAX
        }
    }

    /// A TIME frame (TIME-04/05): an event when consumed (1012h bit 31), in Pre-operational/Operational.
    #[cfg(feature = "time")]
    pub(super) fn handle_time(&mut self, frame: &CanFrame) {
        let consume = CobIdEntry::from_raw(self.comm.params.time_cob_id).bit31();
        if frame.is_rtr() || !consume || !self.nmt.state().allows(Service::Time) {
            return;
        }
        if let Ok(TimeStamp { days, ms }) = TimeStamp::parse(frame.data()) {
            self.comm.optional.time_of_day(ms); // 1013h consumed with TIME (TIME-06)
            self.push_event(Event::Time(TimeOfDay { days, ms }));
        }
    }

    /// Produces a TIME message carrying `time` (TIME-02/04: only when 1012h bit 30 is set, in
    /// Pre-operational/Operational). The core has no wall clock: the application says what time it is.
    /// Returns whether the frame was queued.
    ///
    /// ```
    /// use canopen_core::{profile::NodeConfig, node::{Node, NoApplication}, od::TimeOfDay, Instant, NodeId};
    /// const CFG: NodeConfig = NodeConfig { time_cob_id: 0x4000_0100, ..NodeConfig::DEFAULT };
    /// let mut node: Node<NoApplication> = Node::new(NodeId::new(1).unwrap(), CFG, NoApplication);
    /// node.handle_timeout(Instant::ZERO);
    /// while node.poll_transmit().is_some() {}
    /// assert!(node.produce_time(TimeOfDay::new(9913, 43_200_000).unwrap()));
    /// assert_eq!(node.poll_transmit().unwrap().data(), &[0x00, 0x2E, 0x93, 0x02, 0xB9, 0x26]); // TIME_OF_DAY 2011-02-21 12:00:00.000
    /// ```
    #[cfg(feature = "time")]
    pub fn produce_time(&mut self, time: TimeOfDay) -> bool {
        let cob = CobIdEntry::from_raw(self.comm.params.time_cob_id);
        if !cob.bit30() || !self.nmt.state().allows(Service::Time) {
            return false;
        }
        let b = TimeStamp { days: time.days, ms: time.ms }.emit();
        let mut data = [0u8; 8];
        data[..6].copy_from_slice(&b);
        self.send(cob.can_id(), data, 6);
        self.comm.optional.time_of_day(time.ms); // 1013h produced with TIME (TIME-06)
        true
    }
}

/// Samples the objects of `map` into a payload (PDO-32): through the application dictionary alone when the
/// mapping is [`direct`](ResolvedMap::direct) (no routing per entry), else through the merged view, which
/// alone carries the bit-granular path (one instance of it, not one per dictionary type).
fn sample<A: ObjectDictionary, Z: NodeSizes>(
    map: &ResolvedMap,
    comm: &mut CommProfile<Z>,
    app: &mut A,
) -> ([u8; 8], u8) {
    let mut data = [0u8; 8];
    let len =
        if map.direct() { map.pack_bytes(app, &mut data) } else { map.pack(&mut Merged { comm, app }, &mut data) };
    (data, len as u8)
}

/// RPDO `k` (0-based) as the 1-based number the RPDO EMCYs carry in their first manufacturer byte (8210h,
/// 8220h, 8230h, 8250h): 255 for RPDO 255 and every one above (CiA 301 allows 512; a byte holds no more).
pub(super) fn rpdo_number(k: usize) -> u8 {
    u8::try_from(k + 1).unwrap_or(u8::MAX)
}

/// Up to this many PDOs of a direction, a received frame is matched by comparing the PDOs' own CAN-IDs: at
/// most 8 compares, and no table to keep (less flash than the table's upkeep: footprint.sh, see the
/// commit). Above it, by a binary search of a sorted (CAN-ID, PDO number) table, rebuilt when a PDO is
/// configured, so that the work per frame does not grow with the number of PDOs (CiA 301 allows 512).
pub(super) const SCAN_MAX: usize = 8;

/// The CAN-ID an RPDO receives on: a valid one's.
pub(super) fn rx_id(r: &Rpdo) -> Option<u16> {
    r.is_valid().then(|| r.can_id())
}

/// The CAN-ID whose remote request a TPDO answers: one that allows RTR (PDO-29).
pub(super) fn rtr_id(t: &Tpdo) -> Option<u16> {
    t.rtr_allowed().then(|| t.can_id())
}

/// The first of `n` PDOs (by number) whose CAN-ID (`ids`: [`rx_id`] or [`rtr_id`] of each) is `id`: compared
/// one by one up to [`SCAN_MAX`] PDOs, else looked up in `table`, which [`rebuild`] filled from the same IDs
/// (its first entry of `id` is the lowest-numbered PDO: [`insert_sorted`] keeps equal CAN-IDs in PDO order).
fn find<T: VecStorage<(u16, u16)> + ?Sized>(
    n: usize,
    mut ids: impl Iterator<Item = Option<u16>>,
    table: &PdoTable<T>,
    id: u16,
) -> Option<usize> {
    if n <= SCAN_MAX {
        return ids.position(|pdo| pdo == Some(id));
    }
    let i = table.partition_point(|e| e.0 < id);
    table.get(i).filter(|e| e.0 == id).map(|e| usize::from(e.1))
}

/// Fills `table` with (CAN-ID, PDO number) of the PDOs that have an ID in `ids`, sorted by CAN-ID.
fn rebuild<T: VecStorage<(u16, u16)>>(table: &mut PdoTable<T>, ids: impl Iterator<Item = Option<u16>>) {
    table.clear();
    for (k, id) in ids.enumerate() {
        if let Some(id) = id {
            insert_sorted(table, (id, k as u16));
        }
    }
}

/// Inserts `e` after every entry whose CAN-ID is not greater, so the table stays sorted by CAN-ID with equal
/// IDs in PDO order (what the stable small-slice path of `sort_unstable_by_key` gave). A plain insertion:
/// `sort_unstable_by_key` linked about 4 KB of quicksort into a Cortex-M firmware for tables of at most a few
/// entries.
fn insert_sorted<T: VecStorage<(u16, u16)>>(table: &mut PdoTable<T>, e: (u16, u16)) {
    let at = table.iter().position(|x| x.0 > e.0).unwrap_or(table.len());
    // push and swap down rather than Vec::insert, whose ptr::copy links compiler_builtins' memmove.
    if table.push(e).is_err() {
        return;
    }
    let mut i = table.len() - 1;
    while i > at {
        table.swap(i, i - 1);
        i -= 1;
    }
}
