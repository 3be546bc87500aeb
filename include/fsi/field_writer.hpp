// Fields for ParaView: fields.h5 (parallel HDF5 through PETSc's viewer) and fields.xdmf (written
// by rank 0 when the run ends, so a killed run never leaves an XDMF that looks complete).
// Vertex values on the straight-sided mesh: velocity (P2 vertex dofs), pressure, and the mesh
// displacement when the mesh moves.  Datasets: /geometry/vertices, /topology/cells,
// /fields/<name>_<step>.
#pragma once
#include "fsi/space.hpp"
#include <string>
#include <vector>

namespace fsi {

class FieldWriter {
public:
  FieldWriter(const Space &space, const std::string &dir);
  ~FieldWriter();
  // U_local: ghosted solution; X: current vertex coordinates (3 per local vertex).
  void write(long step, double t, Vec U_local, const std::vector<double> &X);
  void close(); // writes fields.xdmf

private:
  Vec vertex_vec(int bs) const;
  void write_and_destroy(const char *group, const std::string &name, Vec &v);
  const Space &space_;
  std::string dir_;
  PetscViewer h5_ = nullptr;
  PetscInt nv_owned_ = 0, nv_global_ = 0, ncells_global_ = 0;
  std::vector<PetscInt> owned_vertices_; // local vertex indices owned here, in global id order
  std::vector<std::pair<long, double>> steps_;
};

} // namespace fsi
