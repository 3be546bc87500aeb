"""Study mode end to end (issue 6) on a cheap scene: Womersley over one period, dt = 0.05, 0.025,
0.0125, 0.00625 s on 1 rank.  The script runs the four cases, finds a Richardson reference along
dt, reports the observed order of the centre-line velocity curve (~2: generalized-alpha is second
order; the peak of a sampled curve is not a clean order measure, so the curve's is checked),
writes study.csv, study.md and accuracy_cost.png, and --target-error picks the cheapest case
that meets it.  A second quantity (the centre-line velocity's mean over [0.2, 0.4] s, issue 55's
window means) gets its own columns, each case's value equal to the trapezoid mean of its
monitor.csv, and its own panel.  The mesh is coarser than the scene's (9 855 dofs against 28 369: the order along dt
does not need the fine mesh; measured curve orders 1.97, 1.91, against 1.72 at 5 231 dofs)."""
import csv
import os
import subprocess
import tempfile
from fsitest import ENV, SRC, APP, check, finish

out = tempfile.mkdtemp(prefix="fsi_study_")
MEAN = "probe0_vz:mean@0.2-0.4"
cmd = ["/usr/bin/python3", os.path.join(SRC, "scripts", "study.py"), "womersley", "--vary",
       "dt=0.05,0.025,0.0125,0.00625", "--qoi", "probe0_vz:max", "--qoi", MEAN, "--np", "1", "--out", out,
       "--target-error", "1e-3", "--", "-mesh_cache_dir", os.path.join(SRC, "build", "mesh_cache"),
       "-mesh_params", "R=0.005,L=0.01,ncirc=24", "-mesh_h", "0.0025"]
p = subprocess.run(cmd, cwd=SRC, env=dict(ENV, FSI_APP=APP), stdout=subprocess.PIPE,
                   stderr=subprocess.STDOUT, text=True, timeout=900)
print(p.stdout)
check(p.returncode == 0, "study runs")
for f in ("study.csv", "study.md", "accuracy_cost.png", "accuracy_cost_all.png"):
    check(os.path.exists(os.path.join(out, f)), f"{f} written")
rows = list(csv.DictReader(open(os.path.join(out, "study.csv")))) if p.returncode == 0 else []
check(len(rows) == 4, f"4 cases in study.csv ({len(rows)})")
check("Richardson with observed order" in p.stdout, "Richardson reference along dt")
order = None
for line in p.stdout.splitlines():
    if line.startswith("| dt | - |"):  # the orders table: along dt, no other parameter
        order = [float(x) for x in line.split("|")[6].split(",")]
print("observed dt orders of the centre-line velocity curve:", order)
check(order is not None and all(1.7 < o < 2.3 for o in order), f"dt order ~2 ({order})")
errs = [float(r["err_curve"]) for r in rows]
check(all(errs[i] > errs[i + 1] for i in range(len(errs) - 1)), f"curve error falls with dt ({errs})")
check("cheapest setting" in p.stdout, "--target-error picks a case")
# The window mean, recomputed from each case's own monitor (its rows land on 0.2 and 0.4 s).
for r in rows:
    m = list(csv.DictReader(open(os.path.join(out, f"dt-{r['dt']}", "monitor.csv"))))
    pts = [(float(x["time"]), float(x["probe0_vz"])) for x in m if 0.2 - 1e-9 <= float(x["time"]) <= 0.4 + 1e-9]
    mean = sum(0.5 * (a[1] + b[1]) * (b[0] - a[0]) for a, b in zip(pts, pts[1:])) / 0.2
    got = float(r[f"qoi[{MEAN}]"])
    check(abs(got - mean) <= 1e-9 * abs(mean), f"dt {r['dt']}: window mean {got:.6e} = {mean:.6e} from monitor.csv")
finish()
