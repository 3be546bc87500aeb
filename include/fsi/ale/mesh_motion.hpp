// Mesh motion (ALE): the fluid mesh displacement d_m at the vertices at a time level.  The fluid
// sees the configuration X + d_m at t_{n+alpha_f} and the mesh velocity
// w = (d_m^{n+1} - d_m^n) / dt, which makes a uniform flow stay uniform on any mesh motion
// (discrete geometric conservation for affine tetrahedra).  -ale_motion none|prescribed|laplace:
//   prescribed: d_m = A (t / T) b(X) (1, 1, 1), b a bubble vanishing on the bounding box
//     (-ale_amplitude A [m], -ale_time T [s]); verifies the ALE terms.
//   laplace: div(k grad d_m) = 0 in the fluid (P1, each component), d_m = the solid displacement
//     on every vertex of a solid cell (so the interface follows the solid and the whole mesh is
//     the deformed configuration), d_m = 0 on the other exterior boundaries except the normal
//     component only on -ale_slip_boundaries a,b (planar, axis-aligned: inlet/outlet planes);
//     k = (V_max / V_e)^chi with -ale_stiffening chi (default 0: plain Laplace; 1: small cells
//     stiffer, the Jacobian-stiffened variant for large deformation).  Linear solver prefix
//     -ale_ (default CG + GAMG, rtol 1e-10).
#pragma once
#include "fsi/discretization/space.hpp"
#include "fsi/mesh/mesh.hpp"
#include <memory>
#include <string>
#include <vector>

namespace fsi {

struct MeshMotion {
  virtual ~MeshMotion() = default;
  virtual std::string name() const = 0;
  // Does the motion follow the solid (then `solid` below must be given)?
  virtual bool follows_solid() const { return false; }
  // Vertex displacement at time t, 3 per local vertex.  solid: the solid displacement at t as a
  // local array in the velocity layout (nullptr when the motion does not follow the solid).
  virtual void displacement(double t, const PetscScalar *solid, std::vector<double> &d) = 0;
  // Initial guess of an iterative motion solve (3 per local vertex); ignored by direct motions.
  virtual void set_guess(const std::vector<double> &d) {}
};

// fluid_cells: local cells of the fluid (nullptr without a fluid).
// material_X: the solid's material reference per local vertex (the solid displacement moves
// solid vertices from there; after a remesh it differs from the ALE reference Space::X).
std::unique_ptr<MeshMotion> make_mesh_motion(const Mesh &mesh, const Space &space,
                                             const std::vector<PetscInt> *fluid_cells,
                                             const std::vector<double> &material_X);

// Quality of the fluid cells on vertex coordinates X: the smallest ratio of deformed to
// reference volume (<= 0: inverted) and the largest volume skewness 1 - V / V_regular(R)
// (R the circumradius; 0 regular, 1 degenerate), over all ranks.
struct MeshQuality {
  double min_jacobian = 1, max_skewness = 0;
  // The worst skewness among cells whose quality 1 - s has at least halved against the
  // reference mesh (given its per-cell skewness): what remeshing can cure.  A mesh generator's
  // slivers that stay as bad as they were do not count.
  double max_degraded_skewness = 0;
  double where_degraded[3] = {0, 0, 0}; // centre of the cell of max_degraded_skewness
  // The same without the exempt cells (all cells when none are): what asks for a remesh.
  double max_degraded_open = 0;
  double where_degraded_open[3] = {0, 0, 0};
  double where[3] = {0, 0, 0}; // centre of the cell with the smallest volume ratio (the one the
                               // motion crushes most)
};
// exempt (per cell, optional): cells left out of max_degraded_open.
MeshQuality mesh_quality(const Space &space, const std::vector<PetscInt> &cells,
                         const std::vector<double> &X,
                         const std::vector<double> *skewness0 = nullptr,
                         const std::vector<char> *exempt = nullptr);
// Volume skewness of one tetrahedron (0 regular, 1 degenerate).
double tet_skewness(const double P[4][3]);

} // namespace fsi
