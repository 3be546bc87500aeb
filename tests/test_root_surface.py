"""A patient's root surface (issue 58, first part): scripts/root_stl.py writes meshes/valve.geo's
idealised root (binary STL) and an asymmetric one (elliptic annulus 13.5 x 11.5 mm, sinus depths
4, 3, 5 mm; ASCII STL) with their landmarks; scripts/root_surface.py reads each through gmsh and
finds the annulus through the nadirs (centre, axis, radius: the circle through the three nadirs,
known exactly), the commissures' heights (16.875 mm) and the two open ends (inlet 15 mm upstream,
outlet 66.875 mm downstream).  Bad input, each one line and exit 2: a third open boundary (a hole
in the wall), a duplicated triangle (non-manifold), one flipped triangle, all flipped (normals into
the blood), a vertex pushed through the opposite wall (self-intersection), a commissure 3 mm off
the wall, commissures out of order, a unit that makes the annulus 12.5 m."""
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

from fsitest import SRC, check, finish

sys.path.insert(0, os.path.join(SRC, "scripts"))
from root_surface import read_surface  # noqa: E402

PY = "/usr/bin/python3"


def script(name, *args):
    p = subprocess.run([PY, os.path.join(SRC, "scripts", name), *args], capture_output=True, text=True)
    return p.returncode, p.stdout + p.stderr


def write_stl(path, pts, tris):
    """Binary STL in mm (the test's own writer: the bad surfaces are edits of a good one)."""
    p = pts[tris] * 1e3
    rec = np.zeros(len(tris), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    rec["v"] = p
    with open(path, "wb") as f:
        f.write(b"\0" * 80 + np.uint32(len(tris)).tobytes() + rec.tobytes())


def circumradius(a, b, c):
    ab, ac, bc = (np.linalg.norm(x) for x in (b - a, c - a, c - b))
    return ab * ac * bc / (2 * np.linalg.norm(np.cross(b - a, c - a)))


d = tempfile.mkdtemp(prefix="fsi_root_")
for name, extra in (("ideal", []), ("asym", ["--asymmetric", "--ascii"])):
    stl = os.path.join(d, name + ".stl")
    code, out = script("root_stl.py", stl, *extra)
    check(code == 0, f"root_stl.py {name}: rc {code} {out.strip()}")
    code, out = script("root_surface.py", stl, stl[:-4] + ".json", "--json", stl[:-4] + ".frame.json")
    print(out)
    check(code == 0, f"root_surface.py {name}: rc {code}")
    if code:
        continue
    marks = json.load(open(stl[:-4] + ".json"))
    frame = json.load(open(stl[:-4] + ".frame.json"))
    want_r = circumradius(*np.array(marks["sinus_bottoms"])) * 1e-3
    check(abs(frame["radius"] - want_r) < 1e-8, f"{name}: annulus radius {frame['radius']*1e3:.4f} mm, "
          f"expected {want_r*1e3:.4f} (the circle through the nadirs)")
    check(np.allclose(frame["axis"], [0, 0, 1], atol=1e-9), f"{name}: axis {frame['axis']} (expected +z)")
    heights = [np.dot(np.array(c) - frame["centre"], frame["axis"]) for c in frame["commissures"]]
    check(all(abs(h - 0.016875) < 1e-8 for h in heights), f"{name}: commissure heights {heights}")
    check(abs(frame["inlet"]["offset"] + 0.015) < 1e-6 and abs(frame["outlet"]["offset"] - 0.066875) < 1e-6,
          f"{name}: ends at {frame['inlet']['offset']}, {frame['outlet']['offset']} m (-0.015, 0.066875)")
    check("no self-intersection" in out, f"{name}: the surface checks pass")

# The other surface formats give the same frame: gmsh .msh and legacy VTK (root_stl.py writes
# them through gmsh), VTP (written here through VTK, 100 triangle pairs as quads, so that the
# reader's polygon split is exercised too).
stl_frame = json.load(open(os.path.join(d, "ideal.frame.json")))


def write_vtp(path, pts, tris):
    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
    # Pair up to 100 triangles (a, b, c) with their neighbours across b-c into quads (a, b, d, c).
    edge = {(int(t[i]), int(t[(i + 1) % 3])): k for k, t in enumerate(tris) for i in range(3)}
    used, polys = set(), []
    for k, (a, b, c) in enumerate(tris):
        j = edge.get((int(c), int(b)))
        if len(polys) < 100 and k not in used and j is not None and j not in used:
            dd = [v for v in tris[j] if v not in (b, c)][0]
            used.update((k, j))
            polys.append([a, b, dd, c])
    polys += [list(t) for k, t in enumerate(tris) if k not in used]
    poly = vtkPolyData()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(pts * 1e3, deep=True))
    poly.SetPoints(points)
    cells = vtkCellArray()
    offsets = np.cumsum([0] + [len(q) for q in polys])
    cells.SetData(numpy_to_vtkIdTypeArray(offsets.astype(np.int64), deep=True),
                  numpy_to_vtkIdTypeArray(np.concatenate(polys).astype(np.int64), deep=True))
    poly.SetPolys(cells)
    w = vtkXMLPolyDataWriter()
    w.SetFileName(path)
    w.SetInputData(poly)
    w.Write()


ideal_pts, ideal_tris = read_surface(os.path.join(d, "ideal.stl"), 1e-3)
for ext in (".msh", ".vtk", ".vtp"):
    path = os.path.join(d, "ideal_as" + ext)
    if ext == ".vtp":
        write_vtp(path, ideal_pts, ideal_tris)
    else:
        code, out = script("root_stl.py", path)
        check(code == 0, f"root_stl.py {path}: rc {code} {out.strip()}")
    code, out = script("root_surface.py", path, os.path.join(d, "ideal.json"), "--json", path + ".json")
    check(code == 0, f"root_surface.py on {ext}: rc {code} {out.strip()[-300:]}")
    if code == 0:
        f = json.load(open(path + ".json"))
        same = all(np.allclose(f[k], stl_frame[k], atol=1e-9) for k in ("centre", "axis", "radius"))
        same = same and abs(f["inlet"]["offset"] - stl_frame["inlet"]["offset"]) < 1e-9
        check(same and "8056 triangles" in out, f"{ext}: the STL's frame and 8056 triangles ({out.splitlines()[0]})")

# Bad input: edits of the idealised root.
stl, marks_path = os.path.join(d, "ideal.stl"), os.path.join(d, "ideal.json")
pts, tris = read_surface(stl, 1e-3)
marks = json.load(open(marks_path))
mid = np.argmin(np.linalg.norm(pts - [0.0125, 0, 0.04], axis=1))  # a wall vertex 40 mm up
fan = np.nonzero((tris == mid).any(1))[0]
pushed = pts.copy()
pushed[mid] = [-0.0145, 0, 0.04]  # through the opposite wall
cases = {
    "hole": (pts, np.delete(tris, fan, 0), None, "3 open boundaries"),
    "duplicate": (pts, np.vstack([tris, tris[fan[:1]]]), None, "more than two triangles"),
    "one flipped": (pts, np.vstack([tris[:fan[0]], tris[fan[0]][::-1], tris[fan[0] + 1:]]), None, "inconsistent normals"),
    "all flipped": (pts, tris[:, ::-1], None, "inverted normals"),
    "self-intersecting": (pushed, tris, None, "intersects itself"),
    "landmark off the wall": (pts, tris, {"commissures": [[8.2272, 4.75, 16.875]] + marks["commissures"][1:]}, "commissure 0 lies 2.9"),
    "commissures out of order": (pts, tris, {"commissures": marks["commissures"][::-1]}, "out of order"),
    "unit m": (pts, tris, {"unit": "m"}, "annulus radius is 1.25e+04 mm"),
}
open(os.path.join(d, "junk.vtp"), "w").write("<VTKFile>not a surface")
for path, word in ((os.path.join(d, "ideal.obj"), "unknown surface format '.obj'"),
                   (os.path.join(d, "junk.vtp"), "VTK cannot read triangles")):
    code, out = script("root_surface.py", path, marks_path)
    check(code == 2 and len(out.strip().splitlines()) == 1 and word in out, f"{path}: rc {code}, {out.strip()}")
for name, (p, t, edit, word) in cases.items():
    path = os.path.join(d, "bad.stl")
    write_stl(path, p, t)
    lm = dict(marks, **(edit or {}))
    json.dump(lm, open(os.path.join(d, "bad.json"), "w"))
    code, out = script("root_surface.py", path, os.path.join(d, "bad.json"))
    lines = out.strip().splitlines()
    check(code == 2 and len(lines) == 1 and word in out, f"{name}: rc {code}, {out.strip()}")
finish()
