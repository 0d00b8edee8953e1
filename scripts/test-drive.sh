#!/usr/bin/env bash
# CiA 402 against a master nobody here wrote: python canopen's BaseNode402 (tests/python/test_drive402.py) takes
# examples/drive through every state it can command, a fault and its reset, mode changes, homing (methods 37 and
# 17) and a profile position move that ends with target reached; then canopenctl drive ... (our master,
# canopen-master's Drive402) does the same and streams cyclic set-points, over vcan0 (here if it exists, else in ONE
# with-vcan VM, scripts/vcan-run.sh). Builds on the host first.
# Usage: scripts/test-drive.sh        (installs tests/python/requirements.txt first unless SKIP_PIP=1)
set -euo pipefail
cd "$(dirname "$0")/.."
# python canopen, python-can, pytest in the project's own virtual environment (target/venv).
source scripts/python-env.sh
source scripts/vcan-run.sh
cargo build --quiet --example drive
cargo test --quiet --no-run -p canopenctl --test drive_cli
cat > target/drive-in-vm.sh <<'INNER'
set -euo pipefail
echo "== python canopen's BaseNode402 against the example drive"
CANOPEN_REQUIRE_VCAN=1 python3 -m pytest -q -rs -s -p no:cacheprovider -o faulthandler_timeout=120 \
    tests/python/test_drive402.py
echo "== canopenctl drive ... (canopen-master's Drive402) against the example drive"
cargo test -q -p canopenctl --test drive_cli -- --include-ignored --test-threads 1
INNER
set +e
vcan_run vcan0 -- env DRIVE_BIN="$PWD/target/debug/examples/drive" bash target/drive-in-vm.sh
rc=$?
set -e
if [[ $rc -eq 125 ]]; then
    echo "test-drive: FAILED: no vcan0 and the vcan VM could not start (exit 125); nothing was tested" >&2
fi
exit $rc
