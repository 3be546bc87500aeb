// Fields for ParaView: fields.h5 (parallel HDF5 through PETSc's viewer) and fields.xdmf (written
// by rank 0 when the run ends, so a killed run never leaves an XDMF that looks complete).
// Values at the P2 nodes (vertices, then edge midpoints) on quadratic tetrahedra (XDMF
// Tetrahedron_10, VTK node order), so that ParaView shows the computed P2 fields, not only their
// vertex values; only the fields of the physics that ran: velocity always, pressure with a fluid
// (P1, linear along the edges), the mesh displacement when the mesh moves (P1 motion), the solid
// displacement with a solid (zero at fluid nodes).  Geometry: the reference positions (warp by
// mesh_displacement for the current ones).  Datasets: /geometry/nodes, /topology/cells (10 per
// cell), /fields/<name>_<step>; with both a fluid and a solid, the cell attribute region
// (/topology/region: 1 solid, 0 fluid).
#pragma once
#include "fsi/discretization/space.hpp"
#include <functional>
#include <string>
#include <vector>

namespace fsi {

struct FieldSet {
  bool pressure = true, mesh_displacement = false, displacement = false;
  std::string base = "fields"; // file names base.h5, base.xdmf ("fields_restart" on restart)
  std::vector<int> region;     // per local cell: 1 solid, 0 fluid (written as /topology/region
                               // when not empty)
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
  Vec node_vec(int bs) const;
  std::vector<std::pair<std::string, int>> names() const;
  void write_and_destroy(const char *group, const std::string &name, Vec &v);
  // Runs a PETSc call that writes the file; a failure on any rank (disk full, directory made
  // read-only) becomes an OutputError on every rank, without PETSc's error trace.
  void io(const std::string &what, const std::function<PetscErrorCode()> &call) const;
  void write_xdmf() const; // rank 0
  void check_room() const; // collective: OutputError if the step's fields would not fit
  std::string path() const { return dir_ + "/" + set_.base + ".h5"; }
  const Space &space_;
  std::string dir_;
  FieldSet set_;
  PetscViewer h5_ = nullptr;
  // A P2 node written by this rank: vertex (b < 0) or edge midpoint between local vertices a, b.
  struct Node {
    int a, b;
    PetscInt vdof; // its first local velocity dof
  };
  PetscInt n_owned_ = 0, n_global_ = 0, ncells_global_ = 0;
  std::vector<Node> owned_;      // nodes owned here, in global id order
  std::vector<PetscInt> pdof_;   // pressure dof per local vertex
  std::vector<char> solid_node_; // per local dof: in a solid cell (with a region attribute)
  static double node_value(const double *Xv, const Node &n, int d);
  std::vector<std::pair<long, double>> steps_;
};

// One XDMF for a run whose mesh changed (rebuilds, remeshes): the time steps of every part
// (DIR/<part>.xdmf, each on its own mesh) in one temporal collection DIR/<name>.xdmf, so that
// ParaView plays the whole run.  Rank 0; parts without a file are skipped.
void merge_xdmf(const std::string &dir, const std::vector<std::string> &parts,
                const std::string &name);

} // namespace fsi
