//! The dictionary from device.eds: `$OUT_DIR/device.rs`, rewritten when device.eds changes; what it leaves
//! out of the EDS is printed as cargo warnings (this EDS leaves out one object on purpose, 2200h).
fn main() {
    if let Err(e) = canopen_eds::generate("device.eds") {
        panic!("{e}");
    }
}
