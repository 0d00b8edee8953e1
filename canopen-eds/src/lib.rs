//! CiA 306 electronic data sheets (EDS) and device configuration files (DCF), with std only.
//!
//! - [`Eds::parse`]: the text of an EDS or DCF into a dictionary description, every object with its
//!   entries (index, sub-index, name, data type, access, default, limits, PDO mapping);
//! - [`rust_module`] / [`to_rust`]: EDS → Rust, a module that uses only `canopen-core` and
//!   `canopen-od-derive` (what `canopenctl eds-to-rust` prints), with the list of what it leaves out.
//!
//! No IO crate and no platform crate: it builds on Linux, macOS and Windows, and a firmware's `build.rs` can
//! use it without pulling in tokio or SocketCAN.
//!
//! ```
//! let eds = canopen_eds::Eds::parse("[2001]\nParameterName=Setpoint\nDataType=0x0003\nAccessType=rw\n").unwrap();
//! let rust = canopen_eds::to_rust(&eds, "device.eds");
//! assert!(rust.contains("#[od(index = 0x2001, name = \"Setpoint\", access = \"rw\")]"));
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod codegen;
mod dcf;
mod eds;
mod write;

pub use codegen::{rust_module, to_rust, Dropped, Generated, LeftOut};
pub use dcf::{ConciseDcf, ConciseError, Configured, DcfError};
pub use eds::{
    data_type_name, eval_default, eval_typed, no_limit, type_range, Access, DeviceCommissioning, Eds, EdsError, Entry,
    InfoSection, Object, ObjectKind,
};
