// Internals of remeshing (remesh.hpp), shared by its files: the gathered mesh (remesh_gather),
// gmsh (remesh_gmsh), the state transfer (remesh_transfer) and the driver (remesh.cpp).  All
// but the gather run on rank 0.  Vertices are indices into the old state's vertex items.
#pragma once
#include "fsi/ale/remesh.hpp"
#include "fsi/io/h5.hpp"
#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <vector>

namespace fsi::remeshing {

using Tri = std::array<int, 3>;
using Tet = std::array<int, 4>;
using Point = std::array<double, 3>;
constexpr int TET_FACE[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}}; // face i: not vertex i

inline Tri sorted(int a, int b, int c) {
  Tri t{a, b, c};
  std::sort(t.begin(), t.end());
  return t;
}

// Physical groups of the mesh (user labels, not PETSc's own): name and dimension (3 or 2).
struct Groups {
  std::vector<std::string> names;
  std::vector<int> dim;
};
Groups mesh_groups(const Mesh &mesh); // collective

// The whole mesh on rank 0: cells (vertex reference coordinates, fluid flag and group mask) and
// the faces of surface groups (vertex coordinates, group mask).
struct Gathered {
  KeyedItems cells; // key: 12 coordinates; value: fluid (0/1), group mask
  KeyedItems faces; // key: 9 coordinates; value: group mask
};
Gathered gather_mesh(const Mesh &mesh, const Space &space, const std::vector<PetscInt> &fluid_cells,
                     const Groups &g); // collective

// The old mesh on rank 0: reference and current vertex positions, cells, labelled faces.
struct OldMesh {
  std::vector<Point> Xref, x;
  std::vector<Tet> cells, fluid_cells;
  std::vector<char> fluid;
  std::vector<double> cell_mask;
  std::map<Tri, double> face_mask;
};

// The new mesh: kept old vertices first (old_of), then gmsh's; fluid cells first.
struct NewMesh {
  std::vector<Point> y;
  std::vector<Tet> cells;
  size_t n_fluid = 0, n_kept = 0;
  std::vector<int> old_of;    // per kept new vertex
  std::vector<int> new_index; // per old vertex, -1 if dropped
  std::vector<char> in_solid; // per old vertex
};

// gmsh: the fluid volume inside the boundary triangles (node k at x[k]; new nodes appended to
// x), then the sliver removal; inward: unit normal into the fluid per triangle; records gap
// vertices, gmsh's worst cell and the flips in rep.  Throws RemeshError.
std::vector<Tet> mesh_volume(std::vector<Point> &x, const std::vector<Tri> &tris,
                             const std::vector<double> &mask, const std::vector<Point> &inward,
                             const RemeshOptions &o, RemeshReport &rep);
// Local flips (edge removal, 2-3 face flips) and, where no flip helps, interior edge splits (a
// new vertex appended to x) on the cells of skewness above `threshold`: boundary triangles stay,
// each move raises the worst quality it touches.  New cells have positive orientation
// (remesh_flips.cpp).
struct FlipReport {
  long flips = 0, splits = 0; // flips and edge splits (new vertices)
  long moves = 0;             // interior vertices moved
};
FlipReport remove_slivers(std::vector<Point> &x, std::vector<Tet> &tets, double threshold);
// A gmsh 2.2 ASCII mesh (exact coordinates with 17 digits), written atomically.
void write_msh(const std::string &path, const std::vector<Point> &x, const std::vector<Tet> &tets,
               const std::vector<double> &tet_mask, const std::vector<Tri> &tris,
               const std::vector<double> &tri_mask, const Groups &g);
double skewness_of(const std::vector<Point> &x, const Tet &t);

// The dof values of a node with ALE reference position X from the state: out[3 h + c] for
// component c of history h (V, A, D).  False if the state has no such node.
bool node_values(const KeyedItems &dofs, const double X[3], double out[9]);

// The state on the new mesh, and the report's measures (skewness, volume, kinetic energy,
// divergence before and after).
RunState transfer_state(const OldMesh &om, const NewMesh &nm, const RunState &old,
                        RemeshReport &rep);

} // namespace fsi::remeshing
