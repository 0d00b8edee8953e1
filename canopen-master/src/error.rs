//! Why a master operation failed, and what an SDO abort code means.

use std::fmt;
use std::io;

use canopen_core::sdo::client::ClientError;

/// Why a master operation failed.
///
/// An SDO abort carries its code and who sent it; [`Error::abort_code`] gives the code and the
/// `Display` text its meaning from CiA 301 Table 22 (ABORT-01..ABORT-31).
///
/// ```
/// use canopen_master::Error;
/// let e = Error::Aborted { code: 0x0602_0000, by_server: true };
/// assert_eq!(e.abort_code(), Some(0x0602_0000));
/// assert_eq!(e.to_string(), "SDO aborted by the server: 0602 0000h: object does not exist in the object dictionary");
/// ```
#[derive(Debug)]
#[non_exhaustive]
pub enum Error {
    /// The socket failed.
    Io(io::Error),
    /// The SDO transfer was aborted with this code, by the server or by this master (a time-out is the
    /// master's abort 0504 0000h).
    Aborted {
        /// The abort code.
        code: u32,
        /// Whether the server sent the abort (else this master did, and sent the abort frame).
        by_server: bool,
    },
    /// An LSS service or an NMT wait got no answer in time.
    Timeout,
    /// The value read has another size than the type asked for.
    TypeMismatch {
        /// Bytes the type has.
        expected: usize,
        /// Bytes the server sent.
        got: usize,
    },
    /// An argument is out of range (a node-ID outside 1..=127, a PDO number outside 1..=512, ...).
    InvalidArgument(String),
    /// A peer answered something the protocol does not allow there, or a sequence failed (the text says
    /// what).
    Protocol(String),
    /// The master's receive task has stopped (the socket failed for good); the text says why.
    Closed(String),
    /// The transfer was cut off because the socket failed while it waited (the interface went down); the
    /// text says why. The master reopens its socket when the interface is up again: a later transfer can
    /// work on the same master.
    Interrupted(String),
}

impl Error {
    /// The SDO abort code, if the operation ended with an abort.
    ///
    /// ```
    /// assert_eq!(canopen_master::Error::Timeout.abort_code(), None);
    /// ```
    pub fn abort_code(&self) -> Option<u32> {
        match self {
            Error::Aborted { code, .. } => Some(*code),
            _ => None,
        }
    }

    /// Whether this is a time-out: the master's SDO abort 0504 0000h or an unanswered LSS/NMT wait.
    ///
    /// ```
    /// use canopen_master::Error;
    /// assert!(Error::Aborted { code: 0x0504_0000, by_server: false }.is_timeout());
    /// assert!(!Error::Aborted { code: 0x0504_0000, by_server: true }.is_timeout());
    /// ```
    pub fn is_timeout(&self) -> bool {
        matches!(self, Error::Timeout | Error::Aborted { code: 0x0504_0000, by_server: false })
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Io(e) => write!(f, "{e}"),
            Error::Aborted { code, by_server } => {
                let who = if *by_server { "the server" } else { "the master" };
                write!(f, "SDO aborted by {who}: {:04X} {:04X}h: ", code >> 16, code & 0xFFFF)?;
                f.write_str(abort_meaning(*code).unwrap_or("unknown abort code"))
            }
            Error::Timeout => f.write_str("no answer in time"),
            Error::TypeMismatch { expected, got } => {
                write!(f, "the value has {got} bytes, the type asked for has {expected}")
            }
            Error::InvalidArgument(what) | Error::Protocol(what) => f.write_str(what),
            Error::Closed(why) => write!(f, "the master's receive task stopped: {why}"),
            Error::Interrupted(why) => write!(f, "transfer interrupted: {why}"),
        }
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Io(e) => Some(e),
            _ => None,
        }
    }
}

impl From<io::Error> for Error {
    fn from(e: io::Error) -> Self {
        Error::Io(e)
    }
}

impl From<ClientError> for Error {
    fn from(e: ClientError) -> Self {
        match e {
            ClientError::Server(code) => Error::Aborted { code, by_server: true },
            ClientError::Local(code) => Error::Aborted { code: code.code(), by_server: false },
        }
    }
}

/// The meaning of an SDO abort code, as CiA 301 Table 22 words it (ABORT-01..ABORT-31); `None` for a code
/// the table does not define.
///
/// ```
/// assert_eq!(canopen_master::abort_meaning(0x0504_0000), Some("SDO protocol timed out"));
/// assert_eq!(canopen_master::abort_meaning(0x1234_5678), None);
/// ```
pub fn abort_meaning(code: u32) -> Option<&'static str> {
    Some(match code {
        0x0503_0000 => "toggle bit not alternated",
        0x0504_0000 => "SDO protocol timed out",
        0x0504_0001 => "client/server command specifier not valid or unknown",
        0x0504_0002 => "invalid block size (block mode only)",
        0x0504_0003 => "invalid sequence number (block mode only)",
        0x0504_0004 => "CRC error (block mode only)",
        0x0504_0005 => "out of memory",
        0x0601_0000 => "unsupported access to an object",
        0x0601_0001 => "attempt to read a write only object",
        0x0601_0002 => "attempt to write a read only object",
        0x0602_0000 => "object does not exist in the object dictionary",
        0x0604_0041 => "object cannot be mapped to the PDO",
        0x0604_0042 => "the number and length of the objects to be mapped would exceed the PDO length",
        0x0604_0043 => "general parameter incompatibility",
        0x0604_0047 => "general internal incompatibility in the device",
        0x0606_0000 => "access failed due to a hardware error",
        0x0607_0010 => "data type does not match, length of service parameter does not match",
        0x0607_0012 => "data type does not match, length of service parameter too high",
        0x0607_0013 => "data type does not match, length of service parameter too low",
        0x0609_0011 => "sub-index does not exist",
        0x0609_0030 => "invalid value for parameter (download only)",
        0x0609_0031 => "value of parameter written too high (download only)",
        0x0609_0032 => "value of parameter written too low (download only)",
        0x0609_0036 => "maximum value is less than minimum value",
        0x060A_0023 => "resource not available: SDO connection",
        0x0800_0000 => "general error",
        0x0800_0020 => "data cannot be transferred or stored to the application",
        0x0800_0021 => "data cannot be transferred or stored to the application because of local control",
        0x0800_0022 => "data cannot be transferred or stored to the application because of the present device state",
        0x0800_0023 => "object dictionary dynamic generation fails or no object dictionary is present",
        0x0800_0024 => "no data available",
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use canopen_core::abort::AbortCode;

    /// Every code of Table 22 the core defines has a meaning (ABORT-01..ABORT-31), and only those.
    #[test]
    fn every_abort_code_has_its_meaning() {
        for a in AbortCode::ALL {
            assert!(abort_meaning(a.code()).is_some(), "{a}");
        }
        assert_eq!(abort_meaning(0), None);
        let e: Error = ClientError::Local(AbortCode::SdoTimeout).into();
        assert!(e.is_timeout());
        assert_eq!(e.to_string(), "SDO aborted by the master: 0504 0000h: SDO protocol timed out");
    }
}
