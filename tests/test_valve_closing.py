"""The aortic valve closing (issue 16), CI mesh, 2 ranks (tests/scenes/valve_closing.opts): the
aortic pressure rises to 1.3 kPa over 3 ms against a zero-pressure ventricle, 4 steps of 1 ms
(contact offset 0.78 mm, just inside the 0.8 mm reference gap, so that the free edges meet
within the steps a CI test affords: measured at t = 4 ms, 48 pairs).  Solved with the valve's
own preset, direct_lagged (GMRES + a reused MUMPS LU: 3.3 s/step against 9.8 with direct.opts,
the monitors equal to 1.7e-7).
The leaflets are pressed shut: every step converges, the free edges come into contact (pairs
> 0) and stop at the offset (penetration below the ramp's half width plus 2 p/k), the gap seal
is active, the flow is backwards (outlet -> inlet) and no fluid cell or leaflet element
inverts.
The same closing with fieldsplit_fsi_lu (the FSI split with an LU of the leaflets only): the same
answer to the solver's tolerance (measured: monitors within 5e-8, the same Newton counts) in less
memory (277 against 523 MB per rank)."""
from fsitest import check, finish, run, scene

VALVE = scene("valve_closing")
OFFSET, RAMP, PENALTY, P = 0.00078, 0.00078 / 4, 1e8, 1300.0

r = run(VALVE, np=2, presets=("direct_lagged",))
check(r.code == 0 and r.summary["converged"], "the valve closes: every step converges on 2 ranks")
rows = r.monitor if r.code == 0 else []
if rows:
    m = rows[-1]
    print(f"t = {m['time']*1e3:.0f} ms: contact pairs {int(m['contact_pairs'])}, penetration "
          f"{m['contact_max_penetration']*1e6:.1f} um, sealing cells {int(m['seal_cells'])}, "
          f"dp {m['valve_dp']:.0f} Pa, inlet flux {m['inlet_flux']:.2e} m^3/s, leaflet |u| max "
          f"{m['valve_leaflet_umax']*1e3:.2f} mm, Newton {[int(x['newton']) for x in rows]}")
    check(m["contact_pairs"] > 0, "the free edges are in contact")
    check(m["contact_max_penetration"] < RAMP / 2 + 2 * P / PENALTY,
          "they stop at the offset (penetration < ramp/2 + 2 p/k)")
    check(m["seal_cells"] > 0, "the gap seal is active")
    check(all(x["valve_dp"] < 0 for x in rows[1:]), "the aorta is above the ventricle (dp < 0)")
    check(m["inlet_flux"] > 0, "the flow through the valve plane is backwards (leaflets closing)")
    check(min(x["mesh_min_jacobian"] for x in rows) > 0, "no fluid cell inverts")
    # The clinical monitors on the closing valve (measured at 4 ms: 1.17 mm of coaptation over
    # 1.8 mm of the seams, the orifice 6.0 % of the annulus and 0.34 % with the gaps narrower than
    # the contact offset closed).  The free edges have just met: one or two rows of P2 surface
    # nodes (0.75 mm apart at h = 1.5 mm) touch, hence 0.5-3 mm of height.
    print(f"coaptation height {m['valve_coaptation_height']*1e3:.2f} mm, length "
          f"{m['valve_coaptation_length']*1e3:.2f} mm; orifice {m['valve_goa_ratio']*100:.2f} %, "
          f"{m['valve_goa_contact_ratio']*100:.2f} % with touching gaps closed; peak velocity "
          f"{m['valve_peak_velocity']:.3f} m/s at {m['valve_peak_velocity_axial']*1e3:.1f} mm")
    check(0.0005 <= m["valve_coaptation_height"] <= 0.003, "the leaflets touch over 0.5-3 mm of height")
    check(all(x["valve_coaptation_height"] == 0 for x in rows if x["contact_pairs"] == 0),
          "no coaptation height without contact")
    check(m["valve_goa_contact_ratio"] < 0.25 * m["valve_goa_ratio"],
          "gaps narrower than the contact offset count as closed (the orifice falls below a quarter)")
    check(0 < m["valve_peak_velocity"] < 1 and 0 <= m["valve_peak_velocity_axial"] <= 0.03,
          "the peak velocity is found between the annulus and the downstream plane")

s = run(VALVE, np=2, presets=("fieldsplit_fsi_lu",))
check(s.code == 0 and s.summary["converged"], "fieldsplit_fsi_lu: every step converges")
if rows and s.code == 0:
    m, n = rows[-1], s.monitor[-1]
    # measured 9e-8, 2.6e-8, 2.6e-7 and 3.6e-6 (the penetration: a difference of two positions)
    for k, tol in (("valve_dp", 1e-5), ("inlet_flux", 1e-5), ("valve_leaflet_umax", 1e-5),
                   ("contact_max_penetration", 1e-4)):
        rel = abs(n[k] - m[k]) / abs(m[k])
        check(rel < tol, f"fieldsplit_fsi_lu: {k} as with direct_lagged ({rel:.1e} < {tol:g})")
    check(n["contact_pairs"] == m["contact_pairs"], "fieldsplit_fsi_lu: the same contact pairs")
    mem = [x.summary["cost"]["peak_memory_mb_per_rank_max"] for x in (r, s)]
    check(mem[1] < 0.8 * mem[0], f"fieldsplit_fsi_lu: less memory ({mem[1]:.0f} against {mem[0]:.0f} MB)")
finish()
