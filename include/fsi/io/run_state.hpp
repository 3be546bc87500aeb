// The complete state of a run between two steps, in a partition-independent form: what a
// checkpoint file holds and what a rebuilt run (new Simulation on the same or a new mesh)
// starts from.  Items carry keys of reference coordinates; the data live on rank 0 (sorted by
// key, as gather_sorted() leaves them) and are empty elsewhere, except the scalars.
#pragma once
#include "fsi/io/h5.hpp"
#include "fsi/io/output.hpp"
#include <map>
#include <string>
#include <vector>

namespace fsi {

struct RunState {
  std::string scene; // physics and time scheme: a state only fits a run of the same scene
  long step = 0;
  double time = 0, dt = 0;
  long easy_run = 0;     // step control's count of easy steps
  double error_prev = 0; // error control's last scaled error estimate (its PI memory)
  long n_dofs = 0;       // global dof count of the run that captured it
  // After a remesh: the mesh the state lives on (a .msh path relative to the checkpoint's
  // directory, or absolute) and how many remeshes led to it; empty: the scene's mesh.
  std::string mesh_file;
  long remeshes = 0;
  // Per dof: key (x, y, z of the node in the ALE reference, component; 3 = pressure), values
  // V_n, A_n, D_n (the generalized-alpha history and the solid displacement).
  KeyedItems dofs;
  // Per vertex: key (x, y, z in the ALE reference), values: mesh displacement (3) and the
  // solid's material reference position (3).
  KeyedItems vertices;
  // Wall-shear accumulators per surface (key: face centroid; values: int tau dt (3), int |tau|
  // dt) and the window (start, elapsed, index, length).
  std::map<std::string, KeyedItems> hemo;
  std::vector<double> hemo_window;
  std::map<std::string, Json> hemo_last_window; // summary of the last closed window (in memory)
  // Lumped models on boundaries (a Windkessel's capacitor pressure), by key.
  std::map<std::string, double> lumped;

  // Checkpoint files (rank 0 writes; all ranks call).  write() is atomic: a .partial file,
  // fsync, rename.  read() checks the format and the scene tag.
  void write(MPI_Comm comm, const std::string &path, long crash_at_write = 0) const;
  static RunState read(MPI_Comm comm, const std::string &path, const std::string &scene);
};

} // namespace fsi
