"""Mooney-Rivlin bars.
1. Uniaxial tension under a dead nominal traction (tests/scenes/mr_uniaxial.opts): at every load
   step the stretch lambda = 1 + u_z/L must satisfy the incompressible closed form
   P = 2 (lambda - lambda^-2)(C10 + C01/lambda) within 0.5 % (kappa = 1000 mu), over
   stretches 1.0-1.5, and J = lambda lambda_lateral^2 must stay within 0.5 % of 1.
2. The paper's Table 2 bar (examples/bar/bar.opts, follower pressure 5 / 10 / 40 kPa): end
   displacements beside the paper's reference values (plausibility: within 10 %), Newton
   converging in <= 6 full steps per load step, and 1 vs 2 ranks identical to 1e-8."""
import os
from fsitest import SRC, check, finish, run, scene

C10, C01, L, W = 8250.0, 500.0, 0.005, 0.001


def nominal(lam):
    return 2 * (lam - lam ** -2) * (C10 + C01 / lam)


r = run(scene("mr_uniaxial"))
check(r.code == 0, "uniaxial bar: run succeeds")
s = r.summary
check(s["physics"] == ["solid (mooney_rivlin)"] and s["fluid_cells"] == 0 and
      s["dofs"]["pressure_held_outside_fluid"] == s["dofs"]["pressure"],
      f"solid-only scene: physics {s['physics']}, no fluid cells, every pressure dof held (not assembled)")
worst, worst_j, lam_max = 0.0, 0.0, 1.0
for row in r.monitor:
    lam = 1 + row["solid_probe0_uz"] / L
    lat = 1 + row["solid_probe0_ux"] / W
    P = 18000.0 * row["time"]
    err = abs(nominal(lam) - P) / P
    worst, worst_j, lam_max = max(worst, err), max(worst_j, abs(lam * lat * lat - 1)), lam
    print(f"P = {P:8.1f} Pa: stretch {lam:.5f}, closed form P(stretch) = {nominal(lam):8.1f} Pa "
          f"({100 * (nominal(lam) - P) / P:+.3f} %), J = {lam * lat * lat:.5f}")
check(lam_max > 1.45, f"stretches reach {lam_max:.3f} (>= 1.45)")
check(worst < 0.005, f"uniaxial stress within 0.5 % of the closed form at every step (worst {100 * worst:.3f} %)")
check(worst_j < 0.005, f"volume nearly preserved: |J - 1| <= {worst_j:.2e} < 5e-3")

bar = os.path.join(SRC, "examples", "bar", "bar.opts")
r1 = run(bar, extra=["-out_fields_every", "0", "-snes_monitor"])
r2 = run(bar, np=2, extra=["-out_fields_every", "0"])
check(r1.code == 0 and r2.code == 0, "Table 2 bar: 1 and 2 rank runs succeed")
m1, m2 = r1.monitor, r2.monitor
paper = {1: (0.5, 0.5), 2: (0.96, 0.95), 8: (3.6, 3.55)}  # step: (paper, paper's reference) [mm]
for step, (p, ref) in paper.items():
    u = 1000 * m1[step - 1]["solid_probe0_uz"]
    print(f"{5000 * step / 1000:4.0f} kPa: end displacement {u:.3f} mm (paper {p}, reference {ref}; "
          f"{100 * (u - ref) / ref:+.1f} % from the reference)")
    check(abs(u - ref) / ref < 0.10, f"{5 * step} kPa: end displacement {u:.3f} mm within 10 % of {ref} mm")
newton = [int(row["newton"]) for row in m1]
check(max(newton) <= 6, f"Newton iterations per load step {newton} (<= 6)")
hist = [l for l in r1.out.splitlines() if "SNES Function norm" in l]
last = []
for l in hist:
    k = int(l.split()[0])
    last = [] if k == 0 else last
    last.append(float(l.split()[-1]))
print("residual history of the 40 kPa step:", " ".join(f"{x:.2e}" for x in last))
diff = max(abs(a[c] - b[c]) / max(abs(a[c]), 1e-30)
           for a, b in zip(m1, m2) for c in ("solid_probe0_ux", "solid_probe0_uy", "solid_probe0_uz"))
check(len(m1) == len(m2) == 8 and diff < 1e-8, f"1 vs 2 ranks: probe displacements agree to {diff:.1e} (< 1e-8)")
finish()
