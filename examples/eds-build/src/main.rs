//! The device as a bare-metal binary for a Cortex-M4F (thumbv7em-none-eabihf), with its own panic
//! handler: it cannot link if anything in its dependency graph needs std. On the host it is a program
//! that says what the dictionary holds.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
mod bare_metal {
    use canopen_core::{CanFrame, Instant, NodeId};
    use core::hint::black_box;

    #[panic_handler]
    fn halt(_: &core::panic::PanicInfo) -> ! {
        loop {
            core::hint::spin_loop();
        }
    }

    /// SDO upload of 2000h (Setpoint), which the generated dictionary answers.
    const READ_SETPOINT: [u8; 8] = [0x40, 0x00, 0x20, 0x00, 0, 0, 0, 0];

    /// The entry point the linker looks for. A sans-IO runner: sleep (here: jump) to the node's next
    /// deadline, feed it a frame it cannot predict (black_box), hand what it sends to the "bus".
    #[no_mangle]
    pub extern "C" fn _start() -> ! {
        let Some(id) = NodeId::new(black_box(5)) else { panic!("5 is a node-ID") };
        let mut node = eds_build::node(id);
        let mut now = Instant::ZERO;
        loop {
            node.handle_timeout(now);
            let request = CanFrame::new(black_box(0x605), &black_box(READ_SETPOINT));
            request.iter().for_each(|f| node.handle_frame(now, f));
            core::iter::from_fn(|| node.poll_transmit()).for_each(|f| {
                black_box(f);
            });
            core::iter::from_fn(|| node.poll_event()).for_each(|e| {
                black_box(e);
            });
            now = node.poll_timeout().unwrap_or(now);
        }
    }
}

#[cfg(not(target_os = "none"))]
fn main() {
    let d = eds_build::Device::default();
    println!(
        "device.eds: setpoint field {} (its EDS default applies at boot), device type {:08X}h",
        d.setpoint_2000,
        eds_build::CONFIG.device_type
    );
}
