"""Wall shear stress and its indices (issue 5, paper eqs. 13-16) on the deformed-configuration
faces of -hemo_surfaces:
1. Poiseuille (steady, exact traction): tau_w against G R / 2, area-L2 over the wall < 2 %, area
   mean < 1 %; in time-dependent mode (5 steps) OSI = 0 on every face.
2. Womersley (zero-mean oscillation, one period): tau_w(t) against the closed form on two meshes
   (36 and 48 elements around): L2 error over the wall, relative to its peak over the period,
   < 2 % on the finer and decreasing at order >= 1; OSI ~ 0.5 everywhere.
3. OSI in [0, 0.5] on every face, TAWSS <= time-averaged |WSS|, RRT = 1 / TAWSS; the surface file
   (hemo.h5 + hemo.xdmf) has the instantaneous maps and the window's indices; no hemo file when the
   scene does not ask for it."""
import math
import os
import h5py
import numpy as np
from fsitest import check, finish, run, scene, fit_order

G, R = 10.0, 0.005
r = run(scene("poiseuille"), np=2, extra=["-hemo_surfaces", "wall", "-out_fields_every", "1"])
check(r.code == 0, "Poiseuille run succeeds")
m = r.monitor[-1]
l2 = m["wall_wss_err_l2"] / m["wall_wss_exact_l2"]
mean = m["wall_wss_mean"] / (G * R / 2) - 1
print(f"Poiseuille: |tau_w| area mean {m['wall_wss_mean']:.6f} Pa (exact {G*R/2:.6f}, "
      f"{100*mean:+.3f} %), L2 error {100*l2:.3f} %, max |tau_w| {m['wall_wss_max']:.6f} Pa")
check(abs(mean) < 0.01, f"Poiseuille area-mean WSS within 1 % ({100*mean:+.3f} %)")
check(l2 < 0.02, f"Poiseuille WSS L2 error over the wall < 2 % ({100*l2:.3f} %)")
with h5py.File(os.path.join(r.dir, "hemo.h5")) as f:
    wss = f["wall/step_1/wss"][()]
    n = f["wall/reference_points"].shape[0] // 3
    check(wss.shape == (n, 3) and f["wall/triangles"].shape == (n, 3),
          f"hemo.h5: {n} wall faces with a WSS vector each")
    # the wall shear of a flow along +z points along +z (the fluid drags the wall downstream)
    check(np.all(wss[:, 2] > 0), "Poiseuille WSS points downstream on every face")
check(os.path.exists(os.path.join(r.dir, "hemo.xdmf")), "hemo.xdmf written")

r = run(scene("poiseuille"), np=1, extra=["-hemo_surfaces", "wall", "-ts_type", "alpha",
        "-ic", "exact", "-ts_dt", "0.1", "-ts_max_steps", "5"])
check(r.code == 0, "Poiseuille time-dependent run succeeds")
h = r.summary["hemodynamics"]["wall"]
print(f"steady flow over 5 steps: OSI in [{h['osi_min']:.2e}, {h['osi_max']:.2e}]")
check(h["osi_max"] < 1e-6, f"steady flow: OSI = 0 on every face to 1e-6 (max {h['osi_max']:.1e})")
r = run(scene("poiseuille"), np=1)
check(not os.path.exists(os.path.join(r.dir, "hemo.h5")) and "hemodynamics" not in r.summary,
      "no -hemo_surfaces: no wall-shear file, no hemodynamics in the summary")

errs, hs = [], []
for nc in (36, 48):
    r = run(scene("womersley"), np=2, extra=[
        "-hemo_surfaces", "wall", "-mesh_params", f"R=0.005,L=0.01,ncirc={nc}", "-mesh_h", "0.001"])
    check(r.code == 0, f"Womersley ncirc = {nc} succeeds")
    if r.code:
        continue
    rows = r.monitor
    peak = max(row["wall_wss_exact_l2"] for row in rows)
    e = max(row["wall_wss_err_l2"] for row in rows) / peak
    errs.append(e)
    hs.append(2 * math.pi * R / nc)
    h = r.summary["hemodynamics"]["wall"]
    print(f"Womersley ncirc = {nc}: WSS error {100*e:.3f} % of its peak; OSI area mean "
          f"{h['osi_area_mean']:.5f} in [{h['osi_min']:.5f}, {h['osi_max']:.5f}]")
    check(0.45 < h["osi_min"] and h["osi_max"] <= 0.5,
          f"zero-mean oscillation: OSI ~ 0.5 on every face ([{h['osi_min']:.4f}, {h['osi_max']:.4f}])")
    with h5py.File(os.path.join(r.dir, "hemo.h5")) as f:
        w = f["wall/window_0"]
        osi, tawss, mag, rrt = (w[k][()] for k in ("osi", "tawss", "wss_magnitude_mean", "rrt"))
    check(np.all((osi >= 0) & (osi <= 0.5)), "OSI in [0, 0.5] on every face")
    check(np.all(tawss <= mag * (1 + 1e-12)), "TAWSS <= time-averaged |WSS| on every face")
    check(np.allclose(rrt * tawss, 1, rtol=1e-12), "RRT = 1 / TAWSS")
if len(errs) == 2:
    p = fit_order(hs, errs)
    print(f"Womersley WSS: errors {100*errs[0]:.3f} %, {100*errs[1]:.3f} %, observed order {p:.2f}")
    check(errs[1] < 0.02, f"Womersley WSS within 2 % on the finer mesh ({100*errs[1]:.3f} %)")
    check(p >= 1.0, f"Womersley WSS error decreases at order >= 1 ({p:.2f})")
finish()
