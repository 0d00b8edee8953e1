//! Instruction-count workload for the whole node (DESIGN.md "Performance"): one `handle_frame` plus the
//! drain of `poll_transmit` per received frame, nothing else.
//!
//! `node_instructions <scenario> <iterations>` runs a scenario `iterations` times and prints how many frames
//! the node received; `scripts/bench-node.sh` runs it under callgrind with N and with 0 iterations and
//! divides the difference by the number of frames, so set-up and process start-up cancel out.
//!
//! The client's frames are recorded once with our SDO client before the measured part and then replayed, so
//! the client's own work is not counted. Scenarios: `expedited_upload` (1000h), `expedited_download` (a U32),
//! `segmented_upload` (a 64-byte VISIBLE_STRING), `block_download` (889·8 bytes with CRC into a DOMAIN).

use std::hint::black_box;

use canopen::core::{
    comm::NodeConfig,
    node::Node,
    od::{DomainBuf, VisibleString},
    sdo::client::{ClientEvent, Mode, SdoClient, SliceData},
    sdo::SdoClientParams,
    wire::sdo::Multiplexer,
    CanFrame, Instant, NodeId,
};
use canopen::ObjectDictionary;

const K: usize = 8;
const BLOCK_LEN: usize = 889 * K;

#[derive(ObjectDictionary, Default)]
#[od(crate = "canopen::core")]
struct App {
    #[od(index = 0x2002, access = "rw")]
    value: u32,
    #[od(index = 0x2004, access = "rw", default = "CANopen test string of exactly sixty-four bytes for SDO uploads.")]
    text: VisibleString<64>,
    #[od(index = 0x2005, domain)]
    blob: DomainBuf<BLOCK_LEN>,
}

type BenchNode = Node<App, 4, 16, 16>;

fn new_node() -> BenchNode {
    let app = App::default(); // power-on (Reset Application) gives every entry its `default =` value
    let cfg = NodeConfig { device_type: 0x000F_0191, ..NodeConfig::DEFAULT };
    let mut node = Node::new(NodeId::new(5).unwrap(), cfg, app);
    node.handle_timeout(Instant::ZERO);
    while node.poll_transmit().is_some() {}
    while node.poll_event().is_some() {}
    node
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
    let mut node = new_node();
    let mut frames = 0usize;
    let mut replies = 0usize;
    for _ in 0..iterations {
        for f in &script {
            node.handle_frame(Instant::ZERO, black_box(f));
            while let Some(out) = node.poll_transmit() {
                replies += black_box(out).dlc() as usize;
            }
            frames += 1;
        }
    }
    println!("{scenario}: {frames} frames, {replies} reply bytes");
}
