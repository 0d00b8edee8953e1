//! Writes the EDS of the all-types test dictionary (comm profile + application, and the SDO records of two
//! additional servers 1201h/1202h and one client record 1280h) to stdout or to the file given as the first
//! argument: `cargo run --example write_eds -- out.eds`.

#[path = "../tests/common/all_types.rs"]
mod all_types;
#[path = "common/eds_file.rs"]
mod eds_file;

use canopen_core::node::{SdoRecordsDesc, WithSdoServers};
use canopen_core::profile::eds::EdsInfo;
use canopen_core::Sizes;

const HELP: &str = "write_eds: writes the EDS (CiA 306 electronic data sheet) of the all-types test device, \
the file a CANopen master or configuration tool loads to know the device's objects.

Usage: write_eds [FILE]    (stdout without FILE)
Example: cargo run --example write_eds -- all_types.eds";

fn main() {
    let info = EdsInfo {
        file_name: "all_types.eds",
        description: "canopener test device with every data type",
        vendor_name: "canopener",
        product_name: "All types",
        order_code: "AT-1",
        ..EdsInfo::DEFAULT
    };
    // The records a node of these sizes serves: 1200h, 1201h, 1202h and 1280h (tests/python/test_eds.py).
    eds_file::run(HELP, &info, || SdoRecordsDesc::of::<WithSdoServers<Sizes, 2, 1>>(all_types::node_od()));
}
