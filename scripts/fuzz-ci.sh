#!/usr/bin/env bash
# Fuzzing in CI (issue 21, item 5): every cargo-fuzz target in fuzz/ runs FUZZ_SECONDS (default 60) of
# fuzzing on nightly, starting from the checked-in corpus fuzz/seeds/<target>/.
#
# Installs what a clean CI machine lacks: the nightly toolchain (minimal profile) and cargo-fuzz.
# The build happens before the clock starts, so each target gets its full time fuzzing.
# New interesting inputs go to fuzz/corpus/<target>/ (gitignored). A crash or time-out is copied into
# fuzz/seeds/<target>/ under its libFuzzer name, so that it is a test case kept: commit it with the fix,
# and every later run replays it first (libFuzzer runs the whole corpus before mutating).
#
# The checked-in corpus is the hand-written seeds (named) plus a libFuzzer merge of runs' corpora (hash-named;
# -merge=1 keeps only inputs that add coverage). To refresh it after a long run, minimising (issue 42 item 3:
# the hand-written seeds stay, the hash-named ones are chosen again from the old ones and the run's corpus):
#   cd fuzz && mkdir /tmp/min /tmp/old && cd seeds/<t>
#   ls | grep -vxE '[0-9a-f]{40}' | xargs cp -t /tmp/min && ls | grep -xE '[0-9a-f]{40}' | xargs cp -t /tmp/old
#   cd ../.. && target/x86_64-unknown-linux-gnu/release/<t> -merge=1 /tmp/min /tmp/old corpus/<t>
#   rm seeds/<t>/* && cp /tmp/min/* seeds/<t>/   # then check: -runs=0 over seeds/<t> gives the union's cov/ft
#
# Usage: scripts/fuzz-ci.sh [target...]   (no target: all of `cargo fuzz list`)
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
SECONDS_PER_TARGET=${FUZZ_SECONDS:-60}

if ! rustup toolchain list | grep -q '^nightly'; then
  rustup toolchain install nightly --profile minimal
fi
if ! command -v cargo-fuzz >/dev/null; then
  cargo install cargo-fuzz --locked
fi
cargo +nightly --version
cargo fuzz --version
# `cargo fuzz build` takes no --locked: check the lockfile first, so a stale fuzz/Cargo.lock fails here (commit
# the refreshed file) instead of being rewritten in the checkout, as .ci/run's no_std builds do with --locked.
cargo +nightly metadata --locked --format-version 1 >/dev/null

targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  mapfile -t targets < <(cargo +nightly fuzz list)
fi
[ ${#targets[@]} -gt 0 ] || { echo "no fuzz targets found"; exit 1; }

# Every target is built first (one cargo at a time), then they fuzz side by side, as many at once as the machine
# has CPUs (libFuzzer runs one process on one CPU): each still gets its full time, the step takes less.
status=0
runnable=()
for t in "${targets[@]}"; do
  [ -d "seeds/$t" ] || { echo "FAIL: no checked-in corpus fuzz/seeds/$t"; status=1; continue; }
  echo "== $t: build"
  cargo +nightly fuzz build -O "$t"
  runnable+=("$t")
done

# One target's run: its libFuzzer output goes to artifacts/<t>.log, its verdict to artifacts/<t>.status.
fuzz_one() {
  local t=$1 start elapsed st=0
  rm -rf "artifacts/$t"
  mkdir -p "corpus/$t" "artifacts/$t"
  start=$(date +%s)
  cargo +nightly fuzz run -O "$t" "corpus/$t" "seeds/$t" -- \
    -max_total_time="$SECONDS_PER_TARGET" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    >"artifacts/$t.log" 2>&1 || st=1
  elapsed=$(($(date +%s) - start))
  echo "$st $elapsed" >"artifacts/$t.status"
}

jobs_max=$(nproc)
for t in "${runnable[@]}"; do
  echo "== $t: ${SECONDS_PER_TARGET} s from $(find "seeds/$t" -type f | wc -l) checked-in inputs"
  while [ "$(jobs -rp | wc -l)" -ge "$jobs_max" ]; do wait -n || true; done
  fuzz_one "$t" &
done
wait

for t in "${runnable[@]}"; do
  echo "== $t: libFuzzer's output (last 40 lines)"
  tail -n 40 "artifacts/$t.log"
  read -r st elapsed <"artifacts/$t.status" || { st=1 elapsed=0; }
  [ "$st" -eq 0 ] || { echo "FAIL: $t: libFuzzer exited with an error"; status=1; }
  # Whatever libFuzzer left behind is kept as a seed.
  found=$(find "artifacts/$t" -type f \( -name 'crash-*' -o -name 'timeout-*' -o -name 'oom-*' -o -name 'leak-*' \))
  if [ -n "$found" ]; then
    for a in $found; do
      cp "$a" "seeds/$t/"
      echo "FAIL: $t found $(basename "$a"); kept as fuzz/seeds/$t/$(basename "$a") (commit it with the fix)"
      echo "  reproduce: (cd fuzz && cargo +nightly fuzz run $t seeds/$t/$(basename "$a"))"
    done
    status=1
  fi
  if [ "$st" -eq 0 ] && [ "$elapsed" -lt "$SECONDS_PER_TARGET" ]; then
    echo "FAIL: $t stopped after ${elapsed} s, before its ${SECONDS_PER_TARGET} s"
    status=1
  fi
  echo "== $t: ${elapsed} s, corpus now $(find "corpus/$t" -type f | wc -l) new inputs"
done
exit "$status"
