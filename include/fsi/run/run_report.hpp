// What a run reports: per-step totals, the extremes of every monitor column, and at the end
// summary.json (what ran, its size, its cost per stage, the accuracy indicators the scene
// defines) and the one-line cost summary on stdout.  Costs of every Simulation the run built
// (rebuilds, remeshes) are summed.
#pragma once
#include "fsi/ale/remesh.hpp"
#include "fsi/io/output.hpp"
#include "fsi/run/simulation.hpp"
#include "fsi/time/step_control.hpp"
#include <map>
#include <string>
#include <vector>

namespace fsi {

struct RunOutcome {
  bool converged = true;
  int exit_code = 0;
  std::string reason = "completed";
};

class RunReport {
public:
  RunReport(MPI_Comm comm, const Scene &scene, const std::vector<std::string> &columns);
  // An accepted step: its statistics and monitor row (after the dt column).
  void step(const StepStats &s, double t, const std::vector<double> &values);
  void failed_step() { ++failed_; }
  // After an accepted step: the Simulation's monitors (and fields) and a monitor.csv row.
  void record(Output &out, Simulation &sim, const StepStats &s, double dt, double step_s);
  // Costs of a Simulation about to be destroyed (a rebuild), or of the last one at the end.
  void absorb(const Simulation &sim);
  void rebuilt(double seconds) { ++rebuilds_, rebuild_time_ += seconds; }
  // A remesh (its seconds include the new Simulation): summary.json's "remesh" and remesh.csv.
  void remeshed(const Output &out, const RemeshReport &r);
  void set_setup_time(double s) { setup_time_ = s; }
  void add_output_time(double s) { output_time_ += s; }
  long steps() const { return steps_; }
  // summary.json and the cost line; `sim` is the final Simulation (already absorbed).
  void write(const Output &out, const Mesh &mesh, const Simulation &sim, const StepControl &c,
             const RunOutcome &o, double wall, const std::string &restart, long first_step,
             double first_time, const std::string &checkpoint) const;

private:
  MPI_Comm comm_;
  const Scene &scene_;
  std::vector<std::string> names_;
  std::vector<double> min_, max_, t_min_, t_max_, last_;
  long steps_ = 0, newton_ = 0, krylov_ = 0, newton_max_ = 0, krylov_max_ = 0, failed_ = 0;
  long rebuilds_ = 0, jacobians_ = 0, residuals_ = 0, pattern_builds_ = 0, pc_rebuilds_ = 0;
  double setup_time_ = 0, output_time_ = 0, rebuild_time_ = 0;
  std::vector<RemeshReport> remeshes_;
  double jacobian_time_ = 0, residual_time_ = 0, solve_time_ = 0, mesh_motion_time_ = 0;
  std::map<std::string, double> module_jacobian_time_;
};

} // namespace fsi
