// Incompressible Navier-Stokes in ALE form on the mesh at t_{n+alpha_f} (paper eqs. 1, 2, 8):
//   rho (dv/dt|_X + ((v - w) . grad) v) - div sigma = 0,  div v = 0,
//   sigma = -p I + mu (grad v + grad v^T),
// P2 velocity / P1 pressure, generalized-alpha in time (velocity at n+af, acceleration at n+am,
// pressure at n+1; continuity div v_{n+1} = 0 on the mesh of t_{n+1}, so that each step's
// velocity is divergence-free on its own configuration), exact Newton Jacobian.  Options (prefix
// -fluid_):
//   region NAME (physical volume, default "fluid"), rho [kg/m^3], mu [Pa s],
//   model navier_stokes|stokes (stokes skips convection), quad_degree (default 4),
//   convection convective|skew_symmetric (skew_symmetric adds Temam's rho/2 (div v) v, zero for
//   the exact solution: Taylor-Hood's velocity is only weakly divergence-free, and without it
//   convection can feed kinetic energy into an under-resolved flow), direct_insertion (default
//   true; false = MatSetValuesLocal, for checking).
#pragma once
#include "fsi/discretization/element_assembler.hpp"
#include "fsi/discretization/p2tet.hpp"
#include "fsi/discretization/space.hpp"
#include "fsi/mesh/mesh.hpp"
#include "fsi/physics/physics_module.hpp"

namespace fsi {

struct FluidParams {
  std::string region = "fluid";
  double rho = 1000, mu = 0.003;
  bool stokes = false;
  bool skew = false;   // Temam's skew-symmetric convection
  double grad_div = 0; // gamma of gamma (div v, div w): penalises the weak divergence [Pa s]
  int quad_degree = 4;
  bool direct_insertion = true; // element matrices straight into the AIJ arrays
  static FluidParams from_options();
};

class FluidModule : public PhysicsModule {
public:
  FluidModule(const Space &space, const Mesh &mesh, const FluidParams &p);
  std::string name() const override {
    return p_.stokes ? "fluid (Stokes)" : "fluid (Navier-Stokes, ALE)";
  }
  void add_residual(const StepContext &ctx, PetscScalar *F) override;
  void add_jacobian(const StepContext &ctx, Mat J) override;
  PetscInt n_cells() const override { return (PetscInt)cells_.size(); }
  void pattern_built() override { assembler_.reset(); }
  void element_dofs(std::vector<PetscInt> &dofs, int &n) const override {
    dofs = dofs_;
    n = 34;
  }
  const FluidParams &params() const { return p_; }
  const std::vector<PetscInt> &cells() const { return cells_; }
  // P1 pressure-space operators of fluid cell c (index into cells()) on the mesh of t_{n+af},
  // for the pressure convection-diffusion preconditioner (pcd.hpp): the lumped mass ml and the
  // operator the momentum Jacobian applies to a velocity, F = rho cm M_lumped + cf (mu L +
  // rho N(v - w)), L the Laplacian, N the convection by the cell's mean velocity.
  void pressure_operators(const StepContext &ctx, size_t c, double ml[4], double F[4][4],
                          PetscInt pdof[4]) const;

private:
  struct Element; // gathered nodal data of one cell
  void gather(const StepContext &ctx, PetscInt k, Element &e) const;
  const Space &space_;
  FluidParams p_;
  std::vector<PetscInt> cells_; // local cell indices (0-based)
  QuadRule rule_;
  std::vector<std::array<double, 10>> N_; // P2 values per quadrature point
  // Reference integrals for the Jacobian (see add_jacobian), on the residual's rule so that the
  // two stay consistent where the integrand is above the rule's degree.
  P2Integrals ref_;
  QuadRule rule2_;             // degree 2: exact for products of two P2 gradients
  std::vector<PetscInt> dofs_; // per cell: 34 local dofs in element order
  ElementAssembler assembler_;
  std::vector<size_t> jacobian_order_; // cells by their first dof: matrix rows stay in cache
};

} // namespace fsi
