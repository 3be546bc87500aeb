"""Jacobian checks for every kernel: PETSc's -snes_test_jacobian compares our assembled Jacobian
with a finite-difference one at every Newton iterate, on tiny scenes, one per module or term:
fluid on a moving mesh (convective, and skew-symmetric with grad-div), Stokes, each solid material (static and dynamic; Mooney-Rivlin with the
exponential stiffening and with a fibre family), the follower pressure,
the conservative interface, the backflow stabilisation and the Windkessel outlet.  Each case runs with the
finite-difference step -snes_test_err 1e-9, and 1e-7 if needed; it fails when, at both, some
||J - J_fd||_F / ||J||_F exceeds TOL: on a right Jacobian the discrepancy is the truncation error
of the differences and falls with the step (measured: follower pressure 2.8e-4 / 2.8e-6 / 2.8e-8
at steps 1e-6 / 1e-8 / 1e-10), while a wrong or missing term leaves a discrepancy of its own
size at every step (backflow Jacobian removed on purpose: 7.9e-6 at both steps)."""
import os
import re
from fsitest import SRC, check, finish, run, scene

TOL = 1e-6
ES = scene("ethier_steinman")
CANTILEVER = [scene("cantilever"), "-mesh_h", "0.1", "-ts_max_steps", "2"]
PIPE = os.path.join(SRC, "examples", "pipe", "pipe.opts")
TUBE = os.path.join(SRC, "examples", "tube", "tube.opts")
BAR = os.path.join(SRC, "examples", "bar", "bar.opts")
WK = scene("windkessel_pipe")
CASES = [
    ("fluid, Navier-Stokes on a moving mesh", [ES], ["-mesh_h", "1", "-ts_max_steps", "2",
     "-ale_motion", "prescribed", "-ale_amplitude", "0.1", "-ale_time", "0.02"]),
    ("fluid, skew-symmetric convection + grad-div on a moving mesh (the (div v) v term removed: "
     "5.4e-3; the grad-div block added into the Laplacian too: 0.14)", [ES],
     ["-mesh_h", "1", "-ts_max_steps", "2", "-ale_motion", "prescribed", "-ale_amplitude", "0.1",
      "-ale_time", "0.02", "-fluid_convection", "skew_symmetric", "-fluid_grad_div", "1"]),
    ("fluid, Stokes", [ES], ["-mesh_h", "1", "-ts_max_steps", "1", "-fluid_model", "stokes"]),
    ("solid, linear", CANTILEVER[:1], CANTILEVER[1:] + ["-solid_material", "linear"]),
    ("solid, St Venant-Kirchhoff", CANTILEVER[:1], CANTILEVER[1:] + ["-solid_material", "svk"]),
    ("solid, neo-Hookean", CANTILEVER[:1], CANTILEVER[1:]),
    # Mooney-Rivlin with the exponential stiffening (the plain law is this with c1 = 0; its
    # tangent is checked at the material level in solid_material_tangents).  c2 = 1e3 makes the
    # exponential dominate the curvature at the cantilever's strains (FD truncation error 1.5e-8
    # without it, 2.0e-7 with it, the same at FD steps 1e-9 and 1e-10).
    ("solid, Mooney-Rivlin + exponential stiffening", CANTILEVER[:1], CANTILEVER[1:] + [
        "-solid_material", "mooney_rivlin", "-solid_C10", "1.5e5", "-solid_C01", "2e4",
        "-solid_kappa", "1e7", "-solid_exp_c1", "1e6", "-solid_exp_c2", "1e3",
        "-allow_unused_options"]),
    # A fibre family along x (chord fibres of the sector 0-180 degrees), on both sides of I4 = 1:
    # the tension-only switch is a kink of W at the rest state that finite differences straddle
    # (checked at the material level in solid_material_tangents instead).
    ("solid, Mooney-Rivlin + fibres", CANTILEVER[:1], CANTILEVER[1:] + [
        "-solid_material", "mooney_rivlin", "-solid_C10", "1.5e5", "-solid_C01", "2e4",
        "-solid_kappa", "1e7", "-solid_fibres", "chord", "-solid_fibre_commissures", "0,180",
        "-solid_fibre_c1", "1e5", "-solid_fibre_c2", "10", "-solid_fibre_tension_only", "false",
        "-pc_type", "lu",
        "-allow_unused_options"]),
    ("solid, neo-Hookean, generalized-alpha", CANTILEVER[:1], CANTILEVER[1:] + [
        "-ts_type", "alpha", "-ts_dt", "0.01", "-bc_zmax_value", "2e4",
        "-bc_zmax_waveform", "constant", "-allow_unused_options"]),
    ("solid, follower pressure", [BAR], ["-mesh_h", "0.001", "-ts_max_steps", "2",
                                         "-ts_max_time", "0.25", "-allow_unused_options"]),
    ("FSI, conservative interface (geometry iterated)", [TUBE], [
        "-mesh_h", "0.005", "-ts_max_steps", "1", "-ale_interface", "interface",
        "-ale_geometry_iterations", "2", "-ale_geometry_rtol", "1e-12"]),
    ("fluid, backflow stabilisation (flow enters through the outlet)", [PIPE], [
        "-mesh_h", "0.004", "-mesh_params", "R=0.005,L=0.02", "-bc_inlet_value", "-1",
        "-bc_inlet_ramp", "0", "-ts_dt", "0.01", "-ts_max_steps", "1", "-out_fields_every", "0"]),
    ("fluid, Windkessel outlet (its dense rank-one block; without it: 8.3e-6)",
     [WK], ["-mesh_h", "0.006", "-mesh_params", "R=0.005,L=0.01,ncirc=8",
                                  "-ts_max_steps", "1"]),
]

for name, opts, extra in CASES:
    worst = []
    for step in ("1e-9", "1e-7"):  # the second only when the first is above TOL
        # Three Newton iterates per solve are checked (the first from rest, where some nonlinear terms
        # vanish, then two away from it), two on the larger scenes (each check costs one residual
        # per unknown); the check needs no convergence.
        its = "2" if opts[0] in (TUBE, PIPE, WK) else "3"
        r = run(opts, np=1, extra=extra + ["-snes_test_jacobian", "-snes_test_err", step,
                                           "-snes_max_it", its, "-ts_adapt_type", "none"])
        ratios = [float(x) for x in re.findall(r"\|\|J - Jfd\|\|_F/\|\|J\|\|_F = ([0-9.eE+-]+)", r.out)]
        check(r.code in (0, 3) and len(ratios) >= 1, f"{name}: runs and checks its Jacobian")
        worst.append(max(ratios) if ratios else float("inf"))
        if worst[-1] <= TOL:
            break
    print(f"{name}: worst ||J - Jfd||/||J|| = " +
          ", ".join(f"{w:.3e} (FD step {s})" for w, s in zip(worst, ("1e-9", "1e-7"))))
    check(min(worst) <= TOL, f"{name}: Jacobian matches finite differences ({min(worst):.2e} <= {TOL:g})")
finish()
