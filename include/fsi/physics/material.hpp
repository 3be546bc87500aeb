// Solid constitutive laws in total-Lagrangian form (paper eq. 6): first Piola-Kirchhoff stress
// P(F) and its exact consistent tangent A_iJkL = dP_iJ / dF_kL.  -solid_material selects
// (moduli in Pa):
//   linear         small-strain Hooke, P = lambda tr(eps) I + 2 mu eps     (-solid_E, -solid_nu)
//   svk            St Venant-Kirchhoff, S = lambda tr(E) I + 2 mu E, P = F S (-solid_E, -solid_nu)
//   neo_hookean    W = mu/2 (I1bar - 3) + kappa/2 (J - 1)^2   (-solid_mu, -solid_kappa, or E, nu)
//   mooney_rivlin  W = C10 (I1bar - 3) + C01 (I2bar - 3) + kappa/2 (J - 1)^2
//                  (-solid_C10, -solid_C01, -solid_kappa)
//   either split law + e1/2 (exp(e2 (I1bar - 3)^2) - 1): isotropic Fung-type stiffening, the
//                  isotropic part of the Lee-Sacks leaflet law (-solid_exp_c1 e1, -solid_exp_c2 e2)
// For the split laws W(F) gives the energy, P is its closed-form derivative, and the tangent its
// closed-form second derivative (through the invariants I1, I2, J); the unit test checks P
// against finite differences of W and A against finite differences of P.  A cell with J <= 0 raises
// SolveError (inverted element) instead of producing NaN.
#pragma once
#include <memory>
#include <string>

namespace fsi {

struct Material {
  virtual ~Material() = default;
  virtual std::string name() const = 0;
  virtual double energy(const double F[3][3]) const = 0;
  virtual void stress(const double F[3][3], double P[3][3]) const = 0;
  // Every law here has an energy, so A has the major symmetry A_iJkL = A_kLiJ: the solid's
  // Jacobian forms only the (i, k) blocks with i <= k and mirrors the others.
  virtual void tangent(const double F[3][3], double P[3][3], double A[3][3][3][3]) const = 0;
  // True when A does not depend on F (small-strain linear elasticity): the stiffness is then a
  // product of P2 gradients, integrated exactly by a 4-point rule.
  virtual bool constant_tangent() const { return false; }
};

// Reads -solid_material and its parameters (validated: positive moduli, -1 < nu < 0.5).
std::unique_ptr<Material> make_material();
std::unique_ptr<Material> make_material(const std::string &kind, double p1, double p2,
                                        double p3 = 0, double e1 = 0, double e2 = 0);

} // namespace fsi
