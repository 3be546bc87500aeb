"""1 rank against 2 ranks: the same scene gives the same results to 1e-8 relative (direct solver),
for the moving-mesh Ethier-Steinman flow (errors, 4 steps) and the Poiseuille pipe (monitors)."""
from fsitest import check, finish, run, scene

cases = [("ethier_steinman", ["-mesh_h", "0.25", "-ale_motion", "prescribed", "-ale_amplitude", "0.1", "-ale_time", "0.02"]),
         ("poiseuille", [])]
for name, extra in cases:
    r1 = run(scene(name), np=1, extra=extra)
    r2 = run(scene(name), np=2, extra=extra)
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
    check(worst < 1e-8, f"{name}: 1 vs 2 ranks agree to {worst:.1e} < 1e-8")
finish()
