// Constitutive laws: P against finite differences of W, the tangent against finite differences
// of P (relative error < 1e-6, issue: hyperelastic solid), inverted elements and bad parameters.
#include "fsi/common.hpp"
#include "fsi/physics/fibres.hpp"
#include "fsi/physics/material.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

using namespace fsi;

static int failures = 0;
static void check(bool ok, const char *what, double v) {
  std::printf("%s: %s (%.2e)\n", ok ? "PASS" : "FAIL", what, v);
  if (!ok) ++failures;
}

int main() {
  bool threw = false;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.25, 0.25);
  double F[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      F[i][j] = (i == j ? 1.0 + 0.3 * (i - 1) : 0.0) + u(rng);
  struct Case {
    const char *kind;
    double p1, p2, p3, e1 = 0, e2 = 0;
  };
  const Case cases[] = {{"linear", 3e5, 0.3, 0},
                        {"svk", 3e5, 0.3, 0},
                        {"neo_hookean", 1e5, 1e7, 0},
                        {"mooney_rivlin", 8.25e3, 0.5e3, 8.75e6},
                        {"mooney_rivlin", 30420, 3380, 3.38e6, 13.3e3, 38.2}};
  for (const Case &c : cases) {
    auto m = make_material(c.kind, c.p1, c.p2, c.p3, c.e1, c.e2);
    double P[3][3], Pt[3][3], A[3][3][3][3];
    m->stress(F, P);
    m->tangent(F, Pt, A);
    double eP = 0, nP = 0, eA = 0, nA = 0, eC = 0;
    for (int k = 0; k < 3; ++k)
      for (int L = 0; L < 3; ++L) {
        const double h = 1e-6;
        double Fp[3][3], Fm[3][3], Pp[3][3], Pm[3][3];
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            Fp[i][j] = Fm[i][j] = F[i][j];
        Fp[k][L] += h;
        Fm[k][L] -= h;
        const double dW = (m->energy(Fp) - m->energy(Fm)) / (2 * h);
        eP += std::pow(dW - P[k][L], 2);
        nP += P[k][L] * P[k][L];
        eC += std::pow(Pt[k][L] - P[k][L], 2);
        m->stress(Fp, Pp);
        m->stress(Fm, Pm);
        for (int i = 0; i < 3; ++i)
          for (int J = 0; J < 3; ++J) {
            const double fd = (Pp[i][J] - Pm[i][J]) / (2 * h);
            eA += std::pow(fd - A[i][J][k][L], 2);
            nA += A[i][J][k][L] * A[i][J][k][L];
          }
      }
    char msg[128];
    const char *kind = c.e1 > 0 ? "mooney_rivlin+exp" : c.kind;
    std::snprintf(msg, sizeof msg, "%s: P = dW/dF (relative error)", kind);
    check(std::sqrt(eP / nP) < 1e-6, msg, std::sqrt(eP / nP));
    std::snprintf(msg, sizeof msg, "%s: tangent = dP/dF (relative error)", kind);
    check(std::sqrt(eA / nA) < 1e-6, msg, std::sqrt(eA / nA));
    std::snprintf(msg, sizeof msg, "%s: tangent call returns the same P", kind);
    check(std::sqrt(eC / nP) < 1e-14, msg, std::sqrt(eC / nP));
    // Stress-free reference state.
    double I[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, P0[3][3], n0 = 0;
    m->stress(I, P0);
    for (auto &r : P0)
      n0 += r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    std::snprintf(msg, sizeof msg, "%s: P(I) = 0", kind);
    check(std::sqrt(n0) < 1e-9 * c.p1, msg, std::sqrt(n0));
  }
  // Mooney-Rivlin uniaxial tension at a material point (kappa/mu = 1000): free lateral stretch
  // (P22 = P33 = 0 by bisection) against the incompressible closed form of benchmarks.md s.2,
  // nominal stress P = 2 (l - l^-2)(C10 + C01 / l), stretches 1.0 .. 1.5.
  {
    const double C10 = 8.25e3, C01 = 0.5e3, kappa = 1000 * 2 * (C10 + C01);
    auto m = make_material("mooney_rivlin", C10, C01, kappa);
    double worst = 0;
    for (double l = 1.05; l <= 1.5001; l += 0.05) {
      double lo = 0.5, hi = 1.0, Pl[3][3];
      for (int it = 0; it < 100; ++it) { // P22 increases with the lateral stretch
        const double t = 0.5 * (lo + hi);
        double Fu[3][3] = {{l, 0, 0}, {0, t, 0}, {0, 0, t}};
        m->stress(Fu, Pl);
        (Pl[1][1] > 0 ? hi : lo) = t;
      }
      const double exact = 2 * (l - 1 / (l * l)) * (C10 + C01 / l);
      worst = std::max(worst, std::fabs(Pl[0][0] / exact - 1));
    }
    check(worst < 0.005, "mooney_rivlin: uniaxial nominal stress within 0.5% of closed form",
          worst);
  }
  // The same with the exponential term (the valve's leaflets): dW/dI1 = C10 + e1 e2 x exp(e2 x^2),
  // x = I1 - 3, I1 = l^2 + 2/l, stretches 1.0 .. 1.3 (the stress grows 1000-fold).
  {
    // kappa 1e5 times the small-strain modulus: at l = 1.3 the tangent shear modulus is 25 times
    // it.
    const double C10 = 30420, C01 = 3380, kappa = 1e5 * 2 * (C10 + C01), e1 = 13.3e3, e2 = 38.2;
    auto m = make_material("mooney_rivlin", C10, C01, kappa, e1, e2);
    double worst = 0;
    for (double l = 1.025; l <= 1.3001; l += 0.025) {
      double lo = 0.5, hi = 1.0, Pl[3][3];
      for (int it = 0; it < 100; ++it) {
        const double t = 0.5 * (lo + hi);
        double Fu[3][3] = {{l, 0, 0}, {0, t, 0}, {0, 0, t}};
        m->stress(Fu, Pl);
        (Pl[1][1] > 0 ? hi : lo) = t;
      }
      const double x = l * l + 2 / l - 3;
      const double exact =
          2 * (l - 1 / (l * l)) * (C10 + e1 * e2 * x * std::exp(e2 * x * x) + C01 / l);
      worst = std::max(worst, std::fabs(Pl[0][0] / exact - 1));
    }
    check(worst < 0.005, "mooney_rivlin+exp: uniaxial nominal stress within 0.5% of closed form",
          worst);
  }
  // The fibre family (fibres.hpp): P against finite differences of W_f, the tangent against
  // finite differences of P, in tension along a0 (1.5 times F above: I4 1.32) and zero
  // stress and stiffness under fibre compression.
  {
    FibreFamily f;
    f.kind = FibreFamily::Circumferential;
    f.c1 = 5e3;
    f.c2 = 20;
    const double X[3] = {0.3, 0.4, 0.1}, a[3] = {-0.8, 0.6, 0}; // e_theta at X
    double ad[3];
    f.direction(X, ad);
    check(std::fabs(ad[0] - a[0]) + std::fabs(ad[1] - a[1]) + std::fabs(ad[2]) < 1e-15,
          "fibres: circumferential direction", std::fabs(ad[0] - a[0]));
    double Ff[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        Ff[i][j] = 1.5 * F[i][j];
    double P0[3][3] = {}, A[3][3][3][3] = {}, Pt[3][3] = {};
    f.add_stress(Ff, a, P0);
    f.add_tangent(Ff, a, Pt, A);
    double eP = 0, nP = 0, eA = 0, nA = 0;
    for (int k = 0; k < 3; ++k)
      for (int L = 0; L < 3; ++L) {
        const double h = 1e-7;
        double Fp[3][3], Fm[3][3], Pp[3][3] = {}, Pm[3][3] = {};
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            Fp[i][j] = Fm[i][j] = Ff[i][j];
        Fp[k][L] += h;
        Fm[k][L] -= h;
        eP += std::pow((f.energy(Fp, a) - f.energy(Fm, a)) / (2 * h) - P0[k][L], 2);
        nP += P0[k][L] * P0[k][L];
        f.add_stress(Fp, a, Pp);
        f.add_stress(Fm, a, Pm);
        for (int i = 0; i < 3; ++i)
          for (int J = 0; J < 3; ++J) {
            eA += std::pow((Pp[i][J] - Pm[i][J]) / (2 * h) - A[i][J][k][L], 2);
            nA += A[i][J][k][L] * A[i][J][k][L];
          }
      }
    double Fa[3] = {};
    for (int i = 0; i < 3; ++i)
      for (int J = 0; J < 3; ++J)
        Fa[i] += Ff[i][J] * a[J];
    std::printf("fibres: I4 = %.3f at the test F\n", Fa[0] * Fa[0] + Fa[1] * Fa[1] + Fa[2] * Fa[2]);
    check(nP > 0 && std::sqrt(eP / nP) < 1e-6, "fibres: P = dW/dF (relative error)",
          std::sqrt(eP / nP));
    check(nA > 0 && std::sqrt(eA / nA) < 1e-6, "fibres: tangent = dP/dF (relative error)",
          std::sqrt(eA / nA));
    // Uniaxial stretch l along a0 = e_x: P_xx = 2 l W'(l^2) = 2 l c1 c2 E exp(c2 E^2), E = l^2 - 1.
    const double ex[3] = {1, 0, 0}, l = 1.1, E = l * l - 1;
    double Fu[3][3] = {{l, 0, 0}, {0, 1, 0}, {0, 0, 1}}, Pu[3][3] = {};
    f.add_stress(Fu, ex, Pu);
    const double exact = 2 * l * f.c1 * f.c2 * E * std::exp(f.c2 * E * E);
    check(std::fabs(Pu[0][0] / exact - 1) < 1e-14, "fibres: uniaxial stress along a0", Pu[0][0]);
    double Fc[3][3] = {{0.9, 0, 0}, {0, 1.1, 0}, {0, 0, 1}}, Pc[3][3] = {}, Ac[3][3][3][3] = {};
    f.add_tangent(Fc, ex, Pc, Ac);
    double nc = 0;
    for (auto &r : Pc)
      nc += std::fabs(r[0]) + std::fabs(r[1]) + std::fabs(r[2]);
    for (auto &b : Ac)
      for (auto &c : b)
        for (auto &d : c)
          nc += std::fabs(d[0]) + std::fabs(d[1]) + std::fabs(d[2]);
    check(nc == 0, "fibres: no stress or stiffness in compression", nc);
    // Chord directions: commissures at 30, 150, 270 deg; the leaflet between 30 and 150 deg has
    // its chord along -x (normal to its bisector at 90 deg), the one across 270 -> 30 deg
    // (bisector 330 deg) along (sin 330, ... ) = (0.5, 0.866).
    FibreFamily g = f;
    g.kind = FibreFamily::Chord;
    g.commissures = {M_PI / 6, 5 * M_PI / 6, 1.5 * M_PI};
    const double X1[3] = {0.1, 0.5, 0}, X2[3] = {0.5, -0.1, 0};
    double a1[3], a2[3];
    g.direction(X1, a1);
    g.direction(X2, a2);
    const double e1c = std::fabs(a1[0] + 1) + std::fabs(a1[1]);
    const double e2c = std::fabs(a2[0] - 0.5) + std::fabs(a2[1] - std::sqrt(0.75));
    check(e1c < 1e-14 && e2c < 1e-14, "fibres: chord directions of two sectors", e1c + e2c);
  }
  // Bad exponential parameters.
  threw = false;
  try {
    make_material("mooney_rivlin", 8e3, 5e2, 1e7, 1e4, 0);
  } catch (InputError &) {
    threw = true;
  }
  check(threw, "exponential term: c1 > 0 with c2 = 0 rejected", 0);
  // An inverted element is an error, not a NaN.
  double Finv[3][3] = {{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, P[3][3];
  threw = false;
  try {
    make_material("mooney_rivlin", 8e3, 5e2, 1e7)->stress(Finv, P);
  } catch (SolveError &) {
    threw = true;
  }
  check(threw, "mooney_rivlin: det F < 0 raises SolveError", 0);
  threw = false;
  try {
    make_material("svk", 3e5, 0.5);
  } catch (InputError &) {
    threw = true;
  }
  check(threw, "svk: nu = 0.5 rejected", 0);
  std::printf("%d failed\n", failures);
  return failures ? 1 : 0;
}
