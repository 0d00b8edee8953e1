#!/usr/bin/env bash
# SDO throughput over vcan0 (here if it exists, else inside ONE with-vcan VM: scripts/vcan-run.sh), release builds:
#   - our client (`canopenctl bench`, on canopen-master) <-> our node (examples/node.rs, tokio runner): 1 MiB each way by
#     block transfer with CRC (16 transfers of 64 KiB, the 2005h DOMAIN's capacity), 128 KiB segmented;
#   - the same node with the blocking runner (--blocking), block+CRC only;
#   - python canopen <-> our node: 64 KiB block download and upload with CRC (python is the bottleneck).
# Each line also gives the node process's CPU time per frame it handled (/proc/<pid>/stat, 10 ms ticks).
# Then, in the same VM, system calls per frame (issue 19): python canopen drives four workloads against the
# node (tokio and blocking runner, heartbeat off) while `strace -f -c` counts the node's and python's calls:
# 2,000 expedited reads of 1018h:1, a 64 KiB block download with CRC (9,365 frames in), 4,000 SDO requests
# for node 6 (bystander), 1 s idle. Per frame sent towards the node: all calls, calls without clock_gettime,
# and the node's CPU (ticks under strace, so inflated alike for every row). python's counts are net of its
# interpreter start-up (what its idle run costs); the idle row counts the node's calls from 0.5 s after
# strace attached to the end of its window (1.3 s).
# Usage: scripts/bench-vcan.sh [SIZE_BYTES]   (SKIP_PIP=1 skips the pip install). Fails if the VM cannot start.
set -euo pipefail
cd "$(dirname "$0")/.."
SIZE=${1:-1048576}
source scripts/bench-setup.sh
cargo build --release --examples
cargo build --release -p canopenctl
cat > target/bench-in-vm.sh <<INNER
set -euo pipefail
N=target/release/examples/node; M=target/release/canopenctl
\$N --eds target/bench.eds >/dev/null
run_node() { \$N --quiet --heartbeat 1000 "\$@" > target/bench-node.log 2>&1 & echo \$!; }
pid=\$(run_node); sleep 0.5
echo "== our client <-> our node (tokio runner)"
\$M bench 5 --size $SIZE --segmented-size 131072 --node-pid \$pid
echo "== python canopen <-> our node (tokio runner)"
python3 tests/python/bench_python.py target/bench.eds \$pid 65536
kill \$pid; wait \$pid 2>/dev/null || true
pid=\$(run_node --blocking); sleep 0.5
echo "== our client <-> our node (blocking runner)"
\$M bench 5 --size $SIZE --node-pid \$pid
kill \$pid; wait \$pid 2>/dev/null || true
calls() { awk '\$NF=="total"{t=\$4} \$NF=="clock_gettime"{c=\$4} END{print t+0, c+0}' "\$1"; }
hz=\$(getconf CLK_TCK)
echo "== system calls per frame (strace -f -c), python canopen as the master, heartbeat off"
printf '| runner | workload | node calls/frame | node w/o clock | node CPU us/frame | python calls/frame | python w/o clock |\n|---|---|---:|---:|---:|---:|---:|\n'
for runner in tokio blocking; do
    flag=; [[ \$runner == blocking ]] && flag=--blocking
    \$N --quiet --heartbeat 0 \$flag > target/bench-node.log 2>&1 & pid=\$!; sleep 0.5
    pt0=0; pc0=0
    for w in idle bystander expedited block; do
        tids=\$(ls /proc/\$pid/task | paste -sd, -)
        # Idle: a full trace, counted from 0.5 s after the attach (attaching interrupts tokio's epoll_wait
        # with EINTR, which tokio answers with one more turn of its loop: an artefact of strace, not idle
        # cost). The workloads: strace -c over the whole window.
        if [[ \$w == idle ]]; then mode=(-ttt -o target/strace-idle.txt); else mode=(-c -o target/strace-node.txt); fi
        strace -f "\${mode[@]}" -p "\$tids" 2>/dev/null & spid=\$!; sleep 0.5
        t0=\$(date +%s.%N)
        out=\$(strace -f -c -o target/strace-py.txt python3 tests/python/bench_syscalls.py \$w target/bench.eds \$pid)
        sleep 0.3; kill -INT \$spid; wait \$spid 2>/dev/null || true
        frames=\$(sed -n 's/.*frames=\([0-9]*\).*/\1/p' <<<"\$out"); ticks=\$(sed -n 's/.*node_cpu_ticks=\([0-9]*\).*/\1/p' <<<"\$out")
        if [[ \$w == idle ]]; then
            # Lines "TID SECONDS call(...": calls entered after t0 (a call's "resumed" half is not a new one).
            read -r nt nc < <(awk -v t0=\$t0 '\$2+0 >= t0 && \$3 !~ /^</ {t++; if (\$3 ~ /^clock_gettime/) c++} END{print t+0, c+0}' target/strace-idle.txt)
        else
            read -r nt nc < <(calls target/strace-node.txt)
        fi
        read -r pt pc < <(calls target/strace-py.txt)
        # python's start-up (imports) is what its idle run costs; the other rows are net of it.
        if [[ \$w == idle ]]; then pt0=\$pt; pc0=\$pc; label="idle, 1.3 s (from 0.5 s after the attach)"; else label=\$w; fi
        awk -v r=\$runner -v w="\$label" -v f=\$frames -v nt=\$nt -v nc=\$nc -v pt=\$((pt-pt0)) -v pc=\$((pc-pc0)) -v tk=\$ticks -v hz=\$hz \
            'BEGIN{printf "| %s | %s | %.2f | %.2f | %.0f | %.2f | %.2f |\n", r, w, nt/f, (nt-nc)/f, tk*1e6/hz/f, pt/f, (pt-pc)/f}'
    done
    kill \$pid; wait \$pid 2>/dev/null || true
done
INNER
status=0
vcan_run vcan0 -- bash target/bench-in-vm.sh || status=$?
if [[ $status == 125 ]]; then echo "bench-vcan: no vcan0 and the with-vcan VM could not start (exit 125)" >&2; exit 1; fi
exit $status
