#!/usr/bin/env bash
# Loads the EDS of the all-types test dictionary in python canopen (tests/python/test_eds.py).
# Usage: scripts/test-eds.sh            (installs tests/python/requirements.txt first unless SKIP_PIP=1)
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ "${SKIP_PIP:-0}" != 1 ]]; then
    python3 -m pip install --quiet -r tests/python/requirements.txt
fi
eds="$(mktemp -d)/all_types.eds"
cargo run --quiet --example write_eds -- "$eds"
CANOPEN_EDS="$eds" python3 -m pytest -q tests/python/test_eds.py
