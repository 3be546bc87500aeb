"""Hard solid cases.
1. Nearly incompressible (nu = 0.49) neo-Hookean cantilever bent to ~19 % of its length
   (tests/scenes/cantilever.opts): Newton converges (<= 6 iterations per load step) and the P2
   tip deflection with 2 elements through the thickness is within 2 % of the finest mesh's: no
   locking worth the name.  The same figure at nu = 0.3 is printed beside it.
2. An element inverts (bar pulled by 1 MPa in one load step): the run stops with exit code 3 and
   a message naming the inverted element, and the summary says converged = false; no NaN."""
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
r = run(os.path.join(SRC, "examples", "bar", "bar.opts"),
        extra=["-bc_zmax_value", "-1e6", "-ts_max_steps", "1", "-out_fields_every", "0"])
check(r.code == 3, f"inverted element: exit code {r.code} (expected 3)")
check("inverted" in r.out and "nan" not in r.out.lower(), "inverted element: message names it, no NaN printed")
check(r.summary["converged"] is False and "inverted" in r.summary["reason"], "summary: converged false, reason given")
finish()
