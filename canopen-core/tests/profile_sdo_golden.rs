//! The communication profile's answers on the bus, pinned (issue 41: the profile's dictionary is being
//! restructured for flash; the bus must not see a difference). A node 5 with RAM storage, PDO defaults and
//! a heartbeat consumer gets every expedited download of a grid: each object of 1000h–1FFFh this stack can
//! have (and some it cannot), sub-indices 00h–09h, 24 values from the spec's vectors (COB-IDs valid and not,
//! with bit 29 or bits 28–11 set, restricted CAN-IDs, transmission types, SYNC counter limits, the "save"
//! and "load" signatures, consumer entries, mapping entries), written with 1 to 4 bytes indicated and with
//! no size indicated. After each one the transcript records every frame the node sends (the SDO answer,
//! abort codes included, and any EMCY, boot-up or PDO), its events, its next deadline (what the write did
//! to the services' timers: heartbeat, SYNC, PDO event timers, in simulated time) and the upload of the
//! same entry. The writes run in sequence, so the later ones meet the states the earlier ones left (a PDO
//! made invalid, a mapping emptied); after each object's writes an NMT reset communication records the
//! boot-up, the deadlines and the object's values as the defaults and the stored record (1010h) set them.
//!
//! Covers, as answers rather than as code paths: OD-04, OD-08, OD-16 (0602 0000h, 0609 0011h, 0601 0002h),
//! SDO-13 (size not indicated), COB-13/15/16 (0609 0030h), SYNC-03/10/12, HB-06..09 (0604 0043h),
//! GUARD-02/03, STORE-04/09 (0800 0020h), EMCY-02/03/09, ERR-04..11, TIME-01..03, PDO-06..18, PDO-24..26,
//! PDO-30..37 (0601 0000h, 0602 0000h, 0604 0041h/42h, 0609 0031h), NMT-27.
//!
//! The transcript is hashed per object (FNV-1a 64): `tests/data/profile_sdo_golden/<features>.txt` holds one
//! line per object. A mismatch prints the transcript of that object; `BLESS=1 cargo test --test
//! profile_sdo_golden` writes the file for the feature set under test (only when a change of behaviour is
//! meant, and said in the commit). The feature sets with a file are those CI and scripts/footprint.sh build:
//! a missing file fails the test.

use canopen_core::node::{NoApplication, Node};
use canopen_core::pdo::PdoDefault;
use canopen_core::profile::NodeConfig;
use canopen_core::storage::RamStorage;
use canopen_core::{CanFrame, Instant, NodeId, Sizes};
use std::fmt::Write as _;

type N = Node<NoApplication, Sizes<2, 16, 16, 4, 4>, RamStorage<1024>>;

static RPDO: [PdoDefault; 2] = [
    PdoDefault { mapping: &[0x1001_0008], ..PdoDefault::EVENT },
    PdoDefault { valid: false, mapping: &[], ..PdoDefault::EVENT },
];
static TPDO: [PdoDefault; 2] = [
    PdoDefault { event_timer_ms: 100, mapping: &[0x1001_0008], ..PdoDefault::EVENT },
    PdoDefault { max_mapped: 2, rtr_allowed: false, ..PdoDefault::EVENT },
];

fn node() -> N {
    let cfg = NodeConfig {
        device_type: 0x0004_0191,
        device_name: "golden",
        heartbeat_time_ms: 1000,
        guard_time_ms: 100,
        life_time_factor: 3,
        emcy_inhibit_100us: 10,
        rpdo: &RPDO,
        tpdo: &TPDO,
        ..NodeConfig::DEFAULT
    };
    let mut node: N =
        Node::with_storage(NodeId::new(5).unwrap_or_else(|| unreachable!()), cfg, NoApplication, RamStorage::new());
    node.handle_timeout(Instant::ZERO);
    while node.poll_transmit().is_some() {}
    while node.poll_event().is_some() {}
    node
}

const INDICES: [u16; 36] = [
    0x1000, 0x1001, 0x1002, 0x1003, 0x1004, 0x1005, 0x1006, 0x1007, 0x1008, 0x100C, 0x100D, 0x1010, 0x1011, 0x1012,
    0x1014, 0x1015, 0x1016, 0x1017, 0x1018, 0x1019, 0x1029, 0x1200, 0x1400, 0x1401, 0x1404, 0x1600, 0x1601, 0x1604,
    0x1800, 0x1801, 0x1804, 0x1A00, 0x1A01, 0x1A04, 0x1F80, 0x1FFF,
];

const VALUES: [u32; 24] = [
    0,
    1,
    2,
    0x7F,
    0xF0,
    0xF1,
    0xFF,
    0x0181,
    0x0000_0080,
    0x4000_0080,
    0x4000_0185,
    0x8000_0185,
    0x8000_0205,
    0x0000_0205,
    0x8000_0305,
    0x0000_0105,
    0x2000_0181,
    0x8000_0981,
    0x0002_0064,
    0x0005_00C8,
    0x1001_0008,
    0x6000_0108,
    0x6576_6173, // "save"
    0x6461_6F6C, // "load"
];

/// Expedited download command specifiers: 1..4 bytes indicated, then size not indicated.
const COMMANDS: [(u8, usize); 5] = [(0x2F, 1), (0x2B, 2), (0x27, 3), (0x23, 4), (0x22, 4)];

fn fnv(s: &str) -> u64 {
    s.bytes().fold(0xCBF2_9CE4_8422_2325, |h, b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01B3))
}

fn record(node: &mut N, out: &mut String) {
    while let Some(f) = node.poll_transmit() {
        let _ = write!(out, " {:03X}:{:02X?}", f.cob_id(), f.data());
    }
    while let Some(e) = node.poll_event() {
        let _ = write!(out, " {e:?}");
    }
    let _ = write!(out, " next {:?}", node.poll_timeout());
}

/// The transcript of every object of [`INDICES`], in order, one object's writes together.
fn transcripts() -> Vec<(u16, String)> {
    let mut node = node();
    let mut t = Instant::ZERO;
    INDICES
        .iter()
        .map(|&index| {
            let mut out = String::new();
            let [i0, i1] = index.to_le_bytes();
            for sub in 0..=9u8 {
                for v in VALUES {
                    for (cs, n) in COMMANDS {
                        t += canopen_core::Duration::from_millis(1);
                        let [b0, b1, b2, b3] = v.to_le_bytes();
                        let mut req = [cs, i0, i1, sub, b0, b1, b2, b3];
                        req[4 + n..].fill(0);
                        let _ = write!(out, "{sub:02X} {v:08X}/{cs:02X}:");
                        node.handle_frame(t, &CanFrame::new(0x605, &req).unwrap_or_else(|| unreachable!()));
                        record(&mut node, &mut out);
                        node.handle_frame(
                            t,
                            &CanFrame::new(0x605, &[0x40, i0, i1, sub, 0, 0, 0, 0]).unwrap_or_else(|| unreachable!()),
                        );
                        out.push_str(" |");
                        record(&mut node, &mut out);
                        out.push('\n');
                    }
                }
            }
            // NMT reset communication (NMT-05/06): the defaults, then what 1010h stored; the boot-up, the
            // services' deadlines and the object's values after it.
            t += canopen_core::Duration::from_millis(1);
            node.handle_frame(t, &CanFrame::new(0x000, &[0x82, 5]).unwrap_or_else(|| unreachable!()));
            out.push_str("reset:");
            record(&mut node, &mut out);
            for sub in 0..=9u8 {
                let _ = write!(out, "\n{sub:02X}:");
                let req = [0x40, i0, i1, sub, 0, 0, 0, 0];
                node.handle_frame(t, &CanFrame::new(0x605, &req).unwrap_or_else(|| unreachable!()));
                record(&mut node, &mut out);
            }
            (index, out)
        })
        .collect()
}

/// The feature set under test, as the file name of its hashes.
fn feature_key() -> String {
    let features = [
        ("time", cfg!(feature = "time")),
        ("guarding", cfg!(feature = "guarding")),
        ("error-history", cfg!(feature = "error-history")),
        ("manufacturer-strings", cfg!(feature = "manufacturer-strings")),
        ("sync-window", cfg!(feature = "sync-window")),
        ("sync-counter", cfg!(feature = "sync-counter")),
        ("emcy-inhibit", cfg!(feature = "emcy-inhibit")),
        ("error-behaviour", cfg!(feature = "error-behaviour")),
        ("store-restore", cfg!(feature = "store-restore")),
        ("pdo-dynamic-mapping", cfg!(feature = "pdo-dynamic-mapping")),
        ("pdo-mapping-64", cfg!(feature = "pdo-mapping-64")),
        ("pdo-rtr", cfg!(feature = "pdo-rtr")),
        ("sync-producer", cfg!(feature = "sync-producer")),
        ("mpdo", cfg!(feature = "mpdo")),
        ("manufacturer-status", cfg!(feature = "manufacturer-status")),
        ("high-res-time", cfg!(feature = "high-res-time")),
        ("verify-config", cfg!(feature = "verify-config")),
        ("emcy-consumer", cfg!(feature = "emcy-consumer")),
        ("lss", cfg!(feature = "lss")),
    ];
    let on: Vec<&str> = features.iter().filter(|(_, on)| *on).map(|(name, _)| *name).collect();
    if on.is_empty() {
        "none".into()
    } else {
        format!("{:016x}", fnv(&on.join(",")))
    }
}

/// Every answer of the grid is the one pinned for this feature set.
#[test]
fn profile_answers_are_pinned() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/profile_sdo_golden");
    let path = dir.join(format!("{}.txt", feature_key()));
    let got = transcripts();
    let lines: String = got.iter().map(|(index, s)| format!("{index:04X} {:016x}\n", fnv(s))).collect();
    if std::env::var_os("BLESS").is_some() {
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
        std::fs::write(&path, &lines).unwrap_or_else(|e| panic!("{e}"));
        for (index, s) in &got {
            let _ = std::fs::write(std::env::temp_dir().join(format!("profile_sdo_golden_{index:04X}.txt")), s);
        }
        return;
    }
    let want = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e}; run with BLESS=1 for a new feature set", path.display()));
    for ((index, s), (got_line, want_line)) in got.iter().zip(lines.lines().zip(want.lines())) {
        if got_line != want_line {
            let dump = std::env::temp_dir().join(format!("profile_sdo_golden_{index:04X}.now.txt"));
            let _ = std::fs::write(&dump, s);
            panic!("{index:04X}h answers differently ({got_line} vs {want_line}); transcript in {}", dump.display());
        }
    }
    assert_eq!(lines.lines().count(), want.lines().count());
}
