//! LSS (CiA 305 layer setting services): the slave state machine ([`LssSlave`]) and, in [`master`], the
//! master side. Sans-IO, no heap, no `unsafe`, no panics on peer data.
//!
//! CiA 305 is not among the CiA 301 sources behind `docs/CONFORMANCE.md`, so this module relies on public sources, read
//! and cross-checked; none of their code is copied:
//!
//! - python `canopen` 2.4.1 `canopen/lss.py`, the master we must interoperate with: command specifiers,
//!   byte layouts, its fastscan (BitCheck 80h first, then bits 31..0 of each LSSSub, a missing answer
//!   within `RESPONSE_TIMEOUT` = 0.5 s meaning "bit is 1", then BitCheck 0 with LSSNext = sub + 1 mod 4),
//!   and the requests it waits an answer for (11h, 13h, 17h, 43h, 51h, 5Ah–5Eh).
//! - CANopenNode `305/CO_LSS.h`, `305/CO_LSSslave.c`: error codes, the bit timing table (index 5 reserved,
//!   9 = auto), "fastscan only on unconfigured nodes" (active and pending node-ID both FFh), the fastscan
//!   match rule (`LSSPos == LSSSub` and bits 31..BitCheck equal; on match `LSSPos = LSSNext`; BitCheck 0
//!   with `LSSNext < LSSSub` enters LSS configuration), and "switching an unconfigured node that got a
//!   node-ID back to LSS waiting triggers NMT reset communication".
//! - lely-core `src/co/lss.c` (cites CiA 305 v3.0.0 figures 31–46): switch state selective and identify
//!   remote slave as in-order sequences (an out-of-order part restarts them), identify remote slave and
//!   identify non-configured remote slave served in both LSS states, revision/serial compared as ranges.
//! - Device manuals restating CiA 305 (TR-Electronic CANopen manuals, "state behaviour of the supported
//!   services" table; Gefran RK-5-C manual; Elmo DSP 305 implementation guide) for which service is
//!   served in which LSS state and for the two switch-delay periods of activate bit timing.
//!
//! # Which request is served where (silence everywhere else)
//!
//! | request | LSS waiting | LSS configuration |
//! |---------|-------------|-------------------|
//! | switch state global 04h | yes | yes |
//! | switch state selective 40h–43h (→ 44h) | yes | no |
//! | configure node-ID 11h, bit timing 13h, activate 15h, store 17h | no | yes |
//! | inquire 5Ah–5Eh | no | yes |
//! | identify remote slave 46h–4Bh (→ 4Fh) | yes | yes |
//! | identify non-configured remote slave 4Ch (→ 50h) | yes, if unconfigured | yes, if unconfigured |
//! | fastscan 51h (→ 4Fh) | yes, if unconfigured | no |
//!
//! "Unconfigured" means both the active and the pending node-ID are FFh. LSS is independent of the NMT
//! state: the node serves it in Initialisation (while it has no node-ID), Pre-operational, Operational
//! and Stopped alike, as CANopenNode and lely do.
//!
//! # Node-IDs
//!
//! The slave holds an *active* node-ID (the one the node uses now, FFh = none) and a *pending* one (set by
//! configure node-ID). The pending one becomes active at NMT reset communication
//! ([`LssSlave::apply_pending`]); when a node without a node-ID gets one and is switched back to LSS
//! waiting, it resets communication by itself and boots. Store configuration writes the pending node-ID and
//! bit rate through the application; at the next power-up the application passes the stored node-ID to
//! `Node::new` (or `Node::from_raw_node_id`).
//!
//! # Bit timing
//!
//! Configure bit timing checks the index against the CiA 301 table (selector 0 only) and the rates the
//! application declared ([`LssSlave::set_supported_bit_rates`]), and reports the pending rate as
//! [`LssEvent::BitRateConfigured`]. Activate bit timing with switch delay *d* received at *t*: the event
//! [`LssEvent::BitRateActivation`] carries the rate and *d* (the instants are
//! [`LssSlave::poll_timeout`]'s, and an event holding two 8-byte instants made every queued event 8 bytes
//! larger); at *t + d* the node reports
//! [`LssEvent::SwitchBitRate`] (the driver switches its controller then) and holds its transmit queue; at
//! *t + 2d* it reports [`LssEvent::TransmitResumed`] and sends again. Changing the controller's bit rate
//! is the driver's business, not the core's.
//!
//! # Store
//!
//! Store configuration is answered once the application has stored: the node reports
//! [`LssEvent::StoreRequested`] and the application calls `Node::complete_lss_store` with its
//! [`LssStore`] (or [`LssSlave::complete_store`] with a result). Until then the master waits (python
//! `canopen` for 0.5 s). [`LssStore`] takes just the two values, so it can be implemented on top of the
//! general `Storage` trait being built for 1010h (a blanket adapter that writes them into a reserved
//! record), or on a file, as `examples/common/store_file.rs` does. A slave whose application does not store
//! ([`LssSlave::set_store_supported`] false, the default) answers 17h with error 01h at once.

//!
//! # Features
//!
//! The slave (`slave.rs`, re-exported here) is the `lss` feature, the master ([`master`]) the `lss-master`
//! feature; both are on by default. [`Identity`] (1018h) is always here: every node has one.

#[cfg(feature = "lss-master")]
pub mod master;
#[cfg(feature = "lss")]
mod slave;

#[cfg(feature = "lss")]
pub use slave::*;

/// 1018h identity object (DEV-03).
///
/// ```
/// use canopen_core::lss::Identity;
/// let id = Identity { vendor_id: 0, product_code: 1, revision: 0x0001_0000, serial: 42 };
/// assert_eq!(id.serial, 42);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Identity {
    /// 1018h:01 vendor-ID (CiA-assigned).
    pub vendor_id: u32,
    /// 1018h:02 product code.
    pub product_code: u32,
    /// 1018h:03 revision number (major.minor in the high/low 16 bits).
    pub revision: u32,
    /// 1018h:04 serial number.
    pub serial: u32,
}
