#!/usr/bin/env bash
# python canopen's LSS master (network.lss: fastscan, configure_node_id, store_configuration) against
# examples/node (--node-id 255 --store FILE) over vcan: tests/python/test_lss.py. Builds on the host, then
# runs the node + pytest in ONE with-vcan VM (processes in different VMs cannot see each other).
# Usage: scripts/test-lss.sh        (installs tests/python/requirements.txt first unless SKIP_PIP=1)
set -euo pipefail
cd "$(dirname "$0")/.."
WITH_VCAN="${WITH_VCAN:-../shared/vcan/with-vcan}"
# python canopen, python-can, pytest in the project's own virtual environment (target/venv).
source scripts/python-env.sh
cargo build --quiet --example node
set +e
"$WITH_VCAN" -- env NODE_EXAMPLE_BIN="$PWD/target/debug/examples/node" \
    python3 -m pytest -q -p no:cacheprovider tests/python/test_lss.py
rc=$?
set -e
if [[ $rc -eq 125 ]]; then
    echo "test-lss: FAILED: the vcan VM could not start (with-vcan exit 125); nothing was tested" >&2
fi
exit $rc
