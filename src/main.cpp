// fsi_app: blood flow and deformable tissue, monolithic ALE finite elements on DMPlex.
//   mpirun -n 2 fsi_app -options_file examples/<scene>/<scene>.opts [-solver_preset X]
// The scene (a PETSc options file) switches physics on; what it does not ask for is not built.
// The algorithm: scene -> mesh -> Simulation(mesh, state) -> loop { step | remesh | rebuild } ->
// report.
#include "fsi/run/help.hpp"
#include "fsi/run/loop_state.hpp"
#include "fsi/run/run_control.hpp"
#include "fsi/run/run_report.hpp"
#include "fsi/run/stages.hpp"
#include "fsi/scene/options.hpp"
#include "fsi/scene/petsc_input.hpp"
#include "fsi/solver/pcd.hpp"
#include "fsi/solver/schur_bilu.hpp"

#include <memory>

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
  const std::unique_ptr<RunState> resume = read_restart(comm, restart, scene);
  auto mesh = std::make_unique<Mesh>();
  const std::string mesh_file = load_run_mesh(comm, restart, resume.get(), *mesh);
  const long remesh_every = opt::integer_at_least("ale_remesh_every", 0, 0);
  const RemeshOptions remesh_options = RemeshOptions::from_options();
  auto sim = std::make_unique<Simulation>(*mesh, scene, names, resume.get());
  StepControl control = step_control(comm, scene, *sim, resume.get(), restart);
  const long first_step = sim->step_index();
  const double first_time = sim->time(), t_end = scene.time.t_end;
  print_run_header(comm, scene, *mesh, *sim);
  out.write_options();
  auto columns = sim->monitor_columns();
  RunReport report(comm, scene, columns);
  columns.insert(columns.begin(), "dt");
  out.open_monitor(columns, restart.empty() ? -1 : first_step);
  LoopState loop(comm, out, report, names, control, sim, mesh, remesh_options, mesh_file,
                 resume ? resume->remeshes : 0);
  FSI_CALL(PetscLogStagePop());
  report.set_setup_time(MPI_Wtime() - t_start);

  // Time loop to the scene's end time; a failed step is retried with a smaller dt.
  RunOutcome outcome;
  const double loop_start = MPI_Wtime();
  const auto before_end = [&]() { return sim->time() < t_end - 1e-9 * scene.time.dt; };
  bool options_checked = false;
  install_stop_handlers();
  try {
    while (before_end() && (scene.time.step_cap == 0 || sim->step_index() < scene.time.step_cap)) {
      double dt = control.landing(sim->time());
      if (t_end - sim->time() < dt * (1 - 1e-9)) dt = t_end - sim->time(); // land on t_end
      sim->set_dt(dt);
      const double t0 = MPI_Wtime();
      StepStats s;
      bool accepted;
      try {
        accepted = attempt_step(comm, *sim, control, s);
      } catch (RemeshNeeded &e) { // the step's predicted mesh degrades: retaken on a new mesh
        PetscPrintf(comm, "fsi_app: remeshing before step %ld: %s\n", sim->step_index() + 1,
                    e.what());
        loop.remesh();
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
      follow_switch(*sim, control);
      progress(comm, sim->step_index(), sim->time(), t_end, dt, s.newton, s.krylov, step_s,
               MPI_Wtime() - loop_start, first_time);
      const long k = sim->step_index();
      if (remesh_every > 0 && k % remesh_every == 0 && before_end()) loop.remesh();
      if (checkpoint_every > 0 && k % checkpoint_every == 0) loop.write_checkpoint();
      if (rebuild_every > 0 && k % rebuild_every == 0 && before_end()) loop.rebuild();
      if (const int sig = stop_requested(comm)) {
        outcome = loop.stop(sig);
        break;
      }
    }
  } catch (SolveError &e) {
    outcome = loop.failed(e.what());
  }
  if (outcome.converged && checkpoint_every > 0 && sim->step_index() % checkpoint_every != 0)
    loop.write_checkpoint(); // the end state, to extend the run
  out.close_monitor();
  sim->close_outputs();
  loop.merge_fields();
  report.absorb(*sim);
  report.write(out, *mesh, *sim, control, outcome, MPI_Wtime() - t_start, restart, first_step,
               first_time, loop.checkpoints() > 0 ? loop.checkpoint_path() : "");
  return outcome.exit_code;
}

} // namespace

int main(int argc, char **argv) {
  // A missing options file: one line before PETSc would print its trace (MPI first, so that
  // only rank 0 says it).
  MPI_Init(&argc, &argv);
  if (!options_files_exist(argc, argv)) {
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
