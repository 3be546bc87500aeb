"""Figures of a valve run for a note or a paper, from its monitor.csv, remesh.csv and summary.json:
  /usr/bin/python3 scripts/valve_report.py DIR [DIR ...] [--every MS] [--period S]
Several DIRs are the pieces of one run continued by -restart, in order: where a later piece
starts, the earlier one's rows stop.  Prints (markdown)
  - the state every MS milliseconds (default 25): flow rate, transvalvular pressure drop, orifice
    area, leaflet displacement and stress, contact pairs, sealed cells, Newton, dt;
  - per cycle of the inlet's period (default 1.1 s): forward (ejected) and backward (regurgitant)
    volume through the inlet, and their ratio;
  - cost: steps, cut steps, s/step, Newton and Krylov per step, remeshes and their share of the
    wall time, peak memory per rank."""
import json
import os
import sys

from run_pieces import read_rows, stitch


args = sys.argv[1:]
every, period = 25.0, 1.1
if "--every" in args:
    i = args.index("--every")
    every = float(args[i + 1])
    del args[i:i + 2]
if "--period" in args:
    i = args.index("--period")
    period = float(args[i + 1])
    del args[i:i + 2]
if not args:
    sys.exit(__doc__)
mon = stitch([read_rows(d, "monitor.csv") for d in args], "step")
rem = stitch([read_rows(d, "remesh.csv") for d in args], "step")
if not mon:
    sys.exit("valve_report: no monitor rows in " + " ".join(args))
dt0 = max(r["dt"] for r in mon)

print("| t [ms] | Q [L/min] | dp [Pa] | orifice [cm^2] | of annulus | leaflet max u [mm] | von Mises [kPa] | contact pairs | sealed cells | Newton | dt [ms] |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
mark = 0.0
for r in mon:
    if r["time"] * 1e3 + 1e-9 < mark and r is not mon[-1]:
        continue
    mark = (int(r["time"] * 1e3 / every + 1e-9) + 1) * every
    print(f"| {r['time']*1e3:.2f} | {-r['inlet_flux']*6e4:.2f} | {r.get('valve_dp', 0):.0f} | "
          f"{r.get('valve_goa', 0)*1e4:.2f} | {r.get('valve_goa_ratio', 0)*100:.0f} % | "
          f"{r.get('valve_leaflet_umax', 0)*1e3:.2f} | {r.get('valve_leaflet_vm_max', 0)/1e3:.1f} | "
          f"{r.get('contact_pairs', 0):.0f} | {r.get('seal_cells', 0):.0f} | {r['newton']:.0f} | {r['dt']*1e3:.3f} |")

# Volumes through the inlet (inlet_flux > 0 leaves the domain there: backwards through the valve).
print("\n| cycle | from [ms] | to [ms] | forward [mL] | backward [mL] | backward / forward |")
print("|---|---|---|---|---|---|")
cycles = {}
prev_t = 0.0
for r in mon:
    c = int(r["time"] / period - 1e-12)
    q = -r["inlet_flux"] * (r["time"] - prev_t)
    prev_t = r["time"]
    f, b, t0, t1 = cycles.get(c, (0.0, 0.0, r["time"], r["time"]))
    cycles[c] = (f + max(q, 0), b + max(-q, 0), min(t0, r["time"]), r["time"])
for c, (f, b, t0, t1) in sorted(cycles.items()):
    print(f"| {c + 1} | {t0*1e3:.1f} | {t1*1e3:.1f} | {f*1e6:.2f} | {b*1e6:.3f} | {b/f*100 if f else 0:.2f} % |")

steps = len(mon)
wall = sum(r["step_seconds"] for r in mon)
remesh_s = sum(r["seconds"] for r in rem)
summaries = [json.load(open(os.path.join(d, "summary.json"))) for d in args
             if os.path.exists(os.path.join(d, "summary.json"))]
peak = max((s["cost"]["peak_memory_mb_per_rank_max"] for s in summaries), default=float("nan"))
print(f"\nsteps {steps} (cut below {dt0*1e3:g} ms: {sum(r['dt'] < 0.99 * dt0 for r in mon)}), "
      f"{wall / steps:.2f} s/step (step seconds, remeshing apart), Newton {sum(r['newton'] for r in mon)/steps:.2f} "
      f"and Krylov {sum(r['krylov'] for r in mon)/steps:.1f} per step, Newton max {max(r['newton'] for r in mon):.0f}; "
      f"remeshes {len(rem)} ({remesh_s:.0f} s = {remesh_s/(wall+remesh_s)*100:.1f} % of step + remesh time, "
      f"{remesh_s/max(len(rem),1):.1f} s each); peak memory {peak:.0f} MB per rank "
      f"({len(summaries)} of {len(args)} pieces with a summary)")
