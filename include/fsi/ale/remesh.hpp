// Remeshing the fluid (the paper: "whenever the skewness of an element is bigger than 0.9"; the
// trigger is in ale.hpp).  The deformed fluid boundary -- walls, inlet, outlet and the
// fluid-solid interface at its current position -- is gathered on rank 0 and the fluid volume is
// meshed again with gmsh (discrete surfaces, Delaunay), keeping every boundary triangle, so that
// the fluid stays conforming to the solid, whose cells, material reference and state are
// untouched.  The new mesh (new fluid cells + the old solid cells, the same physical groups) is
// written as a .msh and read like the first one, so it is distributed the same way and a
// checkpoint can name it.  Sizes come from the boundary triangles (gmsh extends them inwards),
// capped by -ale_remesh_hmax when given, and shrink where the boundary faces itself across a
// gap thinner than its triangles (-ale_remesh_gap_cells cells across, default 2; 0 = off):
// without nodes inside, such a gap (between two leaflets near a commissure) holds one layer of
// slivers that no new mesh of the same boundary avoids.
//
// State transfer (remesh_state): nodes that survive (solid nodes, boundary vertices and edges)
// keep their values exactly; new fluid nodes get the old fields evaluated in the old fluid mesh
// in its current configuration: P2 velocity, acceleration and displacement histories, P1
// pressure.  The new mesh is the new ALE reference (mesh displacement 0); the solid keeps its
// material reference; wall-shear accumulators move with their faces.  The interpolated velocity
// is not projected: its divergence, its kinetic energy and the fluid volume are measured before
// and after and reported (RemeshReport, remesh.csv), see docs/remeshing.md.
//   -ale_remesh_hmax H     largest new cell size [m] (default: from the boundary only)
//   -ale_remesh_every N    also remesh after every N-th step (tests, studies; default 0)
//   -ale_remesh_flip_skewness S   edge and face flips on gmsh's cells worse than S (default
//                          0.8; 0 = off): gmsh leaves slivers on four boundary vertices
#pragma once
#include "fsi/io/run_state.hpp"
#include "fsi/mesh/mesh.hpp"
#include <string>
#include <vector>

namespace fsi {

struct Space;

// gmsh could not mesh the boundary (or changed it): the run stops with a checkpoint (exit 3).
struct RemeshError : SolveError {
  using SolveError::SolveError;
};

struct RemeshOptions {
  double hmax = 0;      // -ale_remesh_hmax
  bool verbose = false; // -ale_remesh_verbose
  int test_fault = 0;   // -ale_remesh_test_fault 1: a boundary vertex thrown across the domain;
                        // 2: a failure once the run is on the new mesh
  double gap_cells = 2; // -ale_remesh_gap_cells: cells across a gap thinner than its triangles
  double flip_skewness = 0.8; // -ale_remesh_flip_skewness: flip cells worse than this (0: off)
  bool project = true;        // -ale_remesh_project: make the new velocity divergence-free
  static RemeshOptions from_options(); // read at start, so that a typo fails before step 1
};

struct RemeshReport {
  long step = 0;
  double time = 0;
  long fluid_cells_before = 0, fluid_cells_after = 0;
  double skewness_before = 0, skewness_after = 0;     // worst fluid cell
  double volume_before = 0, volume_after = 0;         // fluid volume [m^3]
  double kinetic_before = 0, kinetic_after = 0;       // int |v|^2 / 2 over the fluid [m^5/s^2]
  double divergence_before = 0, divergence_after = 0; // ||div v|| / ||grad v|| (L2, fluid)
  double mesh_seconds = 0, seconds = 0; // gmsh alone; the whole remesh (with the new run)
  double memory_mb = 0;                 // rank 0's peak resident memory after the remesh
  long gap_vertices = 0;      // boundary vertices facing a gap thinner than their triangles
  double skewness_gmsh = 0;   // worst new fluid cell as gmsh made it, before the flips
  long flips = 0, splits = 0; // sliver removal: flips and vertex moves; edge splits
  // Weak divergence of the transferred velocity, and after the projection (velocity_projection.hpp;
  // -1: not projected), and the projection's seconds.
  double weak_divergence = 0, weak_divergence_projected = -1, projection_seconds = 0;
  // Largest distance a solid vertex moved from the mesh's (predicted) position to the
  // converged solid position it has in the new mesh [m].
  double solid_shift = 0;
};

// Mesh the fluid again from the boundary of `mesh` at the positions of `state` (the state at the
// last accepted step, as Simulation::capture() gives it) and write it to msh_path (rank 0,
// atomically); return the state on the new mesh (data on rank 0).  Collective.  Throws
// RemeshError if gmsh fails; InputError if the mesh cannot be remeshed (a fluid boundary face in
// no physical group).
RunState remesh_fluid(const Mesh &mesh, const Space &space,
                      const std::vector<PetscInt> &fluid_cells, const RunState &state,
                      const RemeshOptions &options, const std::string &msh_path,
                      RemeshReport &report);

} // namespace fsi
