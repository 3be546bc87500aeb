"""scripts/valve_report.py's per-cycle volumes on a synthetic monitor.csv with known integrals:
three cycles of 1.1 s, each a half-sine ejection (peak 20 L/min over 0.3 s; the ejected volume, not the closed
valve's forward swings), a closing backflow of
5 L/min for 30 ms, then a closed valve (contact_pairs 200) leaking 0.5 L/min under a ringing of
+-2 L/min over whole periods (it must count only by its net); the second cycle starts closed and
leaks until its opening at 50 ms, and opens again 28 ms before its end (5 L/min forward: the
next ejection started early, ejected volume, not a negative leak); the third repeats the second,
so the run is periodic from cycle 3; cycle 1's phases hold known numbers of steps.  Also: a condition on a
missing column and a malformed one exit non-zero naming --closed.  The figures by name (--json) and
scripts/study's --qoi valve:NAME[@CYCLE] reading them.
The clinical table of the first cycle on the same run, given an orifice that opens linearly from
0.2 to 3.0 cm^2 over 50 ms (10-90 %: 40 ms), drifts to 2.5 cm^2 at 0.28 s and closes to 0.2 cm^2 at
0.32 s (90-10 % of the whole swing: 136.3 ms; of the rapid fall: 32 ms; 44.0 % of the peak when
the flow reverses, at the first row after 0.3 s), 1000 Pa across
the valve while blood goes forward (7.50 mmHg mean), a half-sine peak velocity of 1.2 m/s, and
3 mm of coaptation while closed."""
import json
import math
import os
import re
import subprocess
import sys
import tempfile

from fsitest import SRC, check, finish

DT, T = 5e-4, 1.1
REOPEN = 0.33 + 53 * 0.014  # s into the second cycle: after 53 whole periods of the ringing
LPM = 1 / 6e4  # m^3/s per L/min


def flow(s):
    """Flow to the aorta [L/min] and contact pairs at time s into a cycle."""
    if s <= 0.3 + 1e-12:
        return 20 * math.sin(math.pi * s / 0.3), 0
    if s <= 0.33 + 1e-12:
        return -5.0, 0
    return -0.5 + 2 * math.sin(2 * math.pi * (s - 0.33 - DT) / 0.014), 200


def valve(s, q, pairs):
    """Orifice [m^2], dp [Pa], peak velocity [m/s], coaptation height [m] at s into a cycle."""
    if s < 0.05:
        goa = 0.2 + 2.8 * s / 0.05
    elif s < 0.28:  # the slow drift of ejection
        goa = 3.0 - 0.5 * (s - 0.05) / 0.23
    else:  # the rapid closing
        goa = max(0.2, 2.5 - 2.3 * (s - 0.28) / 0.04)
    return goa * 1e-4, 1000.0 if q > 0 else -9000.0, 1.2 * max(0.0, math.sin(math.pi * s / 0.3)), \
        0.003 if pairs else 0.0


def write_run(d):
    with open(os.path.join(d, "monitor.csv"), "w") as f:
        f.write("step,time,newton,krylov,step_seconds,dt,inlet_flux,contact_pairs,valve_goa,valve_dp,"
                "valve_peak_velocity,valve_coaptation_height\n")
        n = int(round(T / DT))
        for k in range(1, 3 * n + 1):
            c = (k - 1) // n
            t, s = k * DT, (k - c * n) * DT
            q, pairs = flow(s)
            if c > 0 and k - c * n <= 100:  # the second and third cycles start closed for 50 ms
                q, pairs = -0.5, 200
            if c > 0 and k - c * n > REOPEN / DT + 1e-9:  # and open again before their end
                q, pairs = 5.0, 0
            g, dp, v, ch = valve(s, q, pairs)
            f.write(f"{k},{t:.10f},3,10,1.0,{DT},{-q * LPM:.12e},{pairs},{g:.8e},{dp},{v:.8f},{ch}\n")


def report(*args):
    p = subprocess.run(["/usr/bin/python3", os.path.join(SRC, "scripts", "valve_report.py"), *args],
                       capture_output=True, text=True)
    return p.returncode, p.stdout + p.stderr


with tempfile.TemporaryDirectory() as d:
    write_run(d)
    code, out = report(d, "--every", "1000")
    check(code == 0, f"valve_report on the synthetic run: rc {code}" + ("" if code == 0 else "\n" + out))
    rows = re.findall(r"^\| (\d) \| ([0-9.]+)(?:, open again at ([0-9.]+))? \| ([0-9.]+) \| ([0-9.-]+) \| ([0-9.-]+) \| ([0-9.-]+) "
                      r"\| ([0-9.-]+) \| ([0-9.]+) % \|$", out, re.M)
    check(len(rows) == 3, f"the split table has {len(rows)} cycle rows (3 expected)" +
          ("" if len(rows) == 3 else ":\n" + out))
    ml = 1e6 * LPM  # mL per (L/min x s)
    forward = 20 * 0.6 / math.pi * ml
    closing = 5 * 0.03 * ml
    after = [0.5 * (T - 0.33) * ml, 0.5 * (REOPEN - 0.33) * ml]
    early = 5 * (T - REOPEN) * ml  # the second cycle's next ejection, started early
    before = [0.0, 0.5 * 0.05 * ml]
    for c, r in enumerate(rows):
        closed_at, f, cl, la, lb, reg, frac = (float(x) for x in r[1:2] + r[3:])
        reopened = float(r[2]) if r[2] else None
        want_reopen = None if c == 0 else 1000 * (c * T + REOPEN + DT)
        check((reopened is None) == (want_reopen is None) and
              (reopened is None or abs(reopened - want_reopen) < 0.06),
              f"cycle {c + 1}: open again at {reopened} ms, expected {want_reopen}")
        check(abs(closed_at - (1000 * (c * T + 0.33 + DT))) < 0.06,
              f"cycle {c + 1}: closed at {closed_at} ms, expected {1000 * (c * T + 0.33 + DT):.1f}")
        # The second cycle's ejection starts 50 ms late: its half-sine loses that part.  The report
        # sums flow x step over the rows (right end points): within 0.05 mL of the integral here.
        f_exp = forward if c == 0 else 20 * (0.3 / math.pi) * (1 + math.cos(math.pi * 0.05 / 0.3)) * ml
        f_rows = sum(flow(k * DT)[0] for k in range(1 if c == 0 else 101, 601)) * DT * ml
        if c > 0:
            f_exp, f_rows = f_exp + early, f_rows + early
        for name, got, want, tol in (("ejected", f, f_rows, 0.006), ("ejected (integral)", f, f_exp, 0.05), ("closing", cl, closing, 0.001),
                                     ("leakage after closure", la, after[min(c, 1)], 0.001),
                                     ("leakage before opening", lb, before[min(c, 1)], 0.001),
                                     ("regurgitant", reg, closing + after[min(c, 1)] + before[min(c, 1)], 0.002)):
            check(abs(got - want) <= tol, f"cycle {c + 1}: {name} {got} mL, expected {want:.4f}")
        check(abs(frac - 100 * reg / f) < 0.01, f"cycle {c + 1}: fraction {frac} % of {reg}/{f}")
    # The clinical table's first cycle (rows at the steps' ends: within a step of the exact times).
    head = re.search(r"^\| cycle \| peak orifice.*$", out, re.M)
    first = re.search(r"^\| 1 \| ([^\n]*) \|$", out[head.end():], re.M) if head else None
    cells = [c.strip() for c in first.group(1).split("|")] if first else []
    names = [c.strip() for c in head.group(0).strip("|").split("|")[1:]] if head else []
    got = dict(zip(names, cells))
    for name, want, tol in (("peak orifice [cm^2]", 3.0, 1e-3), ("mean systolic gradient [mmHg]", 7.50, 0.01),
                            ("peak velocity [m/s]", 1.2, 1e-3), ("opening 10-90 % [ms]", 40.0, 0.6),
                            ("closing 90-10 % [ms]", 136.3, 0.6), ("rapid closing [ms]", 32.0, 0.6),
                            ("orifice at flow reversal [% of peak]", 44.0, 0.1), ("coaptation height [mm]", 3.0, 1e-3)):
        val = float(got[name]) if got.get(name, "-") != "-" else None
        check(val is not None and abs(val - want) <= tol, f"clinical table, cycle 1: {name} {val}, expected {want}")
    # Periodic state: cycle 2 ejects less than cycle 1 (its opening 50 ms late), cycle 3 repeats it.
    strokes = [float(x) for x in re.findall(r"^\| \d \| ([0-9.]+) \| - \| [0-9.]+ \| ", out, re.M)]
    change = re.search(r"^\| 2 \| [^|]+\| - \| [^|]+\| stroke ([0-9.]+) %", out, re.M)
    check(len(strokes) == 3 and change is not None and
          abs(float(change.group(1)) - abs(strokes[1] - strokes[0]) / strokes[0] * 100) < 0.1,
          f"periodicity table: strokes {strokes}, cycle 2's change {change and change.group(1)}")
    check("periodic (each change < 2 %): from cycle 3" in out, "periodic from cycle 3 expected:\n" + out[-1500:])
    # Where the time goes: cycle 1's phases, 1 s per step (rows: opening to 45.05 ms, ejection to
    # the closure at 330.5 ms, 50 ms of ringing, diastole to 1100 ms).
    phases = dict(re.findall(r"^\| 1 \| ([a-z ]+) \| [0-9.]+ \| [0-9.]+ \| (\d+) \| ", out, re.M))
    want = {"opening": "90", "ejection": "571", "closure ringing": "100", "diastole": "1439"}
    check(phases == want, f"cycle 1's phases {phases}, expected {want}")
    # The same figures by name (--json), and scripts/study's --qoi valve:NAME[@CYCLE] reading them.
    code, _ = report(d, "--json", os.path.join(d, "figures.json"))
    fig = json.load(open(os.path.join(d, "figures.json")))["cycles"] if code == 0 else []
    check(len(fig) == 3 and abs(fig[0]["peak_goa_cm2"] - 3.0) < 1e-3 and abs(fig[0]["closing_rapid_ms"] - 32.0) < 0.6
          and abs(fig[1]["regurgitant_mL"] - (closing + after[1] + before[1])) < 0.002 and fig[2]["complete"],
          f"--json: {fig[:1]}")
    sys.path.insert(0, os.path.join(SRC, "scripts"))
    import study
    got = (study.qoi_value("valve:peak_goa_cm2", [], d), study.qoi_value("valve:leakage_mL@2", [], d))
    check(abs(got[0] - 3.0) < 1e-3 and abs(got[1] - (after[1] + before[1])) < 0.002, f"study's valve QoIs {got}")
    try:
        study.qoi_value("valve:orifice", [], d)
        check(False, "study --qoi valve:orifice (no such figure) accepted")
    except SystemExit as e:
        check("no figure 'orifice'" in str(e) and "peak_goa_cm2" in str(e), f"unknown valve figure: {e}")
    for bad, word in (("seal_cells>3", "no monitor column 'seal_cells'"),
                      ("contact_pairs=3", "COLUMN>VALUE or COLUMN<VALUE")):
        code, out = report(d, "--closed", bad)
        check(code != 0 and "--closed" in out and word in out,
              f"--closed {bad}: rc {code}, {out.strip()}")
finish()
