//! SDO: server and client state machines (CiA 301 §7.2.4). Frame formats are in [`crate::wire::sdo`].
//!
//! Both sides are sans-IO: they take received 8-byte frames and the current [`Instant`](crate::Instant), and
//! hand back the frames to send. Neither owns a buffer of the object's size: the server streams between
//! frames and the [`ObjectDictionary`](crate::od::ObjectDictionary), the client between frames and the
//! caller's [`client::ClientData`].
//!
//! - [`server`]: [`SdoServer`] and its 1200h-style [`SdoServerParams`]; [`SdoServers`] for the default
//!   server plus additional servers 1201h–127Fh as a compile-time count.
//! - [`client`] (feature `sdo-client`): [`SdoClient`] (1280h-style [`SdoClientParams`]).
//! - [`block`] (features `sdo-block`, `sdo-client`): the CRC-16 used by block transfer (SDO-49) and sub-block bookkeeping shared by both sides.
//!
//! ```
//! use canopen_core::sdo::{SdoServer, SdoServerParams};
//! use canopen_core::NodeId;
//! let server = SdoServer::new(SdoServerParams::default_server(NodeId::new(3).unwrap()));
//! assert_eq!(server.rx_cob_id(), Some(0x603));
//! assert_eq!(server.tx_cob_id(), Some(0x583));
//! ```

#[cfg(any(feature = "sdo-block", feature = "sdo-client"))]
pub mod block;
#[cfg(feature = "sdo-client")]
pub mod client;
pub mod server;

#[cfg(feature = "sdo-client")]
pub use client::{SdoClient, SdoClientParams};
pub use server::{Response, SdoEvent, SdoServer, SdoServerParams, SdoServers, ServerState};

/// Default SDO protocol time-out (SDO-31 leaves the value to the application): 1 s, as CANopenNode.
///
/// ```
/// assert_eq!(canopen_core::sdo::DEFAULT_TIMEOUT.as_micros(), 1_000_000);
/// ```
pub const DEFAULT_TIMEOUT: crate::Duration = crate::Duration::from_millis(1_000);
