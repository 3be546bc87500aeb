"""Option fuzzing (issue 17): every option `fsi_app -help` lists gets bad values of its kind
(numbers: a word, NaN, inf, 1e999, empty; integers also 2.5; vectors: too few, words, NaN;
keywords: an unknown one; flags: a non-boolean; files: a missing one, a directory) on a small
scene that reads it, and each run must end with exit 2, exactly one `fsi_app: error:` line naming
the option, no PETSc traceback, no backtrace or abort, and no summary.json.  Every number also
gets -1 and 0: an integer count must refuse -1 as above; otherwise the run either works (exit 0)
or ends as above (the sign may be meaningful: a body force, a gauge pressure).
Solver options (-snes_*, -ksp_*, -pc_*, ...) are PETSc's and not fuzzed here.
  test_option_fuzz.py          CI: one bad value per option
  test_option_fuzz.py --all    every bad value of every option, -1 and 0 for every number (scripts/fuzz_options)"""
import os
import re
import subprocess
import sys
from fsitest import APP, ENV, SRC, check, finish, run, scene

ALL = "--all" in sys.argv
p = subprocess.run(["mpirun", "-n", "1", APP, "-help"], cwd="/tmp", env=ENV, text=True,
                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=120)
names = []
ours = p.stdout[p.stdout.find("Every option: -name"):]  # after PETSc's own -help preamble
for line in ours.splitlines():
    m = re.match(r"  -(\S+)\s+<", line)
    if m:
        names += [n.strip().lstrip("-") for n in m.group(1).split(",") if n.strip()]

ES = [scene("ethier_steinman"), "-mesh_h", "1", "-ts_max_steps", "1"]
POIS = [scene("poiseuille"), "-ts_max_steps", "1"]
# Its smallest step half its 10 ms: a sign that the numerics cannot take (-bc_inlet_value -1,
# 1 m^3/s out) ends in exit 3 after one cut, not 10 (56 s of this test's 225).
WK = [scene("windkessel_pipe"), "-ts_max_steps", "1", "-ts_adapt_dt_min", "0.005"]
SOLID = [scene("mr_uniaxial"), "-ts_max_steps", "1"]
FSI = [scene("plates_closing"), "-ts_max_steps", "1"]
VALVE = [scene("valve_closing"), "-ts_max_steps", "1"]
MMS = [scene("solid_mms"), "-ts_max_steps", "1"]
WOM = [scene("womersley"), "-ts_max_steps", "1"]

PETSC = ("snes_", "ksp_", "pc_", "jac_", "fieldsplit_", "ale_ksp_")
SKIP = {"physics", "scene_name", "mesh_params",  # free text (physics: tests/test_bad_input.py)
        "help", "schur_*"}  # schur_*: a PETSc prefix (-schur_pc_type ...)
KEYWORDS = {"ic", "ts_type", "ts_adapt_type", "fluid_model", "solid_material", "ale_motion",
            "exact_solution", "exact_displacement", "fluid_region", "solid_region",
            "contact_surface", "ale_interface", "ale_slip_boundaries", "hemo_surfaces",
            "monitor_surfaces", "bc_names", "bc_<b>_type", "bc_<b>_profile", "bc_<b>_waveform",
            "bc_<b>_jacobian", "bc_<b>_components", "solid_gravity_waveform"}
VECTORS = {"ic_velocity", "solid_gravity", "probe_points", "solid_probe_points", "valve_center",
           "valve_axis", "valve_dp_planes", "bc_<b>_direction", "bc_<b>_center"}
FLAGS = {"allow_unused_options", "restart_reset_dt", "ale_remesh_ignore_sealed",
         "monitor_fluid_volume", "monitor_solid_energy",
         "fluid_direct_insertion", "solid_direct_insertion", "bc_<b>_periodic"}
FILES = {"mesh_file", "mesh_geo", "restart", "bc_<b>_table"}
INTEGERS = {"out_fields_every", "checkpoint_every", "checkpoint_crash_test", "sim_rebuild_every",
            "sim_pattern_rebuild_every", "ts_max_steps", "step_grow_after", "step_easy_newton",
            "fluid_quad_degree", "solid_quad_degree", "ale_geometry_iterations",
            "ale_remesh_every", "ale_remesh_verbose",
            "ale_remesh_test_fault", "valve_goa_pixels", "test_fault_residual"}
EXPRESSIONS = {"bc_<b>_expr"}


# Options read only in some modes, and the mode that reads them (without it the only error is
# "nobody reads", which would pass without testing the value).
ADAPT = ["-ts_adapt_type", "error"]
MODES = {"ic_velocity": ES + ["-ic", "velocity"], "ale_amplitude": ES + ["-ale_motion", "prescribed"],
         "ale_time": ES + ["-ale_motion", "prescribed"], "ts_rtol": ES + ADAPT,
         "ts_atol": ES + ADAPT, "ts_adapt_wnormtype": ES + ADAPT, "ts_adapt_dt_max": ES + ADAPT,
         "ts_adapt_safety": ES + ADAPT, "ts_adapt_max_rejections": ES + ADAPT}


def base(name):
    """The scene that reads the option, and the concrete option name."""
    if name in MODES:
        return MODES[name], name
    if name == "restart_reset_dt":  # read on resuming: a checkpoint of the ES scene
        ck = run(ES[0], extra=ES[1:] + ["-checkpoint_every", "1"])
        return ES + ["-restart", os.path.join(ck.dir, "checkpoint.h5")], name
    if name.startswith("bc_<b>_"):
        tail = name[len("bc_<b>_"):]
        if tail in ("R_p", "C", "R_d", "p_distal", "p0", "jacobian", "backflow_beta"):
            return WK, "bc_outlet_" + tail
        if tail in ("expr",):
            return WK + ["-bc_inlet_profile", "expression"], "bc_inlet_" + tail
        if tail in ("table", "periodic"):
            return WK + ["-bc_inlet_waveform", "table"], "bc_inlet_" + tail
        if tail in ("t_off",):
            return WK + ["-bc_inlet_waveform", "step"], "bc_inlet_" + tail
        if tail in ("period", "offset"):
            return WK + ["-bc_inlet_waveform", "cosine", "-bc_inlet_period", "1"], "bc_inlet_" + tail
        if tail in ("radius", "center"):
            return WK, "bc_inlet_" + tail
        if tail == "components":
            return WK, "bc_outlet_" + tail
        return WK, "bc_inlet_" + tail
    if name.startswith(("solid_", "ic")):
        if name == "solid_gravity_waveform":
            return SOLID + ["-solid_gravity", "0,0,-9.81"], name
        if name == "solid_E":
            return SOLID + ["-solid_material", "svk", "-solid_nu", "0.3"], name
        if name == "solid_nu":
            return SOLID + ["-solid_material", "svk", "-solid_E", "1e4"], name
        if name == "solid_mu":
            return SOLID + ["-solid_material", "neo_hookean"], name
        return (SOLID, name) if name.startswith("solid_") else (ES, name)
    if name.startswith(("contact_", "gap_seal_", "ale_")):
        return FSI, name
    if name.startswith("valve_"):
        return VALVE, name
    if name in ("exact_G", "exact_R", "exact_L"):
        return POIS, name
    if name in ("exact_A", "exact_period"):
        return WOM, name
    if name in ("exact_amplitude", "exact_wavenumber", "exact_displacement"):
        return MMS, name
    if name.startswith("hemo_") or name in ("monitor_surfaces",):
        return POIS + ["-hemo_surfaces", "wall"], name
    return ES, name


def values(name):
    if name in FILES:
        return ["/nonexistent/file", "/tmp"]
    if name in KEYWORDS:
        return ["no_such_value"]
    if name in VECTORS:
        return ["nan,0,0", "1,2", "a,b,c"]
    if name in FLAGS:
        return ["maybe"]
    if name in EXPRESSIONS:
        return ["sin(", "unknown_name * 2"]
    vals = ["nan", "abc", "inf", "1e999", ""]
    if name in INTEGERS:
        vals.insert(1, "2.5")
    return vals


NUMBERS_ONLY = FILES | KEYWORDS | VECTORS | FLAGS | EXPRESSIONS
cases = []
for n in names:
    if n in SKIP or n.startswith(PETSC) or n in ("mesh_cache_dir", "out_dir"):
        continue
    opts, concrete = base(n)
    vals = values(n)
    for v in (vals if ALL else vals[:1]):
        cases.append((n, concrete, opts, v))
    if n not in NUMBERS_ONLY:  # signs and zero (CI: zero for the integers)
        cases += [(n, concrete, opts, v) for v in ("-1", "0") if ALL or v == "-1" or n in INTEGERS]
if not ALL:  # output and cache folders that cannot be written
    cases += [("out_dir", "out_dir", ES, "/proc/fsi_fuzz"),
              ("mesh_cache_dir", "mesh_cache_dir", ES + ["-mesh_h", "0.9"], "/proc/fsi_fuzz")]
print(f"{len(names)} options listed; {len(cases)} fuzz cases")
bad = 0
for n, opt, opts, v in cases:
    r = run(opts[0], extra=opts[1:] + ["-" + opt, v], timeout=300)
    lines = [l for l in r.out.splitlines() if "fsi_app: error:" in l]
    refused = (r.code == 2 and len(lines) == 1 and opt in lines[0] and "nobody reads" not in lines[0]
               and not os.path.exists(os.path.join(r.dir, "summary.json")))
    clean = "PETSC ERROR" not in r.out and "terminate called" not in r.out and "Aborted" not in r.out
    # a sign or zero may be a valid input (exit 0) or one the numerics cannot take (exit 3: a
    # step that cannot be cut further, said in one fsi_app line; -bc_inlet_value -1 is 1 m^3/s out)
    may_work = v in ("-1", "0") and not (v == "-1" and n in INTEGERS)
    said = "fsi_app: done" if r.code == 0 else "fsi_app: "
    ok = clean and (refused or (may_work and r.code in (0, 3) and not lines and said in r.out))
    bad += not ok
    check(ok, f"-{opt} '{v}': exit {r.code}; " + (lines[0] if lines else r.out.strip().splitlines()[-1:]
                                                   and "no error line; last: " + r.out.strip().splitlines()[-1]))
print(f"{len(cases)} cases, {bad} failing")
finish()
