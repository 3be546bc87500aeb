"""Bad input: one clear line naming the problem, a non-zero exit, no PETSc traceback and no
summary.json that could pass for a finished result."""
import os
import tempfile
from fsitest import check, finish, run, scene

garbage = os.path.join(tempfile.mkdtemp(), "corrupt.msh")
with open(garbage, "w") as f:
    f.write("$MeshFormat\nthis is not a mesh\n")
cases = [
    ("missing mesh file", ["-mesh_file", "/nonexistent/pipe.msh"], "not found"),
    ("corrupt mesh file", ["-mesh_file", garbage], "could not be read"),
    ("unknown boundary name", ["-bc_names", "inlet,outlet,wal", "-bc_wal_type", "noslip"], "wal"),
    ("boundary without type", ["-bc_names", "inlet,outlet,wall,inlet2"], "inlet2"),
    ("negative viscosity", ["-fluid_mu", "-0.004"], "fluid_mu"),
    ("negative rebuild interval", ["-sim_rebuild_every", "-1"], "sim_rebuild_every"),
    ("negative pattern rebuild interval", ["-sim_pattern_rebuild_every", "-2"], "sim_pattern_rebuild_every"),
    ("zero density", ["-fluid_rho", "0"], "fluid_rho"),
    ("unknown option value", ["-fluid_model", "eulerian"], "eulerian"),
    ("unknown physics", ["-physics", "fluid,magnetism"], "magnetism"),
    ("option nobody reads", ["-fluid_viscosity", "0.004"], "fluid_viscosity"),
    ("output directory not writable", ["-out_dir", "/proc/fsi_results"], "output directory"),
    ("mesh slip on a curved wall", ["-ale_motion", "laplace", "-ale_slip_boundaries", "wall"], "axis-aligned plane"),
    ("unknown mesh motion", ["-ale_motion", "elastic"], "elastic"),
    ("sealed cells ignored without a gap seal", ["-ale_remesh_ignore_sealed"], "gap_seal"),
    ("mesh without the fluid region", ["-fluid_region", "blood"], "blood"),
    ("zero time step", ["-ts_type", "alpha", "-ts_dt", "0"], "ts_dt"),
    ("negative time step", ["-ts_type", "alpha", "-ts_dt", "-1e-3"], "ts_dt"),
    ("unknown predictor", ["-ts_type", "alpha", "-ts_predictor", "quadratic"], "quadratic"),
    ("unknown convection form", ["-fluid_convection", "rotational"], "rotational"),
    ("wall shear on a missing surface", ["-hemo_surfaces", "aorta"], "aorta"),
    ("negative checkpoint interval", ["-checkpoint_every", "-1"], "checkpoint_every"),
    ("missing restart file", ["-restart", "/nonexistent/checkpoint.h5"], "/nonexistent/checkpoint.h5"),
    ("negative field interval", ["-out_fields_every", "-1"], "out_fields_every"),
    ("negative easy-Newton count", ["-step_easy_newton", "-1"], "step_easy_newton"),
    ("misspelt PETSc type", ["-ksp_type", "nosuchksp"], "-ksp_type"),
    ("unknown solver preset", ["-solver_preset", "nosuchpreset"], "-solver_preset"),
    ("missing options file", ["-options_file", "/nonexistent/scene.opts"], "/nonexistent/scene.opts"),
    ("corrupt restart file", ["-restart", garbage], "not an HDF5 file"),
]
solid_cases = [
    ("zero Young's modulus", ["-solid_material", "neo_hookean", "-solid_E", "0", "-solid_nu", "0.3"], "solid_E"),
    ("nu above 0.5", ["-solid_material", "neo_hookean", "-solid_E", "1e4", "-solid_nu", "0.6"], "solid_nu"),
    ("negative solid density", ["-solid_rho", "-1000"], "solid_rho"),
    ("incompressible linear solid", ["-solid_material", "svk", "-solid_E", "1e4", "-solid_nu", "0.5"], "solid_nu"),
    ("unknown material", ["-solid_material", "ogden"], "ogden"),
    ("Mooney-Rivlin without kappa", ["-solid_kappa", "-5"], "solid_kappa"),
    ("mesh without the solid region", ["-solid_region", "tissue"], "tissue"),
    ("fibre options without a fibre family", ["-solid_fibre_c1", "1e4"], "solid_fibres"),
    ("chord fibres without commissures", ["-solid_fibres", "chord", "-solid_fibre_c1", "1e4",
                                          "-solid_fibre_c2", "10"], "solid_fibre_commissures"),
    ("negative fibre modulus", ["-solid_fibres", "circumferential", "-solid_fibre_c1", "-1",
                                "-solid_fibre_c2", "10"], "solid_fibre_c1"),
    ("unknown solid boundary type", ["-bc_zmax_type", "pinned"], "pinned"),
]
# A checkpoint of the Poiseuille scene, then restarts that do not match it.
ck = run(scene("poiseuille"), extra=["-checkpoint_every", "1"])
ckfile = os.path.join(ck.dir, "checkpoint.h5")
check(ck.code == 0 and os.path.exists(ckfile), "a checkpoint to restart from")
cases += [
    ("restart file from another mesh", ["-restart", ckfile, "-mesh_params", "R=0.005,L=0.01,ncirc=30"], "another mesh"),
    ("restart file from another scene", ["-restart", ckfile, "-ts_type", "alpha", "-ts_dt", "0.1"], "another scene"),
]
cases += [("Windkessel resistance 0", ["-bc_outlet_type", "windkessel", "-bc_outlet_R_p", "0",
                                      "-bc_outlet_C", "1e-8", "-bc_outlet_R_d", "1e8"], "R_p")]
# The valve: leaflets that would intersect (refused by valve.geo before any mesh is built), and
# a contact offset wider than the gap the mesh leaves between the leaflets at rest, an annulus
# that is neither a circle (one radius) nor a polar curve (three or more).
valve_cases = [
    ("leaflets intersecting", ["-mesh_params", "gap=0"], "gap"),
    ("contact offset wider than the gap", ["-contact_offset", "0.0009"], "contact_offset"),
    ("an annulus of two radii", ["-valve_annulus_radius", "0.0125,0.012"], "valve_annulus_radius"),
]
for name, extra, needle, sc in ([c + ("poiseuille",) for c in cases] +
                                [c + ("mr_uniaxial",) for c in solid_cases] +
                                [c + ("valve_closing",) for c in valve_cases]):
    r = run(scene(sc), extra=extra)
    lines = [l for l in r.out.splitlines() if "fsi_app: error:" in l]
    check(r.code != 0, f"{name}: non-zero exit ({r.code})")
    check(len(lines) == 1 and needle in lines[0], f"{name}: one error line naming '{needle}'")
    check("PETSC ERROR" not in r.out, f"{name}: no PETSc traceback")
    outdir = r.dir if "-out_dir" not in extra else extra[extra.index("-out_dir") + 1]
    check(not os.path.exists(os.path.join(outdir, "summary.json")), f"{name}: no summary.json")
    if lines:
        print("   message:", lines[0])
finish()
