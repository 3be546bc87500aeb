#include "fsi/physics/fibres.hpp"
#include "fsi/common.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace fsi {
namespace {

// F a and the strain measure E = I4 - 1.
double stretch(const double F[3][3], const double a[3], double Fa[3]) {
  for (int i = 0; i < 3; ++i)
    Fa[i] = F[i][0] * a[0] + F[i][1] * a[1] + F[i][2] * a[2];
  return Fa[0] * Fa[0] + Fa[1] * Fa[1] + Fa[2] * Fa[2] - 1.0;
}

} // namespace

std::string FibreFamily::name() const {
  if (!active()) return "";
  char s[120];
  std::snprintf(s, sizeof s, "%s fibres, c1 %g Pa, c2 %g",
                kind == Chord ? "chord" : "circumferential", c1, c2);
  return s;
}

void FibreFamily::direction(const double X[3], double a[3]) const {
  a[0] = a[1] = a[2] = 0;
  const double r = std::hypot(X[0], X[1]);
  if (!(r > 0)) return;
  if (kind == Circumferential) {
    a[0] = -X[1] / r;
    a[1] = X[0] / r;
    return;
  }
  // Chord: the sector [c_j, c_j+1) holding the point's angle; a0 is normal to its bisector.
  const double two_pi = 2 * M_PI;
  double phi = std::atan2(X[1], X[0]);
  if (phi < 0) phi += two_pi;
  const size_t n = commissures.size();
  size_t j = n - 1; // the sector that wraps through 0 unless phi lies between two others
  for (size_t i = 0; i + 1 < n; ++i)
    if (phi >= commissures[i] && phi < commissures[i + 1]) j = i;
  double width = (j + 1 < n ? commissures[j + 1] : commissures[0] + two_pi) - commissures[j];
  const double mid = commissures[j] + 0.5 * width;
  a[0] = -std::sin(mid);
  a[1] = std::cos(mid);
}

double FibreFamily::energy(const double F[3][3], const double a[3]) const {
  double Fa[3];
  const double E = stretch(F, a, Fa);
  return E > 0 || !tension_only ? 0.5 * c1 * (std::exp(c2 * E * E) - 1.0) : 0.0;
}

void FibreFamily::add_stress(const double F[3][3], const double a[3], double P[3][3]) const {
  double Fa[3];
  const double E = stretch(F, a, Fa);
  if (!(E > 0) && tension_only) return;
  const double w1 = c1 * c2 * E * std::exp(c2 * E * E); // dW/dI4
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      P[i][J] += 2 * w1 * Fa[i] * a[J];
}

void FibreFamily::add_tangent(const double F[3][3], const double a[3], double P[3][3],
                              double A[3][3][3][3]) const {
  double Fa[3];
  const double E = stretch(F, a, Fa);
  if (!(E > 0) && tension_only) return;
  const double ex = std::exp(c2 * E * E);
  const double w1 = c1 * c2 * E * ex, w2 = c1 * c2 * ex * (1 + 2 * c2 * E * E); // W', W''
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J) {
      P[i][J] += 2 * w1 * Fa[i] * a[J];
      const double g = 4 * w2 * Fa[i] * a[J];
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L)
          A[i][J][k][L] += g * Fa[k] * a[L] + (i == k ? 2 * w1 * a[J] * a[L] : 0.0);
    }
}

FibreFamily FibreFamily::from_options(const std::string &material_kind) {
  FibreFamily f;
  const std::string kind =
      opt::choice("solid_fibres", "none", {"none", "circumferential", "chord"});
  if (kind == "none") {
    for (const char *name : {"solid_fibre_c1", "solid_fibre_c2", "solid_fibre_commissures",
                             "solid_fibre_tension_only"})
      if (opt::has(name))
        throw InputError(std::string("option -") + name +
                         " needs -solid_fibres circumferential or chord");
    return f;
  }
  if (material_kind == "linear" || material_kind == "svk")
    throw InputError("option -solid_fibres needs -solid_material neo_hookean or mooney_rivlin, "
                     "not " +
                     material_kind);
  f.kind = kind == "chord" ? Chord : Circumferential;
  f.c1 = opt::required_positive("solid_fibre_c1");
  f.c2 = opt::required_positive("solid_fibre_c2");
  f.tension_only = opt::flag("solid_fibre_tension_only", true);
  if (f.kind == Chord) {
    if (!opt::has("solid_fibre_commissures"))
      throw InputError("option -solid_fibres chord needs -solid_fibre_commissures a1,a2,... "
                       "[deg]: the commissures' angles about the z axis, e.g. 30,150,270");
    for (double deg : opt::reals("solid_fibre_commissures")) {
      double r = std::fmod(deg * M_PI / 180, 2 * M_PI);
      f.commissures.push_back(r < 0 ? r + 2 * M_PI : r);
    }
    std::sort(f.commissures.begin(), f.commissures.end());
    if (f.commissures.size() < 2 ||
        std::adjacent_find(f.commissures.begin(), f.commissures.end()) != f.commissures.end())
      throw InputError("option -solid_fibre_commissures needs at least two distinct angles [deg]");
  }
  return f;
}

} // namespace fsi
