// fsi_app: blood flow and deformable tissue, monolithic ALE finite elements on DMPlex.
//   mpirun -n 2 fsi_app -options_file examples/<scene>/<scene>.opts [-options_file
//   petsc_options/X.opts]
// The scene (a PETSc options file) switches physics on; what it does not ask for is not built.
// The program reads as the algorithm: scene -> mesh -> space -> physics -> time loop -> outputs.
#include "fsi/analytic.hpp"
#include "fsi/boundary.hpp"
#include "fsi/checkpoint.hpp"
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
#include "fsi/step_control.hpp"
#include "fsi/wall_shear.hpp"

#include <cmath>
#include <csignal>
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
  long steps = 0, newton = 0, krylov = 0, newton_max = 0, krylov_max = 0, failed = 0;
  double wall = 0;
};

// SIGTERM, SIGINT and SIGUSR1 (mpirun forwards SIGUSR1) ask for a checkpoint and a clean stop
// after the current step.
volatile sig_atomic_t g_stop_signal = 0;
extern "C" void on_stop_signal(int sig) {
  g_stop_signal = sig;
}
void install_stop_handlers() {
  struct sigaction sa = {};
  sa.sa_handler = on_stop_signal;
  sa.sa_flags = SA_RESTART;
  sigemptyset(&sa.sa_mask);
  for (int sig : {SIGTERM, SIGINT, SIGUSR1})
    sigaction(sig, &sa, nullptr);
}
int stop_requested(MPI_Comm comm) {
  int mine = g_stop_signal, any;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm);
  return any;
}

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

// Extremes of every monitor column over the run (the accuracy indicators a scene defines, e.g.
// the peak displacement of a wall point and when it happens), for summary.json.
struct MonitorExtremes {
  std::vector<std::string> names;
  std::vector<double> min, max, t_min, t_max, last;
  void add(double t, const std::vector<double> &v, size_t first) {
    if (min.empty()) {
      min.assign(v.begin() + first, v.end());
      max = last = min;
      t_min.assign(min.size(), t);
      t_max = t_min;
    }
    for (size_t i = first; i < v.size(); ++i) {
      const size_t k = i - first;
      if (v[i] < min[k]) min[k] = v[i], t_min[k] = t;
      if (v[i] > max[k]) max[k] = v[i], t_max[k] = t;
      last[k] = v[i];
    }
  }
  Json json() const {
    Json j;
    for (size_t k = 0; k < min.size() && k < names.size(); ++k) {
      Json c;
      c.set("min", min[k]).set("t_min", t_min[k]).set("max", max[k]).set("t_max", t_max[k]);
      c.set("final", last[k]);
      j.set(names[k], c);
    }
    return j;
  }
};

double peak_memory_mb() {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;
}

void progress(MPI_Comm comm, const Problem &pb, const StepStats &s, double step_s, double elapsed,
              double t0) {
  const double t_end = pb.time_params().t_end, done = (pb.time() - t0) / (t_end - t0);
  const double eta = done > 0 ? std::max(0.0, elapsed / done * (1 - done)) : 0;
  PetscPrintf(comm,
              "step %5ld  t = %.4e/%.4e s  dt %.2e  newton %2d  krylov %4d  %.2f s/step  elapsed "
              "%.1f s  eta %.1f s\n",
              pb.step_index(), pb.time(), t_end, pb.dt(), (int)s.newton, (int)s.krylov, step_s,
              elapsed, eta);
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
  if (FluidSolidSplit::requested(fluid != nullptr, solid != nullptr))
    pb.set_fluid_solid_split(std::make_unique<FluidSolidSplit>(space, solid->cells()));
  if (PcdOperators::requested(fluid != nullptr))
    pb.set_pcd(std::make_unique<PcdOperators>(space, mesh, *fluid, bcs));
  pb.setup_solver();
  Monitors mon;
  mon.setup(mesh, space, fluid, exact.get());
  SolidMonitors smon;
  smon.setup(space, solid, exact_solid.get());
  const std::string ic = opt::choice("ic", "rest", {"rest", "exact", "velocity"});
  pb.initialize(ic);

  // Restart, checkpoints, step control: the scene tag must match the checkpoint's.
  const std::string restart = opt::string("restart", "");
  const long checkpoint_every = opt::integer("checkpoint_every", 0);
  if (checkpoint_every < 0) throw InputError("option -checkpoint_every must be >= 0");
  StepControl control = StepControl::from_options(tp.dt);
  char tag[200];
  std::snprintf(tag, sizeof tag, "physics %s, %s", opt::join(physics, ",").c_str(),
                tp.steady ? "steady"
                          : ("generalized-alpha rho_inf " + std::to_string(tp.rho_inf)).c_str());
  Checkpoint checkpoint(space, tag);
  const std::string checkpoint_path = out.dir() + "/checkpoint.h5";
  WallShear wss;
  wss.setup(mesh, space, fluid, exact.get(), out.dir(), tp.t_end, !restart.empty());
  if (!restart.empty()) {
    checkpoint.read(restart, pb, control, wss);
    PetscPrintf(comm, "fsi_app: resumed from %s at step %ld, t = %.6e s, dt = %.3e s\n",
                restart.c_str(), pb.step_index(), pb.time(), control.dt);
  }
  const long first_step = pb.step_index();
  const double first_time = pb.time();

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
  auto columns = mon.columns(), solid_columns = smon.columns(), wss_columns = wss.columns();
  columns.insert(columns.end(), solid_columns.begin(), solid_columns.end());
  columns.insert(columns.end(), wss_columns.begin(), wss_columns.end());
  columns.insert(columns.begin(), "dt");
  if (pb.mesh_motion())
    for (auto c : {"mesh_min_jacobian", "mesh_max_skewness", "geometry_iterations"})
      columns.push_back(c);
  out.open_monitor(columns, restart.empty() ? -1 : first_step);
  MonitorExtremes extremes;
  extremes.names.assign(columns.begin() + 1, columns.end()); // after dt
  std::unique_ptr<FieldWriter> fields;
  FieldSet field_set;
  field_set.pressure = fluid != nullptr;
  field_set.mesh_displacement = pb.mesh_motion() != nullptr;
  field_set.displacement = solid != nullptr;
  if (!restart.empty()) field_set.base = "fields_restart";
  if (fields_every > 0) fields = std::make_unique<FieldWriter>(space, out.dir(), field_set);
  FSI_CALL(PetscLogStagePop());
  const double setup_time = MPI_Wtime() - t_start;

  // Time loop: to the scene's end time; a failed step is retried with a smaller dt.
  RunTotals tot;
  bool converged = true;
  int exit_code = 0;
  std::string reason = "completed";
  const double loop_start = MPI_Wtime();
  double output_time = 0;
  long checkpoints = 0;
  auto write_checkpoint = [&]() {
    const double o0 = MPI_Wtime();
    checkpoint.write(checkpoint_path, pb, control, wss);
    ++checkpoints;
    output_time += MPI_Wtime() - o0;
  };
  install_stop_handlers();
  try {
    while (pb.time() < tp.t_end - 1e-9 * tp.dt) {
      double dt = control.dt;
      if (tp.t_end - pb.time() < dt * (1 - 1e-9)) dt = tp.t_end - pb.time(); // land on t_end
      pb.set_dt(dt);
      const double t0 = MPI_Wtime();
      StepStats s;
      try {
        s = pb.step();
      } catch (DistortionError &) {
        throw;
      } catch (SolveError &e) {
        ++tot.failed;
        if (!control.cut()) {
          if (!control.enabled) throw;
          throw SolveError(std::string(e.what()) + " [step size already cut to " +
                           std::to_string(dt) + " s; -ts_dt_min " + std::to_string(control.dt_min) +
                           " s]");
        }
        PetscPrintf(comm,
                    "fsi_app: step %ld failed with dt = %.4e s (%s); retrying with dt = "
                    "%.4e s\n",
                    pb.step_index() + 1, dt, e.what(), control.dt);
        continue;
      }
      control.accepted(s.newton);
      const double step_s = MPI_Wtime() - t0;
      if (pb.step_index() == first_step + 1) check_unused_options();
      tot.steps++;
      tot.newton += s.newton;
      tot.krylov += s.krylov;
      tot.newton_max = std::max<long>(tot.newton_max, s.newton);
      tot.krylov_max = std::max<long>(tot.krylov_max, s.krylov);
      const double o0 = MPI_Wtime();
      FSI_CALL(PetscLogStagePush(st.output));
      wss.update(pb, dt);
      std::vector<double> row = {(double)pb.step_index(), pb.time(), (double)s.newton,
                                 (double)s.krylov,        step_s,    dt};
      auto m = mon.evaluate(pb), sm = smon.evaluate(pb);
      row.insert(row.end(), m.begin(), m.end());
      row.insert(row.end(), sm.begin(), sm.end());
      row.insert(row.end(), wss.values().begin(), wss.values().end());
      if (pb.mesh_motion())
        row.insert(row.end(), {pb.mesh_quality_last().min_jacobian,
                               pb.mesh_quality_last().max_skewness, (double)s.geometry_iterations});
      out.monitor_row(row);
      extremes.add(pb.time(), row, 6);
      if (fields_every > 0 && pb.step_index() % fields_every == 0) {
        Vec loc = space.create_local(), dloc = space.create_local();
        pb.solution_local(loc);
        pb.displacement_local(dloc);
        fields->write(pb.step_index(), pb.time(), loc, pb.coordinates(), dloc);
        FSI_CALL(VecDestroy(&loc));
        FSI_CALL(VecDestroy(&dloc));
        wss.write_instantaneous(pb.step_index(), pb.time());
      }
      FSI_CALL(PetscLogStagePop());
      output_time += MPI_Wtime() - o0;
      progress(comm, pb, s, step_s, MPI_Wtime() - loop_start, first_time);
      if (checkpoint_every > 0 && pb.step_index() % checkpoint_every == 0) write_checkpoint();
      if (const int sig = stop_requested(comm)) {
        write_checkpoint();
        converged = false;
        exit_code = 128 + sig;
        reason = std::string("stopped by signal ") +
                 (sig == SIGTERM  ? "SIGTERM"
                  : sig == SIGINT ? "SIGINT"
                                  : "SIGUSR1") +
                 " at step " + std::to_string(pb.step_index()) + "; resume with -restart " +
                 checkpoint_path;
        PetscPrintf(comm, "fsi_app: %s\n", reason.c_str());
        break;
      }
    }
  } catch (SolveError &e) {
    converged = false;
    exit_code = 3;
    reason = e.what();
    PetscPrintf(comm, "fsi_app: %s\n", e.what());
    write_checkpoint(); // the last converged state, to resume from with other settings
    reason += "; last converged state in " + checkpoint_path;
    PetscPrintf(comm, "fsi_app: last converged state (step %ld, t = %.6e s) written to %s\n",
                pb.step_index(), pb.time(), checkpoint_path.c_str());
  }
  if (converged && (checkpoint_every > 0) && pb.step_index() % checkpoint_every != 0)
    write_checkpoint(); // the end state, to extend the run
  out.close_monitor();
  if (fields) fields->close();
  wss.close();
  tot.wall = MPI_Wtime() - t_start;

  // Summary: what ran, its size, its cost, and the accuracy indicators the scene defines.
  const CostCounters &c = pb.cost();
  double mem = peak_memory_mb(), mem_max, mem_min;
  MPI_Allreduce(&mem, &mem_max, 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(&mem, &mem_min, 1, MPI_DOUBLE, MPI_MIN, comm);
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
      .set("newton_mean_per_step", tot.steps ? double(tot.newton) / tot.steps : 0.0)
      .set("krylov_mean_per_step", tot.steps ? double(tot.krylov) / tot.steps : 0.0)
      .set("krylov_mean_per_newton", tot.newton ? double(tot.krylov) / tot.newton : 0.0);
  cost.set("jacobians", c.jacobians)
      .set("residuals", c.residuals)
      .set("linear_solver_seconds_per_newton", tot.newton ? ls_max / tot.newton : 0.0)
      .set("jacobian_tets_per_second_per_rank",
           jt_max > 0 ? double(fc_g + sc_g) / size * c.jacobians / jt_max : 0.0)
      .set("residual_tets_per_second_per_rank",
           rt_max > 0 ? double(fc_g + sc_g) / size * c.residuals / rt_max : 0.0)
      .set("peak_memory_mb_per_rank_max", mem_max)
      .set("peak_memory_mb_per_rank_min", mem_min);
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
      .set("final_step", pb.step_index())
      .set("final_time", pb.time())
      .set("iterations", iters)
      .set("wall_time", times)
      .set("cost", cost)
      .set("converged", converged)
      .set("reason", reason);
  Json sc;
  sc.set("adapt", control.enabled ? "cut" : "none")
      .set("failed_steps", tot.failed)
      .set("cuts", control.cuts)
      .set("grows", control.grows)
      .set("dt_final", control.dt);
  j.set("step_control", sc);
  if (!restart.empty()) {
    Json r;
    r.set("file", restart).set("step", first_step).set("time", first_time);
    j.set("restarted_from", r);
  }
  if (checkpoints > 0) j.set("checkpoint", checkpoint_path);
  if (wss.active()) j.set("hemodynamics", wss.summary());
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
  if (tot.steps > 0) j.set("monitors", extremes.json());
  out.write_summary(j);
  // The cost line: what this run paid, per stage (max over ranks), per step and per iteration.
  const char *status = converged ? "done" : exit_code == 3 ? "FAILED" : "STOPPED";
  const double per_step = tot.steps ? (tot.wall - setup_time) / tot.steps : 0.0;
  PetscPrintf(comm,
              "fsi_app: %s: %ld steps, %.3g s/step; Newton %.2f/step (max %ld), Krylov %.1f/Newton "
              "(max %ld/step); wall %.2f s = setup %.2f + Jacobian %.2f + residual %.2f + linear "
              "solver %.2f + mesh motion %.2f + output %.2f + other %.2f; %ld dofs (velocity %ld, "
              "pressure %ld); peak memory %.0f MB/rank; results in %s\n",
              status, tot.steps, per_step, tot.steps ? double(tot.newton) / tot.steps : 0.0,
              tot.newton_max, tot.newton ? double(tot.krylov) / tot.newton : 0.0, tot.krylov_max,
              tot.wall, setup_time, jt_max, rt_max, ls_max, c.mesh_motion_time, output_time,
              std::max(0.0, tot.wall - setup_time - jt_max - rt_max - ls_max - c.mesh_motion_time -
                                output_time),
              (long)(space.n_velocity + space.n_pressure), (long)space.n_velocity,
              (long)space.n_pressure, mem_max, out.dir().c_str());
  return exit_code;
}

} // namespace

int main(int argc, char **argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, help));
  fsi::register_pcd_preconditioner();
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
