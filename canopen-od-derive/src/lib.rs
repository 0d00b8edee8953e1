//! Derive macro that turns a Rust struct into a CANopen object dictionary (filled by the object dictionary issue).
