#!/usr/bin/python3
"""tdc-experiments - the papers' own experiments as named tdc-sim sweeps.

Every experiment group is one folder sim/experiments/<group>/ holding
    *.sweep     tdc-sim sweeps in the sweep format (docs/sweeps.md), with
                optional per-scale lines:  SCALE.key = value  replaces
                key = value at that scale (scales: demo, dev, headset);
    claims.py   def claims(exp): reads the merged results, calls exp.claim()
                for every paper claim it addresses (paper vs tdc);
    README.md   (optional) what the group reproduces, quoted in the report.
Adding a group is adding a folder (docs/experiments.md).

Commands:
    tdc-experiments list [GROUP...] [--scale S] [--out DIR] [--sim PATH]
        groups, sweeps, jobs; with the jobs already in DIR's cache and an
        estimate of the CPU seconds the others take
    tdc-experiments run [GROUP...] [--scale S] [--out DIR] [-j N] [--sim PATH]
        each sweep on GNU parallel (sim/sweep/tdc_sweep.py local) into
        DIR/<group>/<sweep>/, then the group's claims -> DIR/<group>/claims.csv;
        every finished job is kept in DIR/.cache (key: the job's full tdc-sim
        arguments, the binary's SHA-256, the files the arguments name), so a
        run stopped part-way resumes where it stopped when started again
        with the same command; the remaining CPU time is estimated before
        every group
    tdc-experiments claims [GROUP...] [--out DIR]          claims again from cached results
    tdc-experiments report [--out DIR] [--report FILE] [--results FILE]
        every group's claims.csv -> the paper-vs-tdc table in FILE
        (default report/experiments.md) and between the markers of
        docs/results.md

Defaults: --scale headset, --out build/experiments, -j = cores.
Exit codes (the one table, common/tdc_exit.h; docs/tools.md):
0 OK, 1 ARGS (bad command line, unknown group or scale), 13 INPUT (malformed
sweep or claims script), 18 JOBS (a sweep job failed, a claims script
raised, or a cached result is missing).
"""
import csv
import glob
import importlib.util
import json
import math
import os
import re
import shlex
import shutil
import subprocess
import sys
import time
import traceback

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
# the folder of the groups (tests point it at a temporary one)
GROUPS_DIR = os.path.abspath(os.environ.get("TDC_EXPERIMENTS_DIR", HERE))
import tdc_stats  # noqa: E402
sys.path.insert(0, os.path.join(REPO, "sim", "sweep"))
import tdc_sweep  # noqa: E402  (the job expansion and the result cache)
sys.path.insert(0, os.path.join(REPO, "common"))
from tdc_exit import EXIT  # noqa: E402  (the one exit-code table)
import tdc_argv  # noqa: E402  (the one command-line reader)

SCALES = ("demo", "dev", "headset")
EXIT_OK, EXIT_BAD_GROUP, EXIT_USAGE, EXIT_RUN_FAILED = EXIT.OK, EXIT.INPUT, EXIT.ARGS, EXIT.JOBS
CLAIM_COLUMNS = ["group", "paper", "quote", "claim", "paper_value", "tdc_value", "ci", "margin", "n", "run", "verdict",
                 "class", "why"]
VERDICTS = ("agree", "equivalent", "disagree", "inconclusive")
# what a non-agreement rests on (docs/experiments.md); a defect is fixed, not classed
CLASSES = ("", "setting", "model limit", "not reproducible")
MARK_BEGIN = "<!-- experiments:begin (written by sim/experiments/tdc_experiments.py report) -->"
MARK_END = "<!-- experiments:end -->"
# docs/results.md keeps two blocks: the headset-scale run (`make experiments`, hours) and the demo-scale
# results (`make demo` reproduces them in minutes); a report rewrites the block of its results' scale only,
# so saving a demo run never erases the headset numbers nor the reverse
MARK_DEMO_BEGIN = "<!-- experiments-demo:begin (written by sim/experiments/tdc_experiments.py report) -->"
MARK_DEMO_END = "<!-- experiments-demo:end -->"


class ExpError(Exception):
    def __init__(self, code, msg):
        Exception.__init__(self, msg)
        self.code = code


def groups():
    return sorted(d for d in os.listdir(GROUPS_DIR)
                  if os.path.isdir(os.path.join(GROUPS_DIR, d)) and os.path.isfile(os.path.join(GROUPS_DIR, d, "claims.py")))


def sweeps_of(group):
    return sorted(glob.glob(os.path.join(GROUPS_DIR, group, "*.sweep")))


def scale_sweep(path, scale):
    """The sweep file's text at a scale: 'SCALE.key = v' lines replace 'key = v'."""
    plain, over, order = {}, {}, []
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    for n, raw in enumerate(lines, 1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        if "=" not in line:
            raise ExpError(EXIT_BAD_GROUP, "%s line %d: expected 'key = value'" % (path, n))
        key, val = (s.strip() for s in line.split("=", 1))
        if "." in key:
            sc, _, k = key.partition(".")
            if sc not in SCALES:
                raise ExpError(EXIT_BAD_GROUP, "%s line %d: scale '%s' (one of %s)" % (path, n, sc, ", ".join(SCALES)))
            if sc == scale:
                if k in over:
                    raise ExpError(EXIT_BAD_GROUP, "%s line %d: '%s' given twice" % (path, n, key))
                over[k] = val
            continue
        if key in plain:
            raise ExpError(EXIT_BAD_GROUP, "%s line %d: '%s' given twice" % (path, n, key))
        plain[key] = val
        order.append(key)
    order += [k for k in over if k not in plain]  # keys only a scale sets: after the others
    out = ["# %s at scale %s (generated by tdc_experiments.py)" % (os.path.relpath(path, REPO), scale)]
    for k in order:
        out.append("%s = %s" % (k, over.get(k, plain.get(k))))
    return "\n".join(out) + "\n"


def count_jobs(text):
    n = 1
    for line in text.splitlines():
        line = line.split("#", 1)[0].strip()
        if "=" in line:
            k, v = (s.strip() for s in line.split("=", 1))
            if k not in ("name", "base"):
                n *= len(v.split())
    return n


class Experiment:
    """What a group's claims(exp) sees."""

    stats = tdc_stats

    def __init__(self, group, out, scale):
        self.group, self.out, self.scale = group, out, scale
        self.claims = []

    def _csv(self, sweep, name):
        p = os.path.join(self.out, self.group, sweep, name)
        if not os.path.isfile(p):
            raise ExpError(EXIT_RUN_FAILED, "%s: no results (run the group first)" % os.path.relpath(p, REPO))
        with open(p, newline="", encoding="utf-8") as f:
            return list(csv.DictReader(f))

    def rows(self, sweep):
        """Rows of the sweep's merged sweep.csv (one per mode per job)."""
        return self._csv(sweep, "sweep.csv")

    def timings(self, sweep):
        """Rows of its timings.csv (time columns, same job/axis keys)."""
        return self._csv(sweep, "timings.csv")

    def job_rows(self, sweep, name):
        """Rows of a per-job CSV tdc-sim writes beside summary.csv (e.g. foveation.csv), one
        list over the jobs, each row with its job's axis values from sweep.csv added."""
        axes = {}
        for r in self.rows(sweep):
            axes.setdefault(r["job"], r)
        out = []
        for job, ax in sorted(axes.items(), key=lambda kv: int(kv[0])):
            p = os.path.join(self.out, self.group, sweep, "jobs", "%04d" % int(job), name)
            if not os.path.isfile(p):
                raise ExpError(EXIT_RUN_FAILED, "%s: missing (run the group again)" % os.path.relpath(p, REPO))
            with open(p, newline="", encoding="utf-8") as f:
                for r in csv.DictReader(f):
                    for k, v in ax.items():
                        r.setdefault(k, v)
                    r["job"] = job
                    out.append(r)
        return out

    def _render_path(self, name, rep):
        return os.path.join(self.out, self.group, "render-%s-%d.txt" % (name, rep))

    def prefetch_render(self, specs, reps=3, jobs=None, quiet=True):
        """Runs the tdc-render runs of render_stages (quiet) or render_frames (not quiet: the per-frame
        lines) that are not cached yet, jobs at a time (default: the cores; each run is one thread and
        its stage timers are per-thread CPU clocks), repetition by repetition over the specs so that
        a spell of load on the host falls on every spec alike.  specs: (name, args) pairs."""
        import concurrent.futures
        os.makedirs(os.path.join(self.out, self.group), exist_ok=True)
        exe = os.environ.get("TDC_RENDER") or os.path.join(REPO, "build", "gcc-O2", "tdc-render")
        todo = [(self._render_path(n, rep), [exe] + list(a) + (["--quiet"] if quiet else []))
                for rep in range(reps) for n, a in specs if not os.path.isfile(self._render_path(n, rep))]

        def one(job):
            path, cmd = job
            res = subprocess.run(cmd, capture_output=True, text=True)
            if res.returncode != 0:
                return "%s: %s" % (" ".join(cmd), res.stderr.strip())
            with open(path + ".tmp", "w", encoding="utf-8") as fh:
                fh.write(" ".join(cmd) + "\n" + res.stdout)
            os.replace(path + ".tmp", path)
            return None
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs or os.cpu_count() or 1) as pool:
            errors = [e for e in pool.map(one, todo) if e]
        if errors:
            raise ExpError(EXIT_RUN_FAILED, "%s: %s" % (self.group, errors[0]))

    def render_frames(self, name, args, reps=3):
        """tdc-render's frames of one run of args: per frame (in order) its kind (full, reduced, ...)
        and the CPU ms of each stage that ran, the least of reps runs (a frame's least: a spell of load
        inflates a few frames of one run, not the same frames of every run).  Cached as render_stages."""
        self.prefetch_render([(name, args)], reps, 1, quiet=False)
        frames = {}
        for rep in range(reps):
            with open(self._render_path(name, rep), encoding="utf-8") as fh:
                for line in fh:
                    m = re.match(r"frame\s+(\d+)\s+(\S+)\s.* cpu((?: [a-z-]+=[0-9.]+)*)\s*$", line)
                    if not m:
                        continue
                    st = {k: float(v) for k, v in re.findall(r"([a-z-]+)=([0-9.]+)", m.group(3))}
                    f = frames.setdefault(int(m.group(1)), {"kind": m.group(2), "ms": st})
                    f["ms"] = {k: min(v, f["ms"].get(k, v)) for k, v in st.items()}
        return [frames[k] for k in sorted(frames)]

    def render_stages(self, name, args, reps=3):
        """tdc-render's per-stage CPU ms for one run of args (--quiet added): the least of reps runs per
        stage (None: skipped), plus camera_moves, lights and gbuf_lookup (the previous frame's G-buffer
        read in every frame).  One run's stage timers on a shared machine jump by up to 400x when a
        thread is descheduled inside a short stage (the mv pass: 0.3 ms for 4 frames at 160x90 in one
        run, 131 ms at 320x180 in another); the least of a few runs is the cost of the work itself, as
        benchmarks time it.  Outputs are cached in the group's folder as render-NAME-REP.txt (the
        folder starts empty each run, so never across builds); prefetch_render runs many at once."""
        self.prefetch_render([(name, args)], reps, 1)
        ms = {}
        for rep in range(reps):
            with open(self._render_path(name, rep), encoding="utf-8") as fh:
                text = fh.read()
            cam = re.search(r"\(camera (\d)", text)
            ms["camera_moves"] = int(cam.group(1)) if cam else 0
            lights = re.search(r" lights=(\d+)", text)
            ms["lights"] = int(lights.group(1)) if lights else 0
            look = re.search(r"G-buffer read in (\d+) of (\d+) frames", text)
            ms["gbuf_lookup"] = bool(look) and look.group(1) == look.group(2)
            for stage, val, rest in re.findall(r"^[ \t]*([a-z-]+)[ \t]+([0-9.]+) ms[ \t]*(skipped)?", text, re.M):
                v = None if rest else float(val)
                ms[stage] = v if rep == 0 or v is None or ms.get(stage) is None else min(ms[stage], v)
        return ms

    def write_extra(self, text):
        """Markdown the report prints under the group's README (tables beside the claims)."""
        with open(os.path.join(self.out, self.group, "extra.md"), "w", encoding="utf-8") as f:
            f.write(text)

    @staticmethod
    def has_jod(rows, col="jod"):
        """True when every row carries a JOD that pooled frames after the judge's 0.25 s warm-up
        (docs/visual-model.md): a run no longer than the warm-up reports the start-up transient
        (jod_frames 0), which no verdict may rest on."""
        return bool(rows) and all(r.get(col, "") not in ("", "nan") and
                                  float(r.get("jod_frames", "") or 0) > 0 for r in rows)

    @staticmethod
    def saccades(width, height, speed, angle_deg, seconds, gain=1.0):
        """Catch-up saccades the simulated eye makes in a pursuit run (docs/eye.md, sim/simulator/tdc_sim_gaze.h):
        it starts at the centre, moves at gain x the pursued velocity and jumps back to the centre when it
        leaves the central half of the W x H view, i.e. every W/4 (H/4) pixels of travel."""
        a = math.radians(angle_deg)
        n = 0
        for size, v in ((width, speed * math.cos(a)), (height, speed * math.sin(a))):
            travel = abs(gain * v * seconds)
            n += int(math.floor(travel / (size / 4.0) + 1e-9)) if size >= 4 else 0
        return n

    def base_args(self, sweep):
        """The run's tdc-sim options of a sweep's base line at the scale it ran (DIR/<group>/<sweep>.sweep)."""
        p = os.path.join(self.out, self.group, sweep + ".sweep")
        try:
            with open(p, encoding="utf-8") as f:
                for line in f:
                    k, _, v = line.split("#", 1)[0].partition("=")
                    if k.strip() == "base":
                        return shlex.split(v)
        except OSError:
            pass
        return []

    def saccade_note(self, sweep, gain=1.0, speed=None):
        """A row's note when its pursuit runs hold catch-up saccades ("" when none): a TRM pair straddling one
        falls apart on the retina, and the visual model (no saccadic suppression) judges the jump."""
        args = self.base_args(sweep)
        opt = lambda names, d: next((args[i + 1] for i, a in enumerate(args[:-1]) if a in names), d)  # noqa: E731
        if opt(("--gaze",), "pursuit") != "pursuit" or opt(("--pursuit",), "track") != "track":
            return ""
        w, _, h = opt(("-g", "--size"), "0x0").partition("x")
        hz = float(opt(("-r", "--refresh"), "90"))
        secs = float(opt(("-n", "--frames"), "0")) / hz or float(opt(("-d", "--duration"), "0.5"))
        scene = opt(("-s", "--scene"), "pan")
        v = float(speed if speed is not None else opt(("--speed",), {"pan": 450, "thin": 330, "fence": 270,
                                                                       "discs": 600}.get(scene, 0)))
        n = self.saccades(int(w), int(h), v, float(opt(("--angle",), "0")), secs,
                          float(opt(("--pursuit-gain",), gain)))
        if n == 0:
            return ""
        return ("the simulated eye makes %d catch-up saccade%s in each run (back to the centre on leaving the central "
                "half of the %sx%s view at %.0f px/s): a TRM pair straddling one falls apart on the retina and the "
                "visual model, which has no saccadic suppression, judges the jump (docs/experiments.md, 'Saccades')" % (
                    n, "s" if n > 1 else "", w, h, v))

    @staticmethod
    def select(rows, **eq):
        return [r for r in rows if all(str(r.get(k)) == str(v) for k, v in eq.items())]

    @staticmethod
    def values(rows, col, **eq):
        """Floats of col over the rows matching eq, ordered by seed (then job)."""
        sel = Experiment.select(rows, **eq)
        sel.sort(key=lambda r: (int(r.get("seed", 0) or 0), int(r.get("job", 0))))
        return [float(r[col]) for r in sel]

    def claim(self, paper, claim, paper_value, tdc_value, verdict, why="", spread="", n="", run="", quote="",
              ci="", margin="", cls=""):
        """One row.  quote: the paper's sentence the row tests ("§4.3: '...'");
        ci: the 95 % interval of the judged quantity (spread: older rows' sample
        SD, shown when there is no interval); cls: what a non-agreement rests on
        (CLASSES), its reason in why."""
        if verdict not in VERDICTS:
            raise ValueError("verdict '%s' (one of %s)" % (verdict, ", ".join(VERDICTS)))
        if cls not in CLASSES:
            raise ValueError("class '%s' (one of %s)" % (cls, ", ".join(c for c in CLASSES if c)))
        if cls and verdict in ("agree", "equivalent"):
            raise ValueError("class '%s' on an agreeing row" % cls)
        self.claims.append({"group": self.group, "paper": paper, "quote": quote, "claim": claim,
                            "paper_value": paper_value, "tdc_value": tdc_value,
                            "ci": ci or ("SD %s" % spread if spread != "" else ""), "margin": margin, "n": n,
                            "run": run or "%s (scale %s)" % (self.group, self.scale), "verdict": verdict,
                            "class": cls, "why": why})

    def content_spread(self, j, rows, eq_a, eq_b):
        """When a 'better' row is inconclusive with a positive gain carried by a few contents - A ahead on most
        contents in JOD and in FLIP, by more than the margin only on a minority - the per-content picture
        (ahead, flip_ahead, n, [(content, gain) over the margin]); else None.  Contents are named by their
        image (else seed), in exp.values' order."""
        if j["verdict"] != "inconclusive" or j["gain"] <= 0:
            return None
        key = lambda r: (int(r.get("seed", 0) or 0), int(r.get("job", 0)))  # noqa: E731 (values' order)
        names = [os.path.splitext(os.path.basename(r.get("image", "") or r.get("seed", "")))[0]
                 for r in sorted(self.select(rows, **eq_a), key=key)]
        ga = [a - b for a, b in zip(self.values(rows, "jod", **eq_a), self.values(rows, "jod", **eq_b))]
        gf = [b - a for a, b in zip(self.values(rows, "flip", **eq_a), self.values(rows, "flip", **eq_b))]
        ahead, flip_ahead = sum(1 for g in ga if g > 0), sum(1 for g in gf if g > 0)
        big = [(n, g) for n, g in zip(names, ga) if g > j["margin"]]
        if 2 * ahead <= len(ga) or 2 * flip_ahead <= len(gf) or not big or 2 * len(big) > len(ga):
            return None
        return ahead, flip_ahead, len(ga), big

    def class_last(self, cls, why):
        """Classes the last row (a non-agreement) and adds the reason to its why: for a class that
        depends on what the data show beyond the verdict (per content, per scale)."""
        if cls not in CLASSES or not cls:
            raise ValueError("class '%s' (one of %s)" % (cls, ", ".join(c for c in CLASSES if c)))
        row = self.claims[-1]
        if row["verdict"] in ("agree", "equivalent"):
            raise ValueError("class '%s' on an agreeing row" % cls)
        row["class"] = cls
        row["why"] += "; " + why

    def judge(self, paper, quote, claim, paper_value, a, b, kind, metric, label_a="A", label_b="B", digits=4,
              run="", why="", cls="", margin=None, method="t", higher_is_better=None, secondary=(), note=""):
        """A row judged by tdc_stats.judge: the paper says A is 'better' than /
        'not worse' than / 'equal' to B in metric; a and b paired per seed or
        content.  cls/why: the class and reason if it does not agree (kept
        only then).  secondary: (metric, a, b, digits) shown beside the
        primary metric (their gain, interval and own verdict in the tdc and
        CI columns) without deciding the row: FLIP / SSIM / PSNR beside JOD
        on a claim about what an observer sees.  note: said in why whatever
        the verdict.  Returns the judge() result."""
        st = tdc_stats
        if not a or len(a) != len(b):
            raise ExpError(EXIT_RUN_FAILED, "%s: '%s': %d vs %d values (unpaired or missing results)" % (
                self.group, claim, len(a), len(b)))
        j = st.judge(a, b, kind, metric, higher_is_better=higher_is_better, margin=margin, method=method)
        ok = j["verdict"] in ("agree", "equivalent")
        tdc = "%s %s: %s vs %s %s" % (metric, label_a, st.fmt_ms(st.summary(a), digits), label_b,
                                      st.fmt_ms(st.summary(b), digits))
        ci = "gain %s %s" % (st.fmt(j["gain"], digits), st.fmt_ci(j, digits))
        for m2, a2, b2, d2 in secondary:
            if not a2 or len(a2) != len(b2):
                raise ExpError(EXIT_RUN_FAILED, "%s: '%s': secondary %s: %d vs %d values" % (
                    self.group, claim, m2, len(a2), len(b2)))
            j2 = st.judge(a2, b2, kind, m2, method=method)
            tdc += "; secondary %s: %s vs %s" % (m2, st.fmt_ms(st.summary(a2), d2), st.fmt_ms(st.summary(b2), d2))
            ci += "; %s gain %s %s (%s)" % (m2, st.fmt(j2["gain"], d2), st.fmt_ci(j2, d2), j2["verdict"])
        self.claim(paper, claim, paper_value, tdc, j["verdict"],
                   j["why"] + ("; " + note if note else "") + ("" if ok or not why else "; " + why),
                   n=j["n"], run=run, quote=quote, ci=ci, margin=st.fmt(j["margin"], digits), cls="" if ok else cls)
        return j

    def judge_seen(self, paper, quote, claim, paper_value, rows, eq_a, eq_b, kind, label_a="A", label_b="B",
                   secondary=(("flip", 4), ("psnr_db", 2)), run="", why="", cls="", jod_margin=None, note=""):
        """A row on what an observer sees: judged in JOD (tdc-sim --jod, the visual model of
        docs/visual-model.md; margin 0.1 JOD), with the secondary metrics (FLIP, PSNR, ...) beside
        it.  eq_a / eq_b select A's and B's rows (exp.values keywords).  A run made without --jod
        (or no longer than the judge's warm-up: has_jod) has no usable JOD: the first secondary
        metric then decides, and the row says so."""
        sel = self.select(rows, **eq_a) + self.select(rows, **eq_b)
        primary = "jod" if self.has_jod(sel) else None
        sec = [(m, d) for m, d in secondary]
        if primary is None:
            (primary, digits), sec = sec[0], sec[1:]
            note += ("; " if note else "") + ("no JOD in these results (a run without --jod, or no longer than the "
                                              "judge's 0.25 s warm-up): %s decides" % primary)
        else:
            digits = 3
        vals = lambda m, eq: self.values(rows, m, **eq)  # noqa: E731
        return self.judge(paper, quote, claim, paper_value, vals(primary, eq_a), vals(primary, eq_b), kind, primary,
                          label_a, label_b, digits, run=run, why=why, cls=cls, note=note,
                          margin=jod_margin if primary == "jod" else None,
                          secondary=[(m, vals(m, eq_a), vals(m, eq_b), d) for m, d in sec])

    def judge_all(self, paper, quote, claim, paper_value, metrics, kind, label_a="A", label_b="B", run="", why="",
                  cls="", method="t"):
        """One row for a claim the paper makes on several metrics at once ("lower RMSE and higher
        SSIM"): metrics is a list of (metric, a, b, digits), each judged by tdc_stats.judge; the
        row holds only when every metric holds (tdc_stats.judge_all).  Returns the combined result."""
        st = tdc_stats
        js, tdc, cis, margins, whys = [], [], [], [], []
        for metric, a, b, digits in metrics:
            if not a or len(a) != len(b):
                raise ExpError(EXIT_RUN_FAILED, "%s: '%s': %s: %d vs %d values (unpaired or missing results)" % (
                    self.group, claim, metric, len(a), len(b)))
            j = st.judge(a, b, kind, metric, method=method)
            js.append(j)
            tdc.append("%s %s: %s vs %s %s" % (metric, label_a, st.fmt_ms(st.summary(a), digits), label_b,
                                                st.fmt_ms(st.summary(b), digits)))
            cis.append("%s gain %s %s" % (metric, st.fmt(j["gain"], digits), st.fmt_ci(j, digits)))
            margins.append("%s %s" % (metric, st.fmt(j["margin"], digits)))
            whys.append("%s: %s %s" % (metric, j["verdict"], j["why"]))
        c = st.judge_all(js)
        ok = c["verdict"] in ("agree", "equivalent")
        self.claim(paper, claim, paper_value, "; ".join(tdc), c["verdict"],
                   "; ".join(whys) + ("" if ok or not why else "; " + why), n=js[0]["n"], run=run, quote=quote,
                   ci="; ".join(cis), margin="; ".join(margins), cls="" if ok else cls)
        return c


def load_claims_module(group):
    path = os.path.join(GROUPS_DIR, group, "claims.py")
    spec = importlib.util.spec_from_file_location("claims_" + group.replace("-", "_"), path)
    mod = importlib.util.module_from_spec(spec)
    try:
        spec.loader.exec_module(mod)
    except Exception as e:  # a broken claims script is the group's fault: name it
        raise ExpError(EXIT_BAD_GROUP, "%s: cannot load: %s" % (os.path.relpath(path, REPO), e))
    if not hasattr(mod, "claims"):
        raise ExpError(EXIT_BAD_GROUP, "%s: no function claims(exp)" % os.path.relpath(path, REPO))
    return mod


def run_claims(group, out):
    meta = read_meta(out, group)
    exp = Experiment(group, out, meta.get("scale", "?"))
    mod = load_claims_module(group)
    try:
        mod.claims(exp)
    except ExpError:
        raise
    except Exception:
        raise ExpError(EXIT_RUN_FAILED, "%s/claims.py raised:\n%s" % (group, traceback.format_exc()))
    path = os.path.join(out, group, "claims.csv")
    os.makedirs(os.path.dirname(path), exist_ok=True)  # a group without jobs (trm-fig6) may have no folder yet
    tmp = path + ".tmp"
    with open(tmp, "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, CLAIM_COLUMNS, lineterminator="\n")
        w.writeheader()
        for c in exp.claims:
            w.writerow(c)
    os.replace(tmp, path)
    print("tdc-experiments: %s: %d claims -> %s" % (group, len(exp.claims), os.path.relpath(path, REPO)),
          file=sys.stderr)
    return exp.claims


def read_meta(out, group):
    try:
        with open(os.path.join(out, group, "meta.json"), encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError):
        return {}


def cache_dir(out):
    return os.path.join(out, ".cache")


def cache_rates(out):
    """CPU seconds per work unit (tdc_sweep.job_units) of the cached runs: per sweep and over all."""
    per, tot = {}, [0.0, 0.0]
    for st in glob.glob(os.path.join(cache_dir(out), "*", "*", "status.json")):
        try:
            with open(st, encoding="utf-8") as f:
                s = json.load(f)
            cpu, units = float(s["cpu_s"]), float(s["job_units"])
        except (OSError, ValueError, KeyError, TypeError):
            continue
        acc = per.setdefault(s.get("sweep", ""), [0.0, 0.0])
        for a in (acc, tot):
            a[0] += cpu
            a[1] += units
    rate = lambda a: a[0] / a[1] if a[1] > 0 else None  # noqa: E731
    return {k: rate(v) for k, v in per.items()}, rate(tot)


def plan(sel, scale, out, sim):
    """Per sweep: (group, sweep, jobs, cached, estimated CPU s of the rest or None).  The estimate is
    the sweep's own CPU s per unit from its cached runs, else that of every cached run."""
    per, overall = cache_rates(out)
    sha = tdc_sweep.file_sha256(sim)
    rows = []
    for g in sel:
        for sw in sweeps_of(g):
            name = os.path.splitext(os.path.basename(sw))[0]
            tmp = os.path.join(out, ".plan", g, name + ".sweep")  # tdc_sweep reads sweep files
            os.makedirs(os.path.dirname(tmp), exist_ok=True)
            with open(tmp, "w", encoding="utf-8") as f:
                f.write(scale_sweep(sw, scale))
            try:
                spec = {"jobs": tdc_sweep.expand(tdc_sweep.parse_sweep(tmp))}
            except tdc_sweep.SweepError as e:
                raise ExpError(EXIT_BAD_GROUP, str(e))
            done, units = 0, 0.0
            for j in spec["jobs"]:
                if tdc_sweep.cached(cache_dir(out), tdc_sweep.job_key(sha, tdc_sweep.job_argv(spec, j["index"]))):
                    done += 1
                else:
                    units += tdc_sweep.job_units(j["args"])
            rate = per.get("%s/%s.sweep" % (g, name), overall)
            rows.append((g, name, len(spec["jobs"]), done, units * rate if rate is not None else None))
    return rows


def print_plan(rows, scale, file=sys.stderr):
    jobs, done = sum(r[2] for r in rows), sum(r[3] for r in rows)
    est = [r[4] for r in rows if r[2] > r[3]]
    known = sum(e for e in est if e is not None)
    unknown = sum(1 for e in est if e is None)
    print("tdc-experiments: scale %s: %d jobs, %d done (cached), %d to run: about %.0f CPU s (%.1f h)%s" % (
        scale, jobs, done, jobs - done, known, known / 3600.0,
        "; %d sweeps not estimated (nothing cached yet to measure a rate)" % unknown if unknown else ""), file=file)


def run_group(group, scale, out, jobs, sim):
    gdir = os.path.join(out, group)
    # a run starts from nothing: claims scripts cache their own runs (tdc-render timings, tdc-zeng CSVs) in
    # the group's folder, and a cache from an older build or scale must not be judged as this run's
    if os.path.isdir(gdir):
        shutil.rmtree(gdir)
    os.makedirs(gdir)
    t0 = time.monotonic()
    c0 = os.times()
    failed = []
    sweeps = {}
    for sw in sweeps_of(group):
        name = os.path.splitext(os.path.basename(sw))[0]
        text = scale_sweep(sw, scale)
        eff = os.path.join(gdir, name + ".sweep")
        with open(eff, "w", encoding="utf-8") as f:
            f.write(text)
        n = count_jobs(text)
        print("tdc-experiments: %s/%s: %d jobs at scale %s" % (group, name, n, scale), file=sys.stderr)
        ts = time.monotonic()
        rc = subprocess.call([sys.executable, os.path.join(REPO, "sim", "sweep", "tdc_sweep.py"), "local", eff,
                              os.path.join(gdir, name), "-j", str(jobs), "--sim", sim, "--cache", cache_dir(out)])
        sweeps[name] = {"jobs": n, "wall_s": round(time.monotonic() - ts, 1), "rc": rc}
        if rc != 0:
            failed.append("%s/%s (tdc_sweep exit %d)" % (group, name, rc))
    meta = {"group": group, "scale": scale, "jobs_parallel": jobs, "sweeps": sweeps,
            "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
            "command": " ".join(["sim/experiments/tdc_experiments.py"] + sys.argv[1:]),
            "cached_jobs": 0, "load_avg": round(os.getloadavg()[0], 1)}

    # the jobs as they ran (a job restored from the cache keeps its own CPU and wall seconds)
    for p in glob.glob(os.path.join(gdir, "*", "jobs", "*", "status.json")):
        try:
            with open(p, encoding="utf-8") as f:
                st = json.load(f)
        except (OSError, ValueError):
            continue
        meta["cached_jobs"] += 1 if st.get("cached") else 0
        meta["jobs_cpu_s"] = round(meta.get("jobs_cpu_s", 0) + float(st.get("cpu_s", 0)), 1)

    def write_meta():  # the claims' own runs (tdc-render, tdc-zeng) count too
        c1 = os.times()
        meta["wall_s"] = round(time.monotonic() - t0, 1)
        meta["cpu_s"] = round(sum(getattr(c1, k) - getattr(c0, k) for k in ("user", "system", "children_user",
                                                                            "children_system")), 1)
        with open(os.path.join(gdir, "meta.json"), "w", encoding="utf-8") as f:
            json.dump(meta, f, indent=1, sort_keys=True)
    write_meta()
    if failed:
        raise ExpError(EXIT_RUN_FAILED, "failed: " + ", ".join(failed))
    run_claims(group, out)
    write_meta()
    return meta


def read_all_claims(out):
    rows, missing = [], []
    for g in groups():
        p = os.path.join(out, g, "claims.csv")
        if not os.path.isfile(p):
            missing.append(g)
            continue
        with open(p, newline="", encoding="utf-8") as f:
            rows += list(csv.DictReader(f))
    return rows, missing


def md_cell(s):
    return str(s).replace("|", "\\|").replace("\n", " ")


def claims_table(rows):
    out = ["| paper | the sentence tested | claim (condition) | paper | tdc | 95 % CI (n) | margin | run | verdict | why |",
           "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        ci = r.get("ci", r.get("spread", "")) + (" (%s)" % r["n"] if r.get("n") else "")
        v = r["verdict"] if r["verdict"] in ("agree", "equivalent") else "**%s**" % r["verdict"]
        if r.get("class"):
            v += " (%s)" % r["class"]
        out.append("| %s |" % " | ".join(md_cell(x) for x in (r["paper"], r.get("quote", ""), r["claim"],
                                                            r["paper_value"], r["tdc_value"], ci, r.get("margin", ""),
                                                            r["run"], v, r["why"])))
    return "\n".join(out) + "\n"


def counts(rows):
    """The block's count line: verdicts, the classes of the non-agreements, the goal's share."""
    k = {v: sum(1 for r in rows if r["verdict"] == v) for v in VERDICTS}
    cl = {c: sum(1 for r in rows if r.get("class") == c) for c in CLASSES if c}
    good = k["agree"] + k["equivalent"] + cl["setting"]
    return ("%d claims: %d agree, %d equivalent, %d disagree, %d inconclusive; of the non-agreements %d are "
            "setting differences, %d model limits, %d not reproducible here, %d unclassed. Agree, equivalent or "
            "an explained setting difference: %d of %d (%.0f %%)." % (
                len(rows), k["agree"], k["equivalent"], k["disagree"], k["inconclusive"], cl["setting"],
                cl["model limit"], cl["not reproducible"],
                sum(1 for r in rows if r["verdict"] not in ("agree", "equivalent") and not r.get("class")),
                good, len(rows), 100.0 * good / len(rows) if rows else 0.0))


def summary(rows, out):
    """What `make demo` prints: the scale, the count line, and per group its verdicts and run time."""
    scales = sorted({read_meta(out, g).get("scale", "?") for g in groups() if read_meta(out, g)})
    lines = ["Paper vs tdc at scale %s (%s):" % (", ".join(scales) or "?", os.path.relpath(out, REPO)), counts(rows),
             "%-16s %6s %6s %6s %6s %6s %9s %9s" % ("group", "claims", "agree", "equiv", "disagr", "inconc",
                                                     "unclassed", "CPU s")]
    for g in groups():
        gr = [r for r in rows if r["group"] == g]
        if not gr:
            continue
        k = [sum(1 for r in gr if r["verdict"] == v) for v in VERDICTS]
        un = sum(1 for r in gr if r["verdict"] not in ("agree", "equivalent") and not r.get("class"))
        lines.append("%-16s %6d %6d %6d %6d %6d %9d %9.0f" % ((g, len(gr)) + tuple(k) + (
            un, read_meta(out, g).get("cpu_s", 0))))
    return "\n".join(lines)


def runs_table(out):
    """Every group's run: scale, jobs (restored from the cache), the jobs' CPU seconds as they ran, and the
    last invocation's wall and CPU seconds (meta.json), with the totals."""
    lines = ["| group | scale | jobs | of them from the cache | tdc-sim CPU s (as run) | wall s | CPU s (this "
             "invocation: jobs and claims) | date |",
             "| --- | --- | ---: | ---: | ---: | ---: | ---: | --- |"]
    t = [0, 0, 0.0, 0.0, 0.0]
    for g in groups():
        m = read_meta(out, g)
        if m:
            v = [sum(s["jobs"] for s in m["sweeps"].values()), m.get("cached_jobs", 0), m.get("jobs_cpu_s", 0),
                 m.get("wall_s", 0), m.get("cpu_s", 0)]
            t = [a + b for a, b in zip(t, v)]
            lines.append("| %s | %s | %d | %d | %.0f | %.0f | %.0f | %s |" % ((g, m.get("scale")) + tuple(v) + (
                m.get("date", ""),)))
    lines.append("| all | | %d | %d | %.0f | %.0f | %.0f | |" % tuple(t))
    return "\n".join(lines)


def report(out, report_path, results_path):
    rows, missing = read_all_claims(out)
    lines = ["# Paper vs tdc: the papers' experiments in the simulator", "",
             "Written by `sim/experiments/tdc_experiments.py report` from every group's `claims.csv` "
             "(`make experiments`; how a group is added: docs/experiments.md). Each row quotes the sentence it "
             "tests and is judged per condition: the 95 % confidence interval of A's paired gain over B (per "
             "seed/content, n pairs) against the metric's equivalence margin (sim/experiments/tdc_stats.py: "
             "agree, equivalent, disagree or inconclusive). Rows written before that carry \"SD\": the sample "
             "standard deviation.", "", counts(rows), ""]
    if missing:
        lines += ["Groups without results (not run yet): %s." % ", ".join(missing), ""]
    lines += ["## Runs", "", runs_table(out), "", "## Paper vs tdc", "", claims_table(rows)]
    for g in groups():
        readme = os.path.join(GROUPS_DIR, g, "README.md")
        extra = os.path.join(out, g, "extra.md")
        if os.path.isfile(readme) or os.path.isfile(extra):
            lines += ["## %s" % g, ""]
            if os.path.isfile(readme):
                lines += [open(readme, encoding="utf-8").read().strip(), ""]
            if os.path.isfile(extra):  # tables a claims script writes beside its claims
                lines += [open(extra, encoding="utf-8").read().strip(), ""]
    text = "\n".join(lines) + "\n"
    os.makedirs(os.path.dirname(os.path.abspath(report_path)), exist_ok=True)
    with open(report_path, "w", encoding="utf-8") as f:
        f.write(text)
    print("tdc-experiments: %d claims -> %s" % (len(rows), report_path), file=sys.stderr)
    print(summary(rows, out))
    if results_path:
        update_results(results_path, rows, out)
    return EXIT_OK


def update_results(path, rows, out):
    """docs/results.md: the table and the disagreements, between the markers."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    metas = [read_meta(out, g) for g in groups() if read_meta(out, g)]
    scales = sorted({m.get("scale", "?") for m in metas})
    headset = scales == ["headset"]
    begin, end = (MARK_BEGIN, MARK_END) if headset else (MARK_DEMO_BEGIN, MARK_DEMO_END)
    cmds = sorted({m["command"] for m in metas if m.get("command")})
    gs = set(groups())

    def generic(c):  # the command without its group list: one form for runs split over disjoint groups
        t = c.split()
        t = [x for x in t if x not in gs]
        return " ".join(t[:2] + ["[GROUP...]"] + t[2:]) if len(t) > 2 else c
    forms = sorted({generic(c) for c in cmds})
    cmd = ("`%s`" % cmds[0] if len(cmds) == 1 else "`" + "` / `".join(forms) + "` (%d invocations over disjoint "
           "groups, some in parallel; each group's own is in its meta.json)" % len(cmds)) if cmds else (
        "`make experiments`" if headset else
        "`make experiments EXP_SCALE=%s`" % (scales[0] if len(scales) == 1 else "S"))
    wall, cpu = sum(m.get("wall_s", 0) for m in metas), sum(m.get("cpu_s", 0) for m in metas)
    jcpu, njobs = sum(m.get("jobs_cpu_s", 0) for m in metas), sum(sum(s["jobs"] for s in m["sweeps"].values())
                                                                  for m in metas)
    loads = [m["load_avg"] for m in metas if "load_avg" in m]
    scale_note = ("**%s scale** (small frames and short runs: not the headset scale of `make experiments`; the "
                  "`run` column and the runs table say which sweep produced each row)" % scales[0].capitalize()
                  if scales and not headset else "Scale of these results: **%s**" % (", ".join(scales) or "?"))
    body = [begin, "", "%s. Command: %s, then `sim/experiments/tdc_experiments.py report --out %s`; "
            "%d tdc-sim jobs, %.0f CPU s as they ran; the groups' last runs %.0f s wall summed, %.0f CPU s%s (full report "
            "with intervals: `report/experiments.md`; docs/experiments.md)." % (
                scale_note, cmd, os.path.relpath(out, REPO), njobs, jcpu, wall, cpu,
                " on this shared 2-core machine at load average %.0f-%.0f" % (min(loads), max(loads)) if loads else ""),
            "",
            counts(rows), "", runs_table(out), "", claims_table(rows)]
    dis = [r for r in rows if r["verdict"] not in ("agree", "equivalent")]
    if dis:
        body += ["Where tdc disagrees or cannot decide, and why:", ""]
        body += ["- **%s, %s** (%s%s): paper %s, tdc %s — %s" % (
            r["paper"], r["claim"], r["verdict"], ", " + r["class"] if r.get("class") else "", r["paper_value"],
            r["tdc_value"], r["why"] or "(no reason given)") for r in dis]
        body.append("")
    body.append(end)
    block = "\n".join(body)
    if begin in text and end in text:
        a = text.index(begin)
        b = text.index(end) + len(end)
        text = text[:a] + block + text[b:]
    else:
        text = text.rstrip("\n") + "\n\n## The papers' experiments at %s\n\n" % (
            "headset scale (`make experiments`)" if headset else "demo scale (`make demo`)") + block + "\n"
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(path + ".tmp", path)


def main(argv):
    r = tdc_argv.command(argv, __doc__, "tdc-experiments",
                         valued=("--scale", "--out", "-j", "--sim", "--report", "--results"))
    if isinstance(r, int):
        return r
    cmd, opts, pos = r
    scale = opts.get("--scale", "headset")
    out = os.path.abspath(opts.get("--out", os.path.join(REPO, "build", "experiments")))
    if scale not in SCALES:
        print("tdc-experiments: --scale '%s' (one of %s)" % (scale, ", ".join(SCALES)), file=sys.stderr)
        return EXIT_USAGE
    known = groups()
    for g in pos:
        if g not in known:
            print("tdc-experiments: unknown group '%s' (groups: %s)" % (g, ", ".join(known)), file=sys.stderr)
            return EXIT_USAGE
    sel = pos or known
    try:
        if cmd == "list":
            sim = os.path.abspath(opts.get("--sim", os.path.join(REPO, "build", "gcc-O2", "tdc-sim")))
            if not os.path.isfile(sim):  # no binary: the jobs only (no cache key without it)
                for g in sel:
                    for sw in sweeps_of(g):
                        print("%-24s %-24s %4d jobs" % (g, os.path.basename(sw), count_jobs(scale_sweep(sw, scale))))
                return EXIT_OK
            rows = plan(sel, scale, out, sim)
            for g, name, n, done, est in rows:
                print("%-24s %-24s %4d jobs %4d cached %s" % (g, name + ".sweep", n, done,
                                                             "" if n == done else "~%.0f CPU s" % est
                                                             if est is not None else "(no rate yet)"))
            print_plan(rows, scale, sys.stdout)
            return EXIT_OK
        if cmd == "run":
            sim = os.path.abspath(opts.get("--sim", os.path.join(REPO, "build", "gcc-O2", "tdc-sim")))
            j = opts.get("-j", str(os.cpu_count() or 1))
            if not j.isdigit() or int(j) < 1:
                print("tdc-experiments: -j '%s': a positive number" % j, file=sys.stderr)
                return EXIT_USAGE
            if not os.access(sim, os.X_OK):
                print("tdc-experiments: tdc-sim not found at %s (make, or --sim PATH)" % sim, file=sys.stderr)
                return EXIT_USAGE
            # the jobs run a copy: a rebuild of tdc-sim during a long run
            # must not make the jobs started meanwhile fail (or mix builds)
            os.makedirs(os.path.join(out, ".bin"), exist_ok=True)
            copy = os.path.join(out, ".bin", "tdc-sim")
            shutil.copy2(sim, copy + ".tmp")
            os.replace(copy + ".tmp", copy)
            sim = copy
            rc = EXIT_OK
            for g in sel:
                try:
                    print_plan(plan(sel[sel.index(g):], scale, out, sim), scale)
                    m = run_group(g, scale, out, int(j), sim)
                    print("tdc-experiments: %s done in %.0f s wall, %.0f CPU s" % (g, m["wall_s"], m["cpu_s"]),
                          file=sys.stderr)
                except ExpError as e:
                    print("tdc-experiments: %s: %s" % (g, e), file=sys.stderr)
                    rc = e.code
            return rc
        if cmd == "claims":
            rc = EXIT_OK
            for g in sel:
                try:
                    run_claims(g, out)
                except ExpError as e:
                    print("tdc-experiments: %s: %s" % (g, e), file=sys.stderr)
                    rc = e.code
            return rc
        if cmd == "report":
            res = opts.get("--results", os.path.join(REPO, "docs", "results.md"))
            return report(out, opts.get("--report", os.path.join(REPO, "report", "experiments.md")),
                          None if res == "-" else res)
    except ExpError as e:
        print("tdc-experiments: %s" % e, file=sys.stderr)
        return e.code
    print("tdc-experiments: bad command line '%s' (see --help)" % " ".join(argv[1:]), file=sys.stderr)
    return EXIT_USAGE


if __name__ == "__main__":
    sys.exit(main(sys.argv))
