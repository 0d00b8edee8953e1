#!/usr/bin/env bash
# Plants hand-chosen faults in canopen-core one at a time and checks that the test suite catches each
# (issue 21, item 4). A cheap stand-in for cargo-mutants on a 2-core machine: each fault is one literal text
# replacement in one source file, found by its text (not its path, so moving modules does not break it), then
#   cargo test -p canopen-core --lib            (its unit tests; doctests left out: slow, and they check
#                                               examples, not behaviour)
#   cargo test -p canopen-core --test <each>    (its integration tests)
#   cargo test --test <each root test named for the fault>
# run, each only if the one before passed; a failing test "kills" the fault, all passing means it "survived".
# A fault that does not build kills nothing (it proves no test): it is reported NOT BUILT, as a fault whose
# text is not found is NOT PLANTED, and its text needs updating. The file is restored after each fault (and
# on exit or Ctrl-C).
#
# Usage: scripts/plant-faults.sh [name...]   (no name: every fault). Prints a table; exits 1 if any
# survived, could not be planted or did not build. Results also go to target/plant-faults.txt.
set -uo pipefail
cd "$(dirname "$0")/.."

# name @@ root tests (comma-separated) @@ text to find (exactly once in canopen-core/src) @@ replacement. "\n" is a newline.
FAULTS=(
  'pdo10-rpdo-inhibit-changes-while-valid @@ checklist_items @@ if rules && valid {\n                    return Err(AbortCode::InvalidValue); // PDO-10 @@ if rules && valid && f.tx() {\n                    return Err(AbortCode::InvalidValue); // PDO-10'
  'pdo10-rpdo-inhibit-not-kept @@ checklist_items @@ comm.inhibit_100us = v as u16; @@ if f.tx() { comm.inhibit_100us = v as u16; }'
  'sdo31-block-upload-time-out-from-the-take @@ sdo_node @@ if self.block_upload_sent(now) { @@ if false && self.block_upload_sent(now) {'
  'store08-any-1011h-signature @@ store_restore @@ return Err(if v != sig { AbortCode::CannotStore } @@ return Err(if v != sig && f.slot() == Slot::Store { AbortCode::CannotStore }'
  'store08-load-signature-byte-order @@ store_restore @@ LOAD_SIGNATURE: u32 = 0x6461_6F6C @@ LOAD_SIGNATURE: u32 = 0x6C6F_6164'
  'store09-failure-wrong-abort-code @@ store_restore @@ -> AbortCode {\n    AbortCode::HardwareError @@ -> AbortCode {\n    AbortCode::GeneralError'
  'store09-erase-failure-ignored @@ store_restore @@             st.erase(target)?;\n        }\n        let mut crc_data @@             let _ = st.erase(target);\n        }\n        let mut crc_data'
  'sdo-toggle-not-checked @@ sdo_node @@ let last = command & 0x01 != 0;\n        if t != *toggle { @@ let last = command & 0x01 != 0;\n        if false && t != *toggle {'
  'sdo-block-crc-not-checked @@ sdo_node @@ if bd.crc_on && bd.crc.get() != crc { @@ if false && bd.crc_on && bd.crc.get() != crc {'
  'sdo-expedited-size-misread @@ sdo_node @@ let len = 4 - ((b[0] >> 2) & 0x03); @@ let len = 4 - ((b[0] >> 3) & 0x01);'
  'cob13-restricted-off-by-one @@ pdo_sync_emcy @@ 0x701..=0x7FF) @@ 0x702..=0x7FF)'
  'sync-window-doubled @@ pdo_sync_emcy,checklist_items @@ now <= t + Duration::from_micros(u64::from(w)), @@ now <= t + Duration::from_micros(2 * u64::from(w)),'
  'sync-window-boundary @@ pdo_sync_emcy,checklist_items @@ now <= t + Duration::from_micros(u64::from(w)), @@ now < t + Duration::from_micros(u64::from(w)),'
  'sync-counter-wraps-late @@ pdo_sync_emcy @@ self.counter = if c >= self.counter_overflow() @@ self.counter = if c > self.counter_overflow()'
  'rpdo-short-frame-accepted @@ pdo_sync_emcy,checklist_items @@ if data.len() < need { @@ if data.len() + 1 < need {'
  'rpdo-applied-outside-operational @@ checklist_items @@ if frame.is_rtr() || self.nmt.state() != NmtState::Operational { @@ if frame.is_rtr() {'
  'nmt-command-for-any-node @@ nmt_heartbeat_guarding @@ if !request.addresses(self.node_id.get()) { @@ if false {'
  'sdo10-block-initiate-response-without-multiplexer @@ checklist_items @@ frame(0xA0 | (u8::from(crc) << 2), mux.bits(), u32::from(self.block_size)) @@ frame(0xA0 | (u8::from(crc) << 2), 0, u32::from(self.block_size))'
  'err12-default-error-behaviour-not-pre-operational @@ checklist_items @@         emcy_inhibit_100us: 0,\n        error_behaviour: 0,\n        nmt_startup: 0x0000_0004, @@         emcy_inhibit_100us: 0,\n        error_behaviour: 1,\n        nmt_startup: 0x0000_0004,'
  'dev02-device-type-loses-additional-info @@ checklist_items @@ Slot::DeviceType => c.device_type, @@ Slot::DeviceType => c.device_type & 0xFFFF,'
  'heartbeat-producer-late-by-one-tick @@ nmt_heartbeat_guarding @@ let following = self.next.instant() + self.period(); @@ let following = self.next.instant() + self.period() + Duration::from_micros(1);'
  'emcy-inhibit-in-ms-not-100us @@ pdo_sync_emcy @@ Duration::from_100us(if INHIBIT { u64::from(n) } else { 0 }); @@ Duration::from_millis(if INHIBIT { u64::from(n) } else { 0 });'
  'tpdo-inhibit-boundary @@ pdo_sync_emcy,checklist_items @@ self.inhibit != Deadline::NONE && !self.inhibit.passed(now) @@ self.inhibit != Deadline::NONE && (!self.inhibit.passed(now) || self.inhibit.instant() == now)'
  'rpdo-event-timer-one-ms-late @@ pdo_sync_emcy,checklist_items @@ self.deadline = Deadline::at(now + Duration::from_millis(self.event_timer_ms.into())); @@ self.deadline = Deadline::at(now + Duration::from_millis(u64::from(self.event_timer_ms) + 1));'
  'pdo02-scan-takes-an-invalid-rpdo @@ pdo_sync_emcy @@ r.is_valid().then(|| r.can_id()) @@ Some(r.can_id())'
  'pdo29-table-takes-the-last-of-equal-can-ids @@ pdo_sync_emcy @@ let i = table.partition_point(|e| e.0 < id); @@ let i = table.partition_point(|e| e.0 <= id).saturating_sub(1);'
  'sdo-no-streams-begun-write-not-undone @@ sdo_node @@ od.abort_write(mux.index, mux.sub);\n                    return Err(AbortCode::UnsupportedAccess); @@ return Err(AbortCode::UnsupportedAccess);'
  'store02-saving-one-group-drops-the-other @@ store_restore @@ w.item(index, sub, &buf[..n])?; @@ let _ = (index, sub, n);'
  'emcy-inhibit-ignored @@ pdo_sync_emcy @@ self.next_allowed.instant().as_micros().wrapping_add(1) <= now.as_micros().wrapping_add(1) @@ true'
  'od11-table-low-limit-inclusive @@ od_all_types @@ if value < bound(from) { @@ if value <= bound(from) {'
  'pdo-offset-slot-two-bytes-as-one @@ od_all_types @@ 1 => copy_in::<2>(bytes, at, data), @@ 1 => copy_in::<1>(bytes, at, data),'
  'nmt04-table-default-not-unzigzagged @@ od_all_types @@ v = (v >> 1) ^ (v & 1).wrapping_neg(); @@ v >>= 1;'
  'od04-record-rows-run-into-the-next-object @@ od_all_types @@ _ => i < end, @@ _ => i <= end,'
  'pdo12-short-frame-ends-the-time-out @@ pdo_sync_emcy @@ let recovered = outcome != RxOutcome::TooShort && core::mem::take(&mut r.timed_out); @@ let recovered = core::mem::take(&mut r.timed_out) && outcome != RxOutcome::TooShort;'
  'od03-array-length-not-from-its-shape @@ od_all_types @@ n => (u8::from(n != 0), n), @@ n => (u8::from(n != 0), n.min(1)),'
  'od04-member-sub-from-its-place-off-by-one @@ eds_real @@ [] => (i - first + 1) as u8, @@ [] => (i - first + 2) as u8,'
  'od11-limits-of-another-shape @@ od_all_types @@ let Some(&at) = D::LIMITS.get(shape) else { @@ let Some(&at) = D::LIMITS.get(shape ^ 1) else {'
  'od01-first-row-wraps-miscounted @@ eds_real @@ + 256 * wraps.partition_point @@ + 255 * wraps.partition_point'
)

# Field n (1-based) of a fault.
field() { printf '%s' "$1" | awk -v n="$2" 'BEGIN { FS = " @@ " } { printf "%s", $n }'; }

selected=("$@")
out=target/plant-faults.txt
mkdir -p target
: >"$out"
backup=""
file=""
# The property tests replay their saved failing cases (*.proptest-regressions) under each fault, and save the
# case that kills it: a case that fails only with the fault planted. restore puts them back with the source.
regressions() { find . \( -name target -o -name .git \) -prune -o -name '*.proptest-regressions' -print | sort; }
saved=$(mktemp -d)
regressions >"$saved/list"
tar -cf "$saved/files.tar" -T "$saved/list"
restore() {
  if [ -n "$backup" ] && [ -f "$backup" ]; then cp "$backup" "$file"; rm -f "$backup"; backup=""; fi
  regressions | comm -13 "$saved/list" - | xargs -r -d '\n' rm -f
  tar -xf "$saved/files.tar"
}
trap 'restore; exit 130' INT TERM
trap 'restore; rm -rf "$saved"' EXIT

# canopen-core's integration tests, named one by one for `cargo test --test` (`--test '*'` fails on a target
# whose required features are off): those `cargo test -p canopen-core --tests` builds, the ones whose required
# features the default features turn on.
core_tests=()
for t in $(cargo metadata --no-deps --format-version 1 | python3 -c '
import json, sys
pkg = next(p for p in json.load(sys.stdin)["packages"] if p["name"] == "canopen-core")
features, on, todo = pkg["features"], set(), ["default"]
while todo:
    f = todo.pop()
    if f in features and f not in on:
        on.add(f)
        todo += features[f]
for t in pkg["targets"]:
    if t["kind"] == ["test"] and set(t.get("required-features", [])) <= on:
        print(t["name"])
'); do core_tests+=(--test "$t"); done
[ ${#core_tests[@]} -gt 0 ] || { echo "plant-faults: no integration tests of canopen-core found"; exit 1; }

killed=0 survived=0 broken=0
for f in "${FAULTS[@]}"; do
  name=$(field "$f" 1) test=$(field "$f" 2) find=$(field "$f" 3) repl=$(field "$f" 4)
  if [ ${#selected[@]} -gt 0 ] && ! printf '%s\n' "${selected[@]}" | grep -qx "$name"; then continue; fi
  # The one file holding the text exactly once.
  file=$(FIND="$find" python3 - <<'EOF'
import os, pathlib
needle = os.environ["FIND"].replace("\\n", "\n")
hits = [(p, p.read_text().count(needle)) for p in pathlib.Path("canopen-core/src").rglob("*.rs")]
hits = [(p, n) for p, n in hits if n]
print(hits[0][0] if len(hits) == 1 and hits[0][1] == 1 else "")
EOF
)
  if [ -z "$file" ]; then
    printf '%-40s NOT PLANTED (text not found exactly once)\n' "$name" | tee -a "$out"
    broken=$((broken + 1))
    continue
  fi
  backup=$(mktemp)
  cp "$file" "$backup"
  FIND="$find" REPL="$repl" FILE="$file" python3 - <<'EOF'
import os, pathlib
p = pathlib.Path(os.environ["FILE"])
p.write_text(p.read_text().replace(os.environ["FIND"].replace("\\n", "\n"), os.environ["REPL"].replace("\\n", "\n"), 1))
EOF
  start=$(date +%s)
  log=target/plant-faults-$name.log
  root_tests=()
  for t in ${test//,/ }; do root_tests+=(--test "$t"); done
  # A fault that makes a test hang is killed by the time limit. The unit tests first, alone: `--lib --tests`
  # builds every integration test before it runs the first test, and the unit tests kill about half of the
  # faults; the same tests run, in the same order, and a fault survives only if all of them pass.
  if timeout 600 cargo test -q -p canopen-core --lib >"$log" 2>&1 &&
    timeout 600 cargo test -q -p canopen-core "${core_tests[@]}" >>"$log" 2>&1 &&
    timeout 600 cargo test -q "${root_tests[@]}" >>"$log" 2>&1; then
    verdict=SURVIVED
    survived=$((survived + 1))
  elif grep -q "could not compile" "$log"; then
    # A fault that does not build proves nothing about the tests: its text needs updating.
    verdict="NOT BUILT ($(grep -m1 -oE '^error(\[E[0-9]+\])?:.*' "$log" | cut -c1-60))"
    broken=$((broken + 1))
  else
    verdict=killed
    killed=$((killed + 1))
    # Which test caught it.
    by=$(grep -m1 -oE "^---- [^ ]+|has been running for over" "$log" | sed 's/^---- //' | cut -c1-60)
    verdict="killed   ($by)"
  fi
  restore
  printf '%-40s %-16s %4ss %s\n' "$name" "$file" "$(($(date +%s) - start))" "$verdict" | sed "s|canopen-core/src/||" | tee -a "$out"
done
echo "killed $killed, survived $survived, not planted or not built $broken" | tee -a "$out"
[ "$survived" -eq 0 ] && [ "$broken" -eq 0 ]
