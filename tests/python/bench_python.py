"""python canopen as the master of the example node: SDO block download and upload throughput of SIZE bytes
(64 KiB by default: python is the bottleneck in the VM) to/from 2005h, byte-exact, and the node process's
CPU time per frame it handled (from /proc/<pid>/stat). Usage: bench_python.py EDS NODE_PID [SIZE [ROUNDS]]:
ROUNDS transfers of SIZE each way (scripts/bench-master.sh: 16 x 64 KiB = 1 MiB, the DOMAIN's capacity
being 64 KiB)."""

import os
import sys
import time

import canopen


def cpu_seconds(pid):
    with open(f"/proc/{pid}/stat") as f:
        rest = f.read().rsplit(")", 1)[1].split()
    return (int(rest[11]) + int(rest[12])) / os.sysconf("SC_CLK_TCK")


class Counter:
    def __init__(self):
        self.n = 0

    def __call__(self, *args):
        self.n += 1


def main():
    eds, pid = sys.argv[1], int(sys.argv[2])
    size = int(sys.argv[3]) if len(sys.argv) > 3 else 65536
    rounds = int(sys.argv[4]) if len(sys.argv) > 4 else 1
    net = canopen.Network()
    net.connect(interface="socketcan", channel=os.environ.get("CANOPEN_IFACE", "vcan0"))
    node = net.add_node(5, eds)
    node.sdo.RESPONSE_TIMEOUT = 3.0
    rx, tx = Counter(), Counter()
    net.subscribe(0x585, rx)  # what the node sent
    data = bytes((i * 7 + (i >> 8)) & 0xFF for i in range(size))
    for direction in ("download", "upload"):
        rx.n = 0
        cpu0, t0 = cpu_seconds(pid), time.perf_counter()
        for _ in range(rounds):
            if direction == "download":
                with node.sdo.open(0x2005, 0, "wb", size=size, block_transfer=True, request_crc_support=True) as f:
                    f.write(data)
            else:
                with node.sdo.open(0x2005, 0, "rb", block_transfer=True, request_crc_support=True) as f:
                    back = f.read()
                assert back == data, "upload differs"
        secs, cpu = time.perf_counter() - t0, cpu_seconds(pid) - cpu0
        # Frames the node handled: what it sent (counted) + what it received (the segments when downloading,
        # the initiate/ack/end requests when uploading: one ack per 127-segment sub-block).
        segments = (size + 6) // 7
        frames = rx.n + rounds * (segments + 4 if direction == "download" else segments // 127 + 4)
        total = size * rounds
        what = f"{size} bytes" if rounds == 1 else f"{total} bytes ({rounds} x {size})"
        print(f"python block+CRC {direction}: {what} in {secs:.3f} s = {total / 1024 / secs:.1f} KiB/s, "
              f"~{frames} frames, node CPU {cpu:.2f} s = {cpu * 1e6 / frames:.2f} us/frame")
    if node.sdo.upload(0x2005, 0) != data:
        raise SystemExit("final content differs")
    net.unsubscribe(0x585, rx)
    net.disconnect()


if __name__ == "__main__":
    main()
