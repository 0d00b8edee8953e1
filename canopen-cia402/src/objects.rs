//! The drive's objects (6000h–67FFh, the first logical device of CiA 402) as a derived dictionary part,
//! with the standard's defaults, which the EDS then carries (python canopen's `BaseNode402` loads it).
//!
//! Units are the drive's own (no 608Fh–60A2h factor group): positions in increments, velocities in
//! increments per second, accelerations in increments per second². The defaults of the profile objects are
//! this crate's choice for a small simulated axis (the standard leaves them to the manufacturer).
//!
//! | index | name | type | access | PDO |
//! |---|---|---|---|---|
//! | 603Fh | Error code | UNSIGNED16 | ro | T |
//! | 6040h | Controlword | UNSIGNED16 | rw | R |
//! | 6041h | Statusword | UNSIGNED16 | ro | T |
//! | 605Ah | Quick stop option code (default 2) | INTEGER16 | rw | |
//! | 605Bh | Shutdown option code (default 0) | INTEGER16 | rw | |
//! | 605Ch | Disable operation option code (default 1) | INTEGER16 | rw | |
//! | 605Dh | Halt option code (default 1) | INTEGER16 | rw | |
//! | 605Eh | Fault reaction option code (default 2) | INTEGER16 | rw | |
//! | 6060h | Modes of operation | INTEGER8 | rw | R |
//! | 6061h | Modes of operation display | INTEGER8 | ro | T |
//! | 6062h | Position demand value | INTEGER32 | ro | T |
//! | 6064h | Position actual value | INTEGER32 | ro | T |
//! | 6065h | Following error window (FFFF FFFFh: off) | UNSIGNED32 | rw | |
//! | 6067h | Position window | UNSIGNED32 | rw | |
//! | 606Bh | Velocity demand value | INTEGER32 | ro | T |
//! | 606Ch | Velocity actual value | INTEGER32 | ro | T |
//! | 607Ah | Target position | INTEGER32 | rw | R |
//! | 607Ch | Home offset | INTEGER32 | rw | |
//! | 607Dh | Software position limit :01 min, :02 max | ARRAY INTEGER32 | rw | |
//! | 6081h | Profile velocity | UNSIGNED32 | rw | R |
//! | 6083h | Profile acceleration | UNSIGNED32 | rw | R |
//! | 6084h | Profile deceleration | UNSIGNED32 | rw | R |
//! | 6085h | Quick stop deceleration | UNSIGNED32 | rw | |
//! | 6098h | Homing method | INTEGER8 | rw | |
//! | 6099h | Homing speeds :01 switch search, :02 zero search | ARRAY UNSIGNED32 | rw | |
//! | 609Ah | Homing acceleration | UNSIGNED32 | rw | |
//! | 60C2h | Interpolation time period :01 value, :02 index (10^index s) | RECORD | rw | |
//! | 60FFh | Target velocity | INTEGER32 | rw | R |
//! | 6502h | Supported drive modes | UNSIGNED32 | ro | |
//!
//! Writes the drive cannot run are refused with the spec's answer: an option code or mode outside what is
//! supported 0609 0030h, a homing method not run here 0609 0030h, 607Dh min above max 0609 0036h,
//! a zero acceleration or deceleration 0609 0032h (value too low).

use canopen_core::od::AbortCode;
use canopen_od_derive::ObjectDictionary;

use crate::homing::HomingMethod;
use crate::{Mode, Stop};

/// The CiA 402 objects of one axis. Compose it with the application's dictionary through
/// [`Drive`](crate::Drive) (the node sees one dictionary).
///
/// ```
/// use canopen_cia402::Objects;
/// use canopen_core::od::ObjectDictionary;
/// let mut o = Objects::new();
/// assert_eq!(o.quick_stop_option, 2);
/// o.write(0x6040, 0, &6u16.to_le_bytes()).unwrap();
/// assert_eq!(o.controlword, 6);
/// assert!(o.write(0x6060, 0, &[4]).is_err()); // profile torque: not run here
/// ```
#[derive(ObjectDictionary, Debug, Clone)]
pub struct Objects {
    /// 603Fh: the code of the last fault (0: none).
    #[od(index = 0x603F, name = "Error code", access = "ro", pdo = "tpdo")]
    pub error_code: u16,
    /// 6040h: the master's command.
    #[od(
        index = 0x6040,
        name = "Controlword",
        access = "rw",
        pdo = "rpdo",
        default = 0,
        on_write = "controlword_written"
    )]
    pub controlword: u16,
    /// 6041h: the drive's state and mode-specific flags.
    #[od(index = 0x6041, name = "Statusword", access = "ro", pdo = "tpdo")]
    pub statusword: u16,
    /// 605Ah: quick stop option code.
    #[od(index = 0x605A, name = "Quick stop option code", access = "rw", default = 2, check = "check_quick_stop")]
    pub quick_stop_option: i16,
    /// 605Bh: shutdown option code.
    #[od(index = 0x605B, name = "Shutdown option code", access = "rw", default = 0, check = "check_shutdown")]
    pub shutdown_option: i16,
    /// 605Ch: disable operation option code.
    #[od(index = 0x605C, name = "Disable operation option code", access = "rw", default = 1, check = "check_shutdown")]
    pub disable_operation_option: i16,
    /// 605Dh: halt option code.
    #[od(index = 0x605D, name = "Halt option code", access = "rw", default = 1, check = "check_halt")]
    pub halt_option: i16,
    /// 605Eh: fault reaction option code.
    #[od(
        index = 0x605E,
        name = "Fault reaction option code",
        access = "rw",
        default = 2,
        check = "check_fault_reaction"
    )]
    pub fault_reaction_option: i16,
    /// 6060h: the mode the master asks for.
    #[od(index = 0x6060, name = "Modes of operation", access = "rw", pdo = "rpdo", default = 0, check = "check_mode")]
    pub modes_of_operation: i8,
    /// 6061h: the mode the drive runs.
    #[od(index = 0x6061, name = "Modes of operation display", access = "ro", pdo = "tpdo")]
    pub modes_of_operation_display: i8,
    /// 6062h: position demand value.
    #[od(index = 0x6062, name = "Position demand value", access = "ro", pdo = "tpdo")]
    pub position_demand: i32,
    /// 6064h: position actual value.
    #[od(index = 0x6064, name = "Position actual value", access = "ro", pdo = "tpdo")]
    pub position_actual: i32,
    /// 6065h: following error window (FFFF FFFFh: no following error check).
    #[od(index = 0x6065, name = "Following error window", access = "rw", default = 0xFFFF_FFFF)]
    pub following_error_window: u32,
    /// 6067h: position window (target reached when the actual position is this close).
    #[od(index = 0x6067, name = "Position window", access = "rw", default = 10)]
    pub position_window: u32,
    /// 606Bh: velocity demand value.
    #[od(index = 0x606B, name = "Velocity demand value", access = "ro", pdo = "tpdo")]
    pub velocity_demand: i32,
    /// 606Ch: velocity actual value.
    #[od(index = 0x606C, name = "Velocity actual value", access = "ro", pdo = "tpdo")]
    pub velocity_actual: i32,
    /// 607Ah: target position (profile position, cyclic synchronous position).
    #[od(index = 0x607A, name = "Target position", access = "rw", pdo = "rpdo", default = 0)]
    pub target_position: i32,
    /// 607Ch: home offset (the position actual value at the home position).
    #[od(index = 0x607C, name = "Home offset", access = "rw", default = 0)]
    pub home_offset: i32,
    /// 607Dh: software position limits, :01 min, :02 max (both 0: no limit).
    #[od(index = 0x607D, sub = 1..=2, name = "Software position limit", access = "rw", check = "check_limits")]
    pub software_position_limit: [i32; 2],
    /// 6081h: profile velocity.
    #[od(index = 0x6081, name = "Profile velocity", access = "rw", pdo = "rpdo", default = 10_000)]
    pub profile_velocity: u32,
    /// 6083h: profile acceleration.
    #[od(index = 0x6083, name = "Profile acceleration", access = "rw", pdo = "rpdo", min = 1, default = 100_000)]
    pub profile_acceleration: u32,
    /// 6084h: profile deceleration (also the slow-down ramp of the option codes).
    #[od(index = 0x6084, name = "Profile deceleration", access = "rw", pdo = "rpdo", min = 1, default = 100_000)]
    pub profile_deceleration: u32,
    /// 6085h: quick stop deceleration.
    #[od(index = 0x6085, name = "Quick stop deceleration", access = "rw", min = 1, default = 1_000_000)]
    pub quick_stop_deceleration: u32,
    /// 6098h: homing method.
    #[od(index = 0x6098, name = "Homing method", access = "rw", default = 37, check = "check_homing_method")]
    pub homing_method: i8,
    /// 6099h: homing speeds, :01 during the search for the switch, :02 during the search for zero.
    #[od(index = 0x6099, sub = 1..=2, name = "Homing speeds", access = "rw")]
    pub homing_speeds: [u32; 2],
    /// 609Ah: homing acceleration.
    #[od(index = 0x609A, name = "Homing acceleration", access = "rw", min = 1, default = 100_000)]
    pub homing_acceleration: u32,
    /// 60C2h:01: interpolation time period value (units of 10^index s).
    #[od(
        index = 0x60C2,
        sub = 1,
        record = "Interpolation time period",
        name = "Interpolation time period value",
        access = "rw",
        default = 1
    )]
    pub interpolation_period_value: u8,
    /// 60C2h:02: interpolation time index (the period is value × 10^index s; -6..=0).
    #[od(index = 0x60C2, sub = 2, name = "Interpolation time index", access = "rw", min = -6, max = 0, default = -3)]
    pub interpolation_period_index: i8,
    /// 60FFh: target velocity (profile velocity, cyclic synchronous velocity).
    #[od(index = 0x60FF, name = "Target velocity", access = "rw", pdo = "rpdo", default = 0)]
    pub target_velocity: i32,
    /// 6502h: supported drive modes.
    #[od(index = 0x6502, name = "Supported drive modes", access = "ro", default = 0x01A5)]
    pub supported_drive_modes: u32,
    /// Rising edges of the controlword bits since the drive last looked (not in the dictionary): a master
    /// may write 0 and then 80h between two cycles, and the fault reset must not be lost.
    pub(crate) rising: u16,
    /// The controlword before the last write.
    pub(crate) last_controlword: u16,
}

impl Default for Objects {
    fn default() -> Self {
        Objects::new()
    }
}

/// Homing speeds 6099h:01/:02 at power-on.
const HOMING_SPEEDS: [u32; 2] = [5_000, 500];

impl Objects {
    /// The objects at their power-on (default) values.
    ///
    /// ```
    /// let o = canopen_cia402::Objects::new();
    /// assert_eq!(o.supported_drive_modes, canopen_cia402::Mode::SUPPORTED);
    /// assert_eq!(o.homing_speeds, [5_000, 500]);
    /// ```
    pub fn new() -> Self {
        let mut o = Objects {
            error_code: 0,
            controlword: 0,
            statusword: 0,
            quick_stop_option: 0,
            shutdown_option: 0,
            disable_operation_option: 0,
            halt_option: 0,
            fault_reaction_option: 0,
            modes_of_operation: 0,
            modes_of_operation_display: 0,
            position_demand: 0,
            position_actual: 0,
            following_error_window: 0,
            position_window: 0,
            velocity_demand: 0,
            velocity_actual: 0,
            target_position: 0,
            home_offset: 0,
            software_position_limit: [0; 2],
            profile_velocity: 0,
            profile_acceleration: 0,
            profile_deceleration: 0,
            quick_stop_deceleration: 0,
            homing_method: 0,
            homing_speeds: [0; 2],
            homing_acceleration: 0,
            interpolation_period_value: 0,
            interpolation_period_index: 0,
            target_velocity: 0,
            supported_drive_modes: 0,
            rising: 0,
            last_controlword: 0,
        };
        o.power_on();
        o
    }

    /// Every object back to its default (NMT Reset Application calls this through `restore_defaults`);
    /// the arrays, which the derive gives no default, included.
    fn power_on(&mut self) {
        canopen_core::od::ObjectDictionary::restore_defaults(self);
        self.homing_speeds = HOMING_SPEEDS;
        self.software_position_limit = [0; 2];
        self.rising = 0;
        self.last_controlword = 0;
    }

    /// Restores the power-on values (Reset Application): the derived defaults and the arrays'.
    ///
    /// ```
    /// let mut o = canopen_cia402::Objects::new();
    /// o.homing_speeds = [1, 1];
    /// o.reset();
    /// assert_eq!(o.homing_speeds, [5_000, 500]);
    /// ```
    pub fn reset(&mut self) {
        self.power_on();
    }

    /// Sets 6040h as a master's write (SDO or RPDO) does: the drive also sees the rising edges of its bits
    /// (new set-point, fault reset) even when the word changes back before the next cycle.
    ///
    /// ```
    /// let mut o = canopen_cia402::Objects::new();
    /// o.write_controlword(0x80);
    /// assert_eq!(o.controlword, 0x80);
    /// ```
    pub fn write_controlword(&mut self, word: u16) {
        self.controlword = word;
        self.controlword_written(0);
    }

    /// The rising edges of the controlword bits since the last call, and clears them.
    pub(crate) fn take_rising(&mut self) -> u16 {
        core::mem::take(&mut self.rising)
    }

    fn controlword_written(&mut self, _sub: u8) {
        self.rising |= self.controlword & !self.last_controlword;
        self.last_controlword = self.controlword;
    }

    fn check_quick_stop(&self, _sub: u8, v: &i16) -> Result<(), AbortCode> {
        Stop::quick_stop(*v).map(|_| ()).ok_or(AbortCode::InvalidValue)
    }
    fn check_shutdown(&self, _sub: u8, v: &i16) -> Result<(), AbortCode> {
        Stop::shutdown(*v).map(|_| ()).ok_or(AbortCode::InvalidValue)
    }
    fn check_halt(&self, _sub: u8, v: &i16) -> Result<(), AbortCode> {
        Stop::halt(*v).map(|_| ()).ok_or(AbortCode::InvalidValue)
    }
    fn check_fault_reaction(&self, _sub: u8, v: &i16) -> Result<(), AbortCode> {
        Stop::fault_reaction(*v).map(|_| ()).ok_or(AbortCode::InvalidValue)
    }
    fn check_mode(&self, _sub: u8, v: &i8) -> Result<(), AbortCode> {
        Mode::from_code(*v).map(|_| ()).ok_or(AbortCode::InvalidValue)
    }
    fn check_homing_method(&self, _sub: u8, v: &i8) -> Result<(), AbortCode> {
        HomingMethod::from_code(*v).map(|_| ()).ok_or(AbortCode::InvalidValue)
    }
    fn check_limits(&self, sub: u8, v: &i32) -> Result<(), AbortCode> {
        let [min, max] = self.software_position_limit;
        let bad = match sub {
            1 => *v > max && max != 0,
            _ => *v < min && min != 0,
        };
        if bad {
            Err(AbortCode::MaxLessThanMin)
        } else {
            Ok(())
        }
    }
}
