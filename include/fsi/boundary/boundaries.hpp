// The scene's boundary conditions by named boundary (physical surface): -bc_names a,b,c and
// -bc_<name>_type TYPE for each (types: boundary_condition.hpp, registry.cpp; -help lists them
// with their options).  Boundaries not listed are traction-free.
// A node that two Dirichlet boundaries fix in the same component takes the value of the one
// with the higher precedence (noslip and clamped walls over prescribed velocity or
// displacement); between equal precedences, the boundary listed first in -bc_names.
// Pressure dofs of vertices outside the fluid belong to no equation and are held at zero;
// without a traction boundary the fluid's pressure level is fixed at one vertex.
#pragma once
#include "fsi/boundary/boundary_condition.hpp"
#include <memory>
#include <string>
#include <vector>

namespace fsi {

class Boundaries {
public:
  // fluid_cells: the fluid's local cells (nullptr without a fluid).
  Boundaries(const Mesh &mesh, const Space &space, const ExactFlow *exact,
             const ExactSolid *exact_solid, double mu, double rho,
             const std::vector<double> &material_X, const std::vector<PetscInt> *fluid_cells);
  // Local dof mask of all Dirichlet dofs (velocity nodes and the held pressures).
  const std::vector<char> &dirichlet_mask() const { return mask_; }
  // (local dof, value) for every velocity-data Dirichlet dof at time t, node positions X (3 per
  // local vertex), and the held pressures.
  void dirichlet_values(double t, const double *X,
                        std::vector<std::pair<PetscInt, double>> &out) const;
  // (local dof, displacement) for every prescribed-displacement dof at time t.
  void displacement_values(double t, std::vector<std::pair<PetscInt, double>> &out) const;
  // Boundary terms (tractions, loads) and their Jacobian.
  void add_residual(const StepContext &ctx, PetscScalar *F) const;
  void add_jacobian(const StepContext &ctx, Mat J) const;
  bool pressure_pinned() const { return pinned_; }
  // Lumped models on the boundaries (boundary_condition.hpp): after an accepted step, state,
  // monitors.
  void accept_step();
  void save_state(std::map<std::string, double> &s) const;
  void restore_state(const std::map<std::string, double> &s);
  std::vector<std::string> monitor_columns() const;
  std::vector<double> monitor_values() const;
  // Monitor-driven types (boundary_condition.hpp): the run's columns once, each step's row.
  void bind_monitors(const std::vector<std::string> &columns);
  void observe(double t, const std::vector<double> &row);
  // Dense all-to-all couplings of the boundary terms (global dofs, one list per block).
  std::vector<std::vector<PetscInt>> dense_couplings() const;
  // Global number of pressure dofs held at zero because no fluid cell touches them.
  long pressure_dofs_outside_fluid() const;
  const std::vector<std::unique_ptr<BoundaryCondition>> &list() const { return bcs_; }

private:
  void node_values(const BoundaryCondition &bc, size_t index, double t, const double *X,
                   std::vector<std::pair<PetscInt, double>> &out) const;
  const Space &space_;
  const std::vector<double> &material_X_;
  const ExactFlow *exact_ = nullptr;
  std::vector<std::unique_ptr<BoundaryCondition>> bcs_;
  std::vector<char> mask_;
  std::vector<int> owner_;              // per local dof: the index of the BC that sets it, or -1
  std::vector<PetscInt> outside_fluid_; // pressure dofs held at zero
  PetscInt pin_dof_ = -1;
  int pin_vertex_ = -1;
  bool pinned_ = false;
};

} // namespace fsi
