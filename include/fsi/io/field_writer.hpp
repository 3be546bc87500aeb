// Fields for ParaView: fields.h5 (parallel HDF5 through PETSc's viewer) and fields.xdmf (written
// by rank 0 when the run ends, so a killed run never leaves an XDMF that looks complete).
// Vertex values on the straight-sided mesh, only the fields of the physics that ran: velocity
// (P2 vertex dofs) always, pressure with a fluid, the mesh displacement when the mesh moves, the
// solid displacement with a solid.  Datasets: /geometry/vertices, /topology/cells,
// /fields/<name>_<step>.
#pragma once
#include "fsi/discretization/space.hpp"
#include <string>
#include <vector>

namespace fsi {

struct FieldSet {
  bool pressure = true, mesh_displacement = false, displacement = false;
  std::string base = "fields"; // file names base.h5, base.xdmf ("fields_restart" on restart)
};

class FieldWriter {
public:
  FieldWriter(const Space &space, const std::string &dir, const FieldSet &set);
  ~FieldWriter();
  // U_local: ghosted solution; X: current vertex coordinates (3 per local vertex); D_local: the
  // solid displacement (needed if the set has it).
  void write(long step, double t, Vec U_local, const std::vector<double> &X, Vec D_local = nullptr);
  void close(); // writes fields.xdmf

private:
  Vec vertex_vec(int bs) const;
  std::vector<std::pair<std::string, int>> names() const;
  void write_and_destroy(const char *group, const std::string &name, Vec &v);
  const Space &space_;
  std::string dir_;
  FieldSet set_;
  PetscViewer h5_ = nullptr;
  PetscInt nv_owned_ = 0, nv_global_ = 0, ncells_global_ = 0;
  std::vector<PetscInt> owned_vertices_; // local vertex indices owned here, in global id order
  std::vector<std::pair<long, double>> steps_;
};

} // namespace fsi
