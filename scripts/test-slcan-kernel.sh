#!/usr/bin/env bash
# canopen-master's slcan transport (canopenctl --iface slcan:/dev/pts/N) against the Linux kernel's own slcan
# driver (issue 44 item 4), in one with-vcan VM (its UML kernel has slcan.ko): scripts/slcan-pty.py puts the
# N_SLCAN line discipline on a pty pair, which makes a CAN interface (canN); the example node runs on that
# interface through SocketCAN; canopenctl talks to it through the pty's other side as a serial port. Every
# frame thus crosses the kernel's slcan encoder and decoder. Checked: the same answers over slcan as over the
# SocketCAN interface itself, 1008h segmented, 4 KiB into the node's DOMAIN 2005h and back by block transfer
# with CRC and by segmented transfer, byte-exact, and NMT seen in the node's heartbeat.
# Usage: scripts/test-slcan-kernel.sh   Fails (non-zero) if the VM cannot start.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
SHARED=${SHARED:-$ROOT/../shared}
source scripts/vcan-run.sh

echo "== build on the host"
cargo build --quiet -p canopenctl
cargo build --quiet --example node

cat > target/slcan-in-vm.sh <<'INNER'
set -euo pipefail
ko=$(ls /usr/lib/uml/modules/"$(uname -r)"/kernel/drivers/net/can/slcan/slcan.ko)
busybox insmod "$ko"
rm -f target/slcan-pty.txt
python3 scripts/slcan-pty.py target/slcan-pty.txt &
PTY_PID=$!
for _ in $(seq 100); do [[ -s target/slcan-pty.txt ]] && break; sleep 0.05; done
read -r tty iface < target/slcan-pty.txt
echo "kernel slcan: $iface on the pty whose other side is $tty"
ip link set "$iface" up
target/debug/examples/node --iface "$iface" --node-id 5 --heartbeat 200 >target/slcan-node.log 2>&1 &
NODE_PID=$!
trap 'kill $NODE_PID $PTY_PID 2>/dev/null || true' EXIT
sleep 0.5
ctl() { timeout 60 target/debug/canopenctl --iface "slcan:$tty" "$@"; }
fail() { echo "FAIL: $*"; echo "-- node log:"; cat target/slcan-node.log; exit 1; }
for obj in "0x1000 0" "0x1018 1" "0x1008 0"; do
    via_slcan=$(ctl read 5 $obj) || fail "read $obj over slcan"
    via_socketcan=$(timeout 20 target/debug/canopenctl --iface "$iface" read 5 $obj) || fail "read $obj over $iface"
    [[ "$via_slcan" == "$via_socketcan" ]] || fail "$obj: $via_slcan over slcan, $via_socketcan over $iface"
    echo "read 5 $obj: $via_slcan (the same over slcan and over $iface)"
done
head -c 4096 /dev/urandom > target/slcan-blob.bin
for mode in block segmented; do
    ctl download --mode "$mode" 5 0x2005 0 target/slcan-blob.bin >/dev/null || fail "$mode download"
    ctl upload --mode "$mode" 5 0x2005 0 target/slcan-blob.back >/dev/null || fail "$mode upload"
    cmp target/slcan-blob.bin target/slcan-blob.back || fail "$mode round trip differs"
    echo "4096 bytes into 2005h and back, $mode transfer: byte-exact"
done
# --wait: the node's heartbeat, received over slcan, must report each state.
for cmd in start preop reset; do
    ctl nmt --wait "$cmd" 5 || fail "nmt $cmd not seen in the heartbeat"
done
echo "NMT start, preop, reset over slcan: each seen in the node's heartbeat (boot-up after the reset)"
INNER
vcan_run vcan0 -- bash target/slcan-in-vm.sh
