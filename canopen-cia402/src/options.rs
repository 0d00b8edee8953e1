//! Option codes 605Ah–605Eh: how the drive stops when a quick stop, shutdown, disable operation, halt or
//! fault asks it to.
//!
//! Values as IEC 61800-7-201 defines them (restated in drive manuals, e.g. the stepper drive manual among
//! this project's source documents and python canopen's p402 notes): 0 disable the drive function (the
//! motor coasts), 1 slow-down ramp (6084h), 2 quick stop ramp (6085h), 3/4 current or voltage limit, 5–8
//! as 1–4 but staying in Quick stop active. This crate has no current or voltage limit of its own: 3/4 and
//! 7/8 are refused (0609 0030h) rather than silently run as something else.

/// How the drive stops.
///
/// ```
/// use canopen_cia402::Stop;
/// assert_eq!(Stop::quick_stop(6), Some((Stop::QuickStopRamp, true)));
/// assert_eq!(Stop::quick_stop(3), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Stop {
    /// Disable the drive function at once: the motor is free to rotate.
    Coast,
    /// Decelerate with the profile deceleration 6084h.
    SlowDownRamp,
    /// Decelerate with the quick stop deceleration 6085h.
    QuickStopRamp,
}

impl Stop {
    /// 605Ah quick stop option code: the stop and whether the drive then stays in Quick stop active (5, 6)
    /// rather than going on to Switch on disabled (0, 1, 2).
    ///
    /// ```
    /// assert_eq!(canopen_cia402::Stop::quick_stop(2), Some((canopen_cia402::Stop::QuickStopRamp, false)));
    /// ```
    pub const fn quick_stop(code: i16) -> Option<(Stop, bool)> {
        Some(match code {
            0 => (Stop::Coast, false),
            1 => (Stop::SlowDownRamp, false),
            2 => (Stop::QuickStopRamp, false),
            5 => (Stop::SlowDownRamp, true),
            6 => (Stop::QuickStopRamp, true),
            _ => return None,
        })
    }

    /// 605Bh shutdown and 605Ch disable operation option codes: 0 coast, 1 slow-down ramp first.
    ///
    /// ```
    /// assert_eq!(canopen_cia402::Stop::shutdown(1), Some(canopen_cia402::Stop::SlowDownRamp));
    /// ```
    pub const fn shutdown(code: i16) -> Option<Stop> {
        match code {
            0 => Some(Stop::Coast),
            1 => Some(Stop::SlowDownRamp),
            _ => None,
        }
    }

    /// 605Dh halt option code: 1 slow-down ramp, 2 quick stop ramp (the drive stays in Operation enabled).
    ///
    /// ```
    /// assert_eq!(canopen_cia402::Stop::halt(2), Some(canopen_cia402::Stop::QuickStopRamp));
    /// assert_eq!(canopen_cia402::Stop::halt(0), None);
    /// ```
    pub const fn halt(code: i16) -> Option<Stop> {
        match code {
            1 => Some(Stop::SlowDownRamp),
            2 => Some(Stop::QuickStopRamp),
            _ => None,
        }
    }

    /// 605Eh fault reaction option code: 0 coast, 1 slow-down ramp, 2 quick stop ramp.
    ///
    /// ```
    /// assert_eq!(canopen_cia402::Stop::fault_reaction(0), Some(canopen_cia402::Stop::Coast));
    /// ```
    pub const fn fault_reaction(code: i16) -> Option<Stop> {
        match code {
            0 => Some(Stop::Coast),
            1 => Some(Stop::SlowDownRamp),
            2 => Some(Stop::QuickStopRamp),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_option_object_accepts_exactly_its_codes() {
        for code in -300i16..300 {
            assert_eq!(Stop::quick_stop(code).is_some(), matches!(code, 0 | 1 | 2 | 5 | 6), "605Ah {code}");
            assert_eq!(Stop::shutdown(code).is_some(), matches!(code, 0 | 1), "605Bh {code}");
            assert_eq!(Stop::halt(code).is_some(), matches!(code, 1 | 2), "605Dh {code}");
            assert_eq!(Stop::fault_reaction(code).is_some(), matches!(code, 0..=2), "605Eh {code}");
        }
        assert_eq!(Stop::quick_stop(5), Some((Stop::SlowDownRamp, true)));
        assert_eq!(Stop::quick_stop(0), Some((Stop::Coast, false)));
    }
}
