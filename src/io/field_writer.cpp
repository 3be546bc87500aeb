#include "fsi/io/field_writer.hpp"

#include <fstream>
#include <petscviewerhdf5.h>
#include <sstream>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>

namespace fsi {

FieldWriter::FieldWriter(const Space &space, const std::string &dir, const FieldSet &set)
    : space_(space), dir_(dir), set_(set) {
  MPI_Comm comm = PetscObjectComm((PetscObject)space.dm);
  PetscSection ls;
  FSI_CALL(DMGetLocalSection(space.dm, &ls));
  // A node is owned where its velocity dofs are; global ids follow rank order, vertices first.
  pdof_.resize(space.n_vertices());
  for (PetscInt v = space.vStart; v < space.vEnd; ++v) {
    PetscInt o;
    FSI_CALL(PetscSectionGetFieldOffset(ls, v, 0, &o));
    FSI_CALL(PetscSectionGetFieldOffset(ls, v, 1, &pdof_[v - space.vStart]));
    if (space.owned(o)) owned_.push_back({(int)(v - space.vStart), -1, o});
  }
  for (PetscInt e = space.eStart; e < space.eEnd; ++e) {
    PetscInt o, n;
    FSI_CALL(PetscSectionGetFieldDof(ls, e, 0, &n));
    if (n == 0) continue;
    FSI_CALL(PetscSectionGetFieldOffset(ls, e, 0, &o));
    if (!space.owned(o)) continue;
    const PetscInt *cone;
    FSI_CALL(DMPlexGetCone(space.dm, e, &cone));
    owned_.push_back({(int)(cone[0] - space.vStart), (int)(cone[1] - space.vStart), o});
  }
  n_owned_ = (PetscInt)owned_.size();
  PetscInt start = 0;
  MPI_Scan(&n_owned_, &start, 1, MPIU_INT, MPI_SUM, comm);
  start -= n_owned_;
  MPI_Allreduce(&n_owned_, &n_global_, 1, MPIU_INT, MPI_SUM, comm);
  PetscInt nc = space.n_cells();
  MPI_Allreduce(&nc, &ncells_global_, 1, MPIU_INT, MPI_SUM, comm);
  // Global id of every local node (ghosts from their owner) through a dof-sized vector.
  Vec g = space.create_global(), l = space.create_local();
  PetscScalar *ga;
  FSI_CALL(VecGetArray(g, &ga));
  for (PetscInt i = 0; i < n_owned_; ++i)
    ga[space.local_to_global[owned_[i].vdof] - space.rstart] = start + i;
  FSI_CALL(VecRestoreArray(g, &ga));
  space.to_local(g, l);
  const PetscScalar *la;
  FSI_CALL(VecGetArrayRead(l, &la));

  check_room(); // (the mesh written next is about the size of one step's fields)
  io("the file",
     [&]() { return PetscViewerHDF5Open(comm, path().c_str(), FILE_MODE_WRITE, &h5_); });
  // Our P2 node order (4 vertices, then edges TET_EDGE) to VTK's quadratic tetrahedron
  // (4 vertices, then edges 01, 12, 02, 03, 13, 23).
  static const int VTK_FROM_OURS[10] = {0, 1, 2, 3, 4, 7, 5, 6, 8, 9};
  Vec cells;
  FSI_CALL(VecCreateMPI(comm, 10 * nc, PETSC_DETERMINE, &cells));
  FSI_CALL(VecSetBlockSize(cells, 10));
  PetscScalar *ca;
  FSI_CALL(VecGetArray(cells, &ca));
  for (PetscInt k = 0; k < nc; ++k)
    for (int i = 0; i < 10; ++i)
      ca[10 * k + i] = PetscRealPart(la[space.cell_vdof[10 * k + VTK_FROM_OURS[i]]]);
  FSI_CALL(VecRestoreArray(cells, &ca));
  FSI_CALL(VecRestoreArrayRead(l, &la));
  FSI_CALL(VecDestroy(&g));
  FSI_CALL(VecDestroy(&l));
  write_and_destroy("/topology", "cells", cells);
  if (!set.region.empty()) {
    // The solid displacement means nothing at fluid nodes: written as zero there.
    solid_node_.assign(space.n_local, 0);
    for (PetscInt k = 0; k < nc; ++k)
      if (set.region[k] == 1)
        for (int a = 0; a < 10; ++a)
          solid_node_[space.cell_vdof[10 * k + a]] = 1;
    Vec reg;
    FSI_CALL(VecCreateMPI(comm, nc, PETSC_DETERMINE, &reg));
    PetscScalar *ra;
    FSI_CALL(VecGetArray(reg, &ra));
    for (PetscInt k = 0; k < nc; ++k)
      ra[k] = set.region[k];
    FSI_CALL(VecRestoreArray(reg, &ra));
    write_and_destroy("/topology", "region", reg);
  }
  Vec xv = node_vec(3);
  PetscScalar *xa;
  FSI_CALL(VecGetArray(xv, &xa));
  for (PetscInt i = 0; i < n_owned_; ++i)
    for (int d = 0; d < 3; ++d)
      xa[3 * i + d] = node_value(space.X.data(), owned_[i], d);
  FSI_CALL(VecRestoreArray(xv, &xa));
  write_and_destroy("/geometry", "nodes", xv);
}

FieldWriter::~FieldWriter() {
  if (h5_) PetscViewerDestroy(&h5_);
}

void FieldWriter::write_and_destroy(const char *group, const std::string &name, Vec &v) {
  FSI_CALL(PetscObjectSetName((PetscObject)v, name.c_str()));
  FSI_CALL(PetscViewerHDF5PushGroup(h5_, group));
  try {
    io(name, [&]() { return VecView(v, h5_); });
  } catch (OutputError &) {
    VecDestroy(&v);
    throw;
  }
  FSI_CALL(PetscViewerHDF5PopGroup(h5_));
  FSI_CALL(VecDestroy(&v));
}

void FieldWriter::io(const std::string &what, const std::function<PetscErrorCode()> &call) const {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); // HDF5's own error stack: we report it
  FSI_CALL(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr));
  const int bad = call() != 0;
  FSI_CALL(PetscPopErrorHandler());
  int any = 0;
  MPI_Allreduce(&bad, &any, 1, MPI_INT, MPI_MAX, PetscObjectComm((PetscObject)space_.dm));
  if (any)
    throw OutputError("cannot write " + what + " to " + path() +
                      " (disk full or directory not writable?)");
}

// A per-vertex quantity (3 per local vertex) at a node: linear along the edges.
double FieldWriter::node_value(const double *Xv, const Node &n, int d) {
  return n.b < 0 ? Xv[3 * n.a + d] : 0.5 * (Xv[3 * n.a + d] + Xv[3 * n.b + d]);
}

Vec FieldWriter::node_vec(int bs) const {
  Vec v;
  FSI_CALL(
      VecCreateMPI(PetscObjectComm((PetscObject)space_.dm), bs * n_owned_, PETSC_DETERMINE, &v));
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

// Parallel HDF5 does not fail symmetrically (one rank's failed write leaves the other waiting
// in a barrier inside HDF5), so room for the step's fields is checked before writing: free space
// on the disk and the file-size limit, with a margin.
void FieldWriter::check_room() const {
  MPI_Comm comm = PetscObjectComm((PetscObject)space_.dm);
  int rank;
  MPI_Comm_rank(comm, &rank);
  double need = 0;
  for (auto &n : names())
    need += 8.0 * n.second * n_global_;
  need = 1.25 * need + 65536;
  double room = 0;
  if (rank == 0) {
    struct statvfs fs;
    room = statvfs(dir_.c_str(), &fs) == 0 ? (double)fs.f_bavail * fs.f_frsize : 0.0;
    struct rlimit rl;
    struct stat st;
    if (getrlimit(RLIMIT_FSIZE, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
      room = std::min(room, (double)rl.rlim_cur -
                                (stat(path().c_str(), &st) == 0 ? (double)st.st_size : 0.0));
  }
  MPI_Bcast(&room, 1, MPI_DOUBLE, 0, comm);
  if (room < need)
    throw OutputError("cannot write the fields to " + path() + ": " +
                      std::to_string((long)(need / 1024)) + " KiB needed, " +
                      std::to_string((long)(std::max(room, 0.0) / 1024)) +
                      " KiB left (disk full or file-size limit)");
}

void FieldWriter::write(long step, double t, Vec U_local, const std::vector<double> &X,
                        Vec D_local) {
  check_room();
  const PetscScalar *u, *dsol = nullptr;
  FSI_CALL(VecGetArrayRead(U_local, &u));
  if (set_.displacement) FSI_CALL(VecGetArrayRead(D_local, &dsol));
  Vec vel = node_vec(3), p = node_vec(1), disp = node_vec(3), sd = node_vec(3);
  PetscScalar *va, *pa, *da, *sa;
  FSI_CALL(VecGetArray(vel, &va));
  FSI_CALL(VecGetArray(p, &pa));
  FSI_CALL(VecGetArray(disp, &da));
  FSI_CALL(VecGetArray(sd, &sa));
  for (PetscInt i = 0; i < n_owned_; ++i) {
    const Node &n = owned_[i];
    for (int d = 0; d < 3; ++d) {
      va[3 * i + d] = u[n.vdof + d];
      da[3 * i + d] = node_value(X.data(), n, d) - node_value(space_.X.data(), n, d);
      sa[3 * i + d] = dsol && (solid_node_.empty() || solid_node_[n.vdof]) ? dsol[n.vdof + d] : 0.0;
    }
    pa[i] = n.b < 0 ? u[pdof_[n.a]] : 0.5 * (u[pdof_[n.a]] + u[pdof_[n.b]]);
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
  io("the step's fields", [&]() { return PetscViewerFlush(h5_); }); // on disk now, or an error
  steps_.emplace_back(step, t);
}

void FieldWriter::close() {
  if (!h5_) return;
  io("the last fields", [&]() { return PetscViewerDestroy(&h5_); });
  MPI_Comm comm = PetscObjectComm((PetscObject)space_.dm);
  int rank;
  MPI_Comm_rank(comm, &rank);
  collective_output(comm, [&]() {
    if (rank == 0) write_xdmf();
  });
}

void FieldWriter::write_xdmf() const {
  const std::string path = dir_ + "/" + set_.base + ".xdmf", tmp = path + ".tmp";
  std::ofstream f(tmp);
  const auto nv = std::to_string(n_global_), nc = std::to_string(ncells_global_);
  f << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"fields\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (auto &[step, t] : steps_) {
    char tag[32];
    std::snprintf(tag, sizeof tag, "_%06ld", step);
    f << "   <Grid Name=\"step" << tag << "\" GridType=\"Uniform\">\n"
      << "    <Time Value=\"" << t << "\"/>\n"
      << "    <Topology TopologyType=\"Tetrahedron_10\" NumberOfElements=\"" << nc << "\">\n"
      << "     <DataItem Dimensions=\"" << nc
      << " 10\" NumberType=\"Float\" Precision=\"8\" "
         "Format=\"HDF\">"
      << set_.base << ".h5:/topology/cells</DataItem>\n"
      << "    </Topology>\n    <Geometry GeometryType=\"XYZ\">\n"
      << "     <DataItem Dimensions=\"" << nv
      << " 3\" NumberType=\"Float\" Precision=\"8\" "
         "Format=\"HDF\">"
      << set_.base << ".h5:/geometry/nodes</DataItem>\n"
      << "    </Geometry>\n";
    if (!set_.region.empty())
      f << "    <Attribute Name=\"region\" AttributeType=\"Scalar\" Center=\"Cell\">\n"
        << "     <DataItem Dimensions=\"" << nc << "\" NumberType=\"Float\" Precision=\"8\" "
        << "Format=\"HDF\">" << set_.base << ".h5:/topology/region</DataItem>\n    </Attribute>\n";
    for (auto &[name, nc_] : names())
      f << "    <Attribute Name=\"" << name << "\" AttributeType=\""
        << (nc_ == 3 ? "Vector" : "Scalar") << "\" Center=\"Node\">\n     <DataItem Dimensions=\""
        << nv << (nc_ == 3 ? " 3" : "") << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">"
        << set_.base << ".h5:/fields/" << name << tag << "</DataItem>\n    </Attribute>\n";
    f << "   </Grid>\n";
  }
  f << "  </Grid>\n </Domain>\n</Xdmf>\n";
  f.close();
  if (!f || std::rename(tmp.c_str(), path.c_str()) != 0)
    throw OutputError("cannot write " + path + " (disk full or directory not writable?)");
}

void merge_xdmf(const std::string &dir, const std::vector<std::string> &parts,
                const std::string &name) {
  const std::string head = "GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  const std::string tail = "  </Grid>\n </Domain>";
  std::string grids;
  for (auto &p : parts) {
    std::ifstream in(dir + "/" + p + ".xdmf");
    if (!in) continue;
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string x = ss.str();
    const size_t a = x.find(head), b = x.rfind(tail);
    if (a == std::string::npos || b == std::string::npos || b < a) continue;
    grids += x.substr(a + head.size(), b - a - head.size());
  }
  const std::string path = dir + "/" + name + ".xdmf", tmp = path + ".tmp";
  std::ofstream f(tmp);
  f << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"fields\" " << head << grids << tail << "\n</Xdmf>\n";
  f.close();
  std::rename(tmp.c_str(), path.c_str());
}

} // namespace fsi
