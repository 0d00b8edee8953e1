//! Shared test support: the test object dictionary and the in-memory client ↔ server link.
#![allow(dead_code)]

pub mod harness;
pub mod od;
