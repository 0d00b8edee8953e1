//! The drive on a node: its objects and the application's in one dictionary (SDO and the EDS), the
//! controlword by RPDO and the statusword by TPDO, and the EMCY a fault raises and a reset clears.

use canopen_cia402::{cycle_node, Drive, SimAxis, State};
use canopen_core::od::Merged;
use canopen_core::pdo::PdoDefault;
use canopen_core::profile::eds::{write_eds, EdsInfo};
use canopen_core::profile::{CommProfile, NodeConfig};
use canopen_core::{CanFrame, Instant, Node, NodeId, Sizes};
use canopen_od_derive::ObjectDictionary;

/// The application's own objects, below and above the drive's range.
#[derive(ObjectDictionary, Debug, Default)]
struct App {
    #[od(index = 0x2000, name = "Gear ratio", access = "rw", default = 3)]
    gear: u16,
    #[od(index = 0x7000, name = "Board temperature", access = "ro")]
    temperature: i16,
}

const RPDO1: [u32; 1] = [0x6040_0010];
const TPDO1: [u32; 1] = [0x6041_0010];
const CONFIG: NodeConfig = NodeConfig {
    device_type: 0x0002_0192,
    rpdo: &[PdoDefault { mapping: &RPDO1, transmission_type: 255, ..PdoDefault::EVENT }],
    tpdo: &[PdoDefault { mapping: &TPDO1, transmission_type: 255, ..PdoDefault::EVENT }],
    ..NodeConfig::DEFAULT
};
type Z = Sizes<0, 16, 16, 1, 1>;

fn node() -> Node<Drive<App>, Z> {
    let app = App { gear: 3, ..App::default() };
    let mut n = Node::new(NodeId::new(4).unwrap(), CONFIG, Drive::new(app));
    n.handle_timeout(Instant::ZERO);
    while n.poll_transmit().is_some() {}
    n
}

fn sdo(n: &mut Node<Drive<App>, Z>, req: [u8; 8]) -> [u8; 8] {
    n.handle_frame(Instant::ZERO, &CanFrame::new(0x604, &req).unwrap());
    let f = std::iter::from_fn(|| n.poll_transmit()).find(|f| f.cob_id() == 0x584).expect("an SDO answer");
    f.data().try_into().unwrap()
}

#[test]
fn one_dictionary_for_sdo_and_the_eds() {
    let mut n = node();
    // 6502h from the drive, 2000h and 7000h from the application.
    assert_eq!(sdo(&mut n, [0x40, 0x02, 0x65, 0, 0, 0, 0, 0]), [0x43, 0x02, 0x65, 0, 0xA5, 0x01, 0, 0]);
    assert_eq!(sdo(&mut n, [0x40, 0x00, 0x20, 0, 0, 0, 0, 0]), [0x4B, 0x00, 0x20, 0, 3, 0, 0, 0]);
    assert_eq!(sdo(&mut n, [0x40, 0x00, 0x70, 0, 0, 0, 0, 0])[0], 0x4B);
    // A mode not run here: 0609 0030h.
    assert_eq!(sdo(&mut n, [0x2F, 0x60, 0x60, 0, 4, 0, 0, 0]), [0x80, 0x60, 0x60, 0, 0x30, 0, 0x09, 0x06]);

    let comm = CommProfile::<Z>::new(CONFIG);
    let od = Merged { comm, app: Drive::new(App::default()) };
    let mut eds = String::new();
    write_eds(&mut eds, &EdsInfo::DEFAULT, &od).unwrap();
    let pos = |s: &str| eds.find(s).unwrap_or_else(|| panic!("{s} not in the EDS"));
    assert!(pos("[2000]") < pos("[603F]") && pos("[6502]") < pos("[7000]"));
    // The standard's defaults, as python canopen's BaseNode402 reads them.
    let section = |s: &str| &eds[pos(s)..][..eds[pos(s)..].find("\n\n").unwrap_or(eds.len() - pos(s))];
    assert!(section("[605A]").contains("DefaultValue=2"), "{}", section("[605A]"));
    assert!(section("[6502]").contains("DefaultValue=0x1A5"), "{}", section("[6502]"));
    assert!(section("[6040]").contains("PDOMapping=1"));
}

#[test]
fn controlword_by_rpdo_statusword_by_tpdo_and_the_fault_emcy() {
    let mut n = node();
    let mut axis = SimAxis::new(-10_000, 10_000);
    n.handle_frame(Instant::ZERO, &CanFrame::new(0x000, &[0x01, 4]).unwrap());
    cycle_node(&mut n, &mut axis, 1000);
    let tpdo = |n: &mut Node<Drive<App>, Z>| {
        std::iter::from_fn(|| n.poll_transmit()).filter(|f| f.cob_id() == 0x184).last().map(|f| f.data().to_vec())
    };
    assert_eq!(tpdo(&mut n), Some(vec![0x40, 0x02]), "Switch on disabled, remote");
    for (cw, sw) in [(0x06u16, 0x0231u16), (0x07, 0x0233), (0x0F, 0x0237)] {
        n.handle_frame(Instant::ZERO, &CanFrame::new(0x204, &cw.to_le_bytes()).unwrap());
        cycle_node(&mut n, &mut axis, 1000);
        let got = tpdo(&mut n).expect("the statusword changed: a TPDO");
        assert_eq!(u16::from_le_bytes([got[0], got[1]]) & 0x02FF, sw, "after {cw:02X}h");
    }
    assert_eq!(n.app().state(), State::OperationEnabled);
    axis.fault = Some(0x4310);
    cycle_node(&mut n, &mut axis, 1000);
    let frames: Vec<CanFrame> = std::iter::from_fn(|| n.poll_transmit()).collect();
    let emcy = frames.iter().find(|f| f.cob_id() == 0x84).expect("an EMCY");
    assert_eq!(&emcy.data()[..2], &[0x10, 0x43]);
    assert_ne!(emcy.data()[2], 0, "error register set");
    assert_eq!(n.app().state(), State::Fault);
    axis.fault = None;
    for cw in [0x00u16, 0x80] {
        n.handle_frame(Instant::ZERO, &CanFrame::new(0x204, &cw.to_le_bytes()).unwrap());
    }
    cycle_node(&mut n, &mut axis, 1000);
    let frames: Vec<CanFrame> = std::iter::from_fn(|| n.poll_transmit()).collect();
    let reset = frames.iter().find(|f| f.cob_id() == 0x84).expect("the EMCY error reset");
    assert_eq!(&reset.data()[..3], &[0, 0, 0]);
    assert_eq!(n.app().state(), State::SwitchOnDisabled);
}
