//! The access rules of a derived dictionary as an SDO client sees them, on every path (expedited,
//! segmented, block): OD-08/OD-09 (ro, wo, rw, rwr, rww, const), OD-16 and ABORT-09/ABORT-10 (a read of a
//! write-only entry is 0601 0001h, a write of a read-only or const one 0601 0002h, also for sub 00h of an
//! ARRAY or RECORD), OD-04 (sub 00h holds the highest sub-index). Issue 41: the derive's output became
//! tables served by one generic path (`od::data`), so these answers come from the rows' access bits; with
//! those two codes swapped (or the access check dropped on one path) a test here fails.

use canopen_core::node::Node;
use canopen_core::od::{AbortCode, ObjectDictionary};
use canopen_core::profile::NodeConfig;
use canopen_core::{CanFrame, Instant, NodeId};
use canopen_od_derive::ObjectDictionary;

/// Defines a dictionary with one entry per access type, as a VAR of 4 bytes (expedited), a VAR of 8 bytes
/// (segmented), an ARRAY element and a RECORD member; `$attr` picks the derive's layout.
macro_rules! rules {
    ($name:ident $(, $attr:meta)*) => {
        #[derive(ObjectDictionary, Default)]
        $(#[$attr])*
        struct $name {
            #[od(index = 0x2000, access = "ro", default = 0x1111_1111)]
            ro: u32,
            #[od(index = 0x2001, access = "wo")]
            wo: u32,
            #[od(index = 0x2002, access = "rw")]
            rw: u32,
            #[od(index = 0x2003, access = "rwr")]
            rwr: u32,
            #[od(index = 0x2004, access = "rww")]
            rww: u32,
            #[od(index = 0x2005, access = "const", default = 5)]
            konst: u32,
            #[od(index = 0x2010, access = "ro", default = 0x0102_0304_0506_0708)]
            ro64: u64,
            #[od(index = 0x2011, access = "wo")]
            wo64: u64,
            #[od(index = 0x2012, access = "rw")]
            rw64: u64,
            #[od(index = 0x2020, sub = 1..=2, access = "wo")]
            wo_array: [u16; 2],
            #[od(index = 0x2021, sub = 1, record = "Mixed", access = "ro", default = 7)]
            member_ro: u8,
            #[od(index = 0x2021, sub = 3, access = "wo")]
            member_wo: u8,
            /// Not in the dictionary: the tail a `repr(C)` struct would pad (zerocopy's byte view has none).
            _pad: [u8; 2],
        }
    };
}
rules!(Rules);
rules!(Compact, od(compact));
rules!(Offsets, od(compact, zerocopy), derive(zerocopy::IntoBytes, zerocopy::FromBytes, zerocopy::Immutable), repr(C));

const ACCESS_4: [(u16, &str); 6] =
    [(0x2000, "ro"), (0x2001, "wo"), (0x2002, "rw"), (0x2003, "rwr"), (0x2004, "rww"), (0x2005, "const")];

fn booted<A: ObjectDictionary + Default>() -> Node<A> {
    let mut node: Node<A> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, A::default());
    node.handle_timeout(Instant::ZERO);
    while node.poll_transmit().is_some() {}
    node
}

/// The node's one answer to an SDO request on 605h.
fn sdo<A: ObjectDictionary>(node: &mut Node<A>, req: [u8; 8]) -> [u8; 8] {
    node.handle_frame(Instant::from_millis(1), &CanFrame::new(0x605, &req).unwrap());
    let answers: Vec<[u8; 8]> =
        core::iter::from_fn(|| node.poll_transmit()).map(|f| <[u8; 8]>::try_from(f.data()).unwrap()).collect();
    assert_eq!(answers.len(), 1, "{req:02X?} -> {answers:02X?}");
    answers[0]
}

fn abort(index: u16, sub: u8, code: AbortCode) -> [u8; 8] {
    let [i0, i1] = index.to_le_bytes();
    let [c0, c1, c2, c3] = code.code().to_le_bytes();
    [0x80, i0, i1, sub, c0, c1, c2, c3]
}

fn req(cmd: u8, index: u16, sub: u8, data: [u8; 4]) -> [u8; 8] {
    let [i0, i1] = index.to_le_bytes();
    [cmd, i0, i1, sub, data[0], data[1], data[2], data[3]]
}

/// The tests, for a dictionary type: each layout of the derive answers the same.
macro_rules! access_tests {
    ($m:ident, $t:ty) => {
        mod $m {
            use super::*;

            /// OD-08, OD-09, OD-16, ABORT-09, ABORT-10, SDO-12, SDO-17: expedited upload and download of each access
            /// type: wo refuses the read with 0601 0001h, ro and const refuse the write with 0601 0002h (the value
            /// stays), rw/rwr/rww take both.
            #[test]
            fn every_access_type_over_expedited_sdo() {
                let mut node = booted::<$t>();
                for (index, access) in ACCESS_4 {
                    let up = sdo(&mut node, req(0x40, index, 0, [0; 4]));
                    let down = sdo(&mut node, req(0x23, index, 0, [0x78, 0x56, 0x34, 0x12]));
                    match access {
                        "wo" => {
                            assert_eq!(up, abort(index, 0, AbortCode::ReadOfWriteOnly), "{access}");
                            assert_eq!(down, req(0x60, index, 0, [0; 4]), "{access}");
                        }
                        "ro" | "const" => {
                            assert_eq!(up[0], 0x43, "{access}: {up:02X?}");
                            assert_eq!(down, abort(index, 0, AbortCode::WriteOfReadOnly), "{access}");
                            assert_eq!(
                                sdo(&mut node, req(0x40, index, 0, [0; 4])),
                                up,
                                "{access}: a refused write changed it"
                            );
                        }
                        _ => {
                            assert_eq!(down, req(0x60, index, 0, [0; 4]), "{access}");
                            let again = sdo(&mut node, req(0x40, index, 0, [0; 4]));
                            assert_eq!(again, req(0x43, index, 0, [0x78, 0x56, 0x34, 0x12]), "{access}");
                        }
                    }
                }
                assert_eq!((node.app().wo, node.app().rw, node.app().konst), (0x1234_5678, 0x1234_5678, 5));
            }

            /// OD-04, ABORT-09, ABORT-10: an ARRAY's and a RECORD's elements and sub 00h over expedited SDO: sub 00h
            /// reads the highest sub-index and refuses a write with 0601 0002h; a write-only element refuses a read
            /// with 0601 0001h; a missing RECORD sub-index is 0609 0011h.
            #[test]
            fn array_and_record_entries_over_expedited_sdo() {
                let mut node = booted::<$t>();
                assert_eq!(sdo(&mut node, req(0x40, 0x2020, 0, [0; 4])), req(0x4F, 0x2020, 0, [2, 0, 0, 0]));
                assert_eq!(
                    sdo(&mut node, req(0x2F, 0x2020, 0, [1, 0, 0, 0])),
                    abort(0x2020, 0, AbortCode::WriteOfReadOnly)
                );
                assert_eq!(sdo(&mut node, req(0x40, 0x2020, 2, [0; 4])), abort(0x2020, 2, AbortCode::ReadOfWriteOnly));
                assert_eq!(sdo(&mut node, req(0x2B, 0x2020, 2, [0xCD, 0xAB, 0, 0])), req(0x60, 0x2020, 2, [0; 4]));
                assert_eq!(node.app().wo_array, [0, 0xABCD]);
                assert_eq!(
                    sdo(&mut node, req(0x40, 0x2020, 3, [0; 4])),
                    abort(0x2020, 3, AbortCode::SubIndexDoesNotExist)
                );

                assert_eq!(sdo(&mut node, req(0x40, 0x2021, 0, [0; 4])), req(0x4F, 0x2021, 0, [3, 0, 0, 0]));
                assert_eq!(sdo(&mut node, req(0x40, 0x2021, 1, [0; 4])), req(0x4F, 0x2021, 1, [7, 0, 0, 0]));
                assert_eq!(
                    sdo(&mut node, req(0x2F, 0x2021, 1, [1, 0, 0, 0])),
                    abort(0x2021, 1, AbortCode::WriteOfReadOnly)
                );
                assert_eq!(
                    sdo(&mut node, req(0x40, 0x2021, 2, [0; 4])),
                    abort(0x2021, 2, AbortCode::SubIndexDoesNotExist)
                );
                assert_eq!(sdo(&mut node, req(0x40, 0x2021, 3, [0; 4])), abort(0x2021, 3, AbortCode::ReadOfWriteOnly));
                assert_eq!(sdo(&mut node, req(0x2F, 0x2021, 3, [9, 0, 0, 0])), req(0x60, 0x2021, 3, [0; 4]));
                assert_eq!(node.app().member_wo, 9);
            }

            /// ABORT-09, ABORT-10, SDO-14, SDO-19..SDO-21, SDO-25: segmented transfers of 8-byte values: the upload of
            /// a write-only one is refused at the initiate with 0601 0001h, a download to a read-only one with
            /// 0601 0002h; the read-write one takes a download and gives it back.
            #[test]
            fn access_rules_over_segmented_sdo() {
                let mut node = booted::<$t>();
                assert_eq!(sdo(&mut node, req(0x40, 0x2011, 0, [0; 4])), abort(0x2011, 0, AbortCode::ReadOfWriteOnly));
                assert_eq!(
                    sdo(&mut node, req(0x21, 0x2010, 0, [8, 0, 0, 0])),
                    abort(0x2010, 0, AbortCode::WriteOfReadOnly)
                );
                assert_eq!(sdo(&mut node, req(0x40, 0x2010, 0, [0; 4])), req(0x41, 0x2010, 0, [8, 0, 0, 0]));
                assert_eq!(sdo(&mut node, [0x60, 0, 0, 0, 0, 0, 0, 0]), [0x00, 8, 7, 6, 5, 4, 3, 2]);
                assert_eq!(sdo(&mut node, [0x70, 0, 0, 0, 0, 0, 0, 0]), [0x1D, 1, 0, 0, 0, 0, 0, 0]);

                for index in [0x2011, 0x2012] {
                    assert_eq!(sdo(&mut node, req(0x21, index, 0, [8, 0, 0, 0])), req(0x60, index, 0, [0; 4]));
                    assert_eq!(sdo(&mut node, [0x00, 1, 2, 3, 4, 5, 6, 7]), [0x20, 0, 0, 0, 0, 0, 0, 0]);
                    assert_eq!(sdo(&mut node, [0x1D, 8, 0, 0, 0, 0, 0, 0]), [0x30, 0, 0, 0, 0, 0, 0, 0]);
                }
                assert_eq!((node.app().wo64, node.app().rw64), (0x0807_0605_0403_0201, 0x0807_0605_0403_0201));
            }

            /// ABORT-09, ABORT-10, SDO-31 (block transfers): a block upload of a write-only entry is refused at its
            /// initiate with 0601 0001h, a block download to a read-only or const one with 0601 0002h; a writable one
            /// is accepted (scs 5, the block size follows).
            #[cfg(feature = "sdo-block")]
            #[test]
            fn access_rules_over_block_sdo() {
                let mut node = booted::<$t>();
                // Block upload initiate: ccs 5, CRC, cs 0; byte 4 the block size, byte 5 the protocol switch threshold.
                assert_eq!(
                    sdo(&mut node, req(0xA4, 0x2011, 0, [16, 0, 0, 0])),
                    abort(0x2011, 0, AbortCode::ReadOfWriteOnly)
                );
                assert_eq!(
                    sdo(&mut node, req(0xA4, 0x2001, 0, [16, 0, 0, 0])),
                    abort(0x2001, 0, AbortCode::ReadOfWriteOnly)
                );
                // Block download initiate: ccs 6, CRC, size indicated, cs 0.
                for (index, size) in [(0x2010u16, 8u8), (0x2000, 4), (0x2005, 4)] {
                    assert_eq!(
                        sdo(&mut node, req(0xC6, index, 0, [size, 0, 0, 0])),
                        abort(index, 0, AbortCode::WriteOfReadOnly)
                    );
                }
                let ok = sdo(&mut node, req(0xC6, 0x2012, 0, [8, 0, 0, 0]));
                assert_eq!(&ok[..4], &[0xA4, 0x12, 0x20, 0x00], "{ok:02X?}");
                assert!(ok[4] > 0);
            }
        }
    };
}
access_tests!(match_arms, Rules);
access_tests!(compact, Compact);
access_tests!(offsets, Offsets);

/// Defines a dictionary without a writable string or DOMAIN (a read-only string, fixed-size values):
/// `STREAMS` is false, and the streamed-write calls refuse every entry as the rows say.
macro_rules! no_streams {
    ($name:ident $(, $attr:meta)*) => {
        #[derive(ObjectDictionary, Default)]
        $(#[$attr])*
        struct $name {
            #[od(index = 0x2000, access = "ro", default = "abc")]
            name: canopen_core::od::VisibleString<4>,
            #[od(index = 0x2001, access = "rw", default = 3)]
            rw: u32,
            #[od(index = 0x2002, sub = 1..=2, access = "rw")]
            array: [u8; 2],
        }
    };
}
no_streams!(NoStreamsArms);
no_streams!(NoStreamsCompact, od(compact));

/// OD-16, ABORT-10: a dictionary without a writable string or DOMAIN takes no streamed write: `begin_write`,
/// `write_chunk` and `end_write` answer 0602 0000h (no object), 0609 0011h (no sub-index), 0601 0002h (a
/// read-only string, sub 00h) or 0601 0000h (a fixed-size value), and `abort_write` changes nothing.
fn streamed_writes_refused<A: ObjectDictionary + Default>() {
    assert!(!A::STREAMS);
    let mut od = A::default();
    od.restore_defaults();
    let cases = [
        (0x2003, 0, AbortCode::ObjectDoesNotExist),
        (0x2002, 3, AbortCode::SubIndexDoesNotExist),
        (0x2000, 0, AbortCode::WriteOfReadOnly),
        (0x2002, 0, AbortCode::WriteOfReadOnly),
        (0x2001, 0, AbortCode::UnsupportedAccess),
        (0x2002, 1, AbortCode::UnsupportedAccess),
    ];
    for (index, sub, code) in cases {
        assert_eq!(od.begin_write(index, sub, Some(1)), Err(code), "{index:04X}:{sub}");
        assert_eq!(od.write_chunk(index, sub, 0, &[1]), Err(code), "{index:04X}:{sub}");
        assert_eq!(od.end_write(index, sub, 1), Err(code), "{index:04X}:{sub}");
        od.abort_write(index, sub);
    }
    let mut buf = [0u8; 4];
    assert_eq!(od.read(0x2000, 0, 0, &mut buf), Ok(3));
    assert_eq!(&buf[..3], b"abc");
    assert_eq!(od.read(0x2001, 0, 0, &mut buf), Ok(4));
    assert_eq!(buf, [3, 0, 0, 0]);
}

#[test]
fn streamed_writes_refused_match_arms() {
    streamed_writes_refused::<NoStreamsArms>();
}

#[test]
fn streamed_writes_refused_compact() {
    streamed_writes_refused::<NoStreamsCompact>();
}
