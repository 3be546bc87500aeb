"""Hard solid cases.
1. Nearly incompressible (nu = 0.49) neo-Hookean cantilever bent to ~19 % of its length
   (tests/scenes/cantilever.opts): Newton converges (<= 6 iterations per load step) and the P2
   tip deflection with 2 elements through the thickness is within 2 % of the finest mesh's: no
   locking worth the name.  The same figure at nu = 0.3 is printed beside it.
2. An element inverts (bar pulled by 1 MPa in one load step, step cutting off): the run stops
   with exit code 3 and a message naming the inverted element, and the summary says
   converged = false; no NaN.
3. Step cutting (issue 5): the bar at 150 kPa in ONE load step inverts, then diverges at half the
   step; cut to a quarter it converges, grows back, and ends at the answer of 8 load steps
   (a static hyperelastic solution does not depend on the load path) to 1e-6; every cut is logged.
   With -ts_adapt_dt_min above what the load needs, the run stops at the minimum with exit 3, the
   reason, and a checkpoint of the last converged state."""
from fsitest import check, finish, run, scene

tips = {}
for nu in ("0.3", "0.49"):
    for h in ("0.05", "0.033", "0.025"):
        r = run(scene("cantilever"), extra=["-solid_nu", nu, "-mesh_h", h])
        ok = r.code == 0
        check(ok, f"nu = {nu}, h = {h}: run succeeds")
        if not ok:
            continue
        newton = [int(row["newton"]) for row in r.monitor]
        check(max(newton) <= 6, f"nu = {nu}, h = {h}: Newton per load step {newton} (<= 6)")
        tips[(nu, h)] = r.monitor[-1]["solid_probe0_ux"]
for nu in ("0.3", "0.49"):
    if (nu, "0.05") in tips and (nu, "0.025") in tips:
        c, f = tips[(nu, "0.05")], tips[(nu, "0.025")]
        print(f"nu = {nu}: tip deflection {c:.5f} m (2 elements through the thickness) vs "
              f"{f:.5f} m (4 elements): {100 * (c - f) / f:+.2f} %")
        if nu == "0.49":
            check(abs(c - f) / f < 0.02, f"nu = 0.49: coarse P2 within 2 % of the fine mesh ({100 * (c - f) / f:+.2f} %)")

import os
from fsitest import SRC
bar = os.path.join(SRC, "examples", "bar", "bar.opts")
r = run(bar, extra=["-bc_zmax_value", "-1e6", "-ts_max_steps", "1", "-out_fields_every", "0",
                    "-ts_adapt_type", "none"])
check(r.code == 3, f"inverted element: exit code {r.code} (expected 3)")
check("inverted" in r.out and "nan" not in r.out.lower(), "inverted element: message names it, no NaN printed")
check(r.summary["converged"] is False and "inverted" in r.summary["reason"], "summary: converged false, reason given")

ref = run(bar, extra=["-bc_zmax_value", "-1.5e5", "-ts_max_steps", "8", "-out_fields_every", "0"])
cut = run(bar, extra=["-bc_zmax_value", "-1.5e5", "-ts_max_steps", "1", "-out_fields_every", "0"])
check(ref.code == 0 and cut.code == 0, "150 kPa: 8 load steps and 1 cut load step both succeed")
if ref.code == 0 and cut.code == 0:
    sc = cut.summary["step_control"]
    logged = [l for l in cut.out.splitlines() if "retrying with dt" in l]
    print(f"one load step: {sc['failed_steps']} failures, {sc['cuts']} cuts, {sc['grows']} grows, "
          f"{cut.summary['steps']} accepted steps (dt {[r['dt'] for r in cut.monitor]})")
    for l in logged:
        print("   ", l[:160])
    check(sc["cuts"] >= 1 and len(logged) == sc["failed_steps"], "every cut is logged")
    a, b = ref.monitor[-1]["solid_probe0_uz"], cut.monitor[-1]["solid_probe0_uz"]
    print(f"end displacement {b:.9e} m (cut) vs {a:.9e} m (8 steps)")
    check(abs(a - b) < 1e-6 * abs(a), f"cut run reaches the 8-step answer ({abs(a - b) / abs(a):.1e})")
    check(abs(cut.monitor[-1]["time"] - 1) < 1e-12, "it lands exactly on the end of the load")

stop = run(bar, extra=["-bc_zmax_value", "-1.5e5", "-ts_max_steps", "1", "-out_fields_every", "0",
                       "-ts_adapt_dt_min", "0.4"])
check(stop.code == 3, f"dt at its minimum: exit code {stop.code} (expected 3)")
check(stop.summary["converged"] is False and "ts_adapt_dt_min" in stop.summary["reason"]
      and "checkpoint" in stop.summary["reason"], "reason names -ts_adapt_dt_min and the checkpoint")
check(os.path.exists(os.path.join(stop.dir, "checkpoint.h5")), "checkpoint of the last converged state written")
finish()
