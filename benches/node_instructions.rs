//! Instruction-count workload for the whole node (DESIGN.md "Performance"): one main-loop pass per received
//! frame, i.e. one `handle_frame` plus the drain of the node's events and frames the way
//! `canopen_core::driver`'s service loop takes them: `poll_event` until empty, then `peek_transmit` and,
//! once sent, `transmitted` (cancel safety). The driver's `handle_timeout`/`poll_timeout` per wake-up are
//! not counted (time, not frames: see `scripts/bench-node.sh`).
//!
//! `node_instructions <scenario> <iterations>` runs a scenario `iterations` times and prints how many frames
//! the node received and sent; `scripts/bench-node.sh` runs it under callgrind with N and with 0 iterations
//! and divides the difference by the number of frames, so set-up and process start-up cancel out.
//!
//! The SDO client's frames are recorded once with our SDO client before the measured part and then
//! replayed, so the client's own work is not counted. Scenarios, all on a `Node<_, Sizes>`:
//!
//! - `expedited_upload` (1000h), `expedited_download` (a U32), `segmented_upload` (a 64-byte
//!   VISIBLE_STRING), `block_download` (889·8 bytes with CRC into a DOMAIN), node Pre-operational;
//! - `expedited_download_quiet`: `expedited_download` to an application that takes no write events
//!   (`#[od(write_events = false)]`, as a CANopenNode application without OD extension callbacks), so no
//!   `Event::ObjectWritten` is queued and polled;
//! - `rpdo_4_objects`: one 8-byte RPDO (FFh) mapped to 4 UNSIGNED16 objects, node Operational;
//! - `sync_4_tpdos`: one SYNC that makes 4 synchronous (01h) TPDOs of 8 bytes, each mapped to 4 UNSIGNED16,
//!   node Operational (5 bus frames per received frame).
//!
//! The dictionary reached by offset (`#[od(compact, zerocopy)]`, issue 41), beside the default layout:
//! `expedited_download@zerocopy`, `rpdo_4_objects@zerocopy` and `sync_4_tpdos@zerocopy` are the same
//! scenarios on such dictionaries, and `expedited_download@thousand` writes 2002h of a 1,000-VAR one
//! (`thousand.rs`): the lookup cost as the dictionary grows.

use canopen::core::{
    node::Node,
    profile::NodeConfig,
    sdo::client::{ClientEvent, Mode, SdoClient, SliceData},
    sdo::SdoClientParams,
    wire::sdo::Multiplexer,
    CanFrame, Instant, NmtState, NodeId, Sizes,
};
use canopen::ObjectDictionary;

/// `App`'s 2002h alone, reached by offset.
#[derive(ObjectDictionary, Default, zerocopy::IntoBytes, zerocopy::FromBytes, zerocopy::Immutable)]
#[od(crate = "canopen::core", compact, zerocopy)]
#[repr(C)]
struct ZeroCopyApp {
    #[od(index = 0x2002, access = "rw")]
    value: u32,
}

#[path = "thousand.rs"]
mod thousand;
#[path = "common/workload.rs"]
mod workload;
use workload::{App, Process, Quiet, BLOCK_LEN, PDO_CFG};

fn new_node() -> Node<App, Sizes> {
    booted(App::default()) // power-on (Reset Application) gives every entry its `default =` value
}

/// A node of `app`, booted, queues drained.
fn booted<A: canopen::core::od::ObjectDictionary>(app: A) -> Node<A, Sizes> {
    let cfg = NodeConfig { device_type: 0x000F_0191, ..NodeConfig::DEFAULT };
    let mut node = Node::new(NodeId::new(5).unwrap(), cfg, app);
    node.handle_timeout(Instant::ZERO);
    while node.poll_transmit().is_some() {}
    while node.poll_event().is_some() {}
    node
}

/// `Process`, reached by offset.
#[derive(ObjectDictionary, Default, zerocopy::IntoBytes, zerocopy::FromBytes, zerocopy::Immutable)]
#[od(crate = "canopen::core", compact, zerocopy)]
#[repr(C)]
struct ZeroCopyProcess {
    #[od(index = 0x6010, access = "rw", default = 7)]
    unmapped: u32,
    #[od(index = 0x6000, access = "rww", pdo = "both")]
    a: u16,
    #[od(index = 0x6001, access = "rww", pdo = "both")]
    b: u16,
    #[od(index = 0x6002, access = "rww", pdo = "both")]
    c: u16,
    #[od(index = 0x6003, access = "rww", pdo = "both")]
    d: u16,
}

/// A node with one RPDO and four synchronous TPDOs, Operational, queues drained.
fn pdo_node<P: canopen::core::od::ObjectDictionary + Default>() -> Node<P, Sizes> {
    let mut node = Node::new(NodeId::new(5).unwrap(), PDO_CFG, P::default());
    node.handle_timeout(Instant::ZERO);
    node.enter_state(NmtState::Operational);
    while node.poll_transmit().is_some() {}
    while node.poll_event().is_some() {}
    node
}

/// The PDO scenarios on a node of [`pdo_node`]: an RPDO of 8 bytes, or a SYNC (4 TPDOs each).
fn pdo_run<P: canopen::core::od::ObjectDictionary + canopen::core::od::OdDescribe>(
    node: &mut Node<P, Sizes>,
    scenario: &str,
    iterations: usize,
) -> (usize, usize) {
    let frame = match scenario.starts_with("rpdo_4_objects") {
        true => CanFrame::new(0x205, &[1, 2, 3, 4, 5, 6, 7, 8]).unwrap(),
        false => CanFrame::new(0x080, &[]).unwrap(),
    };
    let r = run(node, &[frame], iterations);
    if scenario.starts_with("sync_4_tpdos") {
        assert_eq!(r.1, 4 * iterations);
    }
    r
}

/// Replays `script` `iterations` times, one main-loop pass per frame; returns (received, sent) frames.
fn run<A: canopen::core::od::ObjectDictionary + canopen::core::od::OdDescribe>(
    node: &mut Node<A, Sizes>,
    script: &[CanFrame],
    iterations: usize,
) -> (usize, usize) {
    let (mut frames, mut sent) = (0usize, 0u64);
    for _ in 0..iterations {
        for f in script {
            workload::pass(node, f, &mut sent);
            frames += 1;
        }
    }
    assert_eq!(node.tx_dropped(), 0);
    (frames, sent as usize)
}

/// Runs one transfer with our client against a node and records the client's frames.
fn record(mux: Multiplexer, mode: Mode, download: Option<Vec<u8>>) -> Vec<CanFrame> {
    let mut node = new_node();
    let params = SdoClientParams::for_server(NodeId::new(5).unwrap());
    let mut client = SdoClient::new(params);
    let mut buf = download.clone().unwrap_or_else(|| vec![0; 1 << 16]);
    let mut data = if download.is_some() { SliceData::download(&mut buf) } else { SliceData::upload(&mut buf) };
    let len = download.as_ref().map_or(0, Vec::len);
    match download {
        Some(_) => client.start_download(Instant::ZERO, mux, len, mode).unwrap(),
        None => client.start_upload(Instant::ZERO, mux, mode).unwrap(),
    }
    let mut sent = Vec::new();
    loop {
        while let Some(f) = client.poll_transmit(Instant::ZERO, &mut data) {
            let frame = CanFrame::new(params.tx_cob_id(), &f).unwrap();
            sent.push(frame);
            node.handle_frame(Instant::ZERO, &frame);
        }
        while let Some(out) = node.poll_transmit() {
            if let Some(ClientEvent::Done { .. }) = client.handle_response(Instant::ZERO, out.data(), &mut data) {
                return sent;
            }
        }
    }
}

fn main() {
    let mut args = std::env::args().skip(1);
    let scenario = args.next().unwrap_or_default();
    let iterations: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(1);
    let (frames, sent) = match scenario.as_str() {
        "rpdo_4_objects" | "sync_4_tpdos" => {
            let mut node = pdo_node::<Process>();
            let r = pdo_run(&mut node, &scenario, iterations);
            assert!(scenario != "rpdo_4_objects" || iterations == 0 || node.app().d == 0x0807);
            r
        }
        "rpdo_4_objects@zerocopy" | "sync_4_tpdos@zerocopy" => {
            let mut node = pdo_node::<ZeroCopyProcess>();
            let r = pdo_run(&mut node, &scenario, iterations);
            assert!(scenario != "rpdo_4_objects@zerocopy" || iterations == 0 || node.app().d == 0x0807);
            r
        }
        "expedited_download@zerocopy" => {
            let script = record(Multiplexer::new(0x2002, 0), Mode::Auto, Some(vec![1, 2, 3, 4]));
            let mut node = booted(ZeroCopyApp::default());
            let r = run(&mut node, &script, iterations);
            assert!(iterations == 0 || node.app().value == 0x0403_0201);
            r
        }
        "expedited_download@thousand" => {
            let script = record(Multiplexer::new(0x2002, 0), Mode::Auto, Some(vec![1, 2, 3, 4]));
            let mut node = booted(<thousand::Thousand as zerocopy::FromZeros>::new_zeroed());
            let r = run(&mut node, &script, iterations);
            assert!(iterations == 0 || node.app().v2 == 0x0403_0201);
            r
        }
        "expedited_download_quiet" => {
            let script = record(Multiplexer::new(0x2002, 0), Mode::Auto, Some(vec![1, 2, 3, 4]));
            let mut node = booted(Quiet::default());
            let r = run(&mut node, &script, iterations);
            assert!(iterations == 0 || node.app().value == 0x0403_0201);
            r
        }
        _ => {
            let script = match scenario.as_str() {
                "expedited_upload" => record(Multiplexer::new(0x1000, 0), Mode::Auto, None),
                "expedited_download" => record(Multiplexer::new(0x2002, 0), Mode::Auto, Some(vec![1, 2, 3, 4])),
                "segmented_upload" => record(Multiplexer::new(0x2004, 0), Mode::Auto, None),
                "block_download" => {
                    let data: Vec<u8> = (0..BLOCK_LEN).map(|i| (i * 31 + 7) as u8).collect();
                    record(Multiplexer::new(0x2005, 0), Mode::Block { crc: true, blksize: 127, pst: 0 }, Some(data))
                }
                other => {
                    eprintln!("unknown scenario {other:?}");
                    std::process::exit(2);
                }
            };
            run(&mut new_node(), &script, iterations)
        }
    };
    println!("{scenario}: {frames} frames, {sent} sent");
}
