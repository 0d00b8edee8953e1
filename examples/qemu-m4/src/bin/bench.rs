//! Cortex-M instructions per received frame for the six reference scenarios of DESIGN.md "Performance"
//! (the workload of `benches/node_instructions.rs`, which callgrind counts on x86-64), run on the target's
//! instruction set: QEMU's mps2-an386 with `-icount shift=0`, where each executed guest instruction advances
//! the virtual clock by exactly 1 ns. TIMER0 counts that clock at 25 MHz, so 40 instructions per cycle;
//! each scenario is replayed until about 4,000 frames went through, so the 40-instruction grain is ~0.01.
//!
//! The count is instructions, not cycles (QEMU models no pipeline, wait states or flash latency): the figure
//! to compare with callgrind's `Ir`. The SysTick interrupt (every 1 ms of virtual time, i.e. every 10^6
//! instructions) adds well under 0.1 %. A calibration loop of known length is measured first and must read
//! within 0.5 %, or the bench fails: then the emulator was not run with `-icount shift=0`.
//!
//! Beside each figure: the stack the passes took below the measuring loop (painted before, high-water mark
//! after), i.e. what `handle_frame` and the drain need on this target, without the executor and the driver.
//!
//! One main-loop pass per frame as in the x86 bench: `handle_frame`, then `poll_event` until empty and
//! `peek_transmit`/`transmitted` for every frame out. The SDO client's frames are recorded once with our SDO
//! client before the measured part and replayed. The core's features are the firmware's (the STM32 `node`'s
//! `full` set: the block CRC from the 32-byte nibble table, not the 512-byte one of the x86 build).
#![no_std]
#![no_main]

use core::fmt::Write;

use canopen_core::node::Node;
use canopen_core::od::{ObjectDictionary, OdDescribe};
use canopen_core::profile::NodeConfig;
use canopen_core::sdo::client::{ClientEvent, Mode, SdoClient, SliceData};
use canopen_core::sdo::SdoClientParams;
use canopen_core::wire::sdo::Multiplexer;
use canopen_core::{CanFrame, Instant, NmtState, NodeId, Sizes};
use canopen_qemu_m4::uart::Writer;
use canopen_qemu_m4::{semihosting, stack, time_driver, uart};

#[path = "../../../../benches/common/workload.rs"]
mod workload;
use workload::{App, Process, Quiet, BLOCK_LEN, PDO_CFG};

/// Instructions per TIMER0 cycle under `-icount shift=0` (1 ns each) at 25 MHz.
const INSNS_PER_CYCLE: u64 = 1_000_000_000 / canopen_qemu_m4::SYSCLK_HZ as u64;

/// A recorded client script (block download: ~1,020 frames).
struct Script {
    frames: [CanFrame; 1100],
    len: usize,
}

fn fail(what: &str) -> ! {
    let _ = writeln!(Writer, "FAIL: {what}");
    semihosting::exit(false)
}

fn node_id() -> NodeId {
    NodeId::new(5).unwrap_or_else(|| fail("node-ID"))
}

fn booted<A: ObjectDictionary>(app: A) -> Node<A, Sizes> {
    let cfg = NodeConfig { device_type: 0x000F_0191, ..NodeConfig::DEFAULT };
    let mut node = Node::new(node_id(), cfg, app);
    node.handle_timeout(Instant::ZERO);
    while node.poll_transmit().is_some() {}
    while node.poll_event().is_some() {}
    node
}

fn pdo_node() -> Node<Process, Sizes> {
    let mut node = Node::new(node_id(), PDO_CFG, Process::default());
    node.handle_timeout(Instant::ZERO);
    node.enter_state(NmtState::Operational);
    while node.poll_transmit().is_some() {}
    while node.poll_event().is_some() {}
    node
}

/// One transfer of our client against a fresh node, its frames recorded into `script`.
fn record(script: &mut Script, mux: Multiplexer, mode: Mode, download: Option<&mut [u8]>) {
    let mut node = booted(App::default());
    let params = SdoClientParams::for_server(node_id());
    let mut client = SdoClient::new(params);
    let mut upload_buf = [0u8; 128];
    let started = match &download {
        Some(d) => client.start_download(Instant::ZERO, mux, d.len(), mode),
        None => client.start_upload(Instant::ZERO, mux, mode),
    };
    if started.is_err() {
        fail("client start");
    }
    let mut data = match download {
        Some(d) => SliceData::download(d),
        None => SliceData::upload(&mut upload_buf),
    };
    script.len = 0;
    loop {
        while let Some(f) = client.poll_transmit(Instant::ZERO, &mut data) {
            let frame = CanFrame::new(params.tx_cob_id(), &f).unwrap_or_else(|| fail("client frame"));
            let Some(slot) = script.frames.get_mut(script.len) else { fail("script too long") };
            *slot = frame;
            script.len += 1;
            node.handle_frame(Instant::ZERO, &frame);
        }
        while let Some(out) = node.poll_transmit() {
            match client.handle_response(Instant::ZERO, out.data(), &mut data) {
                Some(ClientEvent::Done { .. }) => return,
                Some(ClientEvent::Failed(_)) => fail("transfer aborted while recording"),
                _ => {}
            }
        }
    }
}

/// Replays `script` until at least `frames` went through; returns (received, sent, instructions, stack
/// bytes the passes took below this function's frame).
#[inline(never)]
fn run<A: ObjectDictionary + OdDescribe>(
    node: &mut Node<A, Sizes>,
    script: &[CanFrame],
    frames: usize,
) -> (u64, u64, u64, u32) {
    let (mut received, mut sent) = (0u64, 0u64);
    let base = stack::paint();
    let start = time_driver::cycles();
    while (received as usize) < frames {
        for f in script {
            workload::pass(node, f, &mut sent);
            received += 1;
        }
    }
    let cycles = time_driver::cycles() - start;
    let stack = stack::high_water().saturating_sub(base);
    if node.tx_dropped() != 0 {
        fail("transmit queue overflow");
    }
    (received, sent, cycles * INSNS_PER_CYCLE, stack)
}

fn report(name: &str, (received, sent, insns, stack): (u64, u64, u64, u32)) {
    report_per(name, insns, received, "received frame", (received, sent));
    let _ = writeln!(Writer, "{:<26} {stack:>6} B of stack below the loop, deepest pass", "");
}

/// `insns / per` with one decimal.
fn report_per(name: &str, insns: u64, per: u64, unit: &str, (received, sent): (u64, u64)) {
    let tenths = insns * 10 / per;
    let _ = writeln!(
        Writer,
        "{name:<26} {:>6}.{} instructions per {unit} ({received} received, {sent} sent)",
        tenths / 10,
        tenths % 10
    );
}

/// 100,000 passes of a 2-instruction loop (SUBS, BNE) measured as the scenarios are.
fn calibrate() {
    let start = time_driver::cycles();
    // SAFETY: a register-only countdown loop.
    unsafe {
        core::arch::asm!("1:", "subs {0}, {0}, #1", "bne 1b", inout(reg) 100_000u32 => _, options(nomem, nostack));
    }
    let insns = (time_driver::cycles() - start) * INSNS_PER_CYCLE;
    let _ = writeln!(Writer, "calibration: a 200,000-instruction loop measured as {insns}");
    if !(199_000..=201_000).contains(&insns) {
        fail("calibration off by more than 0.5 %: run QEMU with -icount shift=0");
    }
}

static mut SCRIPT: Script = Script { frames: [CanFrame::from_parts(0, [0; 8], 0); 1100], len: 0 };
static mut BLOCK_DATA: [u8; BLOCK_LEN] = [0; BLOCK_LEN];

#[cortex_m_rt::entry]
fn main() -> ! {
    let Some(core) = cortex_m::Peripherals::take() else { fail("peripherals") };
    time_driver::init(core.SYST);
    uart::init();
    calibrate();
    // SAFETY: taken once, here, before anything else could reach them.
    let (script, block) = unsafe { (&mut *core::ptr::addr_of_mut!(SCRIPT), &mut *core::ptr::addr_of_mut!(BLOCK_DATA)) };
    const FRAMES: usize = 4000;

    record(script, Multiplexer::new(0x1000, 0), Mode::Auto, None);
    report("expedited_upload", run(&mut booted(App::default()), &script.frames[..script.len], FRAMES));

    let mut value = [1u8, 2, 3, 4];
    record(script, Multiplexer::new(0x2002, 0), Mode::Auto, Some(&mut value));
    report("expedited_download", run(&mut booted(App::default()), &script.frames[..script.len], FRAMES));
    let mut quiet = booted(Quiet::default());
    report("expedited_download_quiet", run(&mut quiet, &script.frames[..script.len], FRAMES));
    if quiet.app().value != 0x0403_0201 {
        fail("expedited_download_quiet wrote nothing");
    }

    record(script, Multiplexer::new(0x2004, 0), Mode::Auto, None);
    report("segmented_upload", run(&mut booted(App::default()), &script.frames[..script.len], FRAMES));

    for (i, b) in block.iter_mut().enumerate() {
        *b = (i * 31 + 7) as u8;
    }
    record(script, Multiplexer::new(0x2005, 0), Mode::Block { crc: true, blksize: 127, pst: 0 }, Some(block));
    report("block_download", run(&mut booted(App::default()), &script.frames[..script.len], FRAMES));

    let mut node = pdo_node();
    let rpdo = CanFrame::from_parts(0x205, [1, 2, 3, 4, 5, 6, 7, 8], 8);
    report("rpdo_4_objects", run(&mut node, &[rpdo], FRAMES));
    if node.app().d != 0x0807 {
        fail("rpdo_4_objects wrote nothing");
    }
    let mut node = pdo_node();
    let (received, sent, insns, stack) = run(&mut node, &[CanFrame::from_parts(0x080, [0; 8], 0)], FRAMES);
    if sent != 4 * received {
        fail("sync_4_tpdos did not send 4 TPDOs per SYNC");
    }
    report("sync_4_tpdos", (received, sent, insns, stack));
    // The x86 ratchet counts this one per bus frame (1 SYNC in, 4 TPDOs out).
    report_per("sync_4_tpdos", insns, received + sent, "bus frame", (received, sent));
    let _ = writeln!(Writer, "done");
    semihosting::exit(true)
}
