"""Both solver presets (MUMPS LU and the Schur field split with BoomerAMG) converge on the
fluid scenes and agree to the solver tolerance, on 2 ranks."""
from fsitest import check, finish, run, scene

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
finish()
