//! The master's CiA 402 drive API against a drive on the simulated bus, in simulated time: a node built as
//! `examples/drive.rs` builds its own (canopen-cia402's `Drive` over a `SimAxis`, the default drive PDOs,
//! 2100h simulated fault), its cycle every 2 ms and at each RPDO, its set-point taken at each SYNC.

use std::time::Duration;

use canopen_cia402::{cycle_node, Drive, Mode, Motor, SimAxis, State};
use canopen_core::profile::NodeConfig;
use canopen_core::{Event, Node, NodeId, Sizes};
use canopen_master::drive::Cyclic;
use canopen_master::sim::{SimBus, SimNode};
use canopen_master::{Master, NmtCommand};
use canopen_od_derive::ObjectDictionary;

#[derive(ObjectDictionary, Debug)]
struct App {
    #[od(index = 0x2100, name = "Simulated fault", access = "rw", default = 0)]
    simulated_fault: u16,
    /// The axis (not in the dictionary).
    axis: SimAxis,
}

type DriveNode = Node<Drive<App>, Sizes<0, 32, 32, 4, 4>>;

const CONFIG: NodeConfig = NodeConfig {
    device_type: 0x0002_0192,
    rpdo: &canopen_cia402::pdo::RPDOS,
    tpdo: &canopen_cia402::pdo::TPDOS,
    ..NodeConfig::DEFAULT
};
const ID: u8 = 6;
const CYCLE_US: u32 = 2_000;

fn cycle(n: &mut DriveNode) {
    let code = n.app().app.simulated_fault;
    let mut axis = n.app().app.axis.clone();
    axis.fault = (code != 0).then_some(code);
    cycle_node(n, &mut axis, CYCLE_US);
    n.app_mut().app.axis = axis;
}

/// The drive on `bus`, its cycle task running.
fn spawn_drive(bus: &SimBus) -> (std::sync::Arc<SimNode<DriveNode>>, tokio::task::JoinHandle<()>) {
    let app = App { simulated_fault: 0, axis: SimAxis::new(-200_000, 200_000) };
    let node: DriveNode = Node::new(NodeId::new(ID).unwrap(), CONFIG, Drive::new(app));
    let sim = std::sync::Arc::new(bus.spawn_node_with(node, |n, e| match e {
        Event::Sync { .. } => {
            n.app_mut().sync();
            cycle(n);
        }
        Event::RpdoReceived { .. } | Event::ObjectWritten { .. } => cycle(n),
        _ => {}
    }));
    let s = sim.clone();
    let task = tokio::spawn(async move {
        let mut tick = tokio::time::interval(Duration::from_micros(u64::from(CYCLE_US)));
        loop {
            tick.tick().await;
            s.with(cycle);
        }
    });
    (sim, task)
}

#[tokio::test(start_paused = true)]
async fn enable_disable_quick_stop_fault_reset() {
    let bus = SimBus::new();
    let (sim, _task) = spawn_drive(&bus);
    let master = Master::new(bus.port());
    let d = master.drive(ID).unwrap();
    tokio::time::sleep(Duration::from_millis(10)).await;
    assert_eq!(d.state().await.unwrap(), State::SwitchOnDisabled);
    d.enable().await.unwrap();
    assert_eq!(d.state().await.unwrap(), State::OperationEnabled);
    for target in [State::SwitchedOn, State::ReadyToSwitchOn, State::OperationEnabled, State::SwitchOnDisabled] {
        d.go_to(target).await.unwrap();
        assert_eq!(d.state().await.unwrap(), target);
    }
    // Quick stop with the default option 2: on to Switch on disabled; with 6 it stays.
    d.enable().await.unwrap();
    assert_eq!(d.quick_stop().await.unwrap(), State::SwitchOnDisabled);
    master.write(ID, 0x605A, 0, 6i16).await.unwrap();
    d.enable().await.unwrap();
    assert_eq!(d.quick_stop().await.unwrap(), State::QuickStopActive);
    d.go_to(State::OperationEnabled).await.unwrap(); // transition 16
    d.disable().await.unwrap();
    // A fault: the walk to Operation enabled resets it once the cause is gone, not before.
    d.enable().await.unwrap();
    master.write(ID, 0x2100, 0, 0x2310u16).await.unwrap();
    d.wait_status(Duration::from_millis(100), |w| w & 0x4F == 0x08).await.unwrap();
    assert_eq!(master.read::<u16>(ID, 0x603F, 0).await.unwrap(), 0x2310);
    assert!(d.fault_reset().await.is_err());
    master.write(ID, 0x2100, 0, 0u16).await.unwrap();
    d.enable().await.unwrap();
    assert_eq!(master.read::<u16>(ID, 0x603F, 0).await.unwrap(), 0);
    assert!(d.go_to(State::Fault).await.is_err());
    assert!(sim.with(|n| n.app().app.axis.powered()));
}

#[tokio::test(start_paused = true)]
async fn modes_moves_velocity_homing_and_a_cyclic_stream() {
    let bus = SimBus::new();
    let (sim, _task) = spawn_drive(&bus);
    let master = Master::new(bus.port());
    let d = master.drive(ID).unwrap();
    tokio::time::sleep(Duration::from_millis(10)).await;
    assert!(master.write(ID, 0x6060, 0, 4i8).await.is_err(), "profile torque is refused");

    d.set_mode(Mode::Homing).await.unwrap();
    d.enable().await.unwrap();
    master.write(ID, 0x607C, 0, 500i32).await.unwrap();
    d.home(Some(37), Duration::from_secs(1)).await.unwrap();
    assert_eq!(master.read::<i32>(ID, 0x6064, 0).await.unwrap(), 500);
    master.write(ID, 0x6099, 1, 50_000u32).await.unwrap();
    master.write(ID, 0x607C, 0, 0i32).await.unwrap();
    d.home(Some(18), Duration::from_secs(10)).await.unwrap();
    assert!(master.read::<i32>(ID, 0x6064, 0).await.unwrap().abs() <= 10);
    // Home is where the positive switch (the hard stop at 200,000 raw) releases.
    assert!(sim.with(|n| n.app().app.axis.position()) > 199_900);

    d.set_mode(Mode::ProfilePosition).await.unwrap();
    let end = d.move_to(-20_000, false, Duration::from_secs(10)).await.unwrap();
    assert!((end + 20_000).abs() <= 10, "{end}");
    let end = d.move_to(5_000, true, Duration::from_secs(10)).await.unwrap();
    assert!((end + 15_000).abs() <= 10, "{end}");

    d.set_mode(Mode::ProfileVelocity).await.unwrap();
    d.velocity(3_000, Duration::from_secs(1)).await.unwrap();
    tokio::time::sleep(Duration::from_millis(100)).await;
    assert!((master.read::<i32>(ID, 0x606C, 0).await.unwrap() - 3_000).abs() <= 10);
    d.velocity(0, Duration::from_secs(1)).await.unwrap();

    // Cyclic synchronous position: RPDO3 + SYNC every 2 ms, 10 increments per period.
    master.nmt(ID, NmtCommand::Start).await.unwrap();
    master.write(ID, 0x60C2, 1, 2u8).await.unwrap(); // the interpolation period: the SYNC's 2 ms
    d.set_mode(Mode::CyclicSyncPosition).await.unwrap();
    let start = master.read::<i32>(ID, 0x6064, 0).await.unwrap();
    let points: Vec<i32> = (1..=200).map(|k| start + 10 * k).collect();
    assert_eq!(d.stream(Cyclic::Position, Duration::from_millis(2), points).await.unwrap(), 200);
    tokio::time::sleep(Duration::from_millis(50)).await;
    assert_eq!(master.read::<i32>(ID, 0x6062, 0).await.unwrap(), start + 2_000, "the demand is the last set-point");
    let actual = master.read::<i32>(ID, 0x6064, 0).await.unwrap();
    assert!((actual - (start + 2_000)).abs() <= 20, "{actual}");
    d.set_mode(Mode::CyclicSyncVelocity).await.unwrap();
    assert_eq!(d.stream(Cyclic::Velocity, Duration::from_millis(2), [-1_000; 100]).await.unwrap(), 100);
    assert_eq!(master.read::<i32>(ID, 0x606B, 0).await.unwrap(), -1_000);
    assert_eq!(d.state().await.unwrap(), State::OperationEnabled);
}
