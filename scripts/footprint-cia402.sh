#!/usr/bin/env bash
# What the CiA 402 drive part (canopen-cia402) costs in firmware: the firmware example's node (STM32F446RE,
# embassy, the footprint profile: opt-level "s", LTO, panic = "abort") built twice with the reference set of
# canopen-core (`--no-default-features --features full`, no flash store), once as it is (`node`) and once as
# a drive (`--features cia402`, copied to `drive`): its application dictionary composed with the drive's
# objects (canopen_cia402::Drive), the drive cycle every 10 ms in the process task with an open-loop stepper
# as the Motor, and the SYNC handed to the drive. Prints text/data/bss of both and the drive's difference:
#   flash = Δ(text + data), RAM = Δ(data + bss)
# Needs: rustup target add thumbv7em-none-eabihf; binutils `size`.
set -euo pipefail
cd "$(dirname "$0")/../examples/firmware"
T=target/thumbv7em-none-eabihf/release
cargo build --release --locked --no-default-features --features cia402 --bin node --quiet
cp "$T/node" "$T/drive"
cargo build --release --locked --no-default-features --features full --bin node --quiet
read -r nt nd nb < <(size -B "$T/node" | awk 'NR == 2 { print $1, $2, $3 }')
read -r dt dd db < <(size -B "$T/drive" | awk 'NR == 2 { print $1, $2, $3 }')
printf '%-8s %8s %8s %8s\n' "" text data bss
printf '%-8s %8d %8d %8d\n' node "$nt" "$nd" "$nb" drive "$dt" "$dd" "$db"
echo "CiA 402 part (drive - node): flash $(( dt + dd - nt - nd )) B, RAM $(( dd + db - nd - nb )) B"
