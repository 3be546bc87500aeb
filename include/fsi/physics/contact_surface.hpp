// The solid's contact surface, gathered on every rank: the P2 nodes of the solid faces of one
// boundary group (e.g. the leaflets' wetted "interface"), each P2 face split into 4 flat
// triangles through its nodes, grouped into connected pieces (one per leaflet).  Every rank holds
// the whole surface (a few thousand nodes for a valve) so that pairs across ranks need no
// ghosting: each rank searches all of it and adds only the rows it owns.  Positions follow the
// solid displacement at t_{n+alpha_f}; update() is collective.
#pragma once
#include "fsi/discretization/space.hpp"
#include "fsi/physics/triangle_bins.hpp"
#include "fsi/time/step_context.hpp"
#include <array>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

namespace fsi {

class ContactSurface {
public:
  ContactSurface(const Space &space, const Mesh &mesh, const std::string &group,
                 const std::vector<PetscInt> &solid_cells, const std::vector<double> &material_X);
  // Node positions at t_{n+alpha_f} from the context's iterate and history (collective).
  void update(const StepContext &ctx);

  int n_nodes() const { return (int)gdof_.size(); }
  int n_triangles() const { return (int)tri_.size(); }
  int n_components() const { return n_components_; }
  const double *x(int node) const { return &x_[3 * node]; }
  int component(int node) const { return comp_[node]; }
  double area(int node) const { return area_[node]; }               // lumped reference area [m^2]
  PetscInt global_dof(int node) const { return gdof_[node]; }       // x component
  PetscInt owned_local_dof(int node) const { return owned_[node]; } // -1 where not owned here
  const std::array<int, 3> &triangle(int t) const { return tri_[t]; }
  int triangle_component(int t) const { return comp_[tri_[t][0]]; }
  // Calls f(t) for every triangle whose box, grown by `radius`, holds p (after bin(radius)).
  void bin(double radius);
  void near(const double p[3], const std::function<void(int)> &f) const;
  MPI_Comm comm() const { return comm_; }

private:
  const Space &space_;
  const std::vector<double> &material_X_;
  // This rank's surface nodes: local velocity dof and the local vertices they sit on.
  std::vector<PetscInt> my_vdof_;
  std::vector<std::array<int, 2>> my_vertices_; // edge node: both ends; vertex node: [v, -1]
  std::vector<int> my_index_;                   // into the gathered node list
  std::vector<PetscInt> gdof_, owned_;
  std::vector<int> comp_, counts_, displs_;
  std::vector<double> x_, area_;
  std::vector<std::array<int, 3>> tri_;
  int n_components_ = 0;
  MPI_Comm comm_;
  TriangleBins bins_;
};

} // namespace fsi
