//! The default PDOs of the firmware's I/O node: what each RPDO and TPDO maps and when it is applied or sent.
//! One definition for every build of that node, each including this file with `#[path]`: `node` and `minimal`
//! here (`minimal` has a TPDO 4 of its own, without the time of day) and the same node on QEMU
//! (`examples/qemu-m4/src/device.rs`, which the host example `qemu_m4_eds` includes in turn). Plain
//! `canopen_core`, so it builds wherever they do.

use canopen_core::pdo::PdoDefault;

/// RPDO 1 (201h + node): 6200h:01, the outputs, applied at reception (FFh).
pub const RPDO1: PdoDefault = PdoDefault { transmission_type: 255, mapping: &[0x6200_0108], ..PdoDefault::EVENT };
/// RPDO 2: 2001h set-point.
pub const RPDO2: PdoDefault = PdoDefault { transmission_type: 255, mapping: &[0x2001_0010], ..PdoDefault::EVENT };
/// RPDO 3: outputs, set-point and blink period, applied at the next SYNC (synchronous, 01h).
pub const RPDO3: PdoDefault =
    PdoDefault { transmission_type: 1, mapping: &[0x6200_0108, 0x2001_0010, 0x2002_0010], ..PdoDefault::EVENT };
/// RPDO 4: blink period; not valid until a master enables it (1403h sub 01h bit 31).
pub const RPDO4: PdoDefault = PdoDefault { mapping: &[0x2002_0010], ..PdoDefault::UNUSED };
/// TPDO 1 (181h + node): the inputs, event-driven (FEh): triggered by the process task on a change.
pub const TPDO1: PdoDefault = PdoDefault { mapping: &[0x6000_0108], ..PdoDefault::EVENT };
/// TPDO 2: uptime and button presses, every second (event timer).
pub const TPDO2: PdoDefault =
    PdoDefault { event_timer_ms: 1000, mapping: &[0x2100_0020, 0x2101_0010], ..PdoDefault::EVENT };
/// TPDO 3: inputs, presses and the set-point in force, at every SYNC (01h).
pub const TPDO3: PdoDefault =
    PdoDefault { transmission_type: 1, mapping: &[0x6000_0108, 0x2101_0010, 0x2001_0010], ..PdoDefault::EVENT };
/// TPDO 4: time of day (2102h, from the TIME consumer) and uptime, every 10th SYNC.
pub const TPDO4: PdoDefault =
    PdoDefault { transmission_type: 10, mapping: &[0x2102_0020, 0x2100_0020], ..PdoDefault::EVENT };
