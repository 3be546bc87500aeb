"""Output contract on 2 ranks: summary.json, monitor.csv, options.txt, fields.h5 + fields.xdmf;
every dataset the XDMF names exists in the HDF5 file with the declared shape, and the written
vertex velocity matches the exact flow at the deformed vertex positions."""
import os
import re
import h5py
import numpy as np
from fsitest import check, finish, run, scene

r = run(scene("ethier_steinman"), np=2,
        extra=["-out_fields_every", "2", "-ale_motion", "prescribed", "-ale_amplitude", "0.1", "-ale_time", "0.02"])
check(r.code == 0, "run succeeds")
for f in ("summary.json", "monitor.csv", "options.txt", "fields.h5", "fields.xdmf"):
    check(os.path.exists(os.path.join(r.dir, f)), f"{f} written")
check(not any(n.endswith((".tmp", ".partial")) for n in os.listdir(r.dir)), "no temporary files left")
s = r.summary
check(s["converged"] and s["ranks"] == 2 and s["steps"] == 4, "summary: converged, 2 ranks, 4 steps")
check("fluid (Navier-Stokes, ALE)" in s["physics"], "summary names the physics that ran")
# Each module's Jacobian cost: its element loop's seconds and rate, within the Jacobian's time.
bym = s["cost"].get("jacobian_by_module", {})
fl = bym.get("fluid (Navier-Stokes, ALE)", {})
check(fl.get("cells") == s["fluid_cells"] and fl.get("cells_per_second_per_rank", 0) > 0,
      f"summary: the fluid's Jacobian rate ({fl})")
t_mod = sum(m["seconds"] for m in bym.values())
check(0 < t_mod <= s["wall_time"]["jacobian_assembly"],
      f"summary: the modules' Jacobian seconds {t_mod:.3f} within the Jacobian's {s['wall_time']['jacobian_assembly']:.3f}")
xdmf = open(os.path.join(r.dir, "fields.xdmf")).read()
refs = re.findall(r'Dimensions="([0-9 ]+)"[^>]*>fields\.h5:(/[^<]+)<', xdmf)
h5 = h5py.File(os.path.join(r.dir, "fields.h5"), "r")
ok = all(path in h5 and tuple(int(x) for x in dims.split()) == h5[path].shape for dims, path in refs)
check(len(refs) > 0 and ok, f"all {len(refs)} XDMF data items exist in fields.h5 with their shapes")
times = [float(t) for t in re.findall(r'<Time Value="([^"]+)"', xdmf)]
check(times == [0.01, 0.02], f"XDMF time steps {times}")
X = h5["geometry/nodes"][:] + h5["fields/mesh_displacement_000004"][:]
v = h5["fields/velocity_000004"][:]
a, d, nu, t = np.pi / 4, np.pi / 2, 0.2, 0.02
def comp(x, y, z):
    return -a * (np.exp(a * x) * np.sin(a * y + d * z) + np.exp(a * z) * np.cos(a * x + d * y)) * np.exp(-nu * d * d * t)
ex = np.stack([comp(X[:, 0], X[:, 1], X[:, 2]), comp(X[:, 1], X[:, 2], X[:, 0]), comp(X[:, 2], X[:, 0], X[:, 1])], 1)
err = np.abs(v - ex).max() / np.abs(ex).max()
check(err < 0.02, f"vertex velocity matches the exact flow at deformed vertices ({err:.2e} relative)")
finish()
