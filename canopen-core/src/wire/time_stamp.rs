//! TIME frame (CHECKLIST TIME-04): DLC 6, the TIME_OF_DAY payload (DT-13: ms after midnight in 28 bits,
//! 4 reserved bits, days since 1984-01-01 in 16 bits).

use super::WireError;
use crate::od::{OdValue, TimeOfDay};

/// One TIME message.
///
/// ```
/// use canopen_core::{wire::time_stamp::TimeStamp, od::TimeOfDay};
/// // V-TIME-02: 2011-02-21 12:00:00.000
/// let t = TimeStamp(TimeOfDay::new(9913, 43_200_000).unwrap());
/// assert_eq!(t.emit(), [0x00, 0x2E, 0x93, 0x02, 0xB9, 0x26]);
/// assert_eq!(TimeStamp::parse(&t.emit()), Ok(t));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct TimeStamp(pub TimeOfDay);

impl TimeStamp {
    /// Parses a TIME payload: exactly 6 bytes (anything else is ignored, CAN-07).
    pub fn parse(data: &[u8]) -> Result<Self, WireError> {
        if data.len() != 6 {
            return Err(WireError::Length);
        }
        TimeOfDay::decode(data).map(TimeStamp).map_err(|_| WireError::Value)
    }

    /// The 6 data bytes.
    pub fn emit(&self) -> [u8; 6] {
        let mut b = [0u8; 6];
        self.0.read_bytes(0, &mut b);
        b
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// V-TIME-02, V-TIME-03, V-ENC-22.
    #[test]
    fn time_vectors() {
        let t = TimeStamp::parse(&[0x95, 0x2C, 0xB3, 0x02, 0xD4, 0x16]).unwrap();
        assert_eq!((t.0.days, t.0.ms), (5844, 45_296_789));
        assert_eq!(TimeStamp::parse(&[0; 6]).unwrap().0, TimeOfDay::default());
        assert_eq!(TimeStamp::parse(&[0; 5]), Err(WireError::Length));
        assert_eq!(TimeStamp::parse(&[0; 8]), Err(WireError::Length));
    }
}
