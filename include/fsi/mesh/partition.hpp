// Partitioning the cells of a mesh read on one rank before it is distributed: PT-Scotch through
// PETSc (the default) or METIS (Debian's libmetis; Debian's PETSc has neither METIS nor ParMETIS
// as a partitioner), chosen by -mesh_partitioner.  Both work on PETSc's dual graph (cells
// sharing a face), the result is handed to DMPlexDistribute through PETSc's shell partitioner,
// and its quality is measured the same way for both: the edge cut (faces between parts) and the
// load imbalance (largest part over the mean).
#pragma once
#include "fsi/common.hpp"
#include <string>
#include <vector>

namespace fsi {

struct PartitionQuality {
  std::string method;
  int parts = 1;
  long cells = 0, faces = 0; // graph vertices and edges (interior faces)
  long edge_cut = 0;         // interior faces whose two cells lie in different parts
  double imbalance = 1;      // largest part / mean part
};

// The dual graph of the cells on this rank (all of them on one rank: a mesh as read): CSR.
struct CellGraph {
  std::vector<PetscInt> start, adjacency;
  long n() const { return start.empty() ? 0 : (long)start.size() - 1; }
};
CellGraph cell_graph(DM dm);

// The part of each graph vertex, by "ptscotch" or "metis".  Throws InputError for an unknown
// method.  Runs on the calling rank alone.
std::vector<int> partition_graph(const CellGraph &g, int parts, const std::string &method);
PartitionQuality partition_quality(const CellGraph &g, const std::vector<int> &part, int parts,
                                   const std::string &method);

// Set dm's partitioner to the -mesh_partitioner choice for the ranks of its communicator (the
// cells must all be on one rank, as after reading a file); returns the partition's quality
// (valid on every rank).  Collective.
PartitionQuality set_partition(DM dm);

} // namespace fsi
