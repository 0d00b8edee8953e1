//! LSS (CiA 305) on the in-memory bus with simulated time: fastscan commissioning of several unconfigured
//! nodes, stored node-IDs across a power cycle, pending node-IDs at reset communication, bit timing, and a
//! property test of random 7E5h frames (never a panic, never an answer where the spec says silence).

mod common;

use std::cell::RefCell;
use std::rc::Rc;

use canopen::core::{
    lss::{
        master::{Commissioning, CommissioningEvent, LssMaster, MasterEvent},
        LssEvent, LssStore, StoreError,
    },
    node::{NoApplication, Node},
    profile::{Identity, NodeConfig},
    sdo::{
        client::{ClientEvent, Mode, SdoClient, SliceData},
        SdoClientParams,
    },
    wire::lss::{BitRate, IdentityField, LssMode, LssRequest, LssResponse, Status},
    wire::sdo::Multiplexer,
    CanFrame, Duration, Event, Instant, NmtState, NodeId, Sizes,
};
use common::{events, frame, ms, sdo_transfer, Bus, Sender, Station};
use proptest::prelude::*;

type TestNode = Node<NoApplication, Sizes<4, 32, 32>>;

const LSS_TIMEOUT: Duration = Duration::from_millis(20);

fn identity(serial: u32) -> Identity {
    Identity { vendor_id: 0x0000_0ABC, product_code: 0x0000_1001, revision: 0x0001_0000, serial }
}

fn config(serial: u32, heartbeat_ms: u16) -> NodeConfig {
    NodeConfig { identity: identity(serial), heartbeat_time_ms: heartbeat_ms, ..NodeConfig::DEFAULT }
}

/// The application's non-volatile memory, shared with the test so it survives "power cycles".
#[derive(Clone, Default)]
struct Flash(Rc<RefCell<Option<(u8, BitRate)>>>);

impl LssStore for Flash {
    fn store(&mut self, node_id: u8, bit_rate: BitRate) -> Result<(), StoreError> {
        *self.0.borrow_mut() = Some((node_id, bit_rate));
        Ok(())
    }
}

/// A storage whose medium fails.
struct Broken;

impl LssStore for Broken {
    fn store(&mut self, _: u8, _: BitRate) -> Result<(), StoreError> {
        Err(StoreError::MediaAccess)
    }
}

/// Powers a node up from what its flash holds (FFh when empty), as an application would.
fn power_up(serial: u32, heartbeat_ms: u16, flash: &Flash) -> TestNode {
    let raw = flash.0.borrow().map_or(0xFF, |(id, _)| id);
    let mut node = Node::from_raw_node_id(raw, config(serial, heartbeat_ms), NoApplication).expect("valid node-ID");
    node.lss_mut().set_store_supported(true);
    node
}

/// A master-side LSS state machine the test drives over the bus.
trait Master {
    type Ev;
    fn tx(&mut self, now: Instant) -> Option<[u8; 8]>;
    fn rx(&mut self, now: Instant, data: &[u8]) -> Option<Self::Ev>;
    fn deadline(&self) -> Option<Instant>;
    fn timeout(&mut self, now: Instant) -> Option<Self::Ev>;
}

impl Master for LssMaster {
    type Ev = MasterEvent;
    fn tx(&mut self, now: Instant) -> Option<[u8; 8]> {
        self.poll_transmit(now)
    }
    fn rx(&mut self, now: Instant, data: &[u8]) -> Option<MasterEvent> {
        self.handle_response(now, data)
    }
    fn deadline(&self) -> Option<Instant> {
        self.poll_timeout()
    }
    fn timeout(&mut self, now: Instant) -> Option<MasterEvent> {
        self.handle_timeout(now)
    }
}

impl Master for Commissioning {
    type Ev = CommissioningEvent;
    fn tx(&mut self, now: Instant) -> Option<[u8; 8]> {
        self.poll_transmit(now)
    }
    fn rx(&mut self, now: Instant, data: &[u8]) -> Option<CommissioningEvent> {
        self.handle_response(now, data)
    }
    fn deadline(&self) -> Option<Instant> {
        self.poll_timeout()
    }
    fn timeout(&mut self, now: Instant) -> Option<CommissioningEvent> {
        self.handle_timeout(now)
    }
}

/// Runs `m` on the bus until it reports an event. After every frame the master sends, each station's
/// application answers a pending store through its flash (as a runner calling `complete_lss_store` would).
fn drive<M: Master>(bus: &mut Bus<TestNode>, m: &mut M, flash: &mut [Flash]) -> M::Ev {
    for _ in 0..100_000 {
        let mut progressed = false;
        while let Some(f) = m.tx(bus.now) {
            progressed = true;
            bus.inject(CanFrame::new(0x7E5, &f).unwrap());
            for (node, fl) in bus.stations.iter_mut().zip(flash.iter_mut()) {
                node.complete_lss_store(fl);
            }
            let now = bus.now;
            bus.run_until(now);
        }
        for seen in bus.take_master_rx() {
            if seen.frame.cob_id() == 0x7E4 {
                progressed = true;
                if let Some(ev) = m.rx(bus.now, seen.frame.data()) {
                    return ev;
                }
            }
        }
        if !progressed {
            let t = m.deadline().expect("master waits for nothing");
            bus.run_until(t);
            if let Some(ev) = m.timeout(bus.now) {
                return ev;
            }
        }
    }
    panic!("LSS master did not finish");
}

fn upload_u32(bus: &mut Bus<TestNode>, node: u8, index: u16, sub: u8) -> Result<u32, ClientEvent> {
    let mut client = SdoClient::new(SdoClientParams::for_server(NodeId::new(node).unwrap()));
    let mut buf = [0u8; 4];
    client.start_upload(bus.now, Multiplexer::new(index, sub), Mode::Auto).unwrap();
    match sdo_transfer(bus, &mut client, &mut SliceData::upload(&mut buf)) {
        ClientEvent::Done { len: 4 } => Ok(u32::from_le_bytes(buf)),
        other => Err(other),
    }
}

fn lss_events(node: &mut TestNode) -> Vec<LssEvent> {
    events(node).into_iter().filter_map(|e| if let Event::Lss(l) = e { Some(l) } else { None }).collect()
}

/// Fastscan finds three unconfigured nodes with different serials, one after another, and gives each a
/// node-ID; each then boots (one boot-up frame) and answers SDO, and the stored node-IDs survive a power
/// cycle. LSS-12 (identify non-configured), LSS-13 (fastscan), LSS-15 (silent without a node-ID, boots once
/// it has one), LSS-05/06 (node-ID configured, active after the reset), LSS-09 (stored), LSS-16 (master).
#[test]
fn fastscan_commissions_three_nodes_which_boot_and_answer_sdo() {
    let serials = [0x0000_0300u32, 0x0000_0007, 0x0001_0000];
    let mut flash = vec![Flash::default(), Flash::default(), Flash::default()];
    let nodes = serials.iter().zip(&flash).map(|(&s, f)| power_up(s, 100, f)).collect();
    let mut bus = Bus::new(nodes);

    // Without a node-ID: silence (no boot-up, no heartbeat), and NMT/SDO are not served.
    bus.run_for_ms(1000);
    bus.inject(frame("000 [2] 01 00"));
    bus.inject(frame("67F [8] 40 18 10 04 00 00 00 00"));
    bus.run_for_ms(1000);
    assert!(bus.log.iter().all(|s| s.from == Sender::Master), "{:?}", bus.log);
    assert!(bus.stations.iter().all(|n| n.state() == NmtState::Initialising));

    // Identify non-configured: all three answer.
    let mut m = LssMaster::new(LSS_TIMEOUT);
    m.identify_non_configured().unwrap();
    assert_eq!(drive(&mut bus, &mut m, &mut flash), MasterEvent::NonConfigured(true));
    let answers = bus.log.iter().filter(|s| s.frame.cob_id() == 0x7E4).count();
    assert_eq!(answers, 3);

    let mut c = Commissioning::new(LSS_TIMEOUT, NodeId::new(0x20).unwrap(), true);
    let mut assigned = Vec::new();
    loop {
        match drive(&mut bus, &mut c, &mut flash) {
            CommissioningEvent::Assigned { identity, node_id } => assigned.push((identity.serial, node_id.get())),
            CommissioningEvent::Finished { assigned: n } => {
                assert_eq!(n, 3);
                break;
            }
            other => panic!("{other:?}"),
        }
    }
    // Fastscan decides a bit 0 whenever any node answers, so the lowest LSS address is found first.
    assert_eq!(assigned, vec![(0x7, 0x20), (0x300, 0x21), (0x1_0000, 0x22)]);
    let ids: Vec<_> = bus.stations.iter().map(|n| n.lss_node_id().map(NodeId::get)).collect();
    assert_eq!(ids, vec![Some(0x21), Some(0x20), Some(0x22)]);

    // Each booted exactly once, from the right station, into Pre-operational.
    for (station, id) in [(1usize, 0x20u16), (0, 0x21), (2, 0x22)] {
        let boots: Vec<_> = bus
            .log
            .iter()
            .filter(|s| s.frame.cob_id() == 0x700 + id && s.frame.data() == [0])
            .map(|s| s.from)
            .collect();
        assert_eq!(boots, vec![Sender::Station(station)], "boot-up of {id:X}");
        assert_eq!(bus.stations[station].state(), NmtState::PreOperational);
    }
    // Nothing on 7E4h other than LSS answers, nothing from a node before its boot-up.
    for s in &bus.log {
        if let Sender::Station(_) = s.from {
            let id = s.frame.cob_id();
            assert!(id == 0x7E4 || (0x720..=0x722).contains(&id), "{:?}", s.frame);
        }
    }

    // Each answers SDO with its own serial number (1018h:04) on its new node-ID.
    for (serial, id) in &assigned {
        assert_eq!(upload_u32(&mut bus, *id, 0x1018, 4), Ok(*serial));
    }
    // And a second fastscan finds nobody.
    let mut m = LssMaster::new(LSS_TIMEOUT);
    m.fastscan().unwrap();
    assert_eq!(drive(&mut bus, &mut m, &mut flash), MasterEvent::Fastscan(None));
    // Heartbeats run on the new IDs.
    bus.log.clear();
    bus.run_for_ms(250);
    assert_eq!(bus.frames_on(0x720).len(), 2);

    // The stored node-IDs survive a power cycle: recreate the nodes from their flash.
    let stored: Vec<_> = flash.iter().map(|f| f.0.borrow().map(|(id, _)| id)).collect();
    assert_eq!(stored, vec![Some(0x21), Some(0x20), Some(0x22)]);
    let nodes = serials.iter().zip(&flash).map(|(&s, f)| power_up(s, 0, f)).collect();
    let mut bus = Bus::new(nodes);
    bus.run_until(ms(0));
    let boot: Vec<_> = bus.log.iter().map(|s| s.frame).collect();
    assert_eq!(boot, vec![frame("721 [1] 00"), frame("720 [1] 00"), frame("722 [1] 00")]);
    for (serial, id) in &assigned {
        assert_eq!(upload_u32(&mut bus, *id, 0x1018, 4), Ok(*serial));
    }
}

/// A node-ID configured while the node has one stays pending until NMT reset communication; inquire
/// reports the active one; LSS is served in Stopped too. LSS-02, LSS-04 (switch selective), LSS-05 (80h
/// refused with 01h), LSS-06, LSS-09 (store not supported: 01h), LSS-10 (inquire node-ID).
#[test]
fn pending_node_id_takes_effect_at_reset_communication() {
    let mut flash = vec![Flash::default()];
    let mut bus = Bus::new(vec![TestNode::new(NodeId::new(5).unwrap(), config(42, 0), NoApplication)]);
    bus.run_until(ms(0));
    bus.inject(frame("000 [2] 02 05")); // Stopped: LSS still served
    let mut m = LssMaster::new(LSS_TIMEOUT);
    m.switch_selective(&identity(42)).unwrap();
    assert_eq!(drive(&mut bus, &mut m, &mut flash), MasterEvent::Selected);
    m.configure_node_id(9).unwrap();
    assert_eq!(drive(&mut bus, &mut m, &mut flash), MasterEvent::Configured(Status::SUCCESS));
    m.inquire_node_id().unwrap();
    assert_eq!(drive(&mut bus, &mut m, &mut flash), MasterEvent::NodeId(5));
    m.configure_node_id(0x80).unwrap();
    assert_eq!(drive(&mut bus, &mut m, &mut flash), MasterEvent::Configured(Status::NOT_SUPPORTED));
    // The store is not supported by this application: error 01h at once.
    m.store().unwrap();
    assert_eq!(drive(&mut bus, &mut m, &mut flash), MasterEvent::Configured(Status::NOT_SUPPORTED));
    m.switch_global(LssMode::Waiting).unwrap();
    bus.inject(CanFrame::new(0x7E5, &m.poll_transmit(bus.now).unwrap()).unwrap());
    // Still node 5, still Stopped, no boot-up.
    assert_eq!(bus.stations[0].lss_node_id(), NodeId::new(5));
    assert_eq!(bus.stations[0].state(), NmtState::Stopped);
    assert!(bus.frames_on(0x709).is_empty());
    bus.take_master_rx();
    bus.inject(frame("000 [2] 82 05"));
    let replies: Vec<_> = bus.take_master_rx().into_iter().map(|s| s.frame).collect();
    assert_eq!(replies, vec![frame("709 [1] 00")]);
    assert_eq!(bus.stations[0].lss_node_id(), NodeId::new(9));
    assert_eq!(upload_u32(&mut bus, 9, 0x1018, 4), Ok(42));
    // The old ID is gone.
    bus.inject(frame("000 [2] 01 05"));
    assert_eq!(bus.stations[0].state(), NmtState::PreOperational);
}

/// A configured node that is given FFh becomes unconfigured at reset node: no boot-up, LSS only.
/// LSS-03 (switch global), LSS-05/06 (FFh accepted, applied at the reset), LSS-12, LSS-15.
#[test]
fn configured_node_can_be_made_unconfigured() {
    let mut flash = vec![Flash::default()];
    let mut bus = Bus::new(vec![TestNode::new(NodeId::new(5).unwrap(), config(1, 50), NoApplication)]);
    bus.run_for_ms(100);
    let mut m = LssMaster::new(LSS_TIMEOUT);
    m.switch_global(LssMode::Configuration).unwrap();
    bus.inject(CanFrame::new(0x7E5, &m.poll_transmit(bus.now).unwrap()).unwrap());
    m.configure_node_id(0xFF).unwrap();
    assert_eq!(drive(&mut bus, &mut m, &mut flash), MasterEvent::Configured(Status::SUCCESS));
    bus.inject(frame("000 [2] 81 05"));
    bus.log.clear();
    bus.run_for_ms(1000);
    assert!(bus.log.is_empty(), "{:?}", bus.log);
    assert_eq!(bus.stations[0].state(), NmtState::Initialising);
    assert_eq!(bus.stations[0].lss_node_id(), None);
    m.identify_non_configured().unwrap();
    assert_eq!(drive(&mut bus, &mut m, &mut flash), MasterEvent::NonConfigured(true));
}

/// The async driver's path, `peek_transmit`, holds frames like `poll_transmit` from the bit-rate switch to the
/// end of the second switch delay (LSS-08: the node sends nothing meanwhile), and hands them out after it.
#[test]
fn peek_transmit_holds_frames_during_the_switch_delay_lss_08() {
    let mut node: TestNode = Node::new(NodeId::new(5).unwrap(), config(42, 10), NoApplication);
    node.handle_timeout(ms(0));
    while node.poll_transmit().is_some() {}
    // Switch state global to configuration (04h 01h), then activate bit timing with a 100 ms delay (15h).
    node.handle_frame(ms(0), &frame("7E5 [8] 04 01 00 00 00 00 00 00"));
    node.handle_frame(ms(0), &frame("7E5 [8] 15 64 00 00 00 00 00 00"));
    while node.poll_transmit().is_some() {}
    node.handle_timeout(ms(100)); // the switch: heartbeats fall due from here on
    node.handle_timeout(ms(150));
    assert!(node.lss().holds_transmit(ms(150)));
    assert_eq!(node.peek_transmit(), None, "a frame was handed out during the switch delay");
    assert_eq!(node.poll_transmit(), None);
    node.handle_timeout(ms(200)); // the end of the second delay
    let heartbeat = frame("705 [1] 7F");
    assert_eq!(node.peek_transmit(), Some(heartbeat));
    node.transmitted(&heartbeat);
}

/// Configure bit timing is answered 13h with 00h or 01h; activate bit timing is not answered, and is
/// reported with both instants; the node is silent from the switch to the end of the second delay.
/// LSS-07, LSS-08; LSS-01 (answers on 7E4h, 8 bytes); LSS-04.
#[test]
fn bit_timing_configure_and_activate() {
    let mut flash = vec![Flash::default()];
    let mut bus = Bus::new(vec![TestNode::new(NodeId::new(5).unwrap(), config(42, 10), NoApplication)]);
    bus.run_until(ms(0));
    bus.stations[0].lss_mut().set_supported_bit_rates(1 << 2 | 1 << 3 | 1 << 4);
    events(&mut bus.stations[0]);
    let mut m = LssMaster::new(LSS_TIMEOUT);
    m.switch_selective(&identity(42)).unwrap();
    assert_eq!(drive(&mut bus, &mut m, &mut flash), MasterEvent::Selected);
    m.configure_bit_timing(BitRate::K1000).unwrap();
    assert_eq!(drive(&mut bus, &mut m, &mut flash), MasterEvent::Configured(Status::NOT_SUPPORTED));
    m.configure_bit_timing(BitRate::K250).unwrap();
    assert_eq!(drive(&mut bus, &mut m, &mut flash), MasterEvent::Configured(Status::SUCCESS));
    let answers: Vec<_> = bus.log.iter().filter(|s| s.frame.cob_id() == 0x7E4).map(|s| s.frame).collect();
    assert_eq!(&answers[1..], &[frame("7E4 [8] 13 01 00 00 00 00 00 00"), frame("7E4 [8] 13 00 00 00 00 00 00 00")]);
    assert_eq!(
        lss_events(&mut bus.stations[0]),
        vec![LssEvent::ModeChanged(LssMode::Configuration), LssEvent::BitRateConfigured(BitRate::K250)]
    );

    bus.run_until(ms(1000));
    bus.log.clear();
    bus.take_master_rx();
    m.activate_bit_timing(100).unwrap();
    bus.inject(CanFrame::new(0x7E5, &m.poll_transmit(bus.now).unwrap()).unwrap());
    assert!(bus.take_master_rx().is_empty(), "activate bit timing is not answered");
    assert_eq!(
        lss_events(&mut bus.stations[0]),
        vec![LssEvent::BitRateActivation { bit_rate: BitRate::K250, switch_delay_ms: 100 }]
    );
    bus.run_until(ms(1100));
    assert_eq!(lss_events(&mut bus.stations[0]), vec![LssEvent::SwitchBitRate(BitRate::K250)]);
    assert_eq!(bus.stations[0].lss().bit_rate(), BitRate::K250);
    bus.run_until(ms(1199));
    assert_eq!(bus.stations[0].poll_timeout(), Some(ms(1200)));
    bus.run_until(ms(1200));
    assert_eq!(lss_events(&mut bus.stations[0]), vec![LssEvent::TransmitResumed]);
    bus.run_until(ms(1300));
    // Heartbeats every 10 ms until the switch (1100 included: due before the hold), none in between, then
    // the held ones leave at 1200 and the period goes on.
    let times: Vec<u64> = bus.frames_on(0x705).into_iter().map(|(t, _)| t).collect();
    assert!(times.iter().all(|&t| t <= 1100 || t >= 1200), "{times:?}");
    assert!(times.contains(&1090) && times.contains(&1210) && times.contains(&1300), "{times:?}");
}

/// The store answer waits for the application and carries its error (LSS-09: 02h); LSS-03, LSS-10
/// (inquire identity and node-ID in configuration), LSS-11 (identify remote slave, ranges inclusive).
#[test]
fn store_errors_are_reported() {
    let mut bus = Bus::new(vec![power_up(3, 0, &Flash::default())]);
    bus.run_until(ms(0));
    let mut m = LssMaster::new(LSS_TIMEOUT);
    m.switch_global(LssMode::Configuration).unwrap();
    bus.inject(CanFrame::new(0x7E5, &m.poll_transmit(bus.now).unwrap()).unwrap());
    m.store().unwrap();
    bus.inject(CanFrame::new(0x7E5, &m.poll_transmit(bus.now).unwrap()).unwrap());
    assert!(bus.take_master_rx().is_empty());
    assert_eq!(
        lss_events(&mut bus.stations[0]),
        vec![
            LssEvent::ModeChanged(LssMode::Configuration),
            LssEvent::StoreRequested { node_id: 0xFF, bit_rate: BitRate::K125 }
        ]
    );
    bus.stations[0].complete_lss_store(&mut Broken);
    bus.run_until(ms(0));
    let rx: Vec<_> = bus.take_master_rx().into_iter().map(|s| s.frame).collect();
    assert_eq!(rx, vec![frame("7E4 [8] 17 02 00 00 00 00 00 00")]);
    assert_eq!(m.handle_response(bus.now, rx[0].data()), Some(MasterEvent::Configured(Status::MEDIA_ACCESS)));
    // Inquiries in configuration state.
    for (f, v) in [(IdentityField::VendorId, 0xABC), (IdentityField::Serial, 3)] {
        m.inquire(f).unwrap();
        assert_eq!(drive(&mut bus, &mut m, &mut [Flash::default()]), MasterEvent::Identity(f, v));
    }
    m.inquire_node_id().unwrap();
    assert_eq!(drive(&mut bus, &mut m, &mut [Flash::default()]), MasterEvent::NodeId(0xFF));
    m.identify_remote(0xABC, 0x1001, 0..=0x0001_0000, 0..=2).unwrap();
    assert_eq!(drive(&mut bus, &mut m, &mut [Flash::default()]), MasterEvent::Identified(false));
    m.identify_remote(0xABC, 0x1001, 0..=0x0001_0000, 0..=3).unwrap();
    assert_eq!(drive(&mut bus, &mut m, &mut [Flash::default()]), MasterEvent::Identified(true));
}

// ---------------------------------------------------------------------------------------------------------
// Property test: random 7E5h frames.

#[derive(Debug, Clone)]
enum Input {
    Lss { data: Vec<u8>, rtr: bool },
    Nmt([u8; 2]),
    Store(bool),
    Wait(u64),
}

fn lss_input() -> impl Strategy<Value = Input> {
    let id = identity(0x55);
    let parts = vec![id.vendor_id, id.product_code, id.revision, id.serial, 0, u32::MAX, 7];
    let plausible = (
        prop::sample::select(vec![
            0x04u8, 0x11, 0x13, 0x15, 0x17, 0x40, 0x41, 0x42, 0x43, 0x46, 0x47, 0x48, 0x49, 0x4A, 0x4B, 0x4C, 0x51,
            0x5A, 0x5B, 0x5C, 0x5D, 0x5E, 0x44, 0x4F, 0x50,
        ]),
        prop::sample::select(parts),
        prop::sample::select(vec![0u8, 1, 2, 3, 5, 9, 0x22, 0x7F, 0x80, 0xFF]),
        prop::sample::select(vec![0u8, 1, 31, 0x80, 0x20]),
        0u8..=4,
        0u8..=4,
        any::<bool>(),
    )
        .prop_map(|(cs, value, b1, bit, sub, next, use_b1)| {
            let mut d = vec![cs];
            d.extend_from_slice(&value.to_le_bytes());
            if use_b1 {
                d[1] = b1;
            }
            d.extend_from_slice(&[bit, sub, next]);
            Input::Lss { data: d, rtr: false }
        });
    prop_oneof![
        4 => plausible,
        1 => (prop::collection::vec(any::<u8>(), 0..=8), any::<bool>()).prop_map(|(data, rtr)| Input::Lss { data, rtr }),
        1 => prop::sample::select(vec![[0x01u8, 0x00], [0x02, 0x00], [0x81, 0x00], [0x82, 0x00]]).prop_map(Input::Nmt),
        1 => any::<bool>().prop_map(Input::Store),
        1 => (0u64..300_000).prop_map(Input::Wait),
    ]
}

/// The command specifiers served only in LSS configuration.
fn config_only(cs: u8) -> bool {
    matches!(cs, 0x11 | 0x13 | 0x15 | 0x17 | 0x5A..=0x5E)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// LSS-14 (configuration services silent in waiting, malformed requests never answered), LSS-01 (one
    /// 8-byte answer on 7E4h per request), LSS-02, LSS-05 (11h answer), LSS-12/13 (4Ch and 51h only from an
    /// unconfigured node), LSS-15 (no other frame without a node-ID, boot-up first once it has one).
    #[test]
    fn random_lss_frames_never_panic_nor_answer_out_of_turn(
        inputs in prop::collection::vec(lss_input(), 1..300),
        configured in any::<bool>(),
    ) {
        let cfg = config(0x55, 20);
        let mut node: TestNode = if configured {
            Node::new(NodeId::new(5).unwrap(), cfg, NoApplication)
        } else {
            Node::new_unconfigured(cfg, NoApplication)
        };
        node.lss_mut().set_store_supported(true);
        let flash = Flash::default();
        let mut now = Instant::ZERO;
        node.handle_timeout(now);
        while node.poll_transmit().is_some() {}
        // While a bit-rate switch holds the transmit queue, answers leave later, at resume: they cannot be
        // matched to their request, so attribution pauses until the queue has been flushed outside a hold.
        let mut deferred = false;
        for inp in inputs {
            deferred |= node.lss().holds_transmit(now);
            let mode = node.lss().mode();
            let unconfigured = node.lss().is_unconfigured();
            let had_id = node.lss_node_id().is_some();
            let mut request = None;
            match &inp {
                Input::Lss { data, rtr } => {
                    let f = if *rtr { CanFrame::new_rtr(0x7E5, data.len() as u8) } else { CanFrame::new(0x7E5, data) };
                    if !*rtr {
                        request = Some(data.clone());
                    }
                    node.handle_frame(now, &f.unwrap());
                }
                Input::Nmt(d) => node.handle_frame(now, &CanFrame::new(0x000, d).unwrap()),
                Input::Store(ok) => {
                    if *ok { node.complete_lss_store(&mut flash.clone()) } else { node.complete_lss_store(&mut Broken) }
                }
                Input::Wait(us) => {
                    now = Instant::from_micros(now.as_micros() + us);
                    node.handle_timeout(now);
                }
            }
            let sent: Vec<CanFrame> = std::iter::from_fn(|| node.poll_transmit()).collect();
            if node.lss().holds_transmit(now) {
                prop_assert!(sent.is_empty(), "sent {:?} during the switch delay", sent);
                deferred = true;
            }
            if deferred {
                for f in sent.iter().filter(|f| f.cob_id() == 0x7E4) {
                    prop_assert!(LssResponse::parse(f.data()).is_ok());
                }
                deferred = node.lss().holds_transmit(now);
                continue;
            }
            let lss: Vec<&CanFrame> = sent.iter().filter(|f| f.cob_id() == 0x7E4).collect();
            for f in &sent {
                if f.cob_id() != 0x7E4 {
                    // Non-LSS traffic only from a node that has a node-ID (now).
                    prop_assert!(node.lss_node_id().is_some(), "{:?} from a node without node-ID", f);
                    prop_assert!(had_id || f.data() == [0], "first frame after getting an ID is the boot-up: {:?}", f);
                }
            }
            match (&inp, request) {
                (Input::Store(_), _) => {
                    for f in &lss {
                        prop_assert_eq!(f.data()[0], 0x17);
                    }
                }
                (_, Some(req)) => {
                    prop_assert!(lss.len() <= 1);
                    if let Some(f) = lss.first() {
                        prop_assert_eq!(req.len(), 8, "answer to a {}-byte frame", req.len());
                        prop_assert_eq!(f.dlc(), 8);
                        let resp = LssResponse::parse(f.data());
                        prop_assert!(resp.is_ok());
                        let resp = resp.unwrap();
                        let cs = req[0];
                        match resp.request_cs() {
                            Some(expected) => prop_assert_eq!(expected, cs),
                            None => prop_assert!(cs == 0x4B || cs == 0x51),
                        }
                        if config_only(cs) {
                            prop_assert_eq!(mode, LssMode::Configuration, "{:02X} answered in waiting", cs);
                        }
                        if cs == 0x43 {
                            prop_assert_eq!(mode, LssMode::Waiting);
                        }
                        if cs == 0x51 {
                            prop_assert!(mode == LssMode::Waiting && unconfigured, "fastscan answered");
                        }
                        if cs == 0x4C {
                            prop_assert!(unconfigured);
                        }
                        if cs == 0x11 {
                            let ok = matches!(req[1], 1..=127 | 0xFF);
                            prop_assert_eq!(resp, LssResponse::NodeIdConfigured(if ok { Status::SUCCESS } else { Status::NOT_SUPPORTED }));
                        }
                    }
                    if LssRequest::parse(&req).is_err() {
                        prop_assert!(lss.is_empty(), "answer to a malformed request {:02X?}", req);
                    }
                }
                _ => prop_assert!(lss.is_empty(), "LSS answer without a request: {:?}", lss),
            }
            if let Some(t) = node.poll_timeout() {
                if t <= now {
                    node.handle_timeout(now);
                }
            }
            // An unconfigured node never leaves Initialisation.
            if node.lss_node_id().is_none() {
                prop_assert_eq!(node.state(), NmtState::Initialising);
            }
        }
    }
}

#[test]
fn station_trait_is_implemented() {
    fn takes<S: Station>(_: &S) {}
    takes(&TestNode::new_unconfigured(NodeConfig::DEFAULT, NoApplication));
}
