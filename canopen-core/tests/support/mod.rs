//! Shared test support: the test object dictionary, the in-memory client ↔ server link and the shared lossy bus.
#![allow(dead_code)]

pub mod bus;
pub mod harness;
pub mod od;

/// Cases per property: `PROPTEST_CASES` when set (CI runs the SDO server properties with 10,000), else
/// `default`. proptest reads that variable only when a test does not set its own count, which ours do.
pub fn cases(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}
