//! One slcan line: [`Message`] (what a line means) and its encoding. Every line ends in `\r`, except the
//! error answer, which is a lone BEL (`\a`, 07h).
//!
//! The LAWICEL CAN232/CANUSB manual is the public description relied on, with the Linux kernel's
//! `drivers/net/can/slcan` documentation and python-can's slcan interface for what hosts really send:
//!
//! | line | meaning |
//! |---|---|
//! | `tiiildd..` | data frame, 3 hex digits of 11-bit id, DLC digit, 2 hex digits per byte |
//! | `Tiiiiiiiildd..` | data frame, 8 hex digits of 29-bit id |
//! | `riiil` / `Riiiiiiiil` | remote frame (11 / 29 bit), DLC digit |
//! | `O`, `L`, `C` | open the channel, open it listen-only, close it |
//! | `S0`..`S8` | bit rate 10, 20, 50, 100, 125, 250, 500, 800 kbit/s, 1 Mbit/s |
//! | `V`, `N`, `F` | ask the version, serial number, status flags |
//! | `Z0` / `Z1` | timestamps off / on |
//! | empty, `\a` | answer: ok, error |
//! | `z`, `Z` | answer: an 11-bit / 29-bit frame was queued for the bus |
//! | `Vhhss`, `Nxxxx`, `Fxx` | answers to `V`, `N`, `F` |
//!
//! A frame line may carry 4 more hex digits, a timestamp in ms, which is accepted and dropped. Hex digits are
//! read in either case and written in upper case.

use embedded_can::Frame;

use crate::frame::SlcanFrame;

/// The longest line: `T`, 8 id digits, the DLC, 16 data digits, a 4-digit timestamp and `\r`.
///
/// ```
/// assert_eq!(canopen_slcan::MAX_LINE, 31);
/// ```
pub const MAX_LINE: usize = 1 + 8 + 1 + 16 + 4 + 1;

/// What one line means (the decoder's output, the encoder's input).
///
/// ```
/// use canopen_slcan::{Message, MAX_LINE};
/// let mut out = [0u8; MAX_LINE];
/// let n = Message::Bitrate(6).encode(&mut out);
/// assert_eq!(&out[..n], b"S6\r");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Message {
    /// A CAN frame (`t`, `T`, `r`, `R`).
    Frame(SlcanFrame),
    /// `O`: open the channel.
    Open,
    /// `L`: open the channel listen-only.
    ListenOnly,
    /// `C`: close the channel.
    Close,
    /// `S0`..`S8`: the bit rate code (6 = 500 kbit/s; see [`bitrate_code`]). A code above 8 is written as one
    /// hex digit (vendor extensions), which this decoder refuses.
    Bitrate(u8),
    /// `V`: ask the version.
    Version,
    /// `N`: ask the serial number.
    SerialNumber,
    /// `F`: ask the status flags.
    Status,
    /// `Z0` / `Z1`: timestamps off / on.
    Timestamps(bool),
    /// Answer: ok (an empty line).
    Ok,
    /// Answer: error (BEL).
    Error,
    /// Answer `z` / `Z`: a frame was queued for the bus (`true`: a 29-bit one).
    Sent {
        /// `Z`: the frame was a 29-bit one.
        extended: bool,
    },
    /// Answer `Vhhss`: hardware and software version, two hex digits each.
    VersionIs {
        /// Hardware version.
        hardware: u8,
        /// Software version.
        software: u8,
    },
    /// Answer `Nxxxx`: the serial number, four hex digits.
    SerialNumberIs(u16),
    /// Answer `Fxx`: the status flags (bit 3: data overrun, bit 5: error passive, bit 7: bus error ...).
    StatusIs(u8),
}

/// The slcan bit rate code (`S`n) of a bit rate in bit/s, if it has one.
///
/// ```
/// assert_eq!(canopen_slcan::bitrate_code(250_000), Some(5));
/// assert_eq!(canopen_slcan::bitrate_code(83_333), None);
/// ```
pub fn bitrate_code(bit_per_s: u32) -> Option<u8> {
    const RATES: [u32; 9] = [10_000, 20_000, 50_000, 100_000, 125_000, 250_000, 500_000, 800_000, 1_000_000];
    RATES.iter().position(|&r| r == bit_per_s).map(|i| i as u8)
}

const HEX: &[u8; 16] = b"0123456789ABCDEF";

/// Writes `digits` hex digits of `value` at `out[at..]`; returns the next position.
fn put_hex(out: &mut [u8; MAX_LINE], at: usize, value: u32, digits: usize) -> usize {
    for i in 0..digits {
        let shift = 4 * (digits - 1 - i);
        out[at + i] = HEX[((value >> shift) & 0xF) as usize];
    }
    at + digits
}

impl Message {
    /// Writes the line into `out`, returns its length. The buffer is [`MAX_LINE`] long, so it always fits.
    ///
    /// ```
    /// use canopen_slcan::{Message, SlcanFrame, MAX_LINE};
    /// let mut out = [0u8; MAX_LINE];
    /// let f = SlcanFrame::from_raw(0x705, false, false, 0, &[0x7F]).unwrap();
    /// let n = Message::Frame(f).encode(&mut out);
    /// assert_eq!(&out[..n], b"t70517F\r");
    /// assert_eq!(Message::Error.encode(&mut out), 1);
    /// assert_eq!(out[0], 0x07);
    /// ```
    pub fn encode(&self, out: &mut [u8; MAX_LINE]) -> usize {
        let end = match *self {
            Message::Frame(ref f) => return encode_frame(f, out),
            Message::Error => {
                out[0] = 0x07;
                return 1;
            }
            Message::Ok => 0,
            Message::Open => put(out, b"O"),
            Message::ListenOnly => put(out, b"L"),
            Message::Close => put(out, b"C"),
            Message::Version => put(out, b"V"),
            Message::SerialNumber => put(out, b"N"),
            Message::Status => put(out, b"F"),
            Message::Bitrate(code) => tagged(out, b'S', u32::from(code.min(15)), 1),
            Message::Timestamps(on) => put(out, if on { b"Z1" } else { b"Z0" }),
            Message::Sent { extended } => put(out, if extended { b"Z" } else { b"z" }),
            Message::VersionIs { hardware, software } => {
                tagged(out, b'V', u32::from(hardware) << 8 | u32::from(software), 4)
            }
            Message::SerialNumberIs(n) => tagged(out, b'N', u32::from(n), 4),
            Message::StatusIs(flags) => tagged(out, b'F', u32::from(flags), 2),
        };
        out[end] = b'\r';
        end + 1
    }
}

/// `letter` then `digits` hex digits of `value`; returns the length.
fn tagged(out: &mut [u8; MAX_LINE], letter: u8, value: u32, digits: usize) -> usize {
    out[0] = letter;
    put_hex(out, 1, value, digits)
}

fn put(out: &mut [u8; MAX_LINE], text: &[u8]) -> usize {
    out[..text.len()].copy_from_slice(text);
    text.len()
}

/// Writes any classic [`Frame`] as an slcan line (`t`/`T`/`r`/`R`, no timestamp) into `out`, returns its
/// length. A DLC above 8 (CAN FD) is written as 8.
///
/// ```
/// use canopen_slcan::{encode_frame, SlcanFrame, MAX_LINE};
/// let mut out = [0u8; MAX_LINE];
/// let n = encode_frame(&SlcanFrame::from_raw(0x1ABC_DEF0, true, true, 2, &[]).unwrap(), &mut out);
/// assert_eq!(&out[..n], b"R1ABCDEF02\r");
/// ```
pub fn encode_frame<F: Frame>(frame: &F, out: &mut [u8; MAX_LINE]) -> usize {
    let (kind, id, digits) = match frame.id() {
        embedded_can::Id::Standard(id) => (b't', u32::from(id.as_raw()), 3),
        embedded_can::Id::Extended(id) => (b'T', id.as_raw(), 8),
    };
    out[0] = if frame.is_remote_frame() { kind - 2 } else { kind }; // 'r' / 'R' are 't' / 'T' less 2
    let mut at = put_hex(out, 1, id, digits);
    let dlc = frame.dlc().min(8);
    at = put_hex(out, at, dlc as u32, 1);
    if !frame.is_remote_frame() {
        for &b in frame.data().iter().take(8) {
            at = put_hex(out, at, u32::from(b), 2);
        }
    }
    out[at] = b'\r';
    at + 1
}
