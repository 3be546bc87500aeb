// The contact gap: point-to-triangle distance against a brute-force closest point, and its
// gradient and Hessian (Jet automatic differentiation) against central differences, in every
// region of the closest point (face, 3 edges, 3 corners); plus the contact pressure ramp
// (continuous, slope = its derivative) and the axis rod's distance with its derivatives.  Bounds:
// relative 1e-6 for derivatives.
#include "fsi/common.hpp"
#include "fsi/physics/contact.hpp"
#include "fsi/physics/contact_geometry.hpp"

#include <cmath>
#include <cstdio>
#include <random>

using namespace fsi;

static int failures = 0;
static void check(bool ok, const char *what, double v) {
  std::printf("%s: %s (%.2e)\n", ok ? "PASS" : "FAIL", what, v);
  if (!ok) ++failures;
}

// Closest point by sampling barycentric coordinates finely, then refining: a slow reference.
static double brute_distance(const double *p, const double *a, const double *b, const double *c) {
  double best = 1e300;
  const int n = 400;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const double u = (double)i / n, v = (double)j / n, w = 1 - u - v;
      double d2 = 0;
      for (int k = 0; k < 3; ++k) {
        const double q = w * a[k] + u * b[k] + v * c[k];
        d2 += (p[k] - q) * (p[k] - q);
      }
      best = std::min(best, std::sqrt(d2));
    }
  return best;
}

int main() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int seen[7] = {};
  double worst_d = 0, worst_g = 0, worst_h = 0;
  for (int trial = 0; trial < 400; ++trial) {
    double x[12];
    for (double &v : x)
      v = u(rng);
    for (int k = 0; k < 3; ++k) // the point somewhat off the triangle's plane
      x[k] *= 1.5;
    TriRegion r;
    const double d = point_triangle_distance(x, x + 3, x + 6, x + 9, r);
    if (d < 0.05) continue;
    seen[(int)r]++;
    if (trial < 60)
      worst_d = std::max(worst_d, std::fabs(d - brute_distance(x, x + 3, x + 6, x + 9)));
    double dd, g[12], H[12][12];
    point_triangle_distance_derivatives(x, x + 3, x + 6, x + 9, r, dd, g, H);
    worst_d = std::max(worst_d, std::fabs(dd - d) / d);
    const double h = 1e-6;
    for (int i = 0; i < 12; ++i) {
      double xp[12], xm[12];
      std::copy(x, x + 12, xp);
      std::copy(x, x + 12, xm);
      xp[i] += h;
      xm[i] -= h;
      TriRegion rp, rm;
      const double dp = point_triangle_distance(xp, xp + 3, xp + 6, xp + 9, rp);
      const double dm = point_triangle_distance(xm, xm + 3, xm + 6, xm + 9, rm);
      if (rp != r || rm != r) continue; // on a region boundary: the Hessian jumps there
      worst_g = std::max(worst_g, std::fabs((dp - dm) / (2 * h) - g[i]));
      double gp[12], gm[12], Hs[12][12], dd2;
      point_triangle_distance_derivatives(xp, xp + 3, xp + 6, xp + 9, r, dd2, gp, Hs);
      point_triangle_distance_derivatives(xm, xm + 3, xm + 6, xm + 9, r, dd2, gm, Hs);
      for (int j = 0; j < 12; ++j)
        worst_h = std::max(worst_h, std::fabs((gp[j] - gm[j]) / (2 * h) - H[j][i]));
    }
  }
  int regions = 0;
  for (int k = 0; k < 7; ++k)
    regions += seen[k] > 0;
  check(regions == 7, "every closest-point region met (face, 3 edges, 3 corners)", regions);
  check(worst_d < 2e-2, "distance = brute-force closest point (grid 1/400)", worst_d);
  check(worst_g < 1e-6, "gradient = central differences", worst_g);
  check(worst_h < 1e-5, "Hessian = central differences of the gradient", worst_h);

  ContactParams p;
  p.offset = 1e-3;
  p.ramp = 2.5e-4;
  p.penalty = 1e8;
  double jump = std::fabs(p.pressure(p.ramp * (1 + 1e-12)) - p.pressure(p.ramp * (1 - 1e-12)));
  check(jump < 1e-6 && p.pressure(0) == 0 && p.pressure(-1e-4) == 0,
        "contact pressure continuous, zero without penetration", jump);
  double worst_s = 0;
  for (double pen : {1e-5, 1e-4, 2e-4, 3e-4, 8e-4}) {
    const double e = 1e-9;
    worst_s = std::max(worst_s, std::fabs((p.pressure(pen + e) - p.pressure(pen - e)) / (2 * e) -
                                          p.pressure_slope(pen)) /
                                    p.penalty);
  }
  check(worst_s < 1e-6, "contact pressure slope = its derivative", worst_s);

  // The axis rod's distance: a tilted line through an off-origin point, against the cross
  // product formula and samples along the line, and its derivatives against central
  // differences.
  AxisLine ax;
  const double e[3] = {0.3, -0.5, 0.8}, en = std::sqrt(0.09 + 0.25 + 0.64);
  for (int i = 0; i < 3; ++i) {
    ax.point[i] = 0.1 * (i + 1);
    ax.dir[i] = e[i] / en;
  }
  double worst_ad = 0, worst_ag = 0, worst_ah = 0;
  for (int trial = 0; trial < 50; ++trial) {
    double x[3];
    for (double &v : x)
      v = u(rng);
    double g[3], H[3][3];
    const double r = ax.distance(x, g, H);
    // Independent references: |(x - a) x e| (the parallelogram's height), and no point of the
    // line near the closest one is closer (samples every 1e-2 along it).
    const double a[3] = {x[0] - ax.point[0], x[1] - ax.point[1], x[2] - ax.point[2]};
    const double *d = ax.dir;
    const double cx = a[1] * d[2] - a[2] * d[1], cy = a[2] * d[0] - a[0] * d[2],
                 cz = a[0] * d[1] - a[1] * d[0];
    const double s = a[0] * d[0] + a[1] * d[1] + a[2] * d[2];
    double far = 1e300;
    for (int k = -50; k <= 50; ++k) {
      double d2 = 0;
      for (int i = 0; i < 3; ++i)
        d2 += std::pow(a[i] - (s + 1e-2 * k) * d[i], 2);
      far = std::min(far, std::sqrt(d2));
    }
    worst_ad = std::max({worst_ad, std::fabs(r - std::sqrt(cx * cx + cy * cy + cz * cz)), r - far});
    const double h = 1e-6;
    for (int j = 0; j < 3; ++j) {
      double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]}, gp[3], gm[3];
      xp[j] += h;
      xm[j] -= h;
      const double rp = ax.distance(xp, gp), rm = ax.distance(xm, gm);
      worst_ag = std::max(worst_ag, std::fabs((rp - rm) / (2 * h) - g[j]));
      for (int i = 0; i < 3; ++i)
        worst_ah = std::max(worst_ah, std::fabs((gp[i] - gm[i]) / (2 * h) - H[i][j]));
    }
  }
  check(worst_ad < 1e-12, "axis distance = |(x - a) x e|, no sample of the line closer", worst_ad);
  check(worst_ag < 1e-6, "axis distance gradient = central differences", worst_ag);
  check(worst_ah < 1e-5, "axis distance Hessian = central differences", worst_ah);
  return failures ? 1 : 0;
}
