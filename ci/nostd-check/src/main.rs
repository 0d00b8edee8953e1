//! Links `canopen-core` into a bare-metal binary; see Cargo.toml. The node's dictionary is a derived struct
//! of 101 entries: CI checks that the binary has no `.data` and no `.bss` at all, so the generated tables
//! live in flash (`.rodata`) and the only RAM is the struct itself (on the stack here).
#![no_std]
#![no_main]

use canopen_core::{profile::NodeConfig, CanFrame, Instant, Node, NodeId};
use canopen_od_derive::ObjectDictionary;

/// 101 entries: ARRAY 6000h (sub 0 + 50) and ARRAY 6401h (sub 0 + 49), plus 2000h.
#[derive(ObjectDictionary)]
struct Hundred {
    #[od(index = 0x2000, access = "rw", min = -100, max = 100, default = 5)]
    setpoint: i16,
    #[od(index = 0x6000, sub = 1..=50, access = "ro", pdo = "tpdo")]
    inputs: [u8; 50],
    #[od(index = 0x6401, sub = 1..=49, access = "rw", pdo = "rpdo")]
    outputs: [i16; 49],
}
use core::hint::black_box;

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}

/// The entry point the linker looks for; runs the node on frames it cannot predict (black_box).
#[no_mangle]
pub extern "C" fn _start() -> ! {
    let Some(id) = NodeId::new(black_box(5)) else { loop {} };
    let mut node: Node<Hundred> =
        Node::new(id, NodeConfig::DEFAULT, Hundred { setpoint: 0, inputs: [0; 50], outputs: [0; 49] });
    let mut t = 0u64;
    loop {
        t += black_box(1000);
        let now = Instant::from_micros(t);
        node.handle_timeout(now);
        if let Some(f) = CanFrame::new(black_box(0x000), &black_box([0x01, 0x05])) {
            node.handle_frame(now, &f);
        }
        // An SDO upload of 6000h:07 exercises the derived dispatch.
        if let Some(f) = CanFrame::new(black_box(0x605), &black_box([0x40, 0x00, 0x60, 0x07, 0, 0, 0, 0])) {
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
