//! SDO through a whole node on the in-memory bus: the communication profile and a derived application
//! dictionary merged (OD-12), served in the right NMT states (NMT-18), with side effects of written
//! communication objects applied at once (HB-04, HB-09), block upload paced by a small transmit queue, and
//! the server's time-out (SDO-31). Frames are written out byte for byte (SDO-12, SDO-17, SDO-24).

mod common;

use canopen::core::{
    node::Node,
    od::DomainBuf,
    od::VisibleString,
    profile::NodeConfig,
    sdo::client::{ClientError, ClientEvent, Mode, SdoClient, SliceData},
    sdo::SdoClientParams,
    wire::sdo::Multiplexer,
    Event, NmtState, NodeId, Sizes,
};
use canopen::ObjectDictionary;
use common::{events, frame, ms, sdo_transfer, Bus};

#[derive(ObjectDictionary, Default)]
#[od(crate = "canopen::core")]
struct App {
    #[od(index = 0x2000, access = "rw", default = 0)]
    byte: u8,
    #[od(index = 0x2001, access = "rw", min = -1000, max = 1000)]
    setpoint: i16,
    #[od(index = 0x2004, access = "rw")]
    text: VisibleString<32>,
    #[od(index = 0x2005, name = "Blob", domain)]
    blob: DomainBuf<4096>,
}

const CFG: NodeConfig = NodeConfig { device_type: 0x000F_0191, device_name: "sdo test node", ..NodeConfig::DEFAULT };

fn node(id: u8) -> Node<App, Sizes<4, 4, 32>> {
    Node::new(NodeId::new(id).unwrap(), CFG, App::default())
}

fn replies(bus: &mut Bus<Node<App, Sizes<4, 4, 32>>>) -> Vec<canopen::core::CanFrame> {
    bus.take_master_rx().into_iter().map(|s| s.frame).filter(|f| f.cob_id() & 0x780 == 0x580).collect()
}

/// Through the node: 1017h written by SDO takes effect at once (HB-04).
#[test]
fn heartbeat_time_written_by_sdo() {
    let mut bus = Bus::new(vec![node(9)]);
    bus.run_until(ms(0));
    bus.take_master_rx();
    bus.run_until(ms(50));
    bus.inject(frame("609 [8] 2B 17 10 00 64 00 00 00"));
    assert_eq!(replies(&mut bus), vec![frame("589 [8] 60 17 10 00 00 00 00 00")]);
    assert!(events(&mut bus.stations[0]).contains(&Event::ObjectWritten { index: 0x1017, sub: 0 }));
    bus.run_until(ms(400));
    let hb: Vec<u64> = bus.frames_on(0x709).into_iter().map(|(t, _)| t).collect();
    assert_eq!(hb, vec![0, 150, 250, 350]);
}

/// Heartbeat consumer entries through the node (HB-07..HB-09, ABORT-14) and a tutorial's wrong-length writes.
#[test]
fn consumer_heartbeat_written_by_sdo() {
    let mut bus = Bus::new(vec![node(9)]);
    bus.run_until(ms(0));
    bus.take_master_rx();
    for (req, rep) in [
        ("609 [8] 23 16 10 01 64 00 02 00", "589 [8] 60 16 10 01 00 00 00 00"),
        ("609 [8] 23 16 10 02 90 01 03 00", "589 [8] 60 16 10 02 00 00 00 00"),
        ("609 [8] 23 16 10 03 A0 0F 07 00", "589 [8] 60 16 10 03 00 00 00 00"),
        ("609 [8] 23 16 10 04 C8 00 02 00", "589 [8] 80 16 10 04 43 00 04 06"),
        ("609 [8] 23 16 10 01 00 00 00 00", "589 [8] 60 16 10 01 00 00 00 00"),
        // A vendor manual's example writes, which a conformant node refuses: sub 00h is const, 2Bh announces 2 of 4
        // bytes.
        ("609 [8] 2B 16 10 00 03 00 00 00", "589 [8] 80 16 10 00 02 00 01 06"),
        ("609 [8] 2B 16 10 02 90 01 03 00", "589 [8] 80 16 10 02 13 00 07 06"),
    ] {
        bus.inject(frame(req));
        assert_eq!(replies(&mut bus), vec![frame(rep)], "{req}");
    }
    // The write of entry 2 made the consumer watch node 3: its first heartbeat starts monitoring.
    events(&mut bus.stations[0]);
    bus.inject(frame("703 [1] 05"));
    assert_eq!(
        events(&mut bus.stations[0]),
        vec![Event::Heartbeat(canopen::core::heartbeat::ConsumerEvent::Started {
            node: 3,
            state: canopen::core::wire::error_control::StateCode::Operational
        })]
    );
}

/// NMT-18: no SDO in Stopped (no reply at all); served again in Pre-operational and Operational.
#[test]
fn sdo_only_in_pre_operational_and_operational() {
    let mut bus = Bus::new(vec![node(5)]);
    bus.run_until(ms(0));
    bus.take_master_rx();
    let upload = "605 [8] 40 00 10 00 00 00 00 00";
    let answer = frame("585 [8] 43 00 10 00 91 01 0F 00");
    bus.inject(frame(upload));
    assert_eq!(replies(&mut bus), vec![answer]);
    bus.inject(frame("000 [2] 02 05"));
    bus.inject(frame(upload));
    assert!(replies(&mut bus).is_empty());
    bus.inject(frame("000 [2] 01 05"));
    assert_eq!(bus.stations[0].state(), NmtState::Operational);
    bus.inject(frame(upload));
    assert_eq!(replies(&mut bus), vec![answer]);
    // A request to another node's server is not ours.
    bus.inject(frame("606 [8] 40 00 10 00 00 00 00 00"));
    assert!(replies(&mut bus).is_empty());
}

/// Every transfer kind through the node, application and communication objects alike; block upload of
/// 4 KiB through a 4-frame transmit queue proves the node pulls segments only when there is room.
#[test]
fn every_transfer_kind_through_the_node() {
    let mut bus = Bus::new(vec![node(5)]);
    bus.run_until(ms(0));
    let mut client = SdoClient::new(SdoClientParams::for_server(NodeId::new(5).unwrap()));
    let blob: Vec<u8> = (0..4096u32).map(|i| (i * 7 + i / 251) as u8).collect();
    let modes = [
        Mode::Segmented,
        Mode::Block { crc: true, blksize: 127, pst: 0 },
        Mode::Block { crc: false, blksize: 13, pst: 0 },
    ];
    for mode in modes {
        let mut out = blob.clone();
        client.start_download(bus.now, Multiplexer::new(0x2005, 0), blob.len(), mode).unwrap();
        let ev = sdo_transfer(&mut bus, &mut client, &mut SliceData::download(&mut out));
        assert_eq!(ev, ClientEvent::Done { len: 4096 }, "download {mode:?}");
        assert_eq!(bus.stations[0].app().blob.as_bytes(), &blob[..]);
        let mut back = vec![0u8; 4096];
        client.start_upload(bus.now, Multiplexer::new(0x2005, 0), mode).unwrap();
        let ev = sdo_transfer(&mut bus, &mut client, &mut SliceData::upload(&mut back));
        assert_eq!(ev, ClientEvent::Done { len: 4096 }, "upload {mode:?}");
        assert_eq!(back, blob);
    }
    assert_eq!(bus.stations[0].tx_dropped(), 0);
    // A string, and the device name from the communication profile (segmented upload).
    let mut text = *b"hello, canopen";
    client.start_download(bus.now, Multiplexer::new(0x2004, 0), text.len(), Mode::Auto).unwrap();
    assert_eq!(sdo_transfer(&mut bus, &mut client, &mut SliceData::download(&mut text)), ClientEvent::Done { len: 14 });
    assert_eq!(bus.stations[0].app().text.as_str(), "hello, canopen");
    let mut name = [0u8; 32];
    client.start_upload(bus.now, Multiplexer::new(0x1008, 0), Mode::Auto).unwrap();
    let ev = sdo_transfer(&mut bus, &mut client, &mut SliceData::upload(&mut name));
    assert_eq!(ev, ClientEvent::Done { len: 13 });
    assert_eq!(&name[..13], b"sdo test node");
    // Limits and access through the merged dictionary (ABORT-10, ABORT-22).
    let mut v = 2000i16.to_le_bytes();
    client.start_download(bus.now, Multiplexer::new(0x2001, 0), 2, Mode::Auto).unwrap();
    let ev = sdo_transfer(&mut bus, &mut client, &mut SliceData::download(&mut v));
    assert_eq!(ev, ClientEvent::Failed(ClientError::Server(0x0609_0031)));
    let mut v = [1, 0, 0, 0];
    client.start_download(bus.now, Multiplexer::new(0x1000, 0), 4, Mode::Auto).unwrap();
    let ev = sdo_transfer(&mut bus, &mut client, &mut SliceData::download(&mut v));
    assert_eq!(ev, ClientEvent::Failed(ClientError::Server(0x0601_0002)));
}

/// SDO-31, ABORT-02: a client that stops in the middle of a segmented download gets 0504 0000h after the
/// server's time-out, and the node reports the abort.
#[test]
fn server_timeout_aborts() {
    let mut bus = Bus::new(vec![node(5)]);
    bus.run_until(ms(0));
    bus.take_master_rx();
    bus.inject(frame("605 [8] 21 04 20 00 0E 00 00 00")); // segmented download of 14 bytes to 2004h
    assert_eq!(replies(&mut bus), vec![frame("585 [8] 60 04 20 00 00 00 00 00")]);
    events(&mut bus.stations[0]);
    bus.run_until(ms(5_000));
    assert_eq!(replies(&mut bus), vec![frame("585 [8] 80 04 20 00 00 00 04 05")]);
    assert!(events(&mut bus.stations[0]).contains(&Event::SdoAborted {
        index: 0x2004,
        sub: 0,
        code: 0x0504_0000,
        by_client: false
    }));
}

/// NMT-04: reset node brings application values back to their defaults; reset communication does not
/// touch them (NMT-05 restores only 1000h–1FFFh).
#[test]
fn reset_node_restores_application_defaults() {
    let mut bus = Bus::new(vec![node(5)]);
    bus.run_until(ms(0));
    bus.inject(frame("605 [8] 2F 00 20 00 2A 00 00 00")); // 2000h = 42
    bus.inject(frame("000 [2] 82 05")); // reset communication
    assert_eq!(bus.stations[0].app().byte, 42);
    bus.inject(frame("000 [2] 81 05")); // reset node
    assert_eq!(bus.stations[0].app().byte, 0);
}

/// A heartbeat that falls due while a block upload fills the transmit queue is queued, not dropped: block
/// upload segments never take the last `TX_RESERVE` slots (HB-03 under SDO load).
#[test]
fn block_upload_leaves_room_for_the_heartbeat() {
    let mut bus = Bus::new(vec![node(5)]);
    bus.run_until(ms(0));
    let mut client = SdoClient::new(SdoClientParams::for_server(NodeId::new(5).unwrap()));
    let mut blob: Vec<u8> = (0..4096u32).map(|i| i as u8).collect();
    client.start_download(bus.now, Multiplexer::new(0x2005, 0), blob.len(), Mode::Auto).unwrap();
    assert_eq!(
        sdo_transfer(&mut bus, &mut client, &mut SliceData::download(&mut blob)),
        ClientEvent::Done { len: 4096 }
    );
    bus.take_master_rx();
    // From here on the test is the driver, and it does not drain the queue while the sub-block goes out.
    let n = &mut bus.stations[0];
    let t = ms(100);
    n.set_heartbeat_time(t, 10);
    n.handle_frame(t, &frame("605 [8] A4 05 20 00 7F 00 00 00")); // block upload, CRC, blksize 127
    assert_eq!(n.poll_transmit(), Some(frame("585 [8] C6 05 20 00 00 10 00 00")));
    n.handle_frame(t, &frame("605 [8] A3 00 00 00 00 00 00 00")); // start: segments fill the queue
    n.handle_timeout(ms(110)); // the heartbeat falls due with the queue full of segments
    assert_eq!(n.tx_dropped(), 0);
    let mut heartbeat_seen = false;
    let mut segments = 0;
    while let Some(f) = n.poll_transmit() {
        match f.cob_id() {
            0x705 => heartbeat_seen = true,
            0x585 => segments += 1,
            other => panic!("unexpected frame on {other:03X}"),
        }
        if segments > 200 {
            break;
        }
    }
    assert!(heartbeat_seen);
    assert_eq!(segments, 127, "the whole first sub-block still goes out, paced by the queue");
}

/// An application that reads its values (or reacts in `on_write`) and says so with
/// `#[od(write_events = false)]`: SDO downloads of its entries queue no `Event::ObjectWritten`, expedited
/// (SDO-12) and segmented (SDO-19) alike, and the value is written all the same; a communication object
/// written is still reported (its side effects are the node's, HB-04).
#[test]
fn write_events_off_for_the_application() {
    #[derive(ObjectDictionary, Default)]
    #[od(crate = "canopen::core", write_events = false)]
    struct Quiet {
        #[od(index = 0x2000, access = "rw")]
        value: u32,
        #[od(index = 0x2004, access = "rw")]
        text: VisibleString<16>,
    }
    assert!(!canopen::core::od::ObjectDictionary::write_events(&Quiet::default()));
    assert!(canopen::core::od::ObjectDictionary::write_events(&App::default()));
    let node: Node<Quiet, Sizes<4, 4, 32>> = Node::new(NodeId::new(9).unwrap(), CFG, Quiet::default());
    let mut bus = Bus::new(vec![node]);
    bus.run_until(ms(0));
    bus.take_master_rx();
    events(&mut bus.stations[0]);
    bus.inject(frame("609 [8] 23 00 20 00 78 56 34 12"));
    bus.inject(frame("609 [8] 21 04 20 00 03 00 00 00")); // segmented download of 3 bytes
    bus.inject(frame("609 [8] 09 61 62 63 00 00 00 00"));
    let replies: Vec<_> = bus.take_master_rx().into_iter().map(|s| s.frame).filter(|f| f.cob_id() == 0x589).collect();
    assert_eq!(
        replies,
        vec![
            frame("589 [8] 60 00 20 00 00 00 00 00"),
            frame("589 [8] 60 04 20 00 00 00 00 00"),
            frame("589 [8] 20 00 00 00 00 00 00 00"),
        ]
    );
    assert_eq!(bus.stations[0].app().value, 0x1234_5678);
    assert_eq!(bus.stations[0].app().text.as_bytes(), b"abc");
    assert!(!events(&mut bus.stations[0]).iter().any(|e| matches!(e, Event::ObjectWritten { .. })));
    bus.inject(frame("609 [8] 2B 17 10 00 64 00 00 00"));
    assert!(events(&mut bus.stations[0]).contains(&Event::ObjectWritten { index: 0x1017, sub: 0 }));
}

/// SDO-31 in a block upload: the server's time-out runs from the last frame it sent, so a client that
/// acknowledges a sub-block within the time-out after its last segment arrived is in time. A runner that
/// takes a whole sub-block from the node at once and then needs long to send it (canopen-socketcan's pass
/// runners: one clock reading per pass, then every frame the node has; 127 segments take 1.3 s at
/// 10 kbit/s, and as long on a congested bus) tells the node the time only in its next pass, after the
/// last segment went out: the time-out starts there. Before, it ran from the instant the segments were taken
/// and such a pass aborted with 0504 0000h (a block upload in the vcan load test, CI9).
#[test]
fn block_upload_time_out_runs_from_the_pass_after_the_sub_block_went_out() {
    let mut n = node(5);
    n.app_mut().blob = DomainBuf::from_bytes(&[0x55; 1000]).unwrap(); // 143 segments: a full sub-block first
    n.handle_timeout(ms(0));
    while n.poll_transmit().is_some() {} // boot-up
    let take_all = |n: &mut Node<App, Sizes<4, 4, 32>>| std::iter::from_fn(|| n.poll_transmit()).collect::<Vec<_>>();
    n.handle_frame(ms(10), &frame("605 [8] A0 05 20 00 7F 00 00 00")); // initiate block upload, blksize 127
    assert_eq!(take_all(&mut n)[0].data()[0] & 0xE0, 0xC0);
    n.handle_frame(ms(20), &frame("605 [8] A3 00 00 00 00 00 00 00")); // start
    let sub_block = take_all(&mut n);
    assert_eq!(sub_block.len(), 127);
    assert_eq!(sub_block[126].data()[0], 0x7F);
    // 1.3 s later the runner has sent the last segment and runs its next pass; the client has not answered
    // yet (it acknowledges within the time-out after the last segment arrived).
    n.handle_timeout(ms(1_320));
    let after = take_all(&mut n);
    assert!(after.iter().all(|f| f.data()[0] != 0x80), "aborted in time: {after:?}");
    n.handle_frame(ms(1_400), &frame("605 [8] A2 7F 7F 00 00 00 00 00")); // acknowledge of all 127
    let next = take_all(&mut n);
    assert_eq!(next.first().map(|f| f.data()[0]), Some(0x01), "the next sub-block: {next:?}");
}
