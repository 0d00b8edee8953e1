//! Instruction-count workload for PDO traffic through a whole `Node` (handle_frame + draining
//! poll_transmit and poll_event), the DESIGN.md reference workload:
//!
//! - `rpdo`: one 8-byte RPDO (event-driven, FFh) mapped to 4 UNSIGNED16 objects of a derived dictionary;
//! - `sync_tpdo`: one SYNC that makes 4 synchronous (type 1) TPDOs of 8 bytes, each mapped to 4 UNSIGNED16.
//!
//! `pdo_instructions <scenario> <iterations>` prints "<n> frames" (frames received + sent);
//! `scripts/bench-instructions.sh` runs it under callgrind with N and 0 iterations and divides the
//! difference by the number of frames (and, for `sync_tpdo`, also by the number of SYNCs).

use std::hint::black_box;

use canopen_core::comm::NodeConfig;
use canopen_core::node::Node;
use canopen_core::pdo::PdoDefault;
use canopen_core::{CanFrame, Instant, NmtState, NodeId};
use canopen_od_derive::ObjectDictionary;

#[derive(ObjectDictionary, Default)]
pub struct App {
    #[od(index = 0x6000, access = "rww", pdo = "both")]
    a: u16,
    #[od(index = 0x6001, access = "rww", pdo = "both")]
    b: u16,
    #[od(index = 0x6002, access = "rww", pdo = "both")]
    c: u16,
    #[od(index = 0x6003, access = "rww", pdo = "both")]
    d: u16,
    #[od(index = 0x6010, access = "rw", default = 7)]
    unmapped: u32,
}

const MAP: &[u32] = &[0x6000_0010, 0x6001_0010, 0x6002_0010, 0x6003_0010];
const RPDO: PdoDefault = PdoDefault { transmission_type: 255, mapping: MAP, ..PdoDefault::EVENT };
const TPDO: PdoDefault = PdoDefault { transmission_type: 1, mapping: MAP, ..PdoDefault::EVENT };
const CFG: NodeConfig = NodeConfig { rpdo: &[RPDO], tpdo: &[TPDO, TPDO, TPDO, TPDO], ..NodeConfig::DEFAULT };

fn main() {
    let mut args = std::env::args().skip(1);
    let scenario = args.next().unwrap_or_else(|| "rpdo".into());
    let iterations: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(1000);
    let mut node: Node<App, 0, 16, 16, 4, 4> = Node::new(NodeId::new(3).unwrap(), CFG, App::default());
    let now = Instant::from_millis(1);
    node.handle_timeout(now);
    node.enter_state(NmtState::Operational);
    while node.poll_transmit().is_some() {}
    while node.poll_event().is_some() {}
    let frame = match scenario.as_str() {
        "rpdo" => CanFrame::new(0x203, &[1, 2, 3, 4, 5, 6, 7, 8]).unwrap(),
        "sync_tpdo" => CanFrame::new(0x080, &[]).unwrap(),
        other => panic!("unknown scenario {other}"),
    };
    let frame = black_box(frame);
    let mut frames = 0usize;
    for _ in 0..iterations {
        node.handle_frame(now, black_box(&frame));
        frames += 1;
        while let Some(f) = node.poll_transmit() {
            black_box(f);
            frames += 1;
        }
        while let Some(e) = node.poll_event() {
            black_box(e);
        }
    }
    if scenario == "rpdo" && iterations > 0 {
        assert_eq!(node.app().d, 0x0807);
    }
    assert_eq!(node.tx_dropped(), 0);
    println!("{scenario}: {frames} frames, {iterations} iterations");
}
