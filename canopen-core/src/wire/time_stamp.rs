//! TIME frame (TIME-04): DLC 6, the TIME_OF_DAY payload (DT-13: ms after midnight in 28 bits,
//! 4 reserved bits, days since 1984-01-01 in 16 bits). The node turns it into an `od::TimeOfDay` for the
//! application.

use super::WireError;

/// One TIME message.
///
/// ```
/// use canopen_core::wire::time_stamp::TimeStamp;
/// // 100 [6] 00 2E 93 02 B9 26: 2011-02-21 12:00:00.000
/// let t = TimeStamp { days: 9913, ms: 43_200_000 };
/// assert_eq!(t.emit(), [0x00, 0x2E, 0x93, 0x02, 0xB9, 0x26]);
/// assert_eq!(TimeStamp::parse(&t.emit()), Ok(t));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct TimeStamp {
    /// Days since 1984-01-01.
    pub days: u16,
    /// Milliseconds after midnight (28 bits; the 4 reserved bits are dropped on parse and sent as 0).
    pub ms: u32,
}

/// The 28 bits of the millisecond field.
const MS_MASK: u32 = (1 << 28) - 1;

impl TimeStamp {
    /// Parses a TIME payload: exactly 6 bytes (anything else is ignored, CAN-07).
    pub fn parse(data: &[u8]) -> Result<Self, WireError> {
        let [m0, m1, m2, m3, d0, d1] = <[u8; 6]>::try_from(data).map_err(|_| WireError::Length)?;
        Ok(TimeStamp { days: u16::from_le_bytes([d0, d1]), ms: u32::from_le_bytes([m0, m1, m2, m3]) & MS_MASK })
    }

    /// The 6 data bytes.
    pub fn emit(&self) -> [u8; 6] {
        let m = (self.ms & MS_MASK).to_le_bytes();
        let d = self.days.to_le_bytes();
        [m[0], m[1], m[2], m[3], d[0], d[1]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 2011-02-21 12:00:00.000 (00 2E 93 02 B9 26), 2000-01-01 12:34:56.789 (95 2C B3 02 D4 16) and the epoch
    /// 1984-01-01 00:00:00.000 (all zero).
    #[test]
    fn time_vectors() {
        let t = TimeStamp::parse(&[0x95, 0x2C, 0xB3, 0x02, 0xD4, 0x16]).unwrap();
        assert_eq!((t.days, t.ms), (5844, 45_296_789));
        assert_eq!(TimeStamp::parse(&[0; 6]).unwrap(), TimeStamp { days: 0, ms: 0 });
        assert_eq!(TimeStamp::parse(&[0xFF, 0xFF, 0xFF, 0xFF, 0, 0]).unwrap().ms, MS_MASK); // reserved bits
        assert_eq!(TimeStamp::parse(&[0; 5]), Err(WireError::Length));
        assert_eq!(TimeStamp::parse(&[0; 8]), Err(WireError::Length));
    }
}
