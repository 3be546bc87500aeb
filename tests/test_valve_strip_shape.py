"""The strip leaflets (meshes/valve.geo shape=1, the pressure scenes' shape: issue 54) on the CI
mesh, 2 ranks: the closed native valve's shape, whose neighbouring coaptation strips stand
gap - t = 1.55 mm apart and narrow to gapw - t = 0.63 mm where they meet the wall.

1. At rest (valve_diastole.opts, the closing run's first step, the aorta 57 Pa up): the mesh is
   the one the scene's options are made for: no leaflet contact (the slits at the commissures are
   wider than -contact_offset 0.6 mm), the gap seal already holds those slits shut (narrower than
   -gap_seal_gap_open 0.78 mm), and the orifice is the slits and the central hole seen along the
   axis, 10.9 % of the annulus measured (the band: the hole pi rcenter^2 plus three slits 1.55 mm
   wide over the 11 mm from the hole to the wall, 11.8 %, less where they narrow at the wall).
2. Closing (the aorta raised to 70 mmHg over 10 ms, 0.5 ms steps): the strips meet and carry
   the load by 16 ms: > 100 contact pairs (586 measured), coaptation height >= 2 mm, the smallest
   healthy one (2.94 measured; 3.1-5.9 mm over the scene's 40 ms ramp and hold), the orifice with
   the gaps narrower than the contact offset counted closed below 2 % of the annulus (1.29
   measured), no fluid cell inverted.  ~11 min on 2 cores: the steps are cut to 0.0625 ms as the
   strips meet (1 ms steps: the same figures to 0.03 points, 16 % dearer: 9 failed steps, not 5).
3. Bad input: shape=1 with commissural posts, a wall gap gapw too narrow for fluid between the
   strips, and a contact offset wider than the mesh's narrowest gap are refused with one line and
   exit 2 before any step."""
from fsitest import check, finish, run, SRC
import math
import os

DIASTOLE = os.path.join(SRC, "examples/valve/valve_diastole.opts")
QUIET = ["-out_fields_every", "0", "-checkpoint_every", "0"]

# One run: the aorta raised to 70 mmHg over 10 ms and held, 0.5 ms steps.
r = run(DIASTOLE, np=2, presets=(), extra=QUIET + [
    "-bc_outlet_expr", "t<0.01 ? 0.5*(1-cos(_pi*t/0.01)) : 1", "-ts_dt", "0.0005",
    "-ts_adapt_switch_when", "time>1", "-ts_max_time", "0.016"])
check(r.code == 0 and r.summary["converged"], "the strip valve closes under 70 mmHg on 2 ranks")

# 1. At rest: its first step (0.5 ms, the aorta 57 Pa up).
if r.code == 0:
    m = r.monitor[0]
    print(f"at rest: orifice {m['valve_goa_ratio']*100:.2f} %, contact pairs "
          f"{int(m['contact_pairs'])}, sealed cells {int(m['seal_cells'])}")
    check(m["contact_pairs"] == 0, "no leaflet contact at rest (the slits are wider than the offset)")
    check(m["seal_cells"] > 0, "the gap seal holds the commissural slits shut at rest")
    Ra, rc, gap, t = 0.0125, 0.0015, 0.002, 0.00045
    est = (math.pi * rc**2 + 3 * (gap - t) * (Ra - rc)) / (math.pi * Ra**2)
    check(0.8 * est < m["valve_goa_ratio"] < est,
          f"orifice at rest {m['valve_goa_ratio']*100:.2f} % within [80 %, 100 %] of the hole "
          f"and slits' {est*100:.2f} %")

# 2. Closed at 16 ms.
if r.code == 0:
    m = r.monitor[-1]
    print(f"t = {m['time']*1e3:.0f} ms: contact pairs {int(m['contact_pairs'])}, coaptation "
          f"height {m['valve_coaptation_height']*1e3:.2f} mm, orifice {m['valve_goa_ratio']*100:.2f}"
          f" % ({m['valve_goa_contact_ratio']*100:.2f} % with contact gaps closed), backflow "
          f"{m['inlet_flux']*6e4:.2f} L/min, dp {m['valve_dp']/133.322:.1f} mmHg")
    check(m["contact_pairs"] > 100, "the strips are in contact")
    check(m["valve_coaptation_height"] >= 0.002, "coaptation height >= 2 mm")
    check(m["valve_goa_contact_ratio"] < 0.02, "orifice with contact gaps closed < 2 % of the annulus")
    check(min(x["mesh_min_jacobian"] for x in r.monitor) > 0, "no fluid cell inverts")

# 3. Bad input.
for params, what in (("shape=1,coapt=0.004,gap=0.002,gapw=0.00108,post=0.0025", "posts"),
                     ("shape=1,coapt=0.004,gap=0.002,gapw=0.0006", "wall gap")):
    b = run(DIASTOLE, np=1, presets=(), extra=QUIET + ["-mesh_params", params, "-ts_max_steps", "1"])
    lines = [ln for ln in b.out.splitlines() if "error" in ln]
    print(lines[:1])
    check(b.code == 2 and len(lines) >= 1 and "valve.geo: shape=1" in lines[0],
          f"{what}: refused with one line naming the parameter, exit 2 (exit {b.code})")
# A contact offset wider than the mesh's narrowest gap between contact pieces (the wall slits,
# 0.61 mm) would push the leaflets apart at the first step: refused before it.
b = run(DIASTOLE, np=1, presets=(), extra=QUIET + ["-contact_offset", "0.0007", "-ts_max_steps", "1"])
lines = [ln for ln in b.out.splitlines() if "error" in ln]
print(lines[:1])
check(b.code == 2 and len(lines) >= 1 and "-contact_offset" in lines[0] and "smallest gap" in lines[0],
      f"contact offset 0.7 mm: refused with one line naming -contact_offset, exit 2 (exit {b.code})")
finish()
