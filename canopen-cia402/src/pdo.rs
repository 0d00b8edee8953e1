//! The default PDO mapping of a CiA 402 drive (the "pre-defined" sets drive manuals publish for
//! IEC 61800-7-201 devices, and python canopen's `BaseNode402` looks for): RPDO1 controlword; RPDO2
//! controlword + modes of operation; RPDO3 controlword + target position; RPDO4 controlword + target
//! velocity; TPDO1 statusword; TPDO2 statusword + modes of operation display; TPDO3 statusword + position
//! actual value; TPDO4 statusword + velocity actual value. Pre-defined COB-IDs, event-driven (FFh).
//!
//! The TPDOs after the first carry values that change while the axis moves: a 10 ms inhibit time spaces
//! them. Each TPDO has an event timer (TPDO1/2 50 ms, TPDO3/4 100 ms): python canopen takes a PDO received
//! twice for a periodic one (`PdoBase.period`) and then waits at most 0.2 s for the next statusword
//! (`BaseNode402.check_statusword`), so a drive that sent only on change would time out there while it
//! stands still.

use canopen_core::pdo::PdoDefault;

const CW: u32 = 0x6040_0010;
const SW: u32 = 0x6041_0010;
const RPDO1: [u32; 1] = [CW];
const RPDO2: [u32; 2] = [CW, 0x6060_0008];
const RPDO3: [u32; 2] = [CW, 0x607A_0020];
const RPDO4: [u32; 2] = [CW, 0x60FF_0020];
const TPDO1: [u32; 1] = [SW];
const TPDO2: [u32; 2] = [SW, 0x6061_0008];
const TPDO3: [u32; 2] = [SW, 0x6064_0020];
const TPDO4: [u32; 2] = [SW, 0x606C_0020];

/// RPDO1–4 of a drive, for `NodeConfig::rpdo`.
///
/// ```
/// assert_eq!(canopen_cia402::pdo::RPDOS[2].mapping, &[0x6040_0010, 0x607A_0020]);
/// ```
pub const RPDOS: [PdoDefault; 4] = [
    PdoDefault { mapping: &RPDO1, transmission_type: 255, ..PdoDefault::EVENT },
    PdoDefault { mapping: &RPDO2, transmission_type: 255, ..PdoDefault::EVENT },
    PdoDefault { mapping: &RPDO3, transmission_type: 255, ..PdoDefault::EVENT },
    PdoDefault { mapping: &RPDO4, transmission_type: 255, ..PdoDefault::EVENT },
];

/// TPDO1–4 of a drive, for `NodeConfig::tpdo`.
///
/// ```
/// assert_eq!(canopen_cia402::pdo::TPDOS[0].mapping, &[0x6041_0010]);
/// ```
pub const TPDOS: [PdoDefault; 4] = [
    PdoDefault { mapping: &TPDO1, transmission_type: 255, event_timer_ms: 50, ..PdoDefault::EVENT },
    PdoDefault { mapping: &TPDO2, transmission_type: 255, inhibit_100us: 100, event_timer_ms: 50, ..PdoDefault::EVENT },
    PdoDefault {
        mapping: &TPDO3,
        transmission_type: 255,
        inhibit_100us: 100,
        event_timer_ms: 100,
        ..PdoDefault::EVENT
    },
    PdoDefault {
        mapping: &TPDO4,
        transmission_type: 255,
        inhibit_100us: 100,
        event_timer_ms: 100,
        ..PdoDefault::EVENT
    },
];
