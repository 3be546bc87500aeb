// Second-order forward automatic differentiation in N variables: a Jet carries a value, its
// gradient and its Hessian, so that a smooth function written once gives the exact derivatives a
// consistent Newton tangent needs (the contact gap, contact_geometry.hpp).  Small and dense: use
// it for a few variables (N = 12 for a point and a triangle).
#pragma once
#include <cmath>

namespace fsi {

template <int N> struct Jet {
  double v = 0, g[N] = {}, h[N][N] = {};

  static Jet variable(double value, int i) {
    Jet j;
    j.v = value;
    j.g[i] = 1;
    return j;
  }
  static Jet constant(double value) {
    Jet j;
    j.v = value;
    return j;
  }
};

// f(a) for a scalar function with derivatives f1 = f'(a.v), f2 = f''(a.v).
template <int N> Jet<N> chain(const Jet<N> &a, double f0, double f1, double f2) {
  Jet<N> r;
  r.v = f0;
  for (int i = 0; i < N; ++i) {
    r.g[i] = f1 * a.g[i];
    for (int j = 0; j < N; ++j)
      r.h[i][j] = f1 * a.h[i][j] + f2 * a.g[i] * a.g[j];
  }
  return r;
}

template <int N> Jet<N> operator+(const Jet<N> &a, const Jet<N> &b) {
  Jet<N> r;
  r.v = a.v + b.v;
  for (int i = 0; i < N; ++i) {
    r.g[i] = a.g[i] + b.g[i];
    for (int j = 0; j < N; ++j)
      r.h[i][j] = a.h[i][j] + b.h[i][j];
  }
  return r;
}

template <int N> Jet<N> operator-(const Jet<N> &a, const Jet<N> &b) {
  Jet<N> r;
  r.v = a.v - b.v;
  for (int i = 0; i < N; ++i) {
    r.g[i] = a.g[i] - b.g[i];
    for (int j = 0; j < N; ++j)
      r.h[i][j] = a.h[i][j] - b.h[i][j];
  }
  return r;
}

template <int N> Jet<N> operator*(const Jet<N> &a, const Jet<N> &b) {
  Jet<N> r;
  r.v = a.v * b.v;
  for (int i = 0; i < N; ++i) {
    r.g[i] = a.v * b.g[i] + b.v * a.g[i];
    for (int j = 0; j < N; ++j)
      r.h[i][j] = a.v * b.h[i][j] + b.v * a.h[i][j] + a.g[i] * b.g[j] + b.g[i] * a.g[j];
  }
  return r;
}

template <int N> Jet<N> operator*(double s, const Jet<N> &a) {
  Jet<N> r;
  r.v = s * a.v;
  for (int i = 0; i < N; ++i) {
    r.g[i] = s * a.g[i];
    for (int j = 0; j < N; ++j)
      r.h[i][j] = s * a.h[i][j];
  }
  return r;
}

template <int N> Jet<N> inverse(const Jet<N> &a) {
  const double i = 1 / a.v;
  return chain(a, i, -i * i, 2 * i * i * i);
}

template <int N> Jet<N> operator/(const Jet<N> &a, const Jet<N> &b) {
  return a * inverse(b);
}

template <int N> Jet<N> sqrt(const Jet<N> &a) {
  const double s = std::sqrt(a.v);
  return chain(a, s, 0.5 / s, -0.25 / (s * a.v));
}

} // namespace fsi
