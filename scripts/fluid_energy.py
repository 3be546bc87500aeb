"""The fluid's kinetic-energy budget from a run's written fields: is the flow losing energy the way
viscosity says, or is the discretisation feeding it?

  /usr/bin/python3 scripts/fluid_energy.py FIELDS.h5 [--rho 1050] [--mu 0.004] [--every K]

For each written step of FIELDS.h5 (fields_*.h5 or remesh*_fields.h5 of a run; region 0 = fluid),
on the P2 velocity, with a 125-point rule per tet:
  kinetic energy      E = int rho/2 |v|^2                                   [J]
  viscous dissipation D = int 2 mu D(v):D(v)                                [W]
  spurious power      P = int rho/2 (div v) |v|^2                           [W]
P is the power the convective form rho (grad v) v puts into the flow because Taylor-Hood's velocity
is only weakly divergence-free; the skew-symmetric form (-fluid_convection skew_symmetric) removes
it.  P comparable to D, or a cell where P is many times its own D, means the convective form is
driving the flow (docs/valve.md, "Diastole blew up in the coarse aorta")."""
import argparse
import sys

import h5py
import numpy as np

EDGES = [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)]


def rule(n=5):
    """Conical-product rule on the reference tet (exact to degree 2n-1 - 2), weights sum to 1/6."""
    g, w = np.polynomial.legendre.leggauss(n)
    g, w = 0.5 * (g + 1), 0.5 * w
    pts, wts = [], []
    for i, a in enumerate(g):
        for j, b in enumerate(g):
            for k, c in enumerate(g):
                pts.append((a, b * (1 - a), c * (1 - a) * (1 - b)))
                wts.append(w[i] * w[j] * w[k] * (1 - a) ** 2 * (1 - b))
    return np.array(pts), np.array(wts)


def p2(p):
    l = np.array([1 - p[0] - p[1] - p[2], p[0], p[1], p[2]])
    dl = np.array([[-1, -1, -1], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    N = [l[i] * (2 * l[i] - 1) for i in range(4)] + [4 * l[a] * l[b] for a, b in EDGES]
    dN = [(4 * l[i] - 1) * dl[i] for i in range(4)] + [4 * (l[a] * dl[b] + l[b] * dl[a]) for a, b in EDGES]
    return np.array(N), np.array(dN)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("fields")
    ap.add_argument("--rho", type=float, default=1050.0, help="fluid density [kg/m^3]")
    ap.add_argument("--mu", type=float, default=0.004, help="dynamic viscosity [Pa s]")
    ap.add_argument("--every", type=int, default=1, help="every K-th written step")
    a = ap.parse_args()
    try:
        f = h5py.File(a.fields, "r")
        X = f["geometry/nodes"][:]
        C = f["topology/cells"][:].astype(int)
        R = f["topology/region"][:]
    except (OSError, KeyError) as e:
        sys.exit(f"fluid_energy: cannot read P2 fields from {a.fields} ({e}); give a run's fields_*.h5")
    if C.shape[1] != 10:
        sys.exit(f"fluid_energy: {a.fields} holds {C.shape[1]}-node cells, not P2 tets")
    C = C[R == 0]
    V = X[C[:, :4]]
    # Which stored edge node is the midpoint of which vertex pair (straight-sided cells).
    slot = np.zeros((len(C), 6), int)
    for e in range(6):
        M = X[C[:, 4 + e]]
        d = [np.linalg.norm(M - 0.5 * (V[:, i] + V[:, j]), axis=1) for i, j in EDGES]
        slot[:, e] = np.argmin(np.array(d), axis=0)
    J = np.stack([V[:, 1] - V[:, 0], V[:, 2] - V[:, 0], V[:, 3] - V[:, 0]], axis=2)
    det, Jinv = np.abs(np.linalg.det(J)), np.linalg.inv(J)
    centre = V.mean(axis=1)
    pts, wts = rule()
    shapes = [p2(p) for p in pts]
    steps = sorted(k[len("velocity_"):] for k in f["fields"].keys() if k.startswith("velocity_"))
    print(f"{'step':>7} {'E [J]':>10} {'D [W]':>10} {'P [W]':>11} {'P/D':>6}  worst cell: P, its D, centre [m]")
    for s in steps[:: a.every]:
        v = f["fields/velocity_" + s][:]
        ve = np.zeros((len(C), 10, 3))
        ve[:, :4] = v[C[:, :4]]
        for e in range(6):
            ve[np.arange(len(C)), 4 + slot[:, e]] = v[C[:, 4 + e]]
        E, D, P = (np.zeros(len(C)) for _ in range(3))
        for (N, dN), w in zip(shapes, wts):
            vq = np.einsum("a,cai->ci", N, ve)
            G = np.einsum("cai,cak->cik", ve, np.einsum("aj,cjk->cak", dN, Jinv))
            S = 0.5 * (G + G.transpose(0, 2, 1))
            v2 = (vq**2).sum(1)
            E += w * det * 0.5 * a.rho * v2
            D += w * det * 2 * a.mu * (S**2).sum((1, 2))
            P += w * det * 0.5 * a.rho * np.trace(G, axis1=1, axis2=2) * v2
        i = np.argmax(P)
        print(f"{int(s):7d} {E.sum():10.3e} {D.sum():10.3e} {P.sum():+11.3e} {P.sum() / D.sum():6.2f}  "
              f"{P[i]:.2e} {D[i]:.2e} ({centre[i][0]:.4f}, {centre[i][1]:.4f}, {centre[i][2]:.4f})")


if __name__ == "__main__":
    main()
