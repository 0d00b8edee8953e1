//! SYNC consumer and producer (SYNC-01..SYNC-15).
//!
//! Implemented: SYNC-02/03 (1005h gen bit and COB-ID rules, [`Sync::set_cob_id`]), SYNC-04 (DLC 0, or 1 with the
//! counter when 1019h > 1), SYNC-06/07 (1006h period; the first SYNC goes out one period after it becomes
//! non-zero and carries counter 1), SYNC-08/09 (1007h window: [`Sync::in_window`]), SYNC-10/11 (counter
//! 1..=1019h, restart at 1 after boot-up and on Stopped → Pre-operational, [`Sync::restart_counter`]),
//! SYNC-12 (1019h refused while 1006h ≠ 0 with 0800 0022h), SYNC-14 (unexpected DLC → EMCY 8240h, reported
//! as [`SyncInput::WrongLength`]). SYNC-05 (only in Pre-operational/Operational) is enforced by `Node`.
//!
//! The producer is the Cargo feature `sync-producer` (on by default). Without it the node is a SYNC
//! consumer only, as CiA 301 allows: 1005h with the gen bit (bit 30) set is refused with 0609 0030h (SYNC-03),
//! a configuration or stored value that sets it is taken without it ([`SyncParams::supported`]), and no SYNC
//! is ever produced (the producer's code is not in the build: about 240 B of Cortex-M flash). 1006h, 1007h
//! and 1019h stay: the window and the counter are the consumer's too.
//!
//! The window and the counter are Cargo features too (`sync-window` for 1007h, `sync-counter` for 1019h,
//! on by default, both optional in CiA 301): without one its object does not exist and the SYNC behaves as
//! with the object at 0 (no window; no counter, so a SYNC has DLC 0 and a TPDO's SYNC start value is not
//! evaluated, PDO-26). [`SyncParams::supported`] clears the value, and the node's paths read it through
//! constants, so the checks are not in the build.

use crate::abort::AbortCode;
use crate::cob::CobIdEntry;
use crate::time::{Deadline, Duration, Instant};

/// Whether this build can produce SYNC (the feature `sync-producer`, see the module docs).
pub const PRODUCER: bool = cfg!(feature = "sync-producer");

/// Whether this build has 1007h, the synchronous window (the feature `sync-window`, see the module docs).
pub const WINDOW: bool = cfg!(feature = "sync-window");

/// Whether this build has 1019h, the SYNC counter (the feature `sync-counter`, see the module docs).
pub const COUNTER: bool = cfg!(feature = "sync-counter");

/// The SYNC parameters (1005h, 1006h, 1007h, 1019h).
///
/// ```
/// use canopen_core::sync::SyncParams;
/// let p = SyncParams::DEFAULT;
/// assert_eq!(p.cob_id.raw(), 0x0000_0080); // 1005h default 0000 0080h
/// assert_eq!(p.counter_overflow, 0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SyncParams {
    /// 1005h COB-ID SYNC; bit 30 = this node produces SYNC.
    pub cob_id: CobIdEntry,
    /// 1006h communication cycle period, µs (0 = no SYNC produced).
    pub period_us: u32,
    /// 1007h synchronous window length, µs (0 = no window).
    pub window_us: u32,
    /// 1019h synchronous counter overflow value (0 = no counter).
    pub counter_overflow: u8,
}

impl SyncParams {
    /// Consumer on 080h, no producer, no window, no counter.
    pub const DEFAULT: SyncParams =
        SyncParams { cob_id: CobIdEntry::from_raw(0x80), period_us: 0, window_us: 0, counter_overflow: 0 };

    /// These parameters as this build can have them: without the feature `sync-producer` the gen bit of
    /// 1005h (bit 30) is cleared, the node being a consumer only (SYNC-03); without `sync-window` the
    /// window is 0, without `sync-counter` the counter overflow value is 0.
    ///
    /// ```
    /// use canopen_core::{cob::CobIdEntry, sync::{self, SyncParams}};
    /// let p = SyncParams { cob_id: CobIdEntry::from_raw(0x4000_0080), window_us: 500, ..SyncParams::DEFAULT };
    /// assert_eq!(p.supported().cob_id.raw(), if sync::PRODUCER { 0x4000_0080 } else { 0x80 });
    /// assert_eq!(p.supported().window_us, if sync::WINDOW { 500 } else { 0 });
    /// ```
    pub const fn supported(self) -> SyncParams {
        let cob_id = if PRODUCER { self.cob_id } else { CobIdEntry::from_raw(self.cob_id.raw() & !CobIdEntry::BIT30) };
        let window_us = if WINDOW { self.window_us } else { 0 };
        let counter_overflow = if COUNTER { self.counter_overflow } else { 0 };
        SyncParams { cob_id, window_us, counter_overflow, ..self }
    }
}

/// SYNC-03: the gen bit of a 1005h value written to a build without the producer is 0609 0030h.
///
/// ```
/// use canopen_core::sync;
/// assert_eq!(sync::check_producible(0x80), Ok(()));
/// assert_eq!(sync::check_producible(0x4000_0080).is_err(), !sync::PRODUCER);
/// ```
pub const fn check_producible(raw: u32) -> Result<(), AbortCode> {
    if !PRODUCER && raw & CobIdEntry::BIT30 != 0 {
        return Err(AbortCode::InvalidValue);
    }
    Ok(())
}

impl Default for SyncParams {
    fn default() -> Self {
        SyncParams::DEFAULT
    }
}

/// A received frame on the SYNC COB-ID, interpreted.
///
/// ```
/// use canopen_core::sync::SyncInput;
/// assert_eq!(SyncInput::Sync { counter: Some(3) }, SyncInput::Sync { counter: Some(3) });
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SyncInput {
    /// A SYNC, with its counter when the counter is enabled.
    Sync {
        /// The counter value (1..=1019h) or `None` when 1019h = 0.
        counter: Option<u8>,
    },
    /// A SYNC whose DLC does not match 1019h: EMCY 8240h (SYNC-14); it is not acted on.
    WrongLength,
}

/// The SYNC object of a node: consumer always, producer when 1005h bit 30 is set and 1006h ≠ 0.
///
/// ```
/// use canopen_core::{sync::{self, Sync, SyncParams}, cob::CobIdEntry, Instant};
/// # if !sync::PRODUCER { return; } // a build without the feature sync-producer produces nothing
/// let mut s = Sync::new(SyncParams { cob_id: CobIdEntry::from_raw(0x4000_0080), period_us: 10_000, counter_overflow: 3, ..SyncParams::DEFAULT });
/// s.start(Instant::ZERO);
/// assert_eq!(s.poll_timeout(), Some(Instant::from_millis(10)));
/// let f = s.produce(Instant::from_millis(10)).unwrap();
/// assert_eq!((f.cob_id(), f.data()), (0x80, &[1u8][..]));
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Sync {
    params: SyncParams,
    counter: u8,
    /// When the next SYNC is to be produced (8 bytes, as `last_sync`).
    next: Deadline,
    /// When the last SYNC went out or arrived: the start of the synchronous window (an optional instant in
    /// 8 bytes, `Option<Instant>` takes 16).
    last_sync: Deadline,
}

impl Sync {
    /// A SYNC object with `params` ([`SyncParams::supported`]); call [`start`](Self::start) at boot-up.
    pub const fn new(params: SyncParams) -> Self {
        Sync { params: params.supported(), counter: 1, next: Deadline::NONE, last_sync: Deadline::NONE }
    }

    /// The parameters.
    pub const fn params(&self) -> &SyncParams {
        &self.params
    }

    /// Whether this node produces SYNC (1005h bit 30; never without the feature `sync-producer`).
    pub const fn is_producer(&self) -> bool {
        PRODUCER && self.params.cob_id.bit30()
    }

    /// The CAN-ID SYNC is received (and produced) on.
    pub const fn can_id(&self) -> u16 {
        self.params.cob_id.can_id()
    }

    /// Boot-up / reset communication at `now`: the counter restarts at 1 (SYNC-11) and the producer, if any,
    /// sends its first SYNC one period later (SYNC-07).
    pub fn start(&mut self, now: Instant) {
        self.counter = 1;
        self.last_sync = Deadline::NONE;
        self.schedule(now);
    }

    /// Stopped → Pre-operational: the counter restarts at 1 (SYNC-11).
    pub fn restart_counter(&mut self) {
        self.counter = 1;
    }

    fn schedule(&mut self, now: Instant) {
        let active = self.is_producer() && self.params.period_us != 0;
        self.next = if active {
            Deadline::at(now + Duration::from_micros(u64::from(self.params.period_us)))
        } else {
            Deadline::NONE
        };
    }

    /// Writes 1005h (SYNC-02/03, COB-15/16): frame bit refused, ID unchangeable while producing, the gen bit
    /// refused by a build without the producer ([`check_producible`]).
    pub fn set_cob_id(&mut self, now: Instant, raw: u32) -> Result<(), AbortCode> {
        check_producible(raw)?;
        self.params.cob_id = self.params.cob_id.check_change(raw, |e| e.bit30())?;
        self.schedule(now);
        Ok(())
    }

    /// Takes over parameters written through the dictionary (which checked them): the counter restarts when
    /// 1019h changed, production is rescheduled when the COB-ID or the period changed (SYNC-07).
    ///
    /// ```
    /// use canopen_core::{sync::{self, Sync, SyncParams}, cob::CobIdEntry, Instant};
    /// # if !sync::PRODUCER { return; } // a build without the feature sync-producer produces nothing
    /// let mut s = Sync::new(SyncParams::DEFAULT);
    /// s.reconfigure(Instant::ZERO, SyncParams { cob_id: CobIdEntry::from_raw(0x4000_0080), period_us: 1000, ..SyncParams::DEFAULT });
    /// assert_eq!(s.poll_timeout(), Some(Instant::from_millis(1)));
    /// ```
    #[inline]
    pub fn reconfigure(&mut self, now: Instant, params: SyncParams) {
        self.take_params(now, params, false);
    }

    /// [`reconfigure`](Self::reconfigure), and with `restart` also [`start`](Self::start) (reset
    /// communication: the node's boot path has no second, inline copy of the scheduling).
    // Out of line: a configuration change, not a per-frame path (8 B of the minimal firmware's flash).
    #[inline(never)]
    pub(crate) fn take_params(&mut self, now: Instant, params: SyncParams, restart: bool) {
        let params = params.supported();
        let old = self.params;
        self.params = params;
        if restart {
            self.start(now);
            return;
        }
        if old.counter_overflow != params.counter_overflow {
            self.counter = 1;
        }
        if old.cob_id != params.cob_id || old.period_us != params.period_us {
            self.schedule(now);
        }
    }

    /// Writes 1006h; production (re)starts within one period (SYNC-07).
    pub fn set_period(&mut self, now: Instant, period_us: u32) {
        self.params.period_us = period_us;
        self.schedule(now);
    }

    /// Writes 1007h (ignored in a build without it, see [`WINDOW`]).
    pub fn set_window(&mut self, window_us: u32) {
        self.params.window_us = if WINDOW { window_us } else { 0 };
    }

    /// Writes 1019h: only while 1006h = 0 (SYNC-12: 0800 0022h); 1 and 241–255 are reserved (0609 0030h).
    /// In a build without it (see [`COUNTER`]) 0 is taken and any other value is 0609 0030h.
    ///
    /// ```
    /// use canopen_core::{sync::{self, Sync, SyncParams}, od::AbortCode, Instant};
    /// # if !sync::COUNTER { return; }
    /// let mut s = Sync::new(SyncParams::DEFAULT);
    /// assert_eq!(s.set_counter_overflow(1), Err(AbortCode::InvalidValue));
    /// assert_eq!(s.set_counter_overflow(240), Ok(()));
    /// s.set_period(Instant::ZERO, 1000);
    /// assert_eq!(s.set_counter_overflow(10), Err(AbortCode::CannotStoreDeviceState));
    /// ```
    pub fn set_counter_overflow(&mut self, value: u8) -> Result<(), AbortCode> {
        if self.params.period_us != 0 {
            return Err(AbortCode::CannotStoreDeviceState);
        }
        if value == 1 || value > 240 || (!COUNTER && value != 0) {
            return Err(AbortCode::InvalidValue);
        }
        self.params.counter_overflow = value;
        self.counter = 1;
        Ok(())
    }

    /// When the next SYNC is to be produced.
    pub const fn poll_timeout(&self) -> Option<Instant> {
        self.next.get()
    }

    /// [`poll_timeout`](Self::poll_timeout) as a [`Deadline`], for the node's minimum over its services (a
    /// constant none without the producer, so the node's producer path is not in the build).
    pub(crate) const fn deadline(&self) -> Deadline {
        if PRODUCER {
            self.next
        } else {
            Deadline::NONE
        }
    }

    /// Produces the SYNC due at `now`, if any; the node also acts on its own SYNC (call
    /// [`consume`](Self::consume)-equivalent logic with the returned counter).
    pub fn produce(&mut self, now: Instant) -> Option<crate::CanFrame> {
        if !PRODUCER || !self.next.passed(now) {
            return None;
        }
        let next = self.next.instant();
        let period = Duration::from_micros(u64::from(self.params.period_us));
        let following = next + period;
        self.next = Deadline::at(if following <= now { now + period } else { following });
        let counter = self.advance_counter();
        self.last_sync = Deadline::at(now);
        let mut data = [0u8; 8];
        let len = match counter {
            Some(c) => {
                data[0] = c;
                1
            }
            None => 0,
        };
        Some(crate::CanFrame::from_parts(self.can_id(), data, len))
    }

    /// 1019h as this build has it: a constant 0 without the counter, so its paths are not built.
    const fn counter_overflow(&self) -> u8 {
        if COUNTER {
            self.params.counter_overflow
        } else {
            0
        }
    }

    /// 1007h as this build has it: a constant 0 without the window, so its check is not built.
    const fn window_us(&self) -> u32 {
        if WINDOW {
            self.params.window_us
        } else {
            0
        }
    }

    fn advance_counter(&mut self) -> Option<u8> {
        if self.counter_overflow() < 2 {
            return None;
        }
        let c = self.counter;
        self.counter = if c >= self.counter_overflow() { 1 } else { c + 1 };
        Some(c)
    }

    /// Interprets a frame received on the SYNC CAN-ID at `now` (SYNC-04, SYNC-14).
    pub fn consume(&mut self, now: Instant, data: &[u8]) -> SyncInput {
        // DLC 1 with the counter, 0 without (one compare): the counter is the byte there is, if any.
        if data.len() != usize::from(self.counter_overflow() >= 2) {
            return SyncInput::WrongLength;
        }
        self.last_sync = Deadline::at(now);
        SyncInput::Sync { counter: data.first().copied() }
    }

    /// Whether `now` is inside the synchronous window that began with the last SYNC (SYNC-08/09); always true
    /// when 1007h = 0.
    ///
    /// ```
    /// use canopen_core::{sync::{self, Sync, SyncParams}, Instant};
    /// # if !sync::WINDOW { return; }
    /// let mut s = Sync::new(SyncParams { window_us: 500, ..SyncParams::DEFAULT });
    /// s.consume(Instant::from_micros(1000), &[]);
    /// assert!(s.in_window(Instant::from_micros(1400)));
    /// assert!(!s.in_window(Instant::from_micros(1600)));
    /// ```
    pub fn in_window(&self, now: Instant) -> bool {
        match (self.window_us(), self.last_sync.get()) {
            (0, _) => true,
            (_, None) => false,
            (w, Some(t)) => now <= t + Duration::from_micros(u64::from(w)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::time::ms;

    /// SYNC-07, SYNC-10, SYNC-11: counter 1..=overflow, then 1 again; restart on reset.
    #[test]
    #[cfg(all(feature = "sync-producer", feature = "sync-counter"))]
    fn producer_counter_wraps() {
        let mut s = Sync::new(SyncParams {
            cob_id: CobIdEntry::from_raw(0x4000_0080),
            period_us: 1000,
            counter_overflow: 3,
            ..SyncParams::DEFAULT
        });
        s.start(ms(0));
        let counters: std::vec::Vec<u8> = (1..=7).filter_map(|k| s.produce(ms(k))).map(|f| f.data()[0]).collect();
        assert_eq!(counters, [1, 2, 3, 1, 2, 3, 1]);
        s.restart_counter();
        assert_eq!(s.produce(ms(8)).map(|f| f.data()[0]), Some(1));
    }

    extern crate std;

    /// SYNC-04: without counter the SYNC has DLC 0 (V-SYNC).
    #[test]
    #[cfg(feature = "sync-producer")]
    fn producer_dlc() {
        let mut s =
            Sync::new(SyncParams { cob_id: CobIdEntry::from_raw(0x4000_0080), period_us: 500, ..SyncParams::DEFAULT });
        s.start(ms(0));
        let f = s.produce(Instant::from_micros(500)).unwrap();
        assert_eq!((f.cob_id(), f.dlc()), (0x080, 0));
    }

    /// SYNC-04, SYNC-14: a consumer-only node produces nothing and checks the DLC against 1019h.
    #[test]
    fn consumer_dlc() {
        let mut c = Sync::new(SyncParams { period_us: 500, ..SyncParams::DEFAULT });
        c.start(ms(0));
        assert_eq!(c.poll_timeout(), None);
        assert_eq!(c.consume(ms(1), &[]), SyncInput::Sync { counter: None });
        assert_eq!(c.consume(ms(1), &[5]), SyncInput::WrongLength); // SYNC-14
        c.set_period(ms(1), 0);
        if COUNTER {
            c.set_counter_overflow(4).unwrap();
            assert_eq!(c.consume(ms(1), &[]), SyncInput::WrongLength);
            assert_eq!(c.consume(ms(1), &[2]), SyncInput::Sync { counter: Some(2) });
        } else {
            // No 1019h in this build: only 0 is taken, and a SYNC with a counter is the wrong length.
            assert_eq!(c.set_counter_overflow(4), Err(AbortCode::InvalidValue));
            assert_eq!(c.set_counter_overflow(0), Ok(()));
            assert_eq!(c.consume(ms(1), &[2]), SyncInput::WrongLength);
            let stored = SyncParams { counter_overflow: 4, ..SyncParams::DEFAULT };
            c.reconfigure(ms(1), stored);
            assert_eq!((c.params().counter_overflow, c.consume(ms(2), &[])), (0, SyncInput::Sync { counter: None }));
        }
    }

    /// SYNC-08/09: with 1007h the window closes; a build without it (`sync-window` off) has no window, whatever
    /// the parameters asked.
    #[test]
    fn window_per_build() {
        let mut s = Sync::new(SyncParams { window_us: 500, ..SyncParams::DEFAULT });
        s.consume(ms(1), &[]);
        assert!(s.in_window(Instant::from_micros(1400)));
        assert_eq!(s.in_window(Instant::from_micros(1600)), !WINDOW);
        s.set_window(0);
        assert!(s.in_window(Instant::from_micros(1600)));
        s.set_window(100);
        assert_eq!(
            (s.params().window_us, s.in_window(Instant::from_micros(1200))),
            if WINDOW { (100, false) } else { (0, true) }
        );
    }

    /// SYNC-03 without the feature `sync-producer`: the gen bit is refused with 0609 0030h, parameters asking
    /// for production are taken as a consumer's, and nothing is produced.
    #[test]
    #[cfg(not(feature = "sync-producer"))]
    fn consumer_only_build_sync_03() {
        let mut s =
            Sync::new(SyncParams { cob_id: CobIdEntry::from_raw(0x4000_0080), period_us: 500, ..SyncParams::DEFAULT });
        assert!(!s.is_producer());
        assert_eq!(s.params().cob_id.raw(), 0x80);
        s.start(ms(0));
        assert_eq!((s.poll_timeout(), s.deadline()), (None, Deadline::NONE));
        assert_eq!(s.produce(ms(1)), None);
        assert_eq!(s.set_cob_id(ms(0), 0x4000_0080), Err(AbortCode::InvalidValue));
        assert_eq!(s.set_cob_id(ms(0), 0x0000_0081), Ok(()));
        s.reconfigure(ms(0), SyncParams { cob_id: CobIdEntry::from_raw(0x4000_0080), ..SyncParams::DEFAULT });
        assert_eq!((s.params().cob_id.raw(), s.poll_timeout()), (0x80, None));
    }

    /// SYNC-03, COB-15/16: 1005h rules.
    #[test]
    #[cfg(feature = "sync-producer")]
    fn cob_id_rules() {
        let mut s = Sync::new(SyncParams::DEFAULT);
        assert_eq!(s.set_cob_id(ms(0), 0x4000_0080), Ok(())); // become producer
        assert_eq!(s.set_cob_id(ms(0), 0x4000_0081), Err(AbortCode::InvalidValue)); // ID change while producing
        assert_eq!(s.set_cob_id(ms(0), 0x2000_0080), Err(AbortCode::InvalidValue)); // 29-bit
        assert_eq!(s.set_cob_id(ms(0), 0x0000_0080), Ok(()));
        assert_eq!(s.set_cob_id(ms(0), 0x0000_0081), Ok(()));
        assert_eq!(s.can_id(), 0x81);
    }
}
