// The coupled nonlinear system of one step: R(U) = sum of the physics modules' element residuals
// + the boundary conditions' terms, with Dirichlet dofs as rows u - g = 0 (identity Jacobian
// rows); Newton (SNES) with our assembled exact Jacobian; every solver choice is a PETSc option.
// The Jacobian's nonzero pattern comes from the modules' element dof lists and is rebuilt when a
// module says its couplings changed (contact pairs appear and vanish).  The kernels' context
// (time, history, geometry) is filled by the time integrator and the ALE object before a solve;
// this object adds the Newton iterate.
// -sim_pattern_rebuild_every N rebuilds the pattern every N solves whatever the modules say (a
// check of the rebuild path: the answer must not change).
#pragma once
#include "fsi/boundary/boundaries.hpp"
#include "fsi/physics/physics_module.hpp"
#include "fsi/solver/fluid_solid_split.hpp"
#include "fsi/solver/pcd.hpp"
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace fsi {

struct SolveStats {
  PetscInt newton = 0, krylov = 0;
  SNESConvergedReason reason = SNES_CONVERGED_ITERATING;
  bool inverted = false; // a residual met an inverted solid element
};

struct CostCounters {
  long residuals = 0, jacobians = 0, pattern_builds = 0;
  long preconditioner_rebuilds = 0; // forced by -newton_pc_rebuild_krylov
  double residual_time = 0, jacobian_time = 0, nonlinear_solve_time = 0;
  std::map<std::string, double> module_jacobian_time; // each module's add_jacobian, by name
};

class CoupledSystem {
public:
  // Largest number of dofs of one element (a Jacobian block): checked when the pattern is built.
  static constexpr int max_element_dofs = 96;

  explicit CoupledSystem(const Space &space);
  ~CoupledSystem();
  CoupledSystem(const CoupledSystem &) = delete;
  CoupledSystem &operator=(const CoupledSystem &) = delete;

  void add_module(std::unique_ptr<PhysicsModule> m) { modules_.push_back(std::move(m)); }
  void set_boundaries(const Boundaries *b) { bcs_ = b; }
  // With a field split, give the velocity block the rigid-body modes as near null space.
  void set_rigid_body_modes(bool on) { rigid_modes_ = on; }
  // F_p and M_p of the pcd Schur preconditioner (pcd.hpp), assembled with each Jacobian.
  void set_pcd(std::unique_ptr<PcdOperators> p) { pcd_ = std::move(p); }
  // Velocity block split into fluid and solid, set up on the first Jacobian.
  void set_fluid_solid_split(std::unique_ptr<FluidSolidSplit> s) { split_ = std::move(s); }
  // After modules and boundaries: matrix, SNES (no options prefix), field-split index sets.
  void setup_solver();

  const std::vector<std::unique_ptr<PhysicsModule>> &modules() const { return modules_; }
  // The context the kernels see (time and geometry filled by their owners).
  StepContext &context() { return ctx_; }
  // Dirichlet data of this step: (local dof, value); set before solve().
  std::vector<std::pair<PetscInt, double>> &dirichlet_values() { return bc_values_; }
  // Solve R(U) = 0 from the initial guess U (Dirichlet values are put into U first).
  SolveStats solve(Vec U);
  // A new step size invalidates a Jacobian the scene computes once (-snes_lag_jacobian -2).
  // The step size became dt: a lagged Jacobian is recomputed; a preconditioner lagged over steps
  // is rebuilt when dt has moved by more than 1.5x from the one it was last rebuilt for.
  void step_size_changed(double dt);
  const CostCounters &cost() const { return cost_; }
  Mat matrix() const { return J_; } // the Jacobian (its pattern serves other operators)

  // SNES callbacks; residual() returns false where a solid element inverted.
  bool residual(Vec U, Vec F);
  void jacobian(Vec U, Mat J);

private:
  void build_pattern();
  void create_solver();
  const Space &space_;
  std::vector<std::unique_ptr<PhysicsModule>> modules_;
  const Boundaries *bcs_ = nullptr;
  std::unique_ptr<PcdOperators> pcd_;
  std::unique_ptr<FluidSolidSplit> split_;
  bool rigid_modes_ = false;
  long pattern_every_ = 0, solves_ = 0; // -sim_pattern_rebuild_every N (tests the rebuild path)
  // Inexact Newton aimed at -snes_rtol (-newton_inexact_gamma G, 0 = off): each linear solve
  // reduces the residual only to G x the Newton target, |F_0| snes_rtol, never tighter than
  // -ksp_rtol (ksp_rtol_min_) nor looser than 0.5.
  double inexact_gamma_ = 0, ksp_rtol_min_ = 0, newton_f0_ = 0;
  static PetscErrorCode inexact_monitor(SNES, PetscInt, PetscReal, void *);
  // A preconditioner lagged over iterations and steps (a reused LU) is rebuilt at the next
  // Jacobian when the last linear solve needed more than this many Krylov iterations
  // (-newton_pc_rebuild_krylov N, 0 = off): a stale factorisation costs more in GMRES
  // iterations than a new one costs.
  long pc_rebuild_krylov_ = 0;
  PetscInt lag_to_restore_ = 0; // the lag to set back after a solve that forced a rebuild
  static PetscErrorCode pc_rebuild_monitor(SNES, PetscInt, PetscReal, void *);
  // The field split's velocity block factored in place
  // (-fieldsplit_velocity_sub_pc_factor_in_place: its ILU overwrites the split's copy of the block
  // instead of holding a second one, ~100 MB per rank on the paper-size tube).  PETSc refills that
  // copy when it rebuilds the preconditioner and refuses a factored matrix, so before a rebuild the
  // block is marked unfactored.
  long factored_state_ = -1; // the Jacobian count when the split was last set up
  static PetscErrorCode in_place_presolve(KSP, Vec, Vec, void *);
  Vec F_ = nullptr, Uloc_ = nullptr, Floc_ = nullptr;
  Mat J_ = nullptr;
  SNES snes_ = nullptr;
  bool inverted_ = false;
  long fault_residual_ = 0; // -test_fault_residual N: evaluation N fails on rank 0 (tests)
  bool rebuild_preconditioner_ = false; // after a step-size change, with a lagged preconditioner
  double preconditioner_dt_ = 0;        // the dt of the last such rebuild
  std::vector<std::pair<PetscInt, double>> bc_values_;
  StepContext ctx_;
  CostCounters cost_;
};

} // namespace fsi
