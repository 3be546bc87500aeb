"""Ethier-Steinman exact Navier-Stokes flow on three meshes: observed L2 orders of the P2/P1
velocity and pressure (>= 2.8 and >= 1.8), on a fixed mesh or (--moving) on a mesh moved by a
prescribed smooth motion, which exercises the ALE convection and the moving-geometry terms;
--skew uses the skew-symmetric convection (Temam's term is consistent: the orders must stay);
--grad-div adds the grad-div penalty gamma (div v, div w) with gamma = 5 mu (consistent: the orders
must stay) and checks that it does its job: ||div v_h|| on the finer mesh at least 1.5x smaller than
without it (measured 0.0809 -> 0.0415, 1.95x) and the velocity error not larger."""
import sys
from fsitest import check, finish, fit_order, order, run, scene

moving = "--moving" in sys.argv
skew = "--skew" in sys.argv
grad_div = "--grad-div" in sys.argv
extra = ["-ale_motion", "prescribed", "-ale_amplitude", "0.1", "-ale_time", "0.02"] if moving else []
extra += ["-fluid_convection", "skew_symmetric"] if skew else []
sizes = [0.5, 0.25] if skew else [0.5, 0.25, 0.16667]  # skew: the two coarse meshes (CI time)
if grad_div:
    plain = run(scene("ethier_steinman"), extra=["-mesh_h", str(sizes[-1])] + extra)
    check(plain.code == 0, "without grad-div: run succeeds")
    extra += ["-fluid_grad_div", "1"]  # [Pa s], 5x the scene's viscosity
res = []
for h in sizes:
    r = run(scene("ethier_steinman"), extra=["-mesh_h", str(h)] + extra)
    check(r.code == 0, f"h={h}: run succeeds")
    s = r.summary
    e = s["error_final"]
    heff = (8.0 / s["cells"]) ** (1.0 / 3.0)  # [-1,1]^3 has volume 8
    res.append((heff, e["velocity_l2"], e["pressure_l2"]))
    print(f"h={h} cells={s['cells']} h_eff={heff:.4f} |e_v|={e['velocity_l2']:.4e} |e_p|={e['pressure_l2']:.4e}")
for (h0, v0, p0), (h1, v1, p1) in zip(res, res[1:]):
    ov, op = order(v0, v1, h0, h1), order(p0, p1, h0, h1)
    print(f"orders between h_eff {h0:.3f} and {h1:.3f}: velocity {ov:.2f}, pressure {op:.2f}")
# Fit over all meshes (least squares in log-log) is the asserted order.
hs = [h for h, _, _ in res]
ov = fit_order(hs, [v for _, v, _ in res])
op = fit_order(hs, [p for _, _, p in res])
tag = ("moving mesh" if moving else "fixed mesh") + (", skew-symmetric convection" if skew else "")
tag += ", grad-div" if grad_div else ""
if grad_div:
    e0, e1 = plain.summary["error_final"], r.summary["error_final"]
    print(f"finest mesh without / with grad-div: ||div v_h|| {e0['divergence_l2']:.4e} / "
          f"{e1['divergence_l2']:.4e}, |e_v| {e0['velocity_l2']:.4e} / {e1['velocity_l2']:.4e}")
    check(e1["divergence_l2"] * 1.5 <= e0["divergence_l2"],
          f"grad-div lowers ||div v_h|| at least 1.5x ({e0['divergence_l2'] / e1['divergence_l2']:.2f}x)")
    check(e1["velocity_l2"] <= e0["velocity_l2"], "grad-div does not raise the velocity error")
check(ov >= 2.8, f"{tag}: velocity L2 order {ov:.2f} >= 2.8")
check(op >= 1.8, f"{tag}: pressure L2 order {op:.2f} >= 1.8")
finish()
