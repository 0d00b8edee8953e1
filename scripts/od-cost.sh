#!/usr/bin/env bash
# Flash per dictionary object (issue 41 item 1): builds ci/od-cost (a bare-metal thumbv7em node, opt "s",
# LTO, one codegen unit) with a base dictionary and with 60 more objects of one kind, and prints
# (variant - base) / 60 for an UNSIGNED32 VAR with a default, an ARRAY of 4 x UNSIGNED16, a RECORD of
# UNSIGNED8 + UNSIGNED16 + UNSIGNED32 and a VISIBLE_STRING<16>; then the application dictionary of python
# canopen's e35.eds (a real drive: `canopenctl eds-to-rust`, scripts/fetch-eds.sh) against a one-VAR
# dictionary. Flash = text + data (Berkeley `size`); RAM (data + bss) is printed too: the node lives on the
# stack here, so any static would show.
#
# Usage: scripts/od-cost.sh [--check]
#   --check   exit 1 when a figure is over its target (VAR <= 24 B, ARRAY <= 40 B, e35 <= 10,700 B)
set -euo pipefail
shopt -s inherit_errexit
ROOT=$(cd "$(dirname "$0")/.." && pwd)
check=0
[ "${1:-}" = "--check" ] && check=1
N=60
BIN=$ROOT/ci/od-cost/target/thumbv7em-none-eabihf/release/od-cost
flash() { size -B "$BIN" | awk 'NR == 2 { print $1 + $2 }'; }
ram() { size -B "$BIN" | awk 'NR == 2 { print $2 + $3 }'; }
build() {
  (cd "$ROOT/ci/od-cost" && OD_COST=$1 cargo build --release --locked --quiet --target thumbv7em-none-eabihf)
  [ "$(ram)" -eq 0 ] || { echo "FAIL: OD_COST=$1 has $(ram) bytes of .data/.bss (a dictionary table in RAM)"; exit 1; }
  flash
}
over=0
verdict() { # figure(x100) target name
  if [ -z "$2" ]; then echo ""; elif [ "$1" -le $(($2 * 100)) ]; then echo "(ok, target <= $2)"; else over=1; echo "(OVER target <= $2)"; fi
}
base=$(build base)
echo "base dictionary: $base B flash, 0 B RAM outside the node"
declare -A TARGET=([var]=24 [array]=40 [record]= [string]=)
declare -A WHAT=([var]="UNSIGNED32 VAR with a default" [array]="ARRAY of 4 x UNSIGNED16" \
  [record]="RECORD of U8 + U16 + U32 (3 members)" [string]="VISIBLE_STRING<16> VAR with a default")
for k in var array record string; do
  f=$(build "$k:$N")
  per=$(((f - base) * 100 / N))
  printf '  one more %-40s %4d.%02d B  %s\n' "${WHAT[$k]}:" $((per / 100)) $((per % 100)) "$(verdict $per "${TARGET[$k]}")"
done
eds_dir=$(bash "$ROOT/scripts/fetch-eds.sh")
gen=$ROOT/ci/od-cost/target/e35.rs
(cd "$ROOT" && cargo run --quiet -p canopenctl -- eds-to-rust "$eds_dir/e35.eds" >"$gen")
one=$(build one)
e35=$(build "file:$gen")
echo "  e35.eds application dictionary ($(grep -c '#\[od(' "$gen") fields), over a one-VAR dictionary: $((e35 - one)) B $(verdict $(((e35 - one) * 100)) 10700)"
(cd "$ROOT/ci/od-cost" && cargo build --release --locked --quiet --target thumbv7em-none-eabihf) # leave base built
[ "$check" = 0 ] || [ "$over" = 0 ] || { echo "FAIL: a figure is over its target"; exit 1; }
