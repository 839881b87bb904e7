#!/usr/bin/python3
"""tdc-sweep - parameter sweeps of tdc-sim on an existing engine.

A sweep file (format below, docs/sweeps.md) expands to one job per
configuration; every job runs tdc-sim once into its own folder
OUT/jobs/NNNN/; the jobs run under GNU parallel on this machine (`local`) or
as a Slurm job array with one configuration per array index (`slurm`); the
`merge` step builds OUT/sweep.csv (deterministic columns: the same bytes from
any engine), OUT/timings.csv (the time columns) and OUT/report.md, and names
every failed or missing job.

Sweep file: one `key = value` per line, '#' starts a comment.
    name    = TEXT             title of the report
    base    = ARGS             tdc-sim arguments every job gets
    modes   = LIST LIST ...    axis: -m LIST (a LIST is comma-separated modes)
    refresh = HZ HZ ...        axis: -r HZ
    r       = NN NN ...        axis: TRM ratio in percent, substituted for {r}
                               in the other values (e.g. modes = full,trm{r})
    speed   = PX_S ...         axis: --speed PX_S
    panel   = oled lcd:NAME .. axis: -p oled | -p lcd --profile NAME
    seed    = N N ...          axis: -S N
    scene / image / size       axes: -s NAME / --image FILE / -g WxH
    pursuit / gain / renderer  axes: --pursuit track|fixate / --pursuit-gain G / -R SCENE
    NAME    = V V ...          any other axis: only substituted for {NAME}
Values are separated by white space.  Jobs are the Cartesian product of the
axes in file order, the last axis varying fastest; job i is the same
configuration on every engine.

Commands:
    tdc-sweep expand SWEEP OUT [--sim PATH]   write OUT/jobs.json, print the jobs
    tdc-sweep run-job OUT [INDEX]             run one job (INDEX or $SLURM_ARRAY_TASK_ID)
    tdc-sweep local SWEEP OUT [-j N] [--cache DIR]
                                              expand, GNU parallel -j N (default: cores), merge
    tdc-sweep slurm SWEEP OUT [--wait] [--partition P] [--time MIN]
                                              expand, sbatch --array=0-(N-1); --wait: then merge
    tdc-sweep merge OUT                       OUT/sweep.csv, timings.csv, report.md

Result cache (--cache DIR, local and slurm): a job that ended with exit 0 is
copied to DIR/<key>/, key = SHA-256 of the job's full tdc-sim arguments, the
tdc-sim binary's SHA-256 and the SHA-256 of every argument that names a file;
a later job with the same key restores those files instead of running, so an
interrupted sweep resumes where it stopped.  status.json records the job's
CPU seconds (cpu_s) and its work units (pixels x refreshes x modes, job_units)
for the remaining-time estimate of tdc_experiments.py.

Exit codes (the one table, common/tdc_exit.h; docs/tools.md):
0 OK, 1 ARGS, 13 INPUT (malformed sweep file or OUT), 18 JOBS (merge: a job
failed or is missing; the rest is merged), 19 ENGINE (GNU parallel / Slurm
missing or refused the array).
"""
import csv
import hashlib
import itertools
import json
import os
import resource
import shlex
import shutil
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "common"))
from tdc_exit import EXIT  # noqa: E402  (the one exit-code table)
import tdc_argv  # noqa: E402  (the one command-line reader)
EXIT_OK, EXIT_BAD_SWEEP, EXIT_USAGE, EXIT_JOBS_FAILED, EXIT_ENGINE = EXIT.OK, EXIT.INPUT, EXIT.ARGS, EXIT.JOBS, EXIT.ENGINE
OPTION_AXES = {"modes": ["-m"], "refresh": ["-r"], "speed": ["--speed"], "seed": ["-S"],
               "scene": ["-s"], "image": ["--image"], "size": ["-g"],
               "pursuit": ["--pursuit"], "gain": ["--pursuit-gain"], "renderer": ["-R"]}
# Columns that measure time (CPU or wall): kept out of sweep.csv so that it is
# the same bytes from every engine; they go to timings.csv.
def is_time_column(name):
    return (name.endswith("_us_per_frame") or name.endswith("_ms") or name.endswith("_wall_s")
            or name.endswith("_cpu_s") or name.startswith("time_") or name.startswith("wall")
            or "_us_" in name or name.endswith("_per_s_wall") or name == "mpix_per_s")


class SweepError(Exception):
    pass


def die(code, msg):
    print("tdc-sweep: " + msg, file=sys.stderr)
    sys.exit(code)


def parse_sweep(path):
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except OSError as e:
        raise SweepError("%s: cannot read: %s" % (path, e.strerror))
    name, base, axes, seen = os.path.basename(path), [], [], set()
    for n, raw in enumerate(text.splitlines(), 1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        if "=" not in line:
            raise SweepError("%s line %d: expected 'key = value', got '%s'" % (path, n, raw.strip()))
        key, val = (s.strip() for s in line.split("=", 1))
        if not key.replace("_", "").replace("-", "").isalnum():
            raise SweepError("%s line %d: bad key '%s'" % (path, n, key))
        if key in seen:
            raise SweepError("%s line %d: '%s' given twice" % (path, n, key))
        seen.add(key)
        if key == "name":
            name = val
        elif key == "base":
            try:
                base = shlex.split(val)
            except ValueError as e:
                raise SweepError("%s line %d: base: %s" % (path, n, e))
        else:
            vals = val.split()
            if not vals:
                raise SweepError("%s line %d: axis '%s' has no values" % (path, n, key))
            if len(set(vals)) != len(vals):
                raise SweepError("%s line %d: axis '%s' repeats a value" % (path, n, key))
            if key == "panel":
                for v in vals:
                    if not (v == "oled" or v == "lcd" or v.startswith("lcd:") or v.startswith("oled:")):
                        raise SweepError("%s line %d: panel '%s' (oled, lcd, lcd:PROFILE, oled:PROFILE)" % (path, n, v))
            axes.append((key, vals))
    if not axes and not base:
        raise SweepError("%s: no axes and no base arguments" % path)
    return {"name": name, "base": base, "axes": axes}


def substitute(s, values):
    for k, v in values.items():
        s = s.replace("{%s}" % k, v)
    return s


def expand(sweep):
    axes = sweep["axes"]
    jobs = []
    for combo in itertools.product(*[vals for _, vals in axes]) if axes else [()]:
        raw = {a: v for (a, _), v in zip(axes, combo)}
        values = {a: substitute(v, raw) for a, v in raw.items()}
        args = [substitute(x, raw) for x in sweep["base"]]
        for a, v in values.items():
            if a in OPTION_AXES:
                args += OPTION_AXES[a] + [v]
            elif a == "panel":
                kind, _, prof = v.partition(":")
                args += ["-p", kind] + (["--profile", prof] if prof else [])
        left = [x for x in args if "{" in x and "}" in x]
        if left:
            raise SweepError("unresolved placeholder in '%s' (no such axis)" % left[0])
        jobs.append({"index": len(jobs), "values": values, "args": args})
    return jobs


_SHA = {}


def file_sha256(path):
    """SHA-256 of a file's bytes (memoised per path, mtime and size)."""
    st = os.stat(path)
    memo = (path, st.st_mtime_ns, st.st_size)
    if memo not in _SHA:
        h = hashlib.sha256()
        with open(path, "rb") as f:
            for block in iter(lambda: f.read(1 << 20), b""):
                h.update(block)
        _SHA[memo] = h.hexdigest()
    return _SHA[memo]


def job_argv(spec, index):
    """tdc-sim's command line for job index, without its output folder."""
    return ["-q", "-l", "job-%04d" % index] + spec["jobs"][index]["args"]


def job_key(sim_sha, argv, cwd=REPO):
    """The cache key of one run: its full arguments, the binary, and the bytes of every file an
    argument names (an image, a scene file), so that an edited input is a new run."""
    files = {}
    for a in argv:
        p = a if os.path.isabs(a) else os.path.join(cwd, a)
        if a and not a.startswith("-") and os.path.isfile(p):
            files[a] = file_sha256(p)
    text = json.dumps({"sim": sim_sha, "argv": argv, "files": files}, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()


def _opt(args, names, default):
    v = default
    for i, a in enumerate(args[:-1]):
        if a in names:
            v = args[i + 1]
    return v


def job_units(args):
    """Work of one run for the time estimate: pixels x refreshes x modes (tdc-sim's defaults:
    128x96, 90 Hz, 48 refreshes or -d seconds).  The cost per unit differs between groups (JOD,
    the renderer, the LCD model), so the estimate calibrates per sweep where it can."""
    try:
        w, _, h = _opt(args, ("-g", "--size"), "128x96").partition("x")
        px = int(w) * int(h)
        hz = float(_opt(args, ("-r", "--refresh"), "90"))
        d = _opt(args, ("-d", "--duration"), None)
        n = float(d) * hz if d is not None else float(_opt(args, ("-n", "--refreshes"), "48"))
        modes = len(_opt(args, ("-m", "--modes"), "full").split(","))
        return max(1.0, px * n * modes)
    except ValueError:
        return 1.0


def sweep_id(path):
    """'<folder>/<file>' of a sweep file: names the sweep in the cache's per-sweep cost rates."""
    return "/".join(os.path.abspath(path).split(os.sep)[-2:])


def write_jobs(sweep_path, out, sim, cache=None):
    sweep = parse_sweep(sweep_path)
    jobs = expand(sweep)
    os.makedirs(os.path.join(out, "jobs"), exist_ok=True)
    spec = {"name": sweep["name"], "sweep_file": os.path.abspath(sweep_path), "sim": os.path.abspath(sim),
            "repo": REPO, "axes": [a for a, _ in sweep["axes"]], "jobs": jobs,
            "cache": os.path.abspath(cache) if cache else None}
    if cache:
        sha = file_sha256(os.path.abspath(sim))
        for j in jobs:
            j["key"] = job_key(sha, job_argv(spec, j["index"]))
            j["units"] = job_units(j["args"])
    tmp = os.path.join(out, "jobs.json.tmp")
    with open(tmp, "w", encoding="utf-8") as f:
        json.dump(spec, f, indent=1, sort_keys=True)
    os.replace(tmp, os.path.join(out, "jobs.json"))
    return spec


def load_jobs(out):
    try:
        with open(os.path.join(out, "jobs.json"), encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        raise SweepError("%s: no readable jobs.json (run expand first): %s" % (out, e))


def job_dir(out, i):
    return os.path.join(out, "jobs", "%04d" % i)


def cached(cache, key):
    """The cache entry of key when it holds a finished, successful run, else None."""
    if not cache or not key:
        return None
    e = os.path.join(cache, key[:2], key)
    try:
        with open(os.path.join(e, "status.json"), encoding="utf-8") as f:
            return e if json.load(f).get("rc") == 0 else None
    except (OSError, ValueError):
        return None


def store(cache, key, d):
    """Copy a successful job's folder into the cache (whole or not at all: copied beside, renamed)."""
    e = os.path.join(cache, key[:2], key)
    if os.path.isdir(e):
        return
    tmp = "%s.tmp%d" % (e, os.getpid())
    try:
        os.makedirs(os.path.dirname(e), exist_ok=True)
        shutil.copytree(d, tmp)
        os.rename(tmp, e)
    except OSError as err:  # a full disk or a concurrent store: the run itself stands
        shutil.rmtree(tmp, ignore_errors=True)
        print("tdc-sweep: cache: %s: not stored: %s" % (key[:12], err.strerror or err), file=sys.stderr)


def run_job(out, index):
    spec = load_jobs(out)
    if not (0 <= index < len(spec["jobs"])):
        raise SweepError("job index %d out of range 0..%d" % (index, len(spec["jobs"]) - 1))
    job = spec["jobs"][index]
    d = job_dir(out, index)
    if os.path.isdir(d):
        shutil.rmtree(d)  # a re-run replaces the job's folder, never mixes two runs
    hit = cached(spec.get("cache"), job.get("key"))
    if hit:  # the same run, the same binary, the same inputs: restore it (status.json says cached)
        shutil.copytree(hit, d)
        with open(os.path.join(d, "status.json"), encoding="utf-8") as f:
            st = json.load(f)
        st["cached"] = True
        with open(os.path.join(d, "status.json"), "w", encoding="utf-8") as f:
            json.dump(st, f, sort_keys=True)
        return 0
    os.makedirs(d)
    argv = [spec["sim"], "-q", "-l", "job-%04d" % index, "-o", os.path.abspath(d)] + job["args"]
    with open(os.path.join(d, "command.txt"), "w", encoding="utf-8") as f:
        f.write(" ".join(shlex.quote(a) for a in argv) + "\n")
    t0 = time.monotonic()
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    with open(os.path.join(d, "stdout.txt"), "wb") as so, open(os.path.join(d, "stderr.txt"), "wb") as se:
        try:
            rc = subprocess.call(argv, stdout=so, stderr=se, cwd=spec["repo"])
        except OSError as e:
            se.write(("tdc-sweep: cannot run %s: %s\n" % (spec["sim"], e.strerror)).encode())
            rc = 127
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    status = {"index": index, "rc": rc, "wall_s": round(time.monotonic() - t0, 3),
              "cpu_s": round(r1.ru_utime + r1.ru_stime - r0.ru_utime - r0.ru_stime, 3),
              "job_units": job_units(job["args"]), "sweep": sweep_id(spec["sweep_file"]),
              "host": os.uname().nodename, "engine": "slurm" if "SLURM_JOB_ID" in os.environ else "local"}
    tmp = os.path.join(d, "status.json.tmp")
    with open(tmp, "w", encoding="utf-8") as f:
        json.dump(status, f, sort_keys=True)
    os.replace(tmp, os.path.join(d, "status.json"))  # written last: its presence means the job ended
    if rc == 0 and spec.get("cache") and job.get("key"):
        store(spec["cache"], job["key"], d)
    return rc


def last_line(path):
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            lines = [l.strip() for l in f if l.strip()]
        return lines[-1] if lines else ""
    except OSError:
        return ""


def merge(out):
    spec = load_jobs(out)
    axes = spec["axes"]
    header, rows, trows, failed = None, [], [], []
    for job in spec["jobs"]:
        i = job["index"]
        d = job_dir(out, i)
        try:
            with open(os.path.join(d, "status.json"), encoding="utf-8") as f:
                st = json.load(f)
        except (OSError, ValueError):
            failed.append((i, "missing: the job never finished (no status.json)"))
            continue
        if st.get("rc") != 0:
            failed.append((i, "exit %s: %s" % (st.get("rc"), last_line(os.path.join(d, "stderr.txt")))))
            continue
        try:
            with open(os.path.join(d, "summary.csv"), encoding="utf-8", newline="") as f:
                table = list(csv.reader(f))
        except OSError:
            failed.append((i, "exit 0 but no summary.csv"))
            continue
        if len(table) < 2:
            failed.append((i, "exit 0 but summary.csv has no rows"))
            continue
        if header is None:
            header = table[0]
        elif table[0] != header:
            failed.append((i, "summary.csv columns differ from job %d's" % rows[0][0]))
            continue
        for r in table[1:]:
            rows.append([i] + [job["values"][a] for a in axes] + r)
    keep = [k for k, c in enumerate(header or []) if not is_time_column(c)]
    tcols = [k for k, c in enumerate(header or []) if is_time_column(c)]
    lead = ["job"] + axes
    with open(os.path.join(out, "sweep.csv"), "w", encoding="utf-8", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(lead + [header[k] for k in keep] if header else lead)
        n = len(lead)
        for r in rows:
            w.writerow(r[:n] + [r[n + k] for k in keep])
    with open(os.path.join(out, "timings.csv"), "w", encoding="utf-8", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(lead + ["mode"] + [header[k] for k in tcols] if header else lead)
        n = len(lead)
        mcol = header.index("mode") if header and "mode" in header else None
        for r in rows:
            w.writerow(r[:n] + [r[n + mcol] if mcol is not None else ""] + [r[n + k] for k in tcols])
    write_report(out, spec, header, rows, failed)
    for i, why in failed:
        print("tdc-sweep: job %04d failed: %s" % (i, why), file=sys.stderr)
    print("tdc-sweep: merged %d of %d jobs (%d rows) into %s; %d failed" %
          (len(spec["jobs"]) - len(failed), len(spec["jobs"]), len(rows), os.path.join(out, "sweep.csv"), len(failed)),
          file=sys.stderr)
    return EXIT_JOBS_FAILED if failed else EXIT_OK


def write_report(out, spec, header, rows, failed):
    axes = spec["axes"]
    # the judge's JOD first (empty where a job was not judged: docs/visual-model.md), then the secondary metrics
    cols = ["mode", "jod", "jod_fovea", "jod_periphery", "display_hz", "psnr_db", "ssim", "flip", "legacy_flicker",
            "rays_vs_full", "link_vs_full"]
    idx = [header.index(c) for c in cols if header and c in header]
    with open(os.path.join(out, "report.md"), "w", encoding="utf-8") as f:
        f.write("# Sweep `%s`\n\n" % spec["name"])
        f.write("%d jobs from `%s` (axes: %s); %d failed.  Every row of `sweep.csv` is one mode of one job;\n"
                "the time columns are in `timings.csv`.\n\n" %
                (len(spec["jobs"]), os.path.basename(spec["sweep_file"]), ", ".join(axes) or "none", len(failed)))
        if failed:
            f.write("## Failed jobs\n\n| job | configuration | why |\n| ---: | --- | --- |\n")
            for i, why in failed:
                conf = " ".join("%s=%s" % kv for kv in spec["jobs"][i]["values"].items())
                f.write("| %04d | %s | %s |\n" % (i, conf, why.replace("|", "\\|")))
            f.write("\n")
        f.write("## Results\n\n| job | %s | %s |\n" % (" | ".join(axes), " | ".join(header[k] for k in idx) if header else ""))
        f.write("| ---: |%s%s\n" % (" --- |" * len(axes), " ---: |" * len(idx)))
        n = 1 + len(axes)
        for r in rows:
            f.write("| %04d | %s | %s |\n" % (r[0], " | ".join(r[1:n]), " | ".join(r[n + k] for k in idx)))


def engine_local(out, n, jobs):
    if not shutil.which("parallel"):
        die(EXIT_ENGINE, "GNU parallel not found (Debian package 'parallel'; make deps)")
    me = os.path.abspath(__file__)
    cmd = ["parallel", "--will-cite", "--halt", "never", "-j", str(jobs), sys.executable, me, "run-job", out, "{}",
           ":::"] + [str(i) for i in range(n)]
    rc = subprocess.call(cmd)
    # parallel's exit status counts failed jobs (1..100) -- merge names them; >= 101 is its own failure
    if rc > 100:
        die(EXIT_ENGINE, "GNU parallel failed (exit %d)" % rc)


def engine_slurm(out, n, wait, partition, minutes):
    if not shutil.which("sbatch"):
        die(EXIT_ENGINE, "sbatch not found (Debian package 'slurm-client'; make deps)")
    os.makedirs(os.path.join(out, "slurm"), exist_ok=True)
    script = os.path.join(out, "sweep.sbatch")
    with open(script, "w", encoding="utf-8") as f:
        f.write("#!/bin/sh\n# one configuration per array index (tdc-sweep slurm)\n"
                "#SBATCH --job-name=tdc-sweep\n#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n"
                "#SBATCH --time=%d\n#SBATCH --output=%s/slurm/%%A_%%a.out\n%s"
                "exec %s %s run-job %s \"$SLURM_ARRAY_TASK_ID\"\n" %
                (minutes, os.path.abspath(out), "#SBATCH --partition=%s\n" % partition if partition else "",
                 shlex.quote(sys.executable), shlex.quote(os.path.abspath(__file__)), shlex.quote(os.path.abspath(out))))
    cmd = ["sbatch", "--parsable", "--array=0-%d" % (n - 1)] + (["--wait"] if wait else []) + [script]
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    jobid = p.stdout.strip().split(";")[0]
    if not jobid:
        die(EXIT_ENGINE, "sbatch refused the array: %s" % (p.stderr.strip().splitlines() or ["exit %d" % p.returncode])[-1])
    print("tdc-sweep: Slurm array job %s, %d tasks" % (jobid, n), file=sys.stderr)
    with open(os.path.join(out, "slurm", "jobid"), "w") as f:
        f.write(jobid + "\n")
    return jobid


def main(argv):
    r = tdc_argv.command(argv, __doc__, "tdc-sweep", valued=("-j", "--sim", "--partition", "--time", "--cache"),
                         flags=("--wait",))
    if isinstance(r, int):
        return r
    cmd, opts, pos = r
    sim = opts.get("--sim", os.path.join(REPO, "build", "gcc-O2", "tdc-sim"))
    try:
        if cmd == "expand" and len(pos) == 2:
            spec = write_jobs(pos[0], pos[1], sim)
            for j in spec["jobs"]:
                print("%04d tdc-sim %s" % (j["index"], " ".join(shlex.quote(a) for a in j["args"])))
            return EXIT_OK
        if cmd == "run-job" and len(pos) in (1, 2):
            idx = pos[1] if len(pos) == 2 else os.environ.get("SLURM_ARRAY_TASK_ID")
            if idx is None or not idx.isdigit():
                die(EXIT_USAGE, "run-job: no INDEX and no SLURM_ARRAY_TASK_ID")
            return 0 if run_job(pos[0], int(idx)) == 0 else EXIT_JOBS_FAILED
        if cmd == "merge" and len(pos) == 1:
            return merge(pos[0])
        if cmd in ("local", "slurm") and len(pos) == 2:
            if not os.access(sim, os.X_OK):
                die(EXIT_USAGE, "tdc-sim not found at %s (make, or --sim PATH)" % sim)
            spec = write_jobs(pos[0], pos[1], sim, opts.get("--cache"))
            n = len(spec["jobs"])
            if cmd == "local":
                j = opts.get("-j", str(os.cpu_count() or 1))
                if not j.isdigit() or int(j) < 1:
                    die(EXIT_USAGE, "-j '%s': a positive number of parallel jobs" % j)
                engine_local(pos[1], n, int(j))
                return merge(pos[1])
            minutes = opts.get("--time", "10")
            if not minutes.isdigit() or int(minutes) < 1:
                die(EXIT_USAGE, "--time '%s': minutes per task" % minutes)
            engine_slurm(pos[1], n, "--wait" in opts, opts.get("--partition"), int(minutes))
            if "--wait" in opts:
                return merge(pos[1])
            print("tdc-sweep: when the array is done: tdc-sweep merge %s" % pos[1], file=sys.stderr)
            return EXIT_OK
    except SweepError as e:
        die(EXIT_BAD_SWEEP, str(e))
    die(EXIT_USAGE, "bad command line '%s' (see --help)" % " ".join(argv[1:]))


if __name__ == "__main__":
    sys.exit(main(sys.argv))
