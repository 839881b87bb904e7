#!/bin/sh
# boards/linux/tdc-board-launch (A/B program slots with roll-back) driven by
# stand-in programs, seconds: the real program's side (DFU install, confirm)
# runs in make test-vm.  A stand-in writes STATE/log lines and acts on its
# STATE/plan-<name> file:
#   update K KIND  install stand-in KIND as slot K (prog-K + pending), exit 20
#   confirm        write STATE/confirmed, then run until SIGTERM
#   exit C         exit C at once (a program that does not start)
#   hang           never confirm
set -u
launch=${1:-boards/linux/tdc-board-launch}
t=$(mktemp -d)
trap 'rm -rf "$t"' EXIT
pass=0; fail=0
ok() { echo "ok   $1"; pass=$((pass + 1)); }
bad() { echo "FAIL $1: $2"; fail=$((fail + 1)); }
mkprog() { # name: a stand-in reading $state/plan-<name>, one step per start
    cat > "$t/$1" <<EOS
#!/bin/sh
state=\$2
n=\$(cat "\$state/runs-$1" 2>/dev/null || echo 0); echo \$((n + 1)) > "\$state/runs-$1"
set -- \$(sed -n "\$((n + 1))p" "\$state/plan-$1")
echo "$1 \$*" >> "\$state/log"
case \$1 in
  update) cp "$t/\$3" "\$state/prog-\$2"; echo \$2 > "\$state/pending"; exit 20 ;;
  confirm) echo \$\$ > "\$state/confirmed"; trap 'exit 0' TERM; while :; do sleep 0.05; done ;;
  exit) exit \$2 ;;
  hang) trap 'exit 0' TERM; while :; do sleep 0.05; done ;;
esac
EOS
    chmod +x "$t/$1"
}
for p in base good broken hung; do mkprog $p; done
s=$t/state; mkdir -p $s
# 1. base runs, installs "broken" into slot 1: it exits 1 before confirming,
#    base runs again (roll-back) and installs "good" into slot 0: it confirms
#    and stays (active = 0); SIGTERM ends it: the launcher exits 0.
printf 'update 1 broken\nupdate 0 good\n' > $s/plan-base
echo 'exit 1' > $s/plan-broken
echo 'confirm' > $s/plan-good
"$launch" --program "$t/base" --confirm-s 2 --state $s 2> $t/err &
l=$!
for i in $(seq 60); do [ "$(cat $s/active 2>/dev/null)" = 0 ] && break; sleep 0.1; done
kill -TERM $l; wait $l; rc=$?
[ "$(tr '\n' ' ' < $s/log)" = "base update 1 broken broken exit 1 base update 0 good good confirm " ] \
    && ok "broken update rolls back, good one sticks" || bad "sequence" "$(tr '\n' ' ' < $s/log)"
grep -q "rollback: slot 1 did not start (it exited with 1 before confirming): back to installed" $t/err \
    && ok "roll-back named" || bad "roll-back named" "$(cat $t/err)"
[ "$(cat $s/active)" = 0 ] && [ ! -f $s/trial ] && [ ! -f $s/pending ] && ok "active = the confirmed slot" \
    || bad "active" "active $(cat $s/active 2>/dev/null), trial/pending left"
[ $rc = 0 ] && ok "SIGTERM: exit 0" || bad "SIGTERM" "exit $rc"
# 2. the next start runs the confirmed slot 0 ("good"), which installs a
#    hanging program into slot 1: no confirmation in 1 s, killed, back to 0.
printf 'update 1 hung\nconfirm\n' > $s/plan-good; rm -f $s/runs-good
echo hang > $s/plan-hung
: > $s/log
"$launch" --program "$t/base" --confirm-s 1 --state $s 2> $t/err &
l=$!
for i in $(seq 60); do grep -q "good confirm" $s/log && break; sleep 0.1; done
kill -TERM $l; wait $l
[ "$(tr '\n' ' ' < $s/log)" = "good update 1 hung hung hang good confirm " ] && grep -q "no confirmation in 1 s" $t/err \
    && ok "a program that never confirms is stopped, the last good one restarts" || bad "hang" "$(tr '\n' ' ' < $s/log) / $(cat $t/err)"
[ "$(cat $s/active)" = 0 ] && ok "active stays 0" || bad "active after hang" "$(cat $s/active)"
# 3. a trial cut short (power lost: trial left behind) counts as failed
echo 1 > $s/trial; : > $s/log; echo confirm > $s/plan-good; rm -f $s/runs-good
"$launch" --program "$t/base" --confirm-s 1 --state $s 2> $t/err &
l=$!
for i in $(seq 60); do grep -q "good confirm" $s/log && break; sleep 0.1; done
kill -TERM $l; wait $l
grep -q "rollback: slot 1 was on trial when the board stopped: back to 0" $t/err && [ ! -f $s/trial ] \
    && ok "an interrupted trial rolls back" || bad "interrupted trial" "$(cat $t/err)"
echo "board-launch: $pass passed, $fail failed"
[ $fail = 0 ]
