#!/usr/bin/env bash
# Flash and RAM of the stack on a Cortex-M4F (DESIGN.md "Performance", footprint): builds the firmware
# example (examples/firmware, STM32F446RE, embassy) with the footprint profile (opt-level "s", LTO,
# panic = "abort", codegen-units = 1) in separate builds, since a Cargo feature holds for a whole build:
#   node      every canopen-core feature but the optional objects and `crc-table` (see --optional): the full
#             reference set, with the block CRC from the 32-byte nibble table;
#   minimal   canopen-core without its optional features (issue 13's minimal device: NMT, heartbeat, SDO
#             expedited + segmented, 4 RPDO + 4 TPDO with a fixed mapping, SYNC, EMCY; none of the optional
#             objects 1003h, 1007h, 1008h-100Ah, 1010h/1011h, 1015h, 1019h, 1029h),
#             `--no-default-features --features minimal`;
#   node-data node with its application dictionary as data (the firmware's feature `od-data`: `#[od(compact,
#             zerocopy)]`, issue 41 goal 3), so the fixed cost of the core's generic path (od::data) over the
#             derive's match arms is held: its flash is ratcheted, and its difference to node printed;
# and the CAN-echo baseline. It prints text/data/bss of each and each device's difference to the baseline,
# which is the stack's own cost:
#   flash = Δ(text + data)     (Berkeley `size`: text = .vector_table + .text + .rodata)
#   RAM   = Δ(data + bss) minus Δ(task storage)
# Task storage is embassy-executor's per-task `POOL` statics (each task's future; there is no shared arena
# in embassy-executor 0.10): it is reported apart. The node itself is a `static` (StaticCell) in .bss, so it
# is counted in RAM.
#
# Usage: scripts/footprint.sh [--check] [--ratchet] [--breakdown] [--optional] [--services]
#   --check      exit 1 when a device's share is over its target (node: flash 12,000 B, RAM 2,500 B;
#                minimal: flash 8,000 B, RAM 2,500 B)
#   --ratchet    exit 1 when a figure grew more than 2 % over its line in scripts/footprint.baseline; a
#                figure that went down prints the one-line update of that file
#   --breakdown  also print where the node and minimal binaries' flash goes, by crate/module (DWARF line
#                table)
#   --optional   also build node with each optional object of canopen-core (features manufacturer-status
#                1002h, high-res-time 1013h, verify-config 1020h, emcy-consumer 1028h, mpdo 1FA0h/1FD0h
#                and the MPDO paths; the reference set leaves them out) and with crc-table (the block CRC
#                from a 512-byte table instead of the nibble table), and print the flash and RAM each adds
#                to node
#   --services   also build the minimal device's application with the full reference set minus one of its
#                canopen-core features at a time, and print what each feature costs in the full set (a
#                feature linked only when the application uses it, e.g. the SDO client, shows about 0)
# Needs: rustup target add thumbv7em-none-eabihf; binutils `size` and `nm` (they read ARM ELF files).
set -euo pipefail
SCRIPTS=$(cd "$(dirname "$0")" && pwd)
cd "$SCRIPTS/../examples/firmware"
declare -A FLASH_TARGET=([node]=12000 [minimal]=8000) RAM_TARGET=([node]=2500 [minimal]=2500)
check=0 ratchet=0 breakdown=0 optional=0 services=0
for a in "$@"; do
  case $a in
    --check) check=1 ;;
    --ratchet) ratchet=1 ;;
    --breakdown) breakdown=1 ;;
    --optional) optional=1 ;;
    --services) services=1 ;;
    *) echo "usage: $0 [--check] [--ratchet] [--breakdown] [--optional] [--services]" >&2; exit 2 ;;
  esac
done

# The firmware's default build stores 1010h and the LSS configuration in flash (feature `store`); DESIGN.md's
# reference set stores nothing, so `node` is measured without it and `node+store` is reported beside it.
T=target/thumbv7em-none-eabihf/release
cargo build --release --bins --quiet
cp "$T/node" "$T/node+store"
cargo build --release --no-default-features --features od-data --bin node --quiet
cp "$T/node" "$T/node-data"
cargo build --release --no-default-features --features full --bin node --quiet
cargo build --release --no-default-features --features minimal --bin minimal --quiet

# text data bss of a binary (Berkeley format, the conventional three numbers)
berkeley() { size -B "$1" | awk 'NR == 2 { print $1, $2, $3 }'; }
# bytes of embassy-executor task storage (every `<task>::POOL` static)
pools() { nm -S -t d -C "$1" | awk '$3 ~ /^[bBdD]$/ && $4 ~ /::POOL$/ { n += $2 } END { print n + 0 }'; }

printf '%-10s %8s %8s %8s | %8s %8s %12s %12s\n' binary text data bss flash ram task-storage ram-w/o-tasks
declare -A F R P
for b in baseline node minimal node+store node-data; do
  read -r text data bss < <(berkeley "$T/$b")
  F[$b]=$((text + data)) R[$b]=$((data + bss)) P[$b]=$(pools "$T/$b")
  printf '%-10s %8d %8d %8d | %8d %8d %12d %12d\n' "$b" "$text" "$data" "$bss" "${F[$b]}" "${R[$b]}" "${P[$b]}" \
    $((R[$b] - P[$b]))
done

verdict() { if [ "$1" -le "$2" ]; then echo "ok, target <= $2"; else echo "OVER target <= $2 by $(($1 - $2))"; fi; }
declare -A FIG # "<device>.<figure>" -> bytes, the figures the ratchet compares
over=0
for d in node minimal; do
  FIG[$d.flash]=$((F[$d] - F[baseline]))
  FIG[$d.ram]=$(((R[$d] - P[$d]) - (R[baseline] - P[baseline])))
  FIG[$d.tasks]=$((P[$d] - P[baseline]))
  echo
  echo "$d: stack's own flash ($d - baseline, text + data): ${FIG[$d.flash]} bytes ($(verdict "${FIG[$d.flash]}" "${FLASH_TARGET[$d]}"))"
  echo "$d: stack's own RAM ($d - baseline, data + bss, without task storage): ${FIG[$d.ram]} bytes ($(verdict "${FIG[$d.ram]}" "${RAM_TARGET[$d]}"))"
  echo "$d: task storage, $d - baseline (executor POOL statics, not counted above): ${FIG[$d.tasks]} bytes"
  all=$((FIG[$d.ram] + FIG[$d.tasks]))
  echo "$d: RAM including the task storage (issue 13's measure): $all bytes ($(verdict "$all" "${RAM_TARGET[$d]}"))"
  if [ "${FIG[$d.flash]}" -gt "${FLASH_TARGET[$d]}" ] || [ "$all" -gt "${RAM_TARGET[$d]}" ]; then over=1; fi
done
# The firmware as shipped (default feature `store`): its stack share is ratcheted whole. What `store` adds
# (node+store - node) is printed, not ratcheted: as a difference of two LTO builds it also moves with what
# LTO inlines in the rest of the node (+64 B when a change took 196 B out of node and 132 B out of
# node+store, the store's own code byte for byte the same).
FIG[node+store.flash]=$((F[node+store] - F[baseline]))
echo
echo "node+store: the firmware as shipped, stack's own flash (node+store - baseline): ${FIG[node+store.flash]} bytes"
echo "node+store: 1010h/1011h and the LSS configuration in flash (canopen-embassy FlashStorage, the firmware's" \
  "default feature store) add $((F[node+store] - F[node])) bytes of flash and" \
  "$(((R[node+store] - P[node+store]) - (R[node] - P[node]))) bytes of RAM to node"
# The node with its dictionary as data: ratcheted whole, and its difference to node (the generic path's
# fixed cost less the match arms it replaces, for the node's 7 objects) printed.
FIG[node-data.flash]=$((F[node-data] - F[baseline]))
echo
echo "node-data: node with its dictionary as data (#[od(compact, zerocopy)]), stack's own flash (node-data - baseline):" \
  "${FIG[node-data.flash]} bytes, $((F[node-data] - F[node])) bytes more than node"
echo
echo "node binary, RAM by static (bytes):"
nm -S -t d -C --size-sort "$T/node" | awk '$3 ~ /^[bBdD]$/ && $2 >= 16 { s = $2; $1 = $2 = $3 = ""; sub(/^ +/, ""); printf "  %6d  %s\n", s, $0 }' | sort -rn

if [ "$breakdown" = 1 ]; then
  echo
  echo "node binary, flash (.text + .rodata code/data with line info) by source, bytes (see footprint-breakdown.py):"
  python3 ../../scripts/footprint-breakdown.py "$T/node" "$T/baseline"
  echo
  echo "minimal binary, flash by source, bytes:"
  python3 ../../scripts/footprint-breakdown.py "$T/minimal" "$T/baseline"
fi

if [ "$optional" = 1 ]; then
  echo
  echo "optional objects and the 512-byte CRC table, each built into node (canopen-core feature; bytes added to node):"
  for f in manufacturer-status high-res-time verify-config emcy-consumer mpdo crc-table; do
    cargo build --release --no-default-features --features "full,canopen-core/$f" --bin node --quiet
    read -r text data bss < <(berkeley "$T/node")
    printf '  %-20s flash %+6d  RAM %+6d\n' "$f" $((text + data - F[node])) $((data + bss - R[node]))
  done
  cargo build --release --no-default-features --features full --bin node --quiet # leave node as measured
fi

if [ "$services" = 1 ]; then
  echo
  echo "what each canopen-core feature of the full set costs there (minimal's application; bytes of flash and of RAM, task storage included):"
  full=$(python3 -c 'import tomllib; print(" ".join(tomllib.load(open("Cargo.toml", "rb"))["features"]["full"]))')
  cargo build --release --no-default-features --features "minimal $full" --bin minimal --quiet
  read -r text data bss < <(berkeley "$T/minimal")
  all_flash=$((text + data)) all_ram=$((data + bss))
  echo "  minimal's application with the full set: flash $((all_flash - F[baseline])), RAM $((all_ram - R[baseline]))"
  for f in $full; do
    others=$(for g in $full; do [ "$g" = "$f" ] || printf '%s ' "$g"; done)
    cargo build --release --no-default-features --features "minimal $others" --bin minimal --quiet
    read -r text data bss < <(berkeley "$T/minimal")
    printf '  %-36s flash %6d  RAM %6d\n' "$f" $((all_flash - text - data)) $((all_ram - data - bss))
  done | sort -k3 -rn
  cargo build --release --no-default-features --features minimal --bin minimal --quiet # leave minimal as measured
fi

status=0
if [ "$ratchet" = 1 ]; then
  echo
  for k in "${!FIG[@]}"; do echo "$k ${FIG[$k]}"; done |
    (cd "$SCRIPTS/.." && python3 scripts/ratchet.py scripts/footprint.baseline bytes) || status=1
fi
if [ "$check" = 1 ] && [ "$over" = 1 ]; then
  echo "FAIL: the stack's own footprint is over target" >&2
  status=1
fi
exit $status
