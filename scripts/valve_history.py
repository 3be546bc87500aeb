"""valve_history.png from a valve run's monitor.csv (called by scripts/valve_pictures).
  /usr/bin/python3 scripts/valve_history.py DIR [DIR ...]
Several DIRs are one run's pieces (each continued from the previous one's checkpoint by
-restart): their rows are joined in time, a later piece replacing an earlier one from its first
time on; the picture goes to the last DIR."""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from run_pieces import read_rows, stitch

dirs = sys.argv[1:]
if not dirs:
    sys.exit("usage: valve_history.py DIR [DIR ...]")
for d in dirs:
    if not read_rows(d):
        sys.exit(f"valve_history: no rows in {d}/monitor.csv")
rows = stitch([read_rows(d) for d in dirs], "time")
if not rows:
    sys.exit("valve_history: monitor.csv has no rows")
col = lambda c, s=1.0: [s * float(r[c]) for r in rows]
t = col("time", 1000)
fig, ax = plt.subplots(4, 1, figsize=(7, 9), sharex=True)
ax[0].plot(t, col("inlet_flux", -6e4), label="inlet")
if "outlet_flux" in rows[0]:
    ax[0].plot(t, col("outlet_flux", 6e4), "--", label="outlet")
ax[0].set_ylabel("flow rate [L/min]")
ax[0].legend()
ax[1].plot(t, col("valve_dp", 1 / 133.322))
ax[1].set_ylabel("pressure drop [mmHg]")
ax[2].plot(t, col("valve_goa", 1e4), label="orifice area")
ax[2].set_ylabel("orifice area [cm$^2$]")
ax2 = ax[2].twinx()
ax2.plot(t, col("valve_goa_ratio", 100), alpha=0)
ax2.set_ylabel("% of annulus")
ax[3].plot(t, col("valve_leaflet_umax", 1000), label="leaflet max |u|")
if "solid_probe0_uz" in rows[0]:
    ax[3].plot(t, col("solid_probe0_uz", 1000), label="free edge u_z")
ax[3].set_ylabel("displacement [mm]")
ax[3].legend()
ax[3].set_xlabel("time [ms]")
for a in ax:
    a.grid(True, alpha=0.3)
fig.suptitle(" + ".join(os.path.basename(os.path.normpath(x)) for x in dirs))
fig.tight_layout()
out = os.path.join(dirs[-1], "valve_history.png")
fig.savefig(out, dpi=110)
print("wrote", out)
