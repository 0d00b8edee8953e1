//! Wire formats: one plain struct per frame kind, each with `parse` and `emit`, apart from the state machines
//! so that tests and fuzzers can build and check frames (the smoltcp `wire` shape).
//!
//! Parsing never panics on short or hostile input; it returns an error that the caller maps to the spec's
//! answer (usually: ignore the frame, CAN-07).

pub mod emcy;
pub mod error_control;
#[cfg(any(feature = "lss", feature = "lss-master"))]
pub mod lss;
pub mod nmt;
pub mod pdo_mapping;
pub mod sdo;
#[cfg(feature = "time")]
pub mod time_stamp;

/// Why a frame's payload could not be parsed.
///
/// ```
/// use canopen_core::wire::{nmt::NodeControl, WireError};
/// assert_eq!(NodeControl::parse(&[0x01]), Err(WireError::Length));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WireError {
    /// The DLC is wrong for this frame kind.
    Length,
    /// A field holds a value the protocol does not define (e.g. an unknown command specifier).
    Value,
}

/// ```
/// use canopen_core::wire::WireError;
/// assert_eq!(WireError::Value.to_string(), "a field holds a value the protocol does not define");
/// ```
impl core::fmt::Display for WireError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            WireError::Length => "wrong data length for this frame",
            WireError::Value => "a field holds a value the protocol does not define",
        })
    }
}

impl core::error::Error for WireError {}
