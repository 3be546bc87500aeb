"""The fluid's kinetic-energy budget, step by step (-monitor_fluid_energy), in a closed box:
the Ethier-Steinman flow at t = 0 left to decay inside no-slip walls (mu 0.01, so that
convection matters), generalized-alpha with rho_inf = 1 (the midpoint rule: no numerical
dissipation).  Tested with the velocity at the half step, the weak form gives
  E_{n+1} - E_n = -dt D(v_{n+1/2})               skew-symmetric convection,
  E_{n+1} - E_n = -dt [D - P](v_{n+1/2})         convective form,
D the viscous dissipation and P = int rho/2 (div v)|v|^2 the power the convective form puts into
a weakly divergence-free velocity; the monitors are at the step ends, so D and P are averaged
over them (an O(dt^2) difference, 0.3 % here).  Checks: each form's own budget closes within
0.5 % at every step, and the other budget does not (P is absent from the skew-symmetric
energy and present in the convective one: measured 5-8 % and up to 1.7 %).  With the grad-div
penalty (-fluid_grad_div 0.05) D includes gamma ||div v||^2 (half of D at the start: leaving it out
would miss by ~50 %), which the skew-symmetric budget must then close with too; at dt = 0.005,
because grad-div damps the initial interpolant's divergence fast (the end-point average of D is
off by 2.4 / 0.77 / 0.20 % at dt = 0.02 / 0.01 / 0.005 in the first step: O(dt^2))."""
from fsitest import check, finish, run, scene

BOX = [scene("ethier_steinman")]
EXTRA = ["-bc_boundary_type", "noslip", "-allow_unused_options", "-fluid_mu", "0.01",
         "-ts_alpha_radius", "1", "-ts_max_steps", "8", "-ts_dt", "0.02", "-monitor_fluid_energy",
         "-out_fields_every", "0"]


def budgets(form, more=()):
    r = run(BOX, extra=EXTRA + ["-fluid_convection", form] + list(more))
    check(r.code == 0, f"{form}: the decaying box flow runs")
    rows = [[float(x[k]) for k in ("time", "fluid_energy_kinetic", "fluid_dissipation",
                                   "fluid_convective_power")] for x in r.monitor]
    own, other = [], []  # |dE / predicted - 1| with D only, and with D - P
    for (t0, e0, d0, p0), (t1, e1, d1, p1) in zip(rows, rows[1:]):
        dt, de = t1 - t0, e1 - e0
        d_only, with_p = -dt * (d0 + d1) / 2, -dt * ((d0 + d1) / 2 - (p0 + p1) / 2)
        own.append(abs(de / d_only - 1))
        other.append(abs(de / with_p - 1))
    print(f"{form}: |dE/(-dt D) - 1| = " + ", ".join(f"{x:.4f}" for x in own))
    print(f"{form}: |dE/(-dt (D - P)) - 1| = " + ", ".join(f"{x:.4f}" for x in other))
    check(all(e1 < e0 for (_, e0, _, _), (_, e1, _, _) in zip(rows, rows[1:])),
          f"{form}: the kinetic energy falls every step")
    return own, other


skew_d, skew_dp = budgets("skew_symmetric")
check(len(skew_d) >= 6 and max(skew_d) < 0.005,
      f"skew-symmetric: dE = -dt D every step within 0.5 % ({max(skew_d):.4f})")
check(max(skew_dp) > 0.03, f"skew-symmetric: the convective power is not in its budget ({max(skew_dp):.3f} off with it)")
gd_d, _ = budgets("skew_symmetric", ["-fluid_grad_div", "0.05", "-ts_dt", "0.005"])
check(len(gd_d) >= 6 and max(gd_d) < 0.005,
      f"skew-symmetric + grad-div: dE = -dt D every step within 0.5 % ({max(gd_d):.4f})")
conv_d, conv_dp = budgets("convective")
check(len(conv_dp) >= 6 and max(conv_dp) < 0.005,
      f"convective: dE = -dt (D - P) every step within 0.5 % ({max(conv_dp):.4f})")
check(max(conv_d) > 0.01, f"convective: without P its budget is off ({max(conv_d):.3f})")
finish()
