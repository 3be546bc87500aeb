#include "fsi/physics/contact_geometry.hpp"
#include "fsi/physics/jet.hpp"

#include <cmath>

namespace fsi {

namespace {

double dot3(const double *u, const double *v) {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

using J12 = Jet<12>;

J12 jdot(const J12 *u, const J12 *v) {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

void jsub(const J12 *u, const J12 *v, J12 *r) {
  for (int i = 0; i < 3; ++i)
    r[i] = u[i] - v[i];
}

// Squared distance from p to the line through a and b: |r|^2 - (r.e)^2 / |e|^2.
J12 line_distance2(const J12 *p, const J12 *a, const J12 *b) {
  J12 r[3], e[3];
  jsub(p, a, r);
  jsub(b, a, e);
  const J12 re = jdot(r, e);
  return jdot(r, r) - re * re / jdot(e, e);
}

} // namespace

double point_triangle_distance(const double p[3], const double a[3], const double b[3],
                               const double c[3], TriRegion &region) {
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int i = 0; i < 3; ++i) {
    ab[i] = b[i] - a[i];
    ac[i] = c[i] - a[i];
    ap[i] = p[i] - a[i];
    bp[i] = p[i] - b[i];
    cp[i] = p[i] - c[i];
  }
  const double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
  double q[3];
  auto finish = [&](TriRegion r) {
    region = r;
    const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    return std::sqrt(dx * dx + dy * dy + dz * dz);
  };
  auto point = [&](const double *o, const double *dir, double t) {
    for (int i = 0; i < 3; ++i)
      q[i] = o[i] + t * dir[i];
  };
  if (d1 <= 0 && d2 <= 0) {
    point(a, ab, 0);
    return finish(TriRegion::corner0);
  }
  const double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  if (d3 >= 0 && d4 <= d3) {
    point(b, ab, 0);
    return finish(TriRegion::corner1);
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    point(a, ab, d1 / (d1 - d3));
    return finish(TriRegion::edge01);
  }
  const double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  if (d6 >= 0 && d5 <= d6) {
    point(c, ab, 0);
    return finish(TriRegion::corner2);
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    point(a, ac, d2 / (d2 - d6));
    return finish(TriRegion::edge02);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    double bc[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
    point(b, bc, (d4 - d3) / ((d4 - d3) + (d5 - d6)));
    return finish(TriRegion::edge12);
  }
  const double den = 1 / (va + vb + vc), v = vb * den, w = vc * den;
  for (int i = 0; i < 3; ++i)
    q[i] = a[i] + v * ab[i] + w * ac[i];
  return finish(TriRegion::face);
}

void point_triangle_distance_derivatives(const double p[3], const double a[3], const double b[3],
                                         const double c[3], TriRegion region, double &d,
                                         double g[12], double H[12][12]) {
  J12 x[4][3];
  const double *in[4] = {p, a, b, c};
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i)
      x[k][i] = J12::variable(in[k][i], 3 * k + i);
  J12 d2;
  switch (region) {
  case TriRegion::corner0:
  case TriRegion::corner1:
  case TriRegion::corner2: {
    const int k = 1 + (region == TriRegion::corner1) + 2 * (region == TriRegion::corner2);
    J12 r[3];
    jsub(x[0], x[k], r);
    d2 = jdot(r, r);
    break;
  }
  case TriRegion::edge01:
    d2 = line_distance2(x[0], x[1], x[2]);
    break;
  case TriRegion::edge02:
    d2 = line_distance2(x[0], x[1], x[3]);
    break;
  case TriRegion::edge12:
    d2 = line_distance2(x[0], x[2], x[3]);
    break;
  case TriRegion::face: {
    // (r.n)^2 / |n|^2 with n = (b - a) x (c - a)
    J12 e1[3], e2[3], r[3], n[3];
    jsub(x[2], x[1], e1);
    jsub(x[3], x[1], e2);
    jsub(x[0], x[1], r);
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const J12 rn = jdot(r, n);
    d2 = rn * rn / jdot(n, n);
    break;
  }
  }
  const J12 dist = sqrt(d2);
  d = dist.v;
  for (int i = 0; i < 12; ++i) {
    g[i] = dist.g[i];
    for (int j = 0; j < 12; ++j)
      H[i][j] = dist.h[i][j];
  }
}

double AxisLine::distance(const double p[3], double g[3], double H[3][3]) const {
  double q[3], s = 0;
  for (int i = 0; i < 3; ++i)
    s += (p[i] - point[i]) * dir[i];
  for (int i = 0; i < 3; ++i)
    q[i] = p[i] - point[i] - s * dir[i]; // the component normal to the line
  const double r = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
  if (!g) return r;
  for (int i = 0; i < 3; ++i)
    g[i] = q[i] / r;
  if (H) // (I - e e^T - n n^T) / r: curvature in the plane normal to the line, across n
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        H[i][j] = ((i == j) - dir[i] * dir[j] - g[i] * g[j]) / r;
  return r;
}

} // namespace fsi
