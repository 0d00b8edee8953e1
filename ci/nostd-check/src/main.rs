//! Links `canopen-core` into a bare-metal binary; see Cargo.toml.
#![no_std]
#![no_main]

use canopen_core::{comm::NodeConfig, node::NoApplication, CanFrame, Instant, Node, NodeId};
use core::hint::black_box;

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}

/// The entry point the linker looks for; runs the node on frames it cannot predict (black_box).
#[no_mangle]
pub extern "C" fn _start() -> ! {
    let Some(id) = NodeId::new(black_box(5)) else { loop {} };
    let mut node: Node<NoApplication> = Node::new(id, NodeConfig::DEFAULT, NoApplication);
    let mut t = 0u64;
    loop {
        t += black_box(1000);
        let now = Instant::from_micros(t);
        node.handle_timeout(now);
        if let Some(f) = CanFrame::new(black_box(0x000), &black_box([0x01, 0x05])) {
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
