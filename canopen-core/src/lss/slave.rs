//! The LSS slave (CiA 305): see the [module docs](super) for what is served where, node-IDs, bit timing and store.

use super::Identity;
use crate::cob::NodeId;
use crate::time::{Duration, Instant};
use crate::wire::lss::{
    cs, frame_u32, BitRate, IdentityField, LssMode, LssResponse, Status, FASTSCAN_CONFIRM, UNCONFIGURED_NODE_ID,
};

/// Something the LSS slave tells the application (inside `Event::Lss`).
///
/// ```
/// use canopen_core::{lss::LssEvent, wire::lss::LssMode};
/// let e = LssEvent::ModeChanged(LssMode::Configuration);
/// assert!(matches!(e, LssEvent::ModeChanged(LssMode::Configuration)));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum LssEvent {
    /// The LSS state changed (switch state global/selective, fastscan match).
    ModeChanged(LssMode),
    /// Configure node-ID set the pending node-ID (1–127, or FFh = unconfigured).
    NodeIdConfigured {
        /// The raw pending node-ID.
        pending: u8,
    },
    /// Configure bit timing set the pending bit rate.
    BitRateConfigured(BitRate),
    /// Activate bit timing was received: the bit rate switches one switch delay later
    /// ([`LssEvent::SwitchBitRate`]), transmission resumes one more switch delay after that
    /// ([`LssEvent::TransmitResumed`]; [`LssSlave::poll_timeout`] has the instants).
    BitRateActivation {
        /// The pending bit rate that becomes active.
        bit_rate: BitRate,
        /// The switch delay, ms: the length of each of the two periods.
        switch_delay_ms: u16,
    },
    /// The first switch delay has passed: the driver switches the controller to `bit_rate` now. The node
    /// holds its transmit queue until [`LssEvent::TransmitResumed`].
    SwitchBitRate(BitRate),
    /// The second switch delay has passed; the node transmits again.
    TransmitResumed,
    /// Store configuration was requested; answer with `Node::complete_lss_store`.
    StoreRequested {
        /// The pending node-ID to store (FFh = unconfigured).
        node_id: u8,
        /// The pending bit rate to store.
        bit_rate: BitRate,
    },
}

/// Why a store failed; maps onto the 17h error codes.
///
/// ```
/// use canopen_core::{lss::StoreError, wire::lss::Status};
/// assert_eq!(StoreError::MediaAccess.status(), Status { error: 2, spec: 0 });
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum StoreError {
    /// 01h: store configuration is not supported.
    NotSupported,
    /// 02h: storage media access error.
    MediaAccess,
    /// FFh: implementation-specific error with this code.
    Manufacturer(u8),
}

impl StoreError {
    /// The wire status.
    ///
    /// ```
    /// use canopen_core::lss::StoreError;
    /// assert_eq!(StoreError::Manufacturer(4).status().spec, 4);
    /// ```
    pub const fn status(self) -> Status {
        match self {
            StoreError::NotSupported => Status::NOT_SUPPORTED,
            StoreError::MediaAccess => Status::MEDIA_ACCESS,
            StoreError::Manufacturer(spec) => Status::manufacturer(spec),
        }
    }
}

/// ```
/// use canopen_core::lss::StoreError;
/// assert_eq!(StoreError::Manufacturer(4).to_string(), "LSS store failed: manufacturer error 04h");
/// ```
impl core::fmt::Display for StoreError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            StoreError::NotSupported => f.write_str("LSS store configuration is not supported"),
            StoreError::MediaAccess => f.write_str("LSS store failed: storage media access error"),
            StoreError::Manufacturer(e) => write!(f, "LSS store failed: manufacturer error {e:02X}h"),
        }
    }
}

impl core::error::Error for StoreError {}

/// Non-volatile storage of the LSS configuration, implemented by the application.
///
/// Only two values travel, so this can sit on top of a general parameter storage (the 1010h `Storage`
/// trait) or a file.
///
/// ```
/// use canopen_core::{lss::{LssStore, StoreError}, wire::lss::BitRate};
/// #[derive(Default)]
/// struct Ram(Option<(u8, BitRate)>);
/// impl LssStore for Ram {
///     fn store(&mut self, node_id: u8, bit_rate: BitRate) -> Result<(), StoreError> {
///         self.0 = Some((node_id, bit_rate));
///         Ok(())
///     }
/// }
/// let mut ram = Ram::default();
/// ram.store(0x22, BitRate::K250).unwrap();
/// assert_eq!(ram.0, Some((0x22, BitRate::K250)));
/// ```
pub trait LssStore {
    /// Stores the pending node-ID (1–127 or FFh) and bit rate so that the next power-up uses them.
    ///
    /// ```
    /// use canopen_core::{lss::{LssStore, StoreError}, wire::lss::BitRate};
    /// struct ReadOnly;
    /// impl LssStore for ReadOnly {
    ///     fn store(&mut self, _: u8, _: BitRate) -> Result<(), StoreError> {
    ///         Err(StoreError::NotSupported)
    ///     }
    /// }
    /// assert_eq!(ReadOnly.store(1, BitRate::K125), Err(StoreError::NotSupported));
    /// ```
    fn store(&mut self, node_id: u8, bit_rate: BitRate) -> Result<(), StoreError>;
}

/// What one request produced.
///
/// ```
/// use canopen_core::lss::LssOutput;
/// assert_eq!(LssOutput::default().response, None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LssOutput {
    /// The frame to send on 7E4h, if the spec asks for one.
    pub response: Option<LssResponse>,
    /// What to tell the application.
    pub event: Option<LssEvent>,
    /// The node got its first node-ID and left LSS configuration: run NMT reset communication now.
    pub reset_communication: bool,
}

/// What one request produced, before typing: the response as its command specifier (0 = none) and the
/// value in bytes 1-4 (for a status: error code, then the implementation-specific error).
#[derive(Debug, Default)]
pub(crate) struct Served {
    pub(crate) cs: u8,
    pub(crate) value: u32,
    pub(crate) event: Option<LssEvent>,
}

impl Served {
    fn respond(&mut self, cs: u8, value: u32) {
        self.cs = cs;
        self.value = value;
    }
}

/// The status values of a configure/store response in [`Served::value`].
const SUCCESS: u32 = 0;
const NOT_SUPPORTED: u32 = 1;

/// Bit mask of the CiA 301 table rates (indices 0–4, 6–8), the default set of supported bit rates.
///
/// ```
/// use canopen_core::{lss::CIA301_BIT_RATES, wire::lss::BitRate};
/// assert!(CIA301_BIT_RATES & (1 << BitRate::K500.index()) != 0);
/// assert!(CIA301_BIT_RATES & (1 << BitRate::Auto.index()) == 0);
/// ```
pub const CIA301_BIT_RATES: u16 = 0b1_1101_1111;

/// The LSS slave: LSS waiting / configuration, node-ID and bit-rate configuration, identification and
/// fastscan.
///
/// ```
/// use canopen_core::{lss::{Identity, LssSlave}, wire::lss::{LssMode, LssRequest, LssResponse}, Instant};
/// let id = Identity { vendor_id: 1, product_code: 2, revision: 3, serial: 4 };
/// let mut s = LssSlave::new(&id, None);
/// let now = Instant::ZERO;
/// s.handle_request(now, &LssRequest::SwitchStateGlobal(LssMode::Configuration).emit());
/// let out = s.handle_request(now, &LssRequest::ConfigureNodeId(0x22).emit());
/// assert_eq!(out.response, Some(LssResponse::NodeIdConfigured(canopen_core::wire::lss::Status::SUCCESS)));
/// // Back to waiting: the node had no node-ID, so it resets communication with the new one.
/// let out = s.handle_request(now, &LssRequest::SwitchStateGlobal(LssMode::Waiting).emit());
/// assert!(out.reset_communication);
/// assert_eq!(s.apply_pending().map(|n| n.get()), Some(0x22));
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LssSlave {
    address: [u32; 4],
    mode: LssMode,
    active: u8,
    pending: u8,
    bit_rate: BitRate,
    pending_bit_rate: BitRate,
    supported: u16,
    store_supported: bool,
    store_pending: bool,
    /// The command specifier of the next expected part: of switch state selective (40h..43h), of identify
    /// remote slave (46h..4Bh).
    sequence_next: [u8; 2],
    /// Fastscan LSSPos (0–3).
    fastscan_pos: u8,
    /// Activate bit timing: the end of the first switch delay (the bit rate switches) and of the second
    /// (transmission resumes).
    switch_at: [Instant; 2],
    /// Which of `switch_at` is next: 0 or 1, [`SWITCH_IDLE`] when no switch is under way.
    switch_phase: u8,
    /// The bit rate activate bit timing switches to.
    switch_rate: BitRate,
}

/// `LssSlave::switch_phase` with no switch under way.
const SWITCH_IDLE: u8 = 2;

impl LssSlave {
    /// A slave in LSS waiting with the LSS address `identity` (1018h) and active node-ID `node_id`
    /// (`None` = FFh, unconfigured). The bit rate defaults to 125 kbit/s; set the real one with
    /// [`set_bit_rate`](Self::set_bit_rate).
    ///
    /// ```
    /// use canopen_core::{lss::{Identity, LssSlave}, NodeId};
    /// let s = LssSlave::new(&Identity::default(), NodeId::new(5));
    /// assert_eq!(s.pending_node_id(), 5);
    /// ```
    pub fn new(identity: &Identity, node_id: Option<NodeId>) -> Self {
        let raw = node_id.map_or(UNCONFIGURED_NODE_ID, NodeId::get);
        LssSlave {
            address: [identity.vendor_id, identity.product_code, identity.revision, identity.serial],
            mode: LssMode::Waiting,
            active: raw,
            pending: raw,
            bit_rate: BitRate::K125,
            pending_bit_rate: BitRate::K125,
            supported: CIA301_BIT_RATES,
            store_supported: false,
            store_pending: false,
            sequence_next: [cs::SWITCH_STATE_SELECTIVE_VENDOR, cs::IDENTIFY_REMOTE_VENDOR],
            fastscan_pos: 0,
            switch_at: [Instant::ZERO; 2],
            switch_phase: SWITCH_IDLE,
            switch_rate: BitRate::K125,
        }
    }

    /// The LSS state.
    ///
    /// ```
    /// # use canopen_core::{lss::{Identity, LssSlave}, wire::lss::LssMode};
    /// assert_eq!(LssSlave::new(&Identity::default(), None).mode(), LssMode::Waiting);
    /// ```
    pub const fn mode(&self) -> LssMode {
        self.mode
    }

    /// The active node-ID, `None` while unconfigured (FFh).
    ///
    /// ```
    /// # use canopen_core::{lss::{Identity, LssSlave}, NodeId};
    /// let n = NodeId::new(3);
    /// assert_eq!(LssSlave::new(&Identity::default(), n).active_node_id(), n);
    /// ```
    pub const fn active_node_id(&self) -> Option<NodeId> {
        NodeId::new(self.active)
    }

    /// The raw pending node-ID (1–127, or FFh).
    ///
    /// ```
    /// # use canopen_core::lss::{Identity, LssSlave};
    /// assert_eq!(LssSlave::new(&Identity::default(), None).pending_node_id(), 0xFF);
    /// ```
    pub const fn pending_node_id(&self) -> u8 {
        self.pending
    }

    /// Whether both the active and the pending node-ID are FFh (the fastscan and 4Ch condition).
    ///
    /// ```
    /// # use canopen_core::lss::{Identity, LssSlave};
    /// assert!(LssSlave::new(&Identity::default(), None).is_unconfigured());
    /// ```
    pub const fn is_unconfigured(&self) -> bool {
        // Each is 1-127 or FFh, so both are FFh exactly when their AND is.
        self.active & self.pending == UNCONFIGURED_NODE_ID
    }

    /// The active bit rate as far as LSS knows (what the application set, or the last activated one).
    ///
    /// ```
    /// # use canopen_core::{lss::{Identity, LssSlave}, wire::lss::BitRate};
    /// assert_eq!(LssSlave::new(&Identity::default(), None).bit_rate(), BitRate::K125);
    /// ```
    pub const fn bit_rate(&self) -> BitRate {
        self.bit_rate
    }

    /// The pending bit rate (configured, not yet activated).
    ///
    /// ```
    /// # use canopen_core::{lss::{Identity, LssSlave}, wire::lss::BitRate};
    /// assert_eq!(LssSlave::new(&Identity::default(), None).pending_bit_rate(), BitRate::K125);
    /// ```
    pub const fn pending_bit_rate(&self) -> BitRate {
        self.pending_bit_rate
    }

    /// Tells LSS the bit rate the node runs at (active and pending).
    ///
    /// ```
    /// # use canopen_core::{lss::{Identity, LssSlave}, wire::lss::BitRate};
    /// let mut s = LssSlave::new(&Identity::default(), None);
    /// s.set_bit_rate(BitRate::K500);
    /// assert_eq!(s.pending_bit_rate(), BitRate::K500);
    /// ```
    pub fn set_bit_rate(&mut self, bit_rate: BitRate) {
        self.bit_rate = bit_rate;
        self.pending_bit_rate = bit_rate;
    }

    /// The bit rates configure bit timing accepts: bit *i* set = table index *i* supported. Default
    /// [`CIA301_BIT_RATES`] (every CiA 301 rate, no automatic detection).
    ///
    /// ```
    /// # use canopen_core::lss::{Identity, LssSlave};
    /// let mut s = LssSlave::new(&Identity::default(), None);
    /// s.set_supported_bit_rates(1 << 2 | 1 << 3); // 500 and 250 kbit/s only
    /// ```
    pub fn set_supported_bit_rates(&mut self, mask: u16) {
        self.supported = mask;
    }

    /// Whether store configuration is served (the application answers [`LssEvent::StoreRequested`]);
    /// when false (the default) it is answered with error 01h.
    ///
    /// ```
    /// # use canopen_core::lss::{Identity, LssSlave};
    /// let mut s = LssSlave::new(&Identity::default(), None);
    /// s.set_store_supported(true);
    /// ```
    pub fn set_store_supported(&mut self, supported: bool) {
        self.store_supported = supported;
    }

    /// Whether a store request waits for [`complete_store`](Self::complete_store).
    ///
    /// ```
    /// # use canopen_core::lss::{Identity, LssSlave};
    /// assert!(!LssSlave::new(&Identity::default(), None).store_pending());
    /// ```
    pub const fn store_pending(&self) -> bool {
        self.store_pending
    }

    /// NMT reset communication: the pending node-ID becomes active. Returns the active node-ID, `None`
    /// if the node has none (it then stays in Initialisation, serving LSS only).
    ///
    /// ```
    /// # use canopen_core::{lss::{Identity, LssSlave}, NodeId};
    /// let mut s = LssSlave::new(&Identity::default(), NodeId::new(4));
    /// assert_eq!(s.apply_pending(), NodeId::new(4));
    /// ```
    pub fn apply_pending(&mut self) -> Option<NodeId> {
        self.active = self.pending;
        NodeId::new(self.active)
    }

    /// Handles one frame received on 7E5h (its data bytes). Malformed frames and requests the current
    /// state does not serve are ignored (an empty output).
    ///
    /// ```
    /// use canopen_core::{lss::{Identity, LssSlave}, wire::lss::LssResponse, Instant};
    /// let mut s = LssSlave::new(&Identity::default(), None);
    /// // Inquire node-ID in LSS waiting: silence.
    /// assert_eq!(s.handle_request(Instant::ZERO, &[0x5E, 0, 0, 0, 0, 0, 0, 0]).response, None);
    /// // Identify non-configured: answered 50h.
    /// let out = s.handle_request(Instant::ZERO, &[0x4C, 0, 0, 0, 0, 0, 0, 0]);
    /// assert_eq!(out.response, Some(LssResponse::IdentifyNonConfiguredSlave));
    /// ```
    pub fn handle_request(&mut self, now: Instant, data: &[u8]) -> LssOutput {
        let s = self.serve(now, data);
        // The typed response is the frame read back: the node sends the frame and never builds the enum.
        let response = if s.cs == 0 { None } else { LssResponse::parse(&frame_u32(s.cs, s.value)).ok() };
        LssOutput {
            response,
            event: s.event,
            reset_communication: s.event.is_some_and(|e| self.resets_communication(e)),
        }
    }

    /// [`handle_request`](Self::handle_request) with the response as its frame's command specifier and
    /// value (what the node sends on 7E4h), so that no typed response is built and emitted on the way.
    pub(crate) fn serve(&mut self, now: Instant, data: &[u8]) -> Served {
        let mut out = Served::default();
        // Every LSS request is 8 bytes (CAN-07: anything else is ignored).
        let Ok(d) = <&[u8; 8]>::try_from(data) else { return out };
        // The whole frame as one number: the command specifier and the value in bytes 1-4 are shifts of it.
        let raw = u64::from_le_bytes(*d);
        let command = raw as u8;
        let value = (raw >> 8) as u32;
        let configuration = self.mode == LssMode::Configuration;
        // Dispatched on the command specifier: no request enum in between, each arm reads its fields from
        // the frame (the layouts are `wire::lss`'s table). Unknown specifiers, out-of-range fields and
        // requests the current state does not serve fall through to silence.
        match command {
            // Byte 1 the mode: 0 waiting, 1 configuration.
            cs::SWITCH_STATE_GLOBAL if d[1] < 2 => {
                let mode = if d[1] != 0 { LssMode::Configuration } else { LssMode::Waiting };
                out.event = self.enter(mode);
            }
            // 40h-43h switch state selective (LSS waiting only) and 46h-4Bh identify remote slave: one rule for
            // both, the parts in order (an out-of-order or wrong part restarts), each with its own position.
            cs::SWITCH_STATE_SELECTIVE_VENDOR..=cs::IDENTIFY_REMOTE_SERIAL_HIGH
                if command & 0xFE != cs::SWITCH_STATE_SELECTIVE_RESPONSE
                    && (command >= cs::IDENTIFY_REMOTE_VENDOR || !configuration) =>
            {
                let identify = command >= cs::IDENTIFY_REMOTE_VENDOR;
                let first = if identify { cs::IDENTIFY_REMOTE_VENDOR } else { cs::SWITCH_STATE_SELECTIVE_VENDOR };
                let matches = self.part_matches(command - cs::SWITCH_STATE_SELECTIVE_VENDOR, value);
                let next = &mut self.sequence_next[usize::from(identify)];
                let in_order = command == first || command == *next;
                *next = first;
                if !(in_order && matches) {
                    // restarted
                } else if command == first + if identify { 5 } else { 3 } {
                    if identify {
                        out.respond(cs::IDENTIFY_SLAVE, 0);
                    } else {
                        out.respond(cs::SWITCH_STATE_SELECTIVE_RESPONSE, 0);
                        out.event = self.enter(LssMode::Configuration);
                    }
                } else {
                    *next = command + 1;
                }
            }
            cs::IDENTIFY_NON_CONFIGURED_REMOTE if self.is_unconfigured() => {
                out.respond(cs::IDENTIFY_NON_CONFIGURED_SLAVE, 0);
            }
            cs::FASTSCAN if !configuration && self.is_unconfigured() => {
                if let (Some(sub), Some(next)) = (IdentityField::from_index(d[6]), IdentityField::from_index(d[7])) {
                    out = self.fastscan(value, d[5], sub, next);
                }
            }
            cs::CONFIGURE_NODE_ID if configuration => {
                let id = d[1];
                let status = if NodeId::new(id).is_some() || id == UNCONFIGURED_NODE_ID {
                    self.pending = id;
                    out.event = Some(LssEvent::NodeIdConfigured { pending: id });
                    SUCCESS
                } else {
                    NOT_SUPPORTED
                };
                out.respond(cs::CONFIGURE_NODE_ID, status);
            }
            cs::CONFIGURE_BIT_TIMING if configuration => {
                // Byte 1 the table selector (0 only), byte 2 the index.
                let rate = BitRate::from_index(d[2]).filter(|r| d[1] == 0 && self.supported & (1 << r.index()) != 0);
                let status = match rate {
                    Some(r) => {
                        self.pending_bit_rate = r;
                        out.event = Some(LssEvent::BitRateConfigured(r));
                        SUCCESS
                    }
                    None => NOT_SUPPORTED,
                };
                out.respond(cs::CONFIGURE_BIT_TIMING, status);
            }
            cs::ACTIVATE_BIT_TIMING if configuration => {
                let switch_delay_ms = u16::from_le_bytes([d[1], d[2]]);
                // At most 65,535,000 µs: a 32-bit product, no 64-bit saturating multiply.
                let delay = Duration::from_micros(u64::from(u32::from(switch_delay_ms) * 1000));
                let switch_at = now + delay;
                let resume_at = switch_at + delay;
                self.switch_at = [switch_at, resume_at];
                self.switch_phase = 0;
                self.switch_rate = self.pending_bit_rate;
                out.event = Some(LssEvent::BitRateActivation { bit_rate: self.pending_bit_rate, switch_delay_ms });
            }
            cs::STORE_CONFIGURATION if configuration => {
                if self.store_supported {
                    self.store_pending = true;
                    out.event =
                        Some(LssEvent::StoreRequested { node_id: self.pending, bit_rate: self.pending_bit_rate });
                } else {
                    out.respond(cs::STORE_CONFIGURATION, NOT_SUPPORTED);
                }
            }
            // 5Ah-5Dh the LSS address parts, 5Eh the active node-ID.
            cs::INQUIRE_VENDOR..=cs::INQUIRE_NODE_ID if configuration => {
                let v = self.address.get(usize::from(command - cs::INQUIRE_VENDOR)).copied();
                out.respond(command, v.unwrap_or(u32::from(self.active)));
            }
            _ => {}
        }
        out
    }

    /// Whether `event`, just reported by [`serve`](Self::serve), means reset communication: CANopenNode
    /// CO_LSSslave.c, an unconfigured node that got a node-ID and is switched from LSS configuration back to
    /// waiting resets communication (switch state global leaves both node-IDs as they were).
    pub(crate) fn resets_communication(&self, event: LssEvent) -> bool {
        event == LssEvent::ModeChanged(LssMode::Waiting)
            && self.active == UNCONFIGURED_NODE_ID
            && self.pending != UNCONFIGURED_NODE_ID
    }

    /// The answer to a pending store request, once the application has stored (or failed to); `None` if
    /// no store was requested.
    ///
    /// ```
    /// # use canopen_core::lss::{Identity, LssSlave};
    /// let mut s = LssSlave::new(&Identity::default(), None);
    /// assert_eq!(s.complete_store(Ok(())), None);
    /// ```
    pub fn complete_store(&mut self, result: Result<(), StoreError>) -> Option<LssResponse> {
        if !core::mem::take(&mut self.store_pending) {
            return None;
        }
        Some(LssResponse::Stored(result.map_or_else(StoreError::status, |()| Status::SUCCESS)))
    }

    /// The next instant [`handle_timeout`](Self::handle_timeout) has work (the ends of the switch delays).
    ///
    /// ```
    /// # use canopen_core::lss::{Identity, LssSlave};
    /// assert_eq!(LssSlave::new(&Identity::default(), None).poll_timeout(), None);
    /// ```
    pub fn poll_timeout(&self) -> Option<Instant> {
        self.switch_at.get(usize::from(self.switch_phase)).copied()
    }

    /// Acts on the time that passed: reports [`LssEvent::SwitchBitRate`] at the end of the first delay and
    /// [`LssEvent::TransmitResumed`] at the end of the second.
    ///
    /// ```
    /// use canopen_core::{lss::{Identity, LssEvent, LssSlave}, wire::lss::LssMode, Instant};
    /// let mut s = LssSlave::new(&Identity::default(), None);
    /// s.handle_request(Instant::ZERO, &[0x04, 1, 0, 0, 0, 0, 0, 0]);
    /// s.handle_request(Instant::ZERO, &[0x15, 10, 0, 0, 0, 0, 0, 0]); // 10 ms switch delay
    /// assert!(matches!(s.handle_timeout(Instant::from_millis(10)), Some(LssEvent::SwitchBitRate(_))));
    /// assert_eq!(s.handle_timeout(Instant::from_millis(20)), Some(LssEvent::TransmitResumed));
    /// ```
    pub fn handle_timeout(&mut self, now: Instant) -> Option<LssEvent> {
        let phase = self.switch_phase;
        if now < *self.switch_at.get(usize::from(phase))? {
            return None;
        }
        self.switch_phase = phase + 1; // after the second period: SWITCH_IDLE
        if phase == 0 {
            self.bit_rate = self.switch_rate;
            return Some(LssEvent::SwitchBitRate(self.switch_rate));
        }
        Some(LssEvent::TransmitResumed)
    }

    /// Whether the node must not transmit at `now` (between the bit-rate switch and the end of the second
    /// switch delay).
    ///
    /// ```
    /// # use canopen_core::{lss::{Identity, LssSlave}, Instant};
    /// assert!(!LssSlave::new(&Identity::default(), None).holds_transmit(Instant::ZERO));
    /// ```
    pub fn holds_transmit(&self, now: Instant) -> bool {
        self.switch_phase != SWITCH_IDLE && now >= self.switch_at[0] && now < self.switch_at[1]
    }

    /// Enters `mode` (restarting switch state selective); the event when the mode changed. Left to LLVM, which
    /// inlines it into `serve` once fastscan is inlined there too (out of line it was 32 B more of the node
    /// firmware's flash).
    fn enter(&mut self, mode: LssMode) -> Option<LssEvent> {
        self.sequence_next[0] = cs::SWITCH_STATE_SELECTIVE_VENDOR;
        if self.mode == mode {
            return None;
        }
        self.mode = mode;
        Some(LssEvent::ModeChanged(mode))
    }

    /// Whether `value` matches the sequence part `i` = command specifier - 40h: 40h-43h (switch state
    /// selective), 46h vendor-ID and 47h product code exactly (`<=` and `>=`), 48h/4Ah the low bound of the
    /// revision/serial number (`value <= own`), 49h/4Bh the high bound (`value >= own`).
    fn part_matches(&self, i: u8, value: u32) -> bool {
        const PART: u32 = 0b11_11_10_10_01_00_00_00_11_10_01_00; // the LSS address part of 40h..4Bh, 2 bits each
        const LOW: u16 = 0b0101_1100_1111; // the parts that need `value <= own`
        const HIGH: u16 = 0b1010_1100_1111; // the parts that need `value >= own`
        let own = self.address[(PART >> (2 * i) & 3) as usize];
        // The bound that `value` is on the wrong side of, if any, must not be one this part checks.
        let violated = if value < own {
            HIGH
        } else if value > own {
            LOW
        } else {
            0
        };
        violated >> i & 1 == 0
    }

    /// One fastscan step (CANopenNode/lely rule; see the module docs). Inlined into `serve`, its only caller:
    /// out of line, its `Served` went back through memory (footprint.sh node 32 B more).
    #[inline(always)]
    fn fastscan(&mut self, id_number: u32, bit_check: u8, sub: IdentityField, next: IdentityField) -> Served {
        let mut out = Served::default();
        if bit_check == FASTSCAN_CONFIRM {
            self.fastscan_pos = 0;
            out.respond(cs::IDENTIFY_SLAVE, 0);
            return out;
        }
        // BitCheck is 0..=31 or 80h; a slave ignores any other value.
        if bit_check > 31 || self.fastscan_pos != sub.index() {
            return out;
        }
        let mask = u32::MAX << bit_check;
        if (id_number ^ self.address[usize::from(sub.index())]) & mask != 0 {
            return out;
        }
        self.fastscan_pos = next.index();
        out.respond(cs::IDENTIFY_SLAVE, 0);
        if bit_check == 0 && next.index() < sub.index() {
            out.event = self.enter(LssMode::Configuration);
        }
        out
    }
}

/// A placeholder node-ID for a node that has none yet; never used on the bus (the node serves only LSS
/// while unconfigured).
pub(crate) const PLACEHOLDER_NODE_ID: NodeId = match NodeId::new(127) {
    Some(n) => n,
    None => panic!("127 is a valid node-ID"),
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wire::lss::{IdentifyPart, LssRequest};

    const ID: Identity = Identity { vendor_id: 0x0000_0123, product_code: 0x42, revision: 0x0001_0002, serial: 77 };
    const T0: Instant = Instant::ZERO;

    fn req(s: &mut LssSlave, r: LssRequest) -> LssOutput {
        s.handle_request(T0, &r.emit())
    }

    fn config(s: &mut LssSlave) {
        req(s, LssRequest::SwitchStateGlobal(LssMode::Configuration));
    }

    #[test]
    fn config_services_are_silent_in_waiting() {
        let mut s = LssSlave::new(&ID, NodeId::new(5));
        for r in [
            LssRequest::ConfigureNodeId(9),
            LssRequest::ConfigureBitTiming { table_selector: 0, table_index: 2 },
            LssRequest::ActivateBitTiming { switch_delay_ms: 10 },
            LssRequest::StoreConfiguration,
            LssRequest::Inquire(IdentityField::Serial),
            LssRequest::InquireNodeId,
        ] {
            assert_eq!(req(&mut s, r), LssOutput::default(), "{r:?}");
        }
        assert_eq!(s.pending_node_id(), 5);
        assert_eq!(s.poll_timeout(), None);
    }

    #[test]
    fn switch_selective_in_order_only() {
        let mut s = LssSlave::new(&ID, NodeId::new(5));
        let sel = |f, v| LssRequest::SwitchStateSelective(f, v);
        use IdentityField::*;
        // Out of order: product first.
        req(&mut s, sel(ProductCode, 0x42));
        req(&mut s, sel(Revision, 0x0001_0002));
        assert_eq!(req(&mut s, sel(Serial, 77)).response, None);
        // One wrong part restarts.
        req(&mut s, sel(VendorId, 0x123));
        req(&mut s, sel(ProductCode, 0x43));
        req(&mut s, sel(Revision, 0x0001_0002));
        assert_eq!(req(&mut s, sel(Serial, 77)).response, None);
        assert_eq!(s.mode(), LssMode::Waiting);
        // Right.
        for (f, v) in [(VendorId, 0x123), (ProductCode, 0x42), (Revision, 0x0001_0002)] {
            assert_eq!(req(&mut s, sel(f, v)), LssOutput::default());
        }
        let out = req(&mut s, sel(Serial, 77));
        assert_eq!(out.response, Some(LssResponse::SwitchStateSelective));
        assert_eq!(out.event, Some(LssEvent::ModeChanged(LssMode::Configuration)));
        // In configuration, selective is not served.
        for (f, v) in [(VendorId, 0x123), (ProductCode, 0x42), (Revision, 0x0001_0002), (Serial, 77)] {
            assert_eq!(req(&mut s, sel(f, v)), LssOutput::default());
        }
    }

    #[test]
    fn configure_node_id_and_inquire() {
        let mut s = LssSlave::new(&ID, NodeId::new(5));
        config(&mut s);
        for bad in [0u8, 128, 0xFE] {
            assert_eq!(
                req(&mut s, LssRequest::ConfigureNodeId(bad)).response,
                Some(LssResponse::NodeIdConfigured(Status::NOT_SUPPORTED))
            );
        }
        let out = req(&mut s, LssRequest::ConfigureNodeId(9));
        assert_eq!(out.response, Some(LssResponse::NodeIdConfigured(Status::SUCCESS)));
        assert_eq!(out.event, Some(LssEvent::NodeIdConfigured { pending: 9 }));
        // Inquire reports the active node-ID until reset communication.
        assert_eq!(req(&mut s, LssRequest::InquireNodeId).response, Some(LssResponse::NodeId(5)));
        // A configured node does not reset by itself when switched to waiting.
        assert!(!req(&mut s, LssRequest::SwitchStateGlobal(LssMode::Waiting)).reset_communication);
        assert_eq!(s.apply_pending(), NodeId::new(9));
        config(&mut s);
        assert_eq!(req(&mut s, LssRequest::InquireNodeId).response, Some(LssResponse::NodeId(9)));
        for f in IdentityField::ALL {
            let v = [0x123, 0x42, 0x0001_0002, 77][usize::from(f.index())];
            assert_eq!(req(&mut s, LssRequest::Inquire(f)).response, Some(LssResponse::Identity(f, v)));
        }
        // FFh is accepted and makes the node unconfigured at the next reset communication.
        assert_eq!(
            req(&mut s, LssRequest::ConfigureNodeId(0xFF)).response,
            Some(LssResponse::NodeIdConfigured(Status::SUCCESS))
        );
        assert_eq!(s.apply_pending(), None);
        assert!(s.is_unconfigured());
    }

    #[test]
    fn bit_timing_configure_and_activate() {
        let mut s = LssSlave::new(&ID, NodeId::new(5));
        config(&mut s);
        let bt = |sel, idx| LssRequest::ConfigureBitTiming { table_selector: sel, table_index: idx };
        for (sel, idx) in [(0u8, 5u8), (0, 9), (0, 10), (1, 2), (0x80, 2)] {
            assert_eq!(
                req(&mut s, bt(sel, idx)).response,
                Some(LssResponse::BitTimingConfigured(Status::NOT_SUPPORTED))
            );
        }
        let out = req(&mut s, bt(0, 3));
        assert_eq!(out.response, Some(LssResponse::BitTimingConfigured(Status::SUCCESS)));
        assert_eq!(out.event, Some(LssEvent::BitRateConfigured(BitRate::K250)));
        let t = Instant::from_millis(1000);
        let out = s.handle_request(t, &LssRequest::ActivateBitTiming { switch_delay_ms: 100 }.emit());
        assert_eq!(out.response, None);
        assert_eq!(out.event, Some(LssEvent::BitRateActivation { bit_rate: BitRate::K250, switch_delay_ms: 100 }));
        assert!(!s.holds_transmit(Instant::from_millis(1099)));
        assert_eq!(s.poll_timeout(), Some(Instant::from_millis(1100)));
        assert_eq!(s.handle_timeout(Instant::from_millis(1099)), None);
        assert_eq!(s.handle_timeout(Instant::from_millis(1100)), Some(LssEvent::SwitchBitRate(BitRate::K250)));
        assert_eq!(s.bit_rate(), BitRate::K250);
        assert!(s.holds_transmit(Instant::from_millis(1150)));
        assert_eq!(s.poll_timeout(), Some(Instant::from_millis(1200)));
        assert_eq!(s.handle_timeout(Instant::from_millis(1200)), Some(LssEvent::TransmitResumed));
        assert!(!s.holds_transmit(Instant::from_millis(1200)));
        assert_eq!(s.poll_timeout(), None);
        // Supported set restricted by the application.
        s.set_supported_bit_rates(1 << 2);
        assert_eq!(req(&mut s, bt(0, 3)).response, Some(LssResponse::BitTimingConfigured(Status::NOT_SUPPORTED)));
    }

    /// Activate bit timing again while a switch is under way restarts both periods from the new request,
    /// and a late timer call reports one event per call (the switch, then the resume).
    #[test]
    fn activate_again_restarts_the_switch() {
        let mut s = LssSlave::new(&ID, NodeId::new(5));
        config(&mut s);
        let act = |s: &mut LssSlave, t: u64, d: u16| {
            s.handle_request(Instant::from_millis(t), &LssRequest::ActivateBitTiming { switch_delay_ms: d }.emit())
        };
        act(&mut s, 0, 100);
        assert_eq!(s.handle_timeout(Instant::from_millis(100)), Some(LssEvent::SwitchBitRate(BitRate::K125)));
        assert!(s.holds_transmit(Instant::from_millis(150)));
        act(&mut s, 150, 10);
        assert!(!s.holds_transmit(Instant::from_millis(150)));
        assert_eq!(s.poll_timeout(), Some(Instant::from_millis(160)));
        assert!(s.holds_transmit(Instant::from_millis(165)));
        assert!(!s.holds_transmit(Instant::from_millis(170)));
        // Late: both instants have passed, one event per call.
        let late = Instant::from_millis(1000);
        assert_eq!(s.handle_timeout(late), Some(LssEvent::SwitchBitRate(BitRate::K125)));
        assert_eq!(s.poll_timeout(), Some(Instant::from_millis(170)));
        assert_eq!(s.handle_timeout(late), Some(LssEvent::TransmitResumed));
        assert_eq!(s.handle_timeout(late), None);
        assert_eq!(s.poll_timeout(), None);
        assert!(!s.holds_transmit(Instant::from_millis(165)));
        // The longest switch delay, 65,535 ms, each period.
        act(&mut s, 1000, u16::MAX);
        assert_eq!(s.poll_timeout(), Some(Instant::from_millis(1000 + 65_535)));
        s.handle_timeout(Instant::from_millis(1000 + 65_535));
        assert_eq!(s.poll_timeout(), Some(Instant::from_millis(1000 + 2 * 65_535)));
    }

    #[test]
    fn store_deferred_and_not_supported() {
        let mut s = LssSlave::new(&ID, None);
        config(&mut s);
        assert_eq!(
            req(&mut s, LssRequest::StoreConfiguration).response,
            Some(LssResponse::Stored(Status::NOT_SUPPORTED))
        );
        s.set_store_supported(true);
        req(&mut s, LssRequest::ConfigureNodeId(0x22));
        let out = req(&mut s, LssRequest::StoreConfiguration);
        assert_eq!(out.response, None);
        assert_eq!(out.event, Some(LssEvent::StoreRequested { node_id: 0x22, bit_rate: BitRate::K125 }));
        assert!(s.store_pending());
        assert_eq!(
            s.complete_store(Err(StoreError::Manufacturer(3))),
            Some(LssResponse::Stored(Status::manufacturer(3)))
        );
        assert_eq!(s.complete_store(Ok(())), None);
        req(&mut s, LssRequest::StoreConfiguration);
        assert_eq!(s.complete_store(Ok(())), Some(LssResponse::Stored(Status::SUCCESS)));
    }

    #[test]
    fn identify_remote_slave_ranges() {
        let mut s = LssSlave::new(&ID, NodeId::new(5));
        let run = |s: &mut LssSlave, v: u32, p: u32, rl: u32, rh: u32, sl: u32, sh: u32| {
            let parts = [
                (IdentifyPart::VendorId, v),
                (IdentifyPart::ProductCode, p),
                (IdentifyPart::RevisionLow, rl),
                (IdentifyPart::RevisionHigh, rh),
                (IdentifyPart::SerialLow, sl),
            ];
            for (part, x) in parts {
                assert_eq!(req(s, LssRequest::IdentifyRemoteSlave(part, x)).response, None);
            }
            req(s, LssRequest::IdentifyRemoteSlave(IdentifyPart::SerialHigh, sh)).response
        };
        assert_eq!(run(&mut s, 0x123, 0x42, 0, u32::MAX, 0, u32::MAX), Some(LssResponse::IdentifySlave));
        assert_eq!(run(&mut s, 0x123, 0x42, 0x0001_0002, 0x0001_0002, 77, 77), Some(LssResponse::IdentifySlave));
        assert_eq!(run(&mut s, 0x123, 0x42, 0, u32::MAX, 78, 100), None);
        assert_eq!(run(&mut s, 0x123, 0x42, 0, 0x0001_0001, 0, 100), None);
        assert_eq!(run(&mut s, 0x124, 0x42, 0, u32::MAX, 0, u32::MAX), None);
        assert_eq!(run(&mut s, 0x123, 0x43, 0, u32::MAX, 0, u32::MAX), None); // product code
        assert_eq!(run(&mut s, 0x123, 0x42, 0x0001_0003, u32::MAX, 0, u32::MAX), None); // revision low bound
        assert_eq!(run(&mut s, 0x123, 0x42, 0, u32::MAX, 0, 76), None); // serial high bound
                                                                        // Served in configuration too.
        config(&mut s);
        assert_eq!(run(&mut s, 0x123, 0x42, 0, u32::MAX, 0, u32::MAX), Some(LssResponse::IdentifySlave));
        // Only the last part on its own: nothing.
        assert_eq!(req(&mut s, LssRequest::IdentifyRemoteSlave(IdentifyPart::SerialHigh, 100)).response, None);
    }

    /// Switch state selective and identify remote slave keep separate positions (one interleaved with the
    /// other does not restart it), an identify part out of order restarts identify, and a first part
    /// restarts a sequence that is under way.
    #[test]
    fn selective_and_identify_sequences_are_independent() {
        use IdentifyPart::*;
        let mut s = LssSlave::new(&ID, NodeId::new(5));
        let sel = |f, v| LssRequest::SwitchStateSelective(f, v);
        let idr = |p, v| LssRequest::IdentifyRemoteSlave(p, v);
        // Identify with a part skipped (revision high missing): no answer, and the sequence restarts.
        for (p, v) in [(VendorId, 0x123), (ProductCode, 0x42), (RevisionLow, 0), (SerialLow, 0)] {
            assert_eq!(req(&mut s, idr(p, v)).response, None);
        }
        assert_eq!(req(&mut s, idr(SerialHigh, u32::MAX)).response, None);
        // Interleaved: selective vendor, identify vendor, selective product, ... each completes.
        req(&mut s, sel(IdentityField::VendorId, 0x123));
        req(&mut s, idr(VendorId, 0x123));
        req(&mut s, idr(VendorId, 0x123)); // a repeated first part restarts identify at its start
        req(&mut s, sel(IdentityField::ProductCode, 0x42));
        req(&mut s, idr(ProductCode, 0x42));
        req(&mut s, sel(IdentityField::Revision, 0x0001_0002));
        for (p, v) in [(RevisionLow, 0), (RevisionHigh, u32::MAX), (SerialLow, 0)] {
            assert_eq!(req(&mut s, idr(p, v)).response, None);
        }
        assert_eq!(req(&mut s, idr(SerialHigh, u32::MAX)).response, Some(LssResponse::IdentifySlave));
        // The identify answer did not disturb selective: its last part completes it.
        let out = req(&mut s, sel(IdentityField::Serial, 77));
        assert_eq!(out.response, Some(LssResponse::SwitchStateSelective));
        assert_eq!(s.mode(), LssMode::Configuration);
        // A selective part in configuration is ignored and does not touch identify's position.
        req(&mut s, idr(VendorId, 0x123));
        req(&mut s, sel(IdentityField::VendorId, 0x123));
        req(&mut s, idr(ProductCode, 0x42));
        for (p, v) in [(RevisionLow, 0), (RevisionHigh, u32::MAX), (SerialLow, 0)] {
            req(&mut s, idr(p, v));
        }
        assert_eq!(req(&mut s, idr(SerialHigh, u32::MAX)).response, Some(LssResponse::IdentifySlave));
        // Back in waiting, a selective sequence is interrupted by a wrong part and restarts from its vendor-ID.
        req(&mut s, LssRequest::SwitchStateGlobal(LssMode::Waiting));
        req(&mut s, sel(IdentityField::VendorId, 0x123));
        req(&mut s, sel(IdentityField::ProductCode, 0x42));
        req(&mut s, sel(IdentityField::VendorId, 0x123)); // first part again: restart, still in order
        req(&mut s, sel(IdentityField::ProductCode, 0x42));
        req(&mut s, sel(IdentityField::Revision, 0x0001_0002));
        assert_eq!(req(&mut s, sel(IdentityField::Serial, 77)).response, Some(LssResponse::SwitchStateSelective));
    }

    #[test]
    fn identify_non_configured() {
        let r = LssRequest::IdentifyNonConfiguredRemoteSlave;
        assert_eq!(req(&mut LssSlave::new(&ID, NodeId::new(5)), r).response, None);
        let mut s = LssSlave::new(&ID, None);
        assert_eq!(req(&mut s, r).response, Some(LssResponse::IdentifyNonConfiguredSlave));
        config(&mut s);
        assert_eq!(req(&mut s, r).response, Some(LssResponse::IdentifyNonConfiguredSlave));
        req(&mut s, LssRequest::ConfigureNodeId(3));
        assert_eq!(req(&mut s, r).response, None);
    }

    /// The python canopen fastscan against one slave, bit by bit.
    #[test]
    fn fastscan_python_sequence() {
        let mut s = LssSlave::new(&ID, None);
        let mut step = |id: u32, bit: u8, sub: u8, next: u8| {
            let f = [cs::FASTSCAN, id as u8, (id >> 8) as u8, (id >> 16) as u8, (id >> 24) as u8, bit, sub, next];
            s.handle_request(T0, &f).response == Some(LssResponse::IdentifySlave)
        };
        assert!(step(0, 0x80, 0, 0));
        let mut found = [0u32; 4];
        for sub in 0..4u8 {
            for bit in (0..32u8).rev() {
                if !step(found[usize::from(sub)], bit, sub, sub) {
                    found[usize::from(sub)] |= 1 << bit;
                }
            }
            assert!(step(found[usize::from(sub)], 0, sub, (sub + 1) & 3));
        }
        assert_eq!(found, [ID.vendor_id, ID.product_code, ID.revision, ID.serial]);
        assert_eq!(s.mode(), LssMode::Configuration);
        // Configured and fastscan is no longer answered, even after going back to waiting.
        let mut s2 = LssSlave::new(&ID, NodeId::new(5));
        assert_eq!(
            req(
                &mut s2,
                LssRequest::Fastscan {
                    id_number: 0,
                    bit_check: 0x80,
                    lss_sub: IdentityField::VendorId,
                    lss_next: IdentityField::VendorId
                }
            )
            .response,
            None
        );
    }

    /// CAN-07: frames that are not 8 bytes, unknown command specifiers and out-of-range fields (mode,
    /// fastscan BitCheck, LSSSub, LSSNext) are ignored, in both LSS states; nothing changes.
    #[test]
    fn malformed_requests_are_silent() {
        let mut s = LssSlave::new(&ID, None);
        let before = s.clone();
        let silent = |s: &mut LssSlave, f: &[u8]| assert_eq!(s.handle_request(T0, f), LssOutput::default(), "{f:02X?}");
        silent(&mut s, &[cs::SWITCH_STATE_GLOBAL, 1, 0, 0, 0, 0, 0]); // 7 bytes
        silent(&mut s, &[cs::IDENTIFY_NON_CONFIGURED_REMOTE, 0, 0, 0, 0, 0, 0, 0, 0]); // 9 bytes
        silent(&mut s, &[]);
        silent(&mut s, &[cs::SWITCH_STATE_GLOBAL, 2, 0, 0, 0, 0, 0, 0]); // no such mode
        for bit_check in [32u8, 0x7F, 0x81, 0xFF] {
            silent(&mut s, &[cs::FASTSCAN, 0, 0, 0, 0, bit_check, 0, 0]);
        }
        silent(&mut s, &[cs::FASTSCAN, 0, 0, 0, 0, FASTSCAN_CONFIRM, 4, 0]); // LSSSub 4
        silent(&mut s, &[cs::FASTSCAN, 0, 0, 0, 0, FASTSCAN_CONFIRM, 0, 4]); // LSSNext 4
        for unknown in [0x00, 0x05, 0x12, 0x44, 0x45, 0x4D, 0x4F, 0x50, 0x52, 0x59, 0x5F, 0xFF] {
            silent(&mut s, &[unknown, 0, 0, 0, 0, 0, 0, 0]);
        }
        assert_eq!(s, before);
        config(&mut s);
        let before = s.clone();
        silent(&mut s, &[cs::INQUIRE_NODE_ID, 0, 0, 0, 0, 0, 0]);
        silent(&mut s, &[cs::CONFIGURE_NODE_ID, 3, 0, 0, 0, 0, 0, 0, 0]);
        silent(&mut s, &[cs::SWITCH_STATE_GLOBAL, 0xFF, 0, 0, 0, 0, 0, 0]);
        for unknown in [0x10, 0x12, 0x14, 0x16, 0x18, 0x59, 0x5F] {
            silent(&mut s, &[unknown, 0, 0, 0, 0, 0, 0, 0]);
        }
        assert_eq!(s, before);
    }

    #[test]
    fn fastscan_wrong_sub_is_silent() {
        let mut s = LssSlave::new(&ID, None);
        let fs = |id, bit, sub: u8, next: u8| LssRequest::Fastscan {
            id_number: id,
            bit_check: bit,
            lss_sub: IdentityField::from_index(sub).unwrap(),
            lss_next: IdentityField::from_index(next).unwrap(),
        };
        // LSSPos is 0: a product-code step is ignored.
        assert_eq!(req(&mut s, fs(0x42, 0, 1, 2)).response, None);
        assert_eq!(req(&mut s, fs(0x123, 0, 0, 1)).response, Some(LssResponse::IdentifySlave));
        assert_eq!(req(&mut s, fs(0x42, 0, 1, 2)).response, Some(LssResponse::IdentifySlave));
        assert_eq!(s.mode(), LssMode::Waiting);
    }
}
