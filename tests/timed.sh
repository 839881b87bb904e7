#!/bin/sh
# Runs one `make test` step and prints "[time] LABEL: W s wall, C s CPU":
# the CPU is what the step and everything it waited for used (cutime +
# cstime of this shell, /proc/PID/stat fields 16-17), so a step that keeps
# both cores busy shows C near 2 W, a serial one C near W.  CI's wall time
# is what counts (< 20 min); the CPU column says where it can still come
# from.  Usage: tests/timed.sh LABEL command...  (exit status: the command's)
label=$1; shift
t0=$(date +%s)
"$@"; rc=$?
t1=$(date +%s)
tck=$(getconf CLK_TCK)
cpu=$(awk -v t="$tck" '{ sub(/^.*\) /, ""); printf "%d", ($14 + $15) / t + 0.5 }' /proc/$$/stat)
echo "[time] $label: $((t1 - t0)) s wall, $cpu s CPU"
exit $rc
