#!/bin/sh
# test_sweep.sh TDC_SIM - sweeps on real engines (issue 13 item 6):
#   1. a malformed sweep file: one line, exit 13 (INPUT), nothing run;
#   2. the small sweep (16 jobs) under GNU parallel -j 2;
#   3. the same sweep as a Slurm job array on a one-node cluster this test
#      starts itself (munged + slurmctld + slurmd on 127.0.0.1, generated
#      key and slurm.conf in a temp dir, free ports), merged CSV byte-equal
#      to the parallel run's;
#   4. a sweep with a failing job: merge names it and exits 18 (JOBS),
#      the other jobs are merged.
# Every daemon is stopped at the end, also on failure (trap), with timeouts;
# if the cluster cannot start here the test FAILS and prints what failed.
set -u
SIM=$(readlink -f "$1")
SWEEP="/usr/bin/python3 $(pwd)/sim/sweep/tdc_sweep.py"
EX=$(pwd)/sim/sweep/examples/small.sweep
T=$(mktemp -d /tmp/tdc_sweep_test.XXXXXX)
fail=0
ok() { echo "ok: $*"; }
bad() { echo "FAIL: $*"; fail=1; }

stop_cluster() {
    if [ -n "${SLURM_CONF:-}" ] && [ -f "$SLURM_CONF" ]; then
        timeout 10 scancel --quiet --full "${jobid:-0}" 2>/dev/null
    fi
    for p in "$T/slurm/slurmd.pid" "$T/slurm/slurmctld.pid" "$T/munge/munged.pid"; do
        [ -s "$p" ] || continue
        pid=$(cat "$p")
        kill "$pid" 2>/dev/null || continue
        i=0; while kill -0 "$pid" 2>/dev/null && [ $i -lt 50 ]; do sleep 0.2; i=$((i + 1)); done
        kill -9 "$pid" 2>/dev/null && echo "note: daemon $pid ($p) needed SIGKILL"
    done
}
cleanup() { stop_cluster; rm -rf "$T"; }
trap cleanup EXIT
trap 'exit 1' INT TERM HUP

# 1. malformed sweep file
printf 'name = broken\nmodes full trm50\n' > "$T/broken.sweep"
$SWEEP local "$T/broken.sweep" "$T/broken" --sim "$SIM" > "$T/o.txt" 2> "$T/e.txt"; rc=$?
if [ $rc -eq 13 ] && [ "$(wc -l < "$T/e.txt")" -eq 1 ] && grep -q "broken.sweep line 2" "$T/e.txt" && \
   [ ! -d "$T/broken/jobs/0000" ]; then ok "malformed: $(cat "$T/e.txt")"
else bad "malformed sweep: exit $rc, $(cat "$T/e.txt")"; fi
printf 'modes = full,trm{q}\n' > "$T/ph.sweep"
$SWEEP expand "$T/ph.sweep" "$T/ph" --sim "$SIM" > /dev/null 2> "$T/e.txt"; rc=$?
[ $rc -eq 13 ] && grep -q "placeholder" "$T/e.txt" && ok "unknown placeholder: $(cat "$T/e.txt")" || bad "placeholder: exit $rc"

# 2. GNU parallel
t0=$(date +%s)
if $SWEEP local "$EX" "$T/par" -j 2 --sim "$SIM" 2> "$T/par.err"; then
    rows=$(($(wc -l < "$T/par/sweep.csv") - 1))
    [ "$rows" -eq 32 ] && ok "GNU parallel: 16 jobs, $rows rows in $(( $(date +%s) - t0 )) s" || bad "parallel: $rows rows (want 32)"
    grep -q '^tdc-sweep: merged 16 of 16 jobs' "$T/par.err" || bad "parallel merge line: $(tail -1 "$T/par.err")"
    # the expansion: job 5 = modes full,trm50, refresh 120, speed 150, seed 2
    grep -q '^5,"full,trm50",50,120,150,2,job-0005,' "$T/par/sweep.csv" && ok "job 5 is the 6th configuration" \
        || bad "job 5 row: $(grep '^5,' "$T/par/sweep.csv" | head -1)"
    if grep -q 'us_per_frame' "$T/par/sweep.csv"; then bad "time columns in sweep.csv"; fi
else bad "GNU parallel sweep failed: $(tail -3 "$T/par.err")"; fi

# 3. one-node Slurm cluster
start_cluster() {
    for b in munged slurmctld slurmd sbatch squeue; do
        command -v $b > /dev/null || { echo "cannot start Slurm: $b not installed (make deps)"; return 1; }
    done
    [ "$(id -u)" -eq 0 ] || { echo "cannot start Slurm: slurmd must run as root to launch jobs (uid $(id -u))"; return 1; }
    mkdir -p "$T/munge" "$T/slurm/state" "$T/slurm/spool" "$T/slurm/log" && chmod 700 "$T/munge"
    dd if=/dev/urandom of="$T/munge/munge.key" bs=1024 count=1 2>/dev/null && chmod 400 "$T/munge/munge.key"
    timeout 10 munged --key-file="$T/munge/munge.key" --socket="$T/munge/sock" --pid-file="$T/munge/munged.pid" \
        --log-file="$T/munge/munged.log" --seed-file="$T/munge/seed" --force \
        || { echo "cannot start Slurm: munged failed: $(tail -1 "$T/munge/munged.log")"; return 1; }
    # two free TCP ports for slurmctld and slurmd
    set -- $(/usr/bin/python3 -c 'import socket
s=[socket.socket() for _ in range(2)]
[x.bind(("127.0.0.1",0)) for x in s]
print(*[x.getsockname()[1] for x in s])')
    host=$(hostname -s)
    cat > "$T/slurm/slurm.conf" <<EOC
ClusterName=tdctest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$1
SlurmdPort=$2
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$T/munge/sock
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$T/slurm/state
SlurmdSpoolDir=$T/slurm/spool
SlurmctldPidFile=$T/slurm/slurmctld.pid
SlurmdPidFile=$T/slurm/slurmd.pid
SlurmctldLogFile=$T/slurm/log/slurmctld.log
SlurmdLogFile=$T/slurm/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1,bf_interval=1,sched_min_interval=100000
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SlurmctldTimeout=30
SlurmdTimeout=30
KillWait=5
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=tdc Nodes=$host Default=YES MaxTime=10 State=UP
EOC
    export SLURM_CONF="$T/slurm/slurm.conf"
    timeout 20 slurmctld -c -f "$SLURM_CONF" || { echo "cannot start Slurm: slurmctld: $(tail -2 "$T/slurm/log/slurmctld.log")"; return 1; }
    timeout 20 slurmd -f "$SLURM_CONF" || { echo "cannot start Slurm: slurmd: $(tail -2 "$T/slurm/log/slurmd.log")"; return 1; }
    i=0
    until timeout 5 sinfo -h -o '%t' 2>/dev/null | grep -q idle; do
        i=$((i + 1))
        [ $i -lt 40 ] || { echo "cannot start Slurm: node not idle after 20 s: $(timeout 5 sinfo -h 2>&1 | head -1); $(tail -1 "$T/slurm/log/slurmd.log")"; return 1; }
        sleep 0.5
    done
    return 0
}
if msg=$(start_cluster); then
    export SLURM_CONF="$T/slurm/slurm.conf"
    ok "one-node Slurm cluster up ($(sinfo -h -o '%P %D %c %t' | head -1))"
    t0=$(date +%s)
    timeout 120 $SWEEP slurm "$EX" "$T/slurm-run" --wait --sim "$SIM" 2> "$T/slurm.err"; rc=$?
    jobid=$(cat "$T/slurm-run/slurm/jobid" 2>/dev/null)
    if [ $rc -eq 0 ]; then
        n=$(ls "$T/slurm-run/slurm/" | grep -c "^${jobid}_")
        eng=$(grep -l '"engine": "slurm"' "$T"/slurm-run/jobs/*/status.json | wc -l)
        [ "$n" -eq 16 ] && [ "$eng" -eq 16 ] && ok "Slurm array $jobid: 16 tasks ran under Slurm in $(( $(date +%s) - t0 )) s" \
            || bad "Slurm: $n task logs, $eng jobs with engine slurm (want 16)"
        if cmp -s "$T/par/sweep.csv" "$T/slurm-run/sweep.csv"; then ok "Slurm sweep.csv == GNU parallel sweep.csv (same bytes)"
        else bad "Slurm and parallel sweep.csv differ: $(diff "$T/par/sweep.csv" "$T/slurm-run/sweep.csv" | head -3)"; fi
    else bad "Slurm sweep failed (exit $rc): $(tail -2 "$T/slurm.err"); slurmctld: $(tail -1 "$T/slurm/log/slurmctld.log")"; fi
else
    bad "$msg"
fi
stop_cluster
SLURM_CONF=

# 4. a failing job is reported, the others merged
cat > "$T/onebad.sweep" <<EOF2
name = onebad
base = -s pan -g 32x24 -n 6 -m full
refresh = 90 2000
EOF2
$SWEEP local "$T/onebad.sweep" "$T/onebad" -j 2 --sim "$SIM" 2> "$T/bad.err"; rc=$?
if [ $rc -eq 18 ] && grep -q 'job 0001 failed: exit 1: tdc-sim: bad refresh' "$T/bad.err" && \
   [ "$(($(wc -l < "$T/onebad/sweep.csv") - 1))" -eq 1 ] && grep -q '| 0001 | refresh=2000 |' "$T/onebad/report.md"; then
    ok "failed job named by merge (exit 18 JOBS): $(grep 'job 0001' "$T/bad.err")"
else bad "failing job: exit $rc, $(cat "$T/bad.err")"; fi
rm -rf "$T/onebad/jobs/0000/status.json"
$SWEEP merge "$T/onebad" 2> "$T/bad2.err"; rc=$?
[ $rc -eq 18 ] && grep -q 'job 0000 failed: missing' "$T/bad2.err" && ok "missing job named: $(grep 'job 0000' "$T/bad2.err")" \
    || bad "missing job: exit $rc $(cat "$T/bad2.err")"
exit $fail
