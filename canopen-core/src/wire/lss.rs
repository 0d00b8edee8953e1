//! LSS frames (CiA 305 layer setting services): master → slave requests on 7E5h, slave → master responses
//! on 7E4h. Every LSS frame carries exactly 8 data bytes; byte 0 is the command specifier (cs), multi-byte
//! values are little-endian, reserved bytes are sent as 0 and ignored on receipt.
//!
//! CiA 305 is not reproduced in this repository, so the layouts here come from public sources, cross-checked:
//! python `canopen` 2.4.1 `canopen/lss.py` (the master we interoperate with: command specifiers, byte
//! layouts via `struct.pack('<BIBBB', ...)`), CANopenNode `305/CO_LSS.h` + `CO_LSSslave.c` (command
//! specifiers, error codes, fastscan bit-check/sub/next ranges, bit timing table) and lely-core
//! `src/co/lss.c` (identify remote slave, identify non-configured remote slave, cites CiA 305 v3.0.0 figures).
//!
//! | cs | direction | frame |
//! |----|-----------|-------|
//! | 04h | m→s | switch state global, byte 1 mode (0 waiting, 1 configuration) |
//! | 40h–43h | m→s | switch state selective: vendor-ID, product code, revision, serial (bytes 1–4) |
//! | 44h | s→m | switch state selective response |
//! | 11h | both | configure node-ID: byte 1 node-ID / error code, byte 2 spec. error |
//! | 13h | both | configure bit timing: bytes 1–2 table selector and index / error code and spec. error |
//! | 15h | m→s | activate bit timing: bytes 1–2 switch delay in ms (no response) |
//! | 17h | both | store configuration: response byte 1 error code, byte 2 spec. error |
//! | 46h–4Bh | m→s | identify remote slave: vendor, product, revision low/high, serial low/high |
//! | 4Ch | m→s | identify non-configured remote slave |
//! | 4Fh | s→m | identify slave (answer to 4Bh and to fastscan) |
//! | 50h | s→m | identify non-configured slave (answer to 4Ch) |
//! | 51h | m→s | fastscan: bytes 1–4 IDNumber, 5 BitCheck (0–31 or 80h), 6 LSSSub, 7 LSSNext (0–3) |
//! | 5Ah–5Dh | both | inquire vendor-ID, product code, revision, serial (response: value in bytes 1–4) |
//! | 5Eh | both | inquire node-ID (response: byte 1) |
//!
//! Error codes (byte 1 of 11h/13h/17h responses): 00h success; 01h node-ID out of range / bit timing not
//! supported / store not supported; 02h storage media access error (store only); FFh implementation-specific
//! error, with the specific code in byte 2.

use super::WireError;

/// Length of every LSS frame.
///
/// ```
/// use canopen_core::wire::lss::{LssRequest, LSS_FRAME_LEN};
/// assert_eq!(LssRequest::InquireNodeId.emit().len(), LSS_FRAME_LEN);
/// ```
pub const LSS_FRAME_LEN: usize = 8;

/// Command specifiers (CiA 305; CANopenNode `CO_LSS.h`, python `canopen/lss.py`).
///
/// ```
/// use canopen_core::wire::lss::{cs, LssRequest};
/// assert_eq!(LssRequest::StoreConfiguration.emit()[0], cs::STORE_CONFIGURATION);
/// ```
pub mod cs {
    /// Switch state global.
    ///
    /// ```
    /// assert_eq!(canopen_core::wire::lss::cs::SWITCH_STATE_GLOBAL, 0x04);
    /// ```
    pub const SWITCH_STATE_GLOBAL: u8 = 0x04;
    /// Configure node-ID.
    ///
    /// ```
    /// assert_eq!(canopen_core::wire::lss::cs::CONFIGURE_NODE_ID, 0x11);
    /// ```
    pub const CONFIGURE_NODE_ID: u8 = 0x11;
    /// Configure bit timing parameters.
    ///
    /// ```
    /// assert_eq!(canopen_core::wire::lss::cs::CONFIGURE_BIT_TIMING, 0x13);
    /// ```
    pub const CONFIGURE_BIT_TIMING: u8 = 0x13;
    /// Activate bit timing parameters.
    ///
    /// ```
    /// assert_eq!(canopen_core::wire::lss::cs::ACTIVATE_BIT_TIMING, 0x15);
    /// ```
    pub const ACTIVATE_BIT_TIMING: u8 = 0x15;
    /// Store configuration.
    ///
    /// ```
    /// assert_eq!(canopen_core::wire::lss::cs::STORE_CONFIGURATION, 0x17);
    /// ```
    pub const STORE_CONFIGURATION: u8 = 0x17;
    /// Switch state selective, vendor-ID (first of 40h–43h).
    ///
    /// ```
    /// assert_eq!(canopen_core::wire::lss::cs::SWITCH_STATE_SELECTIVE_VENDOR, 0x40);
    /// ```
    pub const SWITCH_STATE_SELECTIVE_VENDOR: u8 = 0x40;
    /// Switch state selective, serial number (last of 40h–43h).
    ///
    /// ```
    /// assert_eq!(canopen_core::wire::lss::cs::SWITCH_STATE_SELECTIVE_SERIAL, 0x43);
    /// ```
    pub const SWITCH_STATE_SELECTIVE_SERIAL: u8 = 0x43;
    /// Switch state selective response.
    ///
    /// ```
    /// assert_eq!(canopen_core::wire::lss::cs::SWITCH_STATE_SELECTIVE_RESPONSE, 0x44);
    /// ```
    pub const SWITCH_STATE_SELECTIVE_RESPONSE: u8 = 0x44;
    /// Identify remote slave, vendor-ID (first of 46h–4Bh).
    ///
    /// ```
    /// assert_eq!(canopen_core::wire::lss::cs::IDENTIFY_REMOTE_VENDOR, 0x46);
    /// ```
    pub const IDENTIFY_REMOTE_VENDOR: u8 = 0x46;
    /// Identify remote slave, serial number high bound (last of 46h–4Bh).
    ///
    /// ```
    /// assert_eq!(canopen_core::wire::lss::cs::IDENTIFY_REMOTE_SERIAL_HIGH, 0x4B);
    /// ```
    pub const IDENTIFY_REMOTE_SERIAL_HIGH: u8 = 0x4B;
    /// Identify non-configured remote slave.
    ///
    /// ```
    /// assert_eq!(canopen_core::wire::lss::cs::IDENTIFY_NON_CONFIGURED_REMOTE, 0x4C);
    /// ```
    pub const IDENTIFY_NON_CONFIGURED_REMOTE: u8 = 0x4C;
    /// Identify slave (response).
    ///
    /// ```
    /// assert_eq!(canopen_core::wire::lss::cs::IDENTIFY_SLAVE, 0x4F);
    /// ```
    pub const IDENTIFY_SLAVE: u8 = 0x4F;
    /// Identify non-configured slave (response).
    ///
    /// ```
    /// assert_eq!(canopen_core::wire::lss::cs::IDENTIFY_NON_CONFIGURED_SLAVE, 0x50);
    /// ```
    pub const IDENTIFY_NON_CONFIGURED_SLAVE: u8 = 0x50;
    /// Fastscan.
    ///
    /// ```
    /// assert_eq!(canopen_core::wire::lss::cs::FASTSCAN, 0x51);
    /// ```
    pub const FASTSCAN: u8 = 0x51;
    /// Inquire identity vendor-ID (first of 5Ah–5Dh).
    ///
    /// ```
    /// assert_eq!(canopen_core::wire::lss::cs::INQUIRE_VENDOR, 0x5A);
    /// ```
    pub const INQUIRE_VENDOR: u8 = 0x5A;
    /// Inquire node-ID.
    ///
    /// ```
    /// assert_eq!(canopen_core::wire::lss::cs::INQUIRE_NODE_ID, 0x5E);
    /// ```
    pub const INQUIRE_NODE_ID: u8 = 0x5E;
}

/// Fastscan BitCheck value that resets the scan: every non-configured slave in LSS waiting answers.
///
/// ```
/// use canopen_core::wire::lss::{LssRequest, FASTSCAN_CONFIRM};
/// let f = [0x51, 0, 0, 0, 0, FASTSCAN_CONFIRM, 0, 0];
/// assert!(matches!(LssRequest::parse(&f), Ok(LssRequest::Fastscan { bit_check: 0x80, .. })));
/// ```
pub const FASTSCAN_CONFIRM: u8 = 0x80;

/// The node-ID value that means "not configured" (CiA 305).
///
/// ```
/// use canopen_core::wire::lss::{LssResponse, UNCONFIGURED_NODE_ID};
/// assert_eq!(LssResponse::NodeId(UNCONFIGURED_NODE_ID).emit()[1], 0xFF);
/// ```
pub const UNCONFIGURED_NODE_ID: u8 = 0xFF;

/// The LSS slave states (CiA 305 LSS FSA).
///
/// ```
/// use canopen_core::wire::lss::LssMode;
/// assert_eq!(LssMode::from_u8(1), Some(LssMode::Configuration));
/// assert_eq!(LssMode::Waiting as u8, 0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u8)]
pub enum LssMode {
    /// LSS waiting: only switch, identify and fastscan are served.
    Waiting = 0,
    /// LSS configuration: node-ID, bit timing, store and inquire are served.
    Configuration = 1,
}

impl LssMode {
    /// The mode for a mode byte, `None` if undefined.
    ///
    /// ```
    /// use canopen_core::wire::lss::LssMode;
    /// assert_eq!(LssMode::from_u8(2), None);
    /// ```
    pub const fn from_u8(v: u8) -> Option<Self> {
        match v {
            0 => Some(LssMode::Waiting),
            1 => Some(LssMode::Configuration),
            _ => None,
        }
    }
}

/// One of the four 32-bit parts of the LSS address (= 1018h sub 1–4), in fastscan LSSSub order.
///
/// ```
/// use canopen_core::wire::lss::IdentityField;
/// assert_eq!(IdentityField::from_index(3), Some(IdentityField::Serial));
/// assert_eq!(IdentityField::ProductCode.index(), 1);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum IdentityField {
    /// 1018h:01 vendor-ID.
    VendorId = 0,
    /// 1018h:02 product code.
    ProductCode = 1,
    /// 1018h:03 revision number.
    Revision = 2,
    /// 1018h:04 serial number.
    Serial = 3,
}

impl IdentityField {
    /// All four, in order.
    ///
    /// ```
    /// use canopen_core::wire::lss::IdentityField;
    /// assert_eq!(IdentityField::ALL[3], IdentityField::Serial);
    /// ```
    pub const ALL: [IdentityField; 4] =
        [IdentityField::VendorId, IdentityField::ProductCode, IdentityField::Revision, IdentityField::Serial];

    /// The field for an index 0–3 (fastscan LSSSub/LSSNext), `None` otherwise.
    ///
    /// ```
    /// use canopen_core::wire::lss::IdentityField;
    /// assert_eq!(IdentityField::from_index(4), None);
    /// assert_eq!(IdentityField::Serial.index(), 3);
    /// ```
    pub const fn from_index(i: u8) -> Option<Self> {
        match i {
            0 => Some(IdentityField::VendorId),
            1 => Some(IdentityField::ProductCode),
            2 => Some(IdentityField::Revision),
            3 => Some(IdentityField::Serial),
            _ => None,
        }
    }

    /// The index 0–3.
    ///
    /// ```
    /// use canopen_core::wire::lss::IdentityField;
    /// assert_eq!(IdentityField::from_index(4), None);
    /// assert_eq!(IdentityField::Serial.index(), 3);
    /// ```
    pub const fn index(self) -> u8 {
        self as u8
    }
}

/// The parts of the identify-remote-slave request sequence (46h–4Bh).
///
/// ```
/// use canopen_core::wire::lss::IdentifyPart;
/// assert_eq!(IdentifyPart::SerialHigh.cs(), 0x4B);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum IdentifyPart {
    /// 46h: vendor-ID (exact).
    VendorId = 0x46,
    /// 47h: product code (exact).
    ProductCode = 0x47,
    /// 48h: revision number, low bound.
    RevisionLow = 0x48,
    /// 49h: revision number, high bound.
    RevisionHigh = 0x49,
    /// 4Ah: serial number, low bound.
    SerialLow = 0x4A,
    /// 4Bh: serial number, high bound (the slaves answer after this one).
    SerialHigh = 0x4B,
}

impl IdentifyPart {
    /// The command specifier.
    ///
    /// ```
    /// use canopen_core::wire::lss::IdentifyPart;
    /// assert_eq!(IdentifyPart::VendorId.cs(), 0x46);
    /// ```
    pub const fn cs(self) -> u8 {
        self as u8
    }

    /// The part for a command specifier 46h–4Bh.
    ///
    /// ```
    /// use canopen_core::wire::lss::IdentifyPart;
    /// assert_eq!(IdentifyPart::from_cs(0x48), Some(IdentifyPart::RevisionLow));
    /// assert_eq!(IdentifyPart::from_cs(0x4C), None);
    /// ```
    pub const fn from_cs(cs: u8) -> Option<Self> {
        Some(match cs {
            0x46 => IdentifyPart::VendorId,
            0x47 => IdentifyPart::ProductCode,
            0x48 => IdentifyPart::RevisionLow,
            0x49 => IdentifyPart::RevisionHigh,
            0x4A => IdentifyPart::SerialLow,
            0x4B => IdentifyPart::SerialHigh,
            _ => return None,
        })
    }
}

/// The CiA 301 bit timing table used by LSS configure bit timing with table selector 0.
///
/// Index 5 is reserved in CiA 305 (CANopenNode `CO_LSS.h`, and CiA 301 Table 1 lists no 100 kbit/s);
/// python `canopen`'s docstring calls it 100 kbit/s, but this slave refuses it with error 01h. Index 9 is
/// automatic bit rate detection.
///
/// ```
/// use canopen_core::wire::lss::BitRate;
/// assert_eq!(BitRate::from_index(2), Some(BitRate::K500));
/// assert_eq!(BitRate::K500.kbit_per_s(), Some(500));
/// assert_eq!(BitRate::from_index(5), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u8)]
pub enum BitRate {
    /// 1000 kbit/s.
    K1000 = 0,
    /// 800 kbit/s.
    K800 = 1,
    /// 500 kbit/s.
    K500 = 2,
    /// 250 kbit/s.
    K250 = 3,
    /// 125 kbit/s.
    K125 = 4,
    /// 50 kbit/s.
    K50 = 6,
    /// 20 kbit/s.
    K20 = 7,
    /// 10 kbit/s.
    K10 = 8,
    /// Automatic bit rate detection.
    Auto = 9,
}

impl BitRate {
    /// The entry for a table index, `None` for reserved or undefined indices.
    ///
    /// ```
    /// use canopen_core::wire::lss::BitRate;
    /// assert_eq!(BitRate::from_index(4).map(BitRate::index), Some(4));
    /// ```
    pub const fn from_index(i: u8) -> Option<Self> {
        Some(match i {
            0 => BitRate::K1000,
            1 => BitRate::K800,
            2 => BitRate::K500,
            3 => BitRate::K250,
            4 => BitRate::K125,
            6 => BitRate::K50,
            7 => BitRate::K20,
            8 => BitRate::K10,
            9 => BitRate::Auto,
            _ => return None,
        })
    }

    /// The table index.
    ///
    /// ```
    /// use canopen_core::wire::lss::BitRate;
    /// assert_eq!(BitRate::from_index(4).map(BitRate::index), Some(4));
    /// ```
    pub const fn index(self) -> u8 {
        self as u8
    }

    /// The bit rate in kbit/s, `None` for automatic detection.
    ///
    /// ```
    /// use canopen_core::wire::lss::BitRate;
    /// assert_eq!(BitRate::K10.kbit_per_s(), Some(10));
    /// assert_eq!(BitRate::Auto.kbit_per_s(), None);
    /// ```
    pub const fn kbit_per_s(self) -> Option<u16> {
        Some(match self {
            BitRate::K1000 => 1000,
            BitRate::K800 => 800,
            BitRate::K500 => 500,
            BitRate::K250 => 250,
            BitRate::K125 => 125,
            BitRate::K50 => 50,
            BitRate::K20 => 20,
            BitRate::K10 => 10,
            BitRate::Auto => return None,
        })
    }
}

/// Error code and implementation-specific error of a configure/store response.
///
/// ```
/// use canopen_core::wire::lss::Status;
/// assert!(Status::SUCCESS.is_success());
/// assert_eq!(Status::manufacturer(7), Status { error: 0xFF, spec: 7 });
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Status {
    /// 00h success, 01h/02h as the service defines, FFh implementation-specific.
    pub error: u8,
    /// The implementation-specific error when `error` is FFh, else 0.
    pub spec: u8,
}

impl Status {
    /// 00h: protocol successfully completed.
    ///
    /// ```
    /// use canopen_core::wire::lss::Status;
    /// assert!(Status::SUCCESS.is_success());
    /// ```
    pub const SUCCESS: Status = Status { error: 0, spec: 0 };
    /// 01h: node-ID out of range (11h), bit timing not supported (13h), store not supported (17h).
    ///
    /// ```
    /// use canopen_core::wire::lss::Status;
    /// assert_eq!(Status::NOT_SUPPORTED.error, 1);
    /// ```
    pub const NOT_SUPPORTED: Status = Status { error: 1, spec: 0 };
    /// 02h: storage media access error (17h).
    ///
    /// ```
    /// use canopen_core::wire::lss::Status;
    /// assert_eq!(Status::MEDIA_ACCESS.error, 2);
    /// ```
    pub const MEDIA_ACCESS: Status = Status { error: 2, spec: 0 };

    /// FFh with an implementation-specific error code.
    ///
    /// ```
    /// use canopen_core::wire::lss::Status;
    /// assert_eq!(Status::manufacturer(1).error, 0xFF);
    /// ```
    pub const fn manufacturer(spec: u8) -> Self {
        Status { error: 0xFF, spec }
    }

    /// Whether this is success.
    ///
    /// ```
    /// use canopen_core::wire::lss::Status;
    /// assert!(!Status::NOT_SUPPORTED.is_success());
    /// ```
    pub const fn is_success(self) -> bool {
        self.error == 0
    }
}

/// A master → slave request (7E5h).
///
/// ```
/// use canopen_core::wire::lss::{LssMode, LssRequest};
/// let r = LssRequest::parse(&[0x04, 0x01, 0, 0, 0, 0, 0, 0]).unwrap();
/// assert_eq!(r, LssRequest::SwitchStateGlobal(LssMode::Configuration));
/// assert_eq!(LssRequest::ConfigureNodeId(0x22).emit(), [0x11, 0x22, 0, 0, 0, 0, 0, 0]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LssRequest {
    /// 04h: every slave enters the given state.
    SwitchStateGlobal(LssMode),
    /// 40h–43h: one part of the LSS address; the slave whose address matches all four enters configuration.
    SwitchStateSelective(IdentityField, u32),
    /// 11h: configure the pending node-ID (1–127, or FFh = unconfigured).
    ConfigureNodeId(u8),
    /// 13h: configure the pending bit timing from a table.
    ConfigureBitTiming {
        /// 0 = the CiA 301 table ([`BitRate`]); 1–127 reserved; 128–255 manufacturer-specific.
        table_selector: u8,
        /// Index into the table.
        table_index: u8,
    },
    /// 15h: activate the pending bit timing after the switch delay.
    ActivateBitTiming {
        /// Length of each of the two delay periods, in ms.
        switch_delay_ms: u16,
    },
    /// 17h: store the pending node-ID and bit timing in non-volatile memory.
    StoreConfiguration,
    /// 46h–4Bh: identify remote slave, one part of the address range.
    IdentifyRemoteSlave(IdentifyPart, u32),
    /// 4Ch: every slave without a node-ID answers 50h.
    IdentifyNonConfiguredRemoteSlave,
    /// 51h: one fastscan step.
    Fastscan {
        /// The part of the LSS address under test.
        id_number: u32,
        /// The lowest bit compared (bits 31..bit_check), 0–31; or 80h to reset the scan.
        bit_check: u8,
        /// Which LSS address part is compared.
        lss_sub: IdentityField,
        /// The part a matching slave compares next.
        lss_next: IdentityField,
    },
    /// 5Ah–5Dh: inquire one part of the LSS address.
    Inquire(IdentityField),
    /// 5Eh: inquire the active node-ID.
    InquireNodeId,
}

fn u32_at(data: &[u8; 8]) -> u32 {
    u32::from_le_bytes([data[1], data[2], data[3], data[4]])
}

fn frame(cs: u8) -> [u8; 8] {
    let mut f = [0u8; 8];
    f[0] = cs;
    f
}

pub(crate) fn frame_u32(cs: u8, v: u32) -> [u8; 8] {
    let mut f = frame(cs);
    f[1..5].copy_from_slice(&v.to_le_bytes());
    f
}

fn eight(data: &[u8]) -> Result<&[u8; 8], WireError> {
    data.try_into().map_err(|_| WireError::Length)
}

impl LssRequest {
    /// Parses an 8-byte request; any other length, an unknown command specifier or an out-of-range field
    /// (mode, fastscan BitCheck/LSSSub/LSSNext) is an error, which the slave ignores (CAN-07).
    ///
    /// ```
    /// use canopen_core::wire::lss::{LssRequest, IdentityField};
    /// assert_eq!(LssRequest::parse(&[0x5D, 0, 0, 0, 0, 0, 0, 0]), Ok(LssRequest::Inquire(IdentityField::Serial)));
    /// assert!(LssRequest::parse(&[0x5D]).is_err());
    /// ```
    pub fn parse(data: &[u8]) -> Result<Self, WireError> {
        let d = eight(data)?;
        Ok(match d[0] {
            cs::SWITCH_STATE_GLOBAL => LssRequest::SwitchStateGlobal(LssMode::from_u8(d[1]).ok_or(WireError::Value)?),
            c @ 0x40..=0x43 => LssRequest::SwitchStateSelective(
                IdentityField::from_index(c - 0x40).ok_or(WireError::Value)?,
                u32_at(d),
            ),
            cs::CONFIGURE_NODE_ID => LssRequest::ConfigureNodeId(d[1]),
            cs::CONFIGURE_BIT_TIMING => LssRequest::ConfigureBitTiming { table_selector: d[1], table_index: d[2] },
            cs::ACTIVATE_BIT_TIMING => {
                LssRequest::ActivateBitTiming { switch_delay_ms: u16::from_le_bytes([d[1], d[2]]) }
            }
            cs::STORE_CONFIGURATION => LssRequest::StoreConfiguration,
            c @ 0x46..=0x4B => {
                LssRequest::IdentifyRemoteSlave(IdentifyPart::from_cs(c).ok_or(WireError::Value)?, u32_at(d))
            }
            cs::IDENTIFY_NON_CONFIGURED_REMOTE => LssRequest::IdentifyNonConfiguredRemoteSlave,
            cs::FASTSCAN => {
                let bit_check = d[5];
                if bit_check > 31 && bit_check != FASTSCAN_CONFIRM {
                    return Err(WireError::Value);
                }
                LssRequest::Fastscan {
                    id_number: u32_at(d),
                    bit_check,
                    lss_sub: IdentityField::from_index(d[6]).ok_or(WireError::Value)?,
                    lss_next: IdentityField::from_index(d[7]).ok_or(WireError::Value)?,
                }
            }
            c @ 0x5A..=0x5D => LssRequest::Inquire(IdentityField::from_index(c - 0x5A).ok_or(WireError::Value)?),
            cs::INQUIRE_NODE_ID => LssRequest::InquireNodeId,
            _ => return Err(WireError::Value),
        })
    }

    /// The 8 data bytes (reserved bytes 0).
    ///
    /// ```
    /// use canopen_core::wire::lss::{LssRequest, BitRate};
    /// let r = LssRequest::ConfigureBitTiming { table_selector: 0, table_index: BitRate::K250.index() };
    /// assert_eq!(r.emit(), [0x13, 0, 3, 0, 0, 0, 0, 0]);
    /// ```
    pub fn emit(&self) -> [u8; 8] {
        match *self {
            LssRequest::SwitchStateGlobal(mode) => {
                let mut f = frame(cs::SWITCH_STATE_GLOBAL);
                f[1] = mode as u8;
                f
            }
            LssRequest::SwitchStateSelective(field, v) => frame_u32(0x40 + field.index(), v),
            LssRequest::ConfigureNodeId(id) => {
                let mut f = frame(cs::CONFIGURE_NODE_ID);
                f[1] = id;
                f
            }
            LssRequest::ConfigureBitTiming { table_selector, table_index } => {
                let mut f = frame(cs::CONFIGURE_BIT_TIMING);
                f[1] = table_selector;
                f[2] = table_index;
                f
            }
            LssRequest::ActivateBitTiming { switch_delay_ms } => {
                let mut f = frame(cs::ACTIVATE_BIT_TIMING);
                f[1..3].copy_from_slice(&switch_delay_ms.to_le_bytes());
                f
            }
            LssRequest::StoreConfiguration => frame(cs::STORE_CONFIGURATION),
            LssRequest::IdentifyRemoteSlave(part, v) => frame_u32(part.cs(), v),
            LssRequest::IdentifyNonConfiguredRemoteSlave => frame(cs::IDENTIFY_NON_CONFIGURED_REMOTE),
            LssRequest::Fastscan { id_number, bit_check, lss_sub, lss_next } => {
                let mut f = frame_u32(cs::FASTSCAN, id_number);
                f[5] = bit_check;
                f[6] = lss_sub.index();
                f[7] = lss_next.index();
                f
            }
            LssRequest::Inquire(field) => frame(cs::INQUIRE_VENDOR + field.index()),
            LssRequest::InquireNodeId => frame(cs::INQUIRE_NODE_ID),
        }
    }
}

/// A slave → master response (7E4h).
///
/// ```
/// use canopen_core::wire::lss::{IdentityField, LssResponse, Status};
/// assert_eq!(LssResponse::NodeIdConfigured(Status::SUCCESS).emit(), [0x11, 0, 0, 0, 0, 0, 0, 0]);
/// let r = LssResponse::parse(&[0x5D, 0x2A, 0, 0, 0, 0, 0, 0]).unwrap();
/// assert_eq!(r, LssResponse::Identity(IdentityField::Serial, 42));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LssResponse {
    /// 44h: this slave entered LSS configuration by switch state selective.
    SwitchStateSelective,
    /// 11h: configure node-ID result.
    NodeIdConfigured(Status),
    /// 13h: configure bit timing result.
    BitTimingConfigured(Status),
    /// 17h: store configuration result.
    Stored(Status),
    /// 4Fh: identify slave (identify remote slave match, fastscan match).
    IdentifySlave,
    /// 50h: identify non-configured slave.
    IdentifyNonConfiguredSlave,
    /// 5Ah–5Dh: one part of the LSS address.
    Identity(IdentityField, u32),
    /// 5Eh: the active node-ID (FFh if none).
    NodeId(u8),
}

impl LssResponse {
    /// Parses an 8-byte response; other lengths and unknown command specifiers are errors.
    ///
    /// ```
    /// use canopen_core::wire::lss::{LssResponse, Status};
    /// assert_eq!(LssResponse::parse(&[0x17, 2, 0, 0, 0, 0, 0, 0]), Ok(LssResponse::Stored(Status::MEDIA_ACCESS)));
    /// ```
    pub fn parse(data: &[u8]) -> Result<Self, WireError> {
        let d = eight(data)?;
        let status = Status { error: d[1], spec: d[2] };
        Ok(match d[0] {
            cs::SWITCH_STATE_SELECTIVE_RESPONSE => LssResponse::SwitchStateSelective,
            cs::CONFIGURE_NODE_ID => LssResponse::NodeIdConfigured(status),
            cs::CONFIGURE_BIT_TIMING => LssResponse::BitTimingConfigured(status),
            cs::STORE_CONFIGURATION => LssResponse::Stored(status),
            cs::IDENTIFY_SLAVE => LssResponse::IdentifySlave,
            cs::IDENTIFY_NON_CONFIGURED_SLAVE => LssResponse::IdentifyNonConfiguredSlave,
            c @ 0x5A..=0x5D => {
                LssResponse::Identity(IdentityField::from_index(c - 0x5A).ok_or(WireError::Value)?, u32_at(d))
            }
            cs::INQUIRE_NODE_ID => LssResponse::NodeId(d[1]),
            _ => return Err(WireError::Value),
        })
    }

    /// The 8 data bytes (reserved bytes 0).
    ///
    /// ```
    /// use canopen_core::wire::lss::LssResponse;
    /// assert_eq!(LssResponse::SwitchStateSelective.emit(), [0x44, 0, 0, 0, 0, 0, 0, 0]);
    /// ```
    pub fn emit(&self) -> [u8; 8] {
        // Every response is the command specifier and at most 4 bytes after it: one frame builder for all.
        let status = |s: Status| u32::from(s.error) | u32::from(s.spec) << 8;
        let (cs, value) = match *self {
            LssResponse::SwitchStateSelective => (cs::SWITCH_STATE_SELECTIVE_RESPONSE, 0),
            LssResponse::NodeIdConfigured(s) => (cs::CONFIGURE_NODE_ID, status(s)),
            LssResponse::BitTimingConfigured(s) => (cs::CONFIGURE_BIT_TIMING, status(s)),
            LssResponse::Stored(s) => (cs::STORE_CONFIGURATION, status(s)),
            LssResponse::IdentifySlave => (cs::IDENTIFY_SLAVE, 0),
            LssResponse::IdentifyNonConfiguredSlave => (cs::IDENTIFY_NON_CONFIGURED_SLAVE, 0),
            LssResponse::Identity(field, v) => (cs::INQUIRE_VENDOR + field.index(), v),
            LssResponse::NodeId(id) => (cs::INQUIRE_NODE_ID, u32::from(id)),
        };
        frame_u32(cs, value)
    }

    /// The command specifier of the request this answers (`None` for 4Fh, which answers both 4Bh and 51h).
    ///
    /// ```
    /// use canopen_core::wire::lss::LssResponse;
    /// assert_eq!(LssResponse::SwitchStateSelective.request_cs(), Some(0x43));
    /// ```
    pub const fn request_cs(&self) -> Option<u8> {
        Some(match self {
            LssResponse::SwitchStateSelective => cs::SWITCH_STATE_SELECTIVE_SERIAL,
            LssResponse::NodeIdConfigured(_) => cs::CONFIGURE_NODE_ID,
            LssResponse::BitTimingConfigured(_) => cs::CONFIGURE_BIT_TIMING,
            LssResponse::Stored(_) => cs::STORE_CONFIGURATION,
            LssResponse::IdentifySlave => return None,
            LssResponse::IdentifyNonConfiguredSlave => cs::IDENTIFY_NON_CONFIGURED_REMOTE,
            LssResponse::Identity(field, _) => cs::INQUIRE_VENDOR + field.index(),
            LssResponse::NodeId(_) => cs::INQUIRE_NODE_ID,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Frames as python canopen 2.4.1 builds them (`bytearray(8)`, `struct.pack('<BIBBB', ...)`).
    #[test]
    fn python_canopen_request_bytes() {
        let v = |r: LssRequest| r.emit();
        assert_eq!(v(LssRequest::SwitchStateGlobal(LssMode::Waiting)), [0x04, 0, 0, 0, 0, 0, 0, 0]);
        assert_eq!(v(LssRequest::SwitchStateGlobal(LssMode::Configuration)), [0x04, 1, 0, 0, 0, 0, 0, 0]);
        assert_eq!(
            v(LssRequest::SwitchStateSelective(IdentityField::Serial, 0x1234_5678)),
            [0x43, 0x78, 0x56, 0x34, 0x12, 0, 0, 0]
        );
        assert_eq!(v(LssRequest::ConfigureNodeId(0x22)), [0x11, 0x22, 0, 0, 0, 0, 0, 0]);
        assert_eq!(
            v(LssRequest::ConfigureBitTiming { table_selector: 0, table_index: 3 }),
            [0x13, 0, 3, 0, 0, 0, 0, 0]
        );
        assert_eq!(v(LssRequest::ActivateBitTiming { switch_delay_ms: 0x0102 }), [0x15, 2, 1, 0, 0, 0, 0, 0]);
        assert_eq!(v(LssRequest::StoreConfiguration), [0x17, 0, 0, 0, 0, 0, 0, 0]);
        // python: struct.pack('<BIBBB', 0x51, 0, 128, 0, 0)
        assert_eq!(
            v(LssRequest::Fastscan {
                id_number: 0,
                bit_check: FASTSCAN_CONFIRM,
                lss_sub: IdentityField::VendorId,
                lss_next: IdentityField::VendorId
            }),
            [0x51, 0, 0, 0, 0, 0x80, 0, 0]
        );
        assert_eq!(
            v(LssRequest::Fastscan {
                id_number: 0xA0B0_C0D0,
                bit_check: 0,
                lss_sub: IdentityField::Revision,
                lss_next: IdentityField::Serial
            }),
            [0x51, 0xD0, 0xC0, 0xB0, 0xA0, 0, 2, 3]
        );
        assert_eq!(v(LssRequest::Inquire(IdentityField::VendorId)), [0x5A, 0, 0, 0, 0, 0, 0, 0]);
        assert_eq!(v(LssRequest::InquireNodeId), [0x5E, 0, 0, 0, 0, 0, 0, 0]);
        assert_eq!(v(LssRequest::IdentifyNonConfiguredRemoteSlave), [0x4C, 0, 0, 0, 0, 0, 0, 0]);
        assert_eq!(v(LssRequest::IdentifyRemoteSlave(IdentifyPart::RevisionLow, 7)), [0x48, 7, 0, 0, 0, 0, 0, 0]);
    }

    #[test]
    fn every_valid_request_round_trips() {
        let mut n = 0;
        for c in 0..=255u8 {
            for b1 in [0u8, 1, 2, 0x7F, 0x80, 0xFF] {
                for tail in [[0u8, 0, 0, 0, 0, 0], [1, 2, 3, 31, 3, 0], [9, 9, 9, 0x80, 1, 2], [0, 0, 0, 32, 0, 0]] {
                    let mut d = [c, b1, 0, 0, 0, 0, 0, 0];
                    d[2..].copy_from_slice(&tail);
                    if let Ok(r) = LssRequest::parse(&d) {
                        n += 1;
                        let again = LssRequest::parse(&r.emit()).unwrap();
                        assert_eq!(again, r, "{d:02X?}");
                    }
                }
            }
        }
        assert!(n > 100);
    }

    #[test]
    fn malformed_requests_are_errors() {
        assert_eq!(LssRequest::parse(&[0x04, 0]), Err(WireError::Length));
        assert_eq!(LssRequest::parse(&[0x04, 0, 0, 0, 0, 0, 0, 0, 0]), Err(WireError::Length));
        assert_eq!(LssRequest::parse(&[]), Err(WireError::Length));
        assert_eq!(LssRequest::parse(&[0x04, 2, 0, 0, 0, 0, 0, 0]), Err(WireError::Value));
        assert_eq!(LssRequest::parse(&[0x51, 0, 0, 0, 0, 32, 0, 0]), Err(WireError::Value));
        assert_eq!(LssRequest::parse(&[0x51, 0, 0, 0, 0, 0x81, 0, 0]), Err(WireError::Value));
        assert_eq!(LssRequest::parse(&[0x51, 0, 0, 0, 0, 0, 4, 0]), Err(WireError::Value));
        assert_eq!(LssRequest::parse(&[0x51, 0, 0, 0, 0, 0, 0, 4]), Err(WireError::Value));
        // Responses and undefined specifiers are not requests.
        for c in [0x00u8, 0x44, 0x45, 0x4D, 0x4E, 0x4F, 0x50, 0x5F, 0xFF] {
            assert_eq!(LssRequest::parse(&[c, 0, 0, 0, 0, 0, 0, 0]), Err(WireError::Value), "{c:02X}");
        }
    }

    #[test]
    fn responses_round_trip() {
        let all = [
            LssResponse::SwitchStateSelective,
            LssResponse::NodeIdConfigured(Status::NOT_SUPPORTED),
            LssResponse::BitTimingConfigured(Status::manufacturer(9)),
            LssResponse::Stored(Status::MEDIA_ACCESS),
            LssResponse::IdentifySlave,
            LssResponse::IdentifyNonConfiguredSlave,
            LssResponse::Identity(IdentityField::Revision, 0x0001_0002),
            LssResponse::NodeId(0xFF),
        ];
        for r in all {
            assert_eq!(LssResponse::parse(&r.emit()), Ok(r));
        }
        assert_eq!(LssResponse::Stored(Status::MEDIA_ACCESS).emit(), [0x17, 2, 0, 0, 0, 0, 0, 0]);
        assert_eq!(LssResponse::IdentifySlave.emit(), [0x4F, 0, 0, 0, 0, 0, 0, 0]);
        assert_eq!(LssResponse::parse(&[0x4F]), Err(WireError::Length));
        assert_eq!(LssResponse::parse(&[0x51, 0, 0, 0, 0, 0, 0, 0]), Err(WireError::Value));
    }

    #[test]
    fn bit_rate_table() {
        let kbit: [Option<u16>; 10] =
            [Some(1000), Some(800), Some(500), Some(250), Some(125), None, Some(50), Some(20), Some(10), None];
        for (i, k) in kbit.iter().enumerate() {
            let r = BitRate::from_index(i as u8);
            assert_eq!(r.and_then(BitRate::kbit_per_s), *k);
            if let Some(r) = r {
                assert_eq!(r.index(), i as u8);
            }
        }
        assert_eq!(BitRate::from_index(9), Some(BitRate::Auto));
        assert_eq!(BitRate::from_index(10), None);
    }
}
