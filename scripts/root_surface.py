"""A patient's aortic-root surface, read and checked for a valve scene (docs/patient_valve.md):
  /usr/bin/python3 scripts/root_surface.py ROOT LANDMARKS.json [--unit mm|cm|m] [--tol MM]
                                            [--json FRAME.json]
ROOT (STL, binary or ASCII, legacy VTK or gmsh .msh, read by gmsh; VTP, read by VTK) is the
lumen's wall, closed apart from its two open ends (the ventricular and the aortic cut), normals
pointing out of the blood.  LANDMARKS.json, in
the surface's unit: {"commissures": [3 points], "sinus_bottoms": [3 points]} (the leaflets'
nadirs), counter-clockwise about the flow direction, nadir k between commissures k and k+1;
"unit" there or --unit (default mm).  Prints the annulus (the plane through the nadirs: centre,
axis towards the aorta, radius), each commissure's angle and height, each landmark's distance
from the surface, and the two ends (inlet: the one on the ventricle's side).  --json writes that
frame in metres for the scene maker.  Bad input (one line naming the problem, exit 2): open
boundaries other than the two ends, edges shared by more than two triangles, triangles facing
the other way or into the blood, a self-intersecting surface, landmarks farther than --tol
(default 1 mm) from it, commissures out of order, an annulus radius outside 5-25 mm."""
import argparse
import json
import math
import os
import sys

import numpy as np

UNITS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3}


class BadInput(Exception):
    pass


SURFACE_FORMATS = (".stl", ".vtp", ".vtk", ".msh")  # .vtp through VTK's reader, the others through gmsh's


def read_vtp(path):
    """Vertices and triangles of a VTK XML PolyData file (polygons split into triangles)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkCommonCore import vtkObject
    from vtkmodules.vtkFiltersCore import vtkTriangleFilter
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    vtkObject.GlobalWarningDisplayOff()  # an unreadable file is reported below, in one line
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    tri = vtkTriangleFilter()
    tri.SetInputConnection(reader.GetOutputPort())
    tri.Update()
    poly = tri.GetOutput()
    if poly.GetNumberOfPoints() == 0 or poly.GetNumberOfPolys() == 0:
        raise BadInput(f"{path}: VTK cannot read triangles from it; give the root's wall as a VTP surface")
    pts = vtk_to_numpy(poly.GetPoints().GetData()).astype(float)
    return pts, vtk_to_numpy(poly.GetPolys().GetConnectivityArray()).astype(int).reshape(-1, 3)


def read_surface(path, scale):
    """Vertices [m] and triangles (vertex indices) of a surface file: STL (binary or ASCII), legacy
    VTK or gmsh .msh through gmsh's reader, VTP through VTK's."""
    ext = os.path.splitext(path)[1].lower()
    if ext not in SURFACE_FORMATS:
        raise BadInput(f"{path}: unknown surface format '{ext}'; give an STL, VTP, VTK or gmsh .msh surface")
    if not os.path.isfile(path):
        raise BadInput(f"{path}: no such file")
    if ext == ".vtp":
        pts, tris = read_vtp(path)
        return unique_vertices(pts * scale, tris)
    import gmsh
    gmsh.initialize()
    gmsh.option.setNumber("General.Verbosity", 0)
    try:
        gmsh.merge(path)
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        types, _, nodes = gmsh.model.mesh.getElements(2)
    except Exception as e:  # gmsh raises on unreadable files
        raise BadInput(f"{path}: gmsh cannot read it as a surface ({e}); give an STL, VTK or .msh surface")
    finally:
        gmsh.finalize()
    tri = next((n for t, n in zip(types, nodes) if t == 2), None)
    if tri is None or len(tri) == 0:
        raise BadInput(f"{path}: no triangles in it; give the root's wall as a triangulated surface")
    pts = np.asarray(xyz).reshape(-1, 3) * scale
    index = np.zeros(int(max(tags)) + 1, dtype=int)
    index[np.asarray(tags, dtype=int)] = np.arange(len(tags))
    return unique_vertices(pts, index[np.asarray(tri, dtype=int)].reshape(-1, 3))


def unique_vertices(pts, tris):
    """One vertex per position (an STL repeats each vertex in every triangle that has it)."""
    key = np.round(pts / (1e-9 + 1e-7 * np.ptp(pts)), 0)
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    pts, tris = pts[first], inverse.reshape(-1)[tris]
    keep = (tris[:, 0] != tris[:, 1]) & (tris[:, 1] != tris[:, 2]) & (tris[:, 2] != tris[:, 0])
    return pts, tris[keep]


def boundary_loops(tris):
    """The open boundaries as vertex loops; raises on non-manifold edges and flipped triangles."""
    e = np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])
    lo, hi = e.min(1), e.max(1)
    key = lo.astype(np.int64) * (tris.max() + 1) + hi
    uniq, inv, count = np.unique(key, return_inverse=True, return_counts=True)
    if (count > 2).any():
        raise BadInput(f"{int((count > 2).sum())} edges are shared by more than two triangles (a non-manifold "
                       "surface): give the lumen's wall as one sheet")
    # Each edge shared by two triangles must run both ways in them (consistent normals).
    sense = np.bincount(inv, weights=np.where(e[:, 0] < e[:, 1], 1.0, -1.0))
    flipped = int(((count == 2) & (sense != 0)).sum())
    if flipped:
        raise BadInput(f"inconsistent normals: {flipped} edges join triangles facing opposite ways; orient "
                       "every triangle alike (e.g. gmsh's or MeshLab's 're-orient')")
    nxt = {}
    for a, b in e[count[inv] == 1]:
        if a in nxt:
            raise BadInput("two open boundaries touch at a vertex: the surface must have two separate open ends")
        nxt[a] = b
    loops = []
    while nxt:
        start = next(iter(nxt))
        loop, v = [start], nxt.pop(start)
        while v != start:
            loop.append(v)
            v = nxt.pop(v)
        loops.append(np.array(loop))
    return loops


def enclosed_volume(pts, tris, loops):
    """The volume inside the surface capped at its ends by fans: > 0 when its normals point out."""
    tri = [pts[tris]]
    for loop in loops:  # the boundary runs a -> b in the wall, so the cap takes b -> a
        c = pts[loop].mean(0)
        tri.append(np.stack([pts[np.roll(loop, -1)], pts[loop], np.broadcast_to(c, (len(loop), 3))], 1))
    t = np.concatenate(tri)
    return float(np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum() / 6)


def crossing_pairs(pts, tris):
    """Pairs of triangles without a common vertex that cross each other (a self-intersection):
    candidates share a cell of a grid twice the mean edge long; an edge of one through the
    other is the test (Moller-Trumbore)."""
    p = pts[tris]
    size = 2 * np.linalg.norm(p[:, 1] - p[:, 0], axis=1).mean()
    lo = np.floor((p.min(1) - pts.min(0)) / size).astype(int)
    hi = np.floor((p.max(1) - pts.min(0)) / size).astype(int)
    cells = {}
    for i in range(len(tris)):
        for c in np.ndindex(*(hi[i] - lo[i] + 1)):
            cells.setdefault(tuple(lo[i] + c), []).append(i)
    pairs = set()
    for members in cells.values():
        for a in range(len(members)):
            for b in range(a + 1, len(members)):
                pairs.add((members[a], members[b]))
    if not pairs:
        return []
    ij = np.array(sorted(pairs))
    ij = ij[~(tris[ij[:, 0]][:, :, None] == tris[ij[:, 1]][:, None, :]).any((1, 2))]
    hit = np.zeros(len(ij), dtype=bool)
    for s, t in ((0, 1), (1, 0)):
        A, B = p[ij[:, s]], p[ij[:, t]]
        for k in range(3):
            o, d = A[:, k], A[:, (k + 1) % 3] - A[:, k]
            e1, e2 = B[:, 1] - B[:, 0], B[:, 2] - B[:, 0]
            h = np.cross(d, e2)
            det = np.einsum("ij,ij->i", e1, h)
            ok = np.abs(det) > 1e-30
            f = np.where(ok, 1 / np.where(ok, det, 1), 0)
            sv = o - B[:, 0]
            u = f * np.einsum("ij,ij->i", sv, h)
            q = np.cross(sv, e1)
            v = f * np.einsum("ij,ij->i", d, q)
            w = f * np.einsum("ij,ij->i", e2, q)
            eps = 1e-9
            hit |= ok & (u > eps) & (v > eps) & (u + v < 1 - eps) & (w > eps) & (w < 1 - eps)
    return ij[hit]


def distance_to_surface(pts, tris, q):
    """Distance from point q to the nearest triangle (closest point on each, clamped)."""
    a, b, c = (pts[tris[:, k]] for k in range(3))
    n = np.cross(b - a, c - a)
    n /= np.linalg.norm(n, axis=1)[:, None]
    x = q - np.einsum("ij,ij->i", q - a, n)[:, None] * n  # projection onto each plane

    def inside(p0, p1):
        return np.einsum("ij,ij->i", np.cross(p1 - p0, x - p0), n) >= 0
    d = np.where(inside(a, b) & inside(b, c) & inside(c, a), np.linalg.norm(q - x, axis=1), np.inf)
    for p0, p1 in ((a, b), (b, c), (c, a)):  # otherwise the nearest point of an edge
        s = np.clip(np.einsum("ij,ij->i", q - p0, p1 - p0) / np.einsum("ij,ij->i", p1 - p0, p1 - p0), 0, 1)
        d = np.minimum(d, np.linalg.norm(q - (p0 + s[:, None] * (p1 - p0)), axis=1))
    return float(d.min())


def annulus_frame(comm, nadir):
    """Centre, unit axis (towards the commissures: downstream), radius of the circle through the
    nadirs; commissure and nadir angles about the axis [deg] from nadir 0; raises when out of order."""
    a, b, c = nadir
    n = np.cross(b - a, c - a)
    if np.linalg.norm(n) < 1e-12:
        raise BadInput("the three sinus bottoms lie on a line: give the leaflets' three nadirs")
    n /= np.linalg.norm(n)
    if np.dot(comm.mean(0) - nadir.mean(0), n) < 0:
        n = -n
    # circumcentre in the nadirs' plane
    ab, ac = b - a, c - a
    w = np.cross(ab, ac)
    centre = a + (np.dot(ac, ac) * np.cross(w, ab) + np.dot(ab, ab) * np.cross(ac, w)) / (2 * np.dot(w, w))
    radius = float(np.linalg.norm(a - centre))
    e1 = (a - centre) / radius
    e2 = np.cross(n, e1)

    def angle(p):
        r = p - centre
        return math.degrees(math.atan2(np.dot(r, e2), np.dot(r, e1))) % 360
    ca, na = [angle(p) for p in comm], [angle(p) for p in nadir]
    for k in range(3):  # nadir k lies counter-clockwise after commissure k and before k + 1
        lo, mid, hi = ca[k], na[k], ca[(k + 1) % 3]
        if not (0 < (mid - lo) % 360 < (hi - lo) % 360):
            raise BadInput(f"commissures out of order: sinus bottom {k} does not lie between commissures {k} and "
                           f"{(k + 1) % 3} counter-clockwise about the flow; list them so (or reverse both lists)")
    return centre, n, radius, ca, na


def load_root(surface, landmarks, unit=None, tol=1.0):
    """Read and check a root surface and its landmarks; raises BadInput naming the problem.
    Returns a dict [m]: vtx, tris, landmarks (commissures, sinus_bottoms: 3x3), centre, axis,
    radius, commissure and nadir angles [deg] from nadir 0, their distances from the surface,
    ends [(offset along the axis, centre, mean radius)], inlet first, unit."""
    try:
        marks = json.load(open(landmarks))
    except (OSError, ValueError) as e:
        raise BadInput(f"{landmarks}: cannot read it as JSON ({e})")
    unit = unit or marks.get("unit", "mm")
    if unit not in UNITS:
        raise BadInput(f"unit '{unit}' unknown: use --unit mm, cm or m")
    scale = UNITS[unit]
    pts = {}
    for k in ("commissures", "sinus_bottoms"):
        v = np.asarray(marks.get(k, []), dtype=float) * scale
        if v.shape != (3, 3):
            raise BadInput(f"{landmarks}: '{k}' must list 3 points [x, y, z] (in {unit})")
        pts[k] = v
    centre, axis, radius, ca, na = annulus_frame(pts["commissures"], pts["sinus_bottoms"])
    if not 0.005 <= radius <= 0.025:
        raise BadInput(f"the annulus radius is {radius * 1e3:.3g} mm in unit '{unit}' (5-25 mm expected): "
                       "give the surface's unit with --unit (mm, cm or m)")
    vtx, tris = read_surface(surface, scale)
    loops = boundary_loops(tris)
    if len(loops) != 2:
        raise BadInput(f"the surface has {len(loops)} open boundaries: it must be closed apart from its two open "
                       "ends (ventricle, aorta); close the others (e.g. coronary ostia) or cut it once at each end")
    if enclosed_volume(vtx, tris, loops) < 0:
        raise BadInput("inverted normals: the triangles face into the blood; flip them all")
    cross = crossing_pairs(vtx, tris)
    if len(cross):
        x = vtx[tris[cross[0, 0]]].mean(0) / scale
        raise BadInput(f"the surface intersects itself ({len(cross)} triangle pairs cross, e.g. near "
                       f"({x[0]:.4g}, {x[1]:.4g}, {x[2]:.4g}) {unit}): repair it before meshing")
    dist = {k: [distance_to_surface(vtx, tris, p) for p in v] for k, v in pts.items()}
    for k, ds in dist.items():
        far = [i for i, d in enumerate(ds) if d > tol * 1e-3]
        if far:
            raise BadInput(f"{k[:-1].replace('_', ' ')} {far[0]} lies {ds[far[0]] * 1e3:.2f} mm from the surface (--tol {tol:g} mm): "
                           "landmarks must lie on the wall, in the surface's unit")
    ends = []
    for loop in loops:
        c = vtx[loop].mean(0)
        r = float(np.linalg.norm(vtx[loop] - c, axis=1).mean())
        ends.append((float(np.dot(c - centre, axis)), c, r))
    ends.sort(key=lambda e: e[0])
    if not (ends[0][0] < 0 < ends[1][0]):
        raise BadInput(f"the open ends lie {ends[0][0] * 1e3:.1f} and {ends[1][0] * 1e3:.1f} mm from the "
                       "annulus plane: one must lie on each side of it (ventricle below, aorta above)")
    return {"vtx": vtx, "tris": tris, "landmarks": pts, "centre": centre, "axis": axis, "radius": radius,
            "commissure_deg": ca, "nadir_deg": na, "distance": dist, "ends": ends, "unit": unit}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("surface")
    ap.add_argument("landmarks")
    ap.add_argument("--unit", choices=sorted(UNITS))
    ap.add_argument("--tol", type=float, default=1.0, help="landmarks' largest distance from the surface [mm]")
    ap.add_argument("--json", help="write the frame [m] here")
    a = ap.parse_args()
    try:
        root = load_root(a.surface, a.landmarks, a.unit, a.tol)
    except BadInput as e:
        print(f"root_surface: {e}", file=sys.stderr)
        sys.exit(2)
    vtx, tris, pts, centre, axis = root["vtx"], root["tris"], root["landmarks"], root["centre"], root["axis"]
    ca, na, dist, ends = root["commissure_deg"], root["nadir_deg"], root["distance"], root["ends"]
    print(f"surface: {len(vtx)} vertices, {len(tris)} triangles, two open ends, normals outward, no self-intersection")
    print(f"annulus: centre {np.round(centre * 1e3, 3).tolist()} mm, axis {np.round(axis, 4).tolist()}, "
          f"radius {root['radius'] * 1e3:.2f} mm")
    for k in range(3):
        h = float(np.dot(pts['commissures'][k] - centre, axis))
        deg = lambda x: (x + 180) % 360 - 180
        print(f"commissure {k}: {deg(ca[k]):.1f} deg from sinus bottom 0, {h * 1e3:.2f} mm above the annulus; "
              f"sinus bottom {k}: {deg(na[k]):.1f} deg")
    print("landmarks' distance from the surface [mm]: " +
          ", ".join(f"{v * 1e3:.3f}" for k in dist for v in dist[k]))
    for name, (z, c, r) in zip(("inlet", "outlet"), ends):
        print(f"{name}: {z * 1e3:+.1f} mm along the axis, mean radius {r * 1e3:.2f} mm")
    if a.json:
        frame = {"centre": centre.tolist(), "axis": axis.tolist(), "radius": root["radius"],
                 "commissures": pts["commissures"].tolist(), "sinus_bottoms": pts["sinus_bottoms"].tolist(),
                 "inlet": {"offset": ends[0][0], "centre": ends[0][1].tolist(), "radius": ends[0][2]},
                 "outlet": {"offset": ends[1][0], "centre": ends[1][1].tolist(), "radius": ends[1][2]}}
        json.dump(frame, open(a.json, "w"), indent=1)


if __name__ == "__main__":
    main()
