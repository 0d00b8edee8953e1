#!/usr/bin/env bash
# The async master's figures over vcan0 (issue 23 item 4), in ONE with-vcan VM (scripts/vcan-run.sh; here if
# vcan0 exists), release builds, against the example node (examples/node.rs, tokio runner, its own process):
#   - 1 MiB by block transfer with CRC each way (16 x 64 KiB, the 2005h DOMAIN's capacity), byte-exact:
#     canopen-master (examples/master_bench.rs) and python canopen (tests/python/bench_python.py), KiB/s,
#     REPEAT rounds (default 3) of one each in turn, and per round how many times python's rate ours is;
#   - ten example nodes (11..20, own processes) read at once (1018h:04), time per round;
#   - the master's system calls per frame on the bus (`strace -f -c` of the master process, all threads):
#     256 KiB block+CRC each way, and the ten-node reads; total and without clock reads (clock_gettime);
#     then the example node's (node 5 restarted under strace) for the same 256 KiB run.
#     Frames: received ones counted by the master, sent ones from the protocol (examples/master_bench.rs).
# Inside the VM master and nodes share one CPU: compare the figures with each other only. bench-vcan.sh may
# call this script. Usage: [REPEAT=3] scripts/bench-master.sh [ROUNDS_OF_64KIB] (default 16; SKIP_PIP=1
# skips pip).
set -euo pipefail
cd "$(dirname "$0")/.."
ROUNDS=${1:-16}
REPEAT=${REPEAT:-3}
source scripts/bench-setup.sh
cargo build --release --example node --example master_bench
cat > target/bench-master-in-vm.sh <<INNER
set -euo pipefail
N=target/release/examples/node; B=target/release/examples/master_bench
\$N --eds target/bench-master.eds >/dev/null
\$N --quiet --heartbeat 0 > target/bench-master-node.log 2>&1 & pid=\$!
pids=\$pid
for id in \$(seq 11 20); do
    \$N --quiet --heartbeat 0 --node-id \$id --serial \$((1000 + id)) >/dev/null 2>&1 & pids="\$pids \$!"
done
trap 'kill \$pids 2>/dev/null || true' EXIT
sleep 1
echo "== 1 MiB block+CRC each way, against the example node (tokio runner), $REPEAT rounds"
kib() { sed -n "s/.*\$1 \\([0-9.]*\\) KiB\\/s.*/\\1/p" | head -1; }
for r in \$(seq $REPEAT); do
    ours=\$(\$B block --node 5 --size \$(( $ROUNDS * 65536 )))
    py=\$(python3 tests/python/bench_python.py target/bench-master.eds \$pid 65536 $ROUNDS)
    echo "\$ours"; echo "\$py"
    od=\$(kib download <<<"\$ours"); ou=\$(kib upload <<<"\$ours")
    pd=\$(grep 'block+CRC download' <<<"\$py" | sed -n 's/.* = \\([0-9.]*\\) KiB\\/s.*/\\1/p')
    pu=\$(grep 'block+CRC upload' <<<"\$py" | sed -n 's/.* = \\([0-9.]*\\) KiB\\/s.*/\\1/p')
    awk -v r=\$r -v od=\$od -v ou=\$ou -v pd=\$pd -v pu=\$pu 'BEGIN{printf "round %d: download %.1f vs python %.1f KiB/s = %.1fx, upload %.1f vs %.1f KiB/s = %.1fx\\n", r, od, pd, od/pd, ou, pu, ou/pu}'
done
echo "== ten nodes read at once"
\$B ten --first 11 --rounds 50
echo "== canopen-master system calls per frame (strace -f -c of the master process)"
calls() { awk '\$NF=="total"{t=\$4} \$NF=="clock_gettime"{c=\$4} END{print t+0, c+0}' "\$1"; }
printf '| workload | frames | calls | calls/frame | w/o clock_gettime /frame |\n|---|---:|---:|---:|---:|\n'
out=\$(strace -f -c -S calls -o target/strace-master-block.txt \$B block --node 5 --size 262144)
frames=\$(sed -n 's/^frames=\([0-9]*\).*/\1/p' <<<"\$out")
read -r t c < <(calls target/strace-master-block.txt)
awk -v f=\$frames -v t=\$t -v c=\$c 'BEGIN{printf "| 256 KiB block+CRC each way | %d | %d | %.3f | %.3f |\n", f, t, t/f, (t-c)/f}'
strace -f -c -S calls -o target/strace-master-ten.txt \$B ten --first 11 --rounds 50 >/dev/null
frames=\$((50 * 10 * 2))
read -r t c < <(calls target/strace-master-ten.txt)
awk -v f=\$frames -v t=\$t -v c=\$c 'BEGIN{printf "| ten nodes read at once, 50 rounds (incl. start-up) | %d | %d | %.3f | %.3f |\n", f, t, t/f, (t-c)/f}'
echo "the master's most frequent calls in the 256 KiB run:"
sed -n '3,9p' target/strace-master-block.txt
echo "== the example node's system calls per frame (strace -f -c of node 5, restarted under strace)"
kill \$pid; wait \$pid 2>/dev/null || true
strace -f -c -S calls -o target/strace-node-block.txt \$N --quiet --heartbeat 0 >/dev/null 2>&1 & spid=\$!
sleep 1.5
out=\$(\$B block --node 5 --size 262144)
kill \$(pgrep -P \$spid) 2>/dev/null || true; wait \$spid || true # strace writes its table when the node ends
frames=\$(sed -n 's/^frames=\([0-9]*\).*/\1/p' <<<"\$out")
read -r t c < <(calls target/strace-node-block.txt)
awk -v f=\$frames -v t=\$t -v c=\$c 'BEGIN{printf "| node: 256 KiB block+CRC each way | %d | %d | %.3f | %.3f |\n", f, t, t/f, (t-c)/f}'
sed -n '3,9p' target/strace-node-block.txt
INNER
status=0
vcan_run vcan0 -- bash target/bench-master-in-vm.sh || status=$?
if [[ $status == 125 ]]; then echo "bench-master: no vcan0 and the with-vcan VM could not start (exit 125)" >&2; exit 1; fi
exit $status
