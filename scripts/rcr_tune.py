#!/usr/bin/python3
"""The outlet Windkessel (RCR) for the pressure-driven valve, tuned on a 0D model of the same
loading: the left-ventricular pressure table of the scene (examples/valve/lv_pressure.dat, gauge
relative to 80 mmHg), an ideal valve of effective orifice area A (Bernoulli loss, blood inertia
in the root, no backflow), and the RCR.  It finds the compliance C and distal resistance R_d for
which the periodic state has the wanted end-diastolic aortic pressure and stroke volume, and
prints the scene's options (SI, gauge relative to 80 mmHg) and the aortic pressure range.

  scripts/rcr_tune.py [--sv 70] [--dia 80] [--area 3.0] [--rp 0.05] [--pv 5]
  (mL, mmHg, cm^2, mmHg s/mL, mmHg)
  scripts/rcr_tune.py --given C,R_d [--area A]   the periodic state of given values instead
  (C in mL/mmHg, R_d in mmHg s/mL)

A 0D model knows nothing of the leaflets: the 3D run's stroke volume follows its own orifice;
this gives the starting values and how the figures move with them."""
import argparse
import os
import numpy as np

MMHG = 133.322          # Pa
ML = 1e-6               # m^3
RHO = 1050.0            # kg/m^3
HERE = os.path.dirname(os.path.abspath(__file__))


def lv_table(path):
    t, p = np.loadtxt(path, comments="#", unpack=True)
    return t, p + 80.0  # absolute mmHg


def cycle(t_tab, p_tab, T, R_p, C, R_d, p_v, area, Pc0, dt=1e-4, inertance=None):
    """One cycle from capacitor pressure Pc0 [mmHg]: stroke volume [mL], aortic pressure
    range [mmHg], the capacitor pressure at its end, the peak flow [mL/s]."""
    A = area * 1e-4
    L = inertance if inertance is not None else RHO * 0.05 / A  # 5 cm of blood column
    # SI: pressures in Pa, flow in m^3/s
    Pc, Q, sv, pmin, pmax, qmax = Pc0 * MMHG, 0.0, 0.0, 1e9, -1e9, 0.0
    Rp, Cs, Rd, pv = R_p * MMHG / ML, C * ML / MMHG, R_d * MMHG / ML, p_v * MMHG
    for k in range(int(round(T / dt))):
        t = k * dt
        plv = np.interp(t % T, t_tab, p_tab) * MMHG
        pao = Pc + Rp * Q
        if Q > 0 or plv > pao:
            dQ = (plv - pao - 0.5 * RHO * (Q / A) ** 2) / L
            Q = max(0.0, Q + dt * dQ)
        Pc += dt * (Q - (Pc - pv) / Rd) / Cs
        sv += Q * dt
        pao = Pc + Rp * Q
        pmin, pmax, qmax = min(pmin, pao), max(pmax, pao), max(qmax, Q)
    return sv / ML, pmin / MMHG, pmax / MMHG, Pc / MMHG, qmax / ML


def periodic(t_tab, p_tab, T, R_p, C, R_d, p_v, area, cycles=40):
    Pc = 80.0
    for _ in range(cycles):
        sv, pmin, pmax, Pc_end, qmax = cycle(t_tab, p_tab, T, R_p, C, R_d, p_v, area, Pc, dt=5e-4)
        if abs(Pc_end - Pc) < 1e-4:
            break
        Pc = Pc_end
    return cycle(t_tab, p_tab, T, R_p, C, R_d, p_v, area, Pc) + (Pc,)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sv", type=float, default=70.0, help="stroke volume [mL]")
    ap.add_argument("--dia", type=float, default=80.0, help="end-diastolic aortic pressure [mmHg]")
    ap.add_argument("--area", type=float, default=3.0, help="effective orifice area [cm^2]")
    ap.add_argument("--rp", type=float, default=0.05, help="R_p [mmHg s/mL]")
    ap.add_argument("--pv", type=float, default=5.0, help="venous pressure [mmHg]")
    ap.add_argument("--period", type=float, default=1.1, help="T [s]")
    ap.add_argument("--table", default=os.path.join(HERE, "..", "examples", "valve", "lv_pressure.dat"))
    ap.add_argument("--given", help="C,R_d: report these instead of tuning")
    a = ap.parse_args()
    if min(a.sv, a.dia, a.area, a.rp, a.period) <= 0:
        raise SystemExit("rcr_tune: --sv, --dia, --area, --rp and --period must be positive")
    t_tab, p_tab = lv_table(a.table)
    if a.given:
        try:
            C, R_d = (float(x) for x in a.given.split(","))
        except ValueError:
            raise SystemExit("rcr_tune: --given takes C,R_d, e.g. --given 2.0,1.0")
        if min(C, R_d) <= 0:
            raise SystemExit("rcr_tune: --given C,R_d must both be positive, e.g. --given 2.0,1.0")
        sv, pmin, pmax, _, qmax, _ = periodic(t_tab, p_tab, a.period, a.rp, C, R_d, a.pv, a.area)
        print(f"0D periodic state with C {C:g} mL/mmHg, R_d {R_d:g} mmHg s/mL, orifice {a.area:g} "
              f"cm^2: stroke {sv:.1f} mL, aorta {pmax:.1f}/{pmin:.1f} mmHg, peak flow {qmax * 60e-3:.1f} L/min")
        return
    # Periodicity ties the mean pressure to the flow: SV / T = mean(P_c - P_v) / R_d.  Search
    # C (which sets how much the aorta swells per stroke) for the stroke volume, with R_d for
    # the end-diastolic pressure at each C (both monotone).
    def rd_for(C):
        lo, hi = 0.2, 10.0
        for _ in range(40):
            mid = np.sqrt(lo * hi)
            pmin = periodic(t_tab, p_tab, a.period, a.rp, C, mid, a.pv, a.area)[1]
            lo, hi = (mid, hi) if pmin < a.dia else (lo, mid)
        return np.sqrt(lo * hi)
    lo, hi = 0.2, 10.0
    for _ in range(30):
        C = np.sqrt(lo * hi)
        R_d = rd_for(C)
        sv = periodic(t_tab, p_tab, a.period, a.rp, C, R_d, a.pv, a.area)[0]
        lo, hi = (C, hi) if sv < a.sv else (lo, C)
    C = np.sqrt(lo * hi)
    R_d = rd_for(C)
    sv, pmin, pmax, _, qmax, Pc0 = periodic(t_tab, p_tab, a.period, a.rp, C, R_d, a.pv, a.area)
    print(f"0D periodic state: stroke {sv:.1f} mL, aorta {pmax:.1f}/{pmin:.1f} mmHg, peak flow "
          f"{qmax * 60e-3:.1f} L/min, cardiac output {sv / a.period * 60e-3:.2f} L/min")
    print(f"R_p {a.rp:.4g} mmHg s/mL, C {C:.4g} mL/mmHg, R_d {R_d:.4g} mmHg s/mL (tau {C * R_d:.3g} s)")
    print("scene options (SI, gauge relative to 80 mmHg):")
    print(f"-bc_outlet_R_p {a.rp * MMHG / ML:.4g}\n-bc_outlet_C {C * ML / MMHG:.4g}\n"
          f"-bc_outlet_R_d {R_d * MMHG / ML:.4g}\n-bc_outlet_p_distal {(a.pv - 80) * MMHG:.5g}\n"
          f"-bc_outlet_p0 {(Pc0 - 80) * MMHG:.5g}")


if __name__ == "__main__":
    main()
