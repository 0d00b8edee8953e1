#!/usr/bin/env bash
# Instructions per frame (x86-64, callgrind) for the SDO server ALONE (canopen-core/benches/sdo_instructions.rs):
# SdoServer::handle_request on a minimal hand-written dictionary, no Node, no dispatch, no derived dictionary.
# This is not the reference workload (that is scripts/bench-node.sh, the whole node, all six scenarios): it
# isolates the SDO protocol machine's share of the node figures, so a change in the node's dispatch or the
# dictionary can be told apart from one in the server.
# Usage: scripts/bench-instructions.sh [iterations]
# Runs the bench under callgrind with N and with 0 iterations and divides the difference by the number of
# frames, so set-up and process start-up cancel out.
set -euo pipefail
cd "$(dirname "$0")/.."
N="${1:-200}"
BIN=$(cargo bench -p canopen-core --bench sdo_instructions --no-run --message-format=json 2>/dev/null \
  | grep '"executable":"[^"]*sdo_instructions' | sed 's/.*"executable":"\([^"]*\)".*/\1/' | tail -1)
[ -x "$BIN" ] || { echo "bench binary not found" >&2; exit 1; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
ir() { # scenario iterations → total Ir
  valgrind --tool=callgrind --callgrind-out-file="$TMP/out" "$BIN" "$1" "$2" >"$TMP/stdout" 2>/dev/null
  grep -E '^(summary|totals):' "$TMP/out" | head -1 | awk '{print $2}'
}
printf '%-20s %10s %12s %10s\n' scenario frames instructions per-frame
for s in expedited_upload expedited_download segmented_upload block_download; do
  n=$N
  [ "$s" = block_download ] && n=$(( (N + 9) / 10 ))
  base=$(ir "$s" 0)
  full=$(ir "$s" "$n")
  frames=$(sed 's/.*: \([0-9]*\) frames.*/\1/' "$TMP/stdout")
  awk -v s="$s" -v f="$frames" -v a="$full" -v b="$base" \
    'BEGIN { printf "%-20s %10d %12d %10.1f\n", s, f, a - b, (a - b) / f }'
done
