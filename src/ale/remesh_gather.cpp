// Remeshing: the distributed mesh gathered on rank 0 (remesh_internal.hpp).
#include "fsi/discretization/space.hpp"
#include "remesh_internal.hpp"

#include <cmath>
#include <sstream>

namespace fsi::remeshing {

static bool builtin_label(const std::string &n) {
  return n == "depth" || n == "celltype" || n == "Cell Sets" || n == "Face Sets" ||
         n == "Vertex Sets" || n == "Edge Sets" || n.rfind("__", 0) == 0;
}

Groups mesh_groups(const Mesh &mesh) {
  MPI_Comm comm = PetscObjectComm((PetscObject)mesh.dm);
  int rank;
  MPI_Comm_rank(comm, &rank);
  std::string all;
  PetscInt n;
  FSI_CALL(DMGetNumLabels(mesh.dm, &n));
  for (PetscInt i = 0; i < n; ++i) {
    const char *name;
    FSI_CALL(DMGetLabelName(mesh.dm, i, &name));
    if (!builtin_label(name)) all += std::string(name) + "\n";
  }
  int len = rank == 0 ? (int)all.size() : 0;
  MPI_Bcast(&len, 1, MPI_INT, 0, comm);
  all.resize(len);
  MPI_Bcast(all.data(), len, MPI_CHAR, 0, comm);
  Groups g;
  std::istringstream in(all);
  std::string name;
  PetscInt cStart, cEnd, fStart, fEnd;
  FSI_CALL(DMPlexGetHeightStratum(mesh.dm, 0, &cStart, &cEnd));
  FSI_CALL(DMPlexGetHeightStratum(mesh.dm, 1, &fStart, &fEnd));
  while (std::getline(in, name)) {
    long count[2] = {0, 0}, total[2];
    PetscBool has;
    FSI_CALL(DMHasLabel(mesh.dm, name.c_str(), &has));
    if (has) {
      DMLabel l;
      FSI_CALL(DMGetLabel(mesh.dm, name.c_str(), &l));
      IS is;
      FSI_CALL(DMLabelGetValueIS(l, &is));
      PetscInt nv;
      const PetscInt *vals;
      FSI_CALL(ISGetLocalSize(is, &nv));
      FSI_CALL(ISGetIndices(is, &vals));
      for (PetscInt j = 0; j < nv; ++j) {
        IS pts;
        FSI_CALL(DMLabelGetStratumIS(l, vals[j], &pts));
        if (!pts) continue;
        PetscInt np;
        const PetscInt *p;
        FSI_CALL(ISGetLocalSize(pts, &np));
        FSI_CALL(ISGetIndices(pts, &p));
        for (PetscInt k = 0; k < np; ++k) {
          count[0] += p[k] >= cStart && p[k] < cEnd;
          count[1] += p[k] >= fStart && p[k] < fEnd;
        }
        FSI_CALL(ISRestoreIndices(pts, &p));
        FSI_CALL(ISDestroy(&pts));
      }
      FSI_CALL(ISRestoreIndices(is, &vals));
      FSI_CALL(ISDestroy(&is));
    }
    MPI_Allreduce(count, total, 2, MPI_LONG, MPI_SUM, comm);
    if (total[0] > 0 || total[1] > 0) {
      g.names.push_back(name);
      g.dim.push_back(total[0] > 0 ? 3 : 2);
    }
  }
  if (g.names.size() > 50) throw InputError("remeshing supports at most 50 physical groups");
  return g;
}

static bool in_label(DMLabel l, PetscInt p) {
  if (!l) return false;
  PetscInt v;
  FSI_CALL(DMLabelGetValue(l, p, &v));
  return v >= 0;
}

Gathered gather_mesh(const Mesh &mesh, const Space &space, const std::vector<PetscInt> &fluid_cells,
                     const Groups &g) {
  MPI_Comm comm = PetscObjectComm((PetscObject)mesh.dm);
  std::vector<DMLabel> labels(g.names.size(), nullptr);
  for (size_t i = 0; i < g.names.size(); ++i) {
    PetscBool has;
    FSI_CALL(DMHasLabel(mesh.dm, g.names[i].c_str(), &has));
    if (has) FSI_CALL(DMGetLabel(mesh.dm, g.names[i].c_str(), &labels[i]));
  }
  std::vector<char> fluid(space.n_cells(), 0);
  for (PetscInt k : fluid_cells)
    fluid[k] = 1;
  std::vector<double> ck, cv;
  for (PetscInt k = 0; k < space.n_cells(); ++k) {
    double mask = 0;
    for (size_t i = 0; i < labels.size(); ++i)
      if (g.dim[i] == 3 && in_label(labels[i], space.cStart + k)) mask += std::ldexp(1.0, (int)i);
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d)
        ck.push_back(space.X[3 * space.cell_vertex[4 * k + a] + d]);
    cv.insert(cv.end(), {(double)fluid[k], mask});
  }
  std::vector<double> fk, fv;
  PetscInt fStart, fEnd;
  FSI_CALL(DMPlexGetHeightStratum(mesh.dm, 1, &fStart, &fEnd));
  for (PetscInt f = fStart; f < fEnd; ++f) {
    double mask = 0;
    for (size_t i = 0; i < labels.size(); ++i)
      if (g.dim[i] == 2 && in_label(labels[i], f)) mask += std::ldexp(1.0, (int)i);
    if (mask == 0) continue;
    PetscInt *clos = nullptr, nc;
    FSI_CALL(DMPlexGetTransitiveClosure(mesh.dm, f, PETSC_TRUE, &nc, &clos));
    int nvert = 0;
    for (PetscInt j = 0; j < nc; ++j) {
      const PetscInt p = clos[2 * j];
      if (p >= space.vStart && p < space.vEnd && nvert < 3) {
        for (int d = 0; d < 3; ++d)
          fk.push_back(space.X[3 * (p - space.vStart) + d]);
        ++nvert;
      }
    }
    FSI_CALL(DMPlexRestoreTransitiveClosure(mesh.dm, f, PETSC_TRUE, &nc, &clos));
    fv.push_back(mask);
  }
  Gathered out;
  out.cells = gather_sorted(comm, ck, cv, 12, 2);
  out.faces = gather_sorted(comm, fk, fv, 9, 1);
  return out;
}

} // namespace fsi::remeshing
