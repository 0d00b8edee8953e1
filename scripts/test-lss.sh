#!/usr/bin/env bash
# python canopen's LSS master (network.lss: fastscan, configure_node_id, store_configuration) against
# examples/node (--node-id 255 --store FILE) over vcan0: tests/python/test_lss.py. Builds first, then runs the
# node + pytest on vcan0 (here if it exists, else in ONE with-vcan VM, scripts/vcan-run.sh).
# Usage: scripts/test-lss.sh        (installs tests/python/requirements.txt first unless SKIP_PIP=1)
set -euo pipefail
cd "$(dirname "$0")/.."
# python canopen, python-can, pytest in the project's own virtual environment (target/venv).
source scripts/python-env.sh
source scripts/vcan-run.sh
cargo build --quiet --example node
set +e
vcan_run vcan0 -- env NODE_EXAMPLE_BIN="$PWD/target/debug/examples/node" \
    python3 -m pytest -q -p no:cacheprovider tests/python/test_lss.py
rc=$?
set -e
if [[ $rc -eq 125 ]]; then
    echo "test-lss: FAILED: no vcan0 and the vcan VM could not start (exit 125); nothing was tested" >&2
fi
exit $rc
