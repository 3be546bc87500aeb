// Solid constitutive laws in total-Lagrangian form (paper eq. 6): first Piola-Kirchhoff stress
// P(F) and its exact consistent tangent A_iJkL = dP_iJ / dF_kL.  -solid_material selects:
//   linear          small-strain Hooke, P = lambda tr(eps) I + 2 mu eps   (-solid_E, -solid_nu)
//   svk             St Venant-Kirchhoff, S = lambda tr(E) I + 2 mu E, P = F S   (-solid_E,
//   -solid_nu) neo_hookean     W = mu/2 (I1bar - 3) + kappa/2 (J - 1)^2   (-solid_mu, -solid_kappa,
//   or E, nu) mooney_rivlin   W = C10 (I1bar - 3) + C01 (I2bar - 3) + kappa/2 (J - 1)^2
//                   (-solid_C10, -solid_C01, -solid_kappa)  [Pa]
// The split laws are written once as W(F); P and A come from forward-mode automatic
// differentiation of that one expression, so stress and tangent cannot disagree.  A cell with
// J <= 0 raises SolveError (inverted element) instead of producing NaN.
#pragma once
#include <memory>
#include <string>

namespace fsi {

struct Material {
  virtual ~Material() = default;
  virtual std::string name() const = 0;
  virtual double energy(const double F[3][3]) const = 0;
  virtual void stress(const double F[3][3], double P[3][3]) const = 0;
  virtual void tangent(const double F[3][3], double P[3][3], double A[3][3][3][3]) const = 0;
};

// Reads -solid_material and its parameters (validated: positive moduli, -1 < nu < 0.5).
std::unique_ptr<Material> make_material();
std::unique_ptr<Material> make_material(const std::string &kind, double p1, double p2,
                                        double p3 = 0);

} // namespace fsi
