"""Both solver presets (MUMPS LU and the Schur field split with BoomerAMG) converge on the
fluid scenes and agree to the solver tolerance, on 2 ranks.  The FSI tube's fast preset
(fieldsplit_ilu_fast: Newton to 1e-4, inexact Newton aimed at it, one Jacobian per step, Newton
started from the extrapolated velocity) gives the converged answer, its inexact linear solves take
fewer Krylov iterations than exact ones, and its predictor saves Newton iterations."""
import os
from fsitest import SRC, check, finish, run, scene

cases = [("ethier_steinman", ["-mesh_h", "0.25"], ["err_v_l2", "err_p_l2"]),
         ("poiseuille", [], ["outlet_flux", "wall_fz"]),
         ("womersley", ["-ts_max_time", "0.25"], ["probe0_vz", "outlet_flux"])]
for name, extra, keys in cases:
    a = run(scene(name), np=2, extra=extra, presets=("direct",))
    b = run(scene(name), np=2, extra=extra + ["-ksp_rtol", "1e-11"], presets=("fieldsplit",))
    check(a.code == 0, f"{name}: direct preset converges")
    check(b.code == 0, f"{name}: fieldsplit preset converges")
    if a.code or b.code:
        continue
    its = b.summary["iterations"]
    print(f"{name}: fieldsplit Krylov iterations {its['krylov_total']} over {its['newton_total']} Newton steps")
    for k in keys:
        x, y = a.monitor[-1][k], b.monitor[-1][k]
        # Error norms are compared relative to the size of the solution (norm = err / err_rel),
        # monitors relative to their own size: both measure the solver's accuracy.
        scale = abs(x) / a.monitor[-1][k.replace("_l2", "_rel")] if k.startswith("err_") else abs(x)
        rel = abs(x - y) / max(scale, 1e-300)
        check(rel < 1e-6, f"{name}: {k} agrees between presets ({rel:.1e})")

# The tube (coarse, h 3 mm, 30 steps): MUMPS to PETSc's 1e-8 against fieldsplit_ilu_fast, and
# the fast preset with its inexact solves switched off (-newton_inexact_gamma 0).
tube = [os.path.join(SRC, "examples", "tube", "tube.opts")]
short = ["-mesh_h", "0.003", "-ts_max_steps", "30"]
ref = run(tube, np=2, extra=short, presets=("direct",))
fast = run(tube, np=2, extra=short, presets=("fieldsplit_ilu_fast",))
exact = run(tube, np=2, extra=short + ["-newton_inexact_gamma", "0"],
            presets=("fieldsplit_ilu_fast",))
const = run(tube, np=2, extra=short + ["-ts_predictor", "constant"],
            presets=("fieldsplit_ilu_fast",))
check(ref.code == 0 and fast.code == 0 and exact.code == 0, "tube: direct and fast presets run")
check(const.code == 0, "tube: the fast preset with the constant predictor runs")
if ref.code == 0 and fast.code == 0 and exact.code == 0:
    ux = [max(abs(r["solid_probe0_ux"]) for r in x.monitor) for x in (ref, fast)]
    rel = abs(ux[0] - ux[1]) / ux[0]
    # One Newton iteration from V_n + dt A_n stops just under the 1e-4 residual: a larger, still
    # small, error than two from V_n (the bound on u_M is 0.2 %).
    check(rel < 1e-3, f"tube: point M's largest displacement within {rel:.1e} of the converged one (< 1e-3)")
    k_fast, k_exact = (x.summary["iterations"]["krylov_total"] for x in (fast, exact))
    check(k_fast < 0.8 * k_exact,
          f"tube: inexact Newton takes fewer Krylov iterations ({k_fast} against {k_exact})")
    # Newton's first iterate V_n + dt A_n (the preset's -ts_predictor extrapolated) against V_n
    # (measured: 32 Newton iterations in 30 steps against 60; point M within 1.0-1.2e-4 of the
    # converged answer against 1.5e-5-2.9e-5 with V_n, depending on the partition).
    if const.code == 0:
        n_ext, n_const = (x.summary["iterations"]["newton_total"] for x in (fast, const))
        check(n_ext < 0.6 * n_const,
              f"tube: the extrapolated predictor needs fewer Newton iterations ({n_ext} against {n_const})")
        ux_c = max(abs(r["solid_probe0_ux"]) for r in const.monitor)
        rel_c = abs(ux[0] - ux_c) / ux[0]
        check(rel_c < 1e-4,
              f"tube: with V_n, point M's largest displacement agrees with the converged one ({rel_c:.1e})")

# The velocity block's ILU factored in place (-fieldsplit_velocity_sub_pc_factor_in_place: no
# second copy of the block), rebuilt every 2nd Jacobian so that PETSc refills the factored copy
# many times (without CoupledSystem::in_place_presolve it stops at the first rebuild: "Not for
# factored matrix"), on 2 ranks and on 1 (the block is then the split's matrix itself).
if fast.code == 0:
    ux_fast = max(abs(r["solid_probe0_ux"]) for r in fast.monitor)
    for np_ in (2, 1):
        ip = run(tube, np=np_, extra=short + ["-fieldsplit_velocity_sub_pc_factor_in_place",
                                              "-snes_lag_preconditioner", "2"],
                 presets=("fieldsplit_ilu_fast",))
        check(ip.code == 0, f"tube, {np_} rank(s): ILU in place with rebuilds runs")
        if ip.code == 0:
            ux_ip = max(abs(r["solid_probe0_ux"]) for r in ip.monitor)
            rel = abs(ux_ip - ux_fast) / ux_fast
            check(rel < 1e-4, f"tube, {np_} rank(s): ILU in place gives the fast preset's u_M ({rel:.1e})")

# A lagged LU (direct_lagged: MUMPS reused by GMRES over steps) rebuilt whenever a linear solve
# took more than 3 Krylov iterations (-newton_pc_rebuild_krylov): the rebuilds happen, GMRES
# needs fewer iterations, the answer is the same to the Newton tolerance.
short10 = ["-mesh_h", "0.003", "-ts_max_steps", "10"]
lag = run(tube, np=2, extra=short10, presets=("direct_lagged",))
fresh = run(tube, np=2, extra=short10 + ["-newton_pc_rebuild_krylov", "3"], presets=("direct_lagged",))
check(lag.code == 0 and fresh.code == 0, "tube: direct_lagged with and without forced rebuilds runs")
if lag.code == 0 and fresh.code == 0:
    n = [x.summary["cost"]["preconditioner_rebuilds_forced"] for x in (lag, fresh)]
    k = [x.summary["iterations"]["krylov_total"] for x in (lag, fresh)]
    ux = [max(abs(r["solid_probe0_ux"]) for r in x.monitor) for x in (lag, fresh)]
    rel = abs(ux[0] - ux[1]) / ux[0]
    print(f"tube, lagged LU: forced rebuilds {n}, Krylov {k}, u_M {ux[0]:.6e} vs {ux[1]:.6e}")
    check(n[0] == 0 and n[1] > 0, "-newton_pc_rebuild_krylov forces rebuilds (and only with it)")
    check(k[1] < k[0], "a rebuilt LU needs fewer GMRES iterations")
    check(rel < 1e-5, f"the same answer with forced rebuilds ({rel:.1e})")
finish()
