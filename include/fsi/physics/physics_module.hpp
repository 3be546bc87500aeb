// A physics module contributes element residuals and Jacobians on its region.  The scene decides
// which modules exist; the coupled system sums what they add.  A module that is not created costs
// nothing.  A new physics is one new module file plus its line in src/physics/registry.cpp.
#pragma once
#include "fsi/post/monitor_row.hpp"
#include "fsi/time/step_context.hpp"
#include <string>
#include <vector>

namespace fsi {

struct PhysicsModule {
  virtual ~PhysicsModule() = default;
  virtual std::string name() const = 0;
  // Add this module's residual into the local array F (size Space::n_local).
  virtual void add_residual(const StepContext &ctx, PetscScalar *F) = 0;
  // Add this module's Jacobian into J (local indices, ADD_VALUES); rows of Dirichlet dofs skipped.
  virtual void add_jacobian(const StepContext &ctx, Mat J) = 0;
  virtual PetscInt n_cells() const = 0;
  // The local dofs of each of its elements (n per element): the Jacobian's nonzero pattern.
  virtual void element_dofs(std::vector<PetscInt> &dofs, int &n) const = 0;
  // True when element_dofs() changed since the pattern was last built (e.g. contact pairs found
  // on the deformed configuration): the system then rebuilds its matrix before the next solve.
  virtual bool couplings_changed() const { return false; }
  // Called after the pattern was built from element_dofs() and global_couplings().
  virtual void pattern_built() {}
  // Velocity-node pairs (global dof of the x component, two per pair) coupled beyond the
  // elements, possibly across ranks (contact): 3x3 blocks both ways in the pattern.
  virtual void global_couplings(std::vector<PetscInt> &pairs) const { pairs.clear(); }
  // Collective, on every rank before each residual and Jacobian: gather what spans ranks.
  virtual void prepare(const StepContext &) {}
  // Collective, at the start of each nonlinear solve (ctx.U = the initial guess), before
  // couplings_changed() is asked.
  virtual void begin_solve(const StepContext &) {}
  // Its columns of monitor.csv and, when the row wants them, their values after a step.
  virtual void add_to(MonitorRow &) const {}
};

} // namespace fsi
