#!/usr/bin/env bash
# SDO throughput over vcan (inside ONE with-vcan VM), release builds:
#   - our client (examples/master.rs `bench`) <-> our node (examples/node.rs, tokio runner): 1 MiB each way by
#     block transfer with CRC (16 transfers of 64 KiB, the 2005h DOMAIN's capacity), 128 KiB segmented;
#   - the same node with the blocking runner (--blocking), block+CRC only;
#   - python canopen <-> our node: 64 KiB block download and upload with CRC (python is the bottleneck).
# Each line also gives the node process's CPU time per frame it handled (/proc/<pid>/stat, 10 ms ticks).
# Usage: scripts/bench-vcan.sh [SIZE_BYTES]   (SKIP_PIP=1 skips the pip install). Fails if the VM cannot start.
set -euo pipefail
cd "$(dirname "$0")/.."
SHARED=${SHARED:-$PWD/../shared}
SIZE=${1:-1048576}
if [[ "${SKIP_PIP:-0}" != 1 ]]; then
    python3 -m pip install --quiet -r tests/python/requirements.txt
fi
cargo build --release --examples
cat > target/bench-in-vm.sh <<INNER
set -euo pipefail
N=target/release/examples/node; M=target/release/examples/master
\$N --eds target/bench.eds >/dev/null
run_node() { \$N --quiet --heartbeat 1000 "\$@" > target/bench-node.log 2>&1 & echo \$!; }
pid=\$(run_node); sleep 0.5
echo "== our client <-> our node (tokio runner)"
\$M bench --size $SIZE --segmented-size 131072 --node-pid \$pid
echo "== python canopen <-> our node (tokio runner)"
python3 tests/python/bench_python.py target/bench.eds \$pid 65536
kill \$pid; wait \$pid 2>/dev/null || true
pid=\$(run_node --blocking); sleep 0.5
echo "== our client <-> our node (blocking runner)"
\$M bench --size $SIZE --node-pid \$pid
kill \$pid; wait \$pid 2>/dev/null || true
INNER
status=0
"$SHARED/vcan/with-vcan" -- bash target/bench-in-vm.sh || status=$?
if [[ $status == 125 ]]; then echo "bench-vcan: the with-vcan VM could not start (exit 125)" >&2; exit 1; fi
exit $status
