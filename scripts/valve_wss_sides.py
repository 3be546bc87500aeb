"""Wall shear on the two sides of the leaflets, for the paper's claims (Figs. 11-12): WSS on the
ventricular (inflow) side larger than on the aortic side, OSI highest near the free edge.
  /usr/bin/python3 scripts/valve_wss_sides.py DIR [DIR ...] [--times T1,T2,...] [--surface NAME]
                                              [--sampled T0,T1 [--write FILE_hemo.h5]] [--json FILE]
DIRs: one run's pieces (continued by -restart), searched for every *hemo*.xdmf they hold.
Prints (markdown), per requested time, the output step nearest to it: area-mean and 95th
percentile of |tau_w| on the ventricular side, the aortic side and the rims (free edge and
commissure faces across the thickness); and, for every closed window found (TAWSS, OSI), the same
split plus OSI by distance from the free edge.  --sampled T0,T1 computes TAWSS and OSI the same
way from the instantaneous outputs between T0 and T1 (every -out_fields_every steps, trapezoidal
weights): an estimate for a stretch that no closed window covers (the run's own windows
integrate every step); --write puts those TAWSS and OSI per face into an h5 file laid out as a
run's closed window (scripts/valve_pictures renders it when it lies in the run's directory).
--json FILE: every window's figures by name (per side tawss_pa, wss_magnitude_mean_pa, osi_mean,
osi_p95; osi_by_distance_from_free_edge; osi_highest_band with where: free edge < 3 mm, belly,
base >= 10 mm; tawss_ventricular_over_aortic).

Sides, per output file (a remesh writes its faces in its new reference's order): on the faces'
material geometry (material_points, written since 2026-12-02) or else the sample's current one,
a face's outward normal points away from the nearest nearly parallel face across the leaflet's
thickness (within 1.5 mm); the ventricular side is the one whose outward normal points upstream
or towards the axis, n_z + n_r < 0 (true of the nearly closed and of the open leaflets).  Every
split prints how many faces have their partner across the thickness on the other side."""
import glob
import json
import os
import re
import sys

import h5py
import numpy as np

args = sys.argv[1:]
times, surface = [0.198, 0.66], "interface"
if "--times" in args:
    i = args.index("--times")
    times = [float(t) for t in args[i + 1].split(",")]
    del args[i:i + 2]
sampled = None
if "--sampled" in args:
    i = args.index("--sampled")
    sampled = [float(t) for t in args[i + 1].split(",")]
    del args[i:i + 2]


def output_file(flag, example):
    """The file named after FLAG (removed from args), in an existing directory; None without FLAG."""
    if flag not in args:
        return None
    i = args.index(flag)
    if i + 1 >= len(args) or not os.path.isdir(os.path.dirname(os.path.abspath(args[i + 1]))):
        sys.exit(f"valve_wss_sides.py: {flag} needs a file in an existing directory, e.g. {flag} DIR/{example}")
    path = args[i + 1]
    del args[i:i + 2]
    return path


write = output_file("--write", "sampled_hemo.h5")
json_out = output_file("--json", "wss_sides.json")
if "--surface" in args:
    i = args.index("--surface")
    surface = args[i + 1]
    del args[i:i + 2]
if not args:
    sys.exit("usage: valve_wss_sides.py DIR [DIR ...] [--times T1,T2] [--surface NAME] [--sampled T0,T1]")

# Every instantaneous output: time -> (h5 file, group); every closed window: (t0, t1) -> group.
samples, windows = {}, {}
for d in args:
    if not os.path.isdir(d):
        sys.exit(f"valve_wss_sides.py: no directory {d}")
    for x in glob.glob(os.path.join(d, "*hemo*.xdmf")):
        text = open(x).read()
        for _, t, h5, grp in re.findall(
                r'<Grid Name="' + surface + r'_(\d+)"><Time Value="([^"]+)"/>.*?>([^<>:]+\.h5):/(' + surface +
                r'/step_\d+)/points<', text, re.S):
            samples[float(t)] = (os.path.join(d, h5), grp)
    for h in glob.glob(os.path.join(d, "*hemo*.h5")):
        with h5py.File(h, "r") as f:
            if surface not in f:
                continue
            for w in f[surface]:
                if w.startswith("window_") and "interval" in f[surface][w]:
                    t0, t1 = f[surface][w]["interval"][:]
                    windows[(round(t0, 9), round(t1, 9))] = (h, surface + "/" + w)
if not samples and not windows:
    sys.exit(f"valve_wss_sides.py: no wall-shear output of surface '{surface}' in {args}")


def classify(P):
    """Sides of faces with vertices P (nf, 3, 3): outward normal away from the nearly parallel face
    across the thickness; ventricular where n_z + n_r < 0 (true of the nearly closed reference
    shape and of the open leaflets alike)."""
    c = P.mean(axis=1)
    n = np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0])
    area = 0.5 * np.linalg.norm(n, axis=1)
    n /= np.linalg.norm(n, axis=1)[:, None]
    side = np.zeros(len(c), dtype=int)  # -1 ventricular, +1 aortic, 0 rim
    partner = np.full(len(c), -1)
    for i in range(len(c)):
        d = c - c[i]
        dist = np.linalg.norm(d, axis=1)
        across = (dist < 1.5e-3) & (np.abs(n @ n[i]) > 0.8) & (np.abs(d @ n[i]) > 0.5 * dist) & (dist > 0)
        if not across.any():
            continue
        j = partner[i] = np.flatnonzero(across)[np.argmin(dist[across])]
        out = -n[i] if d[j] @ n[i] > 0 else n[i]
        r = np.array([c[i, 0], c[i, 1], 0.0])
        r /= max(np.linalg.norm(r), 1e-12)
        side[i] = -1 if out[2] + out @ r < 0 else 1
    rim = side == 0
    sided = np.flatnonzero(side != 0)
    # Check of the split: a face's partner across the thickness should be on the other side.
    opposite = int(np.sum(side[partner[sided]] == -side[sided]))
    # Distance from the free edge: the rim faces whose centroid is not at the root wall's radius.
    radius = np.hypot(c[:, 0], c[:, 1])
    edge = rim & (radius < radius.max() - 1e-3)
    d_edge = np.full(len(c), np.inf)
    if edge.any():
        for i in range(len(c)):
            d_edge[i] = np.min(np.linalg.norm(c[edge] - c[i], axis=1))
    return {"side": side, "rim": rim, "area": area, "d_edge": d_edge, "c": c,
            "check": f"{(side == -1).sum()} ventricular, {(side == 1).sum()} aortic, {rim.sum()} rim faces; "
                     f"partner across the thickness on the other side: {opposite} of {len(sided)}"}


def material(h5):
    """The faces' material vertices (identity across remeshes), or None for older files."""
    with h5py.File(h5, "r") as f:
        g = f[surface]
        return g["material_points"][:].reshape(-1, 3, 3) if "material_points" in g else None


def split(geo, values, weights):
    rows = []
    for label, m in (("ventricular", geo["side"] == -1), ("aortic", geo["side"] == 1), ("rims", geo["rim"])):
        if m.any():
            mean = np.sum(values[m] * weights[m]) / np.sum(weights[m])
            rows.append((label, m.sum(), 1e4 * np.sum(weights[m]), mean, np.percentile(values[m], 95),
                         values[m].max()))
    return rows


for t in times:
    if not samples:
        break
    tk = min(samples, key=lambda s: abs(s - t))
    h5, grp = samples[tk]
    with h5py.File(h5, "r") as f:
        mag = f[grp]["wss_magnitude"][:]
        pts = f[grp]["points"][:].reshape(-1, 3, 3)
    M = material(h5)
    geo = classify(M if M is not None else pts)
    area = 0.5 * np.linalg.norm(np.cross(pts[:, 1] - pts[:, 0], pts[:, 2] - pts[:, 0]), axis=1)
    print(f"### |tau_w| at t = {tk * 1e3:.1f} ms (asked {t * 1e3:.1f} ms; {os.path.basename(h5)}; sides from the "
          f"{'material' if M is not None else 'current'} geometry: {geo['check']})\n")
    print("| side | faces | area [cm²] | area mean [Pa] | 95th pct [Pa] | max [Pa] |\n|---|---|---|---|---|---|")
    for r in split(geo, mag, area):
        print(f"| {r[0]} | {r[1]} | {r[2]:.2f} | {r[3]:.3f} | {r[4]:.3f} | {r[5]:.3f} |")
    print()


def canonical(files):
    """Face order of each file mapped to the first file's, by material centroid; None if the files'
    faces cannot be matched (older files without material_points, from more than one mesh)."""
    mats = {h: material(h) for h in files}
    if any(m is None for m in mats.values()):
        return None
    key = lambda m: [tuple(np.round(x, 8)) for x in m.mean(axis=1)]
    first = {k: i for i, k in enumerate(key(mats[files[0]]))}
    out = {}
    for h in files:
        idx = np.array([first.get(k, -1) for k in key(mats[h])])
        if (idx < 0).any():
            return None
        out[h] = np.argsort(idx)  # values[out[h]] is in the first file's order
    return out


indices = []
for (t0, t1), (h5, grp) in sorted(windows.items()):
    with h5py.File(h5, "r") as f:
        q = {k: f[grp][k][:] for k in ("tawss", "wss_magnitude_mean", "osi")}
        P = f[surface]["reference_points"][:].reshape(-1, 3, 3)
    M = material(h5)
    indices.append(((t0, t1), f"window ({os.path.basename(h5)})", classify(M if M is not None else P), q))
if sampled:
    ts = sorted(t for t in samples if sampled[0] - 1e-9 <= t <= sampled[1] + 1e-9)
    if len(ts) < 2:
        sys.exit(f"valve_wss_sides.py: fewer than two outputs between {sampled[0]} and {sampled[1]} s")
    files = list(dict.fromkeys(samples[t][0] for t in ts))
    order = canonical(files) if len(files) > 1 else {files[0]: slice(None)}
    if order is None:
        sys.exit("valve_wss_sides.py: --sampled over several mesh pieces needs the faces' material_points "
                 "(written by runs from 2026-12-02 on); these files order their faces by each new mesh's "
                 "reference and cannot be matched")
    vec, mag = 0.0, 0.0
    for k, t in enumerate(ts):
        w = 0.5 * ((ts[min(k + 1, len(ts) - 1)] - t) + (t - ts[max(k - 1, 0)]))
        with h5py.File(samples[t][0], "r") as f:
            tau = f[samples[t][1]]["wss"][:][order[samples[t][0]]]
        vec = vec + w * tau
        mag = mag + w * np.linalg.norm(tau, axis=1)
    T = ts[-1] - ts[0]
    tawss, mean = np.linalg.norm(vec, axis=1) / T, mag / T
    osi = np.clip(0.5 * (1 - tawss / np.maximum(mean, 1e-300)), 0, 0.5)
    M = material(files[0])
    with h5py.File(files[0], "r") as f:
        P = f[surface]["reference_points"][:].reshape(-1, 3, 3)
    indices.append(((ts[0], ts[-1]), f"sampled, {len(ts)} instantaneous outputs",
                    classify(M if M is not None else P), {"tawss": tawss, "wss_magnitude_mean": mean, "osi": osi}))
    if write:
        with h5py.File(write, "w") as f:
            g = f.create_group(surface)
            g["material_points"] = (M if M is not None else P).reshape(-1, 3)
            w = g.create_group("window_sampled")
            w["interval"] = np.array([ts[0], ts[-1]])
            w["tawss"], w["osi"], w["wss_magnitude_mean"] = tawss, osi, mean
elif write:
    sys.exit("valve_wss_sides.py: --write needs --sampled T0,T1")
BINS = ((0, 1), (1, 3), (3, 6), (6, 10), (10, np.inf))  # distance from the free edge [mm]


def where(lo):
    """The name a reader gives a band of the leaflet by its distance from the free edge."""
    return "free edge" if lo < 3 else ("belly" if lo < 10 else "base")


def figures(geo, q):
    """A window's named figures: per side, TAWSS, mean |tau_w| and OSI; OSI by distance from the
    free edge, and the band where its area mean is highest."""
    side, rim, area0, d_edge = geo["side"], geo["rim"], geo["area"], geo["d_edge"]
    out = {}
    for label, m in (("ventricular", side == -1), ("aortic", side == 1), ("rims", rim)):
        w = area0[m]
        out[label] = {"tawss_pa": float(np.sum(q["tawss"][m] * w) / w.sum()),
                      "wss_magnitude_mean_pa": float(np.sum(q["wss_magnitude_mean"][m] * w) / w.sum()),
                      "osi_mean": float(np.sum(q["osi"][m] * w) / w.sum()),
                      "osi_p95": float(np.percentile(q["osi"][m], 95))}
    bands = []
    for lo, hi in BINS:
        m = (d_edge >= lo * 1e-3) & (d_edge < hi * 1e-3)
        if m.any():
            w = area0[m]
            bands.append({"from_mm": lo, "to_mm": None if hi == np.inf else hi, "faces": int(m.sum()),
                          "osi_mean": float(np.sum(q["osi"][m] * w) / w.sum()),
                          "tawss_pa": float(np.sum(q["tawss"][m] * w) / w.sum())})
    top = max(bands, key=lambda b: b["osi_mean"])
    out["osi_by_distance_from_free_edge"] = bands
    out["osi_highest_band"] = {"from_mm": top["from_mm"], "to_mm": top["to_mm"], "osi_mean": top["osi_mean"],
                               "where": where(top["from_mm"])}
    out["tawss_ventricular_over_aortic"] = out["ventricular"]["tawss_pa"] / max(out["aortic"]["tawss_pa"], 1e-300)
    return out


report = []
for (t0, t1), what, geo, q in indices:
    f = figures(geo, q)
    report.append(dict(t0=float(t0), t1=float(t1), source=what, sides=geo["check"], **f))
    print(f"### TAWSS and OSI {t0:.4f}-{t1:.4f} s ({what}; {geo['check']})\n")
    print("| side | TAWSS area mean [Pa] | mean \\|tau_w\\| [Pa] | OSI area mean | OSI 95th pct |\n|---|---|---|---|---|")
    for label in ("ventricular", "aortic", "rims"):
        x = f[label]
        print(f"| {label} | {x['tawss_pa']:.3f} | {x['wss_magnitude_mean_pa']:.3f} | {x['osi_mean']:.3f} | "
              f"{x['osi_p95']:.3f} |")
    print("\n| distance from the free edge [mm] | faces | OSI area mean | TAWSS area mean [Pa] |\n|---|---|---|---|")
    for b in f["osi_by_distance_from_free_edge"]:
        hi = "inf" if b["to_mm"] is None else b["to_mm"]
        print(f"| {b['from_mm']}-{hi} | {b['faces']} | {b['osi_mean']:.3f} | {b['tawss_pa']:.3f} |")
    top = f["osi_highest_band"]
    print(f"\nOSI highest at the {top['where']} ({top['from_mm']}-{'inf' if top['to_mm'] is None else top['to_mm']} mm "
          f"from the free edge); TAWSS ventricular / aortic {f['tawss_ventricular_over_aortic']:.2f}\n")
if json_out:
    with open(json_out, "w") as fh:
        json.dump({"surface": surface, "windows": report}, fh, indent=1)
