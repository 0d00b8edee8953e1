//! A node whose application dictionary is `Dict` (build.rs), on frames the optimizer cannot predict, so
//! that every SDO, PDO and store path of the dictionary is linked; see Cargo.toml. The node is a `static`
//! (in .bss), as in a firmware (examples/firmware): on the stack, a node of more than 4 KiB made every
//! access past it an address computation more, which grew with the dictionary and is no cost of a firmware.
#![no_std]
#![no_main]

use canopen_core::{profile::NodeConfig, CanFrame, Instant, Node, NodeId};
use core::hint::black_box;

#[allow(unused_imports, dead_code, clippy::all)]
mod dict {
    include!(concat!(env!("OUT_DIR"), "/dict.rs"));
}
use dict::Dict;

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}

/// The entry point the linker looks for.
#[no_mangle]
pub extern "C" fn _start() -> ! {
    let Some(id) = NodeId::new(black_box(5)) else { loop {} };
    static NODE: static_cell::StaticCell<Node<Dict>> = static_cell::StaticCell::new();
    let node = NODE.init(Node::new(id, NodeConfig::DEFAULT, black_box(Dict::default())));
    let mut t = 0u64;
    loop {
        t += black_box(1000);
        let now = Instant::from_micros(t);
        node.handle_timeout(now);
        let id = black_box(0x605);
        if let Some(f) = CanFrame::new(id, &black_box([0x40, 0x00, 0x20, 0x00, 0, 0, 0, 0])) {
            node.handle_frame(now, &f);
        }
        while let Some(f) = node.poll_transmit() {
            black_box(f);
        }
        while let Some(e) = node.poll_event() {
            black_box(e);
        }
    }
}
