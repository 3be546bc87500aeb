#!/usr/bin/python3
"""How far the leaflets stretch, from a field file of a valve run:
  /usr/bin/python3 scripts/leaflet_strain.py FIELDS.h5 STEP [--commissures 30,150,270]
For every leaflet cell (region 1 of the file: the solid), F from its four vertices (the P2 cell's
affine part) between the material reference (node + mesh displacement - solid displacement) and
the deformed position (node + mesh displacement); prints the distribution (median, 90th and 99th
percentile, max) of I1 - 3 (what the isotropic exponential term -solid_exp_c2 acts on) and of the
stretch along the chord between the commissures (what -solid_fibres chord acts on), by distance
from the axis.  A remeshed run writes its fields per mesh (remeshN_fields.h5): pick the file that
holds STEP."""
import sys

import h5py
import numpy as np

args = sys.argv[1:]
comm_deg = [30.0, 150.0, 270.0]
if "--commissures" in args:
    i = args.index("--commissures")
    comm_deg = [float(x) for x in args[i + 1].split(",")]
    del args[i:i + 2]
if len(args) != 2:
    sys.exit(__doc__)
fn = args[0]
try:
    step = int(args[1])
except ValueError:
    sys.exit(f"leaflet_strain: STEP must be a step number, got '{args[1]}'")
try:
    f = h5py.File(fn, "r")
except OSError:
    sys.exit(f"leaflet_strain: cannot read {fn} as an HDF5 field file (a run's fields.h5 or remeshN_fields.h5)")
with f:
    key = f"fields/displacement_{step:06d}"
    if key not in f:
        have = sorted(k for k in f.get("fields", {}).keys() if k.startswith("displacement_"))
        sys.exit(f"leaflet_strain: {fn} has no step {step}; it has: " + ", ".join(have))
    nodes = f["geometry/nodes"][:]
    cells = f["topology/cells"][:].astype(int)
    region = f["topology/region"][:].astype(int)
    u = f[key][:]
    dm = f[f"fields/mesh_displacement_{step:06d}"][:]
x = nodes + dm
X = x - u
tets = cells[region == 1][:, :4]
comm = np.sort(np.radians(comm_deg) % (2 * np.pi))
Xc = X[tets].mean(1)
# Chord direction: normal to the bisector of the commissure sector holding the cell's angle.
phi = np.arctan2(Xc[:, 1], Xc[:, 0]) % (2 * np.pi)
j = (np.searchsorted(comm, phi, side="right") - 1) % len(comm)
width = (np.roll(comm, -1) - comm) % (2 * np.pi)
mid = comm[j] + 0.5 * width[j]
a = np.stack([-np.sin(mid), np.cos(mid), np.zeros_like(mid)], 1)
dX = X[tets[:, 1:]] - X[tets[:, :1]]  # rows: edge vectors
dx = x[tets[:, 1:]] - x[tets[:, :1]]
F = np.linalg.solve(dX, dx).transpose(0, 2, 1)  # dx = dX F^T
lam = np.linalg.norm(np.einsum("nij,nj->ni", F, a), axis=1)
i1 = np.einsum("nij,nij->n", F, F) - 3
r = np.hypot(Xc[:, 0], Xc[:, 1])


def dist(v):
    return (f"median {np.median(v):.3f}, 90 % {np.percentile(v, 90):.3f}, "
            f"99 % {np.percentile(v, 99):.3f}, max {v.max():.3f}")


print(f"{fn}, step {step}: {len(tets)} leaflet cells")
print(f"  I1 - 3: {dist(i1)}")
print(f"  chord stretch: {dist(lam)}")
edges = np.linspace(0, r.max() * 1.0001, 5)
for lo, hi in zip(edges, edges[1:]):
    s = (r >= lo) & (r < hi)
    if s.any():
        print(f"  {lo*1e3:4.1f}-{hi*1e3:4.1f} mm from the axis ({s.sum()} cells): I1 - 3 90 % "
              f"{np.percentile(i1[s], 90):.3f}, chord stretch 90 % {np.percentile(lam[s], 90):.3f}")
