//! Shared test support: the test object dictionary, the in-memory client ↔ server link and the shared lossy bus.
#![allow(dead_code)]

pub mod bus;
pub mod harness;
pub mod od;
