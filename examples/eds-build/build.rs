//! The dictionary from device.eds: `$OUT_DIR/device.rs`, rewritten when device.eds changes; what it leaves
//! out of the EDS is printed as cargo warnings (this EDS leaves out one object on purpose, 2200h). And the
//! one from axis.eds (plain numbers only) in the least-flash layout, reached by offset: `$OUT_DIR/axis.rs`.
fn main() {
    if let Err(e) = canopen_eds::generate("device.eds") {
        panic!("{e}");
    }
    if let Err(e) = canopen_eds::generate_as("axis.eds", canopen_eds::StructLayout::Zerocopy) {
        panic!("{e}");
    }
}
