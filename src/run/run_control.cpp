#include "fsi/run/run_control.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <sys/stat.h>

namespace fsi {

bool attempt_step(MPI_Comm comm, Simulation &sim, StepControl &control, StepStats &s) {
  const double dt = sim.dt();
  try {
    s = sim.step(control.error_tolerance());
  } catch (StepRejected &e) {
    if (!control.reject(e.error))
      throw SolveError("the local error estimate stays above -ts_rtol/-ts_atol (" +
                       std::to_string(e.error) + " x) at the smallest step -ts_adapt_dt_min " +
                       std::to_string(control.dt_min) + " s: loosen the tolerances");
    PetscPrintf(comm,
                "fsi_app: step %ld rejected: error estimate %.2f x the tolerance with dt = %.4e s; "
                "retrying with dt = %.4e s\n",
                sim.step_index() + 1, e.error, dt, control.dt);
    return false;
  } catch (FreshMeshDistortion &e) {
    // The step's motion would flatten a cell of a mesh just made: take it in smaller pieces.
    if (!control.cut()) throw;
    PetscPrintf(comm, "fsi_app: step %ld: %s; retrying with dt = %.4e s\n", sim.step_index() + 1,
                e.what(), control.dt);
    return false;
  } catch (DistortionError &) {
    throw;
  } catch (SolveError &e) {
    if (!control.cut()) {
      if (!control.enabled) throw;
      throw SolveError(std::string(e.what()) + " [step size already cut to " + std::to_string(dt) +
                       " s; -ts_adapt_dt_min " + std::to_string(control.dt_min) + " s]");
    }
    PetscPrintf(comm, "fsi_app: step %ld failed with dt = %.4e s (%s); retrying with dt = %.4e s\n",
                sim.step_index() + 1, dt, e.what(), control.dt);
    return false;
  }
  control.accepted(s.newton, s.error);
  return true;
}

std::unique_ptr<Simulation> rebuild(std::unique_ptr<Simulation> old, const Mesh &mesh,
                                    OutputNames &names, const RunState &state) {
  const Scene &scene = old->scene();
  old->close_outputs();
  old.reset(); // nothing of the old space survives
  release_free_heap();
  const std::string part = "rebuild" + std::to_string(state.step) + "_";
  names.fields = part + "fields";
  names.hemo = part + "hemo";
  return std::make_unique<Simulation>(mesh, scene, names, &state);
}

void remesh(MPI_Comm comm, std::unique_ptr<Simulation> &sim, std::unique_ptr<Mesh> &mesh,
            OutputNames &names, RunState &state, const RemeshOptions &options,
            RemeshReport &report) {
  const double t0 = MPI_Wtime();
  const long k = state.remeshes + 1;
  int rank;
  MPI_Comm_rank(comm, &rank);
  const std::string dir = names.dir + "/remesh";
  if (rank == 0) mkdir(dir.c_str(), 0775);
  char file[64];
  std::snprintf(file, sizeof file, "/mesh_%03ld.msh", k);
  const std::string path = dir + file;
  report.step = state.step;
  report.time = state.time;
  if (!sim->fluid()) throw InputError("remeshing needs a fluid");
  RunState next =
      remesh_fluid(*mesh, sim->space(), sim->fluid()->cells(), state, options, path, report);
  char *abs = rank == 0 ? realpath(path.c_str(), nullptr) : nullptr;
  next.mesh_file = abs ? abs : path;
  free(abs);
  next.remeshes = k;
  const Scene &scene = sim->scene();
  sim->close_outputs();
  sim.reset(); // nothing of the old space survives
  mesh = std::make_unique<Mesh>();
  release_free_heap(); // the old run and mesh
  load_mesh_file(comm, *mesh, path);
  names.fields = "remesh" + std::to_string(k) + "_fields";
  names.hemo = "remesh" + std::to_string(k) + "_hemo";
  sim = std::make_unique<Simulation>(*mesh, scene, names, &next);
  // From here the run is on the new mesh: a failure below checkpoints it there.
  state.mesh_file = next.mesh_file;
  state.remeshes = next.remeshes;
  if (options.test_fault == 2) throw SolveError("remesh test fault after the rebuild");
  sim->set_fresh_mesh();
  const ProjectionReport pr = sim->project_velocity(options.project);
  if (!pr.failure.empty())
    PetscPrintf(comm,
                "fsi_app: warning: the divergence-free projection after remesh %ld failed (%s): "
                "the interpolated velocity is kept (weak divergence %.1e)\n",
                k, pr.failure.c_str(), pr.before);
  report.weak_divergence = pr.before;
  report.weak_divergence_projected = options.project && pr.failure.empty() ? pr.after : -1;
  report.projection_seconds = pr.seconds;
  state = std::move(next);
  report.seconds = MPI_Wtime() - t0;
}

static volatile sig_atomic_t g_stop_signal = 0;
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
  // Past a file-size limit (ulimit -f) a write fails with EFBIG and is reported like a full
  // disk (exit 5, the last checkpoint intact) instead of the signal killing the rank.
  signal(SIGXFSZ, SIG_IGN);
}

int stop_requested(MPI_Comm comm) {
  int mine = g_stop_signal, any;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm);
  return any;
}

const char *signal_name(int sig) {
  return sig == SIGTERM ? "SIGTERM" : sig == SIGINT ? "SIGINT" : "SIGUSR1";
}

void check_unused_options() {
  if (opt::flag("allow_unused_options", false)) return;
  PetscInt left = 0;
  char **names, **values;
  FSI_CALL(PetscOptionsLeftGet(nullptr, &left, &names, &values));
  // The remesh projection's solver options are read at the first remesh, perhaps much later.
  std::string list;
  PetscInt n_left = 0;
  for (PetscInt i = 0; i < left; ++i)
    if (std::string(names[i]).rfind("remesh_projection_", 0) != 0)
      list += std::string(n_left++ ? ", -" : "-") + names[i];
  FSI_CALL(PetscOptionsLeftRestore(nullptr, &left, &names, &values));
  if (n_left > 0)
    throw InputError("option(s) nobody reads: " + list +
                     " (a typo? see -help; or pass -allow_unused_options)");
}

void progress(MPI_Comm comm, long step, double t, double t_end, double dt, long newton, long krylov,
              double step_s, double elapsed, double t0) {
  const double done = (t - t0) / (t_end - t0);
  const double eta = done > 0 ? std::max(0.0, elapsed / done * (1 - done)) : 0;
  PetscPrintf(comm,
              "step %5ld  t = %.4e/%.4e s  dt %.2e  newton %2d  krylov %4d  %.2f s/step  elapsed "
              "%.1f s  eta %.1f s\n",
              step, t, t_end, dt, (int)newton, (int)krylov, step_s, elapsed, eta);
}

} // namespace fsi
