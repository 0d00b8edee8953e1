"""A pty pair with the Linux kernel's slcan line discipline (N_SLCAN, 17) on its master side: what `slcand` or
`ldattach` does to a real adapter's tty, without one. The kernel then has a CAN interface whose frames are the
slcan lines read from and written to the pty's slave side, which a serial-port program opens by path.

Usage: python3 scripts/slcan-pty.py OUT   writes "SLAVE_PATH IFACE" to OUT, then holds the pty open until
killed.
Needs slcan.ko loaded and CAP_NET_ADMIN (scripts/test-slcan-kernel.sh runs it in the with-vcan VM).
"""

import fcntl
import os
import pty
import signal
import struct
import sys
import termios

N_SLCAN = 17


def main(out):
    before = set(os.listdir("/sys/class/net"))
    master, slave = pty.openpty()
    # Raw mode on the slave side: no echo or line editing between the kernel's slcan and the program.
    attrs = termios.tcgetattr(slave)
    attrs[0] = attrs[1] = attrs[3] = 0
    termios.tcsetattr(slave, termios.TCSANOW, attrs)
    fcntl.ioctl(master, termios.TIOCSETD, struct.pack("i", N_SLCAN))
    new = sorted(set(os.listdir("/sys/class/net")) - before)
    if len(new) != 1:
        sys.exit(f"slcan-pty: expected one new network interface, found {new}")
    with open(out + ".tmp", "w") as f:
        f.write(f"{os.ttyname(slave)} {new[0]}\n")
    os.rename(out + ".tmp", out)
    os.close(slave)  # the program opens it by path; the master side keeps the pair alive
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(0))
    signal.pause()


if __name__ == "__main__":
    main(sys.argv[1])
