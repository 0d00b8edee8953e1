//! An async CANopen master on tokio: one CAN socket, many nodes at once.
//!
//! - **SDO** through `canopen-core`'s sans-IO client (expedited, segmented, block with CRC): typed
//!   [`Master::read`] / [`Master::write`], bytes and strings of any length ([`Master::upload`],
//!   [`Master::download`]), DOMAIN streaming from a reader / into a writer ([`Master::download_from`],
//!   [`Master::upload_to`]); aborts come back as [`Error::Aborted`] with the code and its meaning.
//! - **NMT** node control ([`Master::nmt`]), **heartbeat** and **EMCY** as broadcast streams
//!   ([`Master::heartbeats`], [`Master::emergencies`]), every received frame ([`Master::frames`]).
//! - Blocking calls for code without a runtime: [`blocking::BlockingMaster`].
//! - **CiA 402 drives** ([`Master::drive`]): enable, disable, quick stop, fault reset, modes, profile
//!   position moves that await target reached, profile velocity, homing, cyclic set-points at SYNC.
//! - A **SYNC** producer ([`Master::start_sync`]), **PDO** remapping through SDO with the CiA 301
//!   disable/map/enable sequence ([`Master::configure_pdo`]), the core's **LSS** master ([`Master::lss`]).
//!
//! # How frames find their transfer
//!
//! One receive task reads the socket and hands each frame to whoever waits for its COB-ID: the SDO
//! transfer talking to that server (580h + node), the LSS service (7E4h), the heartbeat (700h + node) and
//! EMCY (80h + node) streams. So concurrent transfers to different nodes never see each other's frames,
//! and a transfer's time-out (the core client's own deadline, SDO-31) is never extended by frames from
//! other nodes: a read from a stopped node times out on time while that node's heartbeats arrive.
//! Transfers to the same server take turns (a server runs one transfer at a time).
//!
//! # Cancel safety
//!
//! Dropping a transfer's future (a `select!` or `timeout` around it) ends it: the master sends the server
//! an abort (0800 0000h, general error) from a spawned task, and the next transfer to that node can start.
//!
//! ```no_run
//! use canopen_master::{Master, NmtCommand};
//! # async fn demo() -> Result<(), canopen_master::Error> {
//! let master = Master::open("vcan0")?;
//! let device_type: u32 = master.read(5, 0x1000, 0).await?;
//! let name: String = master.read(5, 0x1008, 0).await?;
//! master.write(5, 0x2001, 0, -100i16).await?;
//! master.nmt(5, NmtCommand::Start).await?;
//! # Ok(()) }
//! ```

#![deny(unsafe_code)]
#![warn(missing_docs)]

use std::sync::Arc;
use std::time::Duration;

use canopen_core::NodeId;

use bus::Inner;

// By concern: `bus` (the socket and the receive task that routes frames), `sdo` (transfers), `nmt` (NMT,
// heartbeat and EMCY streams), `sync` (the SYNC producer), `pdo` (PDO configuration), `lss`; each module's
// doc says what it covers.
pub mod blocking;
mod bus;
mod canio;
mod data;
pub mod drive;
mod error;
pub mod lss;
mod nmt;
pub mod pdo;
mod sdo;
pub mod sim;
pub mod slcan;
mod sync;
mod value;

#[cfg(target_os = "linux")]
pub use canio::SocketCan;
pub use canio::{CanIo, IoFuture};
pub use canopen_core::sdo::client::Mode;
pub use canopen_core::wire::error_control::StateCode;
pub use canopen_core::wire::nmt::NmtCommand;
/// EDS/DCF import (CiA 306) and EDS → Rust: the [`canopen_eds`] crate, which holds them (std only, for a
/// firmware's build.rs as well), under the name the master has always given them.
pub use canopen_eds as eds;
pub use data::Progress;
pub use drive::Drive402;
pub use error::{abort_meaning, Error};
pub use nmt::{EmcyEvent, Heartbeat};
pub use sdo::{BLOCK, DEFAULT_SDO_TIMEOUT, QUIET};
pub use sync::SyncProducer;
pub use value::SdoValue;

pub(crate) use bus::{sleep_until, Route};

/// The node-ID for `node`, or an [`Error::InvalidArgument`].
pub(crate) fn node_id(node: u8) -> Result<NodeId, Error> {
    NodeId::new(node).ok_or_else(|| Error::InvalidArgument(format!("node-ID {node} is not in 1..=127")))
}

/// The master: cheap to clone (every clone shares the socket and the receive task, which stops when the
/// last clone is dropped), usable from many tasks at once.
///
/// ```
/// use canopen_core::{node::NoApplication, profile::NodeConfig, Node, NodeId};
/// use canopen_master::{sim::SimBus, Master};
/// # let rt = tokio::runtime::Builder::new_current_thread().enable_all().start_paused(true).build().unwrap();
/// # rt.block_on(async {
/// let bus = SimBus::new();
/// let _nodes: Vec<_> = (1..=3)
///     .map(|id| bus.spawn_node(Node::<NoApplication>::new(NodeId::new(id).unwrap(), NodeConfig::DEFAULT, NoApplication)))
///     .collect();
/// let master = Master::new(bus.port());
/// let (a, b, c) = tokio::join!(master.read::<u32>(1, 0x1000, 0), master.read::<u32>(2, 0x1000, 0), master.read::<u32>(3, 0x1000, 0));
/// assert!(a.is_ok() && b.is_ok() && c.is_ok());
/// # });
/// ```
#[derive(Clone)]
pub struct Master {
    inner: Arc<Inner>,
    sdo_timeout: Duration,
}

/// The README's example, compiled (not run: it needs vcan0) as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctest;
