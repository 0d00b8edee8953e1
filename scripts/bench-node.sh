#!/usr/bin/env bash
# Instructions per received frame for the whole node (x86-64, callgrind): the reference workload of
# DESIGN.md "Performance". Usage: scripts/bench-node.sh [iterations]
# Runs benches/node_instructions.rs under callgrind with N and with 0 iterations and divides the difference by
# the number of frames, so set-up (recording the client's frames) and process start-up cancel out.
set -euo pipefail
cd "$(dirname "$0")/.."
N="${1:-200}"
command -v valgrind >/dev/null || { echo "valgrind is needed (apt-get install valgrind)" >&2; exit 1; }
BIN=$(cargo bench --bench node_instructions --no-run --message-format=json 2>/dev/null \
  | grep '"executable":"[^"]*node_instructions' | sed 's/.*"executable":"\([^"]*\)".*/\1/' | tail -1)
[ -x "$BIN" ] || { echo "bench binary not found" >&2; exit 1; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
ir() { # scenario iterations -> total instructions
  valgrind --tool=callgrind --callgrind-out-file="$TMP/out" "$BIN" "$1" "$2" >"$TMP/stdout" 2>/dev/null
  grep -E '^(summary|totals):' "$TMP/out" | head -1 | awk '{print $2}'
}
printf '%-20s %10s %12s %10s %8s\n' scenario frames instructions per-frame target
for entry in expedited_upload:320 expedited_download:300 segmented_upload:260 block_download:450; do
  s=${entry%%:*}; target=${entry##*:}
  n=$N
  [ "$s" = block_download ] && n=$(( (N + 9) / 10 ))
  base=$(ir "$s" 0)
  full=$(ir "$s" "$n")
  frames=$(sed 's/.*: \([0-9]*\) frames.*/\1/' "$TMP/stdout")
  awk -v s="$s" -v f="$frames" -v a="$full" -v b="$base" -v t="$target" \
    'BEGIN { printf "%-20s %10d %12d %10.1f %8d\n", s, f, a - b, (a - b) / f, t }'
done
