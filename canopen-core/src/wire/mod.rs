//! Wire formats: plain `Repr` structs and enums with `parse` and `emit`, kept apart from the state
//! machines so that tests and fuzzers can build and check frames (the smoltcp `wire/` shape).
//!
//! Parsing never panics on short or hostile input; it returns an error.

pub mod sdo;
