"""Compare a run's monitor against a reference run over their common time window.

  /usr/bin/python3 scripts/compare_runs.py REF_DIR RUN_DIR [--columns c1,c2] [--bound PERCENT]
                                           [--scale-from DIR,DIR...] [--window T0,T1]
                                           [--shift S] [--means]

For each column: the largest (and when) and the RMS difference |run - ref| at the run's times (the reference
interpolated linearly), as a percentage of the reference's largest |value| in the window, and the
same at the window's end.  --scale-from takes the scale instead from the largest |value| over
other runs' whole monitors (e.g. the cycle's pieces: diastole's differences against systole's
peaks).  Prints both runs' cost in the window (steps, wall seconds, Newton).
With --bound, exits 1 when a column's largest difference passes the bound: the check that an
adaptive-step run stays within a stated tolerance of a fixed small-step one (docs/valve.md).
--shift S moves the run's times by -S (a later cycle against the first: --shift 1.1); --means
also prints both runs' time-weighted means of each column over the window."""
import argparse
import math
import sys

from run_pieces import read_rows

DEFAULT = "valve_goa_ratio,valve_dp,valve_leaflet_umax,solid_probe0_uz,inlet_p,probe0_vz,energy_kinetic"


def load(d):
    rows = read_rows(d)
    if not rows:
        sys.exit(f"compare_runs: no rows in {d}/monitor.csv")
    return rows


def interp(rows, c, t):
    lo, hi = 0, len(rows) - 1
    t = min(max(t, rows[lo]["time"]), rows[hi]["time"])  # round-off at the window's ends
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if rows[mid]["time"] <= t:
            lo = mid
        else:
            hi = mid
    a, b = rows[lo], rows[hi]
    w = 0.0 if b["time"] == a["time"] else (t - a["time"]) / (b["time"] - a["time"])
    return (1 - w) * a[c] + w * b[c]


def mean(rows, c, t0, t1):
    """Time-weighted mean of column c over (t0, t1]: each step's value over its own step."""
    s = w = 0.0
    for r in rows:
        a, b = max(r["time"] - r["dt"], t0), min(r["time"], t1)
        if b > a:
            s += (b - a) * r[c]
            w += b - a
    return s / w if w else float("nan")


def cost(rows):
    return len(rows), sum(r["step_seconds"] for r in rows), sum(r["newton"] for r in rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("ref")
    ap.add_argument("run")
    ap.add_argument("--columns", default=DEFAULT)
    ap.add_argument("--bound", type=float, help="largest difference allowed, %% of max |ref|")
    ap.add_argument("--scale-from", help="runs whose whole monitors give each column's scale")
    ap.add_argument("--window", help="T0,T1 [s]: compare only inside this window")
    ap.add_argument("--shift", type=float, default=0.0, help="S [s]: the run's times minus S")
    ap.add_argument("--means", action="store_true", help="time-weighted means in the window")
    a = ap.parse_args()
    ref, run = load(a.ref), load(a.run)
    for r in run:
        r["time"] -= a.shift
    t0 = max(ref[0]["time"] - ref[0]["dt"], run[0]["time"] - run[0]["dt"])
    t1 = min(ref[-1]["time"], run[-1]["time"])
    if a.window:
        try:
            w0, w1 = (float(x) for x in a.window.split(","))
        except ValueError:
            sys.exit(f"compare_runs: --window '{a.window}': give two times in seconds, T0,T1")
        t0, t1 = max(t0, w0), min(t1, w1)
    if t1 <= t0:
        sys.exit(f"compare_runs: the runs share no time window ({a.ref}, {a.run})")
    inside = lambda rows: [r for r in rows if t0 + 1e-12 < r["time"] <= t1 + 1e-12]
    refw, runw = inside(ref), inside(run)
    scaled = [r for x in a.scale_from.split(",") for r in load(x)] if a.scale_from else refw
    print(f"window {t0 * 1e3:.2f} - {t1 * 1e3:.2f} ms; scale: max |value| over "
          f"{a.scale_from if a.scale_from else 'the reference in the window'}")
    for name, rows in (("reference", refw), ("run", runw)):
        n, s, nw = cost(rows)
        dts = [r["dt"] for r in rows]
        print(f"  {name:9s} {n:6d} steps  {s:8.0f} s  Newton {nw:6.0f}  dt {min(dts) * 1e3:.3g} - {max(dts) * 1e3:.3g} ms")
    worst = 0.0
    print(f"  {'column':22s} {'scale':>10s} {'max diff %':>10s} {'rms diff %':>10s} {'end diff %':>10s} {'at ms':>8s}"
          + (f" {'ref mean':>11s} {'run mean':>11s}" if a.means else ""))
    for c in a.columns.split(","):
        if c not in run[0] or c not in ref[0]:
            print(f"  {c:22s} (not in both monitors)")
            continue
        scale = max(abs(r[c]) for r in scaled if c in r) or 1.0
        d = [abs(r[c] - interp(ref, c, r["time"])) / scale * 100 for r in runw]
        end = abs(runw[-1][c] - interp(ref, c, runw[-1]["time"])) / scale * 100
        rms = math.sqrt(sum(x * x for x in d) / len(d))
        worst = max(worst, max(d))
        at = runw[d.index(max(d))]["time"] * 1e3
        means = f" {mean(ref, c, t0, t1):11.4g} {mean(run, c, t0, t1):11.4g}" if a.means else ""
        print(f"  {c:22s} {scale:10.3g} {max(d):10.2f} {rms:10.2f} {end:10.2f} {at:8.2f}{means}")
    if a.bound is not None:
        ok = worst <= a.bound
        print(f"largest difference {worst:.2f} % {'within' if ok else 'PASSES'} the bound {a.bound} %")
        sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
