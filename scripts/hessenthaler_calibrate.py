#!/usr/bin/env python3
"""Calibrate the Hessenthaler flap's shear modulus to the measured zero-flow tip height.

  scripts/hessenthaler_calibrate.py [--h 0.0015] [--mu 55e3,61e3,67e3] [--target 0.0295]

Runs examples/hessenthaler/hessenthaler_calibration.opts (the flap alone under buoyancy, steady load steps) at
each shear modulus (kappa = 50 mu throughout), fits log(tip) against log(mu) through the two
values that bracket the target (or the nearest two), solves for the modulus that gives the
target tip height, runs once more at that modulus to check, and prints the table.  The tip is
the last centreline probe's y displacement (the flap starts straight along z at y = 0).
Results: results/hessenthaler_calibration/h<h>/mu<mu>/ and calibration.csv there.
"""
import argparse
import csv
import math
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MEASURED_TIP = 0.02950  # [m] zero-flow tip height, Hessenthaler et al. 2017


def fail(msg):
    print("hessenthaler_calibrate: " + msg, file=sys.stderr)
    sys.exit(2)


def tip_y(run_dir):
    """The last row's y displacement of the last solid probe (the tip)."""
    with open(os.path.join(run_dir, "monitor.csv")) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        fail(run_dir + "/monitor.csv has no rows")
    probes = sorted(k for k in rows[-1] if k.startswith("solid_probe") and k.endswith("_uy"))
    if not probes:
        fail(run_dir + "/monitor.csv has no solid probe column")
    last = max(probes, key=lambda k: int(k[len("solid_probe"):-3]))
    return float(rows[-1][last])


def run(h, mu, out, np_ranks, extra):
    if os.path.exists(os.path.join(out, "summary.json")):
        return tip_y(out)  # already run
    cmd = ["mpirun", "-n", str(np_ranks), os.path.join(ROOT, "build", "fsi_app"),
           "-options_file", "examples/hessenthaler/hessenthaler_calibration.opts", "-mesh_h", repr(h),
           "-solid_mu", repr(mu), "-solid_kappa", repr(50 * mu), "-out_dir", out] + extra
    res = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if res.returncode != 0:
        sys.stdout.write(res.stdout[-3000:])
        fail("the run at mu = %g Pa failed (exit %d)" % (mu, res.returncode))
    return tip_y(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--h", type=float, default=0.0015, help="element size on the flap [m]")
    ap.add_argument("--mu", default="55e3,61e3,67e3", help="shear moduli to try [Pa], comma-separated")
    ap.add_argument("--target", type=float, default=MEASURED_TIP, help="tip height to match [m]")
    ap.add_argument("--np", type=int, default=1, help="MPI ranks per run")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "hessenthaler_calibration"))
    ap.add_argument("extra", nargs="*", help="further fsi_app options (after --)")
    a = ap.parse_args()
    try:
        mus = sorted(float(m) for m in a.mu.split(","))
    except ValueError:
        fail("--mu takes shear moduli in Pa separated by commas, e.g. 55e3,61e3,67e3")
    if len(mus) < 2 or mus[0] <= 0:
        fail("--mu needs at least two positive shear moduli (Pa), e.g. 55e3,61e3,67e3")
    if a.h <= 0 or a.target <= 0:
        fail("--h and --target must be positive lengths in metres")
    base = os.path.join(a.out, "h%g" % a.h)
    rows = [(mu, run(a.h, mu, os.path.join(base, "mu%g" % mu), a.np, a.extra)) for mu in mus]
    # The tip falls as the modulus rises: pick the bracketing pair, else the two nearest.
    pair = None
    for (m0, t0), (m1, t1) in zip(rows, rows[1:]):
        if (t0 - a.target) * (t1 - a.target) <= 0:
            pair = ((m0, t0), (m1, t1))
    if pair is None:
        near = sorted(rows, key=lambda r: abs(r[1] - a.target))[:2]
        pair = tuple(sorted(near))
        print("note: no modulus brackets the target; extrapolating from the nearest two")
    (m0, t0), (m1, t1) = pair
    if t0 <= 0 or t1 <= 0 or t0 == t1:
        fail("the tips %g and %g m cannot be fitted (the flap must rise, differently at each mu)" % (t0, t1))
    slope = math.log(t1 / t0) / math.log(m1 / m0)
    mu_cal = m0 * math.exp(math.log(a.target / t0) / slope)
    check = run(a.h, mu_cal, os.path.join(base, "mu%.0f" % mu_cal), a.np, a.extra)
    rows.append((mu_cal, check))
    with open(os.path.join(base, "calibration.csv"), "w") as f:
        f.write("mu_Pa,tip_y_m\n")
        for mu, tip in rows:
            f.write("%.6g,%.6g\n" % (mu, tip))
    print("h = %g m: tip height under buoyancy alone against the shear modulus (kappa = 50 mu)" % a.h)
    print("| mu [kPa] | tip y [mm] |\n|---|---|")
    for mu, tip in rows:
        print("| %.2f | %.3f |" % (mu / 1e3, tip * 1e3))
    print("calibrated mu = %.2f kPa (tip exponent %.3f): tip %.3f mm against %.3f mm measured" %
          (mu_cal / 1e3, slope, check * 1e3, a.target * 1e3))


if __name__ == "__main__":
    main()
