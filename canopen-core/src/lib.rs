//! `canopen-core`: a `#![no_std]`, heap-free, sans-IO CANopen (CiA 301) node stack.
//!
//! The core owns no clock, no socket and no allocation: the caller feeds received frames and the current
//! time in, and drains frames to send, events for the application and the next deadline out. Each CiA 301
//! service is a small state machine in its own module; the wire formats live apart from them.
//!
//! The modules form layers, each importing only the ones above it in this list (`docs/ARCHITECTURE.md`):
//! - base: [`frame`] (the CAN frame), [`cob`] (COB-IDs, node-IDs), [`abort`] (SDO abort codes), [`time`]
//!   (`Instant`, `Duration`), [`sizes`] (the node's capacities as one type, [`Sizes`]), [`queue`] (a bounded
//!   FIFO in fixed storage);
//! - wire: [`wire`] (parse/emit of every protocol's frames);
//! - od: [`od`] (values, entries, tables, the `Merged` router, EDS object sections);
//! - services, one state machine each: [`nmt`], [`heartbeat`], [`guarding`], [`sdo`], [`pdo`], [`sync`],
//!   [`emcy`], [`lss`], [`storage`];
//! - profile: [`profile`] (the communication profile 1000h–1FFFh over the services' parameters, the EDS
//!   file);
//! - node: [`node`] (routing of received frames, the node's dictionary view), [`event`] (what the
//!   application is told);
//! - driver: [`driver`] (the async run loop) and the trace points.
//!
//! Services a device may leave out (Cargo features, all on by default; what is left out costs no flash and
//! no RAM, and its objects answer SDO with 0602 0000h and are not in the EDS): `lss` (the node's CiA 305
//! slave), `lss-master` ([`lss::master`]), `sdo-block` (SDO block transfer in the server), `sdo-client`
//! (`sdo::client`), `time` (1012h TIME), `guarding` (100Ch/100Dh node and life guarding), `crc-table` (the
//! block-transfer CRC from a 512-byte table rather than a 32-byte one), `program-download` (`program`:
//! CiA 302-3 1F50h/1F51h/1F56h/1F57h, a dictionary part the application composes with its own),
//! `pdo-bit-mapping` (PDO mapping entries of any bit length; without it whole objects of whole bytes, see
//! [`pdo::mapping`]), `sync-producer` (the SYNC producer; without it a SYNC consumer only, see [`sync`]),
//! `pdo-rtr` (TPDOs answering remote requests, types FCh/FDh; see [`pdo`]), and `pdo-dynamic-mapping` (PDO
//! mapping written by SDO, PDO-35..37; without it each PDO keeps its configured mapping and 1600h+/1A00h+
//! are const, PDO-30).
//!
//! Objects CiA 301 makes optional for the services every node has, one feature each (all on by default;
//! without one its object does not exist and the service behaves as with the object at its default):
//! `error-history` (1003h, see [`emcy`]), `error-behaviour` (1029h; a communication error in Operational
//! then always leads to Pre-operational), `sync-window` (1007h) and `sync-counter` (1019h, see [`sync`]),
//! `emcy-inhibit` (1015h), `manufacturer-strings` (1008h–100Ah) and `store-restore` (1010h/1011h; a node
//! with a [`storage::Storage`] loads it at each reset either way).
//!
//! A capacity, off by default: `pdo-mapping-64` (64 mapping entries per PDO instead of 8, PDO-30; it costs
//! about 670 B of RAM in every PDO whether the device uses it or not, see [`pdo::mapping::MAX_ENTRIES`]).
//!
//! Optional features: `defmt` (derives `defmt::Format` on the public types; NMT state changes, SDO aborts,
//! driver errors and frames are logged through defmt) and `log` (the same trace points through the `log`
//! facade, for std users). Both are off by default; the trace points sit in the [`driver`].
//!
//! Requirement IDs (NMT-03, SDO-17, ...) are those of the repository's `docs/CONFORMANCE.md` (statement,
//! CiA 301 clause and the tests that prove each); each module's docs say which it implements.
//!
//! ```
//! use canopen_core::{node::NoApplication, profile::NodeConfig, CanFrame, Instant, Node, NodeId};
//!
//! let mut node: Node<NoApplication> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication);
//! node.handle_timeout(Instant::ZERO); // power-on: the boot-up message
//! assert_eq!(node.poll_transmit(), CanFrame::new(0x705, &[0x00]));
//! // NMT "start remote node" for node 5: Pre-operational -> Operational
//! node.handle_frame(Instant::from_millis(1), &CanFrame::new(0x000, &[0x01, 0x05]).unwrap());
//! assert_eq!(node.state(), canopen_core::NmtState::Operational);
//! ```
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

// Lets the shared test-support files in `tests/support` use `canopen_core::` paths from unit tests too.
#[cfg(test)]
extern crate self as canopen_core;

pub mod abort;
pub mod bus;
pub mod cob;
pub mod driver;
pub mod emcy;
pub mod event;
pub mod frame;
#[cfg(feature = "guarding")]
pub mod guarding;
pub mod heartbeat;
pub mod lss;
pub mod nmt;
pub mod node;
pub mod od;
pub mod pdo;
pub mod profile;
#[cfg(feature = "program-download")]
pub mod program;
pub mod queue;
pub mod sdo;
pub mod sizes;
pub mod storage;
pub mod sync;
pub mod time;
mod trace;
pub mod wire;

pub use cob::NodeId;
pub use event::Event;
pub use frame::CanFrame;
pub use nmt::NmtState;
pub use node::Node;
pub use sizes::Sizes;
pub use time::{Duration, Instant};

/// The README's example, compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctest;
