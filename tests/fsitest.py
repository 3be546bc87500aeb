"""Helpers for fsi_app tests: run the app (under mpirun on several ranks), read its outputs,
assert with messages."""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import time

APP = os.environ.get("FSI_APP", "")
SRC = os.environ.get("FSI_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# odls_base_sigkill_timeout=0: when a rank exits non-zero (every bad-input case), mpirun would
# wait 1 s between SIGTERM and SIGKILL of the job, twice: 2.7 s instead of 0.8 s per failing run.
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1", OPENBLAS_NUM_THREADS="1",
           OMPI_MCA_odls_base_sigkill_timeout="0")
FAILURES = []


def scene(name):
    return os.path.join(SRC, "tests", "scenes", name + ".opts")


def preset(name):
    return os.path.join(SRC, "petsc_options", name + ".opts")


class Run:
    def __init__(self, code, out, outdir):
        self.code, self.out, self.dir = code, out, outdir

    @property
    def summary(self):
        with open(os.path.join(self.dir, "summary.json")) as f:
            return json.load(f)

    @property
    def monitor(self):
        with open(os.path.join(self.dir, "monitor.csv")) as f:
            return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def run(opts, np=1, extra=(), presets=("direct",), timeout=900):
    """Run fsi_app with scene file(s) `opts` on `np` ranks; returns Run."""
    outdir = tempfile.mkdtemp(prefix="fsi_test_")
    # One rank starts without mpirun (MPI's singleton start): 0.25 s instead of 0.6 s per run, and
    # the option fuzz and bad-input tests start a few hundred.
    cmd = [APP] if np == 1 else ["mpirun", "-n", str(np), APP]
    for o in ([opts] if isinstance(opts, str) else opts):
        cmd += ["-options_file", o]
    for p in presets:
        cmd += ["-options_file", preset(p)]
    cmd += ["-out_dir", outdir, "-mesh_cache_dir", os.path.join(SRC, "build", "mesh_cache")]
    cmd += list(extra)
    t0 = time.time()
    p = subprocess.run(cmd, cwd=SRC, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, timeout=timeout)
    print(f"$ ({time.time() - t0:.1f} s)", " ".join(cmd))
    tail = "\n".join(p.stdout.strip().splitlines()[-3:])
    print(tail)
    return Run(p.returncode, p.stdout, outdir)


def krylov_per_newton(r):
    it = r.summary["iterations"]
    return it["krylov_total"] / it["newton_total"]


def krylov_growth(opts, presets, hs, extra, np=2):
    """Run each preset on the meshes hs = (coarse, fine) with the same options; returns the Krylov
    iterations per Newton step k[preset, h], the growth g[preset] = fine / coarse and the runs."""
    k, g, runs = {}, {}, {}
    for p in presets:
        for h in hs:
            r = runs[p, h] = run(opts, np=np, extra=list(extra) + ["-mesh_h", h], presets=(p,))
            check(r.code == 0, f"{p} h {h} converges")
            k[p, h] = krylov_per_newton(r) if r.code == 0 else float("nan")
        g[p] = k[p, hs[1]] / k[p, hs[0]]
        print(f"Krylov/Newton {p}: {k[p, hs[0]]:.1f} -> {k[p, hs[1]]:.1f} (x{g[p]:.2f})")
    return k, g, runs


def check(cond, msg):
    print(("PASS: " if cond else "FAIL: ") + msg)
    if not cond:
        FAILURES.append(msg)


def order(e_coarse, e_fine, h_coarse, h_fine):
    return math.log(e_coarse / e_fine) / math.log(h_coarse / h_fine)


def fit_order(hs, es):
    """Least-squares slope of log e against log h."""
    xs, ys = [math.log(h) for h in hs], [math.log(e) for e in es]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def finish():
    n = len(FAILURES)
    print(f"{'all checks passed' if n == 0 else str(n) + ' check(s) failed'}")
    sys.exit(1 if n else 0)
