//! The drive against a simulated axis: every transition of the standard's table reached through the
//! controlword (and faults), the option codes' ramps, the modes, the refusals, and properties over random
//! controlword sequences.

use std::collections::BTreeSet;

use canopen_cia402::{Drive, Homing, Mode, Motor, SimAxis, State, Transition, TABLE};
use canopen_core::od::{AbortCode, NoApplication, ObjectDictionary};
use proptest::prelude::*;

const DT: u32 = 1000;

struct Bench {
    drive: Drive<NoApplication>,
    axis: SimAxis,
    seen: Vec<Transition>,
}

impl Bench {
    fn new() -> Self {
        let mut b = Bench { drive: Drive::new(NoApplication), axis: SimAxis::new(-1_000_000, 1_000_000), seen: vec![] };
        b.run(1);
        assert_eq!(b.state(), State::SwitchOnDisabled);
        b
    }
    fn run(&mut self, cycles: usize) {
        for _ in 0..cycles {
            let c = self.drive.cycle(&mut self.axis, DT);
            self.seen.extend(c.transitions());
        }
    }
    /// Writes the controlword as a master does and runs one cycle.
    fn cw(&mut self, word: u16) {
        self.drive.objects.write_controlword(word);
        self.run(1);
    }
    fn state(&self) -> State {
        self.drive.state()
    }
    fn sw(&self) -> u16 {
        self.drive.objects.statusword
    }
    fn write(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), AbortCode> {
        self.drive.write(index, sub, data)
    }
    fn enable(&mut self, mode: Mode) {
        self.drive.objects.modes_of_operation = mode.code();
        for w in [0x06, 0x07, 0x0F] {
            self.cw(w);
        }
        assert_eq!(self.state(), State::OperationEnabled);
        assert_eq!(self.drive.objects.modes_of_operation_display, mode.code());
    }
    /// Runs until `done` or panics after `max` cycles; returns the cycles taken.
    fn until(&mut self, max: usize, done: impl Fn(&Bench) -> bool) -> usize {
        for n in 0..max {
            if done(self) {
                return n;
            }
            self.run(1);
        }
        panic!("not done after {max} cycles: state {:?}, statusword {:04X}h", self.state(), self.sw());
    }
    fn numbers(&self) -> BTreeSet<u8> {
        self.seen.iter().map(|t| t.0).collect()
    }
}

#[test]
fn every_transition_of_the_table_through_the_controlword_and_faults() {
    let mut b = Bench::new();
    // 2, 3, 4, 5, 6, 7.
    for (w, s) in [
        (0x06, State::ReadyToSwitchOn),
        (0x07, State::SwitchedOn),
        (0x0F, State::OperationEnabled),
        (0x07, State::SwitchedOn),
        (0x06, State::ReadyToSwitchOn),
        (0x00, State::SwitchOnDisabled),
    ] {
        b.cw(w);
        assert_eq!(b.state(), s, "after {w:02X}h");
        assert_eq!(State::from_statusword(b.sw()), Some(s));
    }
    // 7 by quick stop, 10 both ways, 8, 9, 3 + 4 at once.
    for (words, end) in [
        (&[0x06, 0x02][..], State::SwitchOnDisabled),
        (&[0x06, 0x07, 0x00][..], State::SwitchOnDisabled),
        (&[0x06, 0x07, 0x02][..], State::SwitchOnDisabled),
        (&[0x06, 0x0F, 0x06][..], State::ReadyToSwitchOn),
        (&[0x0F, 0x00][..], State::SwitchOnDisabled),
    ] {
        for &w in words {
            b.cw(w);
        }
        assert_eq!(b.state(), end, "{words:02X?}");
    }
    assert!(b.seen.contains(&(3, State::ReadyToSwitchOn, State::SwitchedOn)));
    assert!(b.seen.contains(&(4, State::SwitchedOn, State::OperationEnabled)));
    // 11 then 12 by itself (605Ah = 2: quick stop ramp, then Switch on disabled).
    for w in [0x06, 0x0F, 0x02] {
        b.cw(w);
    }
    assert_eq!(b.state(), State::SwitchOnDisabled);
    // 605Ah = 6: stays in Quick stop active; 16 back to Operation enabled; 12 by disable voltage.
    b.write(0x605A, 0, &6i16.to_le_bytes()).unwrap();
    for w in [0x06, 0x0F, 0x02] {
        b.cw(w);
    }
    b.run(5);
    assert_eq!(b.state(), State::QuickStopActive);
    assert_eq!(b.sw() & 0x6F, 0x07);
    b.cw(0x0F);
    assert_eq!(b.state(), State::OperationEnabled);
    b.cw(0x02);
    b.cw(0x00);
    assert_eq!(b.state(), State::SwitchOnDisabled);
    // 13, 14, 15.
    b.cw(0x06);
    b.axis.fault = Some(0x2310);
    b.run(1);
    assert_eq!(b.state(), State::Fault, "605Eh = 2 on a standing axis ends the reaction at once");
    b.axis.fault = None;
    b.cw(0x80);
    assert_eq!(b.state(), State::SwitchOnDisabled);
    let all: BTreeSet<u8> = (1..=16).collect();
    assert_eq!(b.numbers(), all);
    for t in &b.seen {
        assert!(TABLE.contains(t), "{t:?} is not in the table");
    }
}

#[test]
fn commands_a_state_does_not_take_change_nothing() {
    let mut b = Bench::new();
    for w in [0x07, 0x0F, 0x02, 0x00] {
        b.cw(w);
        assert_eq!(b.state(), State::SwitchOnDisabled, "{w:02X}h");
    }
    // In Fault only the rising edge of bit 7 counts, and only once the cause is gone.
    b.axis.fault = Some(0x4210);
    b.run(1);
    assert_eq!(b.state(), State::Fault);
    for w in [0x06, 0x07, 0x0F, 0x80, 0x00, 0x80] {
        b.cw(w);
        assert_eq!(b.state(), State::Fault, "{w:02X}h while the fault is there");
    }
    b.axis.fault = None;
    b.cw(0x80); // bit 7 still high from before: no edge
    assert_eq!(b.state(), State::Fault);
    // An edge between two cycles is not lost: 00h then 80h written before the drive looks.
    b.drive.objects.write_controlword(0x00);
    b.cw(0x80);
    assert_eq!(b.state(), State::SwitchOnDisabled);
}

#[test]
fn a_fault_raises_its_code_ramps_with_605eh_and_ends_powerless() {
    let mut b = Bench::new();
    b.write(0x605E, 0, &1i16.to_le_bytes()).unwrap(); // slow-down ramp 6084h
    b.drive.objects.profile_deceleration = 10_000;
    b.enable(Mode::ProfileVelocity);
    b.drive.objects.target_velocity = 2_000;
    b.run(1);
    b.until(2_000, |b| b.sw() & 0x0400 != 0);
    b.axis.fault = Some(0x2310);
    let c = b.drive.cycle(&mut b.axis, DT);
    assert_eq!(c.raised, Some(0x2310));
    assert_eq!(b.drive.objects.error_code, 0x2310);
    assert_eq!(b.state(), State::FaultReactionActive);
    assert_eq!(b.sw() & 0x4F, 0x0F);
    assert!(b.axis.powered(), "the reaction ramps with power on");
    // 2000 inc/s at 10,000 inc/s²: 0.2 s.
    let n = b.until(1_000, |b| b.state() == State::Fault);
    assert!((150..=250).contains(&n), "{n} cycles");
    assert!(!b.axis.powered());
    assert_eq!(b.sw() & 0x4F, 0x08);
    b.axis.fault = None;
    b.drive.objects.write_controlword(0);
    b.drive.objects.write_controlword(0x80);
    let c = b.drive.cycle(&mut b.axis, DT);
    assert_eq!(c.cleared, Some(0x2310));
    assert_eq!(b.drive.objects.error_code, 0);
}

#[test]
fn disable_operation_waits_for_its_slow_down_ramp_and_shutdown_coasts() {
    let mut b = Bench::new();
    b.drive.objects.profile_deceleration = 20_000;
    b.enable(Mode::ProfileVelocity);
    b.drive.objects.target_velocity = 4_000;
    b.run(1);
    b.until(2_000, |b| b.sw() & 0x0400 != 0);
    // 605Ch = 1 (default): decelerate with 6084h, then transition 5.
    b.cw(0x07);
    assert_eq!(b.state(), State::OperationEnabled);
    let n = b.until(1_000, |b| b.state() == State::SwitchedOn);
    assert!((150..=250).contains(&n), "{n} cycles at 20,000 inc/s² from 4000 inc/s");
    // 605Bh = 0 (default): shutdown from motion cuts the power at once (transition 8).
    b.cw(0x0F);
    b.until(2_000, |b| b.sw() & 0x0400 != 0);
    assert_eq!(b.drive.objects.velocity_demand, 4_000);
    b.cw(0x06);
    assert_eq!(b.state(), State::ReadyToSwitchOn);
    assert!(!b.axis.powered());
}

#[test]
fn quick_stop_uses_6085h() {
    let mut b = Bench::new();
    b.drive.objects.quick_stop_deceleration = 40_000;
    b.enable(Mode::ProfileVelocity);
    b.drive.objects.target_velocity = -4_000;
    b.run(1);
    b.until(2_000, |b| b.sw() & 0x0400 != 0);
    b.cw(0x02);
    assert_eq!(b.state(), State::QuickStopActive);
    assert_eq!(b.sw() & 0x20, 0, "bit 5 low while a quick stop is active");
    let n = b.until(1_000, |b| b.state() == State::SwitchOnDisabled);
    assert!((90..=110).contains(&n), "{n} cycles");
}

#[test]
fn profile_position_handshake_moves_and_target_reached() {
    let mut b = Bench::new();
    b.enable(Mode::ProfilePosition);
    assert_ne!(b.sw() & 0x0400, 0, "standing on the last target");
    b.drive.objects.target_position = 20_000;
    b.cw(0x1F);
    assert_ne!(b.sw() & 0x1000, 0, "set-point acknowledge");
    assert_eq!(b.sw() & 0x0400, 0);
    b.cw(0x0F);
    assert_eq!(b.sw() & 0x1000, 0, "acknowledge cleared when bit 4 falls");
    b.until(5_000, |b| b.sw() & 0x0400 != 0);
    assert!((b.drive.objects.position_actual - 20_000).abs() <= 10);
    // Relative (bit 6), then a buffered set-point (bit 5 = 0) that starts after the first.
    b.drive.objects.target_position = -5_000;
    b.cw(0x5F);
    b.cw(0x0F);
    b.run(10);
    b.drive.objects.target_position = 30_000;
    b.cw(0x1F);
    assert_ne!(b.sw() & 0x1000, 0);
    b.cw(0x0F);
    assert_ne!(b.sw() & 0x1000, 0, "the buffer is full until the first move ends");
    // The first (relative) move ends at 15,000 before the buffered one goes to 30,000.
    let mut lowest = i32::MAX;
    for _ in 0..10_000 {
        b.run(1);
        lowest = lowest.min(b.drive.objects.position_actual);
        if b.sw() & 0x0400 != 0 {
            break;
        }
    }
    assert!((lowest - 15_000).abs() <= 10, "lowest {lowest}");
    assert!((b.drive.objects.position_actual - 30_000).abs() <= 10, "{}", b.drive.objects.position_actual);
    assert_eq!(b.sw() & 0x1000, 0, "the buffer has room again");
}

#[test]
fn profile_position_change_immediately_and_software_limits() {
    let mut b = Bench::new();
    b.write(0x607D, 1, &(-1_000i32).to_le_bytes()).unwrap();
    b.write(0x607D, 2, &1_000i32.to_le_bytes()).unwrap();
    assert_eq!(b.write(0x607D, 1, &2_000i32.to_le_bytes()), Err(AbortCode::MaxLessThanMin));
    b.enable(Mode::ProfilePosition);
    b.drive.objects.target_position = 50_000;
    b.cw(0x1F);
    assert_ne!(b.sw() & 0x0800, 0, "internal limit active: the target was limited");
    b.cw(0x0F);
    b.run(20);
    b.drive.objects.target_position = -500;
    b.cw(0x3F); // change set immediately
    b.cw(0x0F);
    b.until(5_000, |b| b.sw() & 0x0400 != 0);
    assert!((b.drive.objects.position_actual + 500).abs() <= 10, "{}", b.drive.objects.position_actual);
}

#[test]
fn profile_velocity_reaches_the_target_and_halt_stops() {
    let mut b = Bench::new();
    b.enable(Mode::ProfileVelocity);
    assert_ne!(b.sw() & 0x1000, 0, "speed = 0");
    b.drive.objects.target_velocity = 3_000;
    b.run(1);
    assert_eq!(b.sw() & 0x0400, 0);
    b.until(1_000, |b| b.sw() & 0x0400 != 0);
    b.run(50);
    assert!((b.drive.objects.velocity_actual - 3_000).abs() <= 10);
    assert_eq!(b.sw() & 0x1000, 0);
    b.cw(0x010F);
    b.until(1_000, |b| b.sw() & 0x0400 != 0 && b.drive.objects.velocity_demand == 0);
    assert_eq!(b.state(), State::OperationEnabled, "halt keeps the state");
}

#[test]
fn homing_on_the_current_position_and_on_each_limit_switch() {
    let mut b = Bench::new();
    b.axis = SimAxis::new(-3_000, 4_000);
    b.drive.objects.home_offset = 100;
    b.enable(Mode::Homing);
    assert_eq!(b.sw() & 0x3400, 0, "not homed yet");
    b.cw(0x1F);
    b.until(100, |b| b.drive.homing() == Homing::Completed);
    assert_eq!(b.sw() & 0x3400, 0x1400);
    assert_eq!(b.drive.objects.position_actual, 100);
    for (method, edge) in [(17i8, -3_000), (18, 4_000)] {
        b.cw(0x0F);
        b.write(0x6098, 0, &method.to_le_bytes()).unwrap();
        b.drive.objects.home_offset = 0;
        b.cw(0x1F);
        assert_eq!(b.sw() & 0x3400, 0, "in progress");
        b.until(20_000, |b| b.drive.homing() == Homing::Completed);
        // The home is the switch's edge: the raw position there is the travel end.
        let raw = b.axis.position();
        let actual = b.drive.objects.position_actual;
        assert!((actual - (raw - edge)).abs() <= 2, "method {method}: raw {raw}, actual {actual}");
    }
    assert_eq!(b.write(0x6098, 0, &1i8.to_le_bytes()), Err(AbortCode::InvalidValue));
    // Halt interrupts.
    b.cw(0x0F);
    b.write(0x6098, 0, &17i8.to_le_bytes()).unwrap();
    b.cw(0x1F);
    b.run(5);
    b.cw(0x011F);
    b.until(1_000, |b| b.sw() & 0x3400 == 0x0400);
}

#[test]
fn cyclic_synchronous_modes_take_their_set_point_at_sync() {
    let mut b = Bench::new();
    b.enable(Mode::CyclicSyncPosition);
    assert_ne!(b.sw() & 0x1000, 0, "the drive follows the command value");
    for k in 1..=200 {
        b.drive.objects.target_position = k * 10;
        b.run(1);
        // Not taken before the SYNC.
        assert_eq!(b.drive.objects.position_demand, (k - 1) * 10);
        b.drive.sync();
        b.run(1);
        assert_eq!(b.drive.objects.position_demand, k * 10);
        assert_eq!(b.drive.objects.velocity_demand, 10_000, "10 inc per 1 ms period");
    }
    assert!((b.drive.objects.position_actual - 2_000).abs() < 100);
    b.drive.objects.modes_of_operation = Mode::CyclicSyncVelocity.code();
    b.drive.objects.target_velocity = -1_500;
    b.run(1);
    b.drive.sync();
    b.run(300);
    assert_eq!(b.drive.objects.velocity_actual, -1_500);
}

#[test]
fn refusals_get_the_spec_answers() {
    let mut b = Bench::new();
    assert_eq!(b.write(0x6060, 0, &4i8.to_le_bytes()), Err(AbortCode::InvalidValue));
    assert_eq!(b.write(0x605A, 0, &3i16.to_le_bytes()), Err(AbortCode::InvalidValue));
    assert_eq!(b.write(0x605B, 0, &2i16.to_le_bytes()), Err(AbortCode::InvalidValue));
    assert_eq!(b.write(0x605D, 0, &0i16.to_le_bytes()), Err(AbortCode::InvalidValue));
    assert_eq!(b.write(0x605E, 0, &3i16.to_le_bytes()), Err(AbortCode::InvalidValue));
    assert_eq!(b.write(0x6083, 0, &0u32.to_le_bytes()), Err(AbortCode::ValueTooLow));
    assert_eq!(b.write(0x6041, 0, &0u16.to_le_bytes()), Err(AbortCode::WriteOfReadOnly));
    assert_eq!(b.write(0x6502, 0, &0u32.to_le_bytes()), Err(AbortCode::WriteOfReadOnly));
    let mut buf = [0u8; 4];
    assert_eq!(b.drive.read(0x6502, 0, 0, &mut buf), Ok(4));
    assert_eq!(u32::from_le_bytes(buf), 0x01A5);
    assert_eq!(b.drive.read(0x2000, 0, 0, &mut buf), Err(AbortCode::ObjectDoesNotExist));
}

#[test]
fn a_following_error_is_a_fault_8611h() {
    let mut b = Bench::new();
    b.axis = SimAxis::new(-100, 100_000);
    b.drive.objects.following_error_window = 200;
    b.enable(Mode::ProfilePosition);
    b.drive.objects.target_position = -5_000; // behind the hard stop at -100
    b.cw(0x1F);
    b.until(5_000, |b| b.state() == State::Fault);
    assert_eq!(b.drive.objects.error_code, canopen_cia402::FOLLOWING_ERROR);
}

/// One step of a random run: a controlword, an option code change, or the motor's fault on or off.
#[derive(Debug, Clone)]
enum Step {
    Cw(u16),
    QuickStop(i16),
    Shutdown(i16),
    FaultReaction(i16),
    Fault(bool),
    Run(u8),
}

fn step() -> impl Strategy<Value = Step> {
    prop_oneof![
        6 => prop_oneof![Just(0x00u16), Just(0x02), Just(0x06), Just(0x07), Just(0x0F), Just(0x80), Just(0x1F), Just(0x10F), any::<u16>()].prop_map(Step::Cw),
        1 => prop_oneof![Just(0i16), Just(1), Just(2), Just(5), Just(6)].prop_map(Step::QuickStop),
        1 => (0i16..=1).prop_map(Step::Shutdown),
        1 => (0i16..=2).prop_map(Step::FaultReaction),
        1 => any::<bool>().prop_map(Step::Fault),
        2 => any::<u8>().prop_map(Step::Run),
    ]
}

proptest! {
    /// No controlword sequence (with option codes and faults coming and going) makes the state machine
    /// leave the standard's table, and the statusword always tells the state.
    #[test]
    fn no_sequence_leaves_the_table(steps in proptest::collection::vec(step(), 1..80), mode in 0usize..6) {
        let mut b = Bench::new();
        b.drive.objects.modes_of_operation = Mode::ALL[mode].code();
        b.drive.objects.target_velocity = 2_000;
        b.drive.objects.target_position = 3_000;
        for s in steps {
            match s {
                Step::Cw(w) => b.cw(w),
                Step::QuickStop(c) => b.write(0x605A, 0, &c.to_le_bytes()).unwrap(),
                Step::Shutdown(c) => b.write(0x605B, 0, &c.to_le_bytes()).unwrap(),
                Step::FaultReaction(c) => b.write(0x605E, 0, &c.to_le_bytes()).unwrap(),
                Step::Fault(on) => b.axis.fault = on.then_some(0x5000),
                Step::Run(n) => b.run(usize::from(n)),
            }
            prop_assert_eq!(State::from_statusword(b.sw()), Some(b.state()));
            prop_assert_eq!(b.axis.powered(), b.state().power_applied());
        }
        for t in &b.seen {
            prop_assert!(TABLE.contains(t), "{:?} is not in the table", t);
        }
    }

    /// A fault always ends in Fault with the power off, whatever the state, mode, motion and reaction.
    #[test]
    fn a_fault_always_ends_in_fault_powerless(
        steps in proptest::collection::vec(step(), 0..40),
        reaction in 0i16..=2,
        mode in 0usize..6,
    ) {
        let mut b = Bench::new();
        b.drive.objects.modes_of_operation = Mode::ALL[mode].code();
        b.drive.objects.target_velocity = 5_000;
        b.drive.objects.target_position = -8_000;
        for s in steps {
            match s {
                Step::Cw(w) => b.cw(w),
                Step::Run(n) => b.run(usize::from(n)),
                _ => {}
            }
        }
        b.write(0x605E, 0, &reaction.to_le_bytes()).unwrap();
        b.axis.fault = Some(0x3210);
        b.run(1);
        prop_assert!(matches!(b.state(), State::FaultReactionActive | State::Fault));
        // The slowest reaction: 5000 inc/s at 6084h's 100,000 inc/s²: 50 ms.
        for _ in 0..200 {
            b.drive.objects.write_controlword(0x0F);
            b.run(1);
        }
        prop_assert_eq!(b.state(), State::Fault);
        prop_assert!(!b.axis.powered());
        prop_assert_eq!(b.drive.objects.error_code, 0x3210);
    }
}

/// A motor that warns (statusword bit 7), around the simulated axis.
struct Warning(SimAxis);

impl Motor for Warning {
    fn set_power(&mut self, on: bool) {
        self.0.set_power(on)
    }
    fn follow(&mut self, demand: canopen_cia402::Demand, dt_us: u32) {
        self.0.follow(demand, dt_us)
    }
    fn position(&self) -> i32 {
        self.0.position()
    }
    fn velocity(&self) -> i32 {
        self.0.velocity()
    }
    fn limit_switches(&self) -> canopen_cia402::LimitSwitches {
        self.0.limit_switches()
    }
    fn warning(&self) -> bool {
        true
    }
}

#[test]
fn warning_remote_and_a_limit_switch_in_the_statusword() {
    let mut drive = Drive::new(NoApplication);
    let mut motor = Warning(SimAxis::new(-100, 100));
    drive.cycle(&mut motor, DT);
    assert_eq!(drive.objects.statusword, 0x0040 | 0x0080 | 0x0200, "switch on disabled, warning, remote");
    drive.objects.modes_of_operation = Mode::ProfileVelocity.code();
    for w in [0x06, 0x07, 0x0F] {
        drive.objects.write_controlword(w);
        drive.cycle(&mut motor, DT);
    }
    drive.objects.target_velocity = 1_000;
    for _ in 0..200 {
        drive.cycle(&mut motor, DT);
    }
    // At the hard stop: the positive limit switch is active (bit 11).
    assert!(motor.limit_switches().positive);
    assert_ne!(drive.objects.statusword & 0x0800, 0);
}
