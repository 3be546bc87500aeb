// The discrete space: P2 velocity (vertices + edges, 3 components) and P1 pressure (vertices) on
// the whole DMPlex, in one PetscSection with fields "velocity" and "pressure".  Element kernels
// never call DMPlex in their loops: this class precomputes, per local cell, the local dof indices
// of its 10 velocity nodes and 4 pressure nodes in our node order (see p2tet.hpp), and the
// reference vertex coordinates.  Boundary faces and Dirichlet nodes are listed by boundary name.
#pragma once
#include "fsi/mesh/mesh.hpp"
#include <array>
#include <map>
#include <string>
#include <vector>

namespace fsi {

struct BoundaryFace {
  PetscInt cell;    // local cell index (0-based among cells)
  int vertex[3];    // local vertex indices of the face, in P2 triangle node order
  int opposite;     // local vertex index of the cell vertex not on the face
  PetscInt vdof[6]; // first local velocity dof of the 6 face nodes (3 vertices, 3 edges)
  PetscInt pdof[3]; // local pressure dofs of the face vertices
};

// Outward unit normal n of a boundary face on vertex coordinates X (3 per local vertex), oriented
// away from the cell's opposite vertex; returns |cross product| = 2 * area.
double outward_normal(const BoundaryFace &f, const double *X, double n[3]);

struct DofNode {
  PetscInt dof; // first local dof (velocity: x component; pressure: the dof)
  int va, vb;   // local vertex indices; vb = -1 for a vertex node, else edge midpoint
};

struct Space {
  DM dm = nullptr; // the mesh DM, carrying our section
  PetscInt cStart = 0, cEnd = 0, vStart = 0, vEnd = 0, eStart = 0, eEnd = 0;
  PetscInt n_local = 0;                    // local (ghosted) dof count
  PetscInt n_owned = 0, rstart = 0;        // owned global dofs
  PetscInt n_velocity = 0, n_pressure = 0; // global dof counts per field
  std::vector<int> cell_vertex;            // 4 per cell
  std::vector<PetscInt> cell_vdof;         // 10 per cell: first local dof of each velocity node
  std::vector<PetscInt> cell_pdof;         // 4 per cell
  std::vector<double> X;                   // 3 per local vertex, reference coordinates
  std::vector<PetscInt> local_to_global;   // per local dof, global index
  ISLocalToGlobalMapping l2g = nullptr;    // the same, for MatSetValuesLocal
  IS is_velocity = nullptr, is_pressure = nullptr;
  std::vector<double> velocity_node_X; // 3 per owned velocity node, in is_velocity order
  // Our own global <-> local scatter built from local_to_global (the DM's section SF is not used).
  VecScatter g2l = nullptr;
  Vec create_global() const;
  Vec create_local() const;
  void to_local(Vec g, Vec l) const;      // insert owned + ghost values
  void add_to_global(Vec l, Vec g) const; // g += sum over ranks of l (g not zeroed here)

  void build(const Mesh &mesh);
  void check_numbering() const;
  ~Space();
  PetscInt n_cells() const { return cEnd - cStart; }
  // The 4 vertex positions of local cell k taken from Xv (3 per local vertex, e.g. X).
  void cell_points(PetscInt k, const double *Xv, double P[4][3]) const {
    for (int i = 0; i < 4; ++i)
      for (int d = 0; d < 3; ++d)
        P[i][d] = Xv[3 * cell_vertex[4 * k + i] + d];
  }
  PetscInt n_vertices() const { return vEnd - vStart; }
  bool owned(PetscInt local_dof) const {
    PetscInt g = local_to_global[local_dof];
    return g >= rstart && g < rstart + n_owned;
  }
  // Faces of boundary `name` (label from the mesh).  With `region` (a mask over local cells) a
  // face is taken from the side of a region cell, and skipped where no such cell supports it:
  // pass the fluid's cells for a fluid-solid interface.
  std::vector<BoundaryFace> boundary_faces(const Mesh &mesh, const std::string &name,
                                           const std::vector<char> *region = nullptr) const;
  // Velocity nodes (vertices and edges) in the closure of boundary `name`, consistent across
  // ranks: a node shared with a rank that lacks the face is listed there too.
  std::vector<DofNode> boundary_velocity_nodes(const Mesh &mesh, const std::string &name) const;
  // Local pressure dof of the lexicographically smallest vertex (partition independent) among
  // the pressure dofs marked in `among` (all if null), or -1 if this rank does not see it;
  // `vertex` receives its local vertex index.
  PetscInt pinned_pressure_dof(int &vertex, const std::vector<char> *among = nullptr) const;
  // Mask over local dofs: the pressure dofs of the vertices of `cells` (local cell indices),
  // the same on every rank that sees a vertex.
  std::vector<char> pressure_dofs_of(const std::vector<PetscInt> &cells) const;
  // A mask over local dofs made consistent across ranks: a dof marked on any rank is marked on
  // every rank that sees it.
  std::vector<char> mark_on_all_ranks(const std::vector<char> &marked) const;
};

// Give the velocity unknowns in `is` (3 per node, nodes at node_X) the six rigid-body modes as
// near null space, for algebraic multigrid (GAMG) on the block a field split extracts with it.
void compose_rigid_body_modes(IS is, const std::vector<double> &node_X);

} // namespace fsi
