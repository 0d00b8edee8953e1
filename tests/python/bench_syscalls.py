"""One workload of the syscall benchmark (scripts/bench-vcan.sh), python canopen as the master of the example
node 5; run under `strace -f -c` while another strace counts the node. Prints one line
`frames=N node_cpu_ticks=T` (N: frames the workload sends towards the node; T: the node's utime+stime in
clock ticks during the workload). Usage: bench_syscalls.py WORKLOAD EDS NODE_PID, WORKLOAD one of
expedited (2,000 reads of 1018h:1), block (64 KiB block download with CRC into 2005h), bystander (4,000
SDO requests to node 6, which does not exist), idle (1 s, nothing sent)."""

import os
import sys
import time

import can
import canopen


def cpu_ticks(pid):
    with open(f"/proc/{pid}/stat") as f:
        rest = f.read().rsplit(")", 1)[1].split()
    return int(rest[11]) + int(rest[12])


def main():
    workload, eds, pid = sys.argv[1], sys.argv[2], int(sys.argv[3])
    iface = os.environ.get("CANOPEN_IFACE", "vcan0")
    t0 = cpu_ticks(pid)
    if workload == "bystander":
        bus = can.Bus(interface="socketcan", channel=iface)
        msg = can.Message(arbitration_id=0x606, data=[0x40, 0x18, 0x10, 0x01, 0, 0, 0, 0], is_extended_id=False)
        for _ in range(4000):
            while True:
                try:
                    bus.send(msg)
                    break
                except can.CanOperationError:
                    time.sleep(0.0002)
        time.sleep(0.2)
        bus.shutdown()
        frames = 4000
    elif workload == "idle":
        time.sleep(1.0)
        frames = 1
    else:
        net = canopen.Network()
        net.connect(interface="socketcan", channel=iface)
        node = net.add_node(5, eds)
        node.sdo.RESPONSE_TIMEOUT = 3.0
        if workload == "expedited":
            for _ in range(2000):
                node.sdo.upload(0x1018, 1)
            frames = 2000
        else:
            size = 65536
            data = bytes((i * 7 + (i >> 8)) & 0xFF for i in range(size))
            with node.sdo.open(0x2005, 0, "wb", size=size, block_transfer=True, request_crc_support=True) as f:
                f.write(data)
            frames = (size + 6) // 7 + 2
        net.disconnect()
    print(f"frames={frames} node_cpu_ticks={cpu_ticks(pid) - t0}")


if __name__ == "__main__":
    main()
