// A run on one mesh.  Built from the mesh, the scene (options) and optionally a state to resume
// from, a Simulation owns everything that indexes its discrete space: the space itself, the
// physics modules, the boundary conditions, the ALE mesh, the time integrator, the coupled
// system and its solver, the monitors and the field files.  Changing the mesh (or rebuilding on
// the same one) is: capture() -> destroy -> Simulation(new mesh, scene, &state); nothing
// survives that holds an index into the old space.
// Two references are kept apart: the fluid mesh's ALE reference (Space::X, where the mesh
// displacement is zero) and the solid's material reference (material_X(), where the solid
// displacement is measured); a state carries both.
#pragma once
#include "fsi/ale/ale.hpp"
#include "fsi/ale/velocity_projection.hpp"
#include "fsi/analytic/analytic.hpp"
#include "fsi/analytic/exact_solid.hpp"
#include "fsi/boundary/boundaries.hpp"
#include "fsi/io/checkpoint.hpp"
#include "fsi/io/field_writer.hpp"
#include "fsi/physics/fluid.hpp"
#include "fsi/physics/solid.hpp"
#include "fsi/post/monitor.hpp"
#include "fsi/post/monitor_condition.hpp"
#include "fsi/problem/coupled_system.hpp"
#include "fsi/time/generalized_alpha.hpp"
#include "fsi/time/step_control.hpp"
#include <memory>
#include <string>
#include <vector>

namespace fsi {

// What the scene asks for, read once from the options (-scene_name, -physics, -ts_*).
struct Scene {
  std::string name;
  std::vector<std::string> physics; // checked against the registry (physics_registry.hpp)
  TimeParams time;
  bool has(const std::string &physics_name) const;
  std::string tag() const; // what a state must match: physics and time scheme
  static Scene from_options();
};

// Where a Simulation writes its own files (field and wall-shear files are per mesh).
struct OutputNames {
  std::string dir, fields = "fields", hemo = "hemo";
  long fields_every = 0;
};

struct StepStats {
  PetscInt newton = 0, krylov = 0;
  int geometry_iterations = 0; // extra solves on an updated mesh (geometry implicit)
  double geometry_change = 0;  // last relative mesh change
  double error = -1;           // scaled local error estimate (-1: not computed)
};

class Simulation {
public:
  Simulation(const Mesh &mesh, const Scene &scene, const OutputNames &out, const RunState *state);
  ~Simulation();
  Simulation(const Simulation &) = delete;
  Simulation &operator=(const Simulation &) = delete;

  // One step of size dt() (a load step in static mode).  Throws SolveError (Newton failed, a
  // solid element inverted) or DistortionError (fluid mesh past its quality limits); with
  // tolerances, also StepRejected when the local error estimate is above them (not on the
  // run's first step, whose history is the initial condition's).
  StepStats step(const StepErrorTolerance *tol = nullptr);
  void set_dt(double dt);
  // The mesh was just remeshed: its first step does not ask for another remesh.
  // (Its first step has a transferred history: no error estimate.)
  void set_fresh_mesh() {
    ale_->set_fresh(true);
    history_exact_ = false;
  }
  // After a remesh: project V_n onto discretely divergence-free velocities (project = false:
  // only measure); the Dirichlet and solid velocities are kept.
  ProjectionReport project_velocity(bool project);
  double dt() const { return time_->dt(); }
  const Scene &scene() const { return scene_; }
  double time() const { return time_->time(); }
  long step_index() const { return time_->step_index(); }

  // After an accepted step of length dt: wall-shear update and the monitor values (the columns
  // of monitor_columns(), filled by name: monitor_row); fields when due.
  std::vector<std::string> monitor_columns();
  std::vector<double> after_step(double dt, const StepStats &s);
  void close_outputs();
  // -ts_adapt_switch_when: whether it was given, and whether its condition held after the last
  // accepted step (the step controller's error mode follows it).
  bool has_adapt_switch() const { return bool(adapt_switch_); }
  bool adapt_switched() const { return adapt_switched_; }
  // A new period (-ts_adapt_period) starts at the scene's dt whatever the condition: the switch
  // is off until the condition next holds after a step.
  void end_adapt_switch_for_period();
  // The state at the last accepted step (collective; data on rank 0).
  RunState capture() const;

  // Read access for the run's reports (summary.json, the header, the cost line).
  const Space &space() const { return space_; }
  const Ale &ale() const { return *ale_; }
  const CoupledSystem &system() const { return *system_; }
  const Boundaries &boundaries() const { return *bcs_; }
  const FluidModule *fluid() const { return fluid_; }
  const SolidModule *solid() const { return solid_; }
  // The monitors the scene switched on, in monitor.csv's column order.
  const std::vector<std::unique_ptr<Monitor>> &monitors() const { return monitors_; }
  const std::vector<double> &material_X() const { return material_X_; }
  Vec solution() const { return U_; }

private:
  void build_physics(const Mesh &mesh);
  void monitor_row(MonitorRow &row, const StepStats *s, const FieldView &view);
  void initialize(const std::string &ic);
  void restore(const RunState &s);
  void dirichlet_data(double t_np1);
  const Scene &scene_;
  bool geometry_monitor_ = false; // print each geometry pass's mesh change
  bool history_exact_ = true;     // false on a new mesh until its first step is taken
  OutputNames out_;
  Space space_;
  std::vector<double> material_X_;
  std::unique_ptr<ExactFlow> exact_;
  std::unique_ptr<ExactSolid> exact_solid_;
  const FluidModule *fluid_ = nullptr;
  const SolidModule *solid_ = nullptr;
  std::unique_ptr<Boundaries> bcs_;
  std::unique_ptr<GeneralizedAlpha> time_;
  // -ts_alpha_radius_switch_when: rho_inf is rho_switch_to_ after steps where the condition holds.
  MonitorCondition rho_switch_;
  double rho_switch_to_ = 0;
  bool rho_switched_ = false;
  // -ts_adapt_switch_when: error-controlled dt after steps where the condition holds.
  MonitorCondition adapt_switch_;
  bool adapt_switched_ = false;
  std::unique_ptr<Ale> ale_;
  std::unique_ptr<CoupledSystem> system_;
  std::unique_ptr<Checkpoint> keys_;
  std::vector<std::unique_ptr<Monitor>> monitors_;
  std::unique_ptr<FieldWriter> fields_;
  Vec U_ = nullptr, Sloc_ = nullptr;
  double time_af_ = 0;
  std::vector<std::pair<PetscInt, double>> disp_values_;
};

} // namespace fsi
