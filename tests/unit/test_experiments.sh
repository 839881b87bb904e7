#!/bin/sh
# test_experiments.sh TDC_SIM - the experiment framework (issue 15,
# docs/experiments.md) on a temporary group folder:
#   1. (the statistics helper has its own test, test_tdc_stats.py);
#   2. a group of two 5-seed sweeps at 32x32 with per-scale lines: run on GNU
#      parallel, claims.csv with the claim columns, the report table and the
#      docs/results.md block between its markers (rewritten, not appended);
#   3. refusals (common/tdc_exit.h): an unknown group (1 ARGS), a
#      claims script that raises (18 JOBS, named), a bad scale (1 ARGS), a
#      malformed scale key (13 INPUT).
set -u
SIM=$(readlink -f "$1")
EXP="/usr/bin/python3 $(pwd)/sim/experiments/tdc_experiments.py"
T=$(mktemp -d /tmp/tdc_exp_test.XXXXXX)
trap '[ -n "${KEEP:-}" ] || rm -rf "$T"' EXIT
fail=0
ok() { echo "ok: $*"; }
bad() { echo "FAIL: $*"; fail=1; }

# 1. the statistics: tests/unit/test_tdc_stats.py (make test-tdc-stats)

# 2. a group
G=$T/groups
mkdir -p "$G/toy" "$G/broken"
cat > "$G/toy/moving.sweep" <<'SW'
name  = toy
base  = -s pan -g 48x48 -n 8
demo.base = -s pan -g 32x32 -n 6
modes = full,half,trm50
seed  = 1 2 3 4 5
SW
cat > "$G/toy/static.sweep" <<'SW'
name  = toy static
base  = -s static -g 32x32 -n 6
modes = full,trm50
seed  = 1 2 3 4 5
SW
cat > "$G/toy/claims.py" <<'PY'
def claims(exp):
    rows = exp.rows("moving")
    assert all(r["size"] if "size" in r else True for r in rows)
    full = exp.values(rows, "psnr_db", mode="full")
    half = exp.values(rows, "psnr_db", mode="half")
    c = exp.stats.compare(full, half)
    exp.claim("toy paper", "full beats half", "yes", "%.2f dB" % c["diff"],
              "agree" if c["verdict"] == "A beats B" else "disagree", c["verdict"],
              spread="%.3f" % c["spread"], n=c["n"])
    st = exp.rows("static")
    d = exp.stats.compare(exp.values(st, "psnr_db", mode="trm50"), exp.values(st, "psnr_db", mode="full"))
    exp.claim("toy paper", "static TRM = full", "identical", "%.3f dB" % d["diff"], "disagree", "a reason, with | pipe",
              cls="setting")
    exp.judge("toy paper", "§1: 'static content is identical'", "static full equals itself (judged)", "identical",
              exp.values(st, "psnr_db", mode="full"), exp.values(st, "psnr_db", mode="full"), "equal", "psnr_db",
              "full", "full")
    exp.write_extra("| a | b |\n| --- | --- |\n| 1 | 2 |\n")
PY
cp "$G/toy/moving.sweep" "$G/broken/x.sweep"
printf 'def claims(exp):\n    raise RuntimeError("deliberate")\n' > "$G/broken/claims.py"
export TDC_EXPERIMENTS_DIR=$G
O=$T/out
$EXP list --scale demo > "$T/list.txt" 2>&1
if grep -q "toy .*moving.sweep .* 5 jobs" "$T/list.txt"; then ok "list: $(grep toy "$T/list.txt" | head -1)"; else bad "list: $(cat "$T/list.txt")"; fi
$EXP run toy --scale demo --out "$O" -j 2 --sim "$SIM" > "$T/run.txt" 2>&1; rc=$?
if [ $rc -eq 0 ] && [ -f "$O/toy/claims.csv" ] && grep -q -- "-g 32x32" "$O/toy/moving.sweep"; then
    ok "run: 10 jobs at scale demo, $(grep -c . "$O/toy/moving/sweep.csv") rows in moving/sweep.csv"
else bad "run exit $rc: $(tail -3 "$T/run.txt")"; fi
if head -1 "$O/toy/claims.csv" | grep -qx "group,paper,quote,claim,paper_value,tdc_value,ci,margin,n,run,verdict,class,why" \
    && grep -q "^toy,toy paper,,full beats half,yes,.*,5,toy (scale demo),agree,," "$O/toy/claims.csv" \
    && grep -q "^toy,toy paper,§1: 'static content is identical',static full equals itself (judged),identical,.*,\"gain 0.0000 \[0.0000, 0.0000\]\",0.2500,5,toy (scale demo),equivalent,,\"interval inside" "$O/toy/claims.csv"; then
    ok "claims.csv: $(sed -n 2p "$O/toy/claims.csv")"
else bad "claims.csv: $(cat "$O/toy/claims.csv" 2>/dev/null)"; fi
printf '# results\n\ntext before\n\n<!-- experiments:begin (written by sim/experiments/tdc_experiments.py report) -->\nHEADSET KEPT\n<!-- experiments:end -->\n' > "$T/results.md"
$EXP report --out "$O" --report "$T/rep/experiments.md" --results "$T/results.md" > "$T/rep.txt" 2>&1
$EXP report --out "$O" --report "$T/rep/experiments.md" --results "$T/results.md" > "$T/sum.txt" 2>> "$T/rep.txt"; rc=$?
if [ $rc -eq 0 ] && grep -q "| toy paper |  | full beats half | yes |" "$T/rep/experiments.md" \
    && grep -q 'a reason, with \\| pipe' "$T/rep/experiments.md" && grep -q "| 1 | 2 |" "$T/rep/experiments.md" \
    && grep -q "^| toy | demo | 10 |" "$T/rep/experiments.md" \
    && [ "$(grep -c 'experiments-demo:begin' "$T/results.md")" = 1 ] && grep -q "text before" "$T/results.md" \
    && grep -q "HEADSET KEPT" "$T/results.md" \
    && grep -q "static TRM = full\*\* (disagree, setting)" "$T/results.md" \
    && grep -q "^3 claims: 1 agree, 1 equivalent, 1 disagree, 0 inconclusive; of the non-agreements 1 are setting" "$T/results.md" \
    && grep -q "^\*\*Demo scale\*\* (small frames.*Command: \`sim/experiments/tdc_experiments.py run toy --scale demo" "$T/results.md" \
    && grep -q "an explained setting difference: 3 of 3 (100 %)" "$T/rep/experiments.md"; then
    ok "report: the paper-vs-tdc table, the group's extra table, one results.md block with the disagreement"
    if grep -q "^Paper vs tdc at scale demo" "$T/sum.txt" && grep -q "^3 claims: 1 agree" "$T/sum.txt" \
        && grep -Eq "^toy +3 +1 +1 +1 +0 +0 " "$T/sum.txt"; then
        ok "summary (make demo): $(sed -n 3,4p "$T/sum.txt" | tr -s ' ')"
    else bad "summary: $(cat "$T/sum.txt")"; fi
else bad "report exit $rc: $(cat "$T/rep.txt"; cat "$T/results.md")"; fi
# the same results as a headset-scale run: they replace the headset block and leave the demo block
cp -r "$O" "$T/outh" && sed -i 's/"scale": "demo"/"scale": "headset"/' "$T/outh"/*/meta.json
$EXP report --out "$T/outh" --report "$T/reph/experiments.md" --results "$T/results.md" > /dev/null 2>&1; rc=$?
if [ $rc -eq 0 ] && ! grep -q "HEADSET KEPT" "$T/results.md" && grep -q "^Scale of these results: \*\*headset\*\*" "$T/results.md" \
    && [ "$(grep -c 'experiments:begin' "$T/results.md")" = 1 ] && [ "$(grep -c 'experiments-demo:begin' "$T/results.md")" = 1 ] \
    && grep -q "^\*\*Demo scale\*\*" "$T/results.md"; then
    ok "report: a headset run rewrites the headset block, the demo block stays"
else bad "headset report exit $rc: $(cat "$T/results.md")"; fi

# 2b. the result cache: the same run again restores every job (status.json "cached") with the same
# claims; the estimate counts them done; another binary (one byte appended) or another argument
# is a new run
cp "$O/toy/claims.csv" "$T/claims1.csv"
$EXP run toy --scale demo --out "$O" -j 2 --sim "$SIM" > "$T/run2.txt" 2>&1; rc=$?
nc=$(grep -l '"cached": true' "$O"/toy/*/jobs/*/status.json 2>/dev/null | wc -l)
if [ $rc -eq 0 ] && [ "$nc" = 10 ] && cmp -s "$O/toy/claims.csv" "$T/claims1.csv" \
    && grep -q "scale demo: 10 jobs, 0 done (cached), 10 to run" "$T/run.txt" \
    && grep -q "scale demo: 10 jobs, 10 done (cached), 0 to run: about 0 CPU s" "$T/run2.txt"; then
    ok "cache: the second run restored $nc of 10 jobs, same claims.csv"
else bad "cache: exit $rc, $nc cached: $(grep 'scale demo' "$T/run.txt" "$T/run2.txt")"; fi
cp "$SIM" "$T/sim2"; printf x >> "$T/sim2"
$EXP list toy --scale demo --out "$O" --sim "$T/sim2" > "$T/l2.txt" 2>&1
sed 's/-n 6/-n 7/' "$G/toy/static.sweep" > "$T/s.sweep" && mv "$T/s.sweep" "$G/toy/static.sweep"
$EXP list toy --scale demo --out "$O" --sim "$SIM" > "$T/l3.txt" 2>&1
if grep -q "10 jobs, 0 done (cached)" "$T/l2.txt" && grep -q "static.sweep .* 5 jobs    0 cached ~[0-9]* CPU s" "$T/l3.txt" \
    && grep -q "moving.sweep .* 5 jobs    5 cached" "$T/l3.txt"; then
    ok "cache key: another binary and another argument are new runs; $(tail -1 "$T/l3.txt")"
else bad "cache key: $(cat "$T/l2.txt" "$T/l3.txt")"; fi

# 3. refusals
$EXP run nosuch --out "$O" --sim "$SIM" > /dev/null 2> "$T/e1.txt"; rc=$?
[ $rc -eq 1 ] && grep -q "unknown group 'nosuch'" "$T/e1.txt" && ok "unknown group: exit 1, $(cat "$T/e1.txt")" || bad "unknown group exit $rc"
$EXP run broken --scale demo --out "$O" -j 2 --sim "$SIM" > /dev/null 2> "$T/e2.txt"; rc=$?
[ $rc -eq 18 ] && grep -q "broken/claims.py raised" "$T/e2.txt" && grep -q deliberate "$T/e2.txt" \
    && ok "raising claims script: exit 18 (JOBS), named" || bad "raising claims exit $rc: $(cat "$T/e2.txt")"
$EXP run toy --scale huge --out "$O" > /dev/null 2> "$T/e3.txt"; rc=$?
[ $rc -eq 1 ] && ok "bad scale: exit 1 (ARGS)" || bad "bad scale exit $rc"
printf 'name = x\nbase = -n 2\nhuge.base = -n 3\nmodes = full\n' > "$G/broken/x.sweep"
$EXP list broken > /dev/null 2> "$T/e4.txt"; rc=$?
[ $rc -eq 13 ] && grep -q "line 3: scale 'huge'" "$T/e4.txt" && ok "malformed scale key: exit 13 (INPUT), $(cat "$T/e4.txt")" \
    || bad "malformed scale key exit $rc: $(cat "$T/e4.txt")"
# judge_seen: JOD decides only when every row pooled frames after the judge's warm-up (jod_frames > 0);
# otherwise the first secondary metric decides and the row says so
out=$(/usr/bin/python3 - "$(dirname "$0")/../../sim/experiments" <<'PY'
import sys
sys.path.insert(0, sys.argv[1])
import tdc_experiments as te
def rows(frames):
    return [{"mode": m, "seed": str(s), "job": str(s), "jod": "%.3f" % (9.0 + (0.5 if m == "a" else 0.0) + 0.01 * s),
             "jod_frames": frames, "flip": "%.4f" % (0.10 - (0.0 if m == "a" else -0.02) + 0.001 * s),
             "psnr_db": "30"} for s in range(1, 6) for m in ("a", "b")]
for frames in ("13", "0"):
    e = te.Experiment("toy", "/nonexistent", "demo")
    e.judge_seen("p", "q", "c", "v", rows(frames), {"mode": "a"}, {"mode": "b"}, "better", "a", "b")
    c = e.claims[0]
    print(frames, c["tdc_value"].split(" ")[0], c["verdict"], "warm-up" in c["why"])
PY
)
if [ "$(echo "$out" | sed -n 1p)" = "13 jod agree False" ] && [ "$(echo "$out" | sed -n 2p)" = "0 flip agree True" ]; then
    ok "judge_seen: JOD decides with pooled frames, FLIP (named) without"
else bad "judge_seen: $out"; fi
# the set-up check of pursuit runs (Experiment.saccades / saccade_note: the gaze rule of docs/eye.md),
# the content-spread class of the ordering rows (tdrt-fig10 spread_class) and the Fig. 6 computation
# (trm-fig6/fig6.py), on data with known answers
out=$(/usr/bin/python3 - "$(dirname "$0")/../../sim/experiments" "$T" <<'PY'
import importlib.util, os, sys
sys.path.insert(0, sys.argv[1])
import tdc_experiments as te
S = te.Experiment.saccades
print("sac", S(96, 96, 382.5, 0, 0.4), S(640, 64, 382.5, 0, 0.4), S(96, 96, 382.5, 0, 0.4, 0.9), S(96, 96, 450, 90, 0.4))
out = sys.argv[2]
os.makedirs(os.path.join(out, "g"), exist_ok=True)
for name, base in (("wide", "--mono -s pan -g 640x64 --speed 382.5 -r 90 -n 36"),
                   ("narrow", "--mono -s pan -g 96x96 --speed 382.5 -r 90 -n 36"),
                   ("fixate", "--mono -s pan -g 96x96 --speed 382.5 -r 90 -n 36 --pursuit fixate"),
                   ("default", "--mono -s pan -g 96x96 -r 90 -n 36")):
    with open(os.path.join(out, "g", name + ".sweep"), "w") as f:
        f.write("name = x\nbase = %s\nmodes = full\n" % base)
e = te.Experiment("g", out, "demo")
notes = [e.saccade_note(n) for n in ("wide", "narrow", "fixate", "default")]
print("note", notes[0] == "", "6 catch-up saccades" in notes[1], notes[2] == "", "7 catch-up saccades at 450" in
      notes[3].replace(" in each run (back to the centre on leaving the central half of the 96x96 view", ""))
spec = importlib.util.spec_from_file_location("f10", os.path.join(sys.argv[1], "tdrt-fig10", "claims.py"))
f10 = importlib.util.module_from_spec(spec)
spec.loader.exec_module(f10)
def rows(gains):  # A ahead by gains[i] in JOD on content i, and in FLIP on every content
    return [{"mode": m, "seed": "1", "job": str(i), "image": "/x/img%d.jpg" % i,
             "jod": "%.3f" % (9.0 + (g if m == "a" else 0.0)), "flip": "%.4f" % (0.10 - (0.01 if m == "a" else 0.0))}
            for i, g in enumerate(gains) for m in ("a", "b")]
for gains in ([0.70, 0.40, 0.01, 0.02, -0.01, 0.03, 0.02, 0.01, 0.02, 0.01],   # carried by 2 contents: classed
              [0.90, 0.50, -0.05, -0.02, -0.05, 0.30, -0.03, -0.01, -0.04, -0.02]):  # behind on most: unclassed
    e = te.Experiment("g", out, "demo")
    r = rows(gains)
    j = e.judge("p", "q", "c", "v", e.values(r, "jod", mode="a"), e.values(r, "jod", mode="b"), "better", "jod")
    f10.spread_class(e, j, r, {"mode": "a"}, {"mode": "b"})
    print("spread", j["verdict"], e.claims[0]["class"] or "-", "img0, img1 (+0.70, +0.40" in e.claims[0]["why"])
# the user study on photographs: a row that does not agree is classed by the study's premise (full - full60)
spec = importlib.util.spec_from_file_location("taa", os.path.join(sys.argv[1], "tdrt-taa", "claims.py"))
taa = importlib.util.module_from_spec(spec)
spec.loader.exec_module(taa)
import csv
# gains of the assembly over full60: premise: -0.3, 0, -0.2 where full60 = full, then 5 of 7 ahead where
# full60 is 1 JOD worse (interval [-0.1, 0.48]: inconclusive): classed; no premise (full60 = full everywhere)
# and premise everywhere (nothing flat to explain the interval): unclassed
g_p = [-0.3, 0.0, -0.2, 0.9, -0.1, 0.8, 0.05, 0.6, -0.2, 0.3]
g_n = [0.5, -0.3, 0.6, -0.2, 0.4, -0.1, 0.3, -0.4, 0.5, 0.2]
f60_p = [9.95] * 3 + [9.0] * 7
for case, (f60, asm) in {"premise": (f60_p, [a + g for a, g in zip(f60_p, g_p)]),
                         "no premise": ([9.9] * 10, [9.9 + g for g in g_n]),
                         "premise everywhere": ([9.0] * 10, [9.0 + g for g in g_n])}.items():
    d = os.path.join(out, "us", "userstudy")
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, "sweep.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, ["job", "seed", "speed", "image", "mode", "jod", "jod_frames", "flip", "psnr_db"])
        w.writeheader()
        for i in range(10):
            for m, jv in (("full", 9.95 if case == "premise" else 9.9), ("full60", f60[i]), ("asm-adaptive", asm[i])):
                w.writerow({"job": i, "seed": 1, "speed": 360, "image": "/x/p%d.jpg" % i, "mode": m, "jod": jv,
                            "jod_frames": 10, "flip": 0.1, "psnr_db": 30})
    e = te.Experiment("us", out, "demo")
    taa.user_study_photos(e)
    c = e.claims[0]
    print("us", case, c["verdict"], c["class"] or "-", "(p0, p1, p2:" in c["why"])
spec = importlib.util.spec_from_file_location("fig6", os.path.join(sys.argv[1], "trm-fig6", "fig6.py"))
f6 = importlib.util.module_from_spec(spec)
spec.loader.exec_module(f6)
o, u = f6.artefacts(0.25, 0.0, 1.0, "linear", "luminance")
og, ug = f6.artefacts(0.25, 0.0, 1.0, "gamma", "brightness")
ol, ul = f6.artefacts(0.25, 0.0, 1.0, "linear", "brightness")
lin, p = f6.perceived(f6.square(0.0, 0.3, 0.3), "gamma")  # a flat field: TRM changes nothing
print("fig6", abs(o - u) < 1e-9 and o > 0.1, ol > ul, abs(og - ug) < abs(ol - ul), max(abs(a - b) for a, b in zip(lin, p)) < 1e-12)
# thesis eq. 5.1 and the rank correlation of its row: known answers (scipy.stats.spearmanr gives 0.9486833 for
# the tied case; with r <= 1 px the disk is empty and f is the log-polar buffer alone, delta^2)
spec = importlib.util.spec_from_file_location("tfov", os.path.join(sys.argv[1], "thesis-fov", "claims.py"))
tf = importlib.util.module_from_spec(spec)
spec.loader.exec_module(tf)
print("eq51", tf.spearman([1, 2, 3], [10, 20, 30]) == 1.0, tf.spearman([1, 2, 3], [3, 2, 1]) == -1.0,
      abs(tf.spearman([1, 2, 2, 3], [1, 2, 3, 4]) - 0.9486833) < 1e-7, abs(tf.eq51(1e-4, 1920, 1080) - 0.555 ** 2) < 1e-6,
      tf.eq51_argmin(1920, 1080), tf.eq51(0.066, 1920, 1080) < min(tf.eq51(0.03, 1920, 1080), tf.eq51(0.12443, 1920, 1080)))
# exp.render_stages: each stage's least over the cached runs, skipped stages None, the scene's lights and
# the G-buffer lookups from tdc-render's text (three runs written as if cached: no tdc-render run)
e = te.Experiment("rs", out, "demo")
os.makedirs(os.path.join(out, "rs"), exist_ok=True)
for rep, (prim, shade, look) in enumerate(((9.5, 4.0, 4), (3.25, 7.0, 4), (131.0, 5.5, 3))):
    with open(os.path.join(out, "rs", "render-x-%d.txt" % rep), "w") as f:
        f.write("tdc-render ...\nscene x: 8x8, 1 objects, features: motion=1 (camera 1, objects 0) lights=2 "
                "area-lights=0\n  primary %9.3f ms  \n  shade %9.3f ms  \n  reflect 0.000 ms  skipped\n"
                "dual MVs: the previous frame's G-buffer read in %d of 4 frames\n" % (prim, shade, look))
ms = e.render_stages("x", ["--builtin", "x"], 3)
print("rstages", ms["primary"], ms["shade"], ms["reflect"], ms["lights"], ms["camera_moves"], ms["gbuf_lookup"])
PY
)
want="sac 6 0 5 7
note True True True True
spread inconclusive setting True
spread inconclusive - False
us premise inconclusive setting True
us no premise inconclusive - False
us premise everywhere inconclusive - False
fig6 True True True True
eq51 True True True True 0.066 True
rstages 3.25 4.0 None 2 1 False"
if [ "$out" = "$want" ]; then ok "saccade check, content-spread class, Fig. 6 computation, eq. 5.1, render_stages: known answers"
else bad "saccade/spread/fig6: got '$out'"; fi
exit $fail
