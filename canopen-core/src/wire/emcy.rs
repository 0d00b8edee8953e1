//! EMCY frame (EMCY-04): DLC 8; bytes 0–1 emergency error code (LE), byte 2 error register (1001h),
//! bytes 3–7 manufacturer-specific error field.

use super::WireError;

/// One emergency message.
///
/// ```
/// use canopen_core::wire::emcy::Emergency;
/// // Heartbeat consumer time-out: error code 8130h, error register 11h.
/// let e = Emergency { code: 0x8130, register: 0x11, manufacturer: [0; 5] };
/// assert_eq!(e.emit(), [0x30, 0x81, 0x11, 0, 0, 0, 0, 0]);
/// assert_eq!(Emergency::parse(&e.emit()), Ok(e));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Emergency {
    /// Emergency error code (Table 26; 0000h = error reset / no error).
    pub code: u16,
    /// The error register 1001h at the time of the error.
    pub register: u8,
    /// Manufacturer-specific error field.
    pub manufacturer: [u8; 5],
}

impl Emergency {
    /// Parses an EMCY payload: exactly 8 bytes (EMCY-04; anything else is ignored, CAN-07).
    pub fn parse(data: &[u8]) -> Result<Self, WireError> {
        let [c0, c1, register, m0, m1, m2, m3, m4] = *data else {
            return Err(WireError::Length);
        };
        Ok(Emergency { code: u16::from_le_bytes([c0, c1]), register, manufacturer: [m0, m1, m2, m3, m4] })
    }

    /// The 8 data bytes.
    pub const fn emit(&self) -> [u8; 8] {
        let c = self.code.to_le_bytes();
        let m = self.manufacturer;
        [c[0], c[1], self.register, m[0], m[1], m[2], m[3], m[4]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// EMCY frames (EMCY-04): the life-guarding error 8130h with error register 11h, and the error-reset frame
    /// (code 0000h, all zeros).
    #[test]
    fn emcy_vectors() {
        let e = Emergency::parse(&[0x30, 0x81, 0x11, 0, 0, 0, 0, 0]).unwrap();
        assert_eq!((e.code, e.register), (0x8130, 0x11));
        assert_eq!(Emergency { code: 0, register: 0, manufacturer: [0; 5] }.emit(), [0; 8]);
        assert_eq!(Emergency::parse(&[0; 7]), Err(WireError::Length));
        assert_eq!(Emergency::parse(&[]), Err(WireError::Length));
    }
}
