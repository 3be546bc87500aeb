#include "fsi/run/help.hpp"
#include "fsi/boundary/boundary_condition.hpp"
#include "fsi/run/simulation.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace fsi {

namespace {

struct OptionDoc {
  const char *name, *def, *unit, *meaning;
};
struct Section {
  const char *title;
  std::vector<OptionDoc> options;
};

// "-" in the unit column: a dimensionless number, a name or a switch.
const std::vector<Section> &sections() {
  static const std::vector<Section> s = {
      {"Scene and outputs",
       {{"scene_name", "scene", "-", "the scene's name (results/<name> by default)"},
        {"physics", "(required)", "-",
         "physics switched on: fluid, solid, contact (solid-solid), gap_seal (fluid in a closing "
         "gap), e.g. fluid,solid,contact,gap_seal"},
        {"out_dir", "results/SCENE_NAME", "-", "output folder"},
        {"out_fields_every", "0", "steps", "XDMF/HDF5 fields every N steps (0: none)"},
        {"checkpoint_every", "0", "steps",
         "write checkpoint.h5 every N steps (0: only on failure, signal, and at the end if N > 0)"},
        {"checkpoint_crash_test", "0", "-",
         "tests only: SIGKILL halfway through the K-th checkpoint"},
        {"restart", "", "-", "resume from this checkpoint (same scene options, any rank count)"},
        {"restart_reset_dt", "false", "-",
         "resume with the scene's -ts_dt and a fresh step controller, not the checkpoint's"},
        {"sim_rebuild_every", "0", "steps",
         "rebuild the whole discretisation from its state every N steps (checks state transfer)"},
        {"sim_pattern_rebuild_every", "0", "solves",
         "rebuild the Jacobian's nonzero pattern every N solves (checks the rebuild path)"},
        {"allow_unused_options", "false", "-", "otherwise an option nobody reads is an error"},
        {"ic", "rest", "-", "initial state: rest | velocity | exact"},
        {"ic_velocity", "", "m/s", "uniform initial velocity vx,vy,vz for -ic velocity"}}},
      {"Mesh",
       {{"mesh_file", "", "-", "a ready gmsh .msh; physical names become regions/boundaries"},
        {"mesh_geo", "", "-", "or a gmsh .geo source, meshed with the gmsh API"},
        {"mesh_h", "0.1", "m", "mesh size passed to the .geo as h"},
        {"mesh_params", "", "-", "further .geo parameters name=value,..."},
        {"mesh_cache_dir", "results/.mesh_cache", "-", "where meshed .geo files are cached"},
        {"mesh_partitioner", "ptscotch", "-",
         "cell partition over the ranks: ptscotch or metis (edge cut and balance in the header)"},
        {"mesh_reorder", "rcm", "-",
         "rcm | none: mesh points (hence dofs) in reverse Cuthill-McKee order before "
         "distribution (assembly 25-35 % faster) or as read"},
        {"mesh_max_cells", "5e7", "-",
         "refuse a -mesh_h whose cell estimate (bounding box / h^3) exceeds this"}}},
      {"Time integration (PETSc TS names)",
       {{"ts_type", "alpha", "-", "alpha (generalized-alpha) | steady (static load steps)"},
        {"ts_dt", "1e-3", "s", "time step"},
        {"ts_max_steps", "10 (alpha), 1 (steady)", "-",
         "number of steps (wins over ts_max_time; with -ts_adapt_type error: the last step)"},
        {"ts_max_time", "", "s", "end time (a whole number of steps)"},
        {"ts_alpha_radius", "0.5", "-", "spectral radius rho_inf in [0, 1]"},
        {"ts_alpha_radius_switch_when", "", "-",
         "COLUMN<VALUE or COLUMN>VALUE on a monitor.csv column or time: after a step where it "
         "holds "
         "rho_inf is -ts_alpha_radius_switch_to, after one where it does not -ts_alpha_radius"},
        {"ts_alpha_radius_switch_to", "0", "-", "rho_inf after the switch, in [0, 1]"},
        {"ts_predictor", "constant", "-",
         "Newton's first iterate: constant (V_n) | extrapolated (V_n + dt A_n)"},
        {"ts_adapt_type", "cut", "-",
         "cut: retry a failed step with a smaller dt | error: also choose dt by a local error "
         "estimate (PI controller) | none"},
        {"ts_rtol", "0.01", "-", "error: relative tolerance on the velocity's local error"},
        {"ts_atol", "1e-3", "m/s", "error: absolute tolerance on the velocity's local error"},
        {"ts_adapt_wnormtype", "infinity", "-",
         "error: norm of the local error over the velocity dofs, infinity (largest) | 2 (root "
         "mean square)"},
        {"ts_adapt_switch_when", "", "-",
         "COLUMN<VALUE or COLUMN>VALUE (with -ts_adapt_type cut): after a step where it holds dt "
         "is chosen by the error estimate (-ts_rtol, -ts_atol, ...), after one where it does not "
         "it is -ts_dt"},
        {"ts_adapt_dt_max", "10 ts_dt", "s", "error: largest step"},
        {"ts_adapt_period", "0 (none)", "s",
         "error: steps land on every multiple of it (a cardiac cycle's start); with "
         "-ts_adapt_switch_when each new period starts at -ts_dt"},
        {"ts_adapt_safety", "0.9", "-", "error: safety factor of the step-size controller"},
        {"ts_adapt_max_rejections", "5", "-", "error: rejections of one step before it is taken"},
        {"ts_adapt_scale_solve_failed", "0.5", "-", "dt factor after a failed step, in (0, 1)"},
        {"ts_adapt_dt_min", "dt/1000", "s", "below this step size the run stops (exit 3)"},
        {"step_grow_after", "3", "steps", "easy steps before dt grows back by 1/factor"},
        {"step_easy_newton", "4", "-", "a step with at most this many Newton iterations is easy"}}},
      {"Fluid (-physics fluid)",
       {{"fluid_region", "fluid", "-", "physical volume of the fluid"},
        {"fluid_rho", "1000", "kg/m^3", "density"},
        {"fluid_mu", "0.003", "Pa s", "dynamic viscosity"},
        {"fluid_model", "navier_stokes", "-", "navier_stokes | stokes (no convection)"},
        {"fluid_convection", "convective", "-",
         "convective | skew_symmetric (+ rho/2 (div v) v: energy-stable convection)"},
        {"fluid_grad_div", "0", "Pa s",
         "grad-div penalty gamma (div v, div w): local mass conservation of the P2/P1 velocity"},
        {"fluid_quad_degree", "4", "-", "quadrature degree"},
        {"fluid_direct_insertion", "true", "-", "element matrices straight into the AIJ arrays"}}},
      {"Solid (-physics solid)",
       {{"solid_region", "solid", "-", "physical volume of the solid"},
        {"solid_rho", "1000", "kg/m^3", "reference density"},
        {"solid_gravity", "0,0,0", "m/s^2", "body acceleration gx,gy,gz"},
        {"solid_gravity_waveform", "constant (steady: linear over ts_max_time)", "-",
         "gravity's time dependence; its _period, _ramp, ... as for bc_<b>_"},
        {"solid_material", "linear", "-", "linear | svk | neo_hookean | mooney_rivlin"},
        {"solid_E", "(required: linear, svk)", "Pa", "Young's modulus"},
        {"solid_nu", "0.3", "-", "Poisson's ratio"},
        {"solid_mu", "(neo_hookean)", "Pa", "shear modulus"},
        {"solid_kappa", "(neo_hookean, mooney_rivlin)", "Pa", "bulk modulus"},
        {"solid_C10", "(mooney_rivlin)", "Pa", "Mooney-Rivlin C10"},
        {"solid_C01", "0", "Pa", "Mooney-Rivlin C01"},
        {"solid_exp_c1", "0", "Pa",
         "neo_hookean/mooney_rivlin + c1/2 (exp(c2 (I1bar-3)^2) - 1): collagen-like stiffening"},
        {"solid_exp_c2", "0", "-", "exponent c2 of that term (both 0 or both positive)"},
        {"solid_fibres", "none", "-",
         "none | circumferential | chord: a fibre family c1/2 (exp(c2 (I4-1)^2) - 1), I4 > 1, "
         "about "
         "the z axis"},
        {"solid_fibre_c1", "(with solid_fibres)", "Pa", "fibre modulus c1"},
        {"solid_fibre_c2", "(with solid_fibres)", "-", "fibre exponent c2"},
        {"solid_fibre_tension_only", "true", "-",
         "fibres carry no compression (I4 < 1); false: the same law on both sides"},
        {"solid_fibre_commissures", "(chord)", "deg",
         "commissure angles about z; fibres run along the chord of each sector between them"},
        {"solid_quad_degree", "3", "-", "quadrature degree (3: 8 points, 4: 14, 2: 4)"},
        {"solid_direct_insertion", "true", "-", "element matrices straight into the AIJ arrays"}}},
      {"Contact between solid pieces (-physics contact; gap_seal)",
       {{"contact_surface", "interface", "-", "boundary group of the solid's contact surface"},
        {"contact_offset", "(required)", "m", "gap the pieces keep (penalty acts below it)"},
        {"contact_penalty", "1e8", "Pa/m", "contact pressure per metre of penetration"},
        {"contact_ramp", "offset/4", "m", "width over which the contact pressure ramps in"},
        {"contact_pattern_margin", "offset", "m",
         "pairs this much beyond the offset are kept in the Jacobian's pattern"},
        {"contact_walls", "(none)", "-",
         "rigid fluid boundary groups the contact surface keeps away from, e.g. root_wall"},
        {"contact_wall_offset", "offset", "m", "gap the surface keeps from the walls"},
        {"contact_wall_exclude", "2 wall_offset", "m",
         "surface nodes this close to a wall in the reference shape (attachment) take no wall "
         "contact"},
        {"contact_axis_radius", "0 (none)", "m",
         "a virtual rigid rod of this radius along the axis: the surface keeps it from the "
         "line (the fluid where three leaflets meet), and the gap seal counts it as a piece"},
        {"contact_axis", "0,0,0,0,0,1", "m,-", "the rod's axis: a point X,Y,Z and a direction"},
        {"gap_seal_resistance", "1e8", "Pa s/m^2", "Brinkman resistance of a closed gap"},
        {"gap_seal_gap_closed", "1.25 offset", "m", "gap width at full resistance"},
        {"gap_seal_gap_open", "2 offset", "m", "gap width where the resistance starts"},
        {"gap_seal_ramp_time", "0", "s", "time lag of the resistance (0: none)"}}},
      {"Mesh motion (ALE)",
       {{"ale_motion", "none", "-",
         "none | prescribed (verification) | laplace (follows the solid)"},
        {"ale_amplitude", "0.1", "m", "prescribed: bubble amplitude"},
        {"ale_time", "1", "s", "prescribed: time over which the amplitude is reached"},
        {"ale_stiffening", "0", "-",
         "chi in k = (V_max/V_e)^chi (0 Laplace, 1 Jacobian-stiffened)"},
        {"ale_slip_boundaries", "", "-", "planes where the mesh slides (inlet/outlet)"},
        {"ale_geometry_iterations", "0", "-",
         "0: geometry lagged; N: iterate the mesh in the step"},
        {"ale_geometry_rtol", "1e-6", "-", "relative mesh change that ends geometry iterations"},
        {"ale_geometry_monitor", "false", "-",
         "print each geometry pass's Newton count and mesh change"},
        {"ale_interface", "", "-",
         "mass-conservative fluid-solid interface (its physical name); not for thin light "
         "structures such as leaflets (a two-step sawtooth grows: docs/valve.md)"},
        {"ale_min_jacobian", "0", "-", "stop when a fluid cell's volume ratio reaches this"},
        {"ale_max_skewness", "0.99", "-", "stop when a fluid cell's skewness reaches this"},
        {"ale_remesh_skewness", "0.9", "-",
         "remesh the fluid when a degraded cell's skewness passes this (0: off)"},
        {"ale_remesh_skewness_fresh", "0", "-",
         "raise -ale_remesh_skewness to the current mesh's worst cell, up to this (0: off)"},
        {"ale_remesh_min_volume_ratio", "0.1", "-",
         "remesh when a fluid cell is squeezed below this fraction of its volume"},
        {"ale_remesh_ignore_sealed", "false", "-",
         "the skewness trigger leaves out cells a gap seal holds shut (a closed valve's hold)"},
        {"ale_remesh_hmax", "0 (from the boundary)", "m", "largest cell of a new fluid mesh"},
        {"ale_remesh_every", "0", "steps", "also remesh after every N steps (tests, studies)"},
        {"ale_remesh_gap_cells", "2", "-",
         "cells across a fluid gap thinner than its boundary triangles (0: no gap sizing)"},
        {"ale_remesh_flip_skewness", "0.8", "-",
         "edge/face flips on new fluid cells worse than this (0: off)"},
        {"ale_remesh_project", "true", "-",
         "project the remeshed velocity onto discretely divergence-free fields (false: measure)"},
        {"ale_remesh_verbose", "0", "-", "1: show gmsh's messages while remeshing"},
        {"ale_remesh_test_fault", "0", "-",
         "1: corrupt the boundary given to gmsh; 2: fail on the new mesh (tests)"},
        {"ale_ksp_*, ale_pc_*", "cg, gamg", "-", "the mesh-motion linear solver"}}},
      {"Boundary conditions (per boundary <b> in -bc_names)",
       {{"bc_names", "", "-", "boundaries with a condition; unlisted ones are traction-free"},
        {"bc_<b>_type", "(required)", "-", "one of the types listed below"},
        {"bc_<b>_components", "all (Dirichlet types)", "-", "velocity components fixed: x,y,z"},
        {"bc_<b>_value", "0 (flow_rate, expression: 1)", "m/s | Pa | m | m^3/s",
         "velocity scale, pressure, traction, displacement or flow rate (into the fluid)"},
        {"bc_<b>_direction", "flow_rate: inward normal", "-",
         "direction x,y,z (velocity, flow_rate, displacement, traction)"},
        {"bc_<b>_profile", "uniform (flow_rate: plug)", "-",
         "velocity: uniform | parabolic | exact | expression; flow_rate: plug | parabolic | "
         "expression; displacement: uniform | exact"},
        {"bc_<b>_expr", "", "m/s",
         "expression profile in x, y, z, t: 3 values (flow_rate: 1 or 3); "
         "expression waveform: 1 value in t"},
        {"bc_<b>_center", "flow_rate: area centroid", "m", "parabolic: a point on the axis"},
        {"bc_<b>_radius", "flow_rate: farthest vertex", "m", "parabolic: the radius"},
        {"bc_<b>_stop_backflow_when", "", "-",
         "flow_rate: COLUMN<VALUE or COLUMN>VALUE of monitor.csv (e.g. contact_pairs>20): the "
         "backflow stops once it holds (valve closed), until the flow turns forward"},
        {"bc_<b>_stop_ramp", "0.005", "s", "flow_rate: the stop's smooth ramp to zero"},
        {"bc_<b>_backflow_beta", "1", "-", "pressure, windkessel: backflow stabilisation (0 off)"},
        {"bc_<b>_R_p", "(required)", "Pa s/m^3", "windkessel: proximal resistance"},
        {"bc_<b>_C", "(required)", "m^3/Pa", "windkessel: compliance"},
        {"bc_<b>_R_d", "(required)", "Pa s/m^3", "windkessel: distal resistance"},
        {"bc_<b>_p_distal", "0", "Pa", "windkessel: distal (venous) pressure"},
        {"bc_<b>_p0", "p_distal", "Pa", "windkessel: initial capacitor pressure"},
        {"bc_<b>_jacobian", "auto", "-",
         "windkessel: full (dense outlet block), lagged, auto (full up to 3000 dofs)"},
        {"bc_<b>_waveform", "constant", "-",
         "constant | step | pulse | cosine | sine | linear | table | expression"},
        {"bc_<b>_table", "", "-", "table: file of 't value' rows, linear interpolation"},
        {"bc_<b>_periodic", "false", "-", "table: repeat with period t_last - t_first"},
        {"bc_<b>_t_off", "", "s", "step, pulse: end time"},
        {"bc_<b>_period", "", "s", "cosine, sine, linear: period"},
        {"bc_<b>_offset", "0", "-", "cosine, sine: offset + cos(2 pi t / period)"},
        {"bc_<b>_ramp", "0", "s", "smooth start over this time"}}},
      {"Monitors and hemodynamics",
       {{"monitor_surfaces", "", "-", "flux, area, force, mean pressure per named boundary"},
        {"monitor_fluid_volume", "false", "-", "fluid volume per step"},
        {"monitor_fluid_energy", "false", "-",
         "fluid kinetic energy, dissipation (viscous + grad-div), convective form's power per "
         "step"},
        {"probe_points", "", "m", "fluid probes x,y,z;x,y,z"},
        {"solid_probe_points", "", "m", "solid displacement probes at material points"},
        {"monitor_solid_energy", "false", "-", "kinetic and stored energy of the solid"},
        {"valve_annulus_radius", "", "m",
         "valve monitors on: dp, orifice area, leaflet u and stress"},
        {"valve_center", "0,0,0", "m", "annulus centre"},
        {"valve_axis", "0,0,1", "-", "valve axis (flow direction)"},
        {"valve_dp_planes", "", "m", "axial positions a < 0 < b of the pressure discs"},
        {"valve_dp_radius", "0.8 R", "m", "radius of the pressure discs"},
        {"valve_goa_pixels", "400", "-", "orifice-area raster size per side"},
        {"hemo_surfaces", "", "-", "walls for wall shear stress, TAWSS, OSI, RRT"},
        {"hemo_window", "0 (the whole run)", "s", "averaging window"},
        {"hemo_start", "0", "s", "start of the first window"}}},
      {"Verification",
       {{"exact_solution", "none", "-", "none | ethier_steinman | poiseuille | womersley"},
        {"exact_G", "", "Pa/m", "poiseuille: pressure gradient"},
        {"exact_A", "", "Pa/m", "womersley: pressure-gradient amplitude"},
        {"exact_period", "", "s", "womersley: period"},
        {"exact_R", "", "m", "pipe radius"},
        {"exact_L", "0", "m", "pipe length (pressure level)"},
        {"exact_displacement", "none", "-", "none | manufactured (solid)"},
        {"exact_amplitude", "0.1", "m", "manufactured displacement amplitude"},
        {"exact_wavenumber", "1", "1/m", "manufactured displacement wavenumber"}}},
      {"Solver (PETSc; presets in petsc_options/)",
       {{"solver_preset", "(the scene's)", "-",
         "NAME: petsc_options/NAME.opts (or a path ending in .opts) sets every solver option "
         "the scene and command line leave unset; the last one given wins"},
        {"snes_*, ksp_*, pc_*", "PETSc's", "-", "Newton and linear solver of the coupled system"},
        {"fieldsplit_velocity_pc_type", "", "-", "fieldsplit: split velocity into fluid | solid"},
        {"fieldsplit_pressure_pc_type", "", "-", "pcd: convection-aware Schur preconditioner"},
        {"pc_schur_bilu_precision", "single", "-",
         "-pc_type schur_bilu (Schur + block ILU, no block copies): velocity factor storage"},
        {"schur_*", "hypre", "-", "schur_bilu's Sp preconditioner (-schur_pc_type, ...)"},
        {"jac_*", "", "-", "options of the Jacobian matrix (prefix jac_)"},
        {"newton_inexact_gamma", "0 (off)", "-",
         "linear solves only to gamma x the Newton target (|F0| snes_rtol), >= ksp_rtol"},
        {"newton_pc_rebuild_krylov", "0 (off)", "-",
         "a lagged preconditioner is rebuilt when a linear solve took more Krylov iterations"},
        {"test_fault_residual", "0", "-",
         "N: the N-th residual evaluation meets an inverted solid element on rank 0 (tests)"}}},
  };
  return s;
}

} // namespace

bool wants_help() {
  PetscBool h = PETSC_FALSE, h2 = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, "-help", &h);
  PetscOptionsHasName(nullptr, nullptr, "-h", &h2);
  return h || h2;
}

int print_help(MPI_Comm comm) {
  PetscPrintf(comm, "fsi_app: monolithic ALE fluid-structure interaction (P2P1 Navier-Stokes, "
                    "hyperelastic solid, generalized-alpha, Newton).\n"
                    "usage: mpirun -n 2 fsi_app -options_file scene.opts [-options_file "
                    "petsc_options/preset.opts] [-option value ...]\n"
                    "Every option: -name <default> [unit] meaning.  SI units throughout.\n");
  for (auto &sec : sections()) {
    PetscPrintf(comm, "\n%s:\n", sec.title);
    for (auto &o : sec.options)
      PetscPrintf(comm, "  -%-30s <%s> [%s] %s\n", o.name, o.def, o.unit, o.meaning);
  }
  PetscPrintf(comm, "\nBoundary-condition types (-bc_<b>_type):\n");
  for (auto &t : boundary_types())
    PetscPrintf(comm, "  %-20s (%s) %s\n", t.name, t.physics, t.help);
  return 0;
}

void print_run_header(MPI_Comm comm, const Scene &scene, const Mesh &mesh, const Simulation &sim) {
  int size;
  MPI_Comm_size(comm, &size);
  const Space &space = sim.space();
  PetscPrintf(comm,
              "fsi_app: scene '%s', %d rank(s), mesh %s: %d cells, %d vertices; dofs velocity %d, "
              "pressure %d\n",
              scene.name.c_str(), size, mesh.source.c_str(), (int)mesh.cells_global,
              (int)mesh.vertices_global, (int)space.n_velocity, (int)space.n_pressure);
  const PartitionQuality &pq = mesh.partition;
  if (size > 1 && pq.edge_cut >= 0)
    PetscPrintf(comm,
                "  partition: %s, %ld of %ld cell faces cut (%.2f %%), largest part %.3f x mean\n",
                pq.method.c_str(), pq.edge_cut, pq.faces,
                100.0 * pq.edge_cut / std::max(1L, pq.faces), pq.imbalance);
  for (auto &m : sim.system().modules())
    PetscPrintf(comm, "  physics: %s on %d local cells (rank 0)\n", m->name().c_str(),
                (int)m->n_cells());
}

} // namespace fsi
