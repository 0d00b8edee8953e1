#!/usr/bin/env bash
# Interop and SocketCAN tests on real vcan interfaces (vcan0, vcan1): here if they exist, else inside two
# with-vcan VMs side by side (scripts/vcan-run.sh; the optimised 2 and 3 in the release lane, 1 and 4-6 in the
# debug lane):
#   1. canopen-socketcan's own tests on vcan0/vcan1 (send/receive, RTR, 29-bit ignored, error frames,
#      missing interface, interface down/up recovery of both runners, tokio wake);
#   2. tests/vcan_node.rs: OUR SDO client moves 64 KiB through the example node's DOMAIN (segmented, block
#      with and without CRC, byte-exact) and the bounded load test (block transfers under a COB-ID flood);
#   3. tests/vcan_master.rs: canopen-master with ten nodes at once, a stopped node's time-out while its
#      heartbeats arrive, 64 KiB block/segmented byte-exact and 1 MiB block+CRC each way, timed, and the
#      master surviving vcan1 going down and up (transfers in flight fail at once, later ones work);
#   4. canopenctl/tests/cli.rs: the CLI against the example node binary (SDO, NMT, monitor, DOMAIN, LSS, and
#      what it took over from the retired examples/master.rs: bench, nmt --wait, block without CRC);
#   5. tests/python/test_interop.py: python canopen 2.4.1 + python-can 4.6.1 as the master of the example
#      node built with 64 mapping entries per PDO (pdo-mapping-64), on the EDS the node wrote with --eds; tests/python/test_fixed_mapping.py: the same master and the
#      example node built without pdo-dynamic-mapping (const mapping records, PDO-30);
#   6. tests/vcan_master_python.rs: canopen-master as the master of python canopen's LocalNode (ten at once).
# Usage: scripts/test-interop.sh   (SKIP_PIP=1 skips the pip install). Fails (non-zero) if neither the
# interfaces nor the VM are there.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
SHARED=${SHARED:-$ROOT/../shared}

# python canopen, python-can, pytest in the project's own virtual environment (target/venv).
source scripts/python-env.sh
source scripts/vcan-run.sh

echo "== build on the host (the VM compiles ~14x slower)"
# The example node with a fixed PDO mapping (the facade's default features but pdo-dynamic-mapping) for
# tests/python/test_fixed_mapping.py, built first and copied aside: the full build below relinks the same path.
fixed=$(python3 -c 'import tomllib; d = tomllib.load(open("Cargo.toml", "rb"))["features"]["default"]
print(",".join(f for f in d if f != "pdo-dynamic-mapping"))')
cargo build --example node --no-default-features --features "$fixed"
cp target/debug/examples/node target/debug/examples/node-fixed-mapping
# The example node with 64 mapping entries per PDO (canopen-core's pdo-mapping-64, off by default: a feature is
# one per build, and the root package's other tests are about 8) for tests/python/test_interop.py, aside too.
cargo build --example node --features pdo-mapping-64
cp target/debug/examples/node target/debug/examples/node-mapping-64
cargo build --examples
cargo test --no-run -p canopen-socketcan --test vcan
cargo test --no-run -p canopenctl --test cli
cargo test --no-run --test vcan_master_python
# The optimised builds (the release lane's vcan_node and vcan_master) come after the lanes' scripts below: in
# the VMs the debug lane, which needs only the debug builds above, already runs while they compile.
release_builds() {
    # The load test measures the node as it is deployed: optimised (a debug build cannot keep up with a flood
    # plus four 1 ms TPDOs on the VM's one CPU, and then only proves the debug build is slow).
    # canopen-master's vcan tests time 1 MiB transfers: optimised too. Both in one build, so the two test
    # binaries compile side by side.
    cargo test --release --no-run --test vcan_node --test vcan_master
}

# Two lanes, each a script that needs vcan0/vcan1. In the with-vcan VM (one CPU each) they run side by side in
# two VMs, which do not see each other's interfaces: the section takes the longer lane's time instead of the
# sum. The debug lane needs only the debug builds, so its VM starts first and the host compiles the release
# lane's optimised builds (about 150 s in CI, the release profile's dependencies included, which the bench
# section reuses) beside it; the release lane's VM starts when they are built, so the release lane holds only
# what needs them (about 50 s in CI, the debug lane about 180 s). On a host's own vcan interfaces the lanes
# share the bus and the example node's ID, so there they run one after the other, after the builds.
cat > target/interop-lane-release.sh <<'INNER'
set -euo pipefail
echo "== our SDO client + load test on the example node"
cargo test --release -q --test vcan_node -- --include-ignored --nocapture --test-threads 1
echo "== canopen-master: ten nodes at once, a stopped node's time-out, 1 MiB block transfers timed, vcan1 down/up"
cargo test --release -q --test vcan_master -- --include-ignored --nocapture --test-threads 1
INNER
cat > target/interop-lane-debug.sh <<'INNER'
set -euo pipefail
export CANOPEN_REQUIRE_VCAN=1 # python (also vcan_master_python's LocalNodes): fail, not skip, without vcan
echo "== canopen-socketcan on vcan0/vcan1"
cargo test -q -p canopen-socketcan --test vcan -- --include-ignored
echo "== canopen-master against python canopen's LocalNode (ten nodes, typed values, aborts, block fallback)"
NODE_BIN=$PWD/target/debug/examples/node cargo test -q --test vcan_master_python -- --include-ignored
echo "== canopenctl against the example node (SDO, NMT, monitor, DOMAIN files, program download, LSS, bench)"
NODE_BIN=$PWD/target/debug/examples/node cargo test -q -p canopenctl --test cli -- --include-ignored --test-threads 1
echo "== python canopen as the master"
NODE_BIN=target/debug/examples/node-mapping-64 NODE_LOG=target/interop-node.log \
    python3 -m pytest -q -rs -o faulthandler_timeout=300 tests/python/test_interop.py
echo "== python canopen as the master of the node with a fixed PDO mapping (PDO-30)"
NODE_BIN_FIXED=target/debug/examples/node-fixed-mapping python3 -m pytest -q -rs -o faulthandler_timeout=300 \
    tests/python/test_fixed_mapping.py
INNER

# A lane's verdict: 125 is a VM that could not start, which fails (it is not a skip).
verdict() {
    local lane=$1 status=$2
    if [[ $status == 125 ]]; then
        echo "test-interop: lane $lane: no vcan0/vcan1 and the with-vcan VM could not start (exit 125): FAILED, not skipped" >&2
        return 1
    elif [[ $status != 0 ]]; then
        echo "test-interop: lane $lane FAILED (exit $status); node log of the python tests: target/interop-node.log" >&2
        return 1
    fi
}

lanes=(release debug)
declare -A status
if vcan_present vcan0,vcan1; then
    release_builds
    for lane in "${lanes[@]}"; do
        echo "== lane $lane on this host's vcan0/vcan1"
        status[$lane]=0
        vcan_run vcan0,vcan1 -- bash "target/interop-lane-$lane.sh" || status[$lane]=$?
    done
else
    echo "== lanes ${lanes[*]} side by side, each in its own with-vcan VM (vcan0/vcan1); their output follows, lane by lane"
    declare -A pid
    # A time-out (CI's `timeout` sends TERM to this script) or Ctrl-C takes the lanes' VMs down with it.
    trap 'for p in "${pid[@]}"; do kill_tree "$p"; done; exit 143' TERM INT
    start_lane() {
        vcan_run vcan0,vcan1 -- bash "target/interop-lane-$1.sh" >"target/interop-lane-$1.log" 2>&1 &
        pid[$1]=$!
    }
    start_lane debug
    # A failed build fails the script, and takes the debug lane's VM down with it.
    release_builds || { rc=$?; kill_tree "${pid[debug]}"; exit "$rc"; }
    start_lane release
    for lane in "${lanes[@]}"; do
        status[$lane]=0
        wait "${pid[$lane]}" || status[$lane]=$?
        echo "== lane $lane (exit ${status[$lane]})"
        cat "target/interop-lane-$lane.log"
    done
fi
failed=0
for lane in "${lanes[@]}"; do verdict "$lane" "${status[$lane]}" || failed=1; done
[[ $failed == 0 ]] || exit 1
echo "test-interop: all passed"
