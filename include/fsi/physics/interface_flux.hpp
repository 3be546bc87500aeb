// Mass-conservative fluid-solid interface (option -ale_interface NAME, the physical surface
// between fluid and solid; needs a mesh motion).  The continuity equation's flux through the
// moving wall, int_Gamma q v_{n+1}.n dA, is replaced by the volume the wall's faces sweep over the
// step, (1/dt) int_0^1 int_Gamma(s) q delta.n dA ds, delta = X + u_{n+1}(v) - X_n at the face's
// vertices (implicit in the solid velocity, so the coupling stays monolithic; exact for straight
// faces moving linearly in time).  The mesh then sweeps exactly that volume when the geometry is
// iterated to convergence (-ale_geometry_iterations).  The two agree as dt -> 0 (v = w on the
// wall), and with the replacement the fluid's volume change equals dt (inflow - outflow) to
// round-off: the straight-sided mesh moved by the solid's Newmark displacement otherwise sweeps a
// volume that differs from the flux of v_{n+1} by O(dt) (0.3-2.5 % on the tube).
#pragma once
#include "fsi/discretization/p2tet.hpp"
#include "fsi/discretization/space.hpp"
#include "fsi/mesh/mesh.hpp"
#include "fsi/physics/physics_module.hpp"

namespace fsi {

class InterfaceMassFlux : public PhysicsModule {
public:
  // material_X: the solid's material reference (the wall's position is material_X + u).
  InterfaceMassFlux(const Space &space, const Mesh &mesh, const std::string &name,
                    const std::vector<PetscInt> &fluid_cells,
                    const std::vector<double> &material_X);
  std::string name() const override { return "conservative interface flux (" + name_ + ")"; }
  void add_residual(const StepContext &ctx, PetscScalar *F) override;
  void add_jacobian(const StepContext &ctx, Mat J) override;
  PetscInt n_cells() const override { return (PetscInt)faces_.size(); }
  void element_dofs(std::vector<PetscInt> &dofs, int &n) const override;

private:
  // q_a-weighted wall flux of v_{n+1} (sign: outward of the fluid) and its matrix.
  void wall_flux(const StepContext &ctx, const BoundaryFace &f, double K[3][18]) const;
  void swept(const StepContext &ctx, const BoundaryFace &f, double S[3], double dS[3][9]) const;
  const Space &space_;
  const std::vector<double> &material_X_;
  std::string name_;
  std::vector<BoundaryFace> faces_;
  QuadRule rule_;
};

} // namespace fsi
