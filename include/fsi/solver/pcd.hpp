// Pressure convection-diffusion (PCD) preconditioner for the Schur complement of the fluid's
// (velocity | pressure) split, built on PETSc's "selfp" matrix.
//
// S = A11 - B F^{-1} B^T, F the momentum block of one generalized-alpha step (mass rho cm M,
// viscosity, convection).  selfp approximates it by Sp = A11 - B diag(F)^{-1} B^T: exact in
// the mass-dominated limit (small dt), blind to convection (the diagonal of a Galerkin convection
// operator is ~0), so its iterations grow with the Courant number.  The approximate commutator
// of Kay, Loghin and Wathen (2002), F M^{-1} B^T ~ B^T M_p^{-1} F_p, gives
//   S^{-1} ~ (rho cm M_p)^{-1} F_p Sp^{-1},
// with, on the P1 pressure space, M_p the lumped mass and F_p = rho cm M_p + cf (mu L_p +
// rho N_p(v - w)) the same convection-diffusion-reaction operator (Dirichlet rows on the
// fluid's traction (outflow) boundaries, the Robin term -rho cf (c.n) on faces where flow enters
// through a prescribed velocity).  In the mass-dominated limit it is exactly selfp.
//
// Options: -pc_fieldsplit_schur_precondition selfp -fieldsplit_pressure_pc_type pcd; the Sp solve
// takes options under -fieldsplit_pressure_pcd_ (default: one BoomerAMG V-cycle).  F_p and M_p
// are assembled with each Jacobian on the current mesh, only when the options ask for pcd.
#pragma once
#include "fsi/boundary/boundaries.hpp"
#include "fsi/physics/fluid.hpp"

namespace fsi {

// Register the PC type "pcd" with PETSc (once, after PetscInitialize).
void register_pcd_preconditioner();

class PcdOperators {
public:
  // True when the options select the pcd PC for the pressure split; throws InputError when they
  // do on a scene without a fluid or without the selfp Schur matrix.
  static bool requested(bool fluid);
  PcdOperators(const Space &space, const Mesh &mesh, const FluidModule &fluid,
               const Boundaries &bcs);
  ~PcdOperators();
  // F_p and rho cm M_p at the current Newton iterate.
  void assemble(const StepContext &ctx);

private:
  void element_rows(const PetscInt pdof[4], PetscInt rows[4], bool drop[4]) const;
  const Space &space_;
  const FluidModule &fluid_;
  std::vector<PetscInt> pindex_;     // per local dof: row in the pressure block (pressure dofs)
  std::vector<char> outflow_;        // per local dof: a pressure dof on a traction boundary
  std::vector<char> held_;           // per local dof: a Dirichlet (held) dof of the system
  std::vector<PetscInt> held_rows_;  // owned held pressure dofs, pressure-block rows
  std::vector<BoundaryFace> inflow_; // fluid faces with prescribed velocity (Robin term of F_p)
  Mat Fp_ = nullptr;
  Vec D_ = nullptr; // rho cm M_p (lumped); 1 on held rows, where S and Sp are the identity
};

} // namespace fsi
