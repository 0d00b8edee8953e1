//! cargo-fuzz target: the derive's three layouts of one dictionary (match arms, `#[od(compact)]`,
//! `#[od(compact, zerocopy)]`; issue 41) behind three SDO servers and their PDO handles, fed the same
//! input, must answer alike (differential fuzzing). The dictionaries are `canopen-core`'s
//! `tests/layouts/dictionaries.rs`, the ones `tests/layouts_agree.rs` compares by proptest; here the accesses
//! go through the SDO server on every path (expedited, segmented, block download and upload, time-outs)
//! and are chosen by coverage.
//!
//! Input: byte 0 picks the dictionary (`% 4`) and the server's block size; then records of 10 bytes, `op`
//! then 9 bytes `b`. `op % 8`: 0 → the SDO request `b[..8]`; 1 → the same with its index set to
//! 2000h + `b[1] % 10` and its sub-index to `b[3] % 8` (an initiate that finds an object); 2 → pull a
//! block-upload frame; 3 → advance time by `b[0]` ms and handle the time-out; 4 → resolve a PDO handle
//! for 2000h + `b[0] % 10`, sub `b[1] % 8`, and read through it (`b[2]` odd) or write to it a value at a
//! limit (`b[2] & 2`: edge `b[3]`, see `edges`) or `b[3..3 + b[2] / 4 % 7]`; 5 → Reset Application's
//! restore of the defaults; 6 → an expedited download of edge `b[4]` (if it has 1-4 bytes) to 2000h +
//! `b[1] % 10`, sub `b[3] % 8`; 7 → an SDO request of `b[8] % 9` bytes. Random bytes seldom hit a limit
//! exactly (the limits compare keys, which libFuzzer's comparison hints do not see), hence the edges.
//! Checks: the three answer every request with the same frame and event, every PDO access with the same
//! size and result, and hold the same values (every sub-index 00h-07h of 2000h-2009h read back) and hook
//! counts after each record. No panic anywhere.
//!
//! Run (from `fuzz/`; new inputs go to the first, gitignored directory):
//! `cargo +nightly fuzz run od_layouts corpus/od_layouts seeds/od_layouts -- -max_total_time=60`
#![no_main]

use canopen_core::od::{AbortCode, ObjectDictionary, PdoDir};
use canopen_core::sdo::{Response, SdoServer, SdoServerParams};
use canopen_core::{Duration, Instant, NodeId};
use canopen_od_derive::ObjectDictionary;
use libfuzzer_sys::fuzz_target;

include!("../../canopen-core/tests/layouts/dictionaries.rs");

/// One layout of the dictionary with its own SDO server.
struct Side<D> {
    od: D,
    server: SdoServer,
}

impl<D: ObjectDictionary + Default> Side<D> {
    fn new(blksize: u8) -> Self {
        let mut od = D::default();
        od.restore_defaults();
        let params = SdoServerParams::default_server(NodeId::new(3).unwrap());
        Side { od, server: SdoServer::new(params).with_timeout(Duration::from_millis(100)).with_block_size(blksize) }
    }
}

/// What one record's operation answered.
#[derive(Debug, PartialEq)]
enum Answer {
    Sdo(Response),
    PdoRead(Result<(u8, Result<usize, AbortCode>, [u8; 8]), AbortCode>),
    PdoWrite(Result<(u8, Result<(), AbortCode>), AbortCode>),
    None,
}

fn apply<D: ObjectDictionary>(side: &mut Side<D>, now: Instant, op: u8, b: &[u8; 9], edges: &[Vec<u8>]) -> Answer {
    let (od, server) = (&mut side.od, &mut side.server);
    let edge = |k: u8| edges[usize::from(k) % edges.len()].as_slice();
    let (index, sub) = (0x2000 + u16::from(b[1] % 10), b[3] % 8);
    match op % 8 {
        0 => Answer::Sdo(server.handle_request(now, &b[..8], od)),
        1 => {
            let mut f = [0u8; 8];
            f.copy_from_slice(&b[..8]);
            f[1..3].copy_from_slice(&index.to_le_bytes());
            f[3] = sub;
            Answer::Sdo(server.handle_request(now, &f, od))
        }
        2 => Answer::Sdo(server.poll_transmit(now, od).unwrap_or(Response::NONE)),
        3 => Answer::Sdo(server.handle_timeout(now, od)),
        4 => {
            let (index, sub) = (0x2000 + u16::from(b[0] % 10), b[1] % 8);
            if b[2] & 1 != 0 {
                Answer::PdoRead(od.pdo_resolve(index, sub, PdoDir::Tpdo).map(|h| {
                    let mut buf = [0u8; 8];
                    (h.size, od.pdo_read(&h, &mut buf), buf)
                }))
            } else {
                let data = if b[2] & 2 != 0 { edge(b[3]) } else { &b[3..3 + usize::from(b[2] / 4 % 7)] };
                Answer::PdoWrite(od.pdo_resolve(index, sub, PdoDir::Rpdo).map(|h| (h.size, od.pdo_write(&h, data))))
            }
        }
        5 => {
            od.restore_defaults();
            Answer::None
        }
        6 => {
            let value = edge(b[4]);
            let Some(unused @ 0..=3) = 4usize.checked_sub(value.len()) else { return Answer::None };
            let mut f = [0x23 | (unused as u8) << 2, 0, 0, sub, 0, 0, 0, 0];
            f[1..3].copy_from_slice(&index.to_le_bytes());
            f[4..4 + value.len()].copy_from_slice(value);
            Answer::Sdo(server.handle_request(now, &f, od))
        }
        _ => Answer::Sdo(server.handle_request(now, &b[..usize::from(b[8] % 9)], od)),
    }
}

/// Every value as SDO reads it, and the hook's count.
fn state<D: ObjectDictionary + Writes>(d: &D) -> ([Option<([u8; 8], usize)>; 80], u8) {
    let mut out = [None; 80];
    for (i, slot) in out.iter_mut().enumerate() {
        let mut buf = [0u8; 8];
        *slot = d.read(0x2000 + (i / 8) as u16, (i % 8) as u8, 0, &mut buf).ok().map(|n| (buf, n));
    }
    (out, d.writes())
}

fn run<C, P, O>(blksize: u8, records: &[u8])
where
    C: ObjectDictionary + Default + Writes,
    P: ObjectDictionary + Default + Writes,
    O: ObjectDictionary + Default + Writes,
{
    let (mut code, mut compact, mut offsets) =
        (Side::<C>::new(blksize), Side::<P>::new(blksize), Side::<O>::new(blksize));
    let (mut now, edges) = (Instant::ZERO, edges());
    for rec in records.chunks_exact(10) {
        let op = rec[0];
        let mut b = [0u8; 9];
        b.copy_from_slice(&rec[1..]);
        if op % 8 == 3 {
            now += Duration::from_millis(u64::from(b[0]));
        }
        let a = apply(&mut code, now, op, &b, &edges);
        assert_eq!(a, apply(&mut compact, now, op, &b, &edges), "compact differs on op {op} {b:02x?}");
        assert_eq!(a, apply(&mut offsets, now, op, &b, &edges), "zerocopy differs on op {op} {b:02x?}");
        let s = state(&code.od);
        assert_eq!(s, state(&compact.od), "compact's values after op {op} {b:02x?}");
        assert_eq!(s, state(&offsets.od), "zerocopy's values after op {op} {b:02x?}");
        now += Duration::from_micros(100);
    }
}

fuzz_target!(|data: &[u8]| {
    let Some((&first, records)) = data.split_first() else { return };
    let blksize = first / 4 % 127 + 1;
    match first % 4 {
        0 => run::<Code, Compact, Offsets>(blksize, records),
        1 => run::<CodeRecords, CompactRecords, OffsetRecords>(blksize, records),
        2 => run::<CodeRegular, CompactRegular, OffsetRegular>(blksize, records),
        _ => run::<CodeRegularRecords, CompactRegularRecords, OffsetRegularRecords>(blksize, records),
    }
});
