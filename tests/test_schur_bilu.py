"""The coupled system's own Schur preconditioner (-pc_type schur_bilu, preset schur_bilu_fast):
the same preconditioner as PETSc's field split of fieldsplit_ilu_fast (upper Schur factorisation,
selfp, ILU(0) on velocity, BoomerAMG on Sp) without the split's copies of the velocity block, its
velocity ILU(0) with 3x3 node blocks stored in single precision by default.
* 1 rank, the factor in double precision: the field split's Krylov count at every step (the same
  ILU(0): a pattern of whole node blocks makes block and point ILU(0) one factorisation), the
  same answer;
* the factor in single precision: the same Krylov counts to within one iteration per step, the
  answer unchanged to the Newton tolerance;
* 2 ranks: the converged tube's answer (MUMPS), less memory than the field split; the added-mass
  stress test (rho_s = 10) and steps 10x the scene's converge and stay bounded;
* bad input: an unknown precision: one clear line, non-zero exit."""
import os
from fsitest import SRC, check, finish, run

tube = [os.path.join(SRC, "examples", "tube", "tube.opts")]
short = ["-mesh_h", "0.003", "-ts_max_steps", "20"]


def u_max(r):
    return max(abs(x["solid_probe0_ux"]) for x in r.monitor)


def krylov(r):
    return [int(x["krylov"]) for x in r.monitor]


# The field split's Sp preconditioner (BoomerAMG) and Krylov method (FGMRES), so that only the
# velocity factor's storage differs.
as_split = ["-schur_pc_type", "hypre", "-schur_pc_hypre_type", "boomeramg", "-ksp_type", "fgmres",
            "-allow_unused_options"]  # the preset's -schur_sub_pc_type
fs = run(tube, extra=short, presets=("fieldsplit_ilu_fast",))
dbl = run(tube, extra=short + as_split + ["-pc_schur_bilu_precision", "double"],
          presets=("schur_bilu_fast",))
sgl = run(tube, extra=short + as_split, presets=("schur_bilu_fast",))
check(fs.code == 0 and dbl.code == 0 and sgl.code == 0, "1 rank: the three preconditioners run")
if fs.code == 0 and dbl.code == 0 and sgl.code == 0:
    kf, kd, ks = krylov(fs), krylov(dbl), krylov(sgl)
    print("Krylov per step, field split:", kf)
    print("Krylov per step, schur_bilu double:", kd)
    print("Krylov per step, schur_bilu single:", ks)
    check(kd == kf, "1 rank: block ILU(0) in double gives the field split's Krylov count at every step")
    check(max(abs(a - b) for a, b in zip(ks, kd)) <= 1,
          "1 rank: the single-precision factor changes no step's Krylov count by more than 1")
    uf, ud, us = u_max(fs), u_max(dbl), u_max(sgl)
    check(abs(ud - uf) / uf < 1e-9, f"1 rank: double-precision factor, u_M as the field split's ({abs(ud - uf) / uf:.1e})")
    check(abs(us - uf) / uf < 1e-6, f"1 rank: single-precision factor, u_M within 1e-6 ({abs(us - uf) / uf:.1e})")

ref = run(tube, np=2, extra=short, presets=("direct",))
two = run(tube, np=2, extra=short, presets=("schur_bilu_fast",))
fs2 = run(tube, np=2, extra=short, presets=("fieldsplit_ilu_fast",))
check(ref.code == 0 and two.code == 0 and fs2.code == 0, "2 ranks: MUMPS, schur_bilu and the field split run")
if ref.code == 0 and two.code == 0 and fs2.code == 0:
    rel = abs(u_max(two) - u_max(ref)) / u_max(ref)
    check(rel < 1e-3, f"2 ranks: u_M within {rel:.1e} of MUMPS's converged answer (< 1e-3, the fast preset's bound)")
    mb = [x.summary["cost"]["peak_memory_mb_per_rank_max"] for x in (two, fs2)]
    print(f"2 ranks: peak memory per rank schur_bilu {mb[0]:.0f} MB, field split {mb[1]:.0f} MB")
    check(mb[0] < mb[1], "2 ranks: schur_bilu holds less memory than the field split")

# Hard cases on 2 ranks: the added-mass stress test (rho_s / rho_f = 0.01, where partitioned
# schemes fail; measured Newton 2, Krylov 15.3 per Newton) and steps 10x the scene's (Sp no
# longer mass-dominated: Krylov 47 per Newton against the field split's 41 with BoomerAMG).
for name, extra in (("rho_s = 10", ["-solid_rho", "10", "-ts_max_steps", "25"]),
                    ("dt = 1e-3 s", ["-ts_dt", "1e-3", "-ts_max_steps", "10"])):
    r = run(tube, np=2, extra=["-mesh_h", "0.002"] + extra, presets=("schur_bilu_fast",))
    check(r.code == 0, f"hard case {name}: converges with schur_bilu_fast")
    if r.code == 0:
        newton = max(int(x["newton"]) for x in r.monitor)
        check(newton <= 4, f"hard case {name}: Newton <= 4 per step (max {newton})")
        check(u_max(r) < 1e-3, f"hard case {name}: bounded (|u_M| = {1e3 * u_max(r):.4f} mm)")

bad = [("unknown factor precision", ["-pc_schur_bilu_precision", "half"], "half")]
for name, extra, needle in bad:
    r = run(tube, extra=short + extra, presets=("schur_bilu_fast",))
    lines = [l for l in r.out.splitlines() if "fsi_app: error:" in l]
    check(r.code != 0, f"{name}: non-zero exit ({r.code})")
    check(len(lines) == 1 and needle in lines[0], f"{name}: one error line naming '{needle}'")
    if lines:
        print("   message:", lines[0])
finish()
