#include "fsi/physics/triangle_bins.hpp"

#include <algorithm>
#include <cmath>

namespace fsi {

void TriangleBins::build(const std::vector<double> &x, const std::vector<std::array<int, 3>> &tri,
                         double radius) {
  const int nt = (int)tri.size();
  const auto X = [&](int node) { return &x[3 * node]; };
  double hi[3];
  for (int d = 0; d < 3; ++d) {
    lo_[d] = 1e300;
    hi[d] = -1e300;
  }
  double edge = 0;
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const double *p = X(tri[t][k]), *q = X(tri[t][(k + 1) % 3]);
      edge += std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                        (p[2] - q[2]) * (p[2] - q[2]));
      for (int d = 0; d < 3; ++d) {
        lo_[d] = std::min(lo_[d], p[d] - radius);
        hi[d] = std::max(hi[d], p[d] + radius);
      }
    }
  if (nt == 0) {
    start_.assign(2, 0);
    nb_[0] = nb_[1] = nb_[2] = 1;
    return;
  }
  // Bins of about twice the radius or a mean edge, at most 128 per direction.
  h_ = std::max(2 * radius, edge / (3.0 * nt));
  for (int d = 0; d < 3; ++d) {
    while ((hi[d] - lo_[d]) / h_ > 128)
      h_ *= 2;
  }
  for (int d = 0; d < 3; ++d)
    nb_[d] = std::max(1, (int)std::ceil((hi[d] - lo_[d]) / h_));
  const size_t nbins = (size_t)nb_[0] * nb_[1] * nb_[2];
  std::vector<std::array<int, 6>> range(nt);
  for (int t = 0; t < nt; ++t) {
    for (int d = 0; d < 3; ++d) {
      double a = 1e300, b = -1e300;
      for (int k = 0; k < 3; ++k) {
        a = std::min(a, X(tri[t][k])[d]);
        b = std::max(b, X(tri[t][k])[d]);
      }
      range[t][d] = std::clamp((int)((a - radius - lo_[d]) / h_), 0, nb_[d] - 1);
      range[t][3 + d] = std::clamp((int)((b + radius - lo_[d]) / h_), 0, nb_[d] - 1);
    }
  }
  start_.assign(nbins + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> fill;
    if (pass == 1) {
      for (size_t b = 0; b < nbins; ++b)
        start_[b + 1] += start_[b];
      tri_.resize(start_[nbins]);
      fill.assign(start_.begin(), start_.end() - 1);
    }
    for (int t = 0; t < nt; ++t)
      for (int i = range[t][0]; i <= range[t][3]; ++i)
        for (int j = range[t][1]; j <= range[t][4]; ++j)
          for (int k = range[t][2]; k <= range[t][5]; ++k) {
            const size_t b = ((size_t)k * nb_[1] + j) * nb_[0] + i;
            if (pass == 0)
              start_[b + 1]++;
            else
              tri_[fill[b]++] = t;
          }
  }
}

void TriangleBins::near(const double p[3], const std::function<void(int)> &f) const {
  int c[3];
  for (int d = 0; d < 3; ++d) {
    const double s = (p[d] - lo_[d]) / h_;
    if (s < 0 || s >= nb_[d]) return;
    c[d] = (int)s;
  }
  const size_t b = ((size_t)c[2] * nb_[1] + c[1]) * nb_[0] + c[0];
  for (int i = start_[b]; i < start_[b + 1]; ++i)
    f(tri_[i]);
}

} // namespace fsi
