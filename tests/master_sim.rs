//! `canopen-master` against the example node's dictionary (`examples/common/io_module.rs`) on the in-memory
//! bus, in simulated time: every SDO mode with a 64 KiB DOMAIN, typed values with negatives and strings,
//! abort codes with their meaning, DOMAIN streaming, PDO remapping with a SYNC producer, EMCY.

#[path = "../examples/common/io_module.rs"]
mod io_module;

use std::time::Duration;

use canopen_core::NodeId;
use canopen_master::pdo::{MapEntry, Pdo, PdoConfig};
use canopen_master::sim::{SimBus, SimNode};
use canopen_master::{Error, Master, Mode, NmtCommand, StateCode, BLOCK};
use io_module::{IoNode, CONFIG};

fn spawn(bus: &SimBus, id: u8) -> SimNode<IoNode> {
    bus.spawn_node(io_module::new_node(NodeId::new(id).unwrap(), CONFIG))
}

fn pattern(len: usize, seed: u32) -> Vec<u8> {
    (0..len as u32).map(|i| (i.wrapping_mul(2_654_435_761).wrapping_add(seed) >> 13) as u8).collect()
}

/// 64 KiB through the 2005h DOMAIN in every mode, byte-exact: segmented (SDO-12..SDO-34), block with and
/// without CRC (SDO-35..SDO-51), and streamed from a reader / into a writer with progress.
#[tokio::test(start_paused = true)]
async fn a_64_kib_domain_moves_in_every_mode() {
    let bus = SimBus::new();
    let node = spawn(&bus, 5);
    let m = Master::new(bus.port());
    for (i, mode) in [Mode::Segmented, BLOCK, Mode::Block { crc: false, blksize: 64, pst: 0 }].into_iter().enumerate() {
        let data = pattern(65_536, i as u32);
        m.download(5, 0x2005, 0, &data, mode).await.unwrap();
        assert_eq!(node.with(|n| n.app().data_block.as_bytes().to_vec()), data, "{mode:?}");
        assert_eq!(m.upload(5, 0x2005, 0, mode).await.unwrap(), data, "{mode:?}");
    }
    let data = pattern(40_000, 9);
    let (mut seen_down, mut seen_up) = (0, 0);
    let mut source = &data[..];
    m.download_from(5, 0x2005, 0, BLOCK, &mut source, data.len() as u64, Some(&mut |n| seen_down = n)).await.unwrap();
    let mut out = Vec::new();
    let len = m.upload_to(5, 0x2005, 0, BLOCK, &mut out, Some(&mut |n| seen_up = n)).await.unwrap();
    assert_eq!((len, seen_down, seen_up), (40_000, 40_000, 40_000));
    assert_eq!(out, data);
}

/// A source that ends early aborts the download (the node keeps its old content) and is reported as the
/// I/O error it is; more than the DOMAIN holds is the node's abort 0607 0012h with its meaning.
#[tokio::test(start_paused = true)]
async fn a_failing_source_or_an_oversized_value_aborts() {
    let bus = SimBus::new();
    let node = spawn(&bus, 5);
    let m = Master::new(bus.port());
    m.download(5, 0x2005, 0, &[7; 100], BLOCK).await.unwrap();
    let mut short: &[u8] = &[1; 1000];
    let e = m.download_from(5, 0x2005, 0, BLOCK, &mut short, 5000, None).await.unwrap_err();
    assert!(matches!(&e, Error::Io(io) if io.kind() == std::io::ErrorKind::UnexpectedEof), "{e}");
    assert_eq!(node.with(|n| n.app().data_block.as_bytes().to_vec()), vec![7; 100]);
    let e = m.download(5, 0x2005, 0, &vec![0; 65_537], BLOCK).await.unwrap_err();
    assert_eq!(e.abort_code(), Some(0x0607_0012));
    assert!(e.to_string().contains("length of service parameter too high"), "{e}");
    // And the node is ready for the next transfer.
    assert_eq!(m.upload(5, 0x2005, 0, Mode::Auto).await.unwrap(), vec![7; 100]);
}

/// Typed values: negatives, REAL32, UNSIGNED64, strings; the node's limits come back as their abort codes
/// (0609 0031h above the maximum, ABORT-22), and a wrong type is a type mismatch, not a wrong value.
#[tokio::test(start_paused = true)]
async fn typed_values_negatives_strings_and_limits() {
    let bus = SimBus::new();
    let _node = spawn(&bus, 5);
    let m = Master::new(bus.port());
    m.write(5, 0x2001, 0, -1000i16).await.unwrap();
    assert_eq!(m.read::<i16>(5, 0x2001, 0).await.unwrap(), -1000);
    let e = m.write(5, 0x2001, 0, 1001i16).await.unwrap_err();
    assert_eq!(e.abort_code(), Some(0x0609_0031));
    assert_eq!(
        e.to_string(),
        "SDO aborted by the server: 0609 0031h: value of parameter written too high (download only)"
    );
    assert_eq!(m.read::<f32>(5, 0x2003, 0).await.unwrap(), 1.5);
    m.write(5, 0x2003, 0, -0.25f32).await.unwrap();
    assert_eq!(m.read::<f32>(5, 0x2003, 0).await.unwrap(), -0.25);
    assert_eq!(m.read::<String>(5, 0x2004, 0).await.unwrap(), "io module");
    m.write(5, 0x2004, 0, "a label of 30 characters, ok.".to_string()).await.unwrap();
    assert_eq!(m.read::<String>(5, 0x2004, 0).await.unwrap(), "a label of 30 characters, ok.");
    let _uptime: u64 = m.read(5, 0x2006, 0).await.unwrap();
    assert!(matches!(m.read::<u32>(5, 0x2001, 0).await, Err(Error::TypeMismatch { expected: 4, got: 2 })));
    assert_eq!(m.read::<u32>(5, 0x2002, 0).await.unwrap(), 0x1234_5678);
}

/// PDO-35 through the master: TPDO1 remapped to 6401h:01 (16 bits) + 6000h:03 (8 bits), synchronous type 1;
/// with the master's SYNC producer running and the node Operational, every SYNC brings a TPDO with the new
/// mapping (PDO-20, PDO-32).
#[tokio::test(start_paused = true)]
async fn a_remapped_tpdo_follows_the_masters_sync() {
    let bus = SimBus::new();
    let node = spawn(&bus, 5);
    let m = Master::new(bus.port());
    // After the boot (its Reset Application sets the process values to their defaults).
    m.wait_for_state(5, StateCode::BootUp, Duration::from_secs(1)).await.unwrap();
    node.with(|n| {
        n.app_mut().analog_inputs[0] = -2;
        n.app_mut().digital_inputs[2] = 0x5A;
    });
    let map = [MapEntry { index: 0x6401, sub: 1, bits: 16 }, MapEntry { index: 0x6000, sub: 3, bits: 8 }];
    m.configure_pdo(5, Pdo::Tpdo(1), &PdoConfig { transmission_type: Some(1), ..PdoConfig::mapping(&map) })
        .await
        .unwrap();
    assert_eq!(m.read::<u32>(5, 0x1A00, 1).await.unwrap(), 0x6401_0110);
    assert_eq!(m.read::<u32>(5, 0x1800, 1).await.unwrap() & 0x8000_07FF, 0x185);
    let mut frames = m.frames();
    m.nmt(5, NmtCommand::Start).await.unwrap();
    let _sync = m.start_sync(Duration::from_millis(10), 0).unwrap();
    let mut tpdos = 0;
    let until = tokio::time::Instant::now() + Duration::from_millis(55);
    while let Ok(Ok(f)) = tokio::time::timeout_at(until, frames.recv()).await {
        if f.cob_id() == 0x185 {
            assert_eq!(f.data(), &[0xFE, 0xFF, 0x5A]);
            tpdos += 1;
        }
    }
    assert!((5..=6).contains(&tpdos), "{tpdos} TPDOs for 5 SYNCs");
}

/// EMCY-04 and the heartbeat stream: an error the node raises reaches the master's EMCY stream with the
/// node-ID, code and error register.
#[tokio::test(start_paused = true)]
async fn emergencies_reach_the_stream() {
    let bus = SimBus::new();
    let node = spawn(&bus, 5);
    let m = Master::new(bus.port());
    let mut emcy = m.emergencies();
    m.wait_for_state(5, StateCode::PreOperational, Duration::from_secs(2)).await.unwrap();
    node.with(|n| n.raise_error(0x1234, [1, 2, 3, 4, 5]));
    let e = tokio::time::timeout(Duration::from_millis(100), emcy.recv()).await.unwrap().unwrap();
    assert_eq!((e.node, e.emergency.code, e.emergency.manufacturer), (5, 0x1234, [1, 2, 3, 4, 5]));
    assert_ne!(e.emergency.register, 0);
}

/// EDS import (CiA 306) of the EDS the example node writes: every object the node serves is described with
/// its type, access, limits, default and PDO mapping, and every entry it describes is readable from the
/// running node with the size its type has.
#[tokio::test(start_paused = true)]
async fn the_example_nodes_eds_describes_what_the_node_serves() {
    use canopen_master::eds::{Access, Eds, ObjectKind};
    let eds = Eds::parse(&io_module::eds_text(CONFIG, false)).unwrap();
    let setpoint = eds.entry(0x2001, 0).unwrap();
    assert_eq!((setpoint.name.as_str(), setpoint.data_type, setpoint.access), ("Setpoint", 0x0003, Access::ReadWrite));
    assert_eq!((setpoint.low.as_deref(), setpoint.high.as_deref()), (Some("-1000"), Some("1000")));
    let inputs = &eds.objects[&0x6000];
    assert_eq!((inputs.kind, inputs.entries.len()), (ObjectKind::Array, 9));
    assert!(inputs.entries[&1].pdo_mapping && !eds.entry(0x2001, 0).unwrap().pdo_mapping);
    assert_eq!(eds.find("Identity object.Serial number"), Some((0x1018, Some(4))));

    let bus = SimBus::new();
    let _node = spawn(&bus, 5);
    let m = Master::new(bus.port());
    let sizes =
        [(0x0001, 1), (0x0002, 1), (0x0003, 2), (0x0004, 4), (0x0005, 1), (0x0006, 2), (0x0007, 4), (0x0008, 4)];
    let mut read = 0;
    for e in eds.entries().filter(|e| e.access.readable()) {
        let bytes = match m.upload(5, e.index, e.sub, Mode::Auto).await {
            Ok(b) => b,
            // An empty error history has no entries to read (ABORT-31).
            Err(err) if e.index == 0x1003 && err.abort_code() == Some(0x0800_0024) => continue,
            Err(err) => panic!("{:04X}h:{:02X}: {err}", e.index, e.sub),
        };
        if let Some((_, size)) = sizes.iter().find(|(t, _)| *t == e.data_type) {
            assert_eq!(bytes.len(), *size, "{:04X}h:{:02X} {}", e.index, e.sub, e.name);
        }
        read += 1;
    }
    assert!(read > 60, "only {read} entries");
}
