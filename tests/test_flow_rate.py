"""Flow-rate inflow, table and expression waveforms, expression profiles (issue 14), on the rigid
pipe, 1 rank: the flux through the inlet equals Q(t) to 1e-10 relative at every step; with a
parabolic profile the steady flow is Poiseuille's; muparser profiles equal the built-in ones;
the backflow stop (the paper's "inflow set to zero once the valve is closed", issue 16) stops the
table's backflow when a monitor column passes its threshold, along a smooth ramp, holds it at zero
and lets the flow on again when the table turns forward, also across a restart; bad tables,
formulas and stop conditions are one clear line and exit 2."""
import math
import os
import tempfile
from fsitest import check, finish, run, scene

S = scene("flow_rate")
R, mu = 0.005, 0.004
Q0 = 6.1359e-7                       # the scene's -bc_inlet_value [m^3/s]
G = 8 * mu * Q0 / (math.pi * R**4)   # Poiseuille's pressure gradient for it [Pa/m]
tmp = tempfile.mkdtemp()


def table(name, rows):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write("# t [s]  Q [m^3/s]\n" + "".join(f"{t} {q}\n" for t, q in rows))
    return path


def flux_matches(r, Q, what):
    """Inlet flux (outward, so -Q) against Q(t) at every step, relative to the largest |Q|."""
    rows = r.monitor
    scale = max(abs(Q(m["time"])) for m in rows)
    err = max(abs(-m["inlet_flux"] - Q(m["time"])) for m in rows) / scale
    print(f"{what}: {len(rows)} steps, max |flux - Q(t)| / max|Q| = {err:.1e}")
    check(r.code == 0 and err < 1e-10, f"{what}: flux equals Q(t) to 1e-10 ({err:.1e})")


# Steady parabolic inflow: Poiseuille (wall shear G R / 2, centre speed 2 Q / (pi R^2)).
r = run(S)
m = r.monitor[-1]
tau, vc = m["wall_fz"] / m["wall_area"], m["probe0_vz"]
e_tau, e_vc = tau / (G * R / 2) - 1, vc / (2 * Q0 / (math.pi * R**2)) - 1
print(f"steady: wall shear {100*e_tau:+.2f}%, centre speed {100*e_vc:+.2f}% from Poiseuille")
flux_matches(r, lambda t: Q0, "steady parabolic")
check(abs(e_tau) < 0.02 and abs(e_vc) < 0.02, "steady parabolic inflow gives Poiseuille within 2%")

# The same profile as a muparser expression (1 value: speed along the inward normal).
r2 = run(S, extra=["-bc_inlet_profile", "expression", "-bc_inlet_expr", "1 - (x^2 + y^2) / 25e-6"])
d = abs(r2.monitor[-1]["probe0_vz"] / vc - 1) if r2.code == 0 else 1
check(d < 1e-9, f"expression profile equals the parabolic one ({d:.1e})")
# A velocity BC with a 3-component expression equals the built-in parabolic velocity profile.
vel = ["-bc_inlet_type", "velocity", "-bc_inlet_value", "0.003"]
ra = run(S, extra=vel + ["-bc_inlet_profile", "parabolic", "-bc_inlet_center", "0,0,0",
                         "-bc_inlet_radius", "0.005", "-bc_inlet_direction", "0,0,1"])
rb = run(S, extra=vel + ["-bc_inlet_profile", "expression",
                         "-bc_inlet_expr", "0, 0, 2 * max(0, 1 - (x^2 + y^2) / 25e-6)"])
ok = ra.code == 0 and rb.code == 0
d = abs(rb.monitor[-1]["inlet_flux"] / ra.monitor[-1]["inlet_flux"] - 1) if ok else 1
check(d < 1e-12, f"velocity expression profile equals the parabolic profile ({d:.1e})")

# A periodic table (period 0.1 s) sampled over 1.6 periods, and a held (non-periodic) table.
tri = table("tri.dat", [(0, 0), (0.05, 2e-6), (0.1, 0)])
Qtri = lambda t: 2e-6 * (1 - abs((t % 0.1) / 0.05 - 1))
# (the imposed flux does not depend on the mesh: the waveform runs take a coarse one, 3 times cheaper)
unsteady = ["-ts_type", "alpha", "-ts_dt", "0.02", "-ts_alpha_radius", "0.5",
            "-mesh_params", "R=0.005,L=0.01,ncirc=12", "-mesh_h", "0.004"]
r = run(S, extra=unsteady + ["-ts_max_time", "0.16", "-bc_inlet_value", "1",
                             "-bc_inlet_waveform", "table", "-bc_inlet_table", tri,
                             "-bc_inlet_periodic"])
flux_matches(r, Qtri, "periodic table")
ramp = table("ramp.dat", [(0, 1e-6), (0.05, 2e-6)])
r = run(S, extra=unsteady + ["-ts_max_time", "0.08", "-bc_inlet_value", "1",
                             "-bc_inlet_waveform", "table", "-bc_inlet_table", ramp])
flux_matches(r, lambda t: 1e-6 * (1 + min(t, 0.05) / 0.05), "table held past its end")
# An expression waveform, scaled by the value.
r = run(S, extra=unsteady + ["-ts_max_time", "0.06", "-bc_inlet_value", "1e-6",
                             "-bc_inlet_waveform", "expression",
                             "-bc_inlet_expr", "1 + sin(2 * _pi * t / 0.1)"])
flux_matches(r, lambda t: 1e-6 * (1 + math.sin(2 * math.pi * t / 0.1)), "expression waveform")

# Backflow stop: forward 1e-6 m^3/s, reversed from 0.05 s, forward again from 0.1275 s; the inflow
# stops at the end of the first step whose backflow (the outward inlet flux) exceeds 5e-7 and
# ramps to zero over 20 ms.  The flux must be Q(t) x the stop's factor at every step.
stop_rows = [(0, 1e-6), (0.04, 1e-6), (0.06, -1e-6), (0.12, -1e-6), (0.135, 1e-6), (0.2, 1e-6)]
stop_tab = table("stop.dat", stop_rows)


def Qstop(t):  # the table, linearly interpolated
    for (t0, q0), (t1, q1) in zip(stop_rows, stop_rows[1:]):
        if t <= t1:
            return q0 + (q1 - q0) * (t - t0) / (t1 - t0)
    return stop_rows[-1][1]


stop = unsteady[:3] + ["0.01"] + unsteady[4:] + [
    "-bc_inlet_value", "1", "-bc_inlet_waveform", "table", "-bc_inlet_table", stop_tab,
    "-bc_inlet_stop_backflow_when", "inlet_flux>5e-7", "-bc_inlet_stop_ramp", "0.02"]
r = run(S, extra=stop + ["-ts_max_time", "0.18"])
rows = r.monitor if r.code == 0 else []
t_stop = next((m["time"] for m in rows if Qstop(m["time"]) < 0 and m["inlet_flux"] > 5e-7), None)


def factor(t):
    if t_stop is None or t <= t_stop or Qstop(t) > 0:
        return 1.0
    x = min(1.0, (t - t_stop) / 0.02)
    return 1 - x * x * (3 - 2 * x)


err = max((abs(-m["inlet_flux"] - Qstop(m["time"]) * factor(m["time"])) for m in rows),
          default=1) / 1e-6
ferr = max((abs(m["inlet_flow_factor"] - factor(m["time"])) for m in rows), default=1)
print(f"backflow stop: stopped at t = {t_stop}, |flux - Q(t) factor(t)| / max|Q| = {err:.1e}, "
      f"factor error {ferr:.1e}; factors "
      f"{[round(m['inlet_flow_factor'], 3) for m in rows]}")
check(r.code == 0 and t_stop is not None and abs(t_stop - 0.06) < 1e-9,
      "the stop fires at the first step with backflow above the threshold (t = 0.06 s)")
check(err < 1e-10 and ferr < 1e-12,
      f"the flux follows Q(t) times the smooth ramp to zero ({err:.1e}, {ferr:.1e})")
held = [m for m in rows if 0.08 + 1e-9 < m["time"] < 0.12]
check(len(held) == 3 and all(m["inlet_flux"] == 0 for m in held),
      "held at zero while the table is backwards")
check(any(m["time"] > 0.13 for m in rows) and
      all(m["inlet_flow_factor"] == 1 for m in rows if m["time"] > 0.1275),
      "the flow is on again once the table turns forward")
# Interrupted in the ramp (t = 0.07 s) and resumed: the same run.
ra = run(S, extra=stop + ["-ts_max_time", "0.07", "-checkpoint_every", "1"])
rb = run(S, extra=stop + ["-ts_max_time", "0.18", "-restart", os.path.join(ra.dir, "checkpoint.h5")])
ok = ra.code == 0 and rb.code == 0 and r.code == 0
d = max(abs(x["inlet_p"] - y["inlet_p"]) for x, y in zip(rb.monitor, rows[-11:])) / max(
    abs(y["inlet_p"]) for y in rows) if ok and len(rb.monitor) == 11 else 1
check(ok and d < 1e-8, f"resumed in the ramp = uninterrupted (inlet pressure {d:.1e})")

# Bad input.
down = table("down.dat", [(0, 0), (0.05, 1), (0.05, 2)])
nan = table("nan.dat", [(0, 0), (0.05, "nan")])
cases = [
    ("missing table", ["-bc_inlet_waveform", "table", "-bc_inlet_table", "/nonexistent/q.dat"], "/nonexistent/q.dat"),
    ("non-increasing times", ["-bc_inlet_waveform", "table", "-bc_inlet_table", down], "times must increase"),
    ("NaN in a table", ["-bc_inlet_waveform", "table", "-bc_inlet_table", nan], "not a finite number"),
    ("expression syntax error", ["-bc_inlet_profile", "expression", "-bc_inlet_expr", "1 - (x^2"], "bc_inlet_expr"),
    ("unknown variable", ["-bc_inlet_waveform", "expression", "-bc_inlet_expr", "sin(w * t)"], "bc_inlet_expr"),
    ("profile without flux", ["-bc_inlet_profile", "expression", "-bc_inlet_expr", "0"], "no flux"),
    ("stop on an unknown column", ["-bc_inlet_stop_backflow_when", "valve_goa<0.1"], "no monitor column 'valve_goa'"),
    ("stop without a comparison", ["-bc_inlet_stop_backflow_when", "inlet_flux=1"], "give a monitor column, < or >"),
    ("stop on a non-number", ["-bc_inlet_stop_backflow_when", "inlet_flux>1e-6x"], "give a monitor column, < or >"),
    ("negative stop ramp", ["-bc_inlet_stop_backflow_when", "inlet_flux>0", "-bc_inlet_stop_ramp", "-1"], "bc_inlet_stop_ramp"),
]
for name, extra, needle in cases:
    r = run(S, extra=extra)
    lines = [l for l in r.out.splitlines() if "fsi_app: error:" in l]
    check(r.code == 2, f"{name}: exit 2 ({r.code})")
    check(len(lines) == 1 and needle in lines[0], f"{name}: one error line naming '{needle}'")
    check(not os.path.exists(os.path.join(r.dir, "summary.json")), f"{name}: no summary.json")
    if lines:
        print("   message:", lines[0])
finish()
