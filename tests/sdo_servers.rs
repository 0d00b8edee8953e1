//! Additional SDO servers 1201h+ through a whole node (issue 17): the records 1201h/1202h configured by SDO
//! (SDO-54, SDO-55, COB-13..COB-16), a server serving only while both COB-IDs are valid, two segmented
//! transfers interleaved on 1200h and 1201h, the receive filters following the COB-IDs, reset
//! communication invalidating the records again. Every frame is written out byte for byte from CiA 301
//! §7.2.4.3 (SDO-11, SDO-17, SDO-19..SDO-27, SDO-32) and §7.5.2.33.

mod common;

use canopen::core::{
    cob::CobIdEntry,
    node::{Node, WithSdoServers},
    od::VisibleString,
    profile::NodeConfig,
    sdo::SdoServerParams,
    CanFrame, Event, Instant, NodeId, Sizes,
};
use canopen::ObjectDictionary;
use common::{events, frame, ms};

#[derive(ObjectDictionary, Default)]
#[od(crate = "canopen::core")]
struct App {
    #[od(index = 0x2000, access = "rw", default = 0)]
    byte: u8,
    #[od(index = 0x2004, access = "rw")]
    text: VisibleString<32>,
    #[od(index = 0x2005, access = "rw")]
    other: VisibleString<32>,
}

/// Default sizes (32 events) and two additional servers, 1201h and 1202h.
type Z = WithSdoServers<Sizes<4, 16, 32>, 2>;
type N = Node<App, Z>;

fn node() -> N {
    let mut n: N = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, App::default());
    n.handle_timeout(Instant::ZERO);
    while n.poll_transmit().is_some() {}
    events(&mut n);
    n
}

/// Feeds `request` (a frame in the `common::frame` notation) and returns the frames the node sent.
fn exchange(n: &mut N, t: u64, request: &str) -> Vec<CanFrame> {
    n.handle_frame(ms(t), &frame(request));
    core::iter::from_fn(|| n.poll_transmit()).collect()
}

fn accepts(n: &N, id: u16) -> bool {
    n.rx_filters().iter().any(|f| id & f.mask == f.id & f.mask)
}

/// Server 1201h on 6C5h (client → server) and 6D5h (server → client), written through the default server.
fn enable_1201(n: &mut N) {
    assert_eq!(exchange(n, 1, "605 [8] 23 01 12 02 D5 06 00 00"), vec![frame("585 [8] 60 01 12 02 00 00 00 00")]);
    assert_eq!(exchange(n, 1, "605 [8] 23 01 12 01 C5 06 00 00"), vec![frame("585 [8] 60 01 12 01 00 00 00 00")]);
}

/// SDO-53, SDO-54, OD-15 (every additional server has its record): 1200h reads 2 / 600h + node / 580h + node and is read-only; 1201h starts invalid
/// (8000_0000h), its sub 00h is 3 and const, sub 03h the client's node-ID; 1203h does not exist (two
/// additional servers only).
#[test]
fn records_read_as_the_spec_defines_them() {
    let mut n = node();
    assert_eq!(exchange(&mut n, 1, "605 [8] 40 00 12 00 00 00 00 00"), vec![frame("585 [8] 4F 00 12 00 02 00 00 00")]);
    assert_eq!(exchange(&mut n, 1, "605 [8] 40 00 12 01 00 00 00 00"), vec![frame("585 [8] 43 00 12 01 05 06 00 00")]);
    assert_eq!(exchange(&mut n, 1, "605 [8] 40 00 12 02 00 00 00 00"), vec![frame("585 [8] 43 00 12 02 85 05 00 00")]);
    // 0601 0002h: write to a read-only/const entry.
    assert_eq!(exchange(&mut n, 1, "605 [8] 23 00 12 01 06 06 00 00"), vec![frame("585 [8] 80 00 12 01 02 00 01 06")]);
    assert_eq!(exchange(&mut n, 1, "605 [8] 2F 01 12 00 03 00 00 00"), vec![frame("585 [8] 80 01 12 00 02 00 01 06")]);
    assert_eq!(exchange(&mut n, 1, "605 [8] 40 01 12 00 00 00 00 00"), vec![frame("585 [8] 4F 01 12 00 03 00 00 00")]);
    assert_eq!(exchange(&mut n, 1, "605 [8] 40 01 12 01 00 00 00 00"), vec![frame("585 [8] 43 01 12 01 00 00 00 80")]);
    assert_eq!(exchange(&mut n, 1, "605 [8] 40 02 12 02 00 00 00 00"), vec![frame("585 [8] 43 02 12 02 00 00 00 80")]);
    // Sub 03h, the client's node-ID: 0 until written, 01h-7Fh (0609 0032h / 0609 0031h); 1200h has none.
    assert_eq!(exchange(&mut n, 1, "605 [8] 40 01 12 03 00 00 00 00"), vec![frame("585 [8] 4F 01 12 03 00 00 00 00")]);
    assert_eq!(exchange(&mut n, 1, "605 [8] 2F 01 12 03 00 00 00 00"), vec![frame("585 [8] 80 01 12 03 32 00 09 06")]);
    assert_eq!(exchange(&mut n, 1, "605 [8] 2F 01 12 03 80 00 00 00"), vec![frame("585 [8] 80 01 12 03 31 00 09 06")]);
    assert_eq!(exchange(&mut n, 1, "605 [8] 2F 01 12 03 20 00 00 00"), vec![frame("585 [8] 60 01 12 03 00 00 00 00")]);
    assert_eq!(exchange(&mut n, 1, "605 [8] 40 01 12 03 00 00 00 00"), vec![frame("585 [8] 4F 01 12 03 20 00 00 00")]);
    assert_eq!(n.sdo_server_params(0).and_then(|p| p.client_node).map(|c| c.get()), Some(0x20));
    assert_eq!(exchange(&mut n, 1, "605 [8] 40 00 12 03 00 00 00 00"), vec![frame("585 [8] 80 00 12 03 11 00 09 06")]);
    // 0609 0011h: no sub 04h; 0602 0000h: no 1203h.
    assert_eq!(exchange(&mut n, 1, "605 [8] 40 01 12 04 00 00 00 00"), vec![frame("585 [8] 80 01 12 04 11 00 09 06")]);
    assert_eq!(exchange(&mut n, 1, "605 [8] 40 03 12 01 00 00 00 00"), vec![frame("585 [8] 80 03 12 01 00 00 02 06")]);
}

/// SDO-55: the server exists only while bit 31 is clear in both COB-IDs; until then a request on its
/// COB-ID is ignored (no reply on any ID), and the receive filters do not accept it.
#[test]
fn an_invalid_server_is_ignored() {
    let mut n = node();
    // Only sub 02h valid: still no server.
    assert_eq!(exchange(&mut n, 1, "605 [8] 23 01 12 02 D5 06 00 00"), vec![frame("585 [8] 60 01 12 02 00 00 00 00")]);
    assert!(exchange(&mut n, 2, "6C5 [8] 40 00 10 00 00 00 00 00").is_empty());
    assert!(!accepts(&n, 0x6C5));
    let generation = n.rx_filters_generation();
    assert_eq!(exchange(&mut n, 3, "605 [8] 23 01 12 01 C5 06 00 00"), vec![frame("585 [8] 60 01 12 01 00 00 00 00")]);
    assert_ne!(n.rx_filters_generation(), generation, "a runner must re-install its filters");
    assert!(accepts(&n, 0x6C5));
    assert!(!accepts(&n, 0x6D5), "the server's own responses are not received");
    // Now it serves: 1000h (device type) uploaded through 1201h, answered on 6D5h.
    let reply = exchange(&mut n, 4, "6C5 [8] 40 00 10 00 00 00 00 00");
    assert_eq!(reply.len(), 1);
    assert_eq!(reply[0].cob_id(), 0x6D5);
    assert_eq!(&reply[0].data()[..4], &[0x43, 0x00, 0x10, 0x00]);
    // Invalidated again (bit 31 set, same ID: allowed while valid, COB-16): ignored again. The response to
    // the write that disables the server still comes on its old ID.
    assert_eq!(exchange(&mut n, 5, "6C5 [8] 23 01 12 01 C5 06 00 80"), vec![frame("6D5 [8] 60 01 12 01 00 00 00 00")]);
    assert!(exchange(&mut n, 6, "6C5 [8] 40 00 10 00 00 00 00 00").is_empty());
    assert!(!accepts(&n, 0x6C5));
}

/// COB-16: the CAN-ID of a valid entry cannot change (0609 0030h); invalidate, change, re-validate works.
/// COB-15: the frame bit is refused; COB-14: bits 28–11 of an 11-bit entry are refused; COB-13: a
/// restricted CAN-ID is refused for a valid entry; SDO-18: a 2-byte write to the UNSIGNED32 is 0607 0013h.
#[test]
fn cob_id_changes_follow_the_rules() {
    let mut n = node();
    enable_1201(&mut n);
    let invalid_value = |m: &str| frame(&format!("585 [8] 80 01 12 {m} 30 00 09 06"));
    assert_eq!(exchange(&mut n, 2, "605 [8] 23 01 12 01 C6 06 00 00"), vec![invalid_value("01")]);
    assert_eq!(exchange(&mut n, 2, "605 [8] 23 01 12 02 D6 06 00 00"), vec![invalid_value("02")]);
    assert_eq!(exchange(&mut n, 2, "605 [8] 23 01 12 01 C5 06 00 20"), vec![invalid_value("01")]);
    assert_eq!(exchange(&mut n, 2, "605 [8] 23 01 12 01 C5 0E 00 00"), vec![invalid_value("01")]);
    assert_eq!(exchange(&mut n, 2, "605 [8] 2B 01 12 01 C5 06 00 00"), vec![frame("585 [8] 80 01 12 01 13 00 07 06")]);
    // The server still runs on its IDs.
    assert_eq!(exchange(&mut n, 3, "6C5 [8] 40 00 12 00 00 00 00 00"), vec![frame("6D5 [8] 4F 00 12 00 02 00 00 00")]);
    // Invalidate, change, re-validate.
    assert_eq!(exchange(&mut n, 4, "605 [8] 23 01 12 01 C5 06 00 80"), vec![frame("585 [8] 60 01 12 01 00 00 00 00")]);
    assert_eq!(exchange(&mut n, 4, "605 [8] 23 01 12 01 40 06 00 80"), vec![frame("585 [8] 60 01 12 01 00 00 00 00")]);
    // 640h is restricted (601h–67Fh, COB-13): refused while valid, accepted while invalid (above).
    assert_eq!(exchange(&mut n, 4, "605 [8] 23 01 12 01 40 06 00 00"), vec![invalid_value("01")]);
    assert_eq!(exchange(&mut n, 4, "605 [8] 23 01 12 01 C7 06 00 00"), vec![frame("585 [8] 60 01 12 01 00 00 00 00")]);
    assert!(exchange(&mut n, 5, "6C5 [8] 40 00 12 00 00 00 00 00").is_empty());
    assert_eq!(exchange(&mut n, 5, "6C7 [8] 40 00 12 00 00 00 00 00"), vec![frame("6D5 [8] 4F 00 12 00 02 00 00 00")]);
    // Bit 30 (dyn) is kept as written (the entry is invalid first, so its ID may change).
    assert_eq!(exchange(&mut n, 6, "605 [8] 23 01 12 02 D5 06 00 80"), vec![frame("585 [8] 60 01 12 02 00 00 00 00")]);
    assert_eq!(exchange(&mut n, 6, "605 [8] 23 01 12 02 D5 06 00 C0"), vec![frame("585 [8] 60 01 12 02 00 00 00 00")]);
    assert_eq!(exchange(&mut n, 6, "605 [8] 40 01 12 02 00 00 00 00"), vec![frame("585 [8] 43 01 12 02 D5 06 00 C0")]);
}

/// Two segmented transfers at once: a download of 2004h on 1200h and an upload of 2005h on 1201h,
/// segment by segment in turn (SDO-14, SDO-19..SDO-22, SDO-25..SDO-28); each server keeps its own toggle
/// and offset, and each completes.
#[test]
fn two_transfers_interleaved_on_1200h_and_1201h() {
    let mut n = node();
    enable_1201(&mut n);
    n.dictionary().app.other = VisibleString::from_str("0123456789").unwrap();
    // 1200h: initiate a segmented download of 10 bytes to 2004h; 1201h: initiate an upload of 2005h.
    assert_eq!(exchange(&mut n, 10, "605 [8] 21 04 20 00 0A 00 00 00"), vec![frame("585 [8] 60 04 20 00 00 00 00 00")]);
    assert_eq!(exchange(&mut n, 10, "6C5 [8] 40 05 20 00 00 00 00 00"), vec![frame("6D5 [8] 41 05 20 00 0A 00 00 00")]);
    // Segment 1 of each (t = 0): download "abcdefg", upload "0123456".
    assert_eq!(exchange(&mut n, 11, "605 [8] 00 61 62 63 64 65 66 67"), vec![frame("585 [8] 20 00 00 00 00 00 00 00")]);
    assert_eq!(exchange(&mut n, 11, "6C5 [8] 60 00 00 00 00 00 00 00"), vec![frame("6D5 [8] 00 30 31 32 33 34 35 36")]);
    // Segment 2 of each (t = 1, last): download "hij" (n = 4, c = 1), upload "789" (n = 4, c = 1).
    assert_eq!(exchange(&mut n, 12, "605 [8] 19 68 69 6A 00 00 00 00"), vec![frame("585 [8] 30 00 00 00 00 00 00 00")]);
    assert_eq!(exchange(&mut n, 12, "6C5 [8] 70 00 00 00 00 00 00 00"), vec![frame("6D5 [8] 19 37 38 39 00 00 00 00")]);
    assert_eq!(n.dictionary().app.text.as_str(), "abcdefghij");
    assert!(events(&mut n).contains(&Event::ObjectWritten { index: 0x2004, sub: 0 }));
}

/// SDO-31 per server: 1201h's transfer times out on its own COB-ID while 1200h's keeps running; NMT-05:
/// reset communication invalidates 1201h again.
#[test]
fn time_out_per_server_and_reset_communication() {
    let mut n = node();
    n.set_sdo_timeout(canopen::core::Duration::from_millis(100));
    enable_1201(&mut n);
    assert_eq!(exchange(&mut n, 10, "6C5 [8] 21 04 20 00 0A 00 00 00"), vec![frame("6D5 [8] 60 04 20 00 00 00 00 00")]);
    assert_eq!(exchange(&mut n, 60, "605 [8] 21 05 20 00 0A 00 00 00"), vec![frame("585 [8] 60 05 20 00 00 00 00 00")]);
    assert_eq!(n.poll_timeout(), Some(ms(110)));
    n.handle_timeout(ms(110));
    let sent: Vec<CanFrame> = core::iter::from_fn(|| n.poll_transmit()).collect();
    assert_eq!(sent, vec![frame("6D5 [8] 80 04 20 00 00 00 04 05")]); // 0504 0000h on 1201h only
    assert_eq!(exchange(&mut n, 70, "605 [8] 00 61 62 63 64 65 66 67"), vec![frame("585 [8] 20 00 00 00 00 00 00 00")]);
    // Reset communication (NMT 82h): 1201h invalid again.
    n.handle_frame(ms(80), &frame("000 [2] 82 05"));
    while n.poll_transmit().is_some() {}
    assert!(!accepts(&n, 0x6C5));
    assert!(exchange(&mut n, 81, "6C5 [8] 40 00 10 00 00 00 00 00").is_empty());
    assert_eq!(exchange(&mut n, 81, "605 [8] 40 01 12 01 00 00 00 00"), vec![frame("585 [8] 43 01 12 01 00 00 00 80")]);
}

/// NMT-18: a Stopped node ignores requests on every server.
#[test]
fn stopped_node_serves_no_server() {
    let mut n = node();
    enable_1201(&mut n);
    n.handle_frame(ms(2), &frame("000 [2] 02 05"));
    while n.poll_transmit().is_some() {}
    assert!(exchange(&mut n, 3, "6C5 [8] 40 00 10 00 00 00 00 00").is_empty());
}

/// SDO-57: 128 servers per device at most, and all of them usable: a node with 127 additional servers
/// (1201h–127Fh) configures and serves on the last one, 127Fh, and has no 1280h server record (1280h+ are
/// client records).
#[test]
fn the_128th_server_127fh_serves_sdo_57() {
    type Full = Node<App, WithSdoServers<Sizes<4, 16, 32>, 127>>;
    let mut n: Full = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, App::default());
    n.handle_timeout(Instant::ZERO);
    while n.poll_transmit().is_some() {}
    let mut ex = |req: &str| {
        n.handle_frame(ms(1), &frame(req));
        core::iter::from_fn(|| n.poll_transmit()).collect::<Vec<_>>()
    };
    assert_eq!(ex("605 [8] 23 7F 12 02 CF 06 00 00"), vec![frame("585 [8] 60 7F 12 02 00 00 00 00")]);
    assert_eq!(ex("605 [8] 23 7F 12 01 DF 06 00 00"), vec![frame("585 [8] 60 7F 12 01 00 00 00 00")]);
    assert_eq!(ex("6DF [8] 40 7F 12 01 00 00 00 00"), vec![frame("6CF [8] 43 7F 12 01 DF 06 00 00")]);
    assert_eq!(ex("605 [8] 40 80 12 00 00 00 00 00"), vec![frame("585 [8] 80 80 12 00 00 00 02 06")]);
}

/// SDO-56 (client records 1280h+) and COB-14..16: a node with two client records and no additional
/// server. 1280h reads sub 00h = 3, both COB-IDs 8000_0000h, sub 03h = 0; the node-ID is 01h–7Fh (0609
/// 0032h / 0609 0031h); a client may use a default server's IDs (603h/583h: the restricted set is about
/// the node's own objects); the ID of a valid entry cannot change; 1282h does not exist. The record, once
/// valid, gives the application's `SdoClient` its parameters, and that client reads 1000h from node 3.
#[cfg(feature = "sdo-client")]
#[test]
fn client_records_1280h_configure_an_sdo_client() {
    use canopen::core::sdo::{client::Mode, client::SliceData, SdoClient};
    use canopen::core::wire::sdo::Multiplexer;
    type C = Node<App, WithSdoServers<Sizes<4, 16, 32>, 0, 2>>;
    let mut n: C = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, App::default());
    n.handle_timeout(Instant::ZERO);
    while n.poll_transmit().is_some() {}
    let ex = |n: &mut C, req: &str| {
        n.handle_frame(ms(1), &frame(req));
        core::iter::from_fn(|| n.poll_transmit()).collect::<Vec<_>>()
    };
    assert_eq!(ex(&mut n, "605 [8] 40 80 12 00 00 00 00 00"), vec![frame("585 [8] 4F 80 12 00 03 00 00 00")]);
    assert_eq!(ex(&mut n, "605 [8] 40 81 12 02 00 00 00 00"), vec![frame("585 [8] 43 81 12 02 00 00 00 80")]);
    assert_eq!(ex(&mut n, "605 [8] 40 80 12 03 00 00 00 00"), vec![frame("585 [8] 4F 80 12 03 00 00 00 00")]);
    assert_eq!(ex(&mut n, "605 [8] 40 82 12 00 00 00 00 00"), vec![frame("585 [8] 80 82 12 00 00 00 02 06")]);
    assert_eq!(ex(&mut n, "605 [8] 2F 80 12 00 02 00 00 00"), vec![frame("585 [8] 80 80 12 00 02 00 01 06")]);
    assert_eq!(ex(&mut n, "605 [8] 2F 80 12 03 00 00 00 00"), vec![frame("585 [8] 80 80 12 03 32 00 09 06")]);
    assert_eq!(ex(&mut n, "605 [8] 2F 80 12 03 80 00 00 00"), vec![frame("585 [8] 80 80 12 03 31 00 09 06")]);
    assert_eq!(ex(&mut n, "605 [8] 23 80 12 01 03 06 00 20"), vec![frame("585 [8] 80 80 12 01 30 00 09 06")]);
    assert_eq!(ex(&mut n, "605 [8] 2F 80 12 03 03 00 00 00"), vec![frame("585 [8] 60 80 12 03 00 00 00 00")]);
    assert_eq!(ex(&mut n, "605 [8] 23 80 12 01 03 06 00 00"), vec![frame("585 [8] 60 80 12 01 00 00 00 00")]);
    assert_eq!(n.sdo_client_record(0).and_then(|r| r.client_params()), None, "sub 02h still invalid");
    assert_eq!(ex(&mut n, "605 [8] 23 80 12 02 83 05 00 00"), vec![frame("585 [8] 60 80 12 02 00 00 00 00")]);
    assert!(events(&mut n).contains(&Event::ObjectWritten { index: 0x1280, sub: 2 }));
    assert_eq!(ex(&mut n, "605 [8] 23 80 12 02 84 05 00 00"), vec![frame("585 [8] 80 80 12 02 30 00 09 06")]);
    let params = n.sdo_client_record(0).and_then(|r| r.client_params()).unwrap();
    assert_eq!((params.tx_cob_id(), params.rx_cob_id(), params.server_node), (0x603, 0x583, 3));

    // The application's client on those IDs reads 1000h:00 from node 3.
    let mut server: Node<App> = Node::new(NodeId::new(3).unwrap(), NodeConfig::DEFAULT, App::default());
    server.handle_timeout(Instant::ZERO);
    while server.poll_transmit().is_some() {}
    let mut client = SdoClient::new(params);
    let mut buf = [0u8; 4];
    let mut data = SliceData::upload(&mut buf);
    client.start_upload(ms(2), Multiplexer::new(0x1000, 0), Mode::Auto).unwrap();
    let req = client.poll_transmit(ms(2), &mut data).unwrap();
    server.handle_frame(ms(2), &CanFrame::new(params.tx_cob_id(), &req).unwrap());
    let reply = server.poll_transmit().unwrap();
    assert_eq!(reply.cob_id(), params.rx_cob_id());
    assert!(client.handle_response(ms(2), reply.data(), &mut data).is_some());
    assert_eq!(data.len(), 4);
    // Reset communication: the records are invalid again.
    n.handle_frame(ms(3), &frame("000 [2] 82 05"));
    n.handle_timeout(ms(3));
    assert_eq!(n.sdo_client_record(0), Some(canopen::core::node::SdoClientRecord::DISABLED));
}

/// SDO-55: invalidating server 1201h (through 1200h) while it runs a segmented download drops that
/// transfer without a frame; validating it again starts from idle (a segment is then 0504 0001h, as on
/// any idle server). The application's local setter does the same and moves the receive filters.
#[test]
fn invalidating_a_busy_server_drops_its_transfer() {
    let mut n = node();
    enable_1201(&mut n);
    assert_eq!(exchange(&mut n, 10, "6C5 [8] 21 04 20 00 0A 00 00 00"), vec![frame("6D5 [8] 60 04 20 00 00 00 00 00")]);
    assert_eq!(exchange(&mut n, 11, "605 [8] 23 01 12 01 C5 06 00 80"), vec![frame("585 [8] 60 01 12 01 00 00 00 00")]);
    assert!(exchange(&mut n, 12, "6C5 [8] 00 61 62 63 64 65 66 67").is_empty());
    assert_eq!(n.poll_timeout(), None, "no time-out left for the dropped transfer");
    assert_eq!(exchange(&mut n, 13, "605 [8] 23 01 12 01 C5 06 00 00"), vec![frame("585 [8] 60 01 12 01 00 00 00 00")]);
    assert_eq!(exchange(&mut n, 14, "6C5 [8] 00 61 62 63 64 65 66 67"), vec![frame("6D5 [8] 80 00 00 00 01 00 04 05")]);
    // Sub 03h (the client's node-ID) is information only: writing it keeps a transfer under way.
    assert_eq!(exchange(&mut n, 14, "6C5 [8] 21 04 20 00 0A 00 00 00"), vec![frame("6D5 [8] 60 04 20 00 00 00 00 00")]);
    assert_eq!(exchange(&mut n, 14, "605 [8] 2F 01 12 03 7F 00 00 00"), vec![frame("585 [8] 60 01 12 03 00 00 00 00")]);
    assert_eq!(exchange(&mut n, 14, "6C5 [8] 00 61 62 63 64 65 66 67"), vec![frame("6D5 [8] 20 00 00 00 00 00 00 00")]);

    // Locally: 1202h on 6C6h/6D6h, then off again.
    let on =
        SdoServerParams { cob_rx: CobIdEntry::from_raw(0x6C6), cob_tx: CobIdEntry::from_raw(0x6D6), client_node: None };
    let g = n.rx_filters_generation();
    assert!(n.set_sdo_server_params(1, on));
    assert_ne!(n.rx_filters_generation(), g);
    assert!(accepts(&n, 0x6C6));
    assert_eq!(n.sdo_server_params(1), Some(on));
    assert_eq!(exchange(&mut n, 15, "6C6 [8] 40 02 12 01 00 00 00 00"), vec![frame("6D6 [8] 43 02 12 01 C6 06 00 00")]);
    assert!(n.set_sdo_server_params(1, SdoServerParams::DISABLED));
    assert!(!accepts(&n, 0x6C6));
    assert!(exchange(&mut n, 16, "6C6 [8] 40 02 12 01 00 00 00 00").is_empty());
    assert!(!n.set_sdo_server_params(2, on), "two additional servers only");
}

/// The records in the node's EDS (OD-11, SDO-53, SDO-54, SDO-56; CiA 306 layout): 1200h–1202h and the
/// client records 1280h/1281h as RECORDs listed among the optional objects, each sub-entry with the type,
/// access and power-on value SDO reads (`records_read_as_the_spec_defines_them`); a node without
/// additional servers lists no 1200h (it does not serve it) and a node of plain `Sizes` no record at all.
#[test]
fn the_records_are_in_the_eds() {
    use canopen::core::profile::eds::{write_eds, EdsInfo};
    fn eds<Z: canopen::core::node::NodeSizes>() -> String {
        let n: Node<App, Z> = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, App::default());
        let mut s = String::new();
        write_eds(&mut s, &EdsInfo::DEFAULT, &n.describe()).unwrap();
        s
    }
    let s = eds::<WithSdoServers<Sizes<4, 16, 32>, 2, 2>>();
    let listed: Vec<&str> = s.lines().skip_while(|l| *l != "[OptionalObjects]").take_while(|l| !l.is_empty()).collect();
    for index in ["0x1200", "0x1201", "0x1202", "0x1280", "0x1281"] {
        assert!(listed.iter().any(|l| l.ends_with(&format!("={index}"))), "{index} not in {listed:?}");
    }
    assert!(!s.contains("[1203]") && !s.contains("[1282]"));
    let want = [
        "[1200]\nParameterName=SDO server parameter\nObjectType=0x9\nSubNumber=0x3\n\n",
        "[1200sub0]\nParameterName=Highest sub-index supported\nObjectType=0x7\nDataType=0x0005\nAccessType=const\nDefaultValue=0x2\nPDOMapping=0\n\n",
        "[1200sub1]\nParameterName=COB-ID client to server (rx)\nObjectType=0x7\nDataType=0x0007\nAccessType=const\nDefaultValue=$NODEID+0x600\nPDOMapping=0\n\n",
        "[1200sub2]\nParameterName=COB-ID server to client (tx)\nObjectType=0x7\nDataType=0x0007\nAccessType=ro\nDefaultValue=$NODEID+0x580\nPDOMapping=0\n\n",
        "[1202]\nParameterName=SDO server parameter\nObjectType=0x9\nSubNumber=0x4\n\n",
        "[1202sub0]\nParameterName=Highest sub-index supported\nObjectType=0x7\nDataType=0x0005\nAccessType=const\nDefaultValue=0x3\nPDOMapping=0\n\n",
        "[1202sub1]\nParameterName=COB-ID client to server (rx)\nObjectType=0x7\nDataType=0x0007\nAccessType=rw\nDefaultValue=0x80000000\nPDOMapping=0\n\n",
        "[1202sub2]\nParameterName=COB-ID server to client (tx)\nObjectType=0x7\nDataType=0x0007\nAccessType=rw\nDefaultValue=0x80000000\nPDOMapping=0\n\n",
        "[1202sub3]\nParameterName=Node-ID of the SDO client\nObjectType=0x7\nDataType=0x0005\nAccessType=rw\nDefaultValue=0x0\nPDOMapping=0\n\n",
        "[1281]\nParameterName=SDO client parameter\nObjectType=0x9\nSubNumber=0x4\n\n",
        "[1281sub1]\nParameterName=COB-ID client to server (tx)\nObjectType=0x7\nDataType=0x0007\nAccessType=rw\nDefaultValue=0x80000000\nPDOMapping=0\n\n",
        "[1281sub2]\nParameterName=COB-ID server to client (rx)\nObjectType=0x7\nDataType=0x0007\nAccessType=rw\nDefaultValue=0x80000000\nPDOMapping=0\n\n",
        "[1281sub3]\nParameterName=Node-ID of the SDO server\nObjectType=0x7\nDataType=0x0005\nAccessType=rw\nDefaultValue=0x0\nPDOMapping=0\n\n",
    ];
    for section in want {
        assert!(s.contains(section), "missing:\n{section}");
    }
    // The records come in index order: after 1029h, before the PDO parameters 1400h.
    let at = |x: &str| s.find(x).unwrap_or_else(|| panic!("{x}"));
    assert!(at("[1029]") < at("[1200]") && at("[1202sub3]") < at("[1280]") && at("[1281sub3]") < at("[1400]"));

    let clients_only = eds::<WithSdoServers<Sizes<4, 16, 32>, 0, 1>>();
    assert!(clients_only.contains("[1280]\n") && !clients_only.contains("[1200]") && !clients_only.contains("[1281]"));
    let plain = eds::<Sizes<4, 16, 32>>();
    assert!(!plain.contains("[12"), "no SDO record without WithSdoServers");
}

/// SDO-56, CAN-02: the application's SDO client on a 1280h record hears its server. While the record is
/// valid its server → client COB-ID is in the node's receive filters (a runner that installs them on the
/// socket passes the responses); invalid (power-on, sub 02h bit 31 set, reset communication), it is not.
/// Every change moves the filters' generation, the SDO write and the local setter alike.
#[test]
fn client_responses_pass_the_receive_filters() {
    type C = Node<App, WithSdoServers<Sizes<4, 16, 32>, 0, 1>>;
    let mut n: C = Node::new(NodeId::new(5).unwrap(), NodeConfig::DEFAULT, App::default());
    n.handle_timeout(Instant::ZERO);
    while n.poll_transmit().is_some() {}
    let accepts = |n: &C, id: u16| n.rx_filters().iter().any(|f| id & f.mask == f.id & f.mask);
    let ex = |n: &mut C, req: &str| {
        n.handle_frame(ms(1), &frame(req));
        core::iter::from_fn(|| n.poll_transmit()).collect::<Vec<_>>()
    };
    assert!(!accepts(&n, 0x583), "power-on: 1280h invalid");
    assert_eq!(ex(&mut n, "605 [8] 23 80 12 01 03 06 00 00"), vec![frame("585 [8] 60 80 12 01 00 00 00 00")]);
    assert!(!accepts(&n, 0x583), "sub 02h still invalid");
    let g = n.rx_filters_generation();
    assert_eq!(ex(&mut n, "605 [8] 23 80 12 02 83 05 00 00"), vec![frame("585 [8] 60 80 12 02 00 00 00 00")]);
    assert_ne!(n.rx_filters_generation(), g);
    assert!(accepts(&n, 0x583));
    assert!(!accepts(&n, 0x603), "the client sends on sub 01h, it does not receive it");
    assert_eq!(ex(&mut n, "605 [8] 23 80 12 02 83 05 00 80"), vec![frame("585 [8] 60 80 12 02 00 00 00 00")]);
    assert!(!accepts(&n, 0x583), "invalidated");

    // Locally, on 6E0h/6F0h: the generation moves, the filter follows.
    let record = canopen::core::node::SdoClientRecord {
        cob_tx: CobIdEntry::from_raw(0x6E0),
        cob_rx: CobIdEntry::from_raw(0x6F0),
        server_node: 0x10,
    };
    let g = n.rx_filters_generation();
    assert!(n.set_sdo_client_record(0, record));
    assert_ne!(n.rx_filters_generation(), g);
    assert!(accepts(&n, 0x6F0));
    n.handle_frame(ms(2), &frame("000 [2] 82 05")); // reset communication
    n.handle_timeout(ms(2));
    assert!(!accepts(&n, 0x6F0));
}
