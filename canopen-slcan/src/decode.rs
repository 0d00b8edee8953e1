//! [`Decoder`]: bytes from the serial link in, one [`Message`] per line out. Sans-IO: the caller reads the
//! port and pushes the bytes; a fixed [`MAX_LINE`] buffer, no heap.
//!
//! Bad input is skipped and counted in [`Counters`], never a panic (the crate's proptest feeds arbitrary
//! bytes): a line that is not a known message (garbage, a frame whose length disagrees with its DLC, which
//! is what a lost `\r` between two frames makes) is [`LineError::Malformed`] or [`LineError::Unknown`]; a
//! line longer than any message is dropped up to its `\r` ([`LineError::Overlong`]); a BEL ends the line it
//! interrupts (counted malformed) and reads as the error answer. A `\n` at the start of a line is skipped,
//! so `\r\n` line ends work.

use crate::frame::SlcanFrame;
use crate::line::{Message, MAX_LINE};

/// Why a line was skipped.
///
/// ```
/// use canopen_slcan::{Decoder, LineError};
/// let mut d = Decoder::new();
/// let last = b"t12\r".iter().filter_map(|&b| d.push(b)).last();
/// assert_eq!(last, Some(Err(LineError::Malformed)));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LineError {
    /// A known command or frame letter with the wrong length or a bad digit.
    Malformed,
    /// A line that starts with no letter this codec knows (CAN FD frames among them).
    Unknown,
    /// Longer than [`MAX_LINE`]: dropped up to the next `\r`.
    Overlong,
}

/// What the decoder has seen, for diagnostics (each counter wraps at `u32::MAX`).
///
/// ```
/// use canopen_slcan::Decoder;
/// let mut d = Decoder::new();
/// for &b in b"t1230\r??\rO\r" { d.push(b); }
/// let c = d.counters();
/// assert_eq!((c.frames, c.commands, c.malformed, c.unknown, c.overlong), (1, 1, 0, 1, 0));
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counters {
    /// Frame lines decoded.
    pub frames: u32,
    /// Command and answer lines decoded.
    pub commands: u32,
    /// Lines skipped as [`LineError::Malformed`] (including lines cut short by a BEL).
    pub malformed: u32,
    /// Lines skipped as [`LineError::Unknown`].
    pub unknown: u32,
    /// Lines skipped as [`LineError::Overlong`].
    pub overlong: u32,
}

impl Counters {
    /// All skipped lines.
    ///
    /// ```
    /// let c = canopen_slcan::Counters { malformed: 1, unknown: 2, overlong: 3, ..Default::default() };
    /// assert_eq!(c.skipped(), 6);
    /// ```
    pub fn skipped(&self) -> u32 {
        self.malformed.wrapping_add(self.unknown).wrapping_add(self.overlong)
    }
}

/// The line decoder.
///
/// ```
/// use canopen_slcan::{Decoder, Message};
/// let mut d = Decoder::new();
/// let got: Vec<_> = b"S5\rO\r".iter().filter_map(|&b| d.push(b)).collect();
/// assert_eq!(got, [Ok(Message::Bitrate(5)), Ok(Message::Open)]);
/// ```
#[derive(Debug, Clone)]
pub struct Decoder {
    buf: [u8; MAX_LINE],
    len: usize,
    overlong: bool,
    counters: Counters,
}

impl Default for Decoder {
    fn default() -> Self {
        Self::new()
    }
}

impl Decoder {
    /// An empty decoder.
    ///
    /// ```
    /// assert_eq!(canopen_slcan::Decoder::new().counters().frames, 0);
    /// ```
    pub const fn new() -> Self {
        Decoder {
            buf: [0; MAX_LINE],
            len: 0,
            overlong: false,
            counters: Counters { frames: 0, commands: 0, malformed: 0, unknown: 0, overlong: 0 },
        }
    }

    /// What was decoded and skipped so far.
    ///
    /// ```
    /// let mut d = canopen_slcan::Decoder::new();
    /// d.push(b'\r');
    /// assert_eq!(d.counters().commands, 1); // an empty line is the ok answer
    /// ```
    pub fn counters(&self) -> Counters {
        self.counters
    }

    /// Feeds one byte; at the end of a line returns what it was.
    ///
    /// ```
    /// use canopen_slcan::{Decoder, Message};
    /// let mut d = Decoder::new();
    /// assert_eq!(d.push(b'C'), None);
    /// assert_eq!(d.push(b'\r'), Some(Ok(Message::Close)));
    /// assert_eq!(d.push(0x07), Some(Ok(Message::Error)));
    /// ```
    pub fn push(&mut self, byte: u8) -> Option<Result<Message, LineError>> {
        match byte {
            b'\r' => {
                let line = if core::mem::take(&mut self.overlong) {
                    Err(LineError::Overlong)
                } else {
                    parse(&self.buf[..self.len])
                };
                self.len = 0;
                Some(self.count(line))
            }
            0x07 => {
                if self.len > 0 || core::mem::take(&mut self.overlong) {
                    self.counters.malformed = self.counters.malformed.wrapping_add(1);
                }
                self.len = 0;
                Some(self.count(Ok(Message::Error)))
            }
            b'\n' if self.len == 0 && !self.overlong => None,
            _ if self.overlong => None,
            // One byte short of MAX_LINE: room for the line, its `\r` is not stored.
            _ if self.len == MAX_LINE - 1 => {
                self.overlong = true;
                self.len = 0;
                None
            }
            _ => {
                self.buf[self.len] = byte;
                self.len += 1;
                None
            }
        }
    }

    fn count(&mut self, line: Result<Message, LineError>) -> Result<Message, LineError> {
        let c = &mut self.counters;
        let n = match line {
            Ok(Message::Frame(_)) => &mut c.frames,
            Ok(_) => &mut c.commands,
            Err(LineError::Malformed) => &mut c.malformed,
            Err(LineError::Unknown) => &mut c.unknown,
            Err(LineError::Overlong) => &mut c.overlong,
        };
        *n = n.wrapping_add(1);
        line
    }
}

fn hex(digits: &[u8]) -> Option<u32> {
    digits.iter().try_fold(0u32, |acc, &d| Some(acc << 4 | (d as char).to_digit(16)?))
}

/// One line without its `\r`.
fn parse(line: &[u8]) -> Result<Message, LineError> {
    let Some((&first, rest)) = line.split_first() else { return Ok(Message::Ok) };
    let bad = Err(LineError::Malformed);
    match (first, rest) {
        (b't' | b'T' | b'r' | b'R', _) => parse_frame(first, rest).map(Message::Frame).ok_or(LineError::Malformed),
        (b'O', []) => Ok(Message::Open),
        (b'L', []) => Ok(Message::ListenOnly),
        (b'C', []) => Ok(Message::Close),
        (b'V', []) => Ok(Message::Version),
        (b'N', []) => Ok(Message::SerialNumber),
        (b'F', []) => Ok(Message::Status),
        (b'z', []) => Ok(Message::Sent { extended: false }),
        (b'Z', []) => Ok(Message::Sent { extended: true }),
        (b'Z', [b'0']) => Ok(Message::Timestamps(false)),
        (b'Z', [b'1']) => Ok(Message::Timestamps(true)),
        (b'S', &[d]) if (b'0'..=b'8').contains(&d) => Ok(Message::Bitrate(d - b'0')),
        (b'V', [_, _, _, _]) => match hex(rest) {
            Some(v) => Ok(Message::VersionIs { hardware: (v >> 8) as u8, software: v as u8 }),
            None => bad,
        },
        (b'N', [_, _, _, _]) => hex(rest).map(|v| Message::SerialNumberIs(v as u16)).ok_or(LineError::Malformed),
        (b'F', [_, _]) => hex(rest).map(|v| Message::StatusIs(v as u8)).ok_or(LineError::Malformed),
        (b'O' | b'L' | b'C' | b'V' | b'N' | b'F' | b'z' | b'Z' | b'S', _) => bad,
        _ => Err(LineError::Unknown),
    }
}

/// `t`/`T`/`r`/`R`, then the identifier, the DLC, the data (data frames) and an optional 4-digit timestamp.
fn parse_frame(kind: u8, rest: &[u8]) -> Option<SlcanFrame> {
    let extended = kind.is_ascii_uppercase();
    let remote = kind == b'r' || kind == b'R';
    let id_digits = if extended { 8 } else { 3 };
    let id = hex(rest.get(..id_digits)?)?;
    let dlc = *rest.get(id_digits)?;
    let dlc = (b'0'..=b'8').contains(&dlc).then(|| dlc - b'0')?;
    let data_digits = if remote { 0 } else { 2 * usize::from(dlc) };
    let tail = rest.get(id_digits + 1..)?;
    let data_hex = tail.get(..data_digits)?;
    match &tail[data_digits..] {
        [] => {}
        stamp @ [_, _, _, _] => {
            hex(stamp)?;
        }
        _ => return None,
    }
    let mut data = [0u8; 8];
    for (byte, pair) in data.iter_mut().zip(data_hex.chunks_exact(2)) {
        *byte = hex(pair)? as u8;
    }
    SlcanFrame::from_raw(id, extended, remote, dlc, &data[..usize::from(dlc)])
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_can::Frame;

    extern crate std;
    use std::vec::Vec;

    fn lines(input: &[u8]) -> (Vec<Result<Message, LineError>>, Counters) {
        let mut d = Decoder::new();
        let out = input.iter().filter_map(|&b| d.push(b)).collect();
        (out, d.counters())
    }

    #[test]
    fn standard_and_extended_data_and_remote_frames() {
        let (out, c) = lines(b"t18124142\rT1234567F0\rr7051\rR000000008\rt1230\r");
        assert_eq!(out.len(), 5);
        let Some(Ok(Message::Frame(f))) = out.first().copied() else { panic!("{:?}", out.first().copied()) };
        assert_eq!((f.raw_id(), f.is_extended(), f.data()), (0x181, false, &[0x41, 0x42][..]));
        let Some(Ok(Message::Frame(f))) = out.get(1).copied() else { panic!() };
        assert_eq!((f.raw_id(), f.is_extended(), f.dlc()), (0x1234567F, true, 0));
        let Some(Ok(Message::Frame(f))) = out.get(2).copied() else { panic!() };
        assert!(f.is_remote_frame() && f.dlc() == 1 && f.data().is_empty());
        let Some(Ok(Message::Frame(f))) = out.get(3).copied() else { panic!() };
        assert!(f.is_remote_frame() && f.is_extended() && f.dlc() == 8);
        assert_eq!(c.frames, 5);
    }

    #[test]
    fn lower_case_hex_and_a_timestamp_are_accepted() {
        let (out, _) = lines(b"t7ff1ab12ef\r");
        let Some(Ok(Message::Frame(f))) = out.first().copied() else { panic!("{:?}", out.first().copied()) };
        assert_eq!((f.raw_id(), f.data()), (0x7FF, &[0xAB][..]));
    }

    #[test]
    fn ids_out_of_range_bad_dlc_and_bad_digits_are_malformed() {
        for line in [
            &b"t8001\r"[..], // 800h does not fit 11 bits (and DLC 1 without its byte)
            b"T200000000\r", // above 1FFFFFFFh
            b"t1239\r",      // DLC 9
            b"t1231G0\r",    // not hex
            b"t12310\r",     // one digit of data
            b"t1230123\r",   // 3-digit "timestamp"
            b"r12\r",        // short
            b"S9\r",         // no such bit rate code
            b"O1\r",         // a command with a tail
            b"F0\r",         // one status digit
        ] {
            let (out, c) = lines(line);
            assert_eq!(out.first().copied(), Some(Err(LineError::Malformed)), "{:?}", core::str::from_utf8(line));
            assert_eq!(c.malformed, 1);
        }
    }

    #[test]
    fn a_lost_cr_between_two_frames_is_one_malformed_line_then_decoding_goes_on() {
        // "t1230\r" lost its "\r": the merged line is longer than DLC 0 allows.
        let (out, c) = lines(b"t1230t1241AA\rt1250\r");
        assert_eq!(out.first().copied(), Some(Err(LineError::Malformed)));
        assert!(matches!(out.get(1).copied(), Some(Ok(Message::Frame(f))) if f.raw_id() == 0x125));
        assert_eq!((c.malformed, c.frames), (1, 1));
    }

    #[test]
    fn an_overlong_line_is_dropped_to_its_cr_and_counted_once() {
        let mut input = [b'7'; 100];
        input[99] = b'\r';
        let (out, c) = lines(&input);
        assert_eq!((out.len(), out.first().copied()), (1, Some(Err(LineError::Overlong))));
        assert_eq!(c.overlong, 1);
        // The longest valid line fits exactly.
        let (out, _) = lines(b"T1FFFFFFF81122334455667788FFFF\r");
        assert!(matches!(out.first().copied(), Some(Ok(Message::Frame(f))) if f.dlc() == 8));
    }

    #[test]
    fn garbage_is_unknown_and_cr_lf_line_ends_work() {
        let (out, c) = lines(b"\x00\xff?\r\nO\r\nC\r\n");
        assert_eq!(out.first().copied(), Some(Err(LineError::Unknown)));
        assert_eq!(out.get(1).copied(), Some(Ok(Message::Open)));
        assert_eq!(out.get(2).copied(), Some(Ok(Message::Close)));
        assert_eq!((c.unknown, c.commands), (1, 2));
    }

    #[test]
    fn bel_interrupting_a_line_counts_it_and_reads_as_the_error_answer() {
        let (out, c) = lines(b"t12\x07t1230\r");
        assert_eq!(out.first().copied(), Some(Ok(Message::Error)));
        assert!(matches!(out.get(1).copied(), Some(Ok(Message::Frame(_)))));
        assert_eq!(c.malformed, 1);
    }

    #[test]
    fn answers_decode() {
        let (out, _) = lines(b"\rz\rZ\rV1013\rNA1B2\rF08\rZ1\r");
        let want = [
            Message::Ok,
            Message::Sent { extended: false },
            Message::Sent { extended: true },
            Message::VersionIs { hardware: 0x10, software: 0x13 },
            Message::SerialNumberIs(0xA1B2),
            Message::StatusIs(0x08),
            Message::Timestamps(true),
        ];
        for (i, w) in want.iter().enumerate() {
            assert_eq!(out.get(i).copied(), Some(Ok(*w)));
        }
    }
}
