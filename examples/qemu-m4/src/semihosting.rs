//! Ending the program: the ARM semihosting `SYS_EXIT` call (BKPT 0xAB with r0 = 18h), which QEMU turns into
//! its own exit status when started with `-semihosting-config enable=on`. Without semihosting the BKPT
//! would be a fault; the binaries here are for QEMU.

/// Writes `text` to QEMU's standard error (SYS_WRITE0 of a NUL-terminated copy, at most 127 bytes).
pub fn write(text: &str) {
    let mut buf = [0u8; 128];
    let n = text.len().min(buf.len() - 1);
    buf[..n].copy_from_slice(&text.as_bytes()[..n]);
    // SAFETY: SYS_WRITE0 (04h) reads the NUL-terminated string at r1, which `buf` holds.
    unsafe { core::arch::asm!("bkpt 0xAB", inout("r0") 0x04u32 => _, in("r1") buf.as_ptr()) };
}

/// `ADP_Stopped_ApplicationExit` (QEMU exits 0) or `ADP_Stopped_RunTimeErrorUnknown` (QEMU exits 1).
pub fn exit(ok: bool) -> ! {
    let reason: u32 = if ok { 0x2_0026 } else { 0x2_0023 };
    loop {
        // SAFETY: the semihosting call only reads r0/r1; QEMU ends the process.
        unsafe { core::arch::asm!("bkpt 0xAB", in("r0") 0x18u32, in("r1") reason) };
    }
}
