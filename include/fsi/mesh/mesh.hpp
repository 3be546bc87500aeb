// Mesh: a gmsh mesh in a distributed, interpolated DMPlex whose physical groups arrive as one
// DMLabel per physical name ("fluid", "inlet", ...).  A scene names either a ready .msh file
// (-mesh_file) or a .geo source and a size (-mesh_geo, -mesh_h), which is meshed with the gmsh API
// on rank 0 and cached by content, so a scene states its mesh and its resolution in one place.
#pragma once
#include "fsi/common.hpp"
#include "fsi/mesh/partition.hpp"
#include <string>
#include <vector>

namespace fsi {

struct Mesh {
  DM dm = nullptr;    // distributed, interpolated tetrahedral DMPlex
  std::string source; // the .msh actually read
  PetscInt cells_global = 0;
  PetscInt vertices_global = 0;
  PartitionQuality partition; // how the cells were split over the ranks (-mesh_partitioner)

  ~Mesh();
  // Cells of the local mesh that carry physical volume `name` (all local cells if name empty).
  std::vector<PetscInt> cells_in(const std::string &name) const;
  // Label of physical group `name`; throws InputError if no rank has it.
  DMLabel label(const std::string &name) const;
  bool has_group(const std::string &name) const;
  // Throws one InputError listing every group in `names` that the mesh lacks.
  void require_groups(const std::vector<std::string> &names, const std::string &why) const;
};

// Resolve a path given by the user: as given, else relative to the source tree.
std::string resolve_path(const std::string &path);

// Read -mesh_file or -mesh_geo/-mesh_h/-mesh_params, build and distribute the DMPlex.
void load_mesh(MPI_Comm comm, Mesh &mesh);
// The scene's mesh options, read but not used (a run resumed on a remeshed mesh).
void skip_scene_mesh_options();
// Read a gmsh .msh file (e.g. a remeshed one), build and distribute the DMPlex.
void load_mesh_file(MPI_Comm comm, Mesh &mesh, const std::string &file);

} // namespace fsi
