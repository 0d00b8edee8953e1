#!/usr/bin/env bash
# Flash and RAM of the stack on a Cortex-M4F (DESIGN.md "Performance", footprint): builds the firmware
# example (examples/firmware, STM32F446RE, embassy) and its CAN-echo baseline with the footprint profile
# (opt-level "s", LTO, panic = "abort", codegen-units = 1), prints text/data/bss of each, and the
# difference, which is the stack's own cost:
#   flash = Δ(text + data)     (Berkeley `size`: text = .vector_table + .text + .rodata)
#   RAM   = Δ(data + bss) minus Δ(task storage)
# Task storage is embassy-executor's per-task `POOL` statics (each task's future; there is no shared arena
# in embassy-executor 0.10): it is reported apart. The node itself is a `static` (StaticCell) in .bss, so it
# is counted in RAM.
#
# Usage: scripts/footprint.sh [--check] [--breakdown]
#   --check      exit 1 when the stack's own share is over the targets (flash 12,000 B, RAM 2,500 B)
#   --breakdown  also print where the node binary's flash goes, by crate/module (DWARF line table)
# Needs: rustup target add thumbv7em-none-eabihf; binutils `size` and `nm` (they read ARM ELF files).
set -euo pipefail
cd "$(dirname "$0")/../examples/firmware"
FLASH_TARGET=12000
RAM_TARGET=2500
check=0 breakdown=0
for a in "$@"; do
  case $a in
    --check) check=1 ;;
    --breakdown) breakdown=1 ;;
    *) echo "usage: $0 [--check] [--breakdown]" >&2; exit 2 ;;
  esac
done

# The reference feature set of DESIGN.md "Performance" stores nothing: the node is measured without the
# firmware's `store` feature (1010h/LSS in flash), which is measured apart below as `node+store`.
cargo build --release --bins --quiet
T=target/thumbv7em-none-eabihf/release
cp "$T/node" "$T/node+store"
cargo build --release --bins --quiet --no-default-features

# text data bss of a binary (Berkeley format, the conventional three numbers)
berkeley() { size -B "$1" | awk 'NR == 2 { print $1, $2, $3 }'; }
# bytes of embassy-executor task storage (every `<task>::POOL` static)
pools() { nm -S -t d -C "$1" | awk '$3 ~ /^[bBdD]$/ && $4 ~ /::POOL$/ { n += $2 } END { print n + 0 }'; }

printf '%-10s %8s %8s %8s | %8s %8s %12s %12s\n' binary text data bss flash ram task-storage ram-w/o-tasks
declare -A F R P
for b in baseline node node+store; do
  read -r text data bss < <(berkeley "$T/$b")
  F[$b]=$((text + data)) R[$b]=$((data + bss)) P[$b]=$(pools "$T/$b")
  printf '%-10s %8d %8d %8d | %8d %8d %12d %12d\n' "$b" "$text" "$data" "$bss" "${F[$b]}" "${R[$b]}" "${P[$b]}" \
    $((R[$b] - P[$b]))
done

flash=$((F[node] - F[baseline]))
ram=$(((R[node] - P[node]) - (R[baseline] - P[baseline])))
tasks=$((P[node] - P[baseline]))
verdict() { if [ "$1" -le "$2" ]; then echo "ok, target <= $2"; else echo "OVER target <= $2 by $(($1 - $2))"; fi; }
echo
echo "stack's own flash (node - baseline, text + data): $flash bytes ($(verdict $flash $FLASH_TARGET))"
echo "stack's own RAM (node - baseline, data + bss, without task storage): $ram bytes ($(verdict $ram $RAM_TARGET))"
echo "task storage, node - baseline (executor POOL statics, not counted above): $tasks bytes"
echo "store/restore and LSS configuration in flash (canopen-embassy FlashStorage, firmware feature store): +$((F[node+store] - F[node])) bytes flash, +$(((R[node+store] - P[node+store]) - (R[node] - P[node]))) bytes RAM"
echo
echo "node binary, RAM by static (bytes):"
nm -S -t d -C --size-sort "$T/node" | awk '$3 ~ /^[bBdD]$/ && $2 >= 16 { s = $2; $1 = $2 = $3 = ""; sub(/^ +/, ""); printf "  %6d  %s\n", s, $0 }' | sort -rn

if [ "$breakdown" = 1 ]; then
  echo
  echo "node binary, flash (.text + .rodata code/data with line info) by source, bytes (see footprint-breakdown.py):"
  python3 ../../scripts/footprint-breakdown.py "$T/node" "$T/baseline"
fi

if [ "$check" = 1 ] && { [ "$flash" -gt "$FLASH_TARGET" ] || [ "$ram" -gt "$RAM_TARGET" ]; }; then
  echo "FAIL: the stack's own footprint is over target" >&2
  exit 1
fi
