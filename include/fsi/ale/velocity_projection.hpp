// After a remesh the interpolated velocity is not discretely divergence-free on the new mesh
// (int q div v != 0 for the P1 pressure test functions q), and the first step on the new mesh
// answers with a pressure spike.  This projects the velocity V_n onto the discretely
// divergence-free fields in the L2 sense: the saddle-point system
//   M v + B^T l = M v*,   B v - eps Mp l = 0      (on the fluid cells, at the current positions)
// with the Dirichlet and solid velocity dofs held at their values (the solid's mesh does not
// change, the interface moves with it), eps = 1e-9 a relative regularisation that fixes the
// multiplier's constant where every boundary is Dirichlet.  Solved with the KSP of prefix
// -remesh_projection_ (default: MUMPS LU).  The pressure in V is left as it was.
#pragma once
#include "fsi/discretization/space.hpp"
#include <string>
#include <vector>

namespace fsi {

struct ProjectionReport {
  // Weak divergence sqrt(sum_b (int lambda_b div v)^2 / sum_b (int lambda_b)^2) over the RMS of
  // |grad v|: what Taylor-Hood keeps at zero (the L2 divergence it does not).
  double before = 0, after = 0;
  double seconds = 0;
  std::string failure; // the linear solver's reason when the projection failed (V unchanged)
};

// V: global [velocity, pressure] vector, changed in place.  X: current local vertex coordinates
// (3 per vertex).  fixed: local dof mask of the velocity dofs to keep (Dirichlet, solid).
// pattern: a matrix whose nonzero pattern holds the fluid cells' couplings and the diagonal (the
// run's Jacobian): its structure is reused, not rebuilt.
// The weak divergence of the velocity in the global vector V (collective).
double measure_weak_divergence(const Space &space, const std::vector<PetscInt> &fluid_cells,
                               const std::vector<double> &X, Vec V);

ProjectionReport project_divergence_free(const Space &space,
                                         const std::vector<PetscInt> &fluid_cells,
                                         const std::vector<double> &X,
                                         const std::vector<char> &fixed, Mat pattern, Vec V);

} // namespace fsi
