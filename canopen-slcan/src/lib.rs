//! A `no_std`, heap-free, sans-IO codec for serial CAN: the slcan (LAWICEL) ASCII protocol that CANable,
//! USBtin and similar adapters speak over a (USB) serial port, and that the Linux kernel's `slcan` line
//! discipline speaks on a tty. The caller owns the port; this crate turns bytes into lines and lines into
//! bytes:
//!
//! - [`Decoder`]: bytes in, one [`Message`] per line out, bad lines skipped and counted ([`Counters`]);
//! - [`Message::encode`] / [`encode_frame`]: one line out, into a [`MAX_LINE`] buffer;
//! - [`Adapter`]: the adapter end's channel state and answers (a firmware that is the serial interface);
//! - [`SlcanFrame`]: a classic frame, 11- or 29-bit, implementing [`embedded_can::Frame`], so that
//!   `canopen_core::CanFrame::from_frame` converts it (and refuses 29-bit frames, CAN-01).
//!
//! Why a crate of its own rather than a module of `canopen-core`: both ends use it, the firmware (no_std)
//! and `canopen-master`/`canopenctl` (std), and slcan has nothing of CANopen in it; its only dependency is
//! `embedded-can`, which `canopen-core` already has.
//!
//! ```
//! use canopen_slcan::{Decoder, Message, SlcanFrame, MAX_LINE};
//! let mut out = [0u8; MAX_LINE];
//! let frame = SlcanFrame::from_raw(0x605, false, false, 0, &[0x40, 0x00, 0x10, 0x00]).unwrap();
//! let n = Message::Frame(frame).encode(&mut out);
//! assert_eq!(&out[..n], b"t605440001000\r");
//! let mut dec = Decoder::new();
//! let got = out[..n].iter().find_map(|&b| dec.push(b));
//! assert_eq!(got, Some(Ok(Message::Frame(frame))));
//! ```
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod adapter;
mod decode;
mod frame;
mod line;

pub use adapter::{Adapter, Reply, STATUS_BUS_ERROR, STATUS_DATA_OVERRUN, STATUS_ERROR_PASSIVE};
pub use decode::{Counters, Decoder, LineError};
pub use frame::SlcanFrame;
pub use line::{bitrate_code, encode_frame, Message, MAX_LINE};
