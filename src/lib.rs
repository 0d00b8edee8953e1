//! `canopen`: a CiA 301 CANopen node stack.
//!
//! This facade re-exports the workspace crates:
//! - [`core`] (`canopen-core`): the `no_std`, heap-free, sans-IO services;
//! - the `canopen-od-derive` macro that turns a struct into the object dictionary.
//!
//! ```
//! use canopen::core::{CanFrame, NodeId};
//! let node = NodeId::new(5).unwrap();
//! assert_eq!(CanFrame::new(0x700 + node.get() as u16, &[0]).unwrap().cob_id(), 0x705);
//! ```
#![forbid(unsafe_code)]

pub use canopen_core as core;

/// The README's examples are compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
