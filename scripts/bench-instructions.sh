#!/usr/bin/env bash
# Instructions per frame (x86-64, callgrind): the SDO server alone (canopen-core/benches/sdo_instructions.rs)
# and PDO traffic through a whole Node (canopen-core/benches/pdo_instructions.rs: handle_frame + draining
# poll_transmit and poll_event).
# Usage: scripts/bench-instructions.sh [iterations]
# Runs each bench under callgrind with N and with 0 iterations and divides the difference by the number of
# frames (received + sent), so set-up and process start-up cancel out. For the PDO scenarios the
# instructions per iteration (one RPDO received; one SYNC received and its 4 TPDOs sent) are printed too.
set -euo pipefail
cd "$(dirname "$0")/.."
N="${1:-200}"
bench_bin() {
  cargo bench -p canopen-core --bench "$1" --no-run --message-format=json 2>/dev/null \
    | grep "\"executable\":\"[^\"]*$1" | sed 's/.*"executable":"\([^"]*\)".*/\1/' | tail -1
}
BIN=$(bench_bin sdo_instructions)
PDO_BIN=$(bench_bin pdo_instructions)
[ -x "$BIN" ] && [ -x "$PDO_BIN" ] || { echo "bench binary not found" >&2; exit 1; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
ir() { # scenario iterations [binary] → total Ir
  valgrind --tool=callgrind --callgrind-out-file="$TMP/out" "${3:-$BIN}" "$1" "$2" >"$TMP/stdout" 2>/dev/null
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
printf '\n%-20s %10s %12s %10s %14s\n' scenario frames instructions per-frame per-iteration
for s in rpdo sync_tpdo; do
  base=$(ir "$s" 0 "$PDO_BIN")
  full=$(ir "$s" "$N" "$PDO_BIN")
  frames=$(sed 's/.*: \([0-9]*\) frames.*/\1/' "$TMP/stdout")
  awk -v s="$s" -v f="$frames" -v a="$full" -v b="$base" -v n="$N" \
    'BEGIN { printf "%-20s %10d %12d %10.1f %14.1f\n", s, f, a - b, (a - b) / f, (a - b) / n }'
done
