#include "fsi/run/loop_state.hpp"
#include "fsi/io/field_writer.hpp"
#include "fsi/run/run_control.hpp"
#include "fsi/scene/options.hpp"

#include <unistd.h>

namespace fsi {

LoopState::LoopState(MPI_Comm comm, Output &out, RunReport &report, OutputNames &names,
                     StepControl &control, std::unique_ptr<Simulation> &sim,
                     std::unique_ptr<Mesh> &mesh, const RemeshOptions &remesh_options,
                     std::string mesh_file, long remeshes)
    : comm_(comm), out_(out), report_(report), names_(names), control_(control), sim_(sim),
      mesh_(mesh), mesh_file_(std::move(mesh_file)), remeshes_(remeshes),
      remesh_options_(remesh_options), checkpoint_path_(out.dir() + "/checkpoint.h5"),
      crash_test_(opt::integer_at_least("checkpoint_crash_test", 0, 0)), field_parts_{
                                                                             names.fields} {}

RunState LoopState::state() const {
  RunState s = sim_->capture();
  s.dt = control_.dt;
  s.easy_run = control_.easy_run;
  s.error_prev = control_.error_prev;
  s.mesh_file = mesh_file_;
  s.remeshes = remeshes_;
  return s;
}

void LoopState::write_checkpoint() {
  const double o0 = MPI_Wtime();
  state().write(comm_, checkpoint_path_, crash_test_);
  ++checkpoints_;
  report_.add_output_time(MPI_Wtime() - o0);
}

void LoopState::remesh() {
  RemeshReport r;
  report_.absorb(*sim_);
  RunState st = state();
  // st names the mesh the simulation is on, also when remesh() fails after the rebuild: the
  // checkpoint must name it.
  try {
    fsi::remesh(comm_, sim_, mesh_, names_, st, remesh_options_, r);
  } catch (...) {
    mesh_file_ = st.mesh_file, remeshes_ = st.remeshes;
    throw;
  }
  mesh_file_ = st.mesh_file, remeshes_ = st.remeshes;
  field_parts_.push_back(names_.fields);
  report_.remeshed(out_, r);
}

void LoopState::rebuild() {
  const double r0 = MPI_Wtime();
  report_.absorb(*sim_);
  sim_ = fsi::rebuild(std::move(sim_), *mesh_, names_, state());
  field_parts_.push_back(names_.fields);
  report_.rebuilt(MPI_Wtime() - r0);
}

void LoopState::merge_fields() const {
  int rank;
  MPI_Comm_rank(comm_, &rank);
  if (names_.fields_every > 0 && field_parts_.size() > 1 && rank == 0)
    merge_xdmf(out_.dir(), field_parts_, field_parts_[0] + "_all");
}

RunOutcome LoopState::stop(int sig) {
  write_checkpoint();
  RunOutcome o{false, 128 + sig,
               std::string("stopped by signal ") + signal_name(sig) + " at step " +
                   std::to_string(sim_->step_index()) + "; resume with -restart " +
                   checkpoint_path_};
  PetscPrintf(comm_, "fsi_app: %s\n", o.reason.c_str());
  return o;
}

RunOutcome LoopState::failed(const std::string &why) {
  RunOutcome o{false, 3, why};
  PetscPrintf(comm_, "fsi_app: %s\n", why.c_str());
  write_checkpoint(); // the last converged state, to resume from with other settings
  o.reason += "; last converged state in " + checkpoint_path_;
  PetscPrintf(comm_, "fsi_app: last converged state (step %ld, t = %.6e s) written to %s\n",
              sim_->step_index(), sim_->time(), checkpoint_path_.c_str());
  return o;
}

// The state to resume from (-restart), its read errors naming the option.
StepControl step_control(MPI_Comm comm, const Scene &scene, Simulation &sim, const RunState *resume,
                         const std::string &restart) {
  StepControl control = StepControl::from_options(scene.time.dt);
  control.set_error_control(sim.adapt_switched()); // a resumed run's switch state
  if (resume) {
    if (!opt::flag("restart_reset_dt", false))
      control.resume(resume->dt, resume->easy_run, resume->error_prev);
    PetscPrintf(comm, "fsi_app: resumed from %s at step %ld, t = %.6e s, dt = %.3e s\n",
                restart.c_str(), sim.step_index(), sim.time(), control.dt);
  }
  follow_switch(sim, control);
  return control;
}

void follow_switch(Simulation &sim, StepControl &control) {
  if (control.switchable && control.period_start(sim.time())) sim.end_adapt_switch_for_period();
  control.set_error_control(sim.adapt_switched());
}

std::unique_ptr<RunState> read_restart(MPI_Comm comm, const std::string &restart,
                                       const Scene &scene) {
  if (restart.empty()) return nullptr;
  try {
    return std::make_unique<RunState>(RunState::read(comm, restart, scene.tag()));
  } catch (InputError &e) {
    const std::string what = e.what();
    throw InputError(what.find("-restart") == std::string::npos ? what + " (option -restart)"
                                                                : what);
  }
}

std::string load_run_mesh(MPI_Comm comm, const std::string &restart, const RunState *resume,
                          Mesh &mesh) {
  if (!resume || resume->mesh_file.empty()) {
    load_mesh(comm, mesh);
    return "";
  }
  const std::string file = locate_remeshed_mesh(restart, resume->mesh_file);
  load_mesh_file(comm, mesh, file);
  skip_scene_mesh_options();
  return file;
}

std::string locate_remeshed_mesh(const std::string &restart, const std::string &mesh_file) {
  if (access(mesh_file.c_str(), R_OK) == 0) return mesh_file;
  const size_t slash = restart.find_last_of('/'), base = mesh_file.find_last_of('/');
  const std::string near = (slash == std::string::npos ? "." : restart.substr(0, slash)) +
                           "/remesh/" + mesh_file.substr(base + 1);
  if (access(near.c_str(), R_OK) != 0)
    throw InputError("the checkpoint " + restart + " lives on the remeshed mesh " + mesh_file +
                     ", which is missing (also as " + near +
                     "): keep the run's remesh/ folder beside its checkpoint");
  return near;
}

} // namespace fsi
