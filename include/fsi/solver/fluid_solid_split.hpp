// Fluid/solid split of the velocity block, for FSI scenes: the velocity unknowns of the fluid
// and of the solid (every node of a solid cell, interface nodes included) become two sub-blocks
// of the (velocity | pressure) field split, so that each gets its own preconditioner.
//
// Why: at a fixed dt the solid rows of a step's velocity block are stiffness-dominated
// (alpha_f beta dt^2 E / (rho_s h^2) grows 4x per mesh halving), which block ILU cannot follow,
// while the fluid rows stay mass-dominated, where ILU is right and multigrid is not (convection).
// With smoothed-aggregation AMG and the rigid-body modes on the solid and ILU on the fluid, the
// Krylov count stays flat on the tube refined at a fixed dt (docs/solver_scaling.md).
//
// Options: -fieldsplit_velocity_pc_type fieldsplit (and its sub-options under
// -fieldsplit_velocity_fieldsplit_fluid_ / _solid_; preset petsc_options/fieldsplit_fsi.opts).
// PETSc 3.18 cannot split a split by index sets from options, and the velocity block's PC only
// exists after the outer PCSetUp: configure() runs that setup once, on the first Jacobian.
#pragma once
#include "fsi/discretization/space.hpp"
#include <vector>

namespace fsi {

class FluidSolidSplit {
public:
  // True when the options ask for a split velocity block; throws InputError when they do and
  // the scene has no solid or no fluid, or the outer PC is not a field split.
  static bool requested(bool fluid, bool solid);
  FluidSolidSplit(const Space &space, const std::vector<PetscInt> &solid_cells)
      : space_(space), solid_cells_(solid_cells) {}
  // Set up the outer PC on J (assembled) and hand the velocity PC its "fluid" and "solid" index
  // sets, the solid's with the rigid-body modes as near null space.  Once.
  void configure(KSP ksp, Mat J);
  bool configured() const { return done_; }
  void reset() { done_ = false; } // a new solver: configure again

private:
  const Space &space_;
  const std::vector<PetscInt> &solid_cells_;
  bool done_ = false;
};

} // namespace fsi
