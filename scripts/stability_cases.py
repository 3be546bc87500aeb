"""Run one hard case of fsi_app and classify how it ended; shared by the stability suite
(tests/test_stability_suite.py) and the stability map (scripts/stability_map).

A case ends as
  stable     exit 0, no step cut, every monitor finite;
  recovered  exit 0 after step cutting (a failed Newton retried with a smaller step);
  stopped    exit 3, the documented numerical stop, with a checkpoint of the last good state;
  broken     anything else: another exit code, a NaN or inf in monitor.csv, exit 3 without a
             checkpoint, a summary that does not match the exit.
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import time

SRC = os.environ.get("FSI_SOURCE_DIR",
                     os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
APP = os.environ.get("FSI_APP", os.path.join(SRC, "build", "fsi_app"))
sys.path.insert(0, os.path.join(SRC, "tests"))
from fsitest import ENV  # noqa: E402  (the tests' MPI environment, one definition)


def scene_path(name):
    """A scene by name: tests/scenes/<name>.opts or examples/*/<name>.opts."""
    p = os.path.join(SRC, "tests", "scenes", name + ".opts")
    if os.path.exists(p):
        return p
    for d in sorted(os.listdir(os.path.join(SRC, "examples"))):
        p = os.path.join(SRC, "examples", d, name + ".opts")
        if os.path.exists(p):
            return p
    raise FileNotFoundError(f"no scene {name}")


class Case:
    """The outcome of one run: status, iterations, cost, and the monitor table."""

    def __init__(self, name, code, out, outdir, seconds):
        self.name, self.code, self.out, self.dir, self.seconds = name, code, out, outdir, seconds
        self.summary, self.monitor = None, []
        p = os.path.join(outdir, "summary.json")
        if os.path.exists(p):
            self.summary = json.load(open(p))
        for m in ("monitor.csv", "monitor.csv.partial"):
            p = os.path.join(outdir, m)
            if os.path.exists(p):
                with open(p) as f:
                    self.monitor = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
                break
        self.finite = all(math.isfinite(v) for r in self.monitor for v in r.values())
        s = self.summary or {}
        self.cuts = (s.get("step_control") or {}).get("cuts", 0)
        it = s.get("iterations") or {}
        self.newton_mean = it.get("newton_mean_per_step", float("nan"))
        self.newton_max = it.get("newton_max_per_step", 0)
        self.krylov_per_newton = it.get("krylov_mean_per_newton", float("nan"))
        self.steps = s.get("steps", len(self.monitor))
        has_ck = os.path.exists(os.path.join(outdir, "checkpoint.h5"))
        if code == 0 and s.get("converged") is True and self.finite:
            self.status = "recovered" if self.cuts > 0 else "stable"
        elif code == 3 and s.get("converged") is False and has_ck and self.finite:
            self.status = "stopped"
        else:
            self.status = "broken"

    def column(self, name):
        return [r[name] for r in self.monitor if name in r]

    def line(self):
        return (f"{self.name}: {self.status} (exit {self.code}, {self.steps} steps, cuts "
                f"{self.cuts}, Newton {self.newton_mean:.1f}/step max {self.newton_max}, Krylov "
                f"{self.krylov_per_newton:.1f}/Newton, {self.seconds:.1f} s)")


def run_case(name, scene, extra=(), np=2, preset="direct", timeout=1800):
    outdir = tempfile.mkdtemp(prefix="fsi_stab_")
    cmd = ["mpirun", "-n", str(np), APP, "-options_file", scene_path(scene), "-options_file",
           os.path.join(SRC, "petsc_options", preset + ".opts"), "-out_dir", outdir,
           "-mesh_cache_dir", os.path.join(SRC, "build", "mesh_cache"),
           "-checkpoint_every", "0"] + [str(e) for e in extra]
    t0 = time.time()
    p = subprocess.run(cmd, cwd=SRC, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, timeout=timeout)
    c = Case(name, p.returncode, p.stdout, outdir, time.time() - t0)
    print("$", " ".join(cmd))
    print(c.line())
    if c.status == "broken":
        print("\n".join(p.stdout.strip().splitlines()[-5:]))
    return c
