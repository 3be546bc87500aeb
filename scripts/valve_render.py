"""Rendered pictures of a valve run (pvpython; called by scripts/valve_pictures RESULTS_DIR
[TIME ...]): leaflets coloured by displacement, velocity magnitude on the mid-plane x = 0, wall
shear stress on the leaflets, at the fields' times nearest to each TIME [s]; and TAWSS and OSI of every
closed -hemo_window, the leaflets seen from the aorta and from the ventricle, the root from two sides."""
import os
import re
import sys

import h5py
import numpy as np
from paraview import vtk
from paraview.simple import (ColorBy, CreateRenderView, GetColorTransferFunction, GetDisplayProperties,
                             Hide, Render, SaveScreenshot, Show, Slice, Threshold, TrivialProducer,
                             WarpByVector, Xdmf3ReaderS)
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray

d = sys.argv[1]
# A run that remeshed has its fields on several meshes, all listed in fields_all.xdmf; a run
# continued by -restart writes fields_restart(_all).xdmf beside them: the newest list is used.
lists = [f for f in os.listdir(d) if re.fullmatch(r"fields(_restart)?(_all)?\.xdmf", f)]
fields = max(lists, key=lambda f: os.path.getmtime(os.path.join(d, f)))
reader = Xdmf3ReaderS(FileName=[os.path.join(d, fields)])
tv = reader.TimestepValues  # a float when the file holds one time
times = [float(tv)] if isinstance(tv, (int, float)) else (list(tv) if tv else [0.0])
wanted = [float(t) for t in sys.argv[2:]] or [times[-1]]
reader.UpdatePipeline(times[0])  # the arrays are known after a first update
if "region" not in reader.CellData.keys():
    sys.exit("valve_render: fields.xdmf has no region attribute (a fluid-solid run is needed)")


def view(size=(1000, 800)):
    v = CreateRenderView()
    v.ViewSize = list(size)
    v.Background = [1, 1, 1]
    v.OrientationAxesVisibility = 1
    try:
        v.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    return v


def region(lo, hi):
    th = Threshold(Input=reader, Scalars=["CELLS", "region"])
    th.LowerThreshold, th.UpperThreshold = lo, hi
    return th


FACE_ARRAYS = ("wss_magnitude", "tawss", "osi")


def colour(src, v, array, title, vmin=None, vmax=None):
    disp = Show(src, v)
    disp.Ambient, disp.Diffuse = 0.35, 0.75  # thin curved shells: light them from every side
    on_faces = array in FACE_ARRAYS
    ColorBy(disp, ("CELLS", array) if on_faces else ("POINTS", array, "Magnitude"))
    lut = GetColorTransferFunction(array)
    lut.ApplyPreset("Viridis (matplotlib)", True)
    if vmin is None:  # the range of what is shown, not of the whole file
        info = src.CellData[array] if on_faces else src.PointData[array]
        vmin, vmax = 0.0, max(info.GetRange(-1)[1], 1e-30)
    lut.RescaleTransferFunction(vmin, vmax)
    disp.SetScalarBarVisibility(v, True)
    try:
        from paraview.simple import GetScalarBar
        sb = GetScalarBar(lut, v)
        sb.Title, sb.ComponentTitle = title, ""
        sb.TitleColor = sb.LabelColor = [0, 0, 0]
    except Exception:
        pass
    return disp


def camera(v, pos, up, focal=(0, 0, 0.008), scale=0.016):
    v.CameraPosition, v.CameraFocalPoint, v.CameraViewUp = list(pos), list(focal), list(up)
    v.CameraParallelProjection = 1
    v.CameraParallelScale = scale


def face_surface(pts, values, name):
    """A producer of the triangles (3 points each, consecutive) carrying one value per face."""
    poly = vtk.vtkPolyData()
    p = vtk.vtkPoints()
    p.SetData(numpy_to_vtk(np.ascontiguousarray(pts), deep=True))
    poly.SetPoints(p)
    nt = len(values)
    conn = np.hstack([np.full((nt, 1), 3), np.arange(3 * nt).reshape(-1, 3)]).ravel()
    cells = vtk.vtkCellArray()
    cells.SetCells(nt, numpy_to_vtkIdTypeArray(conn.astype(np.int64), deep=True))
    poly.SetPolys(cells)
    arr = numpy_to_vtk(np.ascontiguousarray(values), deep=True)
    arr.SetName(name)
    poly.GetCellData().AddArray(arr)
    tp = TrivialProducer()
    tp.GetClientSideObject().SetOutput(poly)
    tp.UpdatePipeline()
    return tp


# The geometry is each mesh's reference; the mesh displacement moves it to the current one (after
# a remesh the reference is where the leaflets were then, not their material reference).
leaflets = WarpByVector(Input=region(0.5, 1.5), Vectors=["POINTS", "mesh_displacement"])
fluid = WarpByVector(Input=region(-0.5, 0.5), Vectors=["POINTS", "mesh_displacement"])
plane = Slice(Input=fluid)
plane.SliceType = "Plane"
plane.SliceType.Origin = [0, 0, 0]
plane.SliceType.Normal = [1, 0, 0]

# Instantaneous wall shear (hemo.xdmf lists the steps, hemo.h5 holds them; after remeshes each
# mesh has its own remeshK_hemo.xdmf/.h5).
wss_steps = []
for hx in sorted(f for f in os.listdir(d) if f.endswith("hemo.xdmf")):
    base = hx[:-len(".xdmf")]
    wss_steps += [(int(n), float(t), base) for n, t in
                  re.findall(r'<Grid Name="interface_(\d+)"><Time Value="([^"]+)"/>',
                             open(os.path.join(d, hx)).read())]

for want in wanted:
    t = min(times, key=lambda x: abs(x - want))
    tag = f"{1000 * t:.1f}ms"
    for src in (reader, leaflets, fluid, plane):
        src.UpdatePipeline(t)

    for name, pos, up in (("top", (0, 0, 0.2), (0, 1, 0)), ("side", (0.2, -0.12, 0.06), (0, 0, 1))):
        v = view()
        v.ViewTime = t
        colour(leaflets, v, "displacement", "|u| [m]")
        camera(v, pos, up)
        Render(v)
        SaveScreenshot(os.path.join(d, f"leaflets_{name}_{tag}.png"), v, ImageResolution=[1000, 800])

    v = view((1100, 800))
    v.ViewTime = t
    colour(plane, v, "velocity", "|v| [m/s]")
    leaf = Show(leaflets, v)
    ColorBy(leaf, None)
    leaf.DiffuseColor = [0.6, 0.6, 0.6]
    camera(v, (0.2, 0, 0.012), (0, 0, 1), focal=(0, 0, 0.012), scale=0.03)
    Render(v)
    SaveScreenshot(os.path.join(d, f"velocity_{tag}.png"), v, ImageResolution=[1100, 800])

    if wss_steps:
        n, tw, base = min(wss_steps, key=lambda s: abs(s[1] - t))
        with h5py.File(os.path.join(d, base + ".h5"), "r") as h:
            g = h[f"interface/step_{n}"]
            pts = np.asarray(g["points"]).reshape(-1, 3)
            mag = np.asarray(g["wss_magnitude"]).ravel()
        tp = face_surface(pts, mag, "wss_magnitude")
        for name, pos, up in (("top", (0, 0, 0.2), (0, 1, 0)), ("bottom", (0, 0, -0.2), (0, 1, 0))):
            v = view()
            # the 99th percentile: a few edge faces would otherwise take the whole scale
            colour(tp, v, "wss_magnitude", "|WSS| [Pa] (top 1% saturated)", 0.0,
                   float(np.percentile(mag, 99)))
            camera(v, pos, up)
            Render(v)
            SaveScreenshot(os.path.join(d, f"wss_{name}_{1000 * tw:.1f}ms.png"), v,
                           ImageResolution=[1000, 800])
    print(f"valve_render: pictures at t = {t:.4f} s in {d}")

# Closed time windows (-hemo_window): TAWSS and OSI on each surface's material geometry (the
# leaflets' nearly closed shape, the same for every remesh's faces): the leaflets seen from the
# aorta and from the ventricle, any other surface (the root wall) from two sides.
VIEWS = {"interface": (("aortic", (0, 0, 0.2), (0, 1, 0)), ("ventricular", (0, 0, -0.2), (0, 1, 0)))}
SIDES = (("side_x", (0.2, 0, 0.01), (0, 0, 1)), ("side_y", (0, -0.2, 0.01), (0, 0, 1)))
done = set()
for hx in sorted(f for f in os.listdir(d) if f.endswith("hemo.h5")):
    with h5py.File(os.path.join(d, hx), "r") as h:
        for surf in h:
            if "material_points" not in h[surf]:
                continue
            for w in (k for k in h[surf] if k.startswith("window_")):
                g = h[surf][w]
                t0, t1 = (float(x) for x in np.asarray(g["interval"]))
                if (surf, round(t0, 6), round(t1, 6)) in done:
                    continue
                done.add((surf, round(t0, 6), round(t1, 6)))
                pts = np.asarray(h[surf]["material_points"]).reshape(-1, 3)
                name = "" if surf == "interface" else surf + "_"
                for array, title, top in (("tawss", "TAWSS [Pa] (top 1% saturated)", None), ("osi", "OSI", 0.5)):
                    val = np.asarray(g[array]).ravel()
                    tp = face_surface(pts, val, array)
                    for side, pos, up in VIEWS.get(surf, SIDES):
                        v = view()
                        colour(tp, v, array, title, 0.0, top if top else max(float(np.percentile(val, 99)), 1e-30))
                        if surf == "interface":
                            camera(v, pos, up)
                        else:  # the whole root, annulus to outlet
                            camera(v, pos, up, focal=(0, 0, 0.012), scale=0.04)
                        Render(v)
                        out = f"{name}{array}_{side}_{1000 * t0:.0f}-{1000 * t1:.0f}ms.png"
                        SaveScreenshot(os.path.join(d, out), v, ImageResolution=[1000, 800])
                print(f"valve_render: TAWSS and OSI on {surf} over {t0:.4f}-{t1:.4f} s in {d}")
