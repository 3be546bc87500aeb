"""Rigid-wall contact (-contact_walls; issue 16: the open valve's leaflets against their sinus
walls), tests/scenes/plates_wall.opts: two plates in a fluid box, plate a's outer face 1.2 mm from
the wall x = 0, both pushed towards it by a body force (25 m/s^2 over 30 ms), 2 ranks.
1. Plate a stops at the wall offset: its gap to the wall >= wall offset - max penetration, the
   penetration < 10 % of the offset, wall pairs active at the end, the monitored smallest gap the
   probe's; the same load carries plate b (not held by the wall) > 1.2 mm, so without the wall
   plate a would have passed it.
2. Plate b stops at the contact offset from plate a (wall and leaflet contact together).
3. Newton converges at every step (<= 6 iterations with both tangents; no cut step).
4. A curved, faceted wall (tests/scenes/plates_wall_curved.opts: a 6 mm cylinder, ~20 degree
   kinks): plate a reaches the wall and stops at its offset, Newton converges at every step
   (<= 6 iterations, no Newton failure; cuts for mesh distortion are allowed).  Each node's facet
   is picked once per Newton solve: picked at every evaluation, nodes on a kink flipped between
   two facets and this run failed at 41.9 ms (Newton stalled at any step size).
5. Bad input: an unknown wall group, a negative wall offset, a ramp wider than the wall offset,
   walls without a fluid: one error line naming the option, exit 2."""
from fsitest import check, finish, run, scene

WALL_GAP0, PLATE_GAP0, WALL_OFFSET, OFFSET = 0.0012, 0.002, 0.0008, 0.0005
SCENE = scene("plates_wall")

r = run(SCENE, np=2)
check(r.code == 0, f"plates against the wall: run completes ({r.code})")
rows = r.monitor
m = rows[-1]
gap_wall = WALL_GAP0 + m["solid_probe0_ux"]
gap_plates = PLATE_GAP0 - (m["solid_probe0_ux"] - m["solid_probe1_ux"])
pen = m["contact_max_penetration"]
print(f"plate a moved {-m['solid_probe0_ux']*1e3:.3f} mm, wall gap {gap_wall*1e3:.3f} mm "
      f"(offset {WALL_OFFSET*1e3} mm, smallest node gap {m['contact_wall_min_gap']*1e3:.3f} mm), "
      f"{int(m['contact_wall_pairs'])} wall pairs; plate b moved {-m['solid_probe1_ux']*1e3:.3f} "
      f"mm, plate gap {gap_plates*1e3:.3f} mm, {int(m['contact_pairs'])} pairs; max penetration "
      f"{pen*1e6:.1f} um")
check(m["contact_wall_pairs"] > 0, "wall contact active at the end")
check(gap_wall >= WALL_OFFSET - pen - 1e-9, "plate a stops at the wall offset")
check(m["contact_wall_min_gap"] <= gap_wall + 1e-9, "the monitored smallest wall gap is no larger "
      "than the probe's")
check(pen < 0.1 * WALL_OFFSET, "penetration < 10 % of the offset")
check(-m["solid_probe1_ux"] > WALL_GAP0, "the same load carries plate b past 1.2 mm")
check(m["contact_pairs"] > 0 and gap_plates >= OFFSET - pen - 1e-9,
      "plate b stops at the contact offset from plate a")
newton = [int(x["newton"]) for x in rows]
dts = {x["dt"] for x in rows}
print(f"Newton per step: {newton}")
check(max(newton) <= 6 and len(dts) == 1, "Newton <= 6 at every step, no step cut")

c = run(scene("plates_wall_curved"), np=2)
check(c.code == 0, f"curved wall: run completes ({c.code})")
crow = c.monitor
cm = crow[-1]
cnewton = [int(x["newton"]) for x in crow]
stalls = [l for l in c.out.splitlines() if "Newton did not converge" in l]
print(f"curved wall: {int(cm['contact_wall_pairs'])} wall pairs, smallest wall gap "
      f"{cm['contact_wall_min_gap']*1e3:.3f} mm (offset {WALL_OFFSET*1e3} mm), max penetration "
      f"{cm['contact_max_penetration']*1e6:.1f} um; Newton per step {cnewton}; "
      f"{len(stalls)} Newton failures")
check(cm["contact_wall_pairs"] > 0, "curved wall: wall contact active at the end")
check(cm["contact_wall_min_gap"] >= WALL_OFFSET - cm["contact_max_penetration"] - 1e-9 and
      cm["contact_max_penetration"] < 0.1 * WALL_OFFSET,
      "curved wall: the plate stops at the wall offset (penetration < 10 % of it)")
check(max(cnewton) <= 6 and not stalls, "curved wall: Newton <= 6 at every step, never fails")

bad = [
    ("unknown wall group", ["-contact_walls", "sinus"], "sinus"),
    ("negative wall offset", ["-contact_wall_offset", "-0.001"], "contact_wall_offset"),
    ("ramp wider than the wall offset", ["-contact_wall_offset", "0.0001"], "contact_ramp"),
    ("walls without a fluid", ["-physics", "solid,contact", "-mesh_params", "fluid=0"],
     "contact_walls"),
]
for name, extra, needle in bad:
    b = run(SCENE, extra=extra + ["-ts_max_steps", "1"])
    lines = [l for l in b.out.splitlines() if "fsi_app: error:" in l]
    check(b.code == 2, f"{name}: exit 2 ({b.code})")
    check(len(lines) == 1 and needle in lines[0], f"{name}: one error line naming '{needle}'")
    if lines:
        print("   message:", lines[0])
finish()
