// fsi_app: blood flow and deformable tissue, monolithic ALE finite elements on DMPlex.
//   mpirun -n 2 fsi_app -options_file examples/<scene>/<scene>.opts [-options_file
//   petsc_options/X.opts]
// The scene (a PETSc options file) switches physics on; what it does not ask for is not built.
// The program reads as the algorithm: scene -> mesh -> space -> physics -> time loop -> outputs.
#include "fsi/analytic.hpp"
#include "fsi/boundary.hpp"
#include "fsi/field_writer.hpp"
#include "fsi/fluid.hpp"
#include "fsi/interface_flux.hpp"
#include "fsi/mesh.hpp"
#include "fsi/monitors.hpp"
#include "fsi/options.hpp"
#include "fsi/output.hpp"
#include "fsi/problem.hpp"
#include "fsi/solid.hpp"
#include "fsi/solid_monitors.hpp"
#include "fsi/space.hpp"
#include "fsi/stages.hpp"

#include <cmath>
#include <memory>
#include <sys/resource.h>

using namespace fsi;

static const char help[] = "fsi_app: monolithic ALE fluid-structure interaction (P2P1 "
                           "Navier-Stokes, hyperelastic solid).\n"
                           "Scene options: -scene_name, -physics fluid,solid, -mesh_geo/-mesh_h "
                           "or -mesh_file, -fluid_*, -solid_*, -bc_*,\n"
                           "-ts_scheme alpha|steady, -ts_dt, -ts_max_steps|-ts_max_time, "
                           "-ts_alpha_radius, -ic rest|exact,\n"
                           "-exact_solution, -ale_motion, -monitor_surfaces, -probe_points, "
                           "-out_dir, -out_fields_every.\n";

namespace {

struct RunTotals {
  long steps = 0, newton = 0, krylov = 0, newton_max = 0, krylov_max = 0;
  double wall = 0;
};

// Options nobody has read after the first step are typos in a scene (every module and solver
// has read its options by then): an error before any result is written, unless allowed.
void check_unused_options() {
  if (opt::flag("allow_unused_options", false)) return;
  PetscInt left = 0;
  char **names, **values;
  FSI_CALL(PetscOptionsLeftGet(nullptr, &left, &names, &values));
  std::string list;
  for (PetscInt i = 0; i < left; ++i)
    list += std::string(i ? ", -" : "-") + names[i];
  const PetscInt n_left = left; // LeftRestore resets the count
  FSI_CALL(PetscOptionsLeftRestore(nullptr, &left, &names, &values));
  if (n_left > 0)
    throw InputError("option(s) nobody reads: " + list +
                     " (a typo? see -help; or pass -allow_unused_options)");
}

double peak_memory_mb() {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;
}

void progress(MPI_Comm comm, const Problem &pb, const StepStats &s, double step_s, double elapsed) {
  const long n = pb.step_index(), N = pb.time_params().max_steps;
  const double eta = elapsed / n * (N - n);
  PetscPrintf(comm,
              "step %5ld/%ld  t = %.4e s  newton %2d  krylov %4d  %.2f s/step  elapsed %.1f s  eta "
              "%.1f s\n",
              n, N, pb.time(), (int)s.newton, (int)s.krylov, step_s, elapsed, eta);
}

int run(MPI_Comm comm) {
  const double t_start = MPI_Wtime();
  Stages &st = Stages::get();
  FSI_CALL(PetscLogStagePush(st.setup));

  // Scene: what physics, where the results go.
  const std::string scene = opt::string("scene_name", "scene");
  const auto physics = opt::list("physics");
  if (physics.empty())
    throw InputError("the scene switches no physics on: give -physics fluid, solid or both");
  bool want_fluid = false, want_solid = false;
  for (auto &p : physics) {
    if (p == "fluid")
      want_fluid = true;
    else if (p == "solid")
      want_solid = true;
    else if (p == "ale")
      throw InputError("-physics ale is not a physics: the mesh motion is chosen by -ale_motion "
                       "none|prescribed|laplace");
    else
      throw InputError("-physics has unknown value '" + p + "'; use: fluid, solid");
  }
  Output out(comm, opt::string("out_dir", "results/" + scene));
  const long fields_every = opt::integer("out_fields_every", 0);

  // Mesh and discrete space.
  Mesh mesh;
  load_mesh(comm, mesh);
  Space space;
  space.build(mesh);

  // Physics modules switched on by the scene.
  const TimeParams tp = TimeParams::from_options();
  Problem pb(space, tp);
  FluidModule *fluid = nullptr;
  std::unique_ptr<ExactFlow> exact;
  if (want_fluid) {
    auto f = std::make_unique<FluidModule>(space, mesh, FluidParams::from_options());
    fluid = f.get();
    exact = make_exact_flow(fluid->params().rho, fluid->params().mu);
    pb.add_module(std::move(f));
  }
  SolidModule *solid = nullptr;
  std::unique_ptr<ExactSolid> exact_solid;
  if (want_solid) {
    exact_solid = make_exact_solid();
    auto s = std::make_unique<SolidModule>(space, mesh, SolidParams::from_options(),
                                           make_material(), exact_solid.get());
    solid = s.get();
    pb.add_module(std::move(s));
  }
  pb.set_exact(exact.get());
  pb.set_mesh_motion(make_mesh_motion(mesh, space, fluid ? &fluid->cells() : nullptr),
                     fluid ? &fluid->cells() : nullptr);
  const std::string iface = opt::string("ale_interface", "");
  if (!iface.empty()) {
    if (!fluid || !pb.mesh_motion())
      throw InputError("-ale_interface needs a fluid and a mesh motion (-ale_motion laplace)");
    pb.add_module(std::make_unique<InterfaceMassFlux>(space, mesh, iface, fluid->cells()));
  }
  Boundaries bcs;
  bcs.setup(mesh, space, exact.get(), exact_solid.get(), fluid ? fluid->params().mu : 0.0,
            fluid ? fluid->params().rho : 0.0, fluid ? &fluid->cells() : nullptr);
  pb.set_boundaries(&bcs);
  pb.set_rigid_body_modes(solid != nullptr);
  pb.setup_solver();
  Monitors mon;
  mon.setup(mesh, space, fluid, exact.get());
  SolidMonitors smon;
  smon.setup(space, solid, exact_solid.get());
  const std::string ic = opt::choice("ic", "rest", {"rest", "exact", "velocity"});
  pb.initialize(ic);

  int size;
  MPI_Comm_size(comm, &size);
  PetscPrintf(comm,
              "fsi_app: scene '%s', %d rank(s), mesh %s: %d cells, %d vertices; dofs velocity %d, "
              "pressure %d\n",
              scene.c_str(), size, mesh.source.c_str(), (int)mesh.cells_global,
              (int)mesh.vertices_global, (int)space.n_velocity, (int)space.n_pressure);
  for (auto &m : pb.modules())
    PetscPrintf(comm, "  physics: %s on %d local cells (rank 0)\n", m->name().c_str(),
                (int)m->n_cells());
  out.write_options();
  auto columns = mon.columns(), solid_columns = smon.columns();
  columns.insert(columns.end(), solid_columns.begin(), solid_columns.end());
  if (pb.mesh_motion())
    for (auto c : {"mesh_min_jacobian", "mesh_max_skewness", "geometry_iterations"})
      columns.push_back(c);
  out.open_monitor(columns);
  std::unique_ptr<FieldWriter> fields;
  FieldSet field_set;
  field_set.pressure = fluid != nullptr;
  field_set.mesh_displacement = pb.mesh_motion() != nullptr;
  field_set.displacement = solid != nullptr;
  if (fields_every > 0) fields = std::make_unique<FieldWriter>(space, out.dir(), field_set);
  FSI_CALL(PetscLogStagePop());
  const double setup_time = MPI_Wtime() - t_start;

  // Time loop.
  RunTotals tot;
  bool converged = true;
  std::string reason = "completed";
  const double loop_start = MPI_Wtime();
  double output_time = 0;
  try {
    while (pb.step_index() < tp.max_steps) {
      const double t0 = MPI_Wtime();
      StepStats s = pb.step();
      const double step_s = MPI_Wtime() - t0;
      if (pb.step_index() == 1) check_unused_options();
      tot.steps++;
      tot.newton += s.newton;
      tot.krylov += s.krylov;
      tot.newton_max = std::max<long>(tot.newton_max, s.newton);
      tot.krylov_max = std::max<long>(tot.krylov_max, s.krylov);
      const double o0 = MPI_Wtime();
      FSI_CALL(PetscLogStagePush(st.output));
      std::vector<double> row = {(double)pb.step_index(), pb.time(), (double)s.newton,
                                 (double)s.krylov, step_s};
      auto m = mon.evaluate(pb), sm = smon.evaluate(pb);
      row.insert(row.end(), m.begin(), m.end());
      row.insert(row.end(), sm.begin(), sm.end());
      if (pb.mesh_motion())
        row.insert(row.end(), {pb.mesh_quality_last().min_jacobian,
                               pb.mesh_quality_last().max_skewness, (double)s.geometry_iterations});
      out.monitor_row(row);
      if (fields && pb.step_index() % fields_every == 0) {
        Vec loc = space.create_local(), dloc = space.create_local();
        pb.solution_local(loc);
        pb.displacement_local(dloc);
        fields->write(pb.step_index(), pb.time(), loc, pb.coordinates(), dloc);
        FSI_CALL(VecDestroy(&loc));
        FSI_CALL(VecDestroy(&dloc));
      }
      FSI_CALL(PetscLogStagePop());
      output_time += MPI_Wtime() - o0;
      progress(comm, pb, s, step_s, MPI_Wtime() - loop_start);
    }
  } catch (SolveError &e) {
    converged = false;
    reason = e.what();
    PetscPrintf(comm, "fsi_app: %s\n", e.what());
  }
  out.close_monitor();
  if (fields) fields->close();
  tot.wall = MPI_Wtime() - t_start;

  // Summary: what ran, its size, its cost, and the accuracy indicators the scene defines.
  const CostCounters &c = pb.cost();
  double mem = peak_memory_mb(), mem_max;
  MPI_Allreduce(&mem, &mem_max, 1, MPI_DOUBLE, MPI_MAX, comm);
  double jt = c.jacobian_time, jt_max, rt = c.residual_time, rt_max;
  MPI_Allreduce(&jt, &jt_max, 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(&rt, &rt_max, 1, MPI_DOUBLE, MPI_MAX, comm);
  // Linear solver time (factorisation / preconditioner setup and Krylov) = Newton time less
  // assembly.
  double ls = c.nonlinear_solve_time - c.jacobian_time - c.residual_time, ls_max;
  MPI_Allreduce(&ls, &ls_max, 1, MPI_DOUBLE, MPI_MAX, comm);
  PetscInt cc[2] = {fluid ? fluid->n_cells() : 0, solid ? solid->n_cells() : 0}, cc_g[2];
  MPI_Allreduce(cc, cc_g, 2, MPIU_INT, MPI_SUM, comm);
  const PetscInt fc_g = cc_g[0], sc_g = cc_g[1];

  std::vector<std::string> active;
  for (auto &m : pb.modules())
    active.push_back(m->name());
  if (pb.mesh_motion()) active.push_back("mesh motion: " + pb.mesh_motion()->name());
  Json dofs, times, iters, cost, j;
  dofs.set("velocity", (long)space.n_velocity)
      .set("pressure", (long)space.n_pressure)
      .set("pressure_held_outside_fluid", bcs.pressure_dofs_outside_fluid())
      .set("total", (long)(space.n_velocity + space.n_pressure));
  times.set("total", tot.wall)
      .set("setup", setup_time)
      .set("jacobian_assembly", jt_max)
      .set("residual_assembly", rt_max)
      .set("linear_solver", ls_max)
      .set("mesh_motion", c.mesh_motion_time)
      .set("output", output_time)
      .set("per_step", tot.steps ? (tot.wall - setup_time) / tot.steps : 0.0);
  iters.set("newton_total", tot.newton)
      .set("newton_max_per_step", tot.newton_max)
      .set("krylov_total", tot.krylov)
      .set("krylov_max_per_step", tot.krylov_max)
      .set("newton_mean_per_step", tot.steps ? double(tot.newton) / tot.steps : 0.0);
  cost.set("jacobians", c.jacobians)
      .set("residuals", c.residuals)
      .set("linear_solver_seconds_per_newton", tot.newton ? ls_max / tot.newton : 0.0)
      .set("jacobian_tets_per_second_per_rank",
           jt_max > 0 ? double(fc_g + sc_g) / size * c.jacobians / jt_max : 0.0)
      .set("residual_tets_per_second_per_rank",
           rt_max > 0 ? double(fc_g + sc_g) / size * c.residuals / rt_max : 0.0)
      .set("peak_memory_mb_per_rank_max", mem_max);
  j.set("scene", scene)
      .set("physics", active)
      .set("ranks", size)
      .set("mesh", mesh.source)
      .set("cells", (long)mesh.cells_global)
      .set("fluid_cells", (long)fc_g)
      .set("solid_cells", (long)sc_g)
      .set("vertices", (long)mesh.vertices_global)
      .set("dofs", dofs)
      .set("time_scheme", tp.steady ? "steady" : "generalized-alpha")
      .set("dt", tp.dt)
      .set("rho_inf", tp.rho_inf)
      .set("steps", tot.steps)
      .set("final_time", pb.time())
      .set("iterations", iters)
      .set("wall_time", times)
      .set("cost", cost)
      .set("converged", converged)
      .set("reason", reason);
  if (mon.has_exact() && tot.steps > 0) {
    const ErrorNorms &e = mon.last_errors();
    Json err;
    err.set("velocity_l2", e.v_l2)
        .set("pressure_l2", e.p_l2)
        .set("velocity_l2_relative", e.v_l2 / e.v_norm)
        .set("pressure_l2_relative", e.p_l2 / e.p_norm);
    j.set("error_final", err);
  }
  if (smon.columns().size() && exact_solid && tot.steps > 0) {
    Json err;
    err.set("displacement_l2", smon.error_l2())
        .set("displacement_l2_relative", smon.error_relative());
    j.set("error_final", err);
  }
  out.write_summary(j);
  PetscPrintf(
      comm,
      "fsi_app: %s: %ld steps, %ld Newton, %ld Krylov iterations, wall %.2f s "
      "(setup %.2f, Jacobian %.2f, residual %.2f), peak memory %.0f MB/rank; results in %s\n",
      converged ? "done" : "FAILED", tot.steps, tot.newton, tot.krylov, tot.wall, setup_time,
      jt_max, rt_max, mem_max, out.dir().c_str());
  return converged ? 0 : 3;
}

} // namespace

int main(int argc, char **argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, help));
  int code = 0;
  MPI_Comm comm = PETSC_COMM_WORLD;
  try {
    code = run(comm);
  } catch (InputError &e) {
    PetscPrintf(comm, "fsi_app: error: %s\n", e.what());
    code = 2;
  } catch (std::exception &e) {
    PetscPrintf(comm, "fsi_app: failure: %s\n", e.what());
    code = 4;
  }
  PetscFinalize();
  return code;
}
