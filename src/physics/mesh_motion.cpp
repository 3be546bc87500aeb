#include "fsi/mesh_motion.hpp"
#include "fsi/options.hpp"

#include <algorithm>

namespace fsi {
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
  void displacement(double t, std::vector<double> &d) const override {
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

std::unique_ptr<MeshMotion> make_mesh_motion(const Space &space) {
  const std::string kind = opt::choice("ale_motion", "none", {"none", "prescribed"});
  if (kind == "prescribed")
    return std::make_unique<PrescribedBubble>(space, opt::real("ale_amplitude", 0.1),
                                              opt::positive("ale_time", 1.0));
  return nullptr;
}

} // namespace fsi
