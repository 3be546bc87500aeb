"""Womersley flow over one period from the exact state: centre-line velocity within 2% of the
closed form at every step, and second-order convergence in the time step (generalized-alpha):
the change of the centre-line history between dt and dt/2 must fall by ~4 when dt halves."""
import math
from fsitest import check, finish, run, scene

dts = [0.05, 0.025, 0.0125]
hist = []
for dt in dts:
    r = run(scene("womersley"), extra=["-ts_dt", str(dt)])
    check(r.code == 0, f"dt={dt}: run succeeds")
    rows = r.monitor
    err = max(abs(x["probe0_vz"] - x["probe0_vz_exact"]) for x in rows)
    amp = max(abs(x["probe0_vz_exact"]) for x in rows)
    print(f"dt={dt}: max centre-line error {err:.3e} m/s = {100*err/amp:.3f}% of amplitude {amp:.3e}")
    check(err / amp < 0.02, f"dt={dt}: centre-line error {100*err/amp:.3f}% < 2%")
    # keep values at the times of the coarsest step
    hist.append({round(x["time"], 9): x["probe0_vz"] for x in rows})
times = sorted(hist[0])
d = [max(abs(hist[i][t] - hist[i + 1][t]) for t in times) for i in range(2)]
p = math.log(d[0] / d[1]) / math.log(2)
print(f"self-convergence in dt: |v_dt - v_dt/2| = {d[0]:.3e}, {d[1]:.3e}: order {p:.2f}")
check(p > 1.8, f"time order {p:.2f} > 1.8")
finish()
