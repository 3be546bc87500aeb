// Hyperelastic solid in total-Lagrangian form (paper eq. 10) on its reference configuration:
//   rho0 d2u/dt2 - Div P(F) = rho0 g + b,   F = I + Grad u,
// P2 tetrahedra.  The unknown is the solid's velocity (the same field as the fluid's, so in the
// coupled problem the interface velocity is shared); the displacement follows from it by the
// Newmark relation (see step_context.hpp), so the stress enters the momentum rows and its
// tangent enters the velocity block scaled by d(u_af)/dv = alpha_f beta dt / gamma.  In static
// mode the unknown is the displacement rate over a load step and there is no inertia.
// Options (prefix -solid_): region NAME (physical volume, default "solid"), rho [kg/m^3],
// gravity gx,gy,gz [m/s^2] (times -solid_gravity_waveform ...; in steady load stepping a linear
// ramp over the load steps by default), quad_degree (default 4), direct_insertion, and the material
// (material.hpp) with an optional fibre family (fibres.hpp).  A manufactured solution
// (exact_solid.hpp) adds its body force.
#pragma once
#include "fsi/analytic/analytic.hpp"
#include "fsi/analytic/exact_solid.hpp"
#include "fsi/discretization/element_assembler.hpp"
#include "fsi/discretization/p2tet.hpp"
#include "fsi/discretization/space.hpp"
#include "fsi/mesh/mesh.hpp"
#include "fsi/physics/fibres.hpp"
#include "fsi/physics/material.hpp"
#include "fsi/physics/physics_module.hpp"

namespace fsi {

struct SolidParams {
  std::string region = "solid";
  double rho = 1000;
  double gravity[3] = {0, 0, 0};
  Waveform gravity_wave; // its time dependence (steady: ramped with the load steps)
  int quad_degree = 4;
  bool direct_insertion = true;
  FibreFamily fibres; // added to the material where active (fibres.hpp)
  static SolidParams from_options();
};

struct SolidEnergy {
  double kinetic = 0, strain = 0; // [J], summed over all ranks
  double total() const { return kinetic + strain; }
};

class SolidModule : public PhysicsModule {
public:
  // material_X: the material (stress-free) reference, 3 per local vertex; kept by reference.
  SolidModule(const Space &space, const Mesh &mesh, const std::vector<double> &material_X,
              const SolidParams &p, std::unique_ptr<Material> material, const ExactSolid *exact);
  std::string name() const override {
    return "solid (" + material_->name() + (p_.fibres.active() ? " + " + p_.fibres.name() : "") +
           ")";
  }
  void add_residual(const StepContext &ctx, PetscScalar *F) override;
  void add_jacobian(const StepContext &ctx, Mat J) override;
  PetscInt n_cells() const override { return (PetscInt)cells_.size(); }
  void pattern_built() override { assembler_.reset(); }
  void element_dofs(std::vector<PetscInt> &dofs, int &n) const override {
    dofs = dofs_;
    n = 30;
  }
  const std::vector<PetscInt> &cells() const { return cells_; }
  const Material &material() const { return *material_; }
  // The first Piola-Kirchhoff stress at reference point X: the material's plus the fibres'.
  void stress(const double F[3][3], const double X[3], double P[3][3]) const;
  const SolidParams &params() const { return p_; }
  const std::vector<double> &material_X() const { return material_X_; }
  // Kinetic and stored energy of velocity V and displacement D (local arrays).
  SolidEnergy energy(const PetscScalar *V, const PetscScalar *D) const;

private:
  void reference_geometry(PetscInt k, TetGeometry &g, double X[4][3]) const;
  // The fibre direction at barycentric coordinates l of a cell with reference vertices X.
  void fibre_direction(const double *l, const double X[4][3], double a[3]) const;
  const Space &space_;
  const std::vector<double> &material_X_;
  SolidParams p_;
  std::unique_ptr<Material> material_;
  const ExactSolid *exact_;
  std::vector<PetscInt> cells_;
  QuadRule rule_;
  QuadRule jacobian_rule_; // rule_, or degree 2 (exact) for a constant tangent
  std::vector<std::array<double, 10>> N_;
  P2Integrals ref_;            // reference mass (exact from degree 4)
  std::vector<PetscInt> dofs_; // 30 per cell
  ElementAssembler assembler_;
  std::vector<size_t> jacobian_order_; // cells by their first dof: matrix rows stay in cache
  MPI_Comm comm_;
};

} // namespace fsi
