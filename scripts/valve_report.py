"""Figures of a valve run for a note or a paper, from its monitor.csv, remesh.csv and summary.json:
  /usr/bin/python3 scripts/valve_report.py DIR [DIR ...] [--every MS] [--period S] [--hold MS]
                                           [--diastole S] [--stroke ML] [--closed COND]
Several DIRs are the pieces of one run continued by -restart, in order: where a later piece
starts, the earlier one's rows stop.  Prints (markdown)
  - the state every MS milliseconds (default 25): flow rate, transvalvular pressure drop, orifice
    area, leaflet displacement and stress, contact pairs, sealed cells, Newton, dt;
  - per cycle of the inlet's period (default 1.1 s): forward (ejected) and backward (regurgitant)
    volume through the inlet, and their ratio; and the regurgitant volume split the clinical way
    at the instant the valve closes (--closed COND, default contact_pairs>100, the valve scenes'
    own test: the first row after the cycle's peak forward flow where COND holds; COND is
    COLUMN>VALUE or COLUMN<VALUE joined by &, on monitor.csv's columns): the closing volume (flow
    back before that instant) against the ejected volume (flow forward while the valve is not
    closed), and the leakage volume (the net flow back from it until the valve reopens (the
    cycle's end, or the first of the open rows that end the cycle, whose forward flow is the next
    ejection started early and counts as ejected), so that a closed valve's ringing back and
    forth counts only by its net, plus the net flow back while closed before the cycle's
    opening: the previous diastole's tail);
  - per cycle, the figures a cardiologist reads (what each means: docs/valve.md): peak and
    peak-flow orifice area, mean systolic gradient, peak transvalvular velocity, opening and
    closing times (and the rapid closing phase alone, and the orifice left when the flow
    reverses), the diastolic orifice and coaptation height, the aortic pressure range
    (--p-offset MMHG: added to the outlet pressure, for scenes in gauge; 80 for valve_pressure);
  - with --hold MS (a closed valve under a held load, from MS to the end): the leak, i.e. the mean
    flow back through the valve over whole periods of the leaflets' ringing (from the first to the
    last upward crossing of the mean), the same leak from a fit of a decaying oscillation about
    a constant, the net volume, and each period's flow swing; and the regurgitant volume per
    cycle that leak gives over a diastole of S seconds (default 0.79: the paper's inflow, Fig. 7,
    stops at 0.309 s of its 1.1 s cycle) against a stroke volume of ML millilitres (default
    102.1: that table's);
  - per cycle, the periodic state: stroke volume, end-diastolic aortic pressure (the outlet's at
    the cycle's end, with --p-offset) and regurgitant volume, their change from the cycle before,
    and the first cycle from which each changes by less than 2 %;
  - per cycle, where the time goes: opening (to 90 % of the peak orifice), ejection (to the
    closure), closure ringing (50 ms), diastole: steps, their wall time, remeshes and theirs;
  - cost: steps, cut steps, s/step, Newton and Krylov per step, remeshes and their share of the
    wall time, peak memory per rank."""
import json
import os
import sys

import numpy as np

from run_pieces import read_rows, stitch


args = sys.argv[1:]


def take(flag, default):
    """The number after FLAG in args (removed from them), else default; a bad value exits."""
    if flag not in args:
        return default
    i = args.index(flag)
    try:
        value = float(args[i + 1])
    except (IndexError, ValueError):
        sys.exit(f"valve_report: {flag} needs a number, e.g. {flag} {default if default is not None else 40}")
    del args[i:i + 2]
    return value


def take_text(flag, default):
    """The word after FLAG in args (removed from them), else default."""
    if flag not in args:
        return default
    i = args.index(flag)
    if i + 1 >= len(args):
        sys.exit(f"valve_report: {flag} needs a " + (f"condition, e.g. {flag} '{default}'" if default
                                                      else "file name, e.g. --json figures.json"))
    value = args[i + 1]
    del args[i:i + 2]
    return value


def parse_condition(text):
    """COLUMN>VALUE or COLUMN<VALUE terms joined by & as (column, sign, value) triples; a malformed
    term exits naming the option."""
    terms = []
    for term in text.split("&"):
        op = ">" if ">" in term else "<" if "<" in term else None
        column, _, value = term.partition(op) if op else ("", "", "")
        try:
            terms.append((column.strip(), 1.0 if op == ">" else -1.0, float(value)))
        except ValueError:
            op = None
        if not op or not column.strip():
            sys.exit(f"valve_report: --closed '{text}': each term must be COLUMN>VALUE or COLUMN<VALUE "
                     "(joined by &), e.g. --closed 'contact_pairs>100'")
    return terms


every = take("--every", 25.0)
period = take("--period", 1.1)
hold = take("--hold", None)
hold = hold * 1e-3 if hold is not None else None
diastole = take("--diastole", 0.79)
stroke = take("--stroke", 102.1)
closed_text = take_text("--closed", "contact_pairs>100")
p_offset = take("--p-offset", 0.0)
closed_terms = parse_condition(closed_text)
json_out = take_text("--json", None)
if json_out and not os.path.isdir(os.path.dirname(os.path.abspath(json_out))):
    sys.exit(f"valve_report: --json {json_out}: its directory does not exist")
if diastole <= 0 or stroke <= 0:
    sys.exit("valve_report: --diastole and --stroke must be positive (seconds, millilitres), e.g. --diastole 0.79 --stroke 102.1")
if not args:
    sys.exit(__doc__)
mon = stitch([read_rows(d, "monitor.csv") for d in args], "step")
rem = stitch([read_rows(d, "remesh.csv") for d in args], "step")
if not mon:
    sys.exit("valve_report: no monitor rows in " + " ".join(args))
missing = sorted({c for c, _, _ in closed_terms if c not in mon[0]})
if missing:
    sys.exit(f"valve_report: --closed '{closed_text}': the run has no monitor column " +
             ", ".join(f"'{c}'" for c in missing) + "; its columns: " + ", ".join(mon[0]))
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
for r in mon:  # flow at the step's end x its step (a piece resumed mid-cycle starts right)
    c = int(r["time"] / period - 1e-12)
    q = -r["inlet_flux"] * r["dt"]
    f, b, t0, t1 = cycles.get(c, (0.0, 0.0, r["time"], r["time"]))
    cycles[c] = (f + max(q, 0), b + max(-q, 0), min(t0, r["time"]), r["time"])
for c, (f, b, t0, t1) in sorted(cycles.items()):
    print(f"| {c + 1} | {t0*1e3:.1f} | {t1*1e3:.1f} | {f*1e6:.2f} | {b*1e6:.3f} | {b/f*100 if f else 0:.2f} % |")


def is_closed(r):
    return all(sign * (r[col] - value) > 0 for col, sign, value in closed_terms)


def regurgitation(rows):
    """For one cycle's rows (flow to the aorta q = -inlet_flux, volumes by q x the row's step as in
    the table above): the ejected volume (flow forward while the valve is not closed), closure
    time (None if not closed), closing volume (flow back between the peak forward flow and the
    closure), leakage after the closure (net flow back from the closure until the valve reopens:
    the rows after the last closed one, where a valve that opens before the cycle's end starts
    its next ejection, count as ejection, and any flow back there as leakage) and leakage before
    the opening (net flow back over the rows where the valve counts as closed before the forward
    flow that rises to the peak starts: the tail of the previous diastole)."""
    steps = np.array([r["dt"] for r in rows])
    q = np.array([-r["inlet_flux"] for r in rows])
    vol = q * steps
    peak = int(np.argmax(q))
    tc = next((i for i in range(peak + 1, len(rows)) if is_closed(rows[i])), None)
    end = tc if tc is not None else len(rows)
    reopen = len(rows)  # the open rows after the last closed one: the next ejection, started early
    if tc is not None:
        while reopen - 1 > tc and not is_closed(rows[reopen - 1]):
            reopen -= 1
    # Ejection starts after the last row before the peak without forward flow, even where the
    # leaflets still touch (they bulge forward before they part): no leakage from there on.
    start = max((i for i in range(peak) if q[i] <= 0), default=-1)
    shut_before = [i for i in range(start + 1) if is_closed(rows[i])]
    open_rows = np.setdiff1d(np.arange(end), shut_before)
    ejected = float(np.sum(np.maximum(vol[open_rows], 0)) + np.sum(np.maximum(vol[reopen:], 0)))
    closing = float(np.sum(np.maximum(-vol[peak + 1:end], 0)))
    after = float(-np.sum(vol[end:reopen]) + np.sum(np.maximum(-vol[reopen:], 0))) + 0.0  # no "-0.000"
    before = float(-np.sum(vol[shut_before])) + 0.0
    reopened = rows[reopen]["time"] if reopen < len(rows) else None
    return ejected, rows[tc]["time"] if tc is not None else None, closing, after, before, reopened


per_cycle = {}  # cycle -> (ejected, regurgitant [m^3], outlet pressure at its end [Pa], complete)
record = {}  # cycle -> its named figures (--json)
print(f"\n| cycle | closed at [ms] (--closed {closed_text}) | ejected [mL] | closing [mL] | leakage after "
      "closure [mL] | leakage before opening [mL] | regurgitant [mL] | regurgitant fraction |")
print("|---|---|---|---|---|---|---|---|")
for c in sorted(cycles):
    rows = [r for r in mon if int(r["time"] / period - 1e-12) == c]
    f, tc, closing, after, before, reopened = regurgitation(rows)
    shut = f"{tc*1e3:.1f}" if tc is not None else f"not by {rows[-1]['time']*1e3:.1f}"
    if reopened is not None:
        shut += f", open again at {reopened*1e3:.1f}"
    reg = closing + after + before
    complete = rows[-1]["time"] >= (c + 1) * period - 1.5 * rows[-1]["dt"]
    per_cycle[c] = (f, reg, rows[-1].get("outlet_p"), complete)
    t_end = reopened if reopened is not None else rows[-1]["time"]
    record[c] = {"cycle": c + 1, "complete": complete, "ejected_mL": f * 1e6, "closing_mL": closing * 1e6,
                 "leakage_mL": (after + before) * 1e6, "regurgitant_mL": reg * 1e6,
                 "regurgitant_fraction_percent": reg / f * 100 if f else None,
                 "closed_at_s": tc, "leak_L_min": after / (t_end - tc) * 6e4 if tc is not None and t_end > tc else None,
                 "end_diastolic_aorta_mmHg": rows[-1]["outlet_p"] / 133.322 + p_offset
                 if complete and "outlet_p" in rows[-1] else None}
    print(f"| {c + 1} | {shut} | {f*1e6:.2f} | {closing*1e6:.3f} | {after*1e6:.3f} | {before*1e6:.3f} | {reg*1e6:.3f} | "
          f"{reg/f*100 if f else 0:.2f} % |")


def crossing(t, y, level, rising, start, stop):
    """First time in rows [start, stop) where y crosses level upwards (rising) or downwards,
    linearly interpolated; None if it does not."""
    for i in range(max(start, 1), stop):
        a, b = y[i - 1], y[i]
        if (a < level <= b) if rising else (a > level >= b):
            return t[i - 1] + (level - a) / (b - a) * (t[i] - t[i - 1])
    return None


def rapid_closing(t, goa, start, end_time, closed):
    """The rapid closing phase (the leaflets' fast swing that ends the slow drift of ejection,
    Laniado 1976): 90 -> 10 % of the fall from where the closing speed (over 5 ms) first exceeds
    20 % of its largest value before end_time, to the closed orifice. None if it cannot say."""
    if end_time is None:
        return None
    u = np.arange(t[start], end_time + 1e-12, 2.5e-4)
    if len(u) < 21:
        return None
    g = np.interp(u, t, goa)
    speed = np.zeros_like(g)
    speed[10:-10] = (g[:-20] - g[20:]) / (u[20:] - u[:-20])
    fastest = int(np.argmax(speed))
    slow = np.nonzero(speed[:fastest] < 0.2 * speed[fastest])[0]
    if len(slow) == 0:
        return None
    top = g[slow[-1]]
    a = crossing(u, g, closed + 0.9 * (top - closed), False, slow[-1], len(u))
    b = crossing(t, goa, closed + 0.1 * (top - closed), False, int(np.searchsorted(t, u[slow[-1]])), len(t))
    return (b - a) * 1e3 if a is not None and b is not None else None


def clinical(rows):
    """A cycle's clinical figures: dict of name -> value (None where the run cannot say)."""
    t = np.array([r["time"] for r in rows])
    dt = np.array([r["dt"] for r in rows])
    q = np.array([-r["inlet_flux"] for r in rows])
    col = lambda k: np.array([r.get(k, np.nan) for r in rows])
    goa, dp = col("valve_goa"), col("valve_dp")
    peak = int(np.argmax(q))
    tc = next((i for i in range(peak + 1, len(rows)) if is_closed(rows[i])), len(rows))
    out = {}
    if "outlet_p" in rows[0]:
        pa = col("outlet_p") / 133.322 + p_offset
        out["aorta_max_mmHg"], out["aorta_min_mmHg"] = float(np.max(pa)), float(np.min(pa))
    if "valve_goa" not in rows[0]:
        return out
    out["peak_goa_cm2"] = np.nanmax(goa) * 1e4
    win = np.abs(t - t[peak]) <= 0.02  # +-20 ms about peak flow: the leaflets flutter there
    out["peak_flow_goa_cm2"] = float(np.nanmean(goa[win])) * 1e4
    eject = np.arange(len(rows)) < tc
    eject &= q > 0
    out["mean_gradient_mmHg"] = float(np.sum(dp[eject] * dt[eject]) / np.sum(dt[eject])) / 133.322 if eject.any() else None
    out["peak_velocity_m_s"] = float(np.nanmax(col("valve_peak_velocity")[eject])) if eject.any() and "valve_peak_velocity" in rows[0] else None
    # Opening and closing: 10 -> 90 % (90 -> 10 %) of the swing between the cycle's smallest
    # orifice before the peak and the largest.
    g_top = int(np.nanargmax(goa))
    lo, hi = np.nanmin(goa[:g_top + 1]), goa[g_top]
    l10, l90 = lo + 0.1 * (hi - lo), lo + 0.9 * (hi - lo)
    a, b = crossing(t, goa, l10, True, 0, g_top + 1), crossing(t, goa, l90, True, 0, g_top + 1)
    out["opening_ms"] = (b - a) * 1e3 if a is not None and b is not None else None
    out["_opened"], out["_closed"] = b, t[tc] if tc < len(rows) else None  # phase bounds (cost)
    lo2 = np.nanmin(goa[g_top:])
    l10c, l90c = lo2 + 0.1 * (hi - lo2), lo2 + 0.9 * (hi - lo2)
    last90 = max((i for i in range(g_top, len(rows)) if goa[i] >= l90c), default=g_top)
    c90 = crossing(t, goa, l90c, False, last90, len(rows))
    c10 = crossing(t, goa, l10c, False, last90, len(rows))
    out["closing_ms"] = (c10 - c90) * 1e3 if c10 is not None and c90 is not None else None
    out["closing_rapid_ms"] = rapid_closing(t, goa, last90, c10, lo2)
    # Laniado 1976: a healthy valve is shut at zero flow; how open ours is when the flow reverses.
    rev = next((i for i in range(peak + 1, len(rows)) if q[i] <= 0), None)
    out["goa_at_reversal_percent"] = float(goa[rev] / hi) * 100 if rev is not None else None
    shut = np.array([is_closed(r) for r in rows]) & (np.arange(len(rows)) > peak)
    ratio = col("valve_goa_contact_ratio") if "valve_goa_contact_ratio" in rows[0] else col("valve_goa_ratio")
    out["diastolic_goa_percent"] = float(np.median(ratio[shut])) * 100 if shut.any() else None
    out["coaptation_height_mm"] = (float(np.median(col("valve_coaptation_height")[shut])) * 1e3
                                   if shut.any() and "valve_coaptation_height" in rows[0] else None)
    if "valve_leaflet_vm_max" in rows[0]:  # the largest leaflet von Mises stress, open and closed
        vm = col("valve_leaflet_vm_max") / 1e3
        out["leaflet_vm_systole_kPa"] = float(np.nanmax(vm[:tc])) if tc > 0 else None
        out["leaflet_vm_diastole_kPa"] = float(np.nanmax(vm[shut])) if shut.any() else None
    return out


names = [("peak_goa_cm2", "peak orifice [cm^2]"), ("peak_flow_goa_cm2", "orifice at peak flow +-20 ms [cm^2]"),
         ("mean_gradient_mmHg", "mean systolic gradient [mmHg]"), ("peak_velocity_m_s", "peak velocity [m/s]"),
         ("opening_ms", "opening 10-90 % [ms]"), ("closing_ms", "closing 90-10 % [ms]"),
         ("closing_rapid_ms", "rapid closing [ms]"), ("goa_at_reversal_percent", "orifice at flow reversal [% of peak]"),
         ("diastolic_goa_percent", "closed orifice [% annulus]"),
         ("coaptation_height_mm", "coaptation height [mm]"), ("aorta_max_mmHg", "aorta max [mmHg]"),
         ("aorta_min_mmHg", "aorta min [mmHg]"), ("leaflet_vm_systole_kPa", "leaflet von Mises open [kPa]"),
         ("leaflet_vm_diastole_kPa", "closed [kPa]")]
figs = {c: clinical([r for r in mon if int(r["time"] / period - 1e-12) == c]) for c in sorted(cycles)}
print("\n| cycle | " + " | ".join(n for _, n in names) + " |")
print("|---|" + "---|" * len(names))
for c, f in figs.items():
    print(f"| {c + 1} | " + " | ".join("-" if f.get(k) is None else f"{f[k]:.3g}" for k, _ in names) + " |")


def leak_over_periods(t, q):
    """Mean of a ringing flow q(t) over its whole periods: the integral between the first and last
    upward crossings of that mean over their distance, by fixed-point iteration from the plain
    mean.  Returns (mean, first, last crossing, each period's max - min), or None if the flow
    crosses its mean upwards fewer than twice."""
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (q[1:] + q[:-1]) * np.diff(t))])  # trapezoid

    def integral(a, b):  # q linear between rows: its integral is quadratic; interp is exact at rows
        def at(x):
            i = min(max(np.searchsorted(t, x) - 1, 0), len(t) - 2)
            s = x - t[i]
            slope = (q[i + 1] - q[i]) / (t[i + 1] - t[i])
            return cum[i] + q[i] * s + 0.5 * slope * s * s
        return at(b) - at(a)

    def up_crossings(m):
        i = np.nonzero((q[:-1] < m) & (q[1:] >= m))[0]
        return t[i] + (m - q[i]) * (t[i + 1] - t[i]) / (q[i + 1] - q[i])

    mean = cum[-1] / (t[-1] - t[0])
    for _ in range(20):
        ups = up_crossings(mean)
        if len(ups) < 2:
            return None
        new = integral(ups[0], ups[-1]) / (ups[-1] - ups[0])
        done = abs(new - mean) < 1e-12
        mean = new
        if done:
            break
    ups = up_crossings(mean)
    swings = [np.ptp(q[(t >= lo) & (t <= hi)]) for lo, hi in zip(ups, ups[1:])]
    return mean, ups[0], ups[-1], swings


def leak_fit(t, q, period):
    """Least-squares fit of q = a + exp(-k s) (b cos w s + c sin w s), s = t - t[0], over a grid of
    decay rates k and of angular frequencies w about 2 pi / period (a, b, c linear for each): the
    leak a without the bias a decaying ringing leaves in a mean over whole periods.  Returns
    (a, k, w, rms residual)."""
    s = t - t[0]
    best = None
    for w in 2 * np.pi / period * np.linspace(0.5, 2.0, 151):
        for k in np.linspace(0, 5 / s[-1], 101):
            e = np.exp(-k * s)
            A = np.column_stack([np.ones_like(s), e * np.cos(w * s), e * np.sin(w * s)])
            coef, *_ = np.linalg.lstsq(A, q, rcond=None)
            rms = float(np.sqrt(np.mean((A @ coef - q) ** 2)))
            if best is None or rms < best[3]:
                best = (coef[0], k, w, rms)
    return best


if hold is not None:
    held = [r for r in mon if r["time"] >= hold - 1e-12]
    print(f"\nHold from {hold*1e3:.1f} ms:")
    if len(held) < 3:
        print("  too few rows")
    else:
        t = np.array([r["time"] for r in held])
        q = np.array([r["inlet_flux"] for r in held])  # > 0: out through the inlet, to the ventricle
        net = float(np.sum(0.5 * (q[1:] + q[:-1]) * np.diff(t)))
        print(f"  to {t[-1]*1e3:.1f} ms: net {net*1e6:.3f} mL back through the valve, "
              f"{net/(t[-1] - t[0])*6e4:.3f} L/min on average (ringing included)")
        res = leak_over_periods(t, q)
        if res is None:
            print("  less than one whole period of the ringing: no leak figure")
        else:
            mean, a, b, swings = res
            print(f"  over {len(swings)} whole period(s) of the ringing, {a*1e3:.2f} -> {b*1e3:.2f} ms "
                  f"(period {(b - a)/len(swings)*1e3:.1f} ms): leak {mean*6e4:.3f} L/min = "
                  f"{mean*1e6:.2f} mL/s; flow swing per period " +
                  ", ".join(f"{w*6e4:.2f}" for w in swings) + " L/min")
            a_fit, k, w, rms = leak_fit(t, q, (b - a) / len(swings))
            print(f"  fit a + exp(-k t)(b cos wt + c sin wt) over the hold: leak a = {a_fit*6e4:.3f} L/min = "
                  f"{a_fit*1e6:.2f} mL/s, decay time 1/k = {1/k*1e3 if k > 0 else float('inf'):.1f} ms, "
                  f"period {2*np.pi/w*1e3:.1f} ms, rms misfit {rms*6e4:.3f} L/min")
            lo, hi = sorted((mean, a_fit))
            print(f"  over a {diastole:.2f} s diastole under this load: {lo*diastole*1e6:.1f}-"
                  f"{hi*diastole*1e6:.1f} mL back per cycle = {lo*diastole*1e6/stroke*100:.1f}-"
                  f"{hi*diastole*1e6/stroke*100:.1f} % of a {stroke:.1f} mL stroke volume")

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


# Periodic state: the cycle from which stroke volume, end-diastolic aortic pressure (the outlet's
# at the cycle's end) and regurgitant volume each change by less than 2 % from the cycle before.
print("\n| cycle | stroke [mL] | end-diastolic aorta [mmHg] | regurgitant [mL] | change from the cycle before |")
print("|---|---|---|---|---|")
periodic, before = None, None
for c, (f, reg, p_end, complete) in sorted(per_cycle.items()):
    now = (f, (p_end / 133.322 + p_offset) if p_end is not None else None, reg)
    change = "-"
    if not complete:
        change = f"incomplete (to {max(r['time'] for r in mon)*1e3:.1f} ms)"
    elif before is not None:  # a run without an outlet pressure compares the two volumes
        d = {k: abs(a - b) / abs(b) * 100 if b else float("inf")
             for k, a, b in zip(("stroke", "aorta", "regurgitant"), now, before) if a is not None and b is not None}
        change = ", ".join(f"{k} {v:.1f} %" for k, v in d.items())
        if periodic is None and max(d.values()) < 2:
            periodic = c + 1
    print(f"| {c + 1} | {f*1e6:.2f} | " + (f"{now[1]:.1f}" if now[1] is not None else "-") +
          f" | {reg*1e6:.3f} | {change} |")
    before = now if complete else None
print(f"\nperiodic (each change < 2 %): {'from cycle ' + str(periodic) if periodic else 'not yet'}")

# Where the time goes, per cycle: opening (to 90 % of the peak orifice), ejection (to the closure,
# --closed), closure ringing (the 50 ms after it), diastole (the rest); steps' and remeshes' wall.
print("\n| cycle | phase | from [ms] | to [ms] | steps | step wall [min] | remeshes | remesh wall [min] |")
print("|---|---|---|---|---|---|---|---|")
for c, f in figs.items():
    t0, t1 = c * period, (c + 1) * period
    bounds = [t0, f.get("_opened"), f.get("_closed"), f["_closed"] + 0.05 if f.get("_closed") else None, t1]
    names_ph = ["opening", "ejection", "closure ringing", "diastole"]
    for i, name in enumerate(names_ph):
        lo = bounds[i]
        hi = next((b for b in bounds[i + 1:] if b is not None), t1)
        if lo is None:
            continue
        hi = min(hi, t1)
        inside = [r for r in mon if lo < r["time"] <= hi + 1e-12 and c == int(r["time"] / period - 1e-12)]
        if not inside:
            continue
        rm = [x for x in rem if lo < x["time"] <= hi + 1e-12]
        print(f"| {c + 1} | {name} | {lo*1e3:.1f} | {inside[-1]['time']*1e3:.1f} | {len(inside)} | "
              f"{sum(r['step_seconds'] for r in inside)/60:.1f} | {len(rm)} | {sum(x['seconds'] for x in rm)/60:.1f} |")

if json_out:  # every figure above by name, per cycle (scripts/study's --qoi valve:NAME reads them)
    for c, f in figs.items():
        record[c].update({k: None if v is not None and np.isnan(v) else v for k, v in f.items() if not k.startswith("_")})
    cost = {"steps": steps, "step_wall_s": wall, "remeshes": len(rem), "remesh_wall_s": remesh_s,
            "peak_memory_mb_per_rank": None if np.isnan(peak) else peak}
    with open(json_out, "w") as fh:
        json.dump({"cycles": [record[c] for c in sorted(record)], "cost": cost}, fh, indent=1,
                  default=lambda x: float(x))
