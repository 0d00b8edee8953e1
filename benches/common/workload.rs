//! The node's instruction-count workload (DESIGN.md "Performance"): the dictionaries, the PDO configuration
//! and the main-loop pass per received frame, one definition for both measurements of it:
//! `benches/node_instructions.rs` (x86-64, under callgrind) and `examples/qemu-m4/src/bin/bench.rs` (the
//! Cortex-M4 in QEMU, a workspace of its own), which both include this file with `#[path]`. It uses only
//! `canopen_core` and `canopen_od_derive`, which both builds depend on; recording the client's frames, the
//! measuring loops and the reports stay in each bench.

use core::hint::black_box;

use canopen_core::node::Node;
use canopen_core::od::{DomainBuf, ObjectDictionary, OdDescribe, VisibleString};
use canopen_core::pdo::PdoDefault;
use canopen_core::profile::NodeConfig;
use canopen_core::{CanFrame, Instant, Sizes};

const K: usize = 8;
/// The size of 2005h, the DOMAIN `block_download` fills: 889·8 bytes.
pub const BLOCK_LEN: usize = 889 * K;

/// Defines an application struct of the SDO scenarios with the struct attributes given: 2002h (expedited
/// download), 2004h (a 64-byte string, segmented upload), 2005h (block download). `App` and `Quiet` differ in
/// `#[od(write_events = false)]` alone.
macro_rules! sdo_app {
    ($(#[$attr:meta])* $name:ident) => {
        #[derive(canopen_od_derive::ObjectDictionary, Default)]
        #[cfg_attr(feature = "od-compact-tests", od(compact))]
        $(#[$attr])*
        pub struct $name {
            #[od(index = 0x2002, access = "rw")]
            pub value: u32,
            #[od(
                index = 0x2004,
                access = "rw",
                default = "CANopen test string of exactly sixty-four bytes for SDO uploads."
            )]
            pub text: VisibleString<64>,
            #[od(index = 0x2005, domain)]
            pub blob: DomainBuf<BLOCK_LEN>,
        }
    };
}

sdo_app!(
    /// The SDO scenarios' application.
    App
);
sdo_app!(
    /// `App` for an application that takes no write events.
    #[od(write_events = false)]
    Quiet
);

/// The process data of the PDO scenarios: 4 UNSIGNED16 objects mappable both ways. (With the root
/// package's test feature `od-compact-tests` these dictionaries are `#[od(compact)]`: the instructions of
/// that layout, `BENCH_NODE_BIN=<the bench built with it> bash scripts/bench-node.sh`.)
#[derive(canopen_od_derive::ObjectDictionary, Default)]
#[cfg_attr(feature = "od-compact-tests", od(compact))]
pub struct Process {
    #[od(index = 0x6000, access = "rww", pdo = "both")]
    pub a: u16,
    #[od(index = 0x6001, access = "rww", pdo = "both")]
    pub b: u16,
    #[od(index = 0x6002, access = "rww", pdo = "both")]
    pub c: u16,
    #[od(index = 0x6003, access = "rww", pdo = "both")]
    pub d: u16,
    #[od(index = 0x6010, access = "rw", default = 7)]
    pub unmapped: u32,
}

/// The mapping of every PDO of the PDO scenarios: 6000h..6003h, 16 bits each.
pub const MAP: &[u32] = &[0x6000_0010, 0x6001_0010, 0x6002_0010, 0x6003_0010];
const RPDO: PdoDefault = PdoDefault { transmission_type: 255, mapping: MAP, ..PdoDefault::EVENT };
const TPDO: PdoDefault = PdoDefault { transmission_type: 1, mapping: MAP, ..PdoDefault::EVENT };
/// The PDO scenarios' node: one RPDO applied at reception (FFh), four synchronous TPDOs (01h).
pub const PDO_CFG: NodeConfig = NodeConfig { rpdo: &[RPDO], tpdo: &[TPDO, TPDO, TPDO, TPDO], ..NodeConfig::DEFAULT };

/// One main-loop pass for the received frame `f`, as `canopen_core::driver::run`'s service loop takes it:
/// `handle_frame`, the node's events until none is left, then each frame out peeked, sent and only then taken
/// (`transmitted`), so a cancelled send loses nothing. Adds the frames sent to `sent`. Inlined into each
/// bench's measuring loop, so the figures count the pass and not a call to it.
#[inline(always)]
pub fn pass<A: ObjectDictionary + OdDescribe>(node: &mut Node<A, Sizes>, f: &CanFrame, sent: &mut u64) {
    node.handle_frame(Instant::ZERO, black_box(f));
    loop {
        if let Some(e) = node.poll_event() {
            black_box(e);
            continue;
        }
        let Some(out) = node.peek_transmit() else { break };
        node.transmitted(black_box(&out));
        *sent += 1;
    }
}
