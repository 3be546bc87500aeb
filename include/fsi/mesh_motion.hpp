// Mesh motion (ALE): the fluid mesh displacement d_m at the vertices, as a function of time.
// The fluid sees the configuration X + d_m at t_{n+alpha_f} and the mesh velocity
// w = (d_m^{n+1} - d_m^n) / dt, which makes a uniform flow stay uniform on any mesh motion
// (discrete geometric conservation for affine tetrahedra).  Options: -ale_motion none|prescribed.
//   prescribed: d_m = A (t / T) b(X) (1, 1, 1), b a bubble vanishing on the bounding box
//   (-ale_amplitude A [m], -ale_time T [s]); used to verify the ALE terms.
// Later: Laplace / Jacobian-stiffened smoothing driven by the solid displacement.
#pragma once
#include "fsi/space.hpp"
#include <memory>
#include <string>
#include <vector>

namespace fsi {

struct MeshMotion {
  virtual ~MeshMotion() = default;
  virtual std::string name() const = 0;
  // Vertex displacement at time t, 3 per local vertex.
  virtual void displacement(double t, std::vector<double> &d) const = 0;
};

std::unique_ptr<MeshMotion> make_mesh_motion(const Space &space);

} // namespace fsi
