//! Properties of the codec: arbitrary bytes never panic and every line is accounted for (decoded or counted
//! as skipped); every message round-trips through encode and decode; frames survive garbage and lost `\r`s
//! around them.

use canopen_slcan::{Decoder, Message, SlcanFrame, MAX_LINE};
use proptest::prelude::*;

fn frame() -> impl Strategy<Value = SlcanFrame> {
    (any::<bool>(), any::<bool>(), 0u8..=8, prop::collection::vec(any::<u8>(), 8), any::<u32>()).prop_map(
        |(extended, remote, dlc, data, id)| {
            let id = if extended { id & 0x1FFF_FFFF } else { id & 0x7FF };
            SlcanFrame::from_raw(id, extended, remote, dlc, &data[..usize::from(dlc)]).unwrap()
        },
    )
}

fn message() -> impl Strategy<Value = Message> {
    prop_oneof![
        frame().prop_map(Message::Frame),
        Just(Message::Open),
        Just(Message::ListenOnly),
        Just(Message::Close),
        (0u8..=8).prop_map(Message::Bitrate),
        Just(Message::Version),
        Just(Message::SerialNumber),
        Just(Message::Status),
        any::<bool>().prop_map(Message::Timestamps),
        Just(Message::Ok),
        Just(Message::Error),
        any::<bool>().prop_map(|extended| Message::Sent { extended }),
        (any::<u8>(), any::<u8>()).prop_map(|(hardware, software)| Message::VersionIs { hardware, software }),
        any::<u16>().prop_map(Message::SerialNumberIs),
        any::<u8>().prop_map(Message::StatusIs),
    ]
}

proptest! {
    /// Any bytes: no panic, and each line end (`\r` or BEL) yields exactly one item, decoded or an error
    /// that the counters hold.
    #[test]
    fn arbitrary_bytes_never_panic_and_every_line_is_counted(bytes in prop::collection::vec(any::<u8>(), 0..600)) {
        let mut d = Decoder::new();
        let (mut ok, mut err) = (0u32, 0u32);
        for &b in &bytes {
            match d.push(b) {
                Some(Ok(_)) => ok += 1,
                Some(Err(_)) => err += 1,
                None => {}
            }
        }
        let ends = bytes.iter().filter(|&&b| b == b'\r' || b == 0x07).count() as u32;
        prop_assert_eq!(ok + err, ends);
        let c = d.counters();
        prop_assert_eq!(c.frames + c.commands, ok);
        // A BEL that cuts a line short counts that line too, beside its own error answer.
        prop_assert!(c.skipped() >= err);
    }

    #[test]
    fn encode_then_decode_is_the_identity(messages in prop::collection::vec(message(), 1..20)) {
        let mut d = Decoder::new();
        let mut buf = [0u8; MAX_LINE];
        for m in &messages {
            let n = m.encode(&mut buf);
            let got: Vec<_> = buf[..n].iter().filter_map(|&b| d.push(b)).collect();
            prop_assert_eq!(got, vec![Ok(*m)]);
        }
        prop_assert_eq!(d.counters().skipped(), 0);
    }

    /// Garbage without line ends before a frame, or a frame whose `\r` was lost, costs that line only: the
    /// next good line decodes.
    #[test]
    fn a_good_line_after_bad_input_decodes(
        garbage in prop::collection::vec(any::<u8>().prop_filter("no line end", |b| *b != b'\r' && *b != 7), 0..80),
        f in frame(),
    ) {
        let mut d = Decoder::new();
        let mut buf = [0u8; MAX_LINE];
        for &b in &garbage { prop_assert_eq!(d.push(b), None); }
        d.push(b'\r');
        let n = Message::Frame(f).encode(&mut buf);
        let got: Vec<_> = buf[..n].iter().filter_map(|&b| d.push(b)).collect();
        prop_assert_eq!(got, vec![Ok(Message::Frame(f))]);
    }
}
