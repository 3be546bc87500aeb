"""Steady Poiseuille flow in the rigid pipe, driven by the exact traction: outlet flux and mean
wall shear within 1% of Q = pi R^4 G / (8 mu) and tau_w = G R / 2 (benchmarks.md section 3)."""
import math
import sys
from fsitest import check, finish, run, scene

np = int(sys.argv[1]) if len(sys.argv) > 1 else 1
G, R, mu = 10.0, 0.005, 0.004
r = run(scene("poiseuille"), np=np)
check(r.code == 0, "run succeeds")
m = r.monitor[-1]
Q, tw = math.pi * R**4 * G / (8 * mu), G * R / 2
q_err = m["outlet_flux"] / Q - 1
mass = (m["outlet_flux"] + m["inlet_flux"]) / Q
tau_err = (m["wall_fz"] / m["wall_area"]) / tw - 1
print(f"flux {m['outlet_flux']:.6e} (exact {Q:.6e}, {100*q_err:+.3f}%), wall shear "
      f"{m['wall_fz']/m['wall_area']:.6e} Pa (exact {tw:.6e}, {100*tau_err:+.3f}%)")
check(abs(q_err) < 0.01, f"flux within 1% ({100*q_err:+.3f}%)")
check(abs(tau_err) < 0.01, f"wall shear within 1% ({100*tau_err:+.3f}%)")
check(abs(mass) < 1e-10, f"inflow equals outflow (relative imbalance {mass:.1e})")

# The same flow driven by the user-facing pressure boundaries (0.1 Pa over 10 mm) with the
# tangential velocity fixed on inlet and outlet (parallel-flow boundaries, -bc_*_components x,y).
r = run(scene("poiseuille"), np=np, extra=[
    "-bc_inlet_type", "pressure", "-bc_inlet_value", "0.1", "-bc_inlet_components", "x,y",
    "-bc_inlet_backflow_beta", "0", "-bc_outlet_type", "pressure", "-bc_outlet_value", "0",
    "-bc_outlet_components", "x,y"])
check(r.code == 0, "pressure-driven run succeeds")
m = r.monitor[-1]
q_err, tau_err = m["outlet_flux"] / Q - 1, (m["wall_fz"] / m["wall_area"]) / tw - 1
print(f"pressure-driven: flux {100*q_err:+.3f}%, wall shear {100*tau_err:+.3f}%")
check(abs(q_err) < 0.01, f"pressure-driven flux within 1% ({100*q_err:+.3f}%)")
check(abs(tau_err) < 0.01, f"pressure-driven wall shear within 1% ({100*tau_err:+.3f}%)")
finish()
