#!/usr/bin/env bash
# The Cortex-M4 firmware (examples/qemu-m4) in QEMU's mps2-an386, with python canopen as its master over
# python-can's slcan interface (issue 44 items 1-3):
#   1. builds the EDS of the firmware's dictionary on the host (examples/qemu_m4_eds.rs, with the firmware's own
#      canopen-core features) and the firmware image (thumbv7em-none-eabihf, release);
#   2. starts QEMU with UART0 on a free local TCP port, runs tests/python/test_qemu_slcan.py against it through
#      `socket://127.0.0.1:PORT`, and prints the emulator's log (its stderr: panics, faults, guest errors) when
#      anything fails;
#   3. our own master over the same link: canopenctl --iface slcan:tcp:127.0.0.1:PORT reads 1008h and moves
#      256 random bytes into 2105h and back by block transfer with CRC, byte-exact;
#   4. runs the bench image under `-icount shift=0` (one instruction = 1 ns of virtual time) and prints the
#      Cortex-M instructions per received frame of the six reference scenarios (README "Performance"), and
#      fails when one grew more than 2 % over its line in scripts/qemu-bench.baseline (scripts/ratchet.py).
# Usage: scripts/test-qemu.sh   (needs qemu-system-arm; SKIP_PIP=1 skips the pip install)
set -euo pipefail
cd "$(dirname "$0")/.."
command -v qemu-system-arm >/dev/null || { echo "FAIL: qemu-system-arm is not installed (apt-get install qemu-system-arm)"; exit 1; }
source scripts/python-env.sh
OUT=target/qemu-m4
mkdir -p "$OUT"

echo "== build: the EDS on the host, the firmware for thumbv7em-none-eabihf"
features=$(python3 -c 'import tomllib; d = tomllib.load(open("examples/qemu-m4/Cargo.toml", "rb"))
print(",".join(d["dependencies"]["canopen-core"]["features"]))')
cargo build --quiet --example qemu_m4_eds --no-default-features --features "$features"
target/debug/examples/qemu_m4_eds "$OUT/qemu-m4.eds"
cargo build --quiet -p canopenctl
(cd examples/qemu-m4 && cargo build --quiet --release --bins)
IMAGES=examples/qemu-m4/target/thumbv7em-none-eabihf/release

free_port() { python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
QEMU_PID=
LOG="$OUT/qemu-node.log"
stop_qemu() { [[ -n "$QEMU_PID" ]] && kill "$QEMU_PID" 2>/dev/null && wait "$QEMU_PID" 2>/dev/null; QEMU_PID=; true; }
trap stop_qemu EXIT

echo "== the node in QEMU, python canopen over slcan"
PORT=$(free_port)
qemu-system-arm -M mps2-an386 -nographic -monitor none -semihosting-config enable=on,target=native \
    -d guest_errors,unimp -serial "tcp:127.0.0.1:$PORT,server=on,wait=off" \
    -kernel "$IMAGES/node" >"$LOG" 2>&1 &
QEMU_PID=$!
for _ in $(seq 50); do
    python3 -c "import socket; socket.create_connection(('127.0.0.1', $PORT), 0.2).close()" 2>/dev/null && break
    sleep 0.1
done
if ! QEMU_SLCAN="socket://127.0.0.1:$PORT" QEMU_EDS="$OUT/qemu-m4.eds" \
        timeout 600 python3 -m pytest -q -rA -p no:cacheprovider -o faulthandler_timeout=300 tests/python/test_qemu_slcan.py; then
    echo "== FAIL; the emulator's log ($LOG):"
    cat "$LOG"
    kill -0 "$QEMU_PID" 2>/dev/null || echo "(QEMU is no longer running)"
    exit 1
fi

echo "== canopenctl over slcan (tcp) to the same node"
ctl() { timeout 30 target/debug/canopenctl --iface "slcan:tcp:127.0.0.1:$PORT@250000" "$@"; }
name=$(ctl read 5 0x1008 0)
[[ "$name" == '"canopener QEMU AN386"' ]] || { echo "FAIL: 1008h read as $name"; cat "$LOG"; exit 1; }
head -c 256 /dev/urandom >"$OUT/blob.bin"
ctl download 5 0x2105 0 "$OUT/blob.bin" && ctl upload 5 0x2105 0 "$OUT/blob.back" \
    && cmp "$OUT/blob.bin" "$OUT/blob.back" || { echo "FAIL: 2105h block round trip"; cat "$LOG"; exit 1; }
echo "canopenctl over slcan: 1008h = $name, 256 bytes block+CRC both ways byte-exact"
stop_qemu

echo "== Cortex-M instructions per received frame (QEMU -icount shift=0, examples/qemu-m4/src/bin/bench.rs)"
# The bench prints its table on UART0 (stdio here) and leaves QEMU through semihosting (exit status 0/1).
if ! timeout 300 qemu-system-arm -M mps2-an386 -nographic -monitor none -icount shift=0,sleep=off \
        -semihosting-config enable=on,target=native -kernel "$IMAGES/bench" >"$OUT/bench.txt" 2>&1; then
    echo "FAIL: the bench image failed; its output:"
    cat "$OUT/bench.txt"
    exit 1
fi
cat "$OUT/bench.txt"
# The ratchet: each scenario's figure (sync_4_tpdos per bus frame) against scripts/qemu-bench.baseline.
awk '/instructions per received frame/ && $1 != "sync_4_tpdos" { print $1, $2 }
     /instructions per bus frame/ { print $1, $2 }' "$OUT/bench.txt" >"$OUT/bench-figures.txt"
[ "$(wc -l <"$OUT/bench-figures.txt")" -eq 7 ] || { echo "FAIL: expected 7 figures in the bench's table"; exit 1; }
python3 scripts/ratchet.py scripts/qemu-bench.baseline "Cortex-M4 instructions per frame (per-bus for sync_4_tpdos)" \
    <"$OUT/bench-figures.txt"
