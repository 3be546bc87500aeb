// Checkpoint and restart.  One HDF5 file holds the complete state of a run: the generalized-alpha
// history V_n, A_n (the last solution is V_n), the solid displacement D_n, the mesh displacement,
// the step-size control, the wall-shear accumulators, step and time.  Values are stored per dof
// keyed by the node's reference position and component, sorted (partition independent), so a run
// resumes on any number of ranks; a file from another mesh or scene is rejected with one line.
//   -checkpoint_every N   write DIR/checkpoint.h5 every N steps (and at the end, and on a
//                         failure or SIGTERM/SIGINT/SIGUSR1); 0 = only on those events
//   -restart FILE         resume from FILE (same scene options; the run continues to its end time)
// Written atomically: rank 0 writes checkpoint.h5.partial, fsyncs and renames it, so a run killed
// while writing keeps the previous checkpoint intact.
#pragma once
#include "fsi/problem.hpp"
#include "fsi/step_control.hpp"
#include "fsi/wall_shear.hpp"
#include <string>
#include <vector>

namespace fsi {

class Checkpoint {
public:
  // scene: what must match on restart (physics and time scheme).
  Checkpoint(const Space &space, const std::string &scene);
  void write(const std::string &path, const Problem &pb, const StepControl &c,
             const WallShear &w) const;
  void read(const std::string &path, Problem &pb, StepControl &c, WallShear &w) const;

private:
  MPI_Comm comm_;
  int rank_ = 0;
  const Space &space_;
  std::string scene_;
  std::vector<double> dof_keys_;    // x, y, z, component (3 = pressure) per owned dof
  std::vector<PetscInt> dof_index_; // its index in the owned part of a global vector
  std::vector<double> vertex_keys_; // x, y, z per owned vertex
  std::vector<int> vertex_local_;   // its local vertex index
  long crash_at_ = 0;               // -checkpoint_crash_test K: SIGKILL halfway through the
  mutable long writes_ = 0;         // K-th checkpoint write (tests only)
};

} // namespace fsi
