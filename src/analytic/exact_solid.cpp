#include "fsi/analytic/exact_solid.hpp"
#include "fsi/scene/option_doc.hpp"
#include "fsi/scene/options.hpp"

#include <cmath>

namespace fsi {

// phi, its gradient g[i][J] and Hessian h[i][J][L] at X.
void ExactSolid::phi(const double X[3], double p[3], double g[3][3], double h[3][3][3]) const {
  const double k = k_, A = A_;
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J) {
      g[i][J] = 0;
      for (int L = 0; L < 3; ++L)
        h[i][J][L] = 0;
    }
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, l = (i + 2) % 3;
    const double si = std::sin(k * X[i]), ci = std::cos(k * X[i]);
    const double sj = std::sin(k * X[j]), cj = std::cos(k * X[j]);
    const double sl = std::sin(k * X[l]), cl = std::cos(k * X[l]);
    p[i] = A * (si * cj + 0.5 * sl);
    g[i][i] = A * k * ci * cj;
    g[i][j] = -A * k * si * sj;
    g[i][l] = 0.5 * A * k * cl;
    h[i][i][i] = -A * k * k * si * cj;
    h[i][i][j] = h[i][j][i] = -A * k * k * ci * sj;
    h[i][j][j] = -A * k * k * si * cj;
    h[i][l][l] = -0.5 * A * k * k * sl;
  }
}

void ExactSolid::displacement(const double X[3], double t, double u[3]) const {
  double g[3][3], h[3][3][3];
  phi(X, u, g, h);
  for (int i = 0; i < 3; ++i)
    u[i] *= t;
}

void ExactSolid::velocity(const double X[3], double, double v[3]) const {
  double g[3][3], h[3][3][3];
  phi(X, v, g, h);
}

void ExactSolid::gradient(const double X[3], double t, double grad[3][3]) const {
  double p[3], h[3][3][3];
  phi(X, p, grad, h);
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      grad[i][J] *= t;
}

void ExactSolid::body_force(const Material &m, double, const double X[3], double t,
                            double b[3]) const {
  // s(t) = t: no acceleration, b = -Div P.
  double p[3], g[3][3], h[3][3][3], F[3][3], P[3][3], A[3][3][3][3];
  phi(X, p, g, h);
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      F[i][J] = (i == J) + t * g[i][J];
  m.tangent(F, P, A);
  for (int i = 0; i < 3; ++i) {
    b[i] = 0;
    for (int J = 0; J < 3; ++J)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L)
          b[i] -= A[i][J][k][L] * t * h[k][L][J];
  }
}

std::unique_ptr<ExactSolid> make_exact_solid() {
  if (opt::choice("exact_displacement", "none", {"none", "manufactured"}) == "none") return nullptr;
  return std::make_unique<ExactSolid>(opt::positive("exact_amplitude", 0.1),
                                      opt::positive("exact_wavenumber", 1.0));
}

// Its options, for -help and docs/options.md (option_doc.hpp).
OptionSection exact_solid_options() {
  return {"Verification (exact solid displacement)",
          {{"exact_displacement", "none", "-", "none | manufactured (solid)"},
           {"exact_amplitude", "0.1", "m", "manufactured displacement amplitude"},
           {"exact_wavenumber", "1", "1/m", "manufactured displacement wavenumber"}}};
}

} // namespace fsi
