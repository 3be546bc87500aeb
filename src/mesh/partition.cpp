#include "fsi/mesh/partition.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <metis.h>

namespace fsi {

CellGraph cell_graph(DM dm) {
  PetscInt n = 0, *start = nullptr, *adj = nullptr;
  IS numbering = nullptr;
  FSI_CALL(DMPlexCreatePartitionerGraph(dm, 0, &n, &start, &adj, &numbering));
  CellGraph g;
  if (n > 0) {
    g.start.assign(start, start + n + 1);
    g.adjacency.assign(adj, adj + start[n]);
  }
  FSI_CALL(PetscFree(start));
  FSI_CALL(PetscFree(adj));
  FSI_CALL(ISDestroy(&numbering));
  return g;
}

static std::vector<int> by_ptscotch(const CellGraph &g, int parts) {
  PetscPartitioner p;
  FSI_CALL(PetscPartitionerCreate(PETSC_COMM_SELF, &p));
  FSI_CALL(PetscPartitionerSetType(p, PETSCPARTITIONERPTSCOTCH));
  PetscSection sec;
  FSI_CALL(PetscSectionCreate(PETSC_COMM_SELF, &sec));
  IS is;
  std::vector<PetscInt> start = g.start, adj = g.adjacency; // PETSc takes non-const arrays
  FSI_CALL(PetscPartitionerPartition(p, parts, (PetscInt)g.n(), start.data(), adj.data(), nullptr,
                                     nullptr, sec, &is));
  std::vector<int> part(g.n(), 0);
  const PetscInt *pts;
  FSI_CALL(ISGetIndices(is, &pts));
  for (int r = 0; r < parts; ++r) {
    PetscInt n, off;
    FSI_CALL(PetscSectionGetDof(sec, r, &n));
    FSI_CALL(PetscSectionGetOffset(sec, r, &off));
    for (PetscInt i = off; i < off + n; ++i)
      part[pts[i]] = r;
  }
  FSI_CALL(ISRestoreIndices(is, &pts));
  FSI_CALL(ISDestroy(&is));
  FSI_CALL(PetscSectionDestroy(&sec));
  FSI_CALL(PetscPartitionerDestroy(&p));
  return part;
}

static std::vector<int> by_metis(const CellGraph &g, int parts) {
  idx_t n = (idx_t)g.n(), ncon = 1, np = parts, cut = 0;
  std::vector<idx_t> xadj(g.start.begin(), g.start.end()),
      adjncy(g.adjacency.begin(), g.adjacency.end()), part(n, 0);
  if (parts < 2 || n == 0) return std::vector<int>(n, 0);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  const int rc = METIS_PartGraphKway(&n, &ncon, xadj.data(), adjncy.data(), nullptr, nullptr,
                                     nullptr, &np, nullptr, nullptr, options, &cut, part.data());
  if (rc != METIS_OK)
    throw SolveError("METIS could not partition the mesh (code " + std::to_string(rc) +
                     "): use -mesh_partitioner ptscotch");
  return std::vector<int>(part.begin(), part.end());
}

std::vector<int> partition_graph(const CellGraph &g, int parts, const std::string &method) {
  if (method == "metis") return by_metis(g, parts);
  if (method == "ptscotch") return by_ptscotch(g, parts);
  throw InputError("unknown partitioner '" + method + "': use ptscotch or metis");
}

PartitionQuality partition_quality(const CellGraph &g, const std::vector<int> &part, int parts,
                                   const std::string &method) {
  PartitionQuality q;
  q.method = method, q.parts = parts, q.cells = g.n();
  std::vector<long> count(parts, 0);
  for (long v = 0; v < g.n(); ++v) {
    ++count[part[v]];
    for (PetscInt e = g.start[v]; e < g.start[v + 1]; ++e) {
      const PetscInt w = g.adjacency[e];
      if (w <= v) continue; // each face once
      ++q.faces;
      if (part[w] != part[v]) ++q.edge_cut;
    }
  }
  const long most = *std::max_element(count.begin(), count.end());
  q.imbalance = q.cells > 0 ? double(most) * parts / q.cells : 1;
  return q;
}

PartitionQuality set_partition(DM dm) {
  MPI_Comm comm = PetscObjectComm((PetscObject)dm);
  int size, rank;
  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  const std::string method = opt::choice("mesh_partitioner", "ptscotch", {"ptscotch", "metis"});
  PetscPartitioner pp;
  FSI_CALL(DMPlexGetPartitioner(dm, &pp));
  PetscInt c0, c1;
  FSI_CALL(DMPlexGetHeightStratum(dm, 0, &c0, &c1));
  int holds = c1 > c0 ? 1 : 0, holders;
  MPI_Allreduce(&holds, &holders, 1, MPI_INT, MPI_SUM, comm);
  PartitionQuality q;
  q.method = method, q.parts = size;
  if (holders != 1) { // already spread over ranks: PETSc's own (parallel) partitioner
    FSI_CALL(PetscPartitionerSetType(pp, PETSCPARTITIONERPTSCOTCH));
    q.method = "ptscotch", q.edge_cut = -1;
    return q;
  }
  const CellGraph g = cell_graph(dm); // collective; empty where no cells
  std::vector<PetscInt> sizes(size, 0), points;
  double qv[4] = {0, 0, 0, 0};
  if (holds) {
    const std::vector<int> part = partition_graph(g, size, method);
    q = partition_quality(g, part, size, method);
    for (int r = 0; r < size; ++r)
      for (long v = 0; v < g.n(); ++v)
        if (part[v] == r) points.push_back(c0 + (PetscInt)v), ++sizes[r];
    qv[0] = (double)q.cells, qv[1] = (double)q.faces, qv[2] = (double)q.edge_cut;
    qv[3] = q.imbalance;
  }
  MPI_Allreduce(MPI_IN_PLACE, qv, 4, MPI_DOUBLE, MPI_SUM, comm);
  q.method = method, q.parts = size;
  q.cells = (long)qv[0], q.faces = (long)qv[1], q.edge_cut = (long)qv[2], q.imbalance = qv[3];
  FSI_CALL(PetscPartitionerSetType(pp, PETSCPARTITIONERSHELL));
  FSI_CALL(PetscPartitionerShellSetPartition(pp, size, sizes.data(), points.data()));
  return q;
}

} // namespace fsi
