// fsi_app: blood flow and deformable tissue, monolithic ALE finite elements on DMPlex.
//   mpirun -n 2 fsi_app -options_file examples/<scene>/<scene>.opts [-solver_preset X]
// The scene (a PETSc options file) switches physics on; what it does not ask for is not built.
// The algorithm: scene -> mesh -> Simulation(mesh, state) -> loop { step | rebuild } -> report.
#include "fsi/run/help.hpp"
#include "fsi/run/run_control.hpp"
#include "fsi/run/run_report.hpp"
#include "fsi/run/stages.hpp"
#include "fsi/scene/options.hpp"
#include "fsi/scene/petsc_input.hpp"
#include "fsi/solver/pcd.hpp"
#include "fsi/solver/schur_bilu.hpp"

#include <memory>
#include <unistd.h>

using namespace fsi;

namespace {

int run(MPI_Comm comm) {
  const double t_start = MPI_Wtime();
  FSI_CALL(PetscLogStagePush(Stages::get().setup));
  const Scene scene = Scene::from_options();
  Output out(comm, opt::string("out_dir", "results/" + scene.name));
  const std::string restart = opt::string("restart", "");
  const long checkpoint_every = opt::integer_at_least("checkpoint_every", 0, 0);
  const long rebuild_every = opt::integer_at_least("sim_rebuild_every", 0, 0);
  OutputNames names{out.dir(), restart.empty() ? "fields" : "fields_restart",
                    restart.empty() ? "hemo" : "hemo_restart",
                    opt::integer_at_least("out_fields_every", 0, 0)};
  std::unique_ptr<RunState> resume;
  if (!restart.empty()) {
    try {
      resume = std::make_unique<RunState>(RunState::read(comm, restart, scene.tag()));
    } catch (InputError &e) { // name the option the file came from
      const std::string what = e.what();
      throw InputError(what.find("-restart") == std::string::npos ? what + " (option -restart)"
                                                                  : what);
    }
  }
  auto mesh = std::make_unique<Mesh>();
  std::string mesh_file; // the remeshed mesh the run is on (empty: the scene's)
  long remeshes = 0;
  if (resume && !resume->mesh_file.empty()) { // a state after a remesh lives on that mesh
    mesh_file = resume->mesh_file;
    remeshes = resume->remeshes;
    if (access(mesh_file.c_str(), R_OK) != 0) { // moved with its run: next to the checkpoint
      const size_t slash = restart.find_last_of('/'), base = mesh_file.find_last_of('/');
      const std::string near = (slash == std::string::npos ? "." : restart.substr(0, slash)) +
                               "/remesh/" + mesh_file.substr(base + 1);
      if (access(near.c_str(), R_OK) != 0)
        throw InputError("the checkpoint " + restart + " lives on the remeshed mesh " + mesh_file +
                         ", which is missing (also as " + near +
                         "): keep the run's remesh/ folder beside its checkpoint");
      mesh_file = near;
    }
    load_mesh_file(comm, *mesh, mesh_file);
    skip_scene_mesh_options();
  } else {
    load_mesh(comm, *mesh);
  }
  const long remesh_every = opt::integer_at_least("ale_remesh_every", 0, 0);
  const RemeshOptions remesh_options = RemeshOptions::from_options();
  auto sim = std::make_unique<Simulation>(*mesh, scene, names, resume.get());
  std::vector<std::string> field_parts{names.fields}; // one per mesh the run was on
  StepControl control = StepControl::from_options(scene.time.dt);
  control.set_error_control(sim->adapt_switched()); // a resumed run's switch state
  if (resume) {
    // -restart_reset_dt: resume at the scene's step (a run stuck at cut steps), not the saved one
    if (!opt::flag("restart_reset_dt", false))
      control.resume(resume->dt, resume->easy_run, resume->error_prev);
    PetscPrintf(comm, "fsi_app: resumed from %s at step %ld, t = %.6e s, dt = %.3e s\n",
                restart.c_str(), sim->step_index(), sim->time(), control.dt);
  }
  // The error-control switch follows the run's condition; a new period (-ts_adapt_period)
  // starts at the scene's dt, also in a run resumed at a cycle's end.
  auto follow_switch = [&]() {
    if (control.switchable && control.period_start(sim->time())) sim->end_adapt_switch_for_period();
    control.set_error_control(sim->adapt_switched());
  };
  follow_switch();
  const long first_step = sim->step_index();
  const double first_time = sim->time(), t_end = scene.time.t_end;
  print_run_header(comm, scene, *mesh, *sim);
  out.write_options();
  auto columns = sim->monitor_columns();
  RunReport report(comm, scene, columns);
  columns.insert(columns.begin(), "dt");
  out.open_monitor(columns, restart.empty() ? -1 : first_step);
  FSI_CALL(PetscLogStagePop());
  report.set_setup_time(MPI_Wtime() - t_start);

  // Time loop to the scene's end time; a failed step is retried with a smaller dt.
  RunOutcome outcome;
  const std::string checkpoint_path = out.dir() + "/checkpoint.h5";
  long checkpoints = 0, crash_test = opt::integer_at_least("checkpoint_crash_test", 0, 0);
  auto state = [&]() {
    RunState s = sim->capture();
    s.dt = control.dt;
    s.easy_run = control.easy_run;
    s.error_prev = control.error_prev;
    s.mesh_file = mesh_file;
    s.remeshes = remeshes;
    return s;
  };
  auto write_checkpoint = [&]() {
    const double o0 = MPI_Wtime();
    state().write(comm, checkpoint_path, crash_test);
    ++checkpoints;
    report.add_output_time(MPI_Wtime() - o0);
  };
  const double loop_start = MPI_Wtime();
  bool options_checked = false;
  install_stop_handlers();
  try {
    while (sim->time() < t_end - 1e-9 * scene.time.dt &&
           (scene.time.step_cap == 0 || sim->step_index() < scene.time.step_cap)) {
      double dt = control.landing(sim->time());
      if (t_end - sim->time() < dt * (1 - 1e-9)) dt = t_end - sim->time(); // land on t_end
      sim->set_dt(dt);
      const double t0 = MPI_Wtime();
      StepStats s;
      // Remesh the fluid at the last accepted state: when the step asks (its predicted mesh
      // degrades) or every -ale_remesh_every steps; the step is then (re)taken on the new mesh.
      auto remesh_now = [&]() {
        RemeshReport r;
        report.absorb(*sim);
        RunState st = state();
        // st names the mesh the simulation is on, also when remesh() fails after the rebuild:
        // the checkpoint must name it.
        auto adopt = [&]() {
          mesh_file = st.mesh_file;
          remeshes = st.remeshes;
        };
        try {
          remesh(comm, sim, mesh, names, st, remesh_options, r);
        } catch (...) {
          adopt();
          throw;
        }
        adopt();
        field_parts.push_back(names.fields);
        report.remeshed(out, r);
      };
      bool accepted;
      try {
        accepted = attempt_step(comm, *sim, control, s);
      } catch (RemeshNeeded &e) {
        PetscPrintf(comm, "fsi_app: remeshing before step %ld: %s\n", sim->step_index() + 1,
                    e.what());
        remesh_now();
        continue;
      }
      if (!accepted) {
        report.failed_step();
        continue; // retried with the cut step
      }
      const double step_s = MPI_Wtime() - t0;
      // Solver options are read when the solver is first set up: a step with nothing to solve
      // (zero load) defers the check to the first step that solves.
      if (!options_checked && s.newton > 0) {
        check_unused_options();
        options_checked = true;
      }
      report.record(out, *sim, s, dt, step_s); // monitors, monitor.csv row, fields
      follow_switch();
      progress(comm, sim->step_index(), sim->time(), t_end, dt, s.newton, s.krylov, step_s,
               MPI_Wtime() - loop_start, first_time);
      if (remesh_every > 0 && sim->step_index() % remesh_every == 0 &&
          sim->time() < t_end - 1e-9 * scene.time.dt)
        remesh_now();
      if (checkpoint_every > 0 && sim->step_index() % checkpoint_every == 0) write_checkpoint();
      if (rebuild_every > 0 && sim->step_index() % rebuild_every == 0 &&
          sim->time() < t_end - 1e-9 * scene.time.dt) { // as a remesh does, on the same mesh
        const double r0 = MPI_Wtime();
        report.absorb(*sim);
        sim = rebuild(std::move(sim), *mesh, names, state());
        field_parts.push_back(names.fields);
        report.rebuilt(MPI_Wtime() - r0);
      }
      if (const int sig = stop_requested(comm)) {
        write_checkpoint();
        outcome = {false, 128 + sig,
                   std::string("stopped by signal ") + signal_name(sig) + " at step " +
                       std::to_string(sim->step_index()) + "; resume with -restart " +
                       checkpoint_path};
        PetscPrintf(comm, "fsi_app: %s\n", outcome.reason.c_str());
        break;
      }
    }
  } catch (SolveError &e) {
    outcome = {false, 3, e.what()};
    PetscPrintf(comm, "fsi_app: %s\n", e.what());
    write_checkpoint(); // the last converged state, to resume from with other settings
    outcome.reason += "; last converged state in " + checkpoint_path;
    PetscPrintf(comm, "fsi_app: last converged state (step %ld, t = %.6e s) written to %s\n",
                sim->step_index(), sim->time(), checkpoint_path.c_str());
  }
  if (outcome.converged && checkpoint_every > 0 && sim->step_index() % checkpoint_every != 0)
    write_checkpoint(); // the end state, to extend the run
  out.close_monitor();
  sim->close_outputs();
  int rank;
  MPI_Comm_rank(comm, &rank);
  if (names.fields_every > 0 && field_parts.size() > 1 && rank == 0)
    merge_xdmf(out.dir(), field_parts, field_parts[0] + "_all");
  report.absorb(*sim);
  report.write(out, *mesh, *sim, control, outcome, MPI_Wtime() - t_start, restart, first_step,
               first_time, checkpoints > 0 ? checkpoint_path : "");
  return outcome.exit_code;
}

} // namespace

int main(int argc, char **argv) {
  // A missing options file: one line before PETSc would print its trace (MPI first, so that
  // only rank 0 says it).
  MPI_Init(&argc, &argv);
  const std::string missing = check_options_files(argc, argv);
  if (!missing.empty()) {
    int rank;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank == 0) fprintf(stderr, "fsi_app: error: %s\n", missing.c_str());
    MPI_Finalize();
    return 2;
  }
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  fsi::register_pcd_preconditioner();
  fsi::register_schur_bilu_preconditioner();
  int code = 0;
  MPI_Comm comm = PETSC_COMM_WORLD;
  try {
    install_petsc_error_handler();
    apply_solver_preset();
    code = wants_help() ? print_help(comm) : run(comm);
  } catch (InputError &e) {
    PetscPrintf(comm, "fsi_app: error: %s\n", e.what());
    code = 2;
  } catch (OutputError &e) { // every rank has it (collective_output)
    PetscPrintf(comm, "fsi_app: error: output failed: %s\n", e.what());
    code = 5;
  } catch (std::exception &e) {
    PetscPrintf(comm, "fsi_app: failure: %s\n", e.what());
    code = 4;
  }
  PetscFinalize();
  MPI_Finalize();
  return code;
}
