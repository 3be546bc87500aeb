// Checkpoint and restart, and the state transfer of a rebuilt run.  A Checkpoint knows the keys
// of one Space's dofs and vertices (reference positions, partition independent) and moves the
// state between that space's vectors and a RunState (run_state.hpp), which a file holds:
//   -checkpoint_every N   write DIR/checkpoint.h5 every N steps (and at the end, and on a
//                         failure or SIGTERM/SIGINT/SIGUSR1); 0 = only on those events
//   -restart FILE         resume from FILE (same scene options, any rank count)
// A state of another mesh or scene is rejected with one line.
#pragma once
#include "fsi/discretization/space.hpp"
#include "fsi/io/run_state.hpp"
#include <string>
#include <vector>

namespace fsi {

class Checkpoint {
public:
  explicit Checkpoint(const Space &space);
  // Gather V, A, D (global vectors) and the per-vertex data into `s` (collective).
  void capture(const std::vector<Vec> &vecs, const std::vector<double> &mesh_displacement,
               const std::vector<double> &material_X, RunState &s) const;
  // The per-vertex data of `s` on every local vertex (owned and ghost); InputError when the
  // state belongs to another mesh.
  void vertices(const RunState &s, std::vector<double> &mesh_displacement,
                std::vector<double> &material_X) const;
  // The dof data of `s` into the global vectors V, A, D.
  void dofs(const RunState &s, const std::vector<Vec> &vecs) const;

private:
  [[noreturn]] void mismatch(const RunState &s) const;
  MPI_Comm comm_;
  const Space &space_;
  std::vector<double> dof_keys_;    // x, y, z, component (3 = pressure) per owned dof
  std::vector<PetscInt> dof_index_; // its index in the owned part of a global vector
  std::vector<double> vertex_keys_; // x, y, z per owned vertex
  std::vector<int> vertex_local_;   // its local vertex index
};

} // namespace fsi
