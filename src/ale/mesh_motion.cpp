#include "fsi/ale/mesh_motion.hpp"
#include "fsi/discretization/p2tet.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <cmath>

namespace fsi {

std::unique_ptr<MeshMotion> make_laplace_motion(const Mesh &mesh, const Space &space,
                                                const std::vector<PetscInt> &fluid_cells,
                                                const std::vector<double> &material_X);

namespace {

struct PrescribedBubble : MeshMotion {
  const Space &space;
  double A, T, lo[3], hi[3];
  PrescribedBubble(const Space &s, double A_, double T_) : space(s), A(A_), T(T_) {
    double l[3] = {1e300, 1e300, 1e300}, h[3] = {-1e300, -1e300, -1e300};
    for (PetscInt v = 0; v < s.n_vertices(); ++v)
      for (int d = 0; d < 3; ++d) {
        l[d] = std::min(l[d], s.X[3 * v + d]);
        h[d] = std::max(h[d], s.X[3 * v + d]);
      }
    MPI_Comm comm = PetscObjectComm((PetscObject)s.dm);
    MPI_Allreduce(l, lo, 3, MPI_DOUBLE, MPI_MIN, comm);
    MPI_Allreduce(h, hi, 3, MPI_DOUBLE, MPI_MAX, comm);
  }
  std::string name() const override { return "prescribed bubble"; }
  void displacement(double t, const PetscScalar *, std::vector<double> &d) override {
    d.assign(3 * space.n_vertices(), 0.0);
    for (PetscInt v = 0; v < space.n_vertices(); ++v) {
      double b = 1;
      for (int k = 0; k < 3; ++k) {
        double xi = 2 * (space.X[3 * v + k] - lo[k]) / (hi[k] - lo[k]) - 1;
        b *= 1 - xi * xi;
      }
      for (int k = 0; k < 3; ++k)
        d[3 * v + k] = A * (t / T) * b;
    }
  }
};

} // namespace

std::unique_ptr<MeshMotion> make_mesh_motion(const Mesh &mesh, const Space &space,
                                             const std::vector<PetscInt> *fluid_cells,
                                             const std::vector<double> &material_X) {
  const std::string kind = opt::choice("ale_motion", "none", {"none", "prescribed", "laplace"});
  if (kind == "prescribed")
    return std::make_unique<PrescribedBubble>(space, opt::real("ale_amplitude", 0.1),
                                              opt::positive("ale_time", 1.0));
  if (kind == "laplace") {
    if (!fluid_cells) throw InputError("-ale_motion laplace needs a fluid in the scene");
    return make_laplace_motion(mesh, space, *fluid_cells, material_X);
  }
  return nullptr;
}

double tet_skewness(const double P[4][3]) {
  double a[3], b[3], c[3];
  for (int d = 0; d < 3; ++d)
    a[d] = P[1][d] - P[0][d], b[d] = P[2][d] - P[0][d], c[d] = P[3][d] - P[0][d];
  double bc[3], ca[3], ab[3], s[3];
  cross(b, c, bc);
  cross(c, a, ca);
  cross(a, b, ab);
  const double V = std::fabs(a[0] * bc[0] + a[1] * bc[1] + a[2] * bc[2]) / 6;
  if (V <= 0) return 1.0;
  // circumradius: |a^2 (b x c) + b^2 (c x a) + c^2 (a x b)| / (12 V)
  const double a2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2],
               b2 = b[0] * b[0] + b[1] * b[1] + b[2] * b[2],
               c2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
  for (int d = 0; d < 3; ++d)
    s[d] = a2 * bc[d] + b2 * ca[d] + c2 * ab[d];
  const double R = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) / (12 * V);
  const double Vreg = 8 * std::sqrt(3.0) / 27 * R * R * R;
  return std::min(1.0, std::max(0.0, 1 - V / Vreg));
}

static double signed_volume(const double Q[4][3]) {
  double a[3], b[3], c[3];
  for (int d = 0; d < 3; ++d)
    a[d] = Q[1][d] - Q[0][d], b[d] = Q[2][d] - Q[0][d], c[d] = Q[3][d] - Q[0][d];
  return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
          a[2] * (b[0] * c[1] - b[1] * c[0])) /
         6.0;
}

namespace {
struct ValueRank {
  double value;
  int rank;
};
// The largest v over all ranks and the point x (3) of the rank that has it.
double max_with_point(double v, double x[3], MPI_Comm comm) {
  ValueRank mine = {v, 0}, worst;
  MPI_Comm_rank(comm, &mine.rank);
  MPI_Allreduce(&mine, &worst, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm);
  MPI_Bcast(x, 3, MPI_DOUBLE, worst.rank, comm);
  return worst.value;
}
} // namespace

MeshQuality mesh_quality(const Space &space, const std::vector<PetscInt> &cells,
                         const std::vector<double> &X, const std::vector<double> *skewness0,
                         const std::vector<char> *exempt) {
  double jmin = 1e300, smax = 0, sdeg = 0, sopen = 0, at[3] = {0, 0, 0}, atdeg[3] = {0, 0, 0},
         atopen[3] = {0, 0, 0};
  for (size_t i = 0; i < cells.size(); ++i) {
    const PetscInt k = cells[i];
    double P[4][3], P0[4][3];
    space.cell_points(k, X.data(), P);
    space.cell_points(k, space.X.data(), P0);
    const double Vs = signed_volume(P), V0 = signed_volume(P0);
    double c[3];
    for (int d = 0; d < 3; ++d)
      c[d] = 0.25 * (P[0][d] + P[1][d] + P[2][d] + P[3][d]);
    if (Vs / V0 < jmin) { // the vertex order may be negatively oriented: compare signs
      jmin = Vs / V0;
      std::copy(c, c + 3, at);
    }
    const double s = Vs / V0 <= 0 ? 1.0 : tet_skewness(P);
    smax = std::max(smax, s);
    // Degraded: its quality 1 - s at most half of what it was in the reference mesh.
    if (!skewness0 || 1 - s > 0.5 * (1 - (*skewness0)[i])) continue;
    if (s > sdeg) {
      sdeg = s;
      std::copy(c, c + 3, atdeg);
    }
    if (s > sopen && !(exempt && (*exempt)[i])) {
      sopen = s;
      std::copy(c, c + 3, atopen);
    }
  }
  MeshQuality q;
  MPI_Comm comm = PetscObjectComm((PetscObject)space.dm);
  q.min_jacobian = -max_with_point(-jmin, at, comm);
  std::copy(at, at + 3, q.where);
  MPI_Allreduce(&smax, &q.max_skewness, 1, MPI_DOUBLE, MPI_MAX, comm);
  q.max_degraded_skewness = max_with_point(sdeg, atdeg, comm);
  std::copy(atdeg, atdeg + 3, q.where_degraded);
  if (exempt) { // else the same cell as above: no second reduction on this per-step path
    q.max_degraded_open = max_with_point(sopen, atopen, comm);
    std::copy(atopen, atopen + 3, q.where_degraded_open);
  } else {
    q.max_degraded_open = q.max_degraded_skewness;
    std::copy(q.where_degraded, q.where_degraded + 3, q.where_degraded_open);
  }
  return q;
}

} // namespace fsi
