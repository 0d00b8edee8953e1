//! `canopen-cia402`: the CiA 402 drive profile (IEC 61800-7-201) on canopen-core, for drive firmware:
//! `#![no_std]`, no heap, no `unsafe`, sans-IO (the caller passes the cycle time; no clock inside).
//!
//! - [`state`]: the power drive system state machine, its table of transitions 0–16, the controlword
//!   commands and the statusword's state bits;
//! - [`options`](Stop): 605Ah–605Eh, how the drive stops;
//! - [`Mode`]: 6060h/6061h and 6502h; profile position, profile velocity, homing, cyclic synchronous
//!   position and velocity;
//! - [`Objects`]: the drive's objects as a derived dictionary part with the standard's defaults (and so in
//!   the EDS);
//! - [`Drive`]: one axis, the objects composed with the application's own dictionary (one dictionary for
//!   the node), run one cycle at a time against the application's [`Motor`]; [`cycle_node`] on a node
//!   raises the fault's EMCY and sends the changed TPDOs;
//! - [`pdo`]: the default PDO mapping of a drive (controlword, statusword and the mode pairs);
//! - [`Ramp`]: the integer trajectory generator the modes share; [`Homing`]: the homing procedure;
//! - [`SimAxis`]: a simulated axis (inertia, top speed, hard stops with limit switches) for tests and the
//!   example drive.
//!
//! ```
//! use canopen_cia402::{cycle_node, Demand, Drive, Motor, State};
//! use canopen_core::{od::NoApplication, profile::NodeConfig, Node, NodeId};
//!
//! /// The application's hardware: here a motor that is where it is told to be.
//! #[derive(Default)]
//! struct Ideal { pos: i32, vel: i32 }
//! impl Motor for Ideal {
//!     fn set_power(&mut self, _on: bool) {}
//!     fn follow(&mut self, demand: Demand, _dt_us: u32) {
//!         if let Demand::Position { position, velocity } = demand { (self.pos, self.vel) = (position, velocity) }
//!     }
//!     fn position(&self) -> i32 { self.pos }
//!     fn velocity(&self) -> i32 { self.vel }
//! }
//!
//! let id = NodeId::new(1).unwrap();
//! let mut node: Node<Drive<NoApplication>> = Node::new(id, NodeConfig::DEFAULT, Drive::new(NoApplication));
//! let mut motor = Ideal::default();
//! cycle_node(&mut node, &mut motor, 1000); // self-test passed: Switch on disabled (transition 1)
//! // A master wrote 6060h = 1 (profile position), then the controlwords 06h, 0Fh (RPDO or SDO).
//! node.app_mut().objects.modes_of_operation = 1;
//! for cw in [0x06u16, 0x0F] {
//!     node.app_mut().objects.write_controlword(cw);
//!     cycle_node(&mut node, &mut motor, 1000);
//! }
//! assert_eq!(node.app().state(), State::OperationEnabled);
//! // A move to 500 with the set-point handshake (bit 4), 1 ms cycles until target reached (bit 10).
//! node.app_mut().objects.target_position = 500;
//! node.app_mut().objects.write_controlword(0x1F);
//! let mut cycles = 0;
//! while node.app().objects.statusword & 0x0400 == 0 || cycles == 0 {
//!     cycle_node(&mut node, &mut motor, 1000);
//!     cycles += 1;
//! }
//! assert_eq!(node.app().objects.position_actual, 500);
//! ```
//!
//! # What this relies on
//!
//! The project's source documents hold CiA 301, not CiA 402. This crate follows public descriptions of
//! IEC 61800-7-201 / CiA 402-2: python canopen's `canopen/profiles/p402.py` (the master side: the state
//! masks of the statusword, the controlword commands and the transition table it drives, the homing
//! status bits, the mode codes and 6502h bits), the stepper drive manual among the project's sources (its
//! PDO examples with 6040h, 6041h, 6060h, 607Ah, 6064h), and the object list, option codes and profile
//! position handshake as drive manuals publish them. Where those were silent we chose, and say so in the
//! module docs: bit 7 of the controlword masks every other command while set; option codes needing
//! current or voltage limits (3, 4, 7, 8) are refused; 607Dh both 0 means no software limits; the halt
//! bit resumes a profile position move when released.
//!
//! Not here (yet): the velocity mode (2), profile torque (4), interpolated position (7), cyclic
//! synchronous torque (10), the factor group (608Fh–60A2h), 6007h abort connection option code, and
//! homing methods other than 17, 18, 35, 37.
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

mod compose;
mod drive;
mod homing;
mod mode;
mod motor;
mod objects;
mod options;
pub mod pdo;
mod ramp;
mod sim;
pub mod state;

pub use compose::is_drive_index;
pub use drive::{cycle_node, Cycle, Drive, Transition, FOLLOWING_ERROR};
pub use homing::{Homing, HomingMethod};
pub use mode::Mode;
pub use motor::{Demand, LimitSwitches, Motor};
pub use objects::Objects;
pub use options::Stop;
pub use ramp::Ramp;
pub use sim::SimAxis;
pub use state::{transition, Command, State, TABLE};
