"""Contact between leaflet-like plates (issue 16), solid only (tests/scenes/plates_contact.opts:
two plates 10 mm high, 2 mm apart, pressed together by a pressure on their outer faces).
1. Without contact the plates' tips cross (each moves > 1 mm towards the other: they would
   overlap); with contact they stop at the offset: gap >= offset - max penetration, max
   penetration < 10 % of the offset (penalty 1e8 Pa/m), Newton converged at every load step.
2. Two ranks give the one-rank answer (the contact surface is gathered on every rank; pairs
   across ranks): tip displacement equal to 1e-8 relative.
3. The contact Jacobian is consistent: PETSc's -snes_test_jacobian on small plates meshed so that
   no node faces a mesh line of the other plate exactly (sy, hb), with a penalty (1e10) at which
   contact dominates the rows it touches: ||J - J_fd|| / ||J|| < 1e-5 at the converging iterate
   (measured 2.3e-7; the first iterate, in the mirror-aligned reference configuration, sits on
   the distance's region boundaries, where the Hessian jumps, and is not checked), and Newton
   converges on the full scene in <= 8 iterations per load step.
   The axis rod (-contact_axis_radius 0.4 mm through the gap's middle at the top): the top
   edges stop ~0.8 mm apart instead of at the 0.5 mm offset, Newton <= 8; its Jacobian (rod
   pressing on both edges of the small plates) against finite differences: < 2e-6 at every
   iterate after the first (2.3e-7; without the rod's curvature term 4.4e-5).
4. Bad input: a negative offset, a negative axis rod radius, an axis that is not 6 numbers or
   has no direction, a ramp wider than the offset, -physics contact without the
   solid, a gap seal without the fluid, a contact surface the mesh lacks, a seal whose open gap
   is below its closed one, a negative seal resistance:
   one error line naming the option, exit 2."""
import re
from fsitest import check, finish, run, scene

PLATES = scene("plates_contact")
GAP0, OFFSET = 0.002, 0.0005

free = run(PLATES, extra=["-physics", "solid", "-allow_unused_options"])
m = free.monitor[-1]
check(free.code == 0, "plates without contact: run completes")
print(f"without contact: tips move {m['solid_probe0_ux']*1e3:.3f} and {m['solid_probe1_ux']*1e3:.3f} mm")
check(m["solid_probe0_ux"] - m["solid_probe1_ux"] > GAP0, "without contact the tips cross")

c1 = run(PLATES, np=1)
check(c1.code == 0, "plates with contact: every load step converged")
rows = c1.monitor
m = rows[-1]
gap = GAP0 - (m["solid_probe0_ux"] - m["solid_probe1_ux"])
print(f"with contact: tips {m['solid_probe0_ux']*1e3:.4f} / {m['solid_probe1_ux']*1e3:.4f} mm, "
      f"gap {gap*1e3:.4f} mm, max penetration {m['contact_max_penetration']*1e6:.1f} um, "
      f"{int(m['contact_pairs'])} pairs, force {m['contact_force']*1e3:.3f} mN")
check(m["contact_pairs"] > 0, "contact is active at the end")
check(gap >= OFFSET - m["contact_max_penetration"] - 1e-9, "the tips stop at the offset")
check(m["contact_max_penetration"] < 0.1 * OFFSET, "penetration < 10 % of the offset")
newton = [r["newton"] for r in rows if r["contact_pairs"] > 0]
print(f"Newton per load step in contact: {newton}")
check(max(newton) <= 8, "Newton converges in <= 8 iterations with the contact tangent")

c2 = run(PLATES, np=2)
m2 = c2.monitor[-1]
rel = abs(m2["solid_probe0_ux"] - m["solid_probe0_ux"]) / abs(m["solid_probe0_ux"])
print(f"2 ranks vs 1: tip displacement differs by {rel:.2e}")
check(c2.code == 0 and rel < 1e-8, "2 ranks give the 1-rank answer")

# Finite-difference check of the Jacobian with contact dominating.
fd = run(PLATES, extra=["-ts_max_steps", "1", "-ts_max_time", "0.125", "-snes_max_it", "3",
                        "-mesh_h", "0.001", "-mesh_params",
                        "fluid=0,g=0.0006,w=0.001,hp=0.002,t=0.0008,sy=0.00037,hb=0.77",
                        "-contact_offset", "0.00065", "-contact_penalty", "1e10",
                        "-solid_probe_points", "", "-snes_test_jacobian", "-snes_test_err", "1e-9",
                        "-ts_adapt_type", "none"])
ratios = [float(x) for x in re.findall(r"\|\|J - Jfd\|\|_F/\|\|J\|\|_F = ([0-9.eE+-]+)", fd.out)]
print(f"||J - Jfd||/||J|| per iterate: {ratios}")
check(len(ratios) >= 3 and ratios[-1] < 1e-5, "contact Jacobian matches finite differences")

# The axis rod (-contact_axis_radius): a rod of radius 0.4 mm along y through the middle of the
# 2 mm gap at the plates' top (z = 10 mm) stops their top edges 0.4 mm from its axis, so that
# they keep ~0.8 mm between them instead of the 0.5 mm offset.
rod = run(PLATES, np=1, extra=["-contact_axis_radius", "0.0004", "-contact_axis",
                               "0.007,0,0.01,0,1,0"])
m = rod.monitor[-1] if rod.monitor else None
check(rod.code == 0 and m is not None, "plates with the axis rod: every load step converged")
if m:
    gap_rod = GAP0 - (m["solid_probe0_ux"] - m["solid_probe1_ux"])
    print(f"with the axis rod: gap {gap_rod*1e3:.4f} mm, {int(m['contact_axis_pairs'])} nodes on the "
          f"rod, closest {m['contact_axis_min_distance']*1e3:.4f} mm from its axis, Newton "
          f"{[r['newton'] for r in rod.monitor]}")
    check(m["contact_axis_pairs"] > 0, "the rod holds the plates' top edges")
    check(m["contact_axis_min_distance"] > 0.9 * 0.0004 and gap_rod > 0.0007,
          "the rod keeps the edges ~its radius from its axis (gap > 0.7 mm, not the offset)")
    check(max(r["newton"] for r in rod.monitor) <= 8, "Newton converges with the rod's tangent")

# Its Jacobian against finite differences on the small plates, the rod (0.32 mm) pressing on
# both top inner edges (0.3 mm from its axis) from the start.
rodfd = run(PLATES, extra=["-ts_max_steps", "1", "-ts_max_time", "0.125", "-snes_max_it", "3",
                           "-mesh_h", "0.001", "-mesh_params",
                           "fluid=0,g=0.0006,w=0.001,hp=0.002,t=0.0008,sy=0.00037,hb=0.77",
                           "-contact_offset", "0.00065", "-contact_penalty", "1e10",
                           "-contact_axis_radius", "0.00032", "-contact_axis",
                           "0.007,0,0.002,0,1,0", "-solid_probe_points", "",
                           "-snes_test_jacobian", "-snes_test_err", "1e-9", "-ts_adapt_type", "none"])
ratios = [float(x) for x in re.findall(r"\|\|J - Jfd\|\|_F/\|\|J\|\|_F = ([0-9.eE+-]+)", rodfd.out)]
print(f"with the axis rod: ||J - Jfd||/||J|| per iterate: {ratios}")
# Every iterate after the first (bound 2e-6: leaving the rod's curvature term -psi' H out of the
# tangent gives 4.4e-5 and 4.9e-6 there; with it, 2.3e-7).
check(len(ratios) >= 3 and max(ratios[1:]) < 2e-6,
      "contact Jacobian with the axis rod matches finite differences")

bad = [
    ("negative offset", ["-contact_offset", "-0.001"], "contact_offset"),
    ("ramp wider than the offset", ["-contact_ramp", "0.001"], "contact_ramp"),
    ("contact without the solid", ["-physics", "contact"], "contact"),
    ("missing contact surface", ["-contact_surface", "cusps"], "cusps"),
    ("negative axis rod radius", ["-contact_axis_radius", "-0.001"], "contact_axis_radius"),
    ("axis with 3 numbers", ["-contact_axis_radius", "0.001", "-contact_axis", "0,0,1"],
     "contact_axis"),
    ("axis with a zero direction", ["-contact_axis_radius", "0.001", "-contact_axis",
                                    "0,0,0,0,0,0"], "contact_axis"),
    ("gap seal without the fluid", ["-physics", "solid,contact,gap_seal"], "gap_seal"),
]
bad = [(n, e, k, PLATES) for n, e, k in bad] + [
    ("gap seal open below closed", ["-gap_seal_gap_open", "0.0005"], "gap_seal_gap_open",
     scene("plates_closing")),
    ("negative seal resistance", ["-gap_seal_resistance", "-1e7"], "gap_seal_resistance",
     scene("plates_closing")),
    ("negative coaptation height", ["-mesh_params", "coapt=-0.003"], "coapt", scene("valve_closing")),
    ("negative commissural post depth", ["-mesh_params", "post=-0.002"], "post", scene("valve_closing")),
]
for name, extra, needle, sc in bad:
    r = run(sc, extra=extra)
    lines = [l for l in r.out.splitlines() if "fsi_app: error:" in l]
    check(r.code == 2, f"{name}: exit 2 ({r.code})")
    check(len(lines) == 1 and needle in lines[0], f"{name}: one error line naming '{needle}'")
    check("PETSC ERROR" not in r.out, f"{name}: no PETSc traceback")
    if lines:
        print("   message:", lines[0])
finish()
