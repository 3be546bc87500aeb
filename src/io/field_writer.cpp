#include "fsi/io/field_writer.hpp"

#include <fstream>
#include <petscviewerhdf5.h>

namespace fsi {

FieldWriter::FieldWriter(const Space &space, const std::string &dir, const FieldSet &set)
    : space_(space), dir_(dir), set_(set) {
  MPI_Comm comm = PetscObjectComm((PetscObject)space.dm);
  PetscSection ls;
  FSI_CALL(DMGetLocalSection(space.dm, &ls));
  // A vertex is owned where its pressure dof is; global vertex ids follow rank order.
  std::vector<PetscInt> pdof(space.n_vertices());
  for (PetscInt v = space.vStart; v < space.vEnd; ++v)
    FSI_CALL(PetscSectionGetFieldOffset(ls, v, 1, &pdof[v - space.vStart]));
  for (PetscInt v = 0; v < space.n_vertices(); ++v)
    if (space.owned(pdof[v])) owned_vertices_.push_back(v);
  nv_owned_ = (PetscInt)owned_vertices_.size();
  PetscInt vstart = 0;
  MPI_Scan(&nv_owned_, &vstart, 1, MPIU_INT, MPI_SUM, comm);
  vstart -= nv_owned_;
  MPI_Allreduce(&nv_owned_, &nv_global_, 1, MPIU_INT, MPI_SUM, comm);
  PetscInt nc = space.n_cells();
  MPI_Allreduce(&nc, &ncells_global_, 1, MPIU_INT, MPI_SUM, comm);
  // Global id of every local vertex (ghosts from their owner) through a dof-sized vector.
  Vec g = space.create_global(), l = space.create_local();
  PetscScalar *ga;
  FSI_CALL(VecGetArray(g, &ga));
  for (PetscInt i = 0; i < nv_owned_; ++i)
    ga[space.local_to_global[pdof[owned_vertices_[i]]] - space.rstart] = vstart + i;
  FSI_CALL(VecRestoreArray(g, &ga));
  space.to_local(g, l);
  const PetscScalar *la;
  FSI_CALL(VecGetArrayRead(l, &la));
  std::vector<PetscInt> vid(space.n_vertices());
  for (PetscInt v = 0; v < space.n_vertices(); ++v)
    vid[v] = (PetscInt)PetscRealPart(la[pdof[v]]);
  FSI_CALL(VecRestoreArrayRead(l, &la));
  FSI_CALL(VecDestroy(&g));
  FSI_CALL(VecDestroy(&l));

  FSI_CALL(
      PetscViewerHDF5Open(comm, (dir + "/" + set.base + ".h5").c_str(), FILE_MODE_WRITE, &h5_));
  Vec cells;
  FSI_CALL(VecCreateMPI(comm, 4 * nc, PETSC_DETERMINE, &cells));
  FSI_CALL(VecSetBlockSize(cells, 4));
  PetscScalar *ca;
  FSI_CALL(VecGetArray(cells, &ca));
  for (PetscInt k = 0; k < nc; ++k)
    for (int i = 0; i < 4; ++i)
      ca[4 * k + i] = vid[space.cell_vertex[4 * k + i]];
  FSI_CALL(VecRestoreArray(cells, &ca));
  write_and_destroy("/topology", "cells", cells);
  Vec xv = vertex_vec(3);
  PetscScalar *xa;
  FSI_CALL(VecGetArray(xv, &xa));
  for (PetscInt i = 0; i < nv_owned_; ++i)
    for (int d = 0; d < 3; ++d)
      xa[3 * i + d] = space.X[3 * owned_vertices_[i] + d];
  FSI_CALL(VecRestoreArray(xv, &xa));
  write_and_destroy("/geometry", "vertices", xv);
}

FieldWriter::~FieldWriter() {
  if (h5_) PetscViewerDestroy(&h5_);
}

void FieldWriter::write_and_destroy(const char *group, const std::string &name, Vec &v) {
  FSI_CALL(PetscObjectSetName((PetscObject)v, name.c_str()));
  FSI_CALL(PetscViewerHDF5PushGroup(h5_, group));
  FSI_CALL(VecView(v, h5_));
  FSI_CALL(PetscViewerHDF5PopGroup(h5_));
  FSI_CALL(VecDestroy(&v));
}

Vec FieldWriter::vertex_vec(int bs) const {
  Vec v;
  FSI_CALL(
      VecCreateMPI(PetscObjectComm((PetscObject)space_.dm), bs * nv_owned_, PETSC_DETERMINE, &v));
  FSI_CALL(VecSetBlockSize(v, bs));
  return v;
}

std::vector<std::pair<std::string, int>> FieldWriter::names() const {
  std::vector<std::pair<std::string, int>> n = {{"velocity", 3}};
  if (set_.pressure) n.push_back({"pressure", 1});
  if (set_.mesh_displacement) n.push_back({"mesh_displacement", 3});
  if (set_.displacement) n.push_back({"displacement", 3});
  return n;
}

void FieldWriter::write(long step, double t, Vec U_local, const std::vector<double> &X,
                        Vec D_local) {
  PetscSection ls;
  FSI_CALL(DMGetLocalSection(space_.dm, &ls));
  const PetscScalar *u, *dsol = nullptr;
  FSI_CALL(VecGetArrayRead(U_local, &u));
  if (set_.displacement) FSI_CALL(VecGetArrayRead(D_local, &dsol));
  Vec vel = vertex_vec(3), p = vertex_vec(1), disp = vertex_vec(3), sd = vertex_vec(3);
  PetscScalar *va, *pa, *da, *sa;
  FSI_CALL(VecGetArray(vel, &va));
  FSI_CALL(VecGetArray(p, &pa));
  FSI_CALL(VecGetArray(disp, &da));
  FSI_CALL(VecGetArray(sd, &sa));
  for (PetscInt i = 0; i < nv_owned_; ++i) {
    const PetscInt v = owned_vertices_[i];
    PetscInt o0, o1;
    FSI_CALL(PetscSectionGetFieldOffset(ls, v + space_.vStart, 0, &o0));
    FSI_CALL(PetscSectionGetFieldOffset(ls, v + space_.vStart, 1, &o1));
    for (int d = 0; d < 3; ++d) {
      va[3 * i + d] = u[o0 + d];
      da[3 * i + d] = X[3 * v + d] - space_.X[3 * v + d];
      sa[3 * i + d] = dsol ? dsol[o0 + d] : 0.0;
    }
    pa[i] = u[o1];
  }
  FSI_CALL(VecRestoreArray(vel, &va));
  FSI_CALL(VecRestoreArray(p, &pa));
  FSI_CALL(VecRestoreArray(disp, &da));
  FSI_CALL(VecRestoreArray(sd, &sa));
  FSI_CALL(VecRestoreArrayRead(U_local, &u));
  if (dsol) FSI_CALL(VecRestoreArrayRead(D_local, &dsol));
  char tag[32];
  std::snprintf(tag, sizeof tag, "_%06ld", step);
  write_and_destroy("/fields", std::string("velocity") + tag, vel);
  if (set_.pressure)
    write_and_destroy("/fields", std::string("pressure") + tag, p);
  else
    FSI_CALL(VecDestroy(&p));
  if (set_.mesh_displacement)
    write_and_destroy("/fields", std::string("mesh_displacement") + tag, disp);
  else
    FSI_CALL(VecDestroy(&disp));
  if (set_.displacement)
    write_and_destroy("/fields", std::string("displacement") + tag, sd);
  else
    FSI_CALL(VecDestroy(&sd));
  steps_.emplace_back(step, t);
}

void FieldWriter::close() {
  if (!h5_) return;
  FSI_CALL(PetscViewerDestroy(&h5_));
  int rank;
  MPI_Comm_rank(PetscObjectComm((PetscObject)space_.dm), &rank);
  if (rank != 0) return;
  const std::string path = dir_ + "/" + set_.base + ".xdmf", tmp = path + ".tmp";
  std::ofstream f(tmp);
  const auto nv = std::to_string(nv_global_), nc = std::to_string(ncells_global_);
  f << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"fields\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (auto &[step, t] : steps_) {
    char tag[32];
    std::snprintf(tag, sizeof tag, "_%06ld", step);
    f << "   <Grid Name=\"step" << tag << "\" GridType=\"Uniform\">\n"
      << "    <Time Value=\"" << t << "\"/>\n"
      << "    <Topology TopologyType=\"Tetrahedron\" NumberOfElements=\"" << nc << "\">\n"
      << "     <DataItem Dimensions=\"" << nc
      << " 4\" NumberType=\"Float\" Precision=\"8\" "
         "Format=\"HDF\">"
      << set_.base << ".h5:/topology/cells</DataItem>\n"
      << "    </Topology>\n    <Geometry GeometryType=\"XYZ\">\n"
      << "     <DataItem Dimensions=\"" << nv
      << " 3\" NumberType=\"Float\" Precision=\"8\" "
         "Format=\"HDF\">"
      << set_.base << ".h5:/geometry/vertices</DataItem>\n"
      << "    </Geometry>\n";
    for (auto &[name, nc_] : names())
      f << "    <Attribute Name=\"" << name << "\" AttributeType=\""
        << (nc_ == 3 ? "Vector" : "Scalar") << "\" Center=\"Node\">\n     <DataItem Dimensions=\""
        << nv << (nc_ == 3 ? " 3" : "") << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">"
        << set_.base << ".h5:/fields/" << name << tag << "</DataItem>\n    </Attribute>\n";
    f << "   </Grid>\n";
  }
  f << "  </Grid>\n </Domain>\n</Xdmf>\n";
  f.close();
  std::rename(tmp.c_str(), path.c_str());
}

} // namespace fsi
