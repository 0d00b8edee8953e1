//! SDO abort codes (ABORT-01..ABORT-31, 000 §7.2.4.3.17 Table 22).
//!
//! Every error that can reach the bus through SDO is one of these variants, so no error can be lost or
//! mistranslated on the way out: [`AbortCode::code`] is the UNSIGNED32 of bytes 4–7 of the abort frame.

/// An SDO abort code. The discriminant is the code sent on the bus (little-endian in bytes 4–7).
///
/// ```
/// use canopen_core::abort::AbortCode;
/// assert_eq!(AbortCode::ObjectDoesNotExist.code(), 0x0602_0000);
/// assert_eq!(AbortCode::from_code(0x0609_0011), Some(AbortCode::SubIndexDoesNotExist));
/// assert_eq!(AbortCode::from_code(0x1234_5678), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u32)]
pub enum AbortCode {
    /// 0503 0000h: toggle bit not alternated (ABORT-01).
    ToggleNotAlternated = 0x0503_0000,
    /// 0504 0000h: SDO protocol timed out (ABORT-02).
    SdoTimeout = 0x0504_0000,
    /// 0504 0001h: client/server command specifier not valid or unknown (ABORT-03).
    InvalidCommandSpecifier = 0x0504_0001,
    /// 0504 0002h: invalid block size, block mode only (ABORT-04).
    InvalidBlockSize = 0x0504_0002,
    /// 0504 0003h: invalid sequence number, block mode only (ABORT-05).
    InvalidSequenceNumber = 0x0504_0003,
    /// 0504 0004h: CRC error, block mode only (ABORT-06).
    CrcError = 0x0504_0004,
    /// 0504 0005h: out of memory (ABORT-07).
    OutOfMemory = 0x0504_0005,
    /// 0601 0000h: unsupported access to an object (ABORT-08).
    UnsupportedAccess = 0x0601_0000,
    /// 0601 0001h: attempt to read a write-only object (ABORT-09).
    ReadOfWriteOnly = 0x0601_0001,
    /// 0601 0002h: attempt to write a read-only or const object (ABORT-10).
    WriteOfReadOnly = 0x0601_0002,
    /// 0602 0000h: object does not exist in the object dictionary (ABORT-11).
    ObjectDoesNotExist = 0x0602_0000,
    /// 0604 0041h: object cannot be mapped to the PDO (ABORT-12).
    NotMappable = 0x0604_0041,
    /// 0604 0042h: number and length of mapped objects would exceed the PDO length (ABORT-13).
    PdoLengthExceeded = 0x0604_0042,
    /// 0604 0043h: general parameter incompatibility (ABORT-14).
    ParameterIncompatibility = 0x0604_0043,
    /// 0604 0047h: general internal incompatibility in the device (ABORT-15).
    InternalIncompatibility = 0x0604_0047,
    /// 0606 0000h: access failed due to a hardware error (ABORT-16).
    HardwareError = 0x0606_0000,
    /// 0607 0010h: data type does not match, length of service parameter does not match (ABORT-17).
    LengthMismatch = 0x0607_0010,
    /// 0607 0012h: data type does not match, length of service parameter too high (ABORT-18).
    LengthTooHigh = 0x0607_0012,
    /// 0607 0013h: data type does not match, length of service parameter too low (ABORT-19).
    LengthTooLow = 0x0607_0013,
    /// 0609 0011h: sub-index does not exist (ABORT-20).
    SubIndexDoesNotExist = 0x0609_0011,
    /// 0609 0030h: invalid value for parameter, download only (ABORT-21).
    InvalidValue = 0x0609_0030,
    /// 0609 0031h: value of parameter written too high, download only (ABORT-22).
    ValueTooHigh = 0x0609_0031,
    /// 0609 0032h: value of parameter written too low, download only (ABORT-23).
    ValueTooLow = 0x0609_0032,
    /// 0609 0036h: maximum value is less than minimum value (ABORT-24).
    MaxLessThanMin = 0x0609_0036,
    /// 060A 0023h: resource not available: SDO connection (ABORT-25).
    NoSdoConnection = 0x060A_0023,
    /// 0800 0000h: general error (ABORT-26).
    GeneralError = 0x0800_0000,
    /// 0800 0020h: data cannot be transferred or stored to the application (ABORT-27).
    CannotStore = 0x0800_0020,
    /// 0800 0021h: ... because of local control (ABORT-28).
    CannotStoreLocalControl = 0x0800_0021,
    /// 0800 0022h: ... because of the present device state (ABORT-29).
    CannotStoreDeviceState = 0x0800_0022,
    /// 0800 0023h: object dictionary dynamic generation failed or no object dictionary present (ABORT-30).
    NoObjectDictionary = 0x0800_0023,
    /// 0800 0024h: no data available (ABORT-31).
    NoDataAvailable = 0x0800_0024,
}

impl AbortCode {
    /// Every abort code of Table 22, in table order.
    pub const ALL: [AbortCode; 31] = [
        AbortCode::ToggleNotAlternated,
        AbortCode::SdoTimeout,
        AbortCode::InvalidCommandSpecifier,
        AbortCode::InvalidBlockSize,
        AbortCode::InvalidSequenceNumber,
        AbortCode::CrcError,
        AbortCode::OutOfMemory,
        AbortCode::UnsupportedAccess,
        AbortCode::ReadOfWriteOnly,
        AbortCode::WriteOfReadOnly,
        AbortCode::ObjectDoesNotExist,
        AbortCode::NotMappable,
        AbortCode::PdoLengthExceeded,
        AbortCode::ParameterIncompatibility,
        AbortCode::InternalIncompatibility,
        AbortCode::HardwareError,
        AbortCode::LengthMismatch,
        AbortCode::LengthTooHigh,
        AbortCode::LengthTooLow,
        AbortCode::SubIndexDoesNotExist,
        AbortCode::InvalidValue,
        AbortCode::ValueTooHigh,
        AbortCode::ValueTooLow,
        AbortCode::MaxLessThanMin,
        AbortCode::NoSdoConnection,
        AbortCode::GeneralError,
        AbortCode::CannotStore,
        AbortCode::CannotStoreLocalControl,
        AbortCode::CannotStoreDeviceState,
        AbortCode::NoObjectDictionary,
        AbortCode::NoDataAvailable,
    ];

    /// The UNSIGNED32 sent in bytes 4–7 of the abort frame.
    ///
    /// ```
    /// # use canopen_core::abort::AbortCode;
    /// assert_eq!(AbortCode::SdoTimeout.code().to_le_bytes(), [0x00, 0x00, 0x04, 0x05]);
    /// ```
    pub const fn code(self) -> u32 {
        self as u32
    }

    /// The variant for a received code, `None` for a code Table 22 does not define.
    ///
    /// ```
    /// # use canopen_core::abort::AbortCode;
    /// assert_eq!(AbortCode::from_code(0x0800_0024), Some(AbortCode::NoDataAvailable));
    /// ```
    pub fn from_code(code: u32) -> Option<AbortCode> {
        AbortCode::ALL.iter().copied().find(|a| a.code() == code)
    }
}

impl core::fmt::Display for AbortCode {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "{:08X}h ({:?})", self.code(), self)
    }
}

/// An abort code is also the error of the dictionary's operations.
///
/// ```
/// use canopen_core::abort::AbortCode;
/// let e: &dyn core::error::Error = &AbortCode::ObjectDoesNotExist;
/// assert_eq!(e.to_string(), "06020000h (ObjectDoesNotExist)");
/// ```
impl core::error::Error for AbortCode {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_are_unique_and_round_trip() {
        for (i, a) in AbortCode::ALL.iter().enumerate() {
            assert_eq!(AbortCode::from_code(a.code()), Some(*a));
            for b in &AbortCode::ALL[i + 1..] {
                assert_ne!(a.code(), b.code());
            }
        }
    }
}
