//! Ending the program: the ARM semihosting `SYS_EXIT` call (BKPT 0xAB with r0 = 18h), which QEMU turns into
//! its own exit status when started with `-semihosting-config enable=on`. Without semihosting the BKPT
//! would be a fault; the binaries here are for QEMU.

/// `ADP_Stopped_ApplicationExit` (QEMU exits 0) or `ADP_Stopped_RunTimeErrorUnknown` (QEMU exits 1).
pub fn exit(ok: bool) -> ! {
    let reason: u32 = if ok { 0x2_0026 } else { 0x2_0023 };
    loop {
        // SAFETY: the semihosting call only reads r0/r1; QEMU ends the process.
        unsafe { core::arch::asm!("bkpt 0xAB", in("r0") 0x18u32, in("r1") reason) };
    }
}
