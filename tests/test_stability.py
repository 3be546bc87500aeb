"""Stability suite, first cases (ctest -L stability).  Each case states its pass criterion:
1. Gravity, large deflection, steady (tests/scenes/cantilever_gravity.opts: a 1 m cantilever
   drooping ~20 % of its length under its own weight, St Venant-Kirchhoff): one load step
   converges (gravity used to be applied in full at every load step and PETSc's divergence
   test stopped Newton: DIVERGED_DTOL at every step cut); the tip deflection is within 15 % of
   linear beam theory's 0.20 m, below it (geometric stiffening) and the tip moves towards the
   clamp; four load steps (gravity ramped) give the same answer to 1e-6 m with <= 6 Newton per
   step.
2. Gravity, dynamic, 2 ranks: the same beam released from rest under gravity (generalized
   alpha, 20 steps of 10 ms): every step converges, no NaN, and the tip stays within twice the
   static deflection (a suddenly applied load overshoots at most 2x without damping).
3. Absurd sizes and values are refused before they run: -mesh_h 1e-9 on the tube (it used to
   abort inside gmsh with a backtrace, exit 134) and non-finite numbers: exit 2, one error line
   naming the option, no backtrace, in seconds.
4. `scripts/run tube -out_dir X` puts the whole run, monitor.png included, into X (it used to draw
   monitor.png into results/tube)."""
import math
import os
import subprocess
import tempfile
import time
from fsitest import ENV, SRC, check, finish, run, scene

CG = scene("cantilever_gravity")
L, BEAM = 1.0, 0.20  # length, linear-theory tip deflection [m]

one = run(CG, extra=["-ts_max_steps", "1"])
four = run(CG, extra=["-ts_max_steps", "4"])
check(one.code == 0 and four.code == 0, "steady gravity: 1 and 4 load steps converge")
if one.code == 0 and four.code == 0:
    a, b = one.monitor[-1], four.monitor[-1]
    ux, uz = a["solid_probe0_ux"], a["solid_probe0_uz"]
    print(f"tip: deflection {ux:.4f} m ({100 * ux / L:.1f} % of L; beam theory {BEAM} m), "
          f"axial {uz:+.4f} m; Newton {int(a['newton'])} in one step, "
          f"{[int(x['newton']) for x in four.monitor]} in four")
    check(0.85 * BEAM <= ux < BEAM, f"tip deflection {ux:.4f} m within 15 % below beam theory")
    check(uz < -0.01, f"tip moves towards the clamp ({uz:+.4f} m)")
    check(abs(b["solid_probe0_ux"] - ux) < 1e-6, "4 load steps = 1 load step (1e-6 m)")
    check(max(int(x["newton"]) for x in four.monitor) <= 6, "<= 6 Newton per load step")

dyn = run(CG, np=2, extra=["-ts_type", "alpha", "-ts_dt", "0.01", "-ts_max_steps", "20",
                           "-snes_linesearch_type", "bt"])
check(dyn.code == 0, "dynamic gravity, 2 ranks: 20 steps converge")
if dyn.code == 0 and one.code == 0:
    u = [x["solid_probe0_ux"] for x in dyn.monitor]
    static = one.monitor[-1]["solid_probe0_ux"]
    check(all(math.isfinite(v) for v in u) and max(u) <= 2 * static,
          f"tip bounded: max {max(u):.4f} m <= 2 x static {static:.4f} m")

bad = [(os.path.join(SRC, "examples", "tube", "tube.opts"), ["-mesh_h", "1e-9"], "mesh_h"),
       (scene("poiseuille"), ["-fluid_mu", "nan"], "fluid_mu"),
       (scene("poiseuille"), ["-ts_type", "alpha", "-ts_dt", "inf"], "ts_dt"),
       (CG, ["-solid_gravity", "0,nan,0"], "solid_gravity")]
for opts, extra, name in bad:
    t0 = time.time()
    r = run(opts, extra=extra)
    lines = [l for l in r.out.splitlines() if "fsi_app: error:" in l]
    check(r.code == 2 and len(lines) == 1 and name in lines[0] and "PETSC ERROR" not in r.out
          and "terminate called" not in r.out and time.time() - t0 < 30,
          f"{' '.join(extra)}: exit {r.code} in {time.time() - t0:.1f} s: "
          + (lines[0] if lines else "no error line"))

out = os.path.join(tempfile.mkdtemp(), "tube_run")
png = os.path.join(SRC, "results", "tube", "monitor.png")
before = os.path.getmtime(png) if os.path.exists(png) else None
p = subprocess.run([os.path.join(SRC, "scripts", "run"), "tube", "-out_dir", out, "-ts_max_steps", "2"],
                   cwd=SRC, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                   timeout=600)
after = os.path.getmtime(png) if os.path.exists(png) else None
check(p.returncode == 0 and os.path.exists(os.path.join(out, "monitor.png")) and before == after,
      f"scripts/run tube -out_dir X: exit {p.returncode}, monitor.png in X, results/tube untouched")
finish()
