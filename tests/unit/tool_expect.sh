# tool_expect.sh - sourced by the tools' end-to-end tests (test_tdc_run.sh,
# test_tool_errors.sh): a scratch folder $t, pass/fail counting and
# `expect CODE WHAT PATTERN -- command...`, which checks the exit code, a
# message matching PATTERN (on stderr or stdout; empty: any) and no
# sanitizer report.  LeakSanitizer is on, so in the ASan build an error path
# that leaks fails (docs/tools.md).
export ASAN_OPTIONS="detect_leaks=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
t=$(mktemp -d); trap 'rm -rf "$t"' EXIT
pass=0; fail=0
ok()  { pass=$((pass+1)); echo "ok   $1"; }
bad() { fail=$((fail+1)); echo "FAIL $1"; }
expect() {
    code=$1; what=$2; pat=$3; shift 4
    "$@" >"$t/out" 2>"$t/err"; got=$?
    if [ "$got" -eq "$code" ] && { [ -z "$pat" ] || grep -q -- "$pat" "$t/err" "$t/out"; } &&
       ! grep -q "Sanitizer" "$t/err"; then ok "$what"
    else bad "$what (exit $got, want $code; stderr: $(head -c 400 "$t/err"))"; fi
}
