"""Compare two checkpoints (the state a restart resumes from): used by the restart and fault
tests."""
import h5py
import numpy as np
from fsitest import check


def state(path):
    with h5py.File(path) as f:
        return {k: f[k][()] for k in ("dofs/keys", "dofs/state", "vertices/keys",
                                      "vertices/mesh_displacement")}, dict(f.attrs)


def compare(a, b, what, solid_radius=None):
    """Relative L2 differences of the state: V_n (velocity and pressure), dt A_n (velocity
    components, against |V_n|), D_n (solid nodes only: elsewhere it is an unused sum), mesh
    displacement.  Two identical 2-rank runs differ by up to ~1e-13 in these measures (MUMPS's
    parallel factorisation is not bitwise reproducible), so 1e-12 tests the restart, not the
    solver's noise."""
    (sa, aa), (sb, ab) = state(a), state(b)
    check(aa["step"] == ab["step"] and abs(aa["time"] - ab["time"]) < 1e-15,
          f"{what}: same step and time ({aa['step']:.0f}, {ab['step']:.0f})")
    if sa["dofs/state"].shape != sb["dofs/state"].shape:
        check(False, f"{what}: state shapes differ")
        return
    keys, x, y = sa["dofs/keys"], sa["dofs/state"], sb["dofs/state"]
    vel = keys[:, 3] < 3
    # A_n in velocity units (dt A_n against |V_n|): two identical 2-rank tube runs differ by
    # 1.1e-12 in A_n itself (a difference quotient of V_n), 1.4e-13 in these units.
    dt = aa["dt"]
    parts = {"V": (x[:, 0], y[:, 0])}
    nA = np.linalg.norm(x[vel, 1] - y[vel, 1]) * dt / np.linalg.norm(x[vel, 0])
    if solid_radius:
        solid = vel & (np.hypot(keys[:, 0], keys[:, 1]) > solid_radius * (1 + 1e-9))
        parts["D"] = (x[solid, 2], y[solid, 2])
    parts["mesh"] = (sa["vertices/mesh_displacement"].ravel(),
                     sb["vertices/mesh_displacement"].ravel())
    worst, text = nA, [f"dt A {nA:.1e}"]
    for name, (u, v) in parts.items():
        n = np.linalg.norm(u)
        if n == 0:
            continue
        e = np.linalg.norm(u - v) / n
        worst = max(worst, e)
        text.append(f"{name} {e:.1e}")
    print(f"{what}: relative L2 differences " + ", ".join(text))
    check(worst < 1e-12, f"{what}: equal to 1e-12 ({worst:.1e})")
