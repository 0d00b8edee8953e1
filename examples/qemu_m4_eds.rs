//! Writes the EDS of the QEMU Cortex-M4 firmware's node (`examples/qemu-m4`, its dictionary in
//! `examples/qemu-m4/src/device.rs`, included here so host and firmware share one definition) to stdout or
//! to the file given: `cargo run --example qemu_m4_eds -- qemu-m4.eds`. `scripts/test-qemu.sh` loads it into
//! python canopen.

#[path = "qemu-m4/src/device.rs"]
#[allow(dead_code)] // NODE_ID is the firmware's
mod device;
#[path = "common/eds_file.rs"]
mod eds_file;

use canopen_core::node::SdoRecordsDesc;
use canopen_core::od::Merged;
use canopen_core::profile::eds::EdsInfo;
use canopen_core::profile::CommProfile;

const HELP: &str = "qemu_m4_eds: writes the EDS (CiA 306 electronic data sheet) of the node that \
examples/qemu-m4 runs on QEMU's mps2-an386, for a CANopen master such as python canopen.

Usage: qemu_m4_eds [FILE]    (stdout without FILE)
Example: cargo run --example qemu_m4_eds -- qemu-m4.eds";

fn main() {
    let info = EdsInfo {
        file_name: "qemu-m4.eds",
        description: "canopener node on QEMU mps2-an386 (Cortex-M4), slcan on UART0",
        vendor_name: "canopener",
        product_name: "QEMU AN386 node",
        order_code: "QEMU-M4",
        ..EdsInfo::DEFAULT
    };
    eds_file::run(HELP, &info, || {
        let mut comm = CommProfile::<device::NodeSizes>::new(device::CONFIG);
        comm.storage_supported = true; // the firmware saves to RAM (1010h/1011h)
        SdoRecordsDesc::of::<device::NodeSizes>(Merged { comm, app: device::Device::new() })
    });
}
