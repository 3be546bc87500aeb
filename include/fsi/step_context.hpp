// What an element kernel needs to know about the current time step: the generalized-alpha
// coefficients (paper eq. 9), the solution iterate and history as local (ghosted) arrays, and
// the fluid mesh configuration at t_{n+alpha_f} with its mesh velocity (ALE).
#pragma once
#include <petsc.h>
#include <vector>

namespace fsi {

struct StepContext {
  // time
  double t_n = 0, dt = 1, t_af = 0, t_np1 = 0;
  double alpha_m = 1, alpha_f = 1, gamma = 1;
  bool steady = false;
  // local arrays (size Space::n_local)
  const PetscScalar *U = nullptr;  // unknown at t_{n+1} (current Newton iterate)
  const PetscScalar *Vn = nullptr; // solution at t_n
  const PetscScalar *An = nullptr; // time derivative at t_n
  // mesh (3 per local vertex)
  const double *X_af = nullptr;                    // vertex coordinates at t_{n+alpha_f} (momentum)
  const double *X_np1 = nullptr;                   // vertex coordinates at t_{n+1} (continuity)
  const double *W = nullptr;                       // mesh velocity, nullptr for a fixed mesh
  const std::vector<char> *is_dirichlet = nullptr; // per local dof

  // Stage values of a velocity dof: v_{n+af} and dv/dt_{n+am}.
  double v_af(PetscInt i) const {
    return steady ? PetscRealPart(U[i]) : PetscRealPart(Vn[i] + alpha_f * (U[i] - Vn[i]));
  }
  double a_am(PetscInt i) const {
    if (steady) return 0.0;
    const double a1 = PetscRealPart((U[i] - Vn[i]) / (gamma * dt) - (1 - gamma) / gamma * An[i]);
    return PetscRealPart((1 - alpha_m) * An[i]) + alpha_m * a1;
  }
  // d(a_am)/dU and d(v_af)/dU
  double mass_shift() const { return steady ? 0.0 : alpha_m / (gamma * dt); }
  double stiff_shift() const { return steady ? 1.0 : alpha_f; }
};

} // namespace fsi
