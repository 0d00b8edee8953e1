//! The LSS master, sans-IO: every CiA 305 master service ([`LssMaster`]) and a commissioning sequence that
//! finds every unconfigured slave with fastscan and gives each a node-ID ([`Commissioning`]).
//!
//! # Driving it
//!
//! Start a service (`switch_global`, `configure_node_id`, `fastscan`, ...), then loop: send every frame from
//! `poll_transmit` on 7E5h; feed the data of frames received on 7E4h to `handle_response`; call
//! `handle_timeout` at `poll_timeout`. Confirmed services end with a [`MasterEvent`]; unconfirmed ones
//! (switch state global, activate bit timing) end when `poll_transmit` has returned their frame.
//!
//! A slave's silence is information in LSS (fastscan: "this bit is 1"; identify: "nobody matches"), so every
//! confirmed step waits at most the response time-out. python `canopen` waits 0.5 s; a master on a quiet
//! bus with fast slaves can use a few ms. Responses that arrive while nothing is awaited are ignored; the
//! first answer to an identify or fastscan step completes the step (several slaves may answer at once).
//!
//! The fastscan follows python `canopen` / CiA 305: BitCheck 80h (reset; any answer means "there is an
//! unconfigured slave"), then for each LSSSub 0–3 the bits 31..0 (no answer means the bit is 1), then
//! BitCheck 0 with LSSNext = LSSSub + 1 mod 4; after the serial number the matching slave is in LSS
//! configuration.
//!
//! ```
//! use canopen_core::{lss::master::LssMaster, Duration};
//! assert!(LssMaster::new(Duration::from_millis(20)).is_idle());
//! ```

use heapless::Deque;

use crate::lss::Identity;
use crate::time::{Duration, Instant};
use crate::wire::lss::{
    BitRate, IdentifyPart, IdentityField, LssMode, LssRequest, LssResponse, Status, FASTSCAN_CONFIRM,
};
use crate::NodeId;

/// How a confirmed master service ended.
///
/// ```
/// use canopen_core::lss::master::MasterEvent;
/// assert_ne!(MasterEvent::Identified(true), MasterEvent::Timeout);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MasterEvent {
    /// Switch state selective: a slave answered 44h and is in LSS configuration.
    Selected,
    /// Configure node-ID, configure bit timing or store configuration answered with this status.
    Configured(Status),
    /// Inquire identity answered.
    Identity(IdentityField, u32),
    /// Inquire node-ID answered (FFh = none).
    NodeId(u8),
    /// Identify remote slave: whether at least one slave is in the range.
    Identified(bool),
    /// Identify non-configured remote slave: whether at least one slave has no node-ID.
    NonConfigured(bool),
    /// Fastscan: the LSS address of the slave now in LSS configuration, or `None` if no unconfigured slave
    /// answered.
    Fastscan(Option<Identity>),
    /// No answer in time (the slave is absent, or a fastscan lost its slave).
    Timeout,
}

/// A service was started while another one runs.
///
/// ```
/// use canopen_core::{lss::master::{Busy, LssMaster}, Duration};
/// let mut m = LssMaster::new(Duration::from_millis(10));
/// m.inquire_node_id().unwrap();
/// assert_eq!(m.inquire_node_id(), Err(Busy));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Busy;

/// ```
/// assert_eq!(canopen_core::lss::master::Busy.to_string(), "the LSS master is already running a request");
/// ```
impl core::fmt::Display for Busy {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("the LSS master is already running a request")
    }
}

impl core::error::Error for Busy {}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Expect {
    Selected,
    Configured(u8),
    Identity(IdentityField),
    NodeId,
    Identified,
    NonConfigured,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ScanStep {
    Confirm,
    Bit(u8),
    Next,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Scan {
    id: [u32; 4],
    sub: u8,
    step: ScanStep,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Op {
    Idle,
    Await(Expect),
    Fastscan(Scan),
}

/// The LSS master services.
///
/// ```
/// use canopen_core::{lss::master::{LssMaster, MasterEvent}, wire::lss::{LssMode, Status}, Duration, Instant};
/// let mut m = LssMaster::new(Duration::from_millis(50));
/// m.switch_global(LssMode::Configuration).unwrap();
/// assert_eq!(m.poll_transmit(Instant::ZERO), Some([0x04, 1, 0, 0, 0, 0, 0, 0]));
/// m.configure_node_id(0x22).unwrap();
/// assert_eq!(m.poll_transmit(Instant::ZERO), Some([0x11, 0x22, 0, 0, 0, 0, 0, 0]));
/// let ev = m.handle_response(Instant::ZERO, &[0x11, 0, 0, 0, 0, 0, 0, 0]);
/// assert_eq!(ev, Some(MasterEvent::Configured(Status::SUCCESS)));
/// assert!(m.is_idle());
/// ```
#[derive(Debug, Clone)]
pub struct LssMaster {
    timeout: Duration,
    tx: Deque<[u8; 8], 8>,
    op: Op,
    /// Set when the awaited request has been handed out by `poll_transmit`.
    deadline: Option<Instant>,
}

impl LssMaster {
    /// A master that waits `timeout` for each answer.
    ///
    /// ```
    /// use canopen_core::{lss::master::LssMaster, Duration};
    /// let m = LssMaster::new(Duration::from_millis(500)); // python canopen's RESPONSE_TIMEOUT
    /// assert!(m.is_idle());
    /// ```
    pub fn new(timeout: Duration) -> Self {
        LssMaster { timeout, tx: Deque::new(), op: Op::Idle, deadline: None }
    }

    /// Whether no service runs and no frame waits to be sent.
    ///
    /// ```
    /// # use canopen_core::{lss::master::LssMaster, Duration};
    /// assert!(LssMaster::new(Duration::from_millis(1)).is_idle());
    /// ```
    pub fn is_idle(&self) -> bool {
        self.op == Op::Idle && self.tx.is_empty()
    }

    fn start(&mut self, frames: &[LssRequest], op: Op) -> Result<(), Busy> {
        if !self.is_idle() {
            return Err(Busy);
        }
        for f in frames {
            // At most 6 frames per service, the queue holds 8.
            self.tx.push_back(f.emit()).map_err(|_| Busy)?;
        }
        self.op = op;
        self.deadline = None;
        Ok(())
    }

    /// Switch state global (04h), unconfirmed.
    ///
    /// ```
    /// # use canopen_core::{lss::master::LssMaster, wire::lss::LssMode, Duration, Instant};
    /// let mut m = LssMaster::new(Duration::from_millis(1));
    /// m.switch_global(LssMode::Waiting).unwrap();
    /// assert_eq!(m.poll_transmit(Instant::ZERO), Some([4, 0, 0, 0, 0, 0, 0, 0]));
    /// assert!(m.is_idle());
    /// ```
    pub fn switch_global(&mut self, mode: LssMode) -> Result<(), Busy> {
        self.start(&[LssRequest::SwitchStateGlobal(mode)], Op::Idle)
    }

    /// Switch state selective (40h–43h → 44h): [`MasterEvent::Selected`] or [`MasterEvent::Timeout`].
    ///
    /// ```
    /// # use canopen_core::{lss::{master::LssMaster, Identity}, Duration, Instant};
    /// let mut m = LssMaster::new(Duration::from_millis(1));
    /// m.switch_selective(&Identity { vendor_id: 1, product_code: 2, revision: 3, serial: 4 }).unwrap();
    /// let frames: Vec<_> = core::iter::from_fn(|| m.poll_transmit(Instant::ZERO)).collect();
    /// assert_eq!(frames.len(), 4);
    /// assert_eq!(frames[3], [0x43, 4, 0, 0, 0, 0, 0, 0]);
    /// ```
    pub fn switch_selective(&mut self, id: &Identity) -> Result<(), Busy> {
        let f = |field, v| LssRequest::SwitchStateSelective(field, v);
        self.start(
            &[
                f(IdentityField::VendorId, id.vendor_id),
                f(IdentityField::ProductCode, id.product_code),
                f(IdentityField::Revision, id.revision),
                f(IdentityField::Serial, id.serial),
            ],
            Op::Await(Expect::Selected),
        )
    }

    /// Configure node-ID (11h): [`MasterEvent::Configured`].
    ///
    /// ```
    /// # use canopen_core::{lss::master::LssMaster, Duration};
    /// LssMaster::new(Duration::from_millis(1)).configure_node_id(5).unwrap();
    /// ```
    pub fn configure_node_id(&mut self, node_id: u8) -> Result<(), Busy> {
        self.start(&[LssRequest::ConfigureNodeId(node_id)], Op::Await(Expect::Configured(0x11)))
    }

    /// Configure bit timing (13h, CiA 301 table): [`MasterEvent::Configured`].
    ///
    /// ```
    /// # use canopen_core::{lss::master::LssMaster, wire::lss::BitRate, Duration, Instant};
    /// let mut m = LssMaster::new(Duration::from_millis(1));
    /// m.configure_bit_timing(BitRate::K250).unwrap();
    /// assert_eq!(m.poll_transmit(Instant::ZERO), Some([0x13, 0, 3, 0, 0, 0, 0, 0]));
    /// ```
    pub fn configure_bit_timing(&mut self, bit_rate: BitRate) -> Result<(), Busy> {
        let r = LssRequest::ConfigureBitTiming { table_selector: 0, table_index: bit_rate.index() };
        self.start(&[r], Op::Await(Expect::Configured(0x13)))
    }

    /// Activate bit timing (15h), unconfirmed.
    ///
    /// ```
    /// # use canopen_core::{lss::master::LssMaster, Duration, Instant};
    /// let mut m = LssMaster::new(Duration::from_millis(1));
    /// m.activate_bit_timing(100).unwrap();
    /// assert_eq!(m.poll_transmit(Instant::ZERO), Some([0x15, 100, 0, 0, 0, 0, 0, 0]));
    /// ```
    pub fn activate_bit_timing(&mut self, switch_delay_ms: u16) -> Result<(), Busy> {
        self.start(&[LssRequest::ActivateBitTiming { switch_delay_ms }], Op::Idle)
    }

    /// Store configuration (17h): [`MasterEvent::Configured`].
    ///
    /// ```
    /// # use canopen_core::{lss::master::LssMaster, Duration};
    /// LssMaster::new(Duration::from_millis(1)).store().unwrap();
    /// ```
    pub fn store(&mut self) -> Result<(), Busy> {
        self.start(&[LssRequest::StoreConfiguration], Op::Await(Expect::Configured(0x17)))
    }

    /// Inquire identity (5Ah–5Dh): [`MasterEvent::Identity`].
    ///
    /// ```
    /// # use canopen_core::{lss::master::LssMaster, wire::lss::IdentityField, Duration};
    /// LssMaster::new(Duration::from_millis(1)).inquire(IdentityField::Serial).unwrap();
    /// ```
    pub fn inquire(&mut self, field: IdentityField) -> Result<(), Busy> {
        self.start(&[LssRequest::Inquire(field)], Op::Await(Expect::Identity(field)))
    }

    /// Inquire node-ID (5Eh): [`MasterEvent::NodeId`].
    ///
    /// ```
    /// # use canopen_core::{lss::master::LssMaster, Duration};
    /// LssMaster::new(Duration::from_millis(1)).inquire_node_id().unwrap();
    /// ```
    pub fn inquire_node_id(&mut self) -> Result<(), Busy> {
        self.start(&[LssRequest::InquireNodeId], Op::Await(Expect::NodeId))
    }

    /// Identify remote slave (46h–4Bh → 4Fh) with exact vendor-ID and product code and inclusive revision
    /// and serial ranges: [`MasterEvent::Identified`].
    ///
    /// ```
    /// # use canopen_core::{lss::master::LssMaster, Duration};
    /// LssMaster::new(Duration::from_millis(1)).identify_remote(1, 2, 0..=u32::MAX, 100..=199).unwrap();
    /// ```
    pub fn identify_remote(
        &mut self,
        vendor_id: u32,
        product_code: u32,
        revision: core::ops::RangeInclusive<u32>,
        serial: core::ops::RangeInclusive<u32>,
    ) -> Result<(), Busy> {
        let f = LssRequest::IdentifyRemoteSlave;
        self.start(
            &[
                f(IdentifyPart::VendorId, vendor_id),
                f(IdentifyPart::ProductCode, product_code),
                f(IdentifyPart::RevisionLow, *revision.start()),
                f(IdentifyPart::RevisionHigh, *revision.end()),
                f(IdentifyPart::SerialLow, *serial.start()),
                f(IdentifyPart::SerialHigh, *serial.end()),
            ],
            Op::Await(Expect::Identified),
        )
    }

    /// Identify non-configured remote slave (4Ch → 50h): [`MasterEvent::NonConfigured`].
    ///
    /// ```
    /// # use canopen_core::{lss::master::LssMaster, Duration};
    /// LssMaster::new(Duration::from_millis(1)).identify_non_configured().unwrap();
    /// ```
    pub fn identify_non_configured(&mut self) -> Result<(), Busy> {
        self.start(&[LssRequest::IdentifyNonConfiguredRemoteSlave], Op::Await(Expect::NonConfigured))
    }

    /// Fastscan: finds one unconfigured slave and leaves it in LSS configuration: [`MasterEvent::Fastscan`]
    /// (or [`MasterEvent::Timeout`] if the slave stopped answering half-way).
    ///
    /// ```
    /// # use canopen_core::{lss::master::LssMaster, Duration, Instant};
    /// let mut m = LssMaster::new(Duration::from_millis(1));
    /// m.fastscan().unwrap();
    /// assert_eq!(m.poll_transmit(Instant::ZERO), Some([0x51, 0, 0, 0, 0, 0x80, 0, 0]));
    /// ```
    pub fn fastscan(&mut self) -> Result<(), Busy> {
        let scan = Scan { id: [0; 4], sub: 0, step: ScanStep::Confirm };
        self.start(&[scan_frame(&scan)], Op::Fastscan(scan))
    }

    /// The next frame to send on 7E5h. Handing out the last frame of a confirmed service starts its
    /// response time-out at `now`.
    ///
    /// ```
    /// use canopen_core::{lss::master::{LssMaster, MasterEvent}, Instant};
    /// let mut m = LssMaster::new(canopen_core::Duration::from_millis(10));
    /// m.inquire_node_id().unwrap();
    /// assert_eq!(m.poll_timeout(), None);
    /// assert_eq!(m.poll_transmit(Instant::ZERO), Some([0x5E, 0, 0, 0, 0, 0, 0, 0]));
    /// assert_eq!(m.poll_timeout(), Some(Instant::from_millis(10)));
    /// assert_eq!(m.handle_timeout(Instant::from_millis(9)), None);
    /// assert_eq!(m.handle_timeout(Instant::from_millis(10)), Some(MasterEvent::Timeout));
    /// ```
    pub fn poll_transmit(&mut self, now: Instant) -> Option<[u8; 8]> {
        let f = self.tx.pop_front()?;
        if self.tx.is_empty() && self.op != Op::Idle {
            self.deadline = Some(now + self.timeout);
        }
        Some(f)
    }

    /// When [`handle_timeout`](Self::handle_timeout) must be called.
    ///
    /// ```
    /// use canopen_core::{lss::master::{LssMaster, MasterEvent}, Instant};
    /// let mut m = LssMaster::new(canopen_core::Duration::from_millis(10));
    /// m.inquire_node_id().unwrap();
    /// assert_eq!(m.poll_timeout(), None);
    /// assert_eq!(m.poll_transmit(Instant::ZERO), Some([0x5E, 0, 0, 0, 0, 0, 0, 0]));
    /// assert_eq!(m.poll_timeout(), Some(Instant::from_millis(10)));
    /// assert_eq!(m.handle_timeout(Instant::from_millis(9)), None);
    /// assert_eq!(m.handle_timeout(Instant::from_millis(10)), Some(MasterEvent::Timeout));
    /// ```
    pub fn poll_timeout(&self) -> Option<Instant> {
        self.deadline
    }

    /// Feeds the data of one frame received on 7E4h.
    ///
    /// ```
    /// use canopen_core::{lss::master::{LssMaster, MasterEvent}, Instant};
    /// let mut m = LssMaster::new(canopen_core::Duration::from_millis(10));
    /// m.identify_non_configured().unwrap();
    /// m.poll_transmit(Instant::ZERO);
    /// let ev = m.handle_response(Instant::ZERO, &[0x50, 0, 0, 0, 0, 0, 0, 0]);
    /// assert_eq!(ev, Some(MasterEvent::NonConfigured(true)));
    /// ```
    pub fn handle_response(&mut self, now: Instant, data: &[u8]) -> Option<MasterEvent> {
        self.deadline?;
        let response = LssResponse::parse(data).ok()?;
        match (self.op, response) {
            (Op::Await(Expect::Selected), LssResponse::SwitchStateSelective) => self.finish(MasterEvent::Selected),
            (Op::Await(Expect::Configured(0x11)), LssResponse::NodeIdConfigured(s))
            | (Op::Await(Expect::Configured(0x13)), LssResponse::BitTimingConfigured(s))
            | (Op::Await(Expect::Configured(0x17)), LssResponse::Stored(s)) => self.finish(MasterEvent::Configured(s)),
            (Op::Await(Expect::Identity(want)), LssResponse::Identity(field, v)) if want == field => {
                self.finish(MasterEvent::Identity(field, v))
            }
            (Op::Await(Expect::NodeId), LssResponse::NodeId(id)) => self.finish(MasterEvent::NodeId(id)),
            (Op::Await(Expect::Identified), LssResponse::IdentifySlave) => self.finish(MasterEvent::Identified(true)),
            (Op::Await(Expect::NonConfigured), LssResponse::IdentifyNonConfiguredSlave) => {
                self.finish(MasterEvent::NonConfigured(true))
            }
            (Op::Fastscan(scan), LssResponse::IdentifySlave) => self.scan_step(now, scan, true),
            _ => None,
        }
    }

    /// Acts on an expired response time-out.
    ///
    /// ```
    /// use canopen_core::{lss::master::{LssMaster, MasterEvent}, Instant};
    /// let mut m = LssMaster::new(canopen_core::Duration::from_millis(10));
    /// m.inquire_node_id().unwrap();
    /// assert_eq!(m.poll_timeout(), None);
    /// assert_eq!(m.poll_transmit(Instant::ZERO), Some([0x5E, 0, 0, 0, 0, 0, 0, 0]));
    /// assert_eq!(m.poll_timeout(), Some(Instant::from_millis(10)));
    /// assert_eq!(m.handle_timeout(Instant::from_millis(9)), None);
    /// assert_eq!(m.handle_timeout(Instant::from_millis(10)), Some(MasterEvent::Timeout));
    /// ```
    pub fn handle_timeout(&mut self, now: Instant) -> Option<MasterEvent> {
        if self.deadline.is_none_or(|d| d > now) {
            return None;
        }
        match self.op {
            Op::Idle => {
                self.deadline = None;
                None
            }
            Op::Await(Expect::Identified) => self.finish(MasterEvent::Identified(false)),
            Op::Await(Expect::NonConfigured) => self.finish(MasterEvent::NonConfigured(false)),
            Op::Await(_) => self.finish(MasterEvent::Timeout),
            Op::Fastscan(scan) => self.scan_step(now, scan, false),
        }
    }

    fn finish(&mut self, ev: MasterEvent) -> Option<MasterEvent> {
        self.op = Op::Idle;
        self.deadline = None;
        self.tx.clear();
        Some(ev)
    }

    fn scan_step(&mut self, now: Instant, mut scan: Scan, answered: bool) -> Option<MasterEvent> {
        let sub = usize::from(scan.sub & 3);
        scan.step = match scan.step {
            ScanStep::Confirm if !answered => return self.finish(MasterEvent::Fastscan(None)),
            ScanStep::Confirm => ScanStep::Bit(31),
            ScanStep::Bit(b) => {
                if !answered {
                    scan.id[sub] |= 1 << (b & 31);
                }
                if b == 0 {
                    ScanStep::Next
                } else {
                    ScanStep::Bit(b - 1)
                }
            }
            ScanStep::Next if !answered => return self.finish(MasterEvent::Timeout),
            ScanStep::Next if scan.sub >= 3 => {
                let [vendor_id, product_code, revision, serial] = scan.id;
                return self.finish(MasterEvent::Fastscan(Some(Identity {
                    vendor_id,
                    product_code,
                    revision,
                    serial,
                })));
            }
            ScanStep::Next => {
                scan.sub += 1;
                ScanStep::Bit(31)
            }
        };
        self.op = Op::Fastscan(scan);
        self.deadline = None;
        self.tx.clear();
        // The queue was just cleared; one frame always fits.
        let _ = self.tx.push_back(scan_frame(&scan).emit());
        let _ = now;
        None
    }
}

fn scan_frame(scan: &Scan) -> LssRequest {
    let sub = scan.sub & 3;
    let field = |i: u8| IdentityField::from_index(i & 3).unwrap_or(IdentityField::VendorId);
    let (bit_check, next) = match scan.step {
        ScanStep::Confirm => (FASTSCAN_CONFIRM, 0),
        ScanStep::Bit(b) => (b, sub),
        ScanStep::Next => (0, (sub + 1) & 3),
    };
    LssRequest::Fastscan { id_number: scan.id[usize::from(sub)], bit_check, lss_sub: field(sub), lss_next: field(next) }
}

/// What [`Commissioning`] reports.
///
/// ```
/// use canopen_core::lss::master::CommissioningEvent;
/// assert_eq!(CommissioningEvent::Finished { assigned: 0 }, CommissioningEvent::Finished { assigned: 0 });
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CommissioningEvent {
    /// A slave got a node-ID (and stored it, if asked); it is switched to LSS waiting next and boots.
    Assigned {
        /// Its LSS address.
        identity: Identity,
        /// Its new node-ID.
        node_id: NodeId,
    },
    /// No unconfigured slave is left (or the node-IDs ran out): the sequence is over.
    Finished {
        /// How many slaves got a node-ID.
        assigned: u8,
    },
    /// A step failed; the sequence is over.
    Failed {
        /// The event of the step that failed.
        cause: MasterEvent,
    },
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Step {
    Scan,
    Scanning,
    SwitchBack,
    Selecting,
    Configuring,
    Storing,
    Release,
    Done,
}

/// Gives every unconfigured slave a node-ID, one after another: fastscan → switch all to LSS waiting →
/// switch the found slave selectively → configure node-ID → (store) → switch to LSS waiting (the slave
/// resets communication and boots with its node-ID, so the next fastscan no longer finds it).
///
/// ```
/// use canopen_core::{lss::master::Commissioning, Duration, Instant, NodeId};
/// let mut c = Commissioning::new(Duration::from_millis(10), NodeId::new(0x20).unwrap(), false);
/// assert_eq!(c.poll_transmit(Instant::ZERO), Some([0x51, 0, 0, 0, 0, 0x80, 0, 0]));
/// // Nobody answers: finished, nothing assigned.
/// let ev = c.handle_timeout(Instant::from_millis(10));
/// assert_eq!(ev, Some(canopen_core::lss::master::CommissioningEvent::Finished { assigned: 0 }));
/// ```
#[derive(Debug, Clone)]
pub struct Commissioning {
    master: LssMaster,
    next_id: u8,
    store: bool,
    step: Step,
    found: Identity,
    assigned: u8,
}

impl Commissioning {
    /// A sequence that hands out node-IDs from `first` upwards, storing each when `store`.
    ///
    /// ```
    /// use canopen_core::{lss::master::Commissioning, Duration, NodeId};
    /// let c = Commissioning::new(Duration::from_millis(20), NodeId::new(2).unwrap(), true);
    /// assert!(!c.is_done());
    /// ```
    pub fn new(timeout: Duration, first: NodeId, store: bool) -> Self {
        Commissioning {
            master: LssMaster::new(timeout),
            next_id: first.get(),
            store,
            step: Step::Scan,
            found: Identity::default(),
            assigned: 0,
        }
    }

    /// Whether the sequence is over.
    ///
    /// ```
    /// # use canopen_core::{lss::master::Commissioning, Duration, NodeId};
    /// assert!(!Commissioning::new(Duration::from_millis(1), NodeId::new(1).unwrap(), false).is_done());
    /// ```
    pub fn is_done(&self) -> bool {
        self.step == Step::Done
    }

    /// The next frame to send on 7E5h.
    ///
    /// ```
    /// use canopen_core::{lss::master::{Commissioning, CommissioningEvent}, Duration, Instant, NodeId};
    /// let mut c = Commissioning::new(Duration::from_millis(10), NodeId::new(1).unwrap(), false);
    /// assert!(c.poll_transmit(Instant::ZERO).is_some()); // fastscan reset
    /// assert_eq!(c.poll_timeout(), Some(Instant::from_millis(10)));
    /// // One slave answers: the scan goes on with bit 31 of the vendor-ID.
    /// assert_eq!(c.handle_response(Instant::ZERO, &[0x4F, 0, 0, 0, 0, 0, 0, 0]), None);
    /// assert_eq!(c.poll_transmit(Instant::ZERO), Some([0x51, 0, 0, 0, 0, 31, 0, 0]));
    /// assert_eq!(c.handle_timeout(Instant::from_millis(5)), None);
    /// ```
    pub fn poll_transmit(&mut self, now: Instant) -> Option<[u8; 8]> {
        loop {
            if let Some(f) = self.master.poll_transmit(now) {
                return Some(f);
            }
            if !self.master.is_idle() {
                return None;
            }
            // The master is idle: start the next service (after an unconfirmed one went out).
            let started = match self.step {
                Step::Scan => {
                    self.step = Step::Scanning;
                    self.master.fastscan()
                }
                Step::SwitchBack => {
                    self.step = Step::Selecting;
                    self.master.switch_selective(&self.found)
                }
                Step::Release => {
                    self.step = Step::Scan;
                    if self.next_id > 127 {
                        self.step = Step::Done;
                    }
                    continue;
                }
                _ => return None,
            };
            if started.is_err() {
                return None;
            }
        }
    }

    /// When [`handle_timeout`](Self::handle_timeout) must be called.
    ///
    /// ```
    /// use canopen_core::{lss::master::{Commissioning, CommissioningEvent}, Duration, Instant, NodeId};
    /// let mut c = Commissioning::new(Duration::from_millis(10), NodeId::new(1).unwrap(), false);
    /// assert!(c.poll_transmit(Instant::ZERO).is_some()); // fastscan reset
    /// assert_eq!(c.poll_timeout(), Some(Instant::from_millis(10)));
    /// // One slave answers: the scan goes on with bit 31 of the vendor-ID.
    /// assert_eq!(c.handle_response(Instant::ZERO, &[0x4F, 0, 0, 0, 0, 0, 0, 0]), None);
    /// assert_eq!(c.poll_transmit(Instant::ZERO), Some([0x51, 0, 0, 0, 0, 31, 0, 0]));
    /// assert_eq!(c.handle_timeout(Instant::from_millis(5)), None);
    /// ```
    pub fn poll_timeout(&self) -> Option<Instant> {
        self.master.poll_timeout()
    }

    /// Feeds the data of one frame received on 7E4h.
    ///
    /// ```
    /// use canopen_core::{lss::master::{Commissioning, CommissioningEvent}, Duration, Instant, NodeId};
    /// let mut c = Commissioning::new(Duration::from_millis(10), NodeId::new(1).unwrap(), false);
    /// assert!(c.poll_transmit(Instant::ZERO).is_some()); // fastscan reset
    /// assert_eq!(c.poll_timeout(), Some(Instant::from_millis(10)));
    /// // One slave answers: the scan goes on with bit 31 of the vendor-ID.
    /// assert_eq!(c.handle_response(Instant::ZERO, &[0x4F, 0, 0, 0, 0, 0, 0, 0]), None);
    /// assert_eq!(c.poll_transmit(Instant::ZERO), Some([0x51, 0, 0, 0, 0, 31, 0, 0]));
    /// assert_eq!(c.handle_timeout(Instant::from_millis(5)), None);
    /// ```
    pub fn handle_response(&mut self, now: Instant, data: &[u8]) -> Option<CommissioningEvent> {
        let ev = self.master.handle_response(now, data)?;
        self.on_master_event(ev)
    }

    /// Acts on an expired response time-out.
    ///
    /// ```
    /// use canopen_core::{lss::master::{Commissioning, CommissioningEvent}, Duration, Instant, NodeId};
    /// let mut c = Commissioning::new(Duration::from_millis(10), NodeId::new(1).unwrap(), false);
    /// assert!(c.poll_transmit(Instant::ZERO).is_some()); // fastscan reset
    /// assert_eq!(c.poll_timeout(), Some(Instant::from_millis(10)));
    /// // One slave answers: the scan goes on with bit 31 of the vendor-ID.
    /// assert_eq!(c.handle_response(Instant::ZERO, &[0x4F, 0, 0, 0, 0, 0, 0, 0]), None);
    /// assert_eq!(c.poll_transmit(Instant::ZERO), Some([0x51, 0, 0, 0, 0, 31, 0, 0]));
    /// assert_eq!(c.handle_timeout(Instant::from_millis(5)), None);
    /// ```
    pub fn handle_timeout(&mut self, now: Instant) -> Option<CommissioningEvent> {
        let ev = self.master.handle_timeout(now)?;
        self.on_master_event(ev)
    }

    fn on_master_event(&mut self, ev: MasterEvent) -> Option<CommissioningEvent> {
        let fail = |s: &mut Self| {
            s.step = Step::Done;
            Some(CommissioningEvent::Failed { cause: ev })
        };
        match (self.step, ev) {
            (Step::Scanning, MasterEvent::Fastscan(Some(id))) => {
                self.found = id;
                self.step = Step::SwitchBack;
                let _ = self.master.switch_global(LssMode::Waiting);
                None
            }
            (Step::Scanning, MasterEvent::Fastscan(None)) => {
                self.step = Step::Done;
                Some(CommissioningEvent::Finished { assigned: self.assigned })
            }
            (Step::Selecting, MasterEvent::Selected) => {
                self.step = Step::Configuring;
                let _ = self.master.configure_node_id(self.next_id);
                None
            }
            (Step::Configuring, MasterEvent::Configured(s)) if s.is_success() && self.store => {
                self.step = Step::Storing;
                let _ = self.master.store();
                None
            }
            (Step::Configuring | Step::Storing, MasterEvent::Configured(s)) if s.is_success() => {
                let node_id = NodeId::new(self.next_id)?;
                self.next_id += 1;
                self.assigned += 1;
                self.step = Step::Release;
                let _ = self.master.switch_global(LssMode::Waiting);
                Some(CommissioningEvent::Assigned { identity: self.found, node_id })
            }
            _ => fail(self),
        }
    }
}

// The master is tested against our slave.
#[cfg(all(test, feature = "lss"))]
mod tests {
    extern crate std;
    use super::*;
    use crate::lss::LssSlave;
    use std::{vec, vec::Vec};

    const T: Duration = Duration::from_millis(10);

    /// Drives a master against slaves in memory; returns the event and how many frames went out.
    fn run(m: &mut LssMaster, slaves: &mut [LssSlave]) -> (MasterEvent, usize) {
        let mut now = Instant::ZERO;
        let mut sent = 0;
        loop {
            while let Some(f) = m.poll_transmit(now) {
                sent += 1;
                let answers: Vec<_> = slaves.iter_mut().filter_map(|s| s.handle_request(now, &f).response).collect();
                for a in answers {
                    if let Some(ev) = m.handle_response(now, &a.emit()) {
                        return (ev, sent);
                    }
                }
            }
            match m.poll_timeout() {
                Some(t) => {
                    now = t;
                    if let Some(ev) = m.handle_timeout(now) {
                        return (ev, sent);
                    }
                }
                None => panic!("master stalled"),
            }
        }
    }

    fn ident(serial: u32) -> Identity {
        Identity { vendor_id: 0x0000_00AB, product_code: 0x1234, revision: 0x0002_0001, serial }
    }

    #[test]
    fn fastscan_finds_the_lowest_and_only_unconfigured() {
        let mut slaves = [
            LssSlave::new(&ident(0x3000), None),
            LssSlave::new(&ident(0x0102), None),
            LssSlave::new(&ident(1), NodeId::new(4)),
        ];
        let mut m = LssMaster::new(T);
        m.fastscan().unwrap();
        let (ev, sent) = run(&mut m, &mut slaves);
        // Bits are decided 0 whenever any slave answers: the lowest address wins.
        assert_eq!(ev, MasterEvent::Fastscan(Some(ident(0x0102))));
        assert_eq!(sent, 1 + 4 * 33);
        assert_eq!(slaves[1].mode(), LssMode::Configuration);
        assert_eq!(slaves[0].mode(), LssMode::Waiting);
    }

    #[test]
    fn fastscan_with_nobody() {
        let mut m = LssMaster::new(T);
        m.fastscan().unwrap();
        assert_eq!(run(&mut m, &mut [LssSlave::new(&ident(1), NodeId::new(1))]), (MasterEvent::Fastscan(None), 1));
    }

    #[test]
    fn services_against_a_slave() {
        let mut s = [LssSlave::new(&ident(9), NodeId::new(3))];
        let mut m = LssMaster::new(T);
        m.switch_selective(&ident(8)).unwrap();
        assert_eq!(run(&mut m, &mut s).0, MasterEvent::Timeout);
        m.switch_selective(&ident(9)).unwrap();
        assert_eq!(run(&mut m, &mut s).0, MasterEvent::Selected);
        m.inquire(IdentityField::Serial).unwrap();
        assert_eq!(run(&mut m, &mut s).0, MasterEvent::Identity(IdentityField::Serial, 9));
        m.inquire_node_id().unwrap();
        assert_eq!(run(&mut m, &mut s).0, MasterEvent::NodeId(3));
        m.configure_node_id(200).unwrap();
        assert_eq!(run(&mut m, &mut s).0, MasterEvent::Configured(Status::NOT_SUPPORTED));
        m.configure_bit_timing(BitRate::K500).unwrap();
        assert_eq!(run(&mut m, &mut s).0, MasterEvent::Configured(Status::SUCCESS));
        m.store().unwrap();
        assert_eq!(run(&mut m, &mut s).0, MasterEvent::Configured(Status::NOT_SUPPORTED));
        m.identify_remote(0xAB, 0x1234, 0..=u32::MAX, 5..=10).unwrap();
        assert_eq!(run(&mut m, &mut s).0, MasterEvent::Identified(true));
        m.identify_remote(0xAB, 0x1234, 0..=u32::MAX, 10..=20).unwrap();
        assert_eq!(run(&mut m, &mut s).0, MasterEvent::Identified(false));
        m.identify_non_configured().unwrap();
        assert_eq!(run(&mut m, &mut s).0, MasterEvent::NonConfigured(false));
    }

    #[test]
    fn stray_responses_are_ignored() {
        let mut m = LssMaster::new(T);
        assert_eq!(m.handle_response(Instant::ZERO, &[0x44, 0, 0, 0, 0, 0, 0, 0]), None);
        m.inquire_node_id().unwrap();
        // Not yet sent: ignored.
        assert_eq!(m.handle_response(Instant::ZERO, &[0x5E, 1, 0, 0, 0, 0, 0, 0]), None);
        m.poll_transmit(Instant::ZERO);
        assert_eq!(m.handle_response(Instant::ZERO, &[0x5D, 1, 0, 0, 0, 0, 0, 0]), None);
        assert_eq!(m.handle_response(Instant::ZERO, &[0x5E, 1, 0]), None);
        assert_eq!(m.handle_response(Instant::ZERO, &[0x5E, 1, 0, 0, 0, 0, 0, 0]), Some(MasterEvent::NodeId(1)));
    }

    #[test]
    fn commissioning_assigns_every_unconfigured_slave() {
        let mut slaves: Vec<LssSlave> = [7u32, 3, 5].iter().map(|&s| LssSlave::new(&ident(s), None)).collect();
        let mut c = Commissioning::new(T, NodeId::new(0x20).unwrap(), false);
        let mut now = Instant::ZERO;
        let mut events = Vec::new();
        while !c.is_done() {
            while let Some(f) = c.poll_transmit(now) {
                let mut answers = Vec::new();
                for s in slaves.iter_mut() {
                    let out = s.handle_request(now, &f);
                    if out.reset_communication {
                        s.apply_pending();
                    }
                    answers.extend(out.response);
                }
                for a in answers {
                    events.extend(c.handle_response(now, &a.emit()));
                }
            }
            if let Some(t) = c.poll_timeout() {
                now = now.max(t);
                events.extend(c.handle_timeout(now));
            }
        }
        let n = |v| NodeId::new(v).unwrap();
        assert_eq!(
            events,
            vec![
                CommissioningEvent::Assigned { identity: ident(3), node_id: n(0x20) },
                CommissioningEvent::Assigned { identity: ident(5), node_id: n(0x21) },
                CommissioningEvent::Assigned { identity: ident(7), node_id: n(0x22) },
                CommissioningEvent::Finished { assigned: 3 },
            ]
        );
        let ids: Vec<_> = slaves.iter().map(|s| s.active_node_id().map(NodeId::get)).collect();
        assert_eq!(ids, vec![Some(0x22), Some(0x20), Some(0x21)]);
    }
}
