"""The aortic-valve scene (issue 14) at its CI mesh level, the first 3 steps of systole on 2 ranks:
the inlet flux equals the tabulated Q(t) to 1e-10 at every step, the leaflets move downstream,
the transvalvular pressure drop is positive in forward flow, the orifice area starts at the
reference gap's share of the annulus, mesh quality is reported every step, and
scripts/valve_wss_sides.py splits the leaflets' wall shear into their two sides, writes its
sampled TAWSS and OSI for the pictures and their figures by name (--json)."""
import math
import os
import re
import subprocess
import sys
from fsitest import SRC, check, finish, run

table = []
for line in open(os.path.join(SRC, "examples", "valve", "valve_inflow_paper_fig7.dat")):
    if line.split("#")[0].strip():
        t, q = map(float, line.split())
        table.append((t, q))


def Q(t):
    for (t0, q0), (t1, q1) in zip(table, table[1:]):
        if t0 <= t <= t1:
            return q0 + (q1 - q0) * (t - t0) / (t1 - t0)
    raise ValueError(t)


r = run(os.path.join(SRC, "examples", "valve", "valve.opts"), np=2,
        extra=["-ts_max_time", "0.0015", "-out_fields_every", "1"])
check(r.code == 0 and r.summary["converged"], "3 steps of systole converge on 2 ranks")
rows = r.monitor if r.code == 0 else []
check(len(rows) == 3, f"3 rows in monitor.csv ({len(rows)})")
if rows:
    qmax = max(abs(Q(m["time"])) for m in rows)
    err = max(abs(-m["inlet_flux"] - Q(m["time"])) for m in rows) / qmax
    print(f"inlet flux vs table: {err:.1e} relative; Q(t_end) = {Q(rows[-1]['time']):.3e} m^3/s")
    check(err < 1e-10, f"inlet flux equals the table's Q(t) to 1e-10 ({err:.1e})")
    uz = [m["solid_probe0_uz"] for m in rows]
    print("free-edge probe uz [m]:", " ".join(f"{u:.3e}" for u in uz))
    check(uz[-1] > 0 and uz[-1] > uz[0], "the leaflets' free edge moves downstream")
    check(all(m["valve_leaflet_umax"] > 0 for m in rows), "leaflet displacement reported")
    dp = [m["valve_dp"] for m in rows]
    print("dp [Pa]:", " ".join(f"{d:.1f}" for d in dp))
    check(all(d > 0 for d in dp), "transvalvular pressure drop > 0 in forward flow")
    # Three strips of the reference gap g across the annulus: 3 g R / (pi R^2).
    goa, share = rows[0]["valve_goa_ratio"], 3 * 0.002 / (math.pi * 0.0125)
    check(abs(goa / share - 1) < 0.25,
          f"orifice area at the start is the gap's share of the annulus ({goa:.3f} vs {share:.3f})")
    q = [(m["mesh_min_jacobian"], m["mesh_max_skewness"]) for m in rows]
    print("mesh (min volume ratio, max skewness):", q)
    check(all(0 < j <= 1.0 and 0 < s < 1 for j, s in q), "mesh quality reported every step")
    check(all(k in rows[0] for k in ("mesh_min_jacobian_x", "valve_leaflet_vm_max", "energy_kinetic")),
          "where the mesh is worst, leaflet stress and kinetic energy reported")
    check(os.path.exists(os.path.join(r.dir, "fields.xdmf")) and
          'TopologyType="Tetrahedron_10"' in open(os.path.join(r.dir, "fields.xdmf")).read(),
          "fields written on quadratic tetrahedra")
    # The leaflet-side split of scripts/valve_wss_sides.py on this run's wall shear (material
    # geometry written with the faces): both sides found, partners across the thickness on the
    # other side, wall shear reported on each.
    ws = subprocess.run([sys.executable, os.path.join(SRC, "scripts", "valve_wss_sides.py"), r.dir,
                         "--times", "0.0015", "--sampled", "0,0.0015", "--write",
                         os.path.join(r.dir, "sampled_hemo.h5"), "--json", os.path.join(r.dir, "wss_sides.json")],
                        capture_output=True, text=True)
    print(ws.stdout[-1500:], ws.stderr[-500:])
    m = re.search(r"sides from the material geometry: (\d+) ventricular, (\d+) aortic, (\d+) rim faces; "
                  r"partner across the thickness on the other side: (\d+) of (\d+)", ws.stdout)
    check(ws.returncode == 0 and m is not None, "valve_wss_sides.py splits the leaflets by the material geometry")
    if m:
        v, a, rim, good, sided = map(int, m.groups())
        check(min(v, a) > 0.4 * (v + a) and good >= 0.97 * sided,
              f"both leaflet sides found ({v} ventricular, {a} aortic), partners opposite ({good} of {sided})")
        means = re.findall(r"^\| (ventricular|aortic) \| \d+ \| [\d.]+ \| ([\d.]+) \|", ws.stdout, re.M)
        check(len(means) == 2 and all(float(x) > 0 for _, x in means), f"wall shear on both sides {means}")
        # --write: the sampled TAWSS and OSI per face, laid out as a closed window for the pictures.
        import h5py
        with h5py.File(os.path.join(r.dir, "sampled_hemo.h5"), "r") as f:
            n = f["interface/material_points"].shape[0] // 3
            w = f["interface/window_sampled"]
            ok = w["tawss"].shape == (n,) and w["osi"].shape == (n,) and 0 <= w["osi"][:].min() <= w["osi"][:].max() <= 0.5
        check(ok and n == v + a + rim, f"--write: TAWSS and OSI on all {v + a + rim} faces ({n} written)")
        # --json: the same window's figures by name (issue 55), equal to the printed table's.
        import json
        js = json.load(open(os.path.join(r.dir, "wss_sides.json")))
        win = [x for x in js["windows"] if x["source"].startswith("sampled")]
        ok = len(win) == 1 and all(0 <= win[0][k]["osi_mean"] <= 0.5 for k in ("ventricular", "aortic"))
        ok = ok and win[0]["osi_highest_band"]["where"] in ("free edge", "belly", "base")
        printed = re.findall(r"^\| ventricular \| ([\d.]+) \|", ws.stdout, re.M)
        ok = ok and printed and abs(float(printed[-1]) - win[0]["ventricular"]["tawss_pa"]) < 1e-3
        check(ok, f"--json: per-side TAWSS and OSI, the OSI's highest band, as printed ({printed[-1:]})")
finish()
