// Manufactured solid motion for verification: u(X, t) = s(t) phi(X) on the reference
// configuration, with s(t) = t (a load factor in static mode: t = 1 is the full field).
// The body force that makes it exact is computed from the material's own tangent:
//   b = rho0 d2u/dt2 - Div P(F),   (Div P)_i = A_iJkL(F) d2u_k / dX_L dX_J,   F = I + Grad u,
// so every material is verified with the same code.  -exact_displacement manufactured with
// -exact_amplitude A [m] (default 0.1) and -exact_wavenumber k [1/m] (default 1):
//   phi_i = A [sin(k X_i) cos(k X_{i+1}) + 1/2 sin(k X_{i+2})]   (indices cyclic).
#pragma once
#include "fsi/physics/material.hpp"
#include <memory>

namespace fsi {

class ExactSolid {
public:
  ExactSolid(double amplitude, double k) : A_(amplitude), k_(k) {}
  void displacement(const double X[3], double t, double u[3]) const;
  void velocity(const double X[3], double t, double v[3]) const;
  // grad[i][J] = d u_i / d X_J
  void gradient(const double X[3], double t, double grad[3][3]) const;
  // Body force per unit reference volume [N/m^3] for material `m` and density rho0.
  void body_force(const Material &m, double rho0, const double X[3], double t, double b[3]) const;

private:
  void phi(const double X[3], double p[3], double g[3][3], double h[3][3][3]) const;
  double A_, k_;
};

// Reads -exact_displacement none|manufactured and its parameters; nullptr for none.
std::unique_ptr<ExactSolid> make_exact_solid();

} // namespace fsi
