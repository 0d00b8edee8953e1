//! Emergency producer, error register and pre-defined error field (EMCY-01..EMCY-12, EEC-01..23,
//! ERR-01..ERR-09, NMT-22).
//!
//! [`ErrorState`] keeps the set of active errors, derives the error register 1001h from it (ERR-02: bit 0 set
//! whenever any error is active, the class bits from each code's class), records each new error at the top
//! of the 1003h history (ERR-06, ERR-07), and queues the EMCY frames of the emergency state machine
//! (EMCY-07: an EMCY per new error, `0000h` with the remaining register when some errors clear, `0000h` with
//! register 0 when the last one clears; EMCY-05: nothing is repeated). [`EmcyProducer`] then spaces the
//! frames by the 1015h inhibit time without losing any (EMCY-09) and holds them while the node is Stopped,
//! sending the most recent one when it leaves (NMT-22, EMCY-08).
//!
//! The `Node` wires both (`node/errors.rs`): `Node::raise_error`/`Node::clear_error`, 1014h COB-ID (an
//! invalid 1014h drops EMCYs), 1015h, and the errors the stack raises itself: 8110h transmit queue overrun,
//! 8130h heartbeat/life-guarding time-out, 8210h/8220h RPDO length, 8240h SYNC length, 8250h RPDO time-out.
//! The EMCY consumer reports every EMCY on 081h–0FFh from other nodes as an event (EMCY-11); the 1028h
//! object that would select producers (EMCY-10, optional) is not implemented. 8120h/8140h (error passive,
//! bus-off) need the CAN controller's state, which the core does not see: the driver or application raises
//! them with `Node::raise_error`.
//!
//! Two of these objects are optional in CiA 301 and are Cargo features (on by default): `error-history`
//! (1003h; without it [`HISTORY`] is 0 and nothing is recorded) and `emcy-inhibit` (1015h; without it
//! [`INHIBIT`] is false and EMCYs are not spaced). Without one its object does not exist (0602 0000h).

use heapless::Vec;

use crate::abort::AbortCode;
use crate::queue::Queue;
use crate::time::{Deadline, Duration, Instant};
use crate::wire::emcy::Emergency;

/// Emergency error codes of CiA 301 Table 26 used by the stack itself (EEC-01..EEC-23 are all representable
/// as plain `u16` codes; these are the ones the core raises or the application commonly needs).
pub mod codes {
    /// 0000h error reset / no error (EEC-01).
    pub const NO_ERROR: u16 = 0x0000;
    /// 1000h generic error (EEC-02).
    pub const GENERIC: u16 = 0x1000;
    /// 8110h CAN overrun, objects lost (EEC-10).
    pub const CAN_OVERRUN: u16 = 0x8110;
    /// 8120h CAN in error passive mode (EEC-11).
    pub const CAN_ERROR_PASSIVE: u16 = 0x8120;
    /// 8130h life guard error or heartbeat error (EEC-12).
    pub const HEARTBEAT_OR_LIFE_GUARD: u16 = 0x8130;
    /// 8140h recovered from bus-off (EEC-13).
    pub const RECOVERED_FROM_BUS_OFF: u16 = 0x8140;
    /// 8210h PDO not processed due to length error (EEC-16).
    pub const PDO_LENGTH: u16 = 0x8210;
    /// 8220h PDO length exceeded (EEC-17).
    pub const PDO_LENGTH_EXCEEDED: u16 = 0x8220;
    /// 8230h DAM-MPDO not processed, destination object not available (EEC-18, MPDO-02).
    pub const MPDO_NOT_PROCESSED: u16 = 0x8230;
    /// 8240h unexpected SYNC data length (EEC-19).
    pub const SYNC_LENGTH: u16 = 0x8240;
    /// 8250h RPDO time-out (EEC-20).
    pub const RPDO_TIMEOUT: u16 = 0x8250;
}

/// Error register 1001h bits (ERR-02, 000 Table 54).
pub mod register {
    /// Bit 0: generic error (set whenever any error is active).
    pub const GENERIC: u8 = 1 << 0;
    /// Bit 1: current.
    pub const CURRENT: u8 = 1 << 1;
    /// Bit 2: voltage.
    pub const VOLTAGE: u8 = 1 << 2;
    /// Bit 3: temperature.
    pub const TEMPERATURE: u8 = 1 << 3;
    /// Bit 4: communication error (overrun, error state).
    pub const COMMUNICATION: u8 = 1 << 4;
    /// Bit 5: device profile specific.
    pub const DEVICE_PROFILE: u8 = 1 << 5;
    /// Bit 7: manufacturer specific.
    pub const MANUFACTURER: u8 = 1 << 7;

    /// The register bits an error code stands for, from its class (Table 25): 2xxxh current, 3xxxh voltage,
    /// 4xxxh temperature, 81xxh/82xxh communication, FFxxh manufacturer; every error sets the generic bit.
    ///
    /// ```
    /// use canopen_core::emcy::register;
    /// assert_eq!(register::bits_for(0x1000), 0x01);
    /// assert_eq!(register::bits_for(0x8130), 0x11);
    /// assert_eq!(register::bits_for(0x4210), 0x09);
    /// assert_eq!(register::bits_for(0x0000), 0x00);
    /// ```
    pub const fn bits_for(code: u16) -> u8 {
        let class = match code >> 12 {
            0x0 => return 0,
            0x2 => CURRENT,
            0x3 => VOLTAGE,
            0x4 => TEMPERATURE,
            0x8 if matches!(code >> 8, 0x81 | 0x82) => COMMUNICATION,
            0xF if code >> 8 == 0xFF => MANUFACTURER,
            _ => 0,
        };
        GENERIC | class
    }
}

/// An active error.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Active {
    code: u16,
    bits: u8,
}

/// The active errors (at most `ACTIVE`), the error register and the 1003h history (depth `HIST`).
///
/// ```
/// use canopen_core::emcy::ErrorState;
/// let mut e: ErrorState<4, 8, 8> = ErrorState::new();
/// assert!(e.raise(0x1000, [0; 5]));
/// assert!(!e.raise(0x1000, [0; 5])); // already active: no second EMCY (EMCY-05)
/// assert_eq!(e.register(), 0x01);
/// assert_eq!(e.history(), &[0x0000_1000]);
/// assert!(e.clear(0x1000));
/// assert_eq!(e.register(), 0x00);
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ErrorState<const ACTIVE: usize, const HIST: usize, const QUEUE: usize> {
    active: Vec<Active, ACTIVE>,
    /// Newest first (sub-index 1 = newest).
    history: Vec<u32, HIST>,
    pending: Queue<Emergency, [Emergency; QUEUE]>,
    lost: u32,
}

impl<const ACTIVE: usize, const HIST: usize, const QUEUE: usize> Default for ErrorState<ACTIVE, HIST, QUEUE> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const ACTIVE: usize, const HIST: usize, const QUEUE: usize> ErrorState<ACTIVE, HIST, QUEUE> {
    /// Error-free (EMCY-07: after initialisation nothing is sent).
    pub const fn new() -> Self {
        ErrorState {
            active: Vec::new(),
            history: Vec::new(),
            pending: Queue::new([Emergency { code: 0, register: 0, manufacturer: [0; 5] }; QUEUE]),
            lost: 0,
        }
    }

    /// The error register 1001h (ERR-01, ERR-02). Out of line: raising, clearing and reading 1001h each had
    /// their own copy of the fold (footprint.sh: node 60 B, minimal 28 B); no benchmarked path reads it.
    #[inline(never)]
    pub fn register(&self) -> u8 {
        self.active.iter().fold(0, |r, a| r | a.bits)
    }

    /// Whether `code` is active.
    pub fn is_active(&self, code: u16) -> bool {
        self.active.iter().any(|a| a.code == code)
    }

    /// Raises an error with the register bits of its class; see [`raise_with`](Self::raise_with).
    pub fn raise(&mut self, code: u16, manufacturer: [u8; 5]) -> bool {
        self.raise_with(code, register::bits_for(code), manufacturer)
    }

    /// Raises `code` (setting `bits` in the register): records it at the top of 1003h (ERR-06; the entry is
    /// the code in bits 15–0 and manufacturer bytes 0–1 in bits 31–16, ERR-07) and queues its EMCY. Returns
    /// `false`, doing nothing, when the code is already active or is 0000h (EMCY-05). When more distinct
    /// errors are active than the set holds, the EMCY and the history entry are still produced; the
    /// register keeps the bits of the errors it tracks.
    pub fn raise_with(&mut self, code: u16, bits: u8, manufacturer: [u8; 5]) -> bool {
        let (low, high) = manufacturer_in_registers(manufacturer);
        self.change(code, Some(bits), low, high)
    }

    /// [`raise`](Self::raise) with manufacturer bytes 0-3 in `low` (little-endian) and byte 4 in `high`: the
    /// bytes in registers, for the node's out-of-line `raise_error`.
    pub(crate) fn raise_in_registers(&mut self, code: u16, low: u32, high: u8) -> bool {
        self.change(code, Some(register::bits_for(code)), low, high)
    }

    /// Clears `code`: an EMCY 0000h with the remaining register follows (EMCY-07: "error reset" when it was the
    /// last). Returns `false` when the code was not active.
    pub fn clear(&mut self, code: u16) -> bool {
        self.change(code, None, 0, 0)
    }

    /// Raises `code` with register bits `raise` ([`raise_with`](Self::raise_with)), or clears it (`None`,
    /// [`clear`](Self::clear), the manufacturer bytes all 0): one search of the active set and one queued EMCY
    /// with the register after the change, where each had its own. Out of line, shared by both; the
    /// manufacturer bytes 0-3 in `low` (little-endian) and byte 4 in `high`, in registers rather than an
    /// array on the caller's stack.
    #[inline(never)]
    fn change(&mut self, code: u16, raise: Option<u8>, low: u32, high: u8) -> bool {
        let found = self.active.iter().position(|a| a.code == code);
        let emcy_code = match (raise, found) {
            (Some(bits), None) if code != codes::NO_ERROR => {
                let _ = self.active.push(Active { code, bits: bits | register::GENERIC });
                if HIST > 0 {
                    // Manufacturer bytes 0-1 in bits 31-16 (ERR-07).
                    let info = low << 16;
                    // Vec::insert(0, ..) would be a ptr::copy, i.e. the only users of memmove in a firmware
                    // with insert_sorted (1.5 KB of compiler_builtins); one slot more (unless the history is
                    // full), and the new entry carried through the (at most HIST) entries instead: no index,
                    // so no bounds check and no panic path. In a full history the oldest entry is what is
                    // left in `carry` at the end: dropped, with no pop first.
                    let _ = self.history.push(0);
                    let mut carry = info | u32::from(code);
                    for slot in self.history.iter_mut() {
                        core::mem::swap(slot, &mut carry);
                    }
                }
                code
            }
            (None, Some(i)) => {
                self.active.swap_remove(i);
                codes::NO_ERROR
            }
            _ => return false, // raised already (EMCY-05) or 0000h; or not active
        };
        let [a, b, c, d] = low.to_le_bytes();
        self.queue(Emergency { code: emcy_code, register: self.register(), manufacturer: [a, b, c, d, high] });
        true
    }

    /// 1003h sub-entries 1..=n, newest first.
    pub fn history(&self) -> &[u32] {
        &self.history
    }

    /// Reads 1003h `sub`: sub 0 = number of entries (ERR-05); an empty entry → 0800 0024h (ERR-08); beyond the
    /// depth → 0609 0011h.
    ///
    /// ```
    /// use canopen_core::{emcy::ErrorState, od::AbortCode};
    /// let mut e: ErrorState<2, 4, 4> = ErrorState::new();
    /// assert_eq!(e.read_history(1), Err(AbortCode::NoDataAvailable)); // empty history: 0800 0024h
    /// e.raise(0x8130, [0; 5]);
    /// assert_eq!(e.read_history(0), Ok(1));
    /// assert_eq!(e.read_history(1), Ok(0x0000_8130)); // newest first
    /// assert_eq!(e.read_history(5), Err(AbortCode::SubIndexDoesNotExist));
    /// ```
    pub fn read_history(&self, sub: u8) -> Result<u32, AbortCode> {
        match usize::from(sub) {
            0 => Ok(self.history.len() as u32),
            s if s > HIST => Err(AbortCode::SubIndexDoesNotExist),
            s => self.history.get(s - 1).copied().ok_or(AbortCode::NoDataAvailable),
        }
    }

    /// Writes 1003h sub 0: 0 erases the history, anything else is 0609 0030h (ERR-05).
    ///
    /// ```
    /// use canopen_core::{emcy::ErrorState, od::AbortCode};
    /// let mut e: ErrorState<2, 4, 4> = ErrorState::new();
    /// e.raise(0x1000, [0; 5]);
    /// assert_eq!(e.write_history_count(1), Err(AbortCode::InvalidValue)); // only 0 may be written: 0609 0030h
    /// assert_eq!(e.write_history_count(0), Ok(())); // 0 clears the history
    /// assert!(e.history().is_empty());
    /// ```
    pub fn write_history_count(&mut self, value: u8) -> Result<(), AbortCode> {
        if value != 0 {
            return Err(AbortCode::InvalidValue);
        }
        self.history.clear();
        Ok(())
    }

    /// The next EMCY waiting to go out.
    pub fn pop_pending(&mut self) -> Option<Emergency> {
        self.pending.pop_front()
    }

    /// Whether EMCYs are waiting.
    pub fn has_pending(&self) -> bool {
        !self.pending.is_empty()
    }

    /// Keeps only the most recent pending EMCY (NMT-22: after Stopped, the most recent one is sent).
    pub fn keep_most_recent(&mut self) {
        self.lost = self.lost.saturating_add(self.pending.keep_newest() as u32);
    }

    /// Drops every pending EMCY (there is no EMCY object: 1014h bit 31 set).
    ///
    /// ```
    /// use canopen_core::emcy::ErrorState;
    /// let mut e: ErrorState<2, 4, 4> = ErrorState::new();
    /// e.raise(0x1000, [0; 5]);
    /// e.drop_pending();
    /// assert!(!e.has_pending());
    /// assert_eq!(e.register(), 0x01); // the error stays active
    /// ```
    pub fn drop_pending(&mut self) {
        self.pending.clear();
    }

    /// EMCYs dropped because the queue was full or superseded in Stopped.
    pub const fn lost(&self) -> u32 {
        self.lost
    }

    /// Reset communication / reset node: back to error-free, nothing pending (the history survives: it is
    /// erased only by writing 1003h:00 = 0).
    pub fn reset(&mut self) {
        self.active.clear();
        self.pending.clear();
    }

    /// Queues an EMCY; a full queue drops its oldest, counted in [`lost`](Self::lost).
    fn queue(&mut self, e: Emergency) {
        if self.pending.force_push_back(e) {
            self.lost = self.lost.saturating_add(1);
        }
    }
}

/// The error state a node keeps: 8 distinct active errors, a 1003h history of
/// [`HISTORY`] entries and 8 EMCYs waiting for the inhibit time or for the node to
/// leave Stopped.
pub type NodeErrors = ErrorState<8, HISTORY, 8>;

/// Depth of the 1003h error history of a node (ERR-04): 8, or 0 in a build without the Cargo feature
/// `error-history` (no 1003h, nothing recorded).
pub const HISTORY: usize = if cfg!(feature = "error-history") { 8 } else { 0 };

/// Spaces EMCY frames by the 1015h inhibit time (EMCY-09).
///
/// ```
/// use canopen_core::{emcy::{self, EmcyProducer}, Instant};
/// # if !emcy::INHIBIT { return; }
/// let mut p = EmcyProducer::new();
/// p.set_inhibit_100us(10); // 1 ms
/// assert!(p.may_send(Instant::from_micros(0)));
/// p.sent(Instant::from_micros(0));
/// assert!(!p.may_send(Instant::from_micros(200)));
/// assert_eq!(p.next_allowed(), Some(Instant::from_micros(1000)));
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct EmcyProducer {
    inhibit: Duration,
    next_allowed: Deadline,
}

impl EmcyProducer {
    /// A producer with no inhibit time.
    pub const fn new() -> Self {
        EmcyProducer { inhibit: Duration::ZERO, next_allowed: Deadline::NONE }
    }

    /// Sets 1015h, in 100 µs units (0 = off; always off in a build without it, see [`INHIBIT`]).
    pub fn set_inhibit_100us(&mut self, n: u16) {
        // `sent` starts no inhibit time without 1015h anyway; the 0 here also lets that build drop the
        // conversion (footprint.sh minimal: 24 B).
        self.inhibit = Duration::from_100us(if INHIBIT { u64::from(n) } else { 0 });
        if self.inhibit.is_zero() {
            self.next_allowed = Deadline::NONE;
        }
    }

    /// Whether an EMCY may go out at `now`.
    pub fn may_send(&self, now: Instant) -> bool {
        // No inhibit time running (`Deadline::NONE`, u64::MAX µs) or its end passed, in one comparison: one
        // more than NONE wraps to 0, which every instant has passed, and `now + 1` does not overflow for an
        // instant below 2^63 µs (`Instant`'s bound; beyond it the sum wraps, as `Instant` promises, and
        // never panics).
        !INHIBIT || self.next_allowed.instant().as_micros().wrapping_add(1) <= now.as_micros().wrapping_add(1)
    }

    /// An EMCY went out at `now`.
    pub fn sent(&mut self, now: Instant) {
        if !INHIBIT {
            return;
        }
        self.next_allowed = if self.inhibit.is_zero() { Deadline::NONE } else { Deadline::at(now + self.inhibit) };
    }

    /// When the inhibit time of the last EMCY ends.
    pub const fn next_allowed(&self) -> Option<Instant> {
        self.next_allowed.get()
    }

    /// [`next_allowed`](Self::next_allowed) as a [`Deadline`], for the node's minimum over its services.
    pub(crate) const fn deadline(&self) -> Deadline {
        if INHIBIT {
            self.next_allowed
        } else {
            Deadline::NONE
        }
    }
}

/// Whether this build has 1015h, the EMCY inhibit time (EMCY-09; the Cargo feature `emcy-inhibit`, on by
/// default). Without it the object does not exist and EMCYs go out as soon as they are raised, as with
/// 1015h = 0.
pub const INHIBIT: bool = cfg!(feature = "emcy-inhibit");

/// An EMCY's manufacturer bytes 0-3 as a little-endian `u32` and byte 4: how they travel to the out-of-line
/// raise (in registers, not as an array on the caller's stack).
#[inline]
pub(crate) const fn manufacturer_in_registers(manufacturer: [u8; 5]) -> (u32, u8) {
    let [a, b, c, d, e] = manufacturer;
    (u32::from_le_bytes([a, b, c, d]), e)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// EMCY-09: the inhibit time's test in one comparison holds at the ends of the clock: no inhibit time
    /// lets an EMCY go at once, a running one holds it until its end, and an instant beyond `Instant`'s
    /// 2^63 µs bound (up to u64::MAX) is answered without a panic.
    #[test]
    fn may_send_at_the_ends_of_the_clock_emcy_09() {
        let mut p = EmcyProducer::new();
        let last = Instant::from_micros((1 << 63) - 1);
        assert!(p.may_send(Instant::ZERO) && p.may_send(last));
        let _ = p.may_send(Instant::from_micros(u64::MAX)); // beyond the bound: any answer, no panic
        if !INHIBIT {
            return;
        }
        p.set_inhibit_100us(10); // 1 ms
        p.sent(Instant::from_micros(5_000));
        assert!(!p.may_send(Instant::from_micros(5_999)));
        assert!(p.may_send(Instant::from_micros(6_000)) && p.may_send(last));
        let _ = p.may_send(Instant::from_micros(u64::MAX));
    }

    /// Errors 1000h then 8130h raised and cleared (EMCY 00 10 01, 30 81 11, 00 00 11, 00 00 00), ERR-06/07:
    /// the emergency state machine and the history.
    #[test]
    fn emergency_state_machine_vector() {
        let mut e: ErrorState<4, 8, 8> = ErrorState::new();
        assert!(e.raise(0x1000, [0; 5]));
        assert!(e.raise(0x8130, [0; 5]));
        assert_eq!(e.read_history(0), Ok(2));
        assert_eq!(e.read_history(1), Ok(0x0000_8130));
        assert_eq!(e.read_history(2), Ok(0x0000_1000));
        assert!(e.clear(0x1000));
        assert!(!e.clear(0x1000));
        assert!(e.clear(0x8130));
        let frames: std::vec::Vec<[u8; 8]> = core::iter::from_fn(|| e.pop_pending()).map(|f| f.emit()).collect();
        assert_eq!(
            frames,
            [
                [0x00, 0x10, 0x01, 0, 0, 0, 0, 0],
                [0x30, 0x81, 0x11, 0, 0, 0, 0, 0],
                [0x00, 0x00, 0x11, 0, 0, 0, 0, 0],
                [0x00, 0x00, 0x00, 0, 0, 0, 0, 0],
            ]
        );
    }

    extern crate std;

    /// ERR-06: the history keeps the newest HIST entries; manufacturer info lands in bits 31–16 (ERR-07).
    #[test]
    fn history_depth_and_info() {
        let mut e: ErrorState<8, 3, 8> = ErrorState::new();
        for (i, code) in [0x2310u16, 0x3120, 0x4210, 0x5000].iter().enumerate() {
            e.raise(*code, [i as u8, 0xAB, 0, 0, 0]);
        }
        assert_eq!(e.history(), &[0xAB03_5000, 0xAB02_4210, 0xAB01_3120]);
        assert_eq!(e.register(), 0x01 | 0x02 | 0x04 | 0x08);
        assert!(!e.raise(0, [0; 5]));
    }

    /// EMCY-05/EMCY-07 with more distinct errors than the active set holds: the extra error still gets its
    /// EMCY and its 1003h entry (ERR-06), is not tracked (not active, its bits not in the register, clearing
    /// it sends nothing), and raising it again sends it again; a freed place takes the next new error.
    /// Code 0000h is never active. ERR-05/EMCY-07: a reset leaves the history, writing 1003h:00 = 0 empties
    /// it (ERR-08).
    #[test]
    fn full_active_set_code_zero_and_history_lifetime() {
        let mut e: ErrorState<2, 4, 8> = ErrorState::new();
        assert!(!e.is_active(0) && !e.clear(0));
        assert!(e.raise(0x2310, [0; 5]) && e.raise(0x3120, [0; 5]));
        assert!(e.raise(0x4210, [0; 5])); // a third: EMCY and history, not tracked
        assert!(!e.is_active(0x4210) && !e.clear(0x4210));
        assert_eq!(e.register(), 0x01 | 0x02 | 0x04);
        assert!(e.raise(0x4210, [0; 5])); // not active, so a new error event again
        assert_eq!(e.read_history(0), Ok(4));
        assert_eq!(e.history(), &[0x4210, 0x4210, 0x3120, 0x2310]);
        assert!(!e.is_active(0) && !e.clear(0));
        assert!(e.clear(0x2310));
        assert!(e.raise(0x4210, [0; 5])); // the freed place tracks it now
        assert!(e.is_active(0x4210) && e.is_active(0x3120));
        assert_eq!(e.register(), 0x01 | 0x04 | 0x08);
        let codes: std::vec::Vec<(u16, u8)> =
            core::iter::from_fn(|| e.pop_pending()).map(|f| (f.code, f.register)).collect();
        assert_eq!(
            codes,
            [(0x2310, 0x03), (0x3120, 0x07), (0x4210, 0x07), (0x4210, 0x07), (0x0000, 0x05), (0x4210, 0x0D)]
        );
        e.reset();
        assert_eq!((e.register(), e.is_active(0x4210), e.read_history(0)), (0, false, Ok(4)));
        assert_eq!(e.history(), &[0x4210, 0x4210, 0x4210, 0x3120]); // the oldest fell out at depth 4
        assert!(e.raise(0x3120, [0; 5]) && e.clear(0x3120));
        assert_eq!(e.write_history_count(0), Ok(()));
        assert_eq!((e.read_history(0), e.read_history(1)), (Ok(0), Err(AbortCode::NoDataAvailable)));
        assert_eq!(e.history(), &[] as &[u32]);
        assert!(e.raise(0x5000, [0x34, 0x12, 0, 0, 0]));
        assert_eq!(e.history(), &[0x1234_5000]);
    }

    /// A full queue drops the oldest and counts it; keep_most_recent keeps the last (NMT-22).
    #[test]
    fn queue_bounds() {
        let mut e: ErrorState<8, 0, 2> = ErrorState::new();
        e.raise(0x1000, [0; 5]);
        e.raise(0x2000, [0; 5]);
        e.raise(0x3000, [0; 5]);
        assert_eq!(e.lost(), 1);
        e.keep_most_recent();
        assert_eq!(e.pop_pending().map(|f| f.code), Some(0x3000));
        assert_eq!(e.pop_pending(), None);
    }
}
