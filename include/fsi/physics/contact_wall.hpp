// Rigid walls as contact obstacles for the solid's contact surface: the fluid faces of boundary
// groups that never move (the aortic root), gathered on every rank once per mesh.  An opening
// leaflet bulges towards its sinus wall; without a wall contact nothing stops it but the fluid
// cells between them, which collapse.  Each surface node farther than `exclude` from the walls
// in the reference configuration (not the nodes along the leaflet's attachment, which sit on
// the wall) is repelled by its nearest wall triangle when closer than the wall offset.
#pragma once
#include "fsi/discretization/space.hpp"
#include "fsi/physics/contact_geometry.hpp"
#include "fsi/physics/triangle_bins.hpp"
#include <array>
#include <string>
#include <vector>

namespace fsi {

class ContactWall {
public:
  // Faces of `groups` on the side of `fluid_cells`; queries up to `radius` from the walls.
  ContactWall(const Space &space, const Mesh &mesh, const std::vector<std::string> &groups,
              const std::vector<PetscInt> &fluid_cells, double radius);
  int n_triangles() const { return (int)tri_.size(); }
  const double *corner(int t, int k) const { return &x_[3 * tri_[t][k]]; }
  // Nearest wall triangle to p within the radius: its distance (radius and t = -1 if none).
  double nearest(const double p[3], int &t, TriRegion &region) const;
  double radius() const { return radius_; }

private:
  std::vector<double> x_;
  std::vector<std::array<int, 3>> tri_;
  TriangleBins bins_;
  double radius_;
};

} // namespace fsi
