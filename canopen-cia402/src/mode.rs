//! Modes of operation: 6060h (what the master asks), 6061h (what the drive runs) and 6502h (the modes the
//! drive supports, one bit each).
//!
//! The values and bit positions are those of IEC 61800-7-201 as python canopen's `p402.py`
//! (`OperationMode.CODE2NAME`, `OperationMode.SUPPORTED`) restates them. This crate runs profile position,
//! profile velocity, homing and the cyclic synchronous position and velocity modes; 6060h refuses the others
//! with 0609 0030h.

/// A mode of operation this crate runs (6060h/6061h values).
///
/// ```
/// use canopen_cia402::Mode;
/// assert_eq!(Mode::from_code(6), Some(Mode::Homing));
/// assert_eq!(Mode::Homing.code(), 6);
/// assert_eq!(Mode::from_code(4), None); // profile torque: not run here
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Mode {
    /// 0: no mode; the drive holds still.
    NoMode,
    /// 1: profile position (pp): 607Ah with 6081h, 6083h, 6084h, the set-point handshake.
    ProfilePosition,
    /// 3: profile velocity (pv): 60FFh with 6083h, 6084h.
    ProfileVelocity,
    /// 6: homing (hm): 6098h method, 6099h speeds, 609Ah acceleration, 607Ch home offset.
    Homing,
    /// 8: cyclic synchronous position (csp): 607Ah taken at each SYNC, period 60C2h.
    CyclicSyncPosition,
    /// 9: cyclic synchronous velocity (csv): 60FFh taken at each SYNC, period 60C2h.
    CyclicSyncVelocity,
}

impl Mode {
    /// Every mode, in code order.
    ///
    /// ```
    /// assert_eq!(canopen_cia402::Mode::ALL.len(), 6);
    /// ```
    pub const ALL: [Mode; 6] = [
        Mode::NoMode,
        Mode::ProfilePosition,
        Mode::ProfileVelocity,
        Mode::Homing,
        Mode::CyclicSyncPosition,
        Mode::CyclicSyncVelocity,
    ];

    /// The 6060h/6061h value.
    ///
    /// ```
    /// assert_eq!(canopen_cia402::Mode::CyclicSyncPosition.code(), 8);
    /// ```
    pub const fn code(self) -> i8 {
        match self {
            Mode::NoMode => 0,
            Mode::ProfilePosition => 1,
            Mode::ProfileVelocity => 3,
            Mode::Homing => 6,
            Mode::CyclicSyncPosition => 8,
            Mode::CyclicSyncVelocity => 9,
        }
    }

    /// The mode of a 6060h value, `None` for a mode this crate does not run.
    ///
    /// ```
    /// assert_eq!(canopen_cia402::Mode::from_code(3), Some(canopen_cia402::Mode::ProfileVelocity));
    /// ```
    pub const fn from_code(code: i8) -> Option<Mode> {
        Some(match code {
            0 => Mode::NoMode,
            1 => Mode::ProfilePosition,
            3 => Mode::ProfileVelocity,
            6 => Mode::Homing,
            8 => Mode::CyclicSyncPosition,
            9 => Mode::CyclicSyncVelocity,
            _ => return None,
        })
    }

    /// The mode's bit in 6502h supported drive modes (0 for "no mode", which has none).
    ///
    /// ```
    /// assert_eq!(canopen_cia402::Mode::Homing.supported_bit(), 0x20);
    /// ```
    pub const fn supported_bit(self) -> u32 {
        match self {
            Mode::NoMode => 0,
            Mode::ProfilePosition => 1 << 0,
            Mode::ProfileVelocity => 1 << 2,
            Mode::Homing => 1 << 5,
            Mode::CyclicSyncPosition => 1 << 7,
            Mode::CyclicSyncVelocity => 1 << 8,
        }
    }

    /// 6502h of a drive running every mode of [`Mode::ALL`].
    ///
    /// ```
    /// assert_eq!(canopen_cia402::Mode::SUPPORTED, 0x01A5);
    /// ```
    pub const SUPPORTED: u32 = {
        let mut bits = 0;
        let mut i = 0;
        while i < Mode::ALL.len() {
            bits |= Mode::ALL[i].supported_bit();
            i += 1;
        }
        bits
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_round_trip_and_others_are_refused() {
        for m in Mode::ALL {
            assert_eq!(Mode::from_code(m.code()), Some(m));
        }
        let known = Mode::ALL.map(Mode::code);
        for code in i8::MIN..=i8::MAX {
            assert_eq!(Mode::from_code(code).is_some(), known.contains(&code), "{code}");
        }
        // python canopen's OperationMode.SUPPORTED bits for pp, pv, hm, csp, csv.
        assert_eq!(Mode::SUPPORTED, 0x0001 | 0x0004 | 0x0020 | 0x0080 | 0x0100);
    }
}
