# Shared set-up of the vcan benches (bench-vcan.sh, bench-master.sh), sourced from the repository root:
# strace on the host (it runs inside the VM from the shared tree), python canopen in target/venv
# (scripts/python-env.sh; SKIP_PIP=1 skips pip) and vcan_run (scripts/vcan-run.sh).
SHARED=${SHARED:-$PWD/../shared}
command -v strace >/dev/null || { apt-get install -y -qq strace >/dev/null || sudo apt-get install -y -qq strace >/dev/null; }
source scripts/python-env.sh
source scripts/vcan-run.sh
