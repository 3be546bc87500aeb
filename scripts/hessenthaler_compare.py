#!/usr/bin/env python3
"""Compare a Hessenthaler Phase I run with the MRI data and the published computations.

  scripts/hessenthaler_compare.py RUN_DIR [RUN_DIR...] [--png FILE] [--ref CSV]

For each run (examples/hessenthaler/hessenthaler.opts' output): the flap's deformed centreline from
its solid probes (reference points from the run's options.txt, deformed = reference + the last
row's displacement, with the clamp point (0, 0)), interpolated by local cubics at the MRI
points' heights z; the tip height (the last probe); the RMS and largest difference in y to the
59 MRI centreline points; how still the tip is over the last 0.5 s; the jets' speed at the
fluid probes and the largest nodal speed in the MRI's velocity slabs (z = 10 and 30 mm, 6 mm
thick) of the last field file; cost from summary.json.  Prints a markdown table and draws the centrelines
(MRI points, ours, the published tips) into --png (default: the first run's folder).
"""
import argparse
import csv
import json
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REF = os.path.join(ROOT, "examples", "hessenthaler", "phaseI_centreline.csv")  # MRI, CC0
MRI_TIP = 16.41  # [mm] measured tip height under flow
PUBLISHED = [  # (label, tip y [mm], centreline RMS [mm] or None): reference/hessenthaler/README.md
    ("solids4foam 0.23 M cells", 16.55, 0.25),
    ("solids4foam 0.81 M cells", 16.45, 0.20),
    ("CHeart inf-sup stable", 16.9, None),
    ("CHeart cG1cG1", 15.6, None),
    ("Lozovskiy et al. 2019", 13.9, None),
]


def fail(msg):
    print("hessenthaler_compare: " + msg, file=sys.stderr)
    sys.exit(2)


def read_mri(path):
    if not os.path.isfile(path):
        fail("no reference file %s: give its path with --ref (phaseI_centreline.csv of the data set)" % path)
    pts = []
    with open(path) as f:
        for row in csv.DictReader(line for line in f if not line.startswith("#")):
            pts.append((float(row["y_mm"]), float(row["z_mm"])))
    if len(pts) < 4:
        fail("%s holds %d centreline points; expected the 59 MRI points (columns x_mm,y_mm,z_mm)" % (path, len(pts)))
    return pts


def option(run, name):
    """The value of -name in the run's options.txt (the last one given), or None."""
    path = os.path.join(run, "options.txt")
    if not os.path.isfile(path):
        fail("%s has no options.txt: is it an fsi_app output folder?" % run)
    val = None
    for line in open(path):
        parts = line.split()
        if len(parts) >= 2 and parts[0] == "-" + name:
            val = parts[1]
    return val


def read_run(run):
    mon = os.path.join(run, "monitor.csv")
    if not os.path.isfile(mon):
        fail("%s has no monitor.csv: run examples/hessenthaler/hessenthaler.opts into it first" % run)
    with open(mon) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        fail(mon + " has no rows")
    spec = option(run, "solid_probe_points")
    if not spec:
        fail("%s was run without -solid_probe_points: the centreline comes from them" % run)
    ref = [tuple(float(c) for c in p.split(",")) for p in spec.split(";") if p]
    last = rows[-1]
    line = [(0.0, 0.0)]  # the clamped base
    for k, (x, y, z) in enumerate(ref):
        line.append(((y + float(last["solid_probe%d_uy" % k])) * 1e3, (z + float(last["solid_probe%d_uz" % k])) * 1e3))
    t_end = float(last["time"])
    tip_col = "solid_probe%d_uy" % (len(ref) - 1)
    earlier = [r for r in rows if float(r["time"]) <= t_end - 0.5]
    drift = (float(last[tip_col]) - float(earlier[-1][tip_col])) * 1e3 if earlier else float("nan")
    jets = []
    k = 0
    while "probe%d_vx" % k in last:
        v = [float(last["probe%d_v%s" % (k, c)]) for c in "xyz"]
        jets.append(sum(c * c for c in v) ** 0.5)
        k += 1
    summary = {}
    if os.path.isfile(os.path.join(run, "summary.json")):
        summary = json.load(open(os.path.join(run, "summary.json")))
    history = [(float(r["time"]), float(r[tip_col]) * 1e3) for r in rows]
    return line, t_end, drift, jets, summary, history


def slab_peaks(run, planes=(0.010, 0.030), half=0.003):
    """The largest nodal speed within +-half of each plane z (deformed positions) in the run's
    newest field file (fields.h5 or the newest remeshN_fields.h5); None without h5py or fields."""
    try:
        import glob
        import h5py
        import numpy as np
    except ImportError:
        return None
    best, best_step = None, -1
    for path in glob.glob(os.path.join(run, "*fields.h5")):
        with h5py.File(path, "r") as f:
            steps = [int(k.rsplit("_", 1)[1]) for k in f.get("fields", {}) if k.startswith("velocity_")]
            if steps and max(steps) > best_step:
                best, best_step = path, max(steps)
    if best is None:
        return None
    with h5py.File(best, "r") as f:
        tag = "%06d" % best_step
        x = f["geometry/nodes"][:] + f["fields/mesh_displacement_" + tag][:]
        speed = np.linalg.norm(f["fields/velocity_" + tag][:], axis=1)
    slabs = [speed[np.abs(x[:, 2] - z) <= half] for z in planes]
    return [float(v.max()) for v in slabs] if all(v.size for v in slabs) else None


def interp(line, z):
    """y at height z on the polyline's local cubic (the four points nearest in z)."""
    pts = sorted(line, key=lambda p: abs(p[1] - z))[:4]
    y = 0.0
    for i, (yi, zi) in enumerate(pts):
        w = 1.0
        for j, (_, zj) in enumerate(pts):
            if j != i:
                w *= (z - zj) / (zi - zj)
        y += w * yi
    return y


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--ref", default=REF, help="the MRI centreline CSV")
    ap.add_argument("--png", help="the centreline picture (default RUN/centreline.png)")
    ap.add_argument("--labels", help="the runs' names in the picture, comma-separated (default: folders)")
    a = ap.parse_args()
    labels = a.labels.split(",") if a.labels else [os.path.basename(os.path.normpath(r)) for r in a.runs]
    if len(labels) != len(a.runs):
        fail("--labels gives %d names for %d runs" % (len(labels), len(a.runs)))
    mri = read_mri(a.ref)
    print("| run | t end [s] | tip y [mm] (MRI %.2f) | centreline RMS / max diff [mm] | tip drift, last 0.5 s [mm] | jets' speed at probes [m/s] | largest speed, z = 10 / 30 mm slabs [m/s] (MRI ~0.72) | cells | wall [h], ranks | peak MB/rank |" % MRI_TIP)
    print("|---|---|---|---|---|---|---|---|---|---|")
    lines = []
    for run in a.runs:
        line, t_end, drift, jets, s, history = read_run(run)
        zmax = max(z for _, z in line)
        diffs = [interp(line, z) - y for y, z in mri if z <= zmax + 1e-9]
        rms = (sum(d * d for d in diffs) / len(diffs)) ** 0.5
        worst = max(abs(d) for d in diffs)
        tip = line[-1][0]
        wall = s.get("wall_time", {}).get("total", float("nan")) / 3600
        mem = s.get("cost", {}).get("peak_memory_mb_per_rank_max", float("nan"))
        peaks = slab_peaks(run)
        print("| %s | %.2f | %.2f | %.2f / %.2f (%d points) | %+.3f | %s | %s | %s | %.2f, %s | %.0f |" % (
            os.path.basename(os.path.normpath(run)), t_end, tip, rms, worst, len(diffs), drift,
            " ".join("%.3f" % v for v in jets), " / ".join("%.3f" % v for v in peaks) if peaks else "-",
            s.get("cells", "?"), wall, s.get("ranks", "?"), mem))
        lines.append((run, line, history))
    print("\nPublished: " + "; ".join("%s tip %.2f mm%s" % (n, t, ", RMS %.2f mm" % r if r else "") for n, t, r in PUBLISHED))
    png = a.png or os.path.join(a.runs[0], "centreline.png")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("(no matplotlib: no picture)")
        return
    fig, (ax, axt) = plt.subplots(1, 2, figsize=(10, 4.2), gridspec_kw={"width_ratios": [3, 2]})
    ax.plot([z for _, z in mri], [y for y, _ in mri], "k.", label="MRI (59 points)")
    for (run, line, history), label in zip(lines, labels):
        zs = sorted(z for _, z in line)
        fine = [zs[0] + (zs[-1] - zs[0]) * i / 200 for i in range(201)]
        ax.plot(fine, [interp(line, z) for z in fine], "-", label="fsi_app " + label)
        axt.plot([t for t, _ in history], [y for _, y in history], "-", label="fsi_app " + label)
    axt.axhline(MRI_TIP, color="k", ls="--", lw=0.8, label="MRI")
    axt.set_xlabel("t [s]")
    axt.set_ylabel("tip y [mm]")
    axt.set_title("the tip settling (inflow ramped over 0.5 s)")
    axt.grid(alpha=0.3)
    axt.legend(fontsize=7)
    zt = max(z for _, z in mri)
    for i, (n, t, _) in enumerate(PUBLISHED):
        ax.plot([zt], [t], "x^sDv"[i], label=n, ls="none")
    ax.set_xlabel("z [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title("Hessenthaler Phase I: the flap's centreline under flow")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    print("picture: " + os.path.relpath(png, os.getcwd()))


if __name__ == "__main__":
    main()
