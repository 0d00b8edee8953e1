//! [embassy](https://embassy.dev) integration for [`canopen_core`]: everything a firmware needs between the
//! core's executor-agnostic [`driver`](canopen_core::driver) and embassy, so that an application is its
//! dictionary struct and `main`.
//!
//! - [`EmbassyClock`]: the driver's [`Timer`](canopen_core::driver::Timer) on `embassy-time`;
//! - [`NodeCell`]: the driver's [`Shared`](canopen_core::driver::Shared) on an `embassy-sync` critical-section
//!   mutex, so tasks and interrupts change the node while the driver runs;
//! - [`AppWake`]: the driver's [`Wake`](canopen_core::driver::Wake) on an `embassy-sync` `Signal`;
//! - [`bus_state`]: the CAN controller's state for the node (error passive, bus-off, recovered), from a
//!   probe of its status register around any receive half;
//! - `stm32` (feature `stm32`): the driver's `CanTx`/`CanRx` on embassy-stm32's CAN halves, bxCAN and
//!   FDCAN (classic frames) alike;
//! - [`flash`]: store/restore (1010h/1011h, STORE-01..11) and the LSS configuration (CiA 305) on any
//!   `embedded-storage` [`NorFlash`](embedded_storage::nor_flash::NorFlash), power-cut safe.
//!
//! ```
//! use canopen_core::{driver, node::NoApplication, profile::NodeConfig, Node, NodeId};
//! use canopen_embassy::{AppWake, EmbassyClock, NodeCell};
//!
//! static WAKE: AppWake = AppWake::new();
//! let node = NodeCell::new(Node::<NoApplication>::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, NoApplication));
//! // In a task: driver::run(&node, &mut rx, &mut tx, &mut EmbassyClock, &WAKE, |event| ...).await
//! // elsewhere: change the node under its lock, then wake the driver.
//! use canopen_core::driver::Shared;
//! node.lock(|n| n.raise_error(0x5000, [0; 5]));
//! WAKE.signal();
//! # let _ = EmbassyClock;
//! # let _ = driver::NoWake;
//! ```
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod bus_state;
mod cell;
mod clock;
pub mod flash;
#[cfg(feature = "stm32")]
pub mod stm32;
mod wake;

pub use cell::NodeCell;
pub use clock::EmbassyClock;
pub use wake::AppWake;

/// The README's example, compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctest;
