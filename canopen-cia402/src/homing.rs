//! Homing (mode 6): the methods this crate runs and the homing procedure's own state.
//!
//! Methods (6098h; numbering of IEC 61800-7-201 as python canopen's `p402.py` `Homing` lists it):
//! 17 negative limit switch, 18 positive limit switch (search the switch at 6099h:01, leave it at 6099h:02;
//! the edge where it releases is the home position), 35 and 37 the current position (35 is the older
//! number of 37). The home position gets the value of 607Ch home offset. Statusword bits 10/12/13 tell the
//! procedure's progress as the standard's table (and python canopen's `Homing.STATES`) reads them: in
//! progress 0/0/0, interrupted by halt 1/0/0, attained (still moving) 0/1/0, completed 1/1/0, error with
//! the axis moving 0/0/1, error at standstill 1/0/1.

/// A homing method this crate runs.
///
/// ```
/// use canopen_cia402::HomingMethod;
/// assert_eq!(HomingMethod::from_code(18), Some(HomingMethod::PositiveLimitSwitch));
/// assert_eq!(HomingMethod::from_code(1), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HomingMethod {
    /// 17: homing on the negative limit switch.
    NegativeLimitSwitch,
    /// 18: homing on the positive limit switch.
    PositiveLimitSwitch,
    /// 35 or 37: the current position is the home position.
    CurrentPosition,
}

impl HomingMethod {
    /// The method a 6098h value selects, `None` for a method not run here.
    ///
    /// ```
    /// assert_eq!(canopen_cia402::HomingMethod::from_code(35), canopen_cia402::HomingMethod::from_code(37));
    /// ```
    pub const fn from_code(code: i8) -> Option<HomingMethod> {
        match code {
            17 => Some(HomingMethod::NegativeLimitSwitch),
            18 => Some(HomingMethod::PositiveLimitSwitch),
            35 | 37 => Some(HomingMethod::CurrentPosition),
            _ => None,
        }
    }
}

/// Where a homing procedure is.
///
/// ```
/// use canopen_cia402::Homing;
/// assert_eq!(Homing::Completed.status_bits(), 0x1400);
/// assert_eq!(Homing::InProgress.status_bits(), 0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Homing {
    /// Not started since power-on (or since the mode was left while it ran).
    Idle,
    /// Moving toward the switch (6099h:01).
    InProgress,
    /// Moving off the switch (6099h:02).
    Leaving,
    /// The home position is set; the axis still decelerates.
    Attained,
    /// Homing completed, the axis stands at home.
    Completed,
    /// Halt (bit 8) interrupted the procedure.
    Interrupted,
    /// The procedure failed (e.g. the switch was not found within the software limits, or the drive left
    /// Operation enabled).
    Error,
}

impl Homing {
    /// Statusword bits 10, 12, 13 for this progress (with the axis at standstill for [`Homing::Error`]).
    ///
    /// ```
    /// assert_eq!(canopen_cia402::Homing::Error.status_bits(), 0x2400);
    /// ```
    pub const fn status_bits(self) -> u16 {
        match self {
            Homing::Idle | Homing::InProgress | Homing::Leaving => 0,
            Homing::Interrupted => 0x0400,
            Homing::Attained => 0x1000,
            Homing::Completed => 0x1400,
            Homing::Error => 0x2400,
        }
    }

    /// Whether the procedure is moving the axis.
    ///
    /// ```
    /// assert!(canopen_cia402::Homing::Leaving.running());
    /// ```
    pub const fn running(self) -> bool {
        matches!(self, Homing::InProgress | Homing::Leaving | Homing::Attained)
    }
}
