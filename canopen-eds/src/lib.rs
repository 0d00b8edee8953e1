//! CiA 306 electronic data sheets (EDS) and device configuration files (DCF), with std only.
//!
//! - [`Eds::parse`]: the text of an EDS or DCF into objects and entries (index, sub-index, name, data
//!   type, access, default, limits, PDO mapping, a DCF's `ParameterValue` and `[DeviceComissioning]`); a
//!   malformed file is an [`EdsError`] with its line, never a panic.
//! - The writer: an [`Eds`] is `Display`, and what it writes parses back to the same [`Eds`].
//! - DCF out: [`Eds::to_dcf`], a node's EDS plus the values a master configured; [`ConciseDcf`], the
//!   binary concise DCF of 1F22h (CiA 302-3) from a DCF, and parsed back.
//! - EDS → Rust: [`rust_module`] / [`to_rust`], a module that uses only `canopen-core` and
//!   `canopen-od-derive` (what `canopenctl eds-to-rust` prints) with the list of what it leaves out, and
//!   [`generate`] for a build script.
//!
//! No IO crate and no platform crate: it builds on Linux, macOS and Windows, and a firmware's `build.rs`
//! can use it without pulling in tokio or SocketCAN.
//!
//! ```
//! let eds = canopen_eds::Eds::parse("[2001]\nParameterName=Setpoint\nDataType=0x0003\nAccessType=rw\n").unwrap();
//! let rust = canopen_eds::to_rust(&eds, "device.eds");
//! assert!(rust.contains("#[od(index = 0x2001, name = \"Setpoint\", access = \"rw\")]"));
//! ```
//!
//! # The dictionary from an EDS at build time
//!
//! The device crate depends on `canopen-core` and `canopen-od-derive` (the generated module uses them by
//! those names) and has this crate as a build dependency:
//!
//! ```toml
//! [dependencies]
//! canopen-core = { version = "0.1", default-features = false }
//! canopen-od-derive = "0.1"
//! [build-dependencies]
//! canopen-eds = "0.1"
//! ```
//!
//! Its `build.rs` writes the module into `OUT_DIR`; a malformed EDS fails the build with the file and line:
//!
//! ```no_run
//! fn main() {
//!     if let Err(e) = canopen_eds::generate("device.eds") {
//!         panic!("{e}"); // e.g. "device.eds:12: [2001] DataType 'x' is not a number"
//!     }
//! }
//! ```
//!
//! and the crate includes it. The module is named after the file (`device` for `device.eds`) and holds
//! `Device`, the derived application objects, and `CONFIG`, the node configuration of 1000h–1FFFh:
//!
//! ```ignore
//! include!(concat!(env!("OUT_DIR"), "/device.rs"));
//! let node: canopen_core::Node<device::Device> = canopen_core::Node::new(id, device::CONFIG, device::Device::default());
//! ```
//!
//! [`generate`] prints `cargo:rerun-if-changed=` for the EDS, so the module is written again when the file
//! changes, and one `cargo:warning=` per thing the module leaves out ([`LeftOut`]: an unsupported data
//! type, a default relative to `$NODEID`, ...), so that what the dictionary lacks shows in the build, not
//! only in the module's comments. `examples/eds-build` in the repository builds a node this way, for the
//! host (where a test reads its dictionary by SDO) and for `thumbv7em-none-eabihf`.
#![forbid(unsafe_code)]
#![warn(missing_docs)]
// The build.rs example above is a whole file: its `fn main` is the point.
#![allow(clippy::needless_doctest_main)]

mod build_script;
mod codegen;
mod dcf;
mod eds;
mod layout;
mod write;

pub use build_script::{generate, generate_as, generate_into, generate_into_as, BuildError};
pub use codegen::{rust_module, to_rust, Dropped, Generated, LeftOut};
pub use dcf::{ConciseDcf, ConciseError, Configured, DcfError};
pub use eds::{
    data_type_name, eval_default, eval_typed, no_limit, type_range, Access, DeviceCommissioning, Eds, EdsError, Entry,
    InfoSection, Object, ObjectKind,
};
pub use layout::{byte_view_fields, rust_module_as, StructLayout};

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctest;
