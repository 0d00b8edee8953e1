#!/usr/bin/env bash
# Loads the EDS of the all-types test dictionary in python canopen (tests/python/test_eds.py).
# Usage: scripts/test-eds.sh            (installs tests/python/requirements.txt first unless SKIP_PIP=1)
set -euo pipefail
cd "$(dirname "$0")/.."
# python canopen, python-can, pytest in the project's own virtual environment (target/venv).
source scripts/python-env.sh
eds="$(mktemp -d)/all_types.eds"
cargo run --quiet --example write_eds -- "$eds"
CANOPEN_EDS="$eds" python3 -m pytest -q tests/python/test_eds.py
