#include "fsi/physics/material.hpp"
#include "fsi/common.hpp"
#include "fsi/scene/options.hpp"

#include <cmath>
#include <cstdio>

namespace fsi {
namespace {

// C = F^T F (row-major) and its invariants I1 = tr C, I2 = (I1^2 - C:C) / 2 (C symmetric).
void cauchy_green(const double F[9], double C[9], double &I1, double &I2) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      C[3 * i + j] = F[i] * F[j] + F[3 + i] * F[3 + j] + F[6 + i] * F[6 + j];
  I1 = C[0] + C[4] + C[8];
  double trC2 = C[0] * C[0];
  for (int k = 1; k < 9; ++k)
    trC2 = trC2 + C[k] * C[k];
  I2 = 0.5 * (I1 * I1 - trC2);
}

// The isotropic exponential (Fung-type, the isotropic part of the Lee-Sacks leaflet law) added to
// the split laws: W_e = e1/2 (exp(e2 (I1bar - 3)^2) - 1), dW_e/dI1bar = e1 e2 x exp(e2 x^2) with
// x = I1bar - 3.  No stiffness at small strain; it stiffens the leaflets the way collagen does.
struct Exponential {
  double e1 = 0, e2 = 0; // [Pa], [-]
};

// Isochoric/volumetric Mooney-Rivlin energy (neo-Hookean when c01 = 0).
double mooney_rivlin_energy(const double F[9], double c10, double c01, double kappa,
                            Exponential ex) {
  const double J = F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) +
                   F[2] * (F[3] * F[7] - F[4] * F[6]);
  if (!(J > 0)) throw SolveError("inverted solid element (det F <= 0)");
  double C[9], I1, I2;
  cauchy_green(F, C, I1, I2);
  const double I1b = std::pow(J, -2.0 / 3.0) * I1, I2b = std::pow(J, -4.0 / 3.0) * I2;
  const double Jm1 = J - 1.0, x = I1b - 3.0;
  const double w = c10 * x + c01 * (I2b - 3.0) + (0.5 * kappa) * (Jm1 * Jm1);
  return ex.e1 > 0 ? w + (0.5 * ex.e1) * (std::exp(ex.e2 * (x * x)) - 1.0) : w;
}

// What the stress and the tangent of a split law share at one F.  With a = J^(-2/3) and
// g = dW/dI1bar (c10, plus the exponential's share):
struct SplitState {
  double cof[9], J, Jinv, C[9], I1, I2, a, x, g; // cof F = J F^-T (row-major), x = I1bar - 3
};

SplitState split_state(const double F[9], double c10, Exponential ex) {
  SplitState s;
  double *cof = s.cof;
  cof[0] = F[4] * F[8] - F[5] * F[7];
  cof[1] = F[5] * F[6] - F[3] * F[8];
  cof[2] = F[3] * F[7] - F[4] * F[6];
  cof[3] = F[2] * F[7] - F[1] * F[8];
  cof[4] = F[0] * F[8] - F[2] * F[6];
  cof[5] = F[1] * F[6] - F[0] * F[7];
  cof[6] = F[1] * F[5] - F[2] * F[4];
  cof[7] = F[2] * F[3] - F[0] * F[5];
  cof[8] = F[0] * F[4] - F[1] * F[3];
  s.J = F[0] * cof[0] + F[1] * cof[1] + F[2] * cof[2];
  if (!(s.J > 0)) throw SolveError("inverted solid element (det F <= 0)");
  cauchy_green(F, s.C, s.I1, s.I2);
  s.Jinv = std::pow(s.J, -1.0);
  s.a = std::pow(s.J, -2.0 / 3.0);
  s.x = s.a * s.I1 - 3.0;
  s.g = ex.e1 > 0 ? (ex.e1 * ex.e2) * (s.x * std::exp(ex.e2 * (s.x * s.x))) + c10 : c10;
  return s;
}

// The first Piola-Kirchhoff stress in closed form:
//   P = 2 g a (F - I1/3 F^-T) + 2 c01 a^2 (I1 F - F C - 2/3 I2 F^-T) + kappa (J - 1) cof F.
void split_stress(const SplitState &s, const double F[9], double c01, double kappa, double P[9]) {
  const double a2 = s.a * s.a, s1 = 2.0 * (s.g * s.a), s2 = (2 * c01) * a2;
  // coefficient of cof F: -2/3 g a I1 / J - 4/3 c01 a^2 I2 / J + kappa (J - 1)
  const double kc = ((-2.0 / 3.0) * (s.g * s.a * s.I1) + (-4.0 / 3.0 * c01) * a2 * s.I2) * s.Jinv +
                    kappa * (s.J - 1.0);
  for (int i = 0; i < 3; ++i)
    for (int L = 0; L < 3; ++L) {
      const double FC = F[3 * i] * s.C[L] + F[3 * i + 1] * s.C[3 + L] + F[3 * i + 2] * s.C[6 + L];
      P[3 * i + L] = s1 * F[3 * i + L] + s2 * (s.I1 * F[3 * i + L] - FC) + kc * s.cof[3 * i + L];
    }
}

// The tangent A_mn = dP_m / dF_n (m = 3i + J, n = 3k + L) in closed form.  W is a function of
// I1, I2, J (W = g-integral of a I1, c01 a^2 I2, kappa/2 (J-1)^2), so
//   A = sum_pq W_pq dp (x) dq + W1 d2I1 + W2 d2I2 + WJ d2J,
// dI1 = 2F, dI2 = 2(I1 F - F C), dJ = cof F;  d2I1 = 2 d_ik d_JL,
// d2I2 = 4 F_iJ F_kL + 2 I1 d_ik d_JL - 2 d_ik C_LJ - 2 F_iL F_kJ - 2 (F F^T)_ik d_JL,
// d2J = (cof_iJ cof_kL - cof_iL cof_kJ) / J.  It replaced a dual-number pass through P (9
// derivatives carried through every operation): the Mooney-Rivlin Jacobian 1.4x faster
// (docs/performance.md); checked against finite differences of P in test_materials.
void split_tangent(const SplitState &s, const double F[9], double c01, double kappa, Exponential ex,
                   double A[81]) {
  const double *cof = s.cof, *C = s.C, I1 = s.I1, Ji = s.Jinv, a = s.a, g = s.g;
  double B[9]; // F F^T
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      B[3 * i + k] =
          F[3 * i] * F[3 * k] + F[3 * i + 1] * F[3 * k + 1] + F[3 * i + 2] * F[3 * k + 2];
  const double a2 = a * a, I1b = a * I1, I2b = a2 * s.I2;
  const double gp = // dg/dI1bar
      ex.e1 > 0 ? ex.e1 * ex.e2 * std::exp(ex.e2 * s.x * s.x) * (1 + 2 * ex.e2 * s.x * s.x) : 0.0;
  const double W1 = g * a, W2 = c01 * a2;
  const double WJ = (-2.0 / 3.0 * g * I1b - 4.0 / 3.0 * c01 * I2b) * Ji + kappa * (s.J - 1);
  const double W11 = gp * a * a, W1J = -2.0 / 3.0 * a * Ji * (gp * I1b + g);
  const double W2J = -4.0 / 3.0 * c01 * a2 * Ji;
  const double WJJ =
      (4.0 / 9.0 * gp * I1b * I1b + 10.0 / 9.0 * g * I1b + 28.0 / 9.0 * c01 * I2b) * Ji * Ji +
      kappa;
  double D1[9], D2[9];
  for (int i = 0; i < 3; ++i)
    for (int L = 0; L < 3; ++L) {
      const double FC = F[3 * i] * C[L] + F[3 * i + 1] * C[3 + L] + F[3 * i + 2] * C[6 + L];
      D1[3 * i + L] = 2 * F[3 * i + L];
      D2[3 * i + L] = 2 * (I1 * F[3 * i + L] - FC);
    }
  const double dd = 2 * W1 + 2 * W2 * I1, WJ_J = WJ * Ji;
  for (int i = 0; i < 3; ++i)
    for (int Jc = 0; Jc < 3; ++Jc) {
      const int m = 3 * i + Jc;
      // the rank-one terms' coefficients against D1, D2, cof and F
      const double t1 = W11 * D1[m] + W1J * cof[m], t2 = W2J * cof[m];
      const double tJ = W1J * D1[m] + W2J * D2[m] + (WJJ + WJ_J) * cof[m];
      const double tF = 4 * W2 * F[m];
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L) {
          const int n = 3 * k + L;
          double v = t1 * D1[n] + t2 * D2[n] + tJ * cof[n] + tF * F[n];
          v -= WJ_J * cof[3 * i + L] * cof[3 * k + Jc] + 2 * W2 * F[3 * i + L] * F[3 * k + Jc];
          if (i == k) v += (Jc == L ? dd : 0.0) - 2 * W2 * C[3 * L + Jc];
          if (Jc == L) v -= 2 * W2 * B[3 * i + k];
          A[9 * m + n] = v;
        }
    }
}

struct SplitLaw : Material {
  std::string kind;
  double c10, c01, kappa;
  Exponential ex;
  SplitLaw(std::string k, double a, double b, double c, Exponential e)
      : kind(std::move(k)), c10(a), c01(b), kappa(c), ex(e) {}
  std::string name() const override {
    if (ex.e1 <= 0) return kind;
    char s[120];
    std::snprintf(s, sizeof s, "%s + exponential, c1 %g Pa, c2 %g", kind.c_str(), ex.e1, ex.e2);
    return s;
  }
  double energy(const double F[3][3]) const override {
    return mooney_rivlin_energy(&F[0][0], c10, c01, kappa, ex);
  }
  void stress(const double F[3][3], double P[3][3]) const override {
    split_stress(split_state(&F[0][0], c10, ex), &F[0][0], c01, kappa, &P[0][0]);
  }
  void tangent(const double F[3][3], double P[3][3], double A[3][3][3][3]) const override {
    const SplitState s = split_state(&F[0][0], c10, ex); // one state for both
    split_stress(s, &F[0][0], c01, kappa, &P[0][0]);
    split_tangent(s, &F[0][0], c01, kappa, ex, &A[0][0][0][0]);
  }
};

struct StVenantKirchhoff : Material {
  double lambda, mu;
  bool small_strain;
  StVenantKirchhoff(double l, double m, bool lin) : lambda(l), mu(m), small_strain(lin) {}
  std::string name() const override { return small_strain ? "linear" : "svk"; }
  bool constant_tangent() const override { return small_strain; }
  // Strain: E = (F^T F - I)/2 (svk) or eps = sym(F - I) (linear).
  void strain(const double F[3][3], double E[3][3]) const {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        if (small_strain)
          E[i][j] = 0.5 * (F[i][j] + F[j][i]) - (i == j);
        else {
          double c = 0;
          for (int k = 0; k < 3; ++k)
            c += F[k][i] * F[k][j];
          E[i][j] = 0.5 * (c - (i == j));
        }
      }
  }
  void second_pk(const double E[3][3], double S[3][3]) const {
    const double tr = E[0][0] + E[1][1] + E[2][2];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        S[i][j] = 2 * mu * E[i][j] + (i == j ? lambda * tr : 0.0);
  }
  double energy(const double F[3][3]) const override {
    double E[3][3], S[3][3], w = 0;
    strain(F, E);
    second_pk(E, S);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        w += 0.5 * S[i][j] * E[i][j];
    return w;
  }
  void stress(const double F[3][3], double P[3][3]) const override {
    double E[3][3], S[3][3];
    strain(F, E);
    second_pk(E, S);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        if (small_strain)
          P[i][j] = S[i][j];
        else
          P[i][j] = F[i][0] * S[0][j] + F[i][1] * S[1][j] + F[i][2] * S[2][j];
      }
  }
  void tangent(const double F[3][3], double P[3][3], double A[3][3][3][3]) const override {
    stress(F, P);
    double E[3][3], S[3][3];
    strain(F, E);
    second_pk(E, S);
    for (int i = 0; i < 3; ++i)
      for (int J = 0; J < 3; ++J)
        for (int k = 0; k < 3; ++k)
          for (int L = 0; L < 3; ++L) {
            if (small_strain) {
              A[i][J][k][L] =
                  lambda * (i == J) * (k == L) + mu * ((i == k) * (J == L) + (i == L) * (J == k));
            } else {
              double FF = 0; // F_iM F_kM
              for (int m = 0; m < 3; ++m)
                FF += F[i][m] * F[k][m];
              A[i][J][k][L] = (i == k) * S[L][J] + lambda * F[i][J] * F[k][L] +
                              mu * (F[i][L] * F[k][J] + FF * (J == L));
            }
          }
  }
};

void check_modulus(const std::string &name, double v) {
  if (!(v > 0))
    throw InputError("option -solid_" + name + " must be positive, got " + std::to_string(v));
}

} // namespace

std::unique_ptr<Material> make_material(const std::string &kind, double p1, double p2, double p3,
                                        double e1, double e2) {
  if (!(e1 >= 0) || !(e2 >= 0) || (e1 > 0) != (e2 > 0)) {
    char msg[200];
    std::snprintf(msg, sizeof msg,
                  "options -solid_exp_c1 [Pa] and -solid_exp_c2 [-] must both be positive (or "
                  "both 0: no exponential term), got %g and %g",
                  e1, e2);
    throw InputError(msg);
  }
  if (e1 > 0 && (kind == "linear" || kind == "svk"))
    throw InputError("options -solid_exp_c1/-solid_exp_c2 need -solid_material neo_hookean or "
                     "mooney_rivlin, not " +
                     kind);
  if (kind == "linear" || kind == "svk") { // p1 = E, p2 = nu
    check_modulus("E", p1);
    if (!(p2 > -1 && p2 < 0.5))
      throw InputError(
          "option -solid_nu must satisfy -1 < nu < 0.5, got " + std::to_string(p2) +
          " (use mooney_rivlin or neo_hookean with a bulk modulus for incompressibility)");
    const double lambda = p1 * p2 / ((1 + p2) * (1 - 2 * p2)), mu = p1 / (2 * (1 + p2));
    return std::make_unique<StVenantKirchhoff>(lambda, mu, kind == "linear");
  }
  if (kind == "neo_hookean") { // p1 = mu, p2 = kappa
    check_modulus("mu", p1);
    check_modulus("kappa", p2);
    return std::make_unique<SplitLaw>(kind, 0.5 * p1, 0.0, p2, Exponential{e1, e2});
  }
  if (kind == "mooney_rivlin") { // p1 = C10, p2 = C01, p3 = kappa
    check_modulus("C10", p1);
    if (!(p2 >= 0)) throw InputError("option -solid_C01 must be >= 0");
    check_modulus("kappa", p3);
    return std::make_unique<SplitLaw>(kind, p1, p2, p3, Exponential{e1, e2});
  }
  throw InputError("option -solid_material has unknown value '" + kind +
                   "'; use one of: linear, svk, neo_hookean, mooney_rivlin");
}

std::unique_ptr<Material> make_material() {
  const std::string kind =
      opt::choice("solid_material", "linear", {"linear", "svk", "neo_hookean", "mooney_rivlin"});
  const double e1 = opt::real("solid_exp_c1", 0), e2 = opt::real("solid_exp_c2", 0);
  if (kind == "linear" || kind == "svk")
    return make_material(kind, opt::required_positive("solid_E"), opt::real("solid_nu", 0.3), 0, e1,
                         e2);
  if (kind == "neo_hookean") {
    if (opt::has("solid_E")) { // convert E, nu to mu, kappa
      const double E = opt::positive("solid_E", 1), nu = opt::real("solid_nu", 0.3);
      if (!(nu > -1 && nu < 0.5)) throw InputError("option -solid_nu must satisfy -1 < nu < 0.5");
      return make_material(kind, E / (2 * (1 + nu)), E / (3 * (1 - 2 * nu)), 0, e1, e2);
    }
    return make_material(kind, opt::required_positive("solid_mu"),
                         opt::required_positive("solid_kappa"), 0, e1, e2);
  }
  return make_material(kind, opt::required_positive("solid_C10"), opt::nonnegative("solid_C01", 0),
                       opt::required_positive("solid_kappa"), e1, e2);
}

} // namespace fsi
