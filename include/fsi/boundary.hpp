// Boundary conditions by named boundary (physical surface).  The scene lists them with
// -bc_names a,b,c and sets each with -bc_<name>_type:
//   noslip                       v = 0
//   velocity                     v = profile(x) * waveform(t); -bc_<name>_profile
//                                uniform|parabolic|exact, -bc_<name>_value [m/s] (mean speed),
//                                -bc_<name>_direction x,y,z, parabolic: -bc_<name>_center, _radius
//   pressure                     traction -P(t) n, P = -bc_<name>_value [Pa] * waveform(t), plus
//                                backflow stabilisation -beta rho/2 min(v.n, 0) v
//                                (-bc_<name>_backflow_beta, default 1: cancels the convective
//                                energy influx exactly; 0 turns it off, as a pressure-driven
//                                inlet needs): keeps
//                                the energy bounded when flow re-enters through the boundary
//   traction_exact               traction sigma_exact n from -exact_solution (verification)
// Solid boundaries:
//   clamped                      u = 0 (the velocity is held at zero)
//   displacement                 u = value * direction * waveform(t) [m], or -bc_<name>_profile
//                                exact (-exact_displacement); imposed through the velocity by
//                                the Newmark relation so that u_{n+1} is exact
//   traction                     dead load: nominal traction value [Pa] * direction * waveform(t)
//                                per unit reference area
//   follower_pressure            pressure value [Pa] * waveform(t) on the deformed surface:
//                                traction -p n da (p < 0 pulls); its Jacobian is included
// Waveforms: -bc_<name>_waveform constant|step|cosine|sine (+ _t_off, _period, _ramp).
// -bc_<name>_components x,y: the velocity components the boundary fixes.  Default: all for
// noslip/velocity, none for pressure/traction; on a pressure boundary, fixing the tangential
// components (e.g. x,y on a z-facing outlet) gives a parallel-flow outlet.
// Boundaries not listed are traction-free.  Dirichlet data are imposed at t_{n+1} on the nodes'
// current positions; tractions enter the momentum residual at t_{n+alpha_f}.
#pragma once
#include "fsi/analytic.hpp"
#include "fsi/exact_solid.hpp"
#include "fsi/p2tet.hpp"
#include "fsi/space.hpp"
#include "fsi/step_context.hpp"
#include <string>
#include <vector>

namespace fsi {

struct BoundaryCondition {
  enum Type {
    NoSlip,
    Velocity,
    Pressure,
    TractionExact,
    Clamped,
    Displacement,
    Traction,
    FollowerPressure
  } type = NoSlip;
  std::string name, profile = "uniform";
  double value = 0, dir[3] = {0, 0, 1}, center[3] = {0, 0, 0}, radius = 1, beta = 0;
  Waveform wave;
  bool fixed[3] = {false, false, false}; // velocity components fixed on this boundary
  std::vector<DofNode> nodes;            // Dirichlet types
  std::vector<BoundaryFace> faces;       // traction types
  bool displacement_type() const { return type == Displacement; }
  bool dirichlet() const {
    return type == NoSlip || type == Velocity || type == Clamped || type == Displacement;
  }
  bool fluid_traction() const { return type == Pressure || type == TractionExact; }
};

class Boundaries {
public:
  // fluid_cells: the fluid's local cells (nullptr without a fluid): pressure dofs of vertices
  // outside the fluid are held at zero (they belong to no equation).
  void setup(const Mesh &mesh, const Space &space, const ExactFlow *exact,
             const ExactSolid *exact_solid, double mu, double rho,
             const std::vector<PetscInt> *fluid_cells);
  // Local dof mask of all Dirichlet dofs (velocity nodes and the pinned pressures).
  const std::vector<char> &dirichlet_mask() const { return mask_; }
  // (local dof, value) for every Dirichlet dof at time t, node positions X (3 per vertex).
  void dirichlet_values(double t, const double *X,
                        std::vector<std::pair<PetscInt, double>> &out) const;
  // (local dof, displacement) for every prescribed-displacement dof at time t.
  void displacement_values(double t, std::vector<std::pair<PetscInt, double>> &out) const;
  void add_traction_residual(const StepContext &ctx, PetscScalar *F) const;
  // Backflow and follower-pressure terms (the other loads do not depend on the unknown).
  void add_traction_jacobian(const StepContext &ctx, Mat J) const;
  bool pressure_pinned() const { return pin_dof_ >= 0 || pinned_; }
  // Global number of pressure dofs held at zero because no fluid cell touches them.
  long pressure_dofs_outside_fluid() const;
  const std::vector<BoundaryCondition> &list() const { return bcs_; }

private:
  std::vector<BoundaryCondition> bcs_;
  std::vector<char> mask_;
  void add_solid_load_residual(const BoundaryCondition &bc, const StepContext &ctx,
                               PetscScalar *F) const;
  void add_follower_jacobian(const BoundaryCondition &bc, const StepContext &ctx, Mat J) const;
  const ExactFlow *exact_ = nullptr;
  const ExactSolid *exact_solid_ = nullptr;
  const Space *space_ = nullptr;
  std::vector<PetscInt> outside_fluid_; // pressure dofs held at zero
  double mu_ = 0, rho_ = 0;
  PetscInt pin_dof_ = -1;
  int pin_vertex_ = -1;
  bool pinned_ = false;
  QuadRule face_rule_;
};

} // namespace fsi
