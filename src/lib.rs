//! `canopen`: a CiA 301 CANopen node stack.
//!
//! This facade re-exports the workspace crates:
//! - [`core`] ([`canopen-core`](https://docs.rs/canopen-core)): the `no_std`, heap-free, sans-IO services;
//! - [`ObjectDictionary`] ([`canopen-od-derive`](https://docs.rs/canopen-od-derive)): the derive macro that
//!   turns a struct into the object dictionary (and its EDS);
//! - `socketcan` (feature `socketcan`, [`canopen-socketcan`](https://docs.rs/canopen-socketcan)): the Linux
//!   adapter, with tokio and blocking runners, a blocking master and file storage;
//! - `embassy` (feature `embassy`, [`canopen-embassy`](https://docs.rs/canopen-embassy)): the embassy
//!   integration for firmware, with STM32 CAN adapters and NOR-flash storage.
//!
//! ```
//! use canopen::core::{CanFrame, NodeId};
//! let node = NodeId::new(5).unwrap();
//! assert_eq!(CanFrame::new(0x700 + node.get() as u16, &[0]).unwrap().cob_id(), 0x705);
//! ```
#![forbid(unsafe_code)]

pub use canopen_core as core;
/// The embassy integration (feature `embassy`): see the `canopen-embassy` crate docs.
#[cfg(feature = "embassy")]
pub use canopen_embassy as embassy;
/// `#[derive(ObjectDictionary)]`: see the `canopen-od-derive` crate docs. Use `#[od(crate = "canopen::core")]`
/// on the struct when `canopen_core` is only reachable through this facade.
///
/// ```
/// use canopen::ObjectDictionary;
/// use canopen::core::od::ObjectDictionary as _;
///
/// #[derive(ObjectDictionary, Default)]
/// #[od(crate = "canopen::core")]
/// struct App {
///     #[od(index = 0x2000, access = "ro")]
///     counter: u32,
/// }
/// let mut b = [0u8; 4];
/// assert_eq!(App { counter: 7 }.read(0x2000, 0, 0, &mut b), Ok(4));
/// ```
pub use canopen_od_derive::ObjectDictionary;
/// The Linux SocketCAN adapter (feature `socketcan`): see the `canopen-socketcan` crate docs.
#[cfg(feature = "socketcan")]
pub use canopen_socketcan as socketcan;

/// The README's examples are compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
