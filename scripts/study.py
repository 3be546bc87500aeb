"""Study mode: what accuracy costs in time.

  scripts/study <scene> --vary mesh=coarse,medium,fine --vary dt=2e-4,1e-4,5e-5
                [--vary preset=direct,fieldsplit_ilu] [--vary rho_inf=1,0.5,0]
                [--qoi COLUMN:max|min|final|mean@T0-T1|valve:NAME|wss:NAME ...] [--curve COLUMN]
                [--metric qoi|curve]
                [--target-error 1e-2] [--np 2] [--out DIR] [--plot-only] [-- app options]

Runs every case of the grid (cases already finished in DIR are reused), then for each case: the
quantities of interest (a monitor column's max/min/final, or its time-weighted mean over
[T0, T1] s; or valve:NAME[@CYCLE], a figure of scripts/valve_report.py --json such as
valve:peak_flow_goa_cm2; or wss:NAME, a leaflet wall-shear figure of the run's last closed
-hemo_window by scripts/valve_wss_sides.py --json, such as wss:ventricular.tawss_pa or
wss:osi_highest_band.osi_mean; --qoi repeated for several, the first one primary), each one's
error against its reference, the difference of the monitor curve from the finest case's, and the cost (wall time, s/step,
iterations).  The reference is the finest case, improved by Richardson extrapolation along each
refinement direction with >= 3 levels at a constant ratio whose observed order is sane (0.5..6;
the script says which it used).  Writes DIR/study.csv, DIR/study.md and DIR/accuracy_cost.png
(error against wall time, log-log, one curve per varied parameter with the others at their finest,
the Pareto front marked, by the primary quantity), prints observed orders along each numeric
parameter, and with --target-error the cheapest case that meets it.  With several quantities,
also accuracy_cost_all.png (one panel per quantity) and a table of every quantity per case.

Scenes declare their mesh levels and default quantity in comment lines of their .opts:
  # study-levels: coarse=0.002 medium=0.0015 fine=0.001     (values of -mesh_h [m])
  # study-qoi: solid_probe0_ux:max            (several: separated by spaces)
Parameters: mesh (a level name or an -mesh_h value), dt (-ts_dt [s]; the end time stays the
scene's), preset (petsc_options/<name>.opts), rho_inf (-ts_alpha_radius), or any app option as
opt:<name> (e.g. opt:ale_geometry_iterations=0,3).
"""
import argparse
import csv
import itertools
import json
import math
import os
import subprocess
import sys

ROOT = os.environ.get("FSI_ROOT", os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
APP = os.environ.get("FSI_APP", os.path.join(ROOT, "build", "fsi_app"))  # a copy keeps a study
# independent of rebuilds


def scene_file(scene):
    for p in (os.path.join(ROOT, "examples", scene, scene + ".opts"),
              os.path.join(ROOT, "tests", "scenes", scene + ".opts"), scene):
        if os.path.isfile(p):
            return p
    sys.exit(f"study: no scene '{scene}' (looked in examples/ and tests/scenes/)")


def scene_meta(path):
    levels, qoi = {}, None
    for line in open(path):
        if line.startswith("# study-levels:"):
            for item in line.split(":", 1)[1].split():
                k, v = item.split("=")
                levels[k] = v
        elif line.startswith("# study-qoi:"):
            qoi = line.split(":", 1)[1].split()
    return levels, qoi


def numeric(param, value, levels):
    """The number behind a parameter value (mesh levels map to h), or None."""
    if param == "mesh":
        value = levels.get(value, value)
    try:
        return float(value)
    except ValueError:
        return None


def finer(param):
    """Direction in which a numeric parameter is 'finer' (smaller h and dt)."""
    return -1 if param in ("mesh", "dt") else None


def case_options(params, levels):
    opts = []
    for p, v in params.items():
        if p == "mesh":
            opts += ["-mesh_h", levels.get(v, v)]
        elif p == "dt":
            opts += ["-ts_dt", v]
        elif p == "preset":
            opts += ["-options_file", os.path.join(ROOT, "petsc_options", v + ".opts")]
        elif p == "rho_inf":
            opts += ["-ts_alpha_radius", v]
        elif p.startswith("opt:"):
            opts += ["-" + p[4:], v]
        else:
            sys.exit(f"study: unknown parameter '{p}' (mesh, dt, preset, rho_inf, opt:<name>)")
    return opts


def case_name(params):
    return "_".join(f"{p.replace('opt:', '')}-{v}" for p, v in params.items())


def run_case(scene, params, levels, args, extra):
    out = os.path.join(args.out, case_name(params))
    cmd = ["mpirun", "-n", str(args.np), APP, "-options_file", scene]
    if "preset" not in params:
        cmd += ["-options_file", os.path.join(ROOT, "petsc_options", args.preset + ".opts")]
    cmd += case_options(params, levels) + list(extra) + ["-out_dir", out]
    stamp = os.path.join(out, "study_command.txt")
    summary = os.path.join(out, "summary.json")
    if os.path.exists(summary) and os.path.exists(stamp) and open(stamp).read() == " ".join(cmd):
        s = json.load(open(summary))
        if s.get("converged"):
            print(f"  {case_name(params)}: reused ({s['wall_time']['total']:.1f} s)")
            return out
    if args.plot_only:
        return out if os.path.exists(summary) else None
    print(f"  {case_name(params)}: running ...", flush=True)
    os.makedirs(out, exist_ok=True)
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    open(os.path.join(out, "study_log.txt"), "w").write(p.stdout)
    if p.returncode != 0:
        print(f"    failed (exit {p.returncode}): {p.stdout.strip().splitlines()[-1]}")
        return None
    open(stamp, "w").write(" ".join(cmd))
    print("    " + p.stdout.strip().splitlines()[-1][:150])
    return out


def window_mean(t, v, t0, t1):
    """Time-weighted (trapezoid) mean of v over [t0, t1], v linear between rows.  Not
    compare_runs.mean (each step's value over its own step): that rule is first order in dt and
    would add its own dt error to a study along dt (measured on Womersley's [0.2, 0.4] s mean:
    1.48e-2 at dt 0.05 against 1.62e-2 with this rule, whose four dt levels agree within 0.5 %)."""
    def at(x):
        for i in range(len(t) - 1):
            if t[i] <= x <= t[i + 1]:
                w = (x - t[i]) / (t[i + 1] - t[i])
                return (1 - w) * v[i] + w * v[i + 1]
        return None
    pts = [(t0, at(t0))] + [(a, b) for a, b in zip(t, v) if t0 < a < t1] + [(t1, at(t1))]
    if pts[0][1] is None or pts[-1][1] is None:
        return None
    area = sum(0.5 * (pts[i][1] + pts[i + 1][1]) * (pts[i + 1][0] - pts[i][0]) for i in range(len(pts) - 1))
    return area / (t1 - t0)


VALVE_FIGURES = {}  # case directory -> valve_report.py's per-cycle figures (one report per case)


def valve_figure(spec, out):
    """valve:NAME[@CYCLE]: a figure of scripts/valve_report.py --json (cycle 1 unless given)."""
    name, _, cycle = spec[len("valve:"):].partition("@")
    if out not in VALVE_FIGURES:
        path = os.path.join(out, "valve_figures.json")
        p = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "scripts", "valve_report.py"), out, "--json", path],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if p.returncode != 0:
            sys.exit(f"study: --qoi {spec}: valve_report.py failed on {out}: {p.stderr.strip()}")
        VALVE_FIGURES[out] = json.load(open(path))["cycles"]
    cycles = VALVE_FIGURES[out]
    c = int(cycle) if cycle.isdigit() else 1
    if not 1 <= c <= len(cycles) or name not in cycles[c - 1]:
        names = ", ".join(k for k in cycles[0] if k not in ("cycle", "complete")) if cycles else ""
        sys.exit(f"study: --qoi {spec}: no figure '{name}' in cycle {c} of {out} (figures: {names})")
    value = cycles[c - 1][name]
    if value is None:
        sys.exit(f"study: --qoi {spec}: the run in {out} does not reach what '{name}' needs "
                 "(e.g. a closure for closing figures): lengthen the window (-ts_max_time)")
    return float(value)


def wss_figure(spec, out):
    """wss:NAME (dotted path): a figure of the case's last closed wall-shear window, by
    scripts/valve_wss_sides.py --json."""
    path = os.path.join(out, "wss_sides.json")
    summary = os.path.join(out, "summary.json")
    if not os.path.exists(path) or os.path.getmtime(path) < os.path.getmtime(summary):  # none, or of an earlier run
        p = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "scripts", "valve_wss_sides.py"), out, "--json", path],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if p.returncode != 0:
            sys.exit(f"study: --qoi {spec}: valve_wss_sides.py failed on {out}: {p.stderr.strip()}")
    windows = [w for w in json.load(open(path))["windows"] if w["source"].startswith("window")]
    if not windows:
        sys.exit(f"study: --qoi {spec}: no closed -hemo_window in {out}: give -hemo_window the window's length")
    value = windows[-1]
    for key in spec[len("wss:"):].split("."):
        if not isinstance(value, dict) or key not in value:
            sys.exit(f"study: --qoi {spec}: no '{key}' in valve_wss_sides.py's figures (e.g. ventricular.tawss_pa, "
                     "aortic.osi_mean, osi_highest_band.osi_mean, tawss_ventricular_over_aortic)")
        value = value[key]
    return float(value)


def qoi_value(spec, rows, out):
    """A quantity of interest from monitor rows: COLUMN:max|min|final|mean@T0-T1, or a valve
    figure (valve:NAME[@CYCLE], named as in valve_report.py --json)."""
    if spec.startswith("valve:"):
        return valve_figure(spec, out)
    if spec.startswith("wss:"):
        return wss_figure(spec, out)
    col, how = (spec.split(":", 1) + ["max"])[:2]
    if col not in rows[0]:
        sys.exit(f"study: monitor column '{col}' not in {out}/monitor.csv")
    vals = [r[col] for r in rows]
    if how.startswith("mean@"):
        try:
            t0, t1 = (float(x) for x in how[5:].split("-"))
        except ValueError:
            sys.exit(f"study: --qoi {spec}: expected COLUMN:mean@T0-T1 (seconds, T0 < T1)")
        q = window_mean([r["time"] for r in rows], vals, t0, t1) if t0 < t1 else None
        if q is None:
            sys.exit(f"study: --qoi {spec}: the run in {out} does not cover [{t0}, {t1}] s")
        return q
    if how not in ("max", "min", "final"):
        sys.exit(f"study: --qoi {spec}: use COLUMN:max, :min, :final or :mean@T0-T1")
    return {"max": max(vals), "min": min(vals), "final": vals[-1]}[how]


def read_case(out, specs, curve_col):
    s = json.load(open(os.path.join(out, "summary.json")))
    rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(os.path.join(out, "monitor.csv")))]
    qois = {spec: qoi_value(spec, rows, out) for spec in specs}
    curve = ([r["time"] for r in rows], [r[curve_col] for r in rows])
    it = s["iterations"]
    return {"qois": qois, "qoi": qois[specs[0]], "curve": curve, "wall": s["wall_time"]["total"],
            "per_step": s["wall_time"]["per_step"], "steps": s["steps"], "cells": s["cells"],
            "dofs": s["dofs"]["total"], "newton": it["newton_mean_per_step"],
            "krylov": it["krylov_total"] / max(it["newton_total"], 1),
            "memory": s["cost"]["peak_memory_mb_per_rank_max"]}


def curve_diff(a, b):
    """L2-in-time difference of curve a from b (b interpolated at a's times), relative to max|b|."""
    ta, va = a
    tb, vb = b
    t_end = min(ta[-1], tb[-1])
    acc, n, j = 0.0, 0, 0
    for t, v in zip(ta, va):
        if t > t_end + 1e-12:
            break
        while j + 1 < len(tb) - 1 and tb[j + 1] < t:
            j += 1
        if t <= tb[0]:
            ref = vb[0] * t / tb[0]  # from the rest state at t = 0
        else:
            w = (t - tb[j]) / (tb[j + 1] - tb[j])
            ref = (1 - w) * vb[j] + w * vb[j + 1]
        acc += (v - ref) ** 2
        n += 1
    scale = max(abs(x) for x in vb) or 1.0
    return math.sqrt(acc / max(n, 1)) / scale


def richardson(values, h):
    """Observed order p and extrapolated value from the three finest levels (coarse -> fine) of
    q = q* + C h^p, for any spacing of h: solves (h1^p - h2^p)/(h2^p - h3^p) = (q1-q2)/(q2-q3)."""
    q1, q2, q3 = values[-3:]
    h1, h2, h3 = h[-3:]
    if q2 == q3 or q1 == q2 or (q1 - q2) * (q2 - q3) <= 0:
        return None, None
    target = (q1 - q2) / (q2 - q3)
    f = lambda p: (h1 ** p - h2 ** p) / (h2 ** p - h3 ** p) - target
    lo, hi = 0.05, 12.0
    if f(lo) * f(hi) > 0:
        return None, None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(lo) * f(mid) > 0 else (lo, mid)
    p = 0.5 * (lo + hi)
    if not 0.5 <= p <= 6:
        return p, None
    C = (q2 - q3) / (h2 ** p - h3 ** p)
    return p, q3 - C * h3 ** p


def level_values(p, line, grid, levels):
    """Numeric size of each level along p: the effective mesh size (cells)^(-1/3) for meshes
    (unstructured levels are not exactly the nominal -mesh_h ratio), else the parameter value."""
    if p == "mesh":
        return [c["cells"] ** (-1.0 / 3) if c else None for c in line]
    return [numeric(p, v, levels) for v in grid[p]]


def main():
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        k = argv.index("--")
        argv, extra = argv[:k], argv[k + 1:]
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("--vary", action="append", default=[], metavar="PARAM=V1,V2,...")
    ap.add_argument("--qoi", action="append", help="COLUMN:max|min|final|mean@T0-T1 (repeatable)")
    ap.add_argument("--curve", help="monitor column compared over time (default: the qoi's)")
    ap.add_argument("--metric", choices=("qoi", "curve"), default="qoi")
    ap.add_argument("--target-error", type=float)
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--preset", default="direct", help="solver preset when not varied")
    ap.add_argument("--out")
    ap.add_argument("--plot-only", action="store_true", help="use finished cases only")
    args = ap.parse_args(argv)
    scene = scene_file(args.scene)
    levels, qoi = scene_meta(scene)
    args.qoi = args.qoi or qoi
    if not args.qoi:
        sys.exit("study: give --qoi COLUMN:max|min|final (or a '# study-qoi:' line in the scene)")
    specs = args.qoi
    args.qoi = specs[0]  # the primary quantity: the Pareto front's and the curve's
    curve_col = args.curve or ("valve_goa" if args.qoi.startswith(("valve:", "wss:")) else args.qoi.split(":")[0])
    args.out = args.out or os.path.join(ROOT, "results", "study", os.path.basename(scene)[:-5])
    os.makedirs(args.out, exist_ok=True)
    grid = {}
    for v in args.vary:
        if "=" not in v:
            sys.exit(f"study: --vary {v}: expected PARAM=V1,V2,...")
        p, vals = v.split("=", 1)
        grid[p] = vals.split(",")
    if not grid:
        sys.exit("study: nothing to vary (--vary mesh=coarse,medium,fine --vary dt=...)")
    if not os.path.exists(APP):
        sys.exit(f"study: {APP} not built (run scripts/setup)")
    # Order numeric levels coarse -> fine.
    for p in grid:
        nums = [numeric(p, v, levels) for v in grid[p]]
        if finer(p) and all(x is not None for x in nums):
            grid[p] = [v for _, v in sorted(zip(nums, grid[p]), reverse=True)]
    names = list(grid)
    print(f"study of {os.path.relpath(scene, ROOT)}: {' x '.join(f'{p} {grid[p]}' for p in names)}, "
          f"{args.np} ranks -> {os.path.relpath(args.out, ROOT)}")
    cases = []
    for combo in itertools.product(*(grid[p] for p in names)):
        params = dict(zip(names, combo))
        out = run_case(scene, params, levels, args, extra)
        if out:
            c = read_case(out, specs, curve_col)
            c["params"] = params
            cases.append(c)
    if not cases:
        sys.exit("study: no case finished")

    # Reference: the finest case (last level of every refinement parameter, first of the others),
    # improved by Richardson extrapolation along each refinement direction.
    finest = {p: grid[p][-1] if finer(p) else grid[p][0] for p in names}
    by = {tuple(c["params"][p] for p in names): c for c in cases}
    key = lambda params: tuple(params[p] for p in names)
    ref_case = by.get(key(finest))
    if ref_case is None:
        sys.exit("study: the finest case did not finish; no reference")
    # Where a refinement direction gives no extrapolation, the finest level's own error is not
    # known: its last difference (finest against second finest) is added to every case's error
    # as an estimate (a floor), and said.  The curve metric has no extrapolation: its floor is
    # the last curve difference along every refinement direction.
    def reference(spec):
        """The spec's reference value, the notes on how it was found, and the finest case's
        estimated relative error where no extrapolation was possible."""
        q_ref, notes, floor_q = ref_case["qois"][spec], [], 0.0
        for p in names:
            if not finer(p) or len(grid[p]) < 2:
                continue
            line = [by.get(key({**finest, p: v})) for v in grid[p]]
            ext = None
            if len(grid[p]) >= 3 and None not in line[-3:]:
                order, ext = richardson([c["qois"][spec] for c in line], level_values(p, line, grid, levels))
                why = "non-monotone" if order is None else f"observed order {order:.2f} not in 0.5..6"
            else:
                why = "fewer than 3 levels"
            if ext is not None:
                q_ref += ext - ref_case["qois"][spec]  # additive error model e = C_h h^p + C_t dt^q
                notes.append(f"{p}: Richardson with observed order {order:.2f}, correction "
                             f"{ext - ref_case['qois'][spec]:+.4e}")
            elif line[-2] is not None:
                f = abs(line[-1]["qois"][spec] - line[-2]["qois"][spec])
                floor_q += f
                notes.append(f"{p}: no Richardson ({why}); the finest level's error is estimated by its "
                             f"last difference {f:.3e} ({f / max(abs(ref_case['qois'][spec]), 1e-300):.2e} "
                             "relative), added to every case")
        return q_ref, notes, floor_q / max(abs(q_ref), 1e-300)

    floor_c = 0.0
    for p in names:
        if finer(p) and len(grid[p]) >= 2:
            line = [by.get(key({**finest, p: v})) for v in grid[p]]
            if line[-2] is not None:
                floor_c += curve_diff(line[-2]["curve"], line[-1]["curve"])
    refs = {spec: reference(spec) for spec in specs}
    for c in cases:
        c["errs"] = {spec: abs(c["qois"][spec] - r) / max(abs(r), 1e-300) + fl
                     for spec, (r, _, fl) in refs.items()}
    q_ref, notes, floor_q = refs[args.qoi]
    ref_text = (f"reference {args.qoi} = {q_ref:.6e} (finest case {case_name(finest)} "
                f"{ref_case['qoi']:.6e}; " + ("; ".join(notes) if notes else "no extrapolation") + ")")
    print(ref_text)
    for c in cases:
        c["err_qoi"] = c["errs"][args.qoi]
        c["err_curve"] = curve_diff(c["curve"], ref_case["curve"]) + floor_c
        c["error"] = c["err_qoi"] if args.metric == "qoi" else c["err_curve"]
    if floor_c > 0:
        ref_text += (f". Curve errors include the estimated error of the finest case, {floor_c:.2e} "
                     "(the last curve difference along each refinement direction)")

    # Pareto front in (wall time, error).
    front, best = set(), float("inf")
    for c in sorted(cases, key=lambda c: (c["wall"], c["error"])):
        if c["error"] < best:
            best = c["error"]
            front.add(id(c))

    # Observed orders along each numeric parameter, for every setting of the others.
    order_lines = []
    for p in names:
        if None in [numeric(p, v, levels) for v in grid[p]] or len(grid[p]) < 3:
            continue
        others = [o for o in names if o != p]
        for combo in itertools.product(*(grid[o] for o in others)):
            fixed = dict(zip(others, combo))
            line = [by.get(key({**fixed, p: v})) for v in grid[p]]
            if None in line:
                continue
            nums = level_values(p, line, grid, levels)
            dq = [abs(line[i]["qoi"] - line[i + 1]["qoi"]) for i in range(len(line) - 1)]
            dc = [curve_diff(line[i]["curve"], line[i + 1]["curve"]) for i in range(len(line) - 1)]
            oq, oc = [], []
            for i in range(len(dq) - 1):
                r = math.log(nums[i + 1] / nums[i + 2]) if nums[i + 2] else None
                oq.append(math.log(dq[i] / dq[i + 1]) / r if r and dq[i] > 0 and dq[i + 1] > 0 else float("nan"))
                oc.append(math.log(dc[i] / dc[i + 1]) / r if r and dc[i] > 0 and dc[i + 1] > 0 else float("nan"))
            tag = ", ".join(f"{o}={fixed[o]}" for o in others) or "-"
            order_lines.append((p, tag, dq, oq, dc, oc))

    # Outputs.
    cols = names + ["cells", "dofs", "steps", "wall_s", "s_per_step", "newton_per_step",
                    "krylov_per_newton", "memory_mb", "qoi", "err_qoi", "err_curve", "pareto"]
    cols += [f"{k}[{spec}]" for spec in specs[1:] for k in ("qoi", "err")]
    with open(os.path.join(args.out, "study.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for c in cases:
            w.writerow([c["params"][p] for p in names] + [
                c["cells"], c["dofs"], c["steps"], f"{c['wall']:.3f}", f"{c['per_step']:.4f}",
                f"{c['newton']:.3f}", f"{c['krylov']:.2f}", f"{c['memory']:.0f}", f"{c['qoi']:.9e}",
                f"{c['err_qoi']:.4e}", f"{c['err_curve']:.4e}", int(id(c) in front)] +
                [f"{x:.9e}" for spec in specs[1:] for x in (c["qois"][spec], c["errs"][spec])])
    md = [f"# Study: {os.path.basename(scene)[:-5]}", "",
          f"Quantity of interest `{args.qoi}`; curve `{curve_col}` (L2 in time against the finest "
          f"case, relative to its peak); error metric for the Pareto front: **{args.metric}**.", "",
          ref_text + ".", "",
          "| " + " | ".join(names) + " | cells | dofs | steps | wall [s] | s/step | Newton/step | "
          "Krylov/Newton | MB/rank | QoI | QoI error est. | curve error est. | Pareto |",
          "|" + "---|" * (len(names) + 12)]
    for c in sorted(cases, key=lambda c: c["wall"]):
        md.append("| " + " | ".join(c["params"][p] for p in names) +
                  f" | {c['cells']} | {c['dofs']} | {c['steps']} | {c['wall']:.1f} | {c['per_step']:.3f} | "
                  f"{c['newton']:.2f} | {c['krylov']:.1f} | {c['memory']:.0f} | {c['qoi']:.5e} | "
                  f"{c['err_qoi']:.2e} | {c['err_curve']:.2e} | {'**yes**' if id(c) in front else ''} |")
    if len(specs) > 1:
        md += ["", "Every quantity (value, estimated relative error):", ""]
        for spec in specs:
            r, n, _ = refs[spec]
            md.append(f"- `{spec}`: reference {r:.6e} ({'; '.join(n) if n else 'no extrapolation'})")
        md += ["", "| case | wall [s] | " + " | ".join(f"`{x}`" for x in specs) + " |",
               "|---|---|" + "---|" * len(specs)]
        for c in sorted(cases, key=lambda c: c["wall"]):
            md.append(f"| {case_name(c['params'])} | {c['wall']:.1f} | " +
                      " | ".join(f"{c['qois'][x]:.4g} ({c['errs'][x]:.1e})" for x in specs) + " |")
    if order_lines:
        md += ["", "Observed orders (successive differences: QoI, curve):", "",
               "| along | others | QoI differences | QoI orders | curve differences | curve orders |",
               "|---|---|---|---|---|---|"]
        for p, tag, dq, oq, dc, oc in order_lines:
            md.append(f"| {p} | {tag} | {', '.join(f'{x:.2e}' for x in dq)} | "
                      f"{', '.join(f'{x:.2f}' for x in oq)} | {', '.join(f'{x:.2e}' for x in dc)} | "
                      f"{', '.join(f'{x:.2f}' for x in oc)} |")
    choice = None
    if args.target_error:
        ok = [c for c in cases if c["error"] <= args.target_error]
        if ok:
            choice = min(ok, key=lambda c: c["wall"])
            text = (f"cheapest setting with {args.metric} error <= {args.target_error:g}: "
                    f"{case_name(choice['params'])} ({choice['error']:.2e} in {choice['wall']:.1f} s)")
        else:
            text = f"no case meets {args.metric} error <= {args.target_error:g}"
        md += ["", text]
        print(text)
    open(os.path.join(args.out, "study.md"), "w").write("\n".join(md) + "\n")
    print("\n".join(md[6:]))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 5))
    for c in cases:
        if c["error"] > 0:
            ax.loglog(c["wall"], c["error"], "o", color="0.6", ms=5, zorder=2)
    for p in names:  # one curve per varied parameter, the others at their finest
        line = [by.get(key({**finest, p: v})) for v in grid[p]]
        line = [c for c in line if c and c["error"] > 0]
        if len(line) >= 2:
            ax.loglog([c["wall"] for c in line], [c["error"] for c in line], "-o", ms=6, zorder=3,
                      label=f"{p}: {', '.join(c['params'][p] for c in line)}")
    pf = sorted((c for c in cases if id(c) in front and c["error"] > 0), key=lambda c: c["wall"])
    if pf:
        ax.loglog([c["wall"] for c in pf], [c["error"] for c in pf], "k--", lw=1, zorder=4)
        ax.loglog([c["wall"] for c in pf], [c["error"] for c in pf], "s", mfc="none", mec="k",
                  ms=11, zorder=4, label="Pareto front")
        for c in pf:
            ax.annotate(case_name(c["params"]), (c["wall"], c["error"]), fontsize=6,
                        xytext=(4, 4), textcoords="offset points")
    if choice:
        ax.axhline(args.target_error, color="r", lw=0.8, ls=":", label=f"target {args.target_error:g}")
    ax.set_xlabel(f"wall time [s] ({args.np} ranks)")
    ax.set_ylabel(f"relative error ({args.metric}: {args.qoi if args.metric == 'qoi' else curve_col})")
    ax.set_title(f"{os.path.basename(scene)[:-5]}: accuracy against cost")
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "accuracy_cost.png"), dpi=130)
    if len(specs) > 1:
        n = len(specs)
        cols_ = min(n, 3)
        fig, axes = plt.subplots((n + cols_ - 1) // cols_, cols_, figsize=(4.2 * cols_, 3.4 * ((n + cols_ - 1) // cols_)),
                                 squeeze=False)
        for ax, spec in zip(axes.flat, specs):
            for p in names:
                line = [by.get(key({**finest, p: v})) for v in grid[p]]
                line = [c for c in line if c and c["errs"][spec] > 0]
                if line:
                    ax.loglog([c["wall"] for c in line], [c["errs"][spec] for c in line], "-o", ms=4,
                              label=f"{p}: {', '.join(c['params'][p] for c in line)}")
            ax.set_title(spec, fontsize=8)
            ax.set_xlabel(f"wall time [s] ({args.np} ranks)", fontsize=7)
            ax.set_ylabel("relative error (est.)", fontsize=7)
            ax.grid(True, which="both", lw=0.3)
            ax.legend(fontsize=6)
        for ax in list(axes.flat)[n:]:
            ax.axis("off")
        fig.tight_layout()
        fig.savefig(os.path.join(args.out, "accuracy_cost_all.png"), dpi=120)
    print(f"wrote {os.path.relpath(args.out, ROOT)}/study.csv, study.md, accuracy_cost.png"
          + (", accuracy_cost_all.png" if len(specs) > 1 else ""))


if __name__ == "__main__":
    main()
