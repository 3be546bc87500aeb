// What the time loop carries besides the Simulation, and what it does between steps: the mesh
// file the run is on and the remesh count (a checkpoint must name them), the checkpoint file, the
// field files of each mesh; capturing the state, writing a checkpoint, remeshing, rebuilding.
#pragma once
#include "fsi/ale/remesh.hpp"
#include "fsi/io/output.hpp"
#include "fsi/run/run_report.hpp"
#include "fsi/run/simulation.hpp"
#include "fsi/time/step_control.hpp"
#include <memory>
#include <string>
#include <vector>

namespace fsi {

class LoopState {
public:
  LoopState(MPI_Comm comm, Output &out, RunReport &report, OutputNames &names, StepControl &control,
            std::unique_ptr<Simulation> &sim, std::unique_ptr<Mesh> &mesh,
            const RemeshOptions &remesh_options, std::string mesh_file, long remeshes);
  // The state at the last accepted step, with the step control and the mesh it lives on.
  RunState state() const;
  void write_checkpoint();
  // Remesh the fluid at the last accepted state (the Simulation and mesh are replaced).
  void remesh();
  // Rebuild the whole Simulation from its state on the same mesh (-sim_rebuild_every).
  void rebuild();
  const std::string &checkpoint_path() const { return checkpoint_path_; }
  long checkpoints() const { return checkpoints_; }
  // A stop signal: checkpoint, say so; the outcome names the file to resume from.
  RunOutcome stop(int sig);
  // A step that cannot be taken (SolveError): checkpoint of the last converged state, say so.
  RunOutcome failed(const std::string &why);
  // After the loop: one XDMF over the field files of every mesh the run was on.
  void merge_fields() const;

private:
  MPI_Comm comm_;
  Output &out_;
  RunReport &report_;
  OutputNames &names_;
  StepControl &control_;
  std::unique_ptr<Simulation> &sim_;
  std::unique_ptr<Mesh> &mesh_;
  std::string mesh_file_; // the remeshed mesh the run is on (empty: the scene's)
  long remeshes_;
  const RemeshOptions &remesh_options_;
  std::string checkpoint_path_;
  long checkpoints_ = 0, crash_test_;
  std::vector<std::string> field_parts_; // one per mesh the run was on
};

// The step control of a new or resumed run (-restart_reset_dt: the scene's step, not the saved
// one), its error-control switch as the run's condition says.
StepControl step_control(MPI_Comm comm, const Scene &scene, Simulation &sim, const RunState *resume,
                         const std::string &restart);
// After each accepted step: the error-control switch follows the run's condition; a new period
// (-ts_adapt_period) starts at the scene's dt, also in a run resumed at a cycle's end.
void follow_switch(Simulation &sim, StepControl &control);
// The state to resume from (-restart FILE; null without), its read errors naming the option.
std::unique_ptr<RunState> read_restart(MPI_Comm comm, const std::string &restart,
                                       const Scene &scene);
// The run's mesh into `mesh`: the scene's, or the remeshed one a resumed state lives on (whose
// file is returned; "" for the scene's).
std::string load_run_mesh(MPI_Comm comm, const std::string &restart, const RunState *resume,
                          Mesh &mesh);
// The mesh a checkpoint after a remesh lives on: its recorded file, or (a run folder moved with
// its checkpoint) the same name in the remesh/ folder beside the checkpoint.
std::string locate_remeshed_mesh(const std::string &restart, const std::string &mesh_file);

} // namespace fsi
