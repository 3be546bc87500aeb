// What an element kernel needs to know about the current time step: the generalized-alpha
// coefficients (paper eq. 9), the solution iterate and history as local (ghosted) arrays, the
// fluid mesh configuration at t_{n+alpha_f} with its mesh velocity (ALE), and the solid
// displacement, which is not an unknown but follows from the velocity by the Newmark relation
//   u_{n+1} = u_n + dt v_n + dt^2 [(1/2 - beta) a_n + beta a_{n+1}],
//   beta = (1 + alpha_m - alpha_f)^2 / 4   (Chung-Hulbert; trapezoidal rule for rho_inf = 1).
// Static mode (ts_type steady) reads the unknown as a displacement rate over a load step:
// u_{n+1} = u_n + dt v, no inertia.
#pragma once
#include <petsc.h>
#include <vector>

namespace fsi {

struct StepContext {
  // time
  double t_n = 0, dt = 1, t_af = 0, t_np1 = 0;
  double alpha_m = 1, alpha_f = 1, gamma = 1, beta = 0.25;
  bool steady = false;
  // local arrays (size Space::n_local)
  const PetscScalar *U = nullptr;  // unknown at t_{n+1} (current Newton iterate)
  const PetscScalar *Vn = nullptr; // solution at t_n
  const PetscScalar *An = nullptr; // time derivative at t_n
  const PetscScalar *Dn = nullptr; // solid displacement at t_n (velocity dofs)
  // mesh (3 per local vertex)
  const double *X_af = nullptr;                    // vertex coordinates at t_{n+alpha_f} (momentum)
  const double *X_np1 = nullptr;                   // vertex coordinates at t_{n+1} (continuity)
  const double *W = nullptr;                       // mesh velocity, nullptr for a fixed mesh
  const std::vector<char> *is_dirichlet = nullptr; // per local dof

  // Stage values of a velocity dof: v_{n+af} and dv/dt_{n+am}.
  double v_af(PetscInt i) const {
    return steady ? PetscRealPart(U[i]) : PetscRealPart(Vn[i] + alpha_f * (U[i] - Vn[i]));
  }
  double a_np1(PetscInt i) const {
    return PetscRealPart((U[i] - Vn[i]) / (gamma * dt) - (1 - gamma) / gamma * An[i]);
  }
  double a_am(PetscInt i) const {
    if (steady) return 0.0;
    return PetscRealPart((1 - alpha_m) * An[i]) + alpha_m * a_np1(i);
  }
  // Solid displacement at t_{n+1} and at the stage t_{n+af}.
  double u_np1(PetscInt i) const {
    const double un = PetscRealPart(Dn[i]);
    if (steady) return un + dt * PetscRealPart(U[i]);
    return un + dt * PetscRealPart(Vn[i]) +
           dt * dt * ((0.5 - beta) * PetscRealPart(An[i]) + beta * a_np1(i));
  }
  double u_af(PetscInt i) const {
    const double un = PetscRealPart(Dn[i]);
    return steady ? u_np1(i) : un + alpha_f * (u_np1(i) - un);
  }
  // d(a_am)/dU, d(v_af)/dU and d(u_af)/dU
  double mass_shift() const { return steady ? 0.0 : alpha_m / (gamma * dt); }
  double stiff_shift() const { return steady ? 1.0 : alpha_f; }
  double disp_shift() const { return steady ? dt : alpha_f * beta * dt / gamma; }
};

} // namespace fsi
