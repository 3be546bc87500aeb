// Finding a point of the reference mesh: the cell among `cells` (local indices) that contains
// x and its barycentric coordinates, agreed over all ranks (the lowest rank holding it owns it).
#pragma once
#include "fsi/discretization/space.hpp"

namespace fsi {

struct PointLocation {
  int owner = -1;        // rank that holds the point; -1 if no rank does
  PetscInt cell = -1;    // local cell index on the owner
  double lambda[4] = {}; // barycentric coordinates in that cell
};

// X: the vertex coordinates to search on (3 per local vertex; default the mesh's, Space::X).
PointLocation locate_point(const Space &space, const std::vector<PetscInt> &cells,
                           const double x[3], const double *X = nullptr);

// Parse "x,y,z;x,y,z;..." (option `name`) into points.
std::vector<std::array<double, 3>> parse_points(const std::string &name);

} // namespace fsi
