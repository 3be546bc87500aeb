#include "fsi/physics/contact_wall.hpp"
#include "fsi/mpi_gather.hpp"

namespace fsi {

ContactWall::ContactWall(const Space &space, const Mesh &mesh,
                         const std::vector<std::string> &groups,
                         const std::vector<PetscInt> &fluid_cells, double radius)
    : radius_(radius) {
  MPI_Comm comm = PetscObjectComm((PetscObject)space.dm);
  std::vector<char> in_fluid(space.n_cells(), 0);
  for (PetscInt k : fluid_cells)
    in_fluid[k] = 1;
  // The walls are rigid: their faces' corners, flat triangles (a P2 face of a straight-sided
  // tetrahedron is flat), 9 numbers per face from every rank.
  std::vector<double> mine;
  for (const std::string &g : groups)
    for (const BoundaryFace &f : space.boundary_faces(mesh, g, &in_fluid))
      for (int k = 0; k < 3; ++k)
        for (int d = 0; d < 3; ++d)
          mine.push_back(space.X[3 * f.vertex[k] + d]);
  x_ = all_gather(comm, mine, MPI_DOUBLE);
  for (int t = 0; t < (int)x_.size() / 9; ++t)
    tri_.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  bins_.build(x_, tri_, radius);
}

double ContactWall::nearest(const double p[3], int &t, TriRegion &region) const {
  double best = radius_;
  t = -1;
  bins_.near(p, [&](int s) {
    TriRegion r;
    const double d = point_triangle_distance(p, corner(s, 0), corner(s, 1), corner(s, 2), r);
    if (d < best) {
      best = d;
      t = s;
      region = r;
    }
  });
  return best;
}

} // namespace fsi
