"""1 rank against 2 ranks: the same scene gives the same results to 1e-8 relative (direct solver),
for the moving-mesh Ethier-Steinman flow (errors, 4 steps) and the Poiseuille pipe (monitors);
and the moving-mesh case on 2 ranks with the mesh's points as read instead of in reverse
Cuthill-McKee order (-mesh_reorder none: other dof numbers, other partition) gives the same
results too."""
from fsitest import check, finish, run, scene

cases = [("ethier_steinman", ["-mesh_h", "0.25", "-ale_motion", "prescribed", "-ale_amplitude", "0.1", "-ale_time", "0.02"]),
         ("poiseuille", [])]
cases += [("ethier_steinman", cases[0][1], cases[0][1] + ["-mesh_reorder", "none"])]
for case in cases:
    name, extra = case[0], case[1]
    r1 = run(scene(name), np=1, extra=extra)
    r2 = run(scene(name), np=2, extra=case[2] if len(case) > 2 else extra)
    check(r1.code == 0 and r2.code == 0, f"{name}: both runs succeed")
    check(r2.summary["ranks"] == 2, f"{name}: second run used 2 ranks")
    m1, m2 = r1.monitor, r2.monitor
    check(len(m1) == len(m2), f"{name}: same number of steps")
    worst = 0.0
    for a, b in zip(m1, m2):
        for k in a:
            if k in ("step_seconds", "newton", "krylov"):
                continue
            scale = max(abs(a[k]), abs(b[k]), 1e-30)
            if abs(a[k]) < 1e-14 and abs(b[k]) < 1e-14:
                continue  # both zero to round-off
            worst = max(worst, abs(a[k] - b[k]) / scale)
    print(f"{name}: worst relative difference over all monitor columns and steps: {worst:.2e}")
    what = "1 rank vs 2 ranks in RCM order" if len(case) > 2 else "1 vs 2 ranks"
    check(worst < 1e-8, f"{name}: {what} agree to {worst:.1e} < 1e-8")
finish()
