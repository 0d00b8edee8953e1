//! SDO transfers over one shared lossy bus (issue 21 item 3): two client ↔ server pairs and background traffic
//! on one wire, frames dropped, duplicated and reordered across COB-IDs at 1–10 % each, seeded.
//!
//! Every transfer (segmented and block, both directions, block with and without CRC) either completes
//! byte-exact or aborts with a Table 22 code on both sides (SDO-31..SDO-33, ABORT-02); no side's deadline is
//! ever more than the SDO timeout ahead, the wire is never silent longer than that while a side is busy, and
//! every server and client is idle at the end (the bus asserts these as it runs).
//!
//! Run: `cargo test -p canopen-core --test sdo_lossy_bus` (`SDO_LOSSY_SEEDS=n` runs n seeds instead of 40,
//! `SDO_LOSSY_FIRST=k` starts at seed k).

mod support;

use canopen_core::od::AbortCode;
use canopen_core::sdo::client::{ClientEvent, Mode};
use canopen_core::sdo::SdoEvent;
use canopen_core::Duration;
use support::bus::{Bus, Job, Outcome, Pair, Rates};
use support::harness::{is_spec_code, Dir, Rng};

const TIMEOUT: Duration = Duration::from_millis(100);

fn payload(len: usize, seed: u64) -> Vec<u8> {
    (0..len).map(|i| (i as u64).wrapping_mul(131).wrapping_add(seed) as u8).collect()
}

/// A seeded mix of transfers: segmented and block, both directions, sizes 0..=1500; block without CRC only
/// when `no_crc`.
fn jobs(rng: &mut Rng, n: usize, no_crc: bool) -> Vec<Job> {
    (0..n)
        .map(|_| {
            let mode = match rng.next() % 4 {
                0 => Mode::Segmented,
                1 if no_crc => Mode::Block { crc: false, blksize: 1 + (rng.next() % 127) as u8, pst: 0 },
                _ => Mode::Block { crc: true, blksize: 1 + (rng.next() % 127) as u8, pst: 0 },
            };
            let dir = if rng.next() % 2 == 0 { Dir::Download } else { Dir::Upload };
            let len = (rng.next() % 1500) as usize;
            Job { dir, mode, payload: payload(len, rng.next()) }
        })
        .collect()
}

/// The outcome without the data.
fn brief(o: &Outcome) -> String {
    format!(
        "client {:?}, server {:?}, {} B of data, first difference at {:?}",
        o.client,
        o.server,
        o.data.len(),
        o.data.iter().zip(&o.job.payload).position(|(a, b)| a != b)
    )
}

/// The per-transfer checks; returns whether the transfer completed.
fn check(o: &Outcome, what: &str) -> bool {
    let len = o.job.payload.len();
    let client = o.client.unwrap_or_else(|| panic!("{what}: no client outcome: {o:?}"));
    for ev in &o.server {
        if let SdoEvent::AbortReceived { code, .. } = ev {
            assert!(is_spec_code(*code), "{what}: server got an abort with a non-spec code: {ev:?}");
        }
    }
    let written = o.server.iter().any(|e| matches!(e, SdoEvent::Written { .. }));
    if o.job.dir == Dir::Download {
        // the dictionary committed the new value exactly, or (no Written) nothing: 2000h keeps its old value
        // (the test dictionary streams in place and commits the length at end_write)
        if written {
            assert!(o.data == o.job.payload, "{what}: server reported Written with other data; {}", brief(o));
            assert_eq!(o.commits, 1, "{what}");
        } else {
            assert_eq!(o.commits, 0, "{what}: an aborted download committed; {}", brief(o));
            assert_eq!(o.data.len(), o.before.len(), "{what}: an aborted download changed 2000h's length");
        }
    }
    match client {
        ClientEvent::Done { len: n } => {
            assert_eq!(n, len, "{what}");
            if o.job.dir == Dir::Upload {
                assert!(o.data == o.job.payload, "{what}: upload completed with other data; {}", brief(o));
            } else {
                assert!(written, "{what}: client Done but the server never wrote: {:?}", o.server);
            }
            true
        }
        ClientEvent::Failed(e) => {
            assert!(is_spec_code(e.code()), "{what}: client failed with a non-spec code {e:?}");
            false
        }
    }
}

/// One seeded run of two pairs with six transfers each. With `dup`, frames are also duplicated and block
/// transfers use CRC: a block transfer without CRC cannot tell a duplicated acknowledge from a new one
/// (CiA 301 has no other integrity check there; the CRC turns it into abort 0504 0004h).
fn run_seed(seed: u64, dup: bool) -> (usize, usize) {
    let mut rng = Rng::new(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0x5D0);
    let rates = Rates {
        drop: 10 + (rng.next() % 91) as u32,
        dup: if dup { 10 + (rng.next() % 91) as u32 } else { 0 },
        reorder: 10 + (rng.next() % 91) as u32,
    };
    let pairs = vec![
        Pair::new(3, 1 + (rng.next() % 127) as u8, TIMEOUT, jobs(&mut rng, 6, !dup)),
        Pair::new(4, 1 + (rng.next() % 127) as u8, TIMEOUT, jobs(&mut rng, 6, !dup)),
    ];
    let mut bus = Bus::new(pairs, rates, rng.next());
    bus.run(TIMEOUT);
    let (mut done, mut failed) = (0, 0);
    for p in &bus.pairs {
        assert!(
            p.server.is_idle() && p.client.is_idle(),
            "seed {seed}: node {} left busy: server {:?}, client idle {}, last {:?}",
            p.node,
            p.server.state(),
            p.client.is_idle(),
            p.done.last().map(brief)
        );
        for (i, o) in p.done.iter().enumerate() {
            let what = format!(
                "seed {seed} {rates:?} node {} transfer {i} {:?} {:?} {} B",
                p.node,
                o.job.dir,
                o.job.mode,
                o.job.payload.len()
            );
            if check(o, &what) {
                done += 1;
            } else {
                failed += 1;
            }
        }
    }
    (done, failed)
}

/// Issue 21 item 3 over many seeds: every transfer completes byte-exact or aborts cleanly on both sides.
#[test]
fn lossy_shared_bus_completes_or_aborts_cleanly() {
    let seeds: u64 = std::env::var("SDO_LOSSY_SEEDS").ok().and_then(|s| s.parse().ok()).unwrap_or(40);
    let (mut done, mut failed) = (0, 0);
    let first: u64 = std::env::var("SDO_LOSSY_FIRST").ok().and_then(|s| s.parse().ok()).unwrap_or(0);
    for seed in first..first + seeds {
        for dup in [true, false] {
            let (d, f) = run_seed(seed, dup);
            done += d;
            failed += f;
        }
    }
    eprintln!("{seeds} seeds: {done} transfers completed, {failed} aborted");
    // the faults bite (a segmented transfer has no retry: one lost frame ends it by the time-out), and
    // transfers still get through
    assert!(failed > 0 && done > 0, "done {done}, failed {failed}");
}

/// Lost last segment of a sub-block (issue 21 item 2, server side): the server acknowledges the segments it
/// has after a quarter of the SDO timeout of silence, the client resends the rest, and the download completes
/// well before the timeout instead of aborting with 0504 0000h.
#[test]
fn lost_last_segment_of_a_sub_block_recovers_before_the_timeout() {
    for crc in [true, false] {
        let data = payload(100, 7);
        let job = Job { dir: Dir::Download, mode: Mode::Block { crc, blksize: 127, pst: 0 }, payload: data.clone() };
        let mut bus = Bus::new(vec![Pair::new(3, 4, TIMEOUT, vec![job])], Rates::default(), 1);
        bus.noise_every = 0;
        let mut lost = false;
        bus.lose(move |cob, f| {
            // the 4th segment (seqno 4 of the first sub-block, blksize 4): once
            let hit = !lost && cob == 0x603 && f[0] == 0x04;
            lost |= hit;
            hit
        });
        bus.run(TIMEOUT);
        let o = &bus.pairs[0].done[0];
        assert_eq!(o.client, Some(ClientEvent::Done { len: 100 }), "crc {crc}: {}", brief(o));
        assert_eq!(o.data, data);
        let took = o.client_done.saturating_duration_since(o.started);
        assert!(took < Duration::from_micros(TIMEOUT.as_micros() / 2), "crc {crc}: took {took:?}");
        assert!(!o.server.iter().any(|e| matches!(e, SdoEvent::Aborted { code: AbortCode::SdoTimeout, .. })));
    }
}
