// How a run is steered from outside: SIGTERM, SIGINT and SIGUSR1 (mpirun forwards SIGUSR1) ask
// for a checkpoint and a clean stop after the current step; options nobody read after the first
// step are typos in a scene (an error before any result is written, unless
// -allow_unused_options); a progress line per step.
#pragma once
#include "fsi/ale/remesh.hpp"
#include "fsi/run/simulation.hpp"
#include "fsi/time/step_control.hpp"
#include <memory>

namespace fsi {

// One step of the simulation: true when accepted (s holds its statistics); false when it failed
// and the step control cut dt for a retry; throws when it cannot be cut (or the fluid mesh is too
// distorted, which a smaller step does not cure).
bool attempt_step(MPI_Comm comm, Simulation &sim, StepControl &control, StepStats &s);
// The whole discretisation rebuilt from the state of `old` (destroyed first): fields and
// wall-shear files continue under new names.
std::unique_ptr<Simulation> rebuild(std::unique_ptr<Simulation> old, const Mesh &mesh,
                                    OutputNames &names, const RunState &state);
// Remesh the fluid of `sim` at `state` (its last accepted state, with dt and step control set):
// the new mesh is written to DIR/remesh/mesh_<k>.msh, read and distributed into `mesh` (which
// the old sim indexed; destroyed first), and `sim` becomes the run on it.  `state` receives the
// new mesh's file and count.  Throws RemeshError with `sim` and `mesh` untouched (the caller
// can still checkpoint the last good state).
void remesh(MPI_Comm comm, std::unique_ptr<Simulation> &sim, std::unique_ptr<Mesh> &mesh,
            OutputNames &names, RunState &state, const RemeshOptions &options,
            RemeshReport &report);
void install_stop_handlers();
// The signal any rank received (0 if none), collective.
int stop_requested(MPI_Comm comm);
const char *signal_name(int sig);
void check_unused_options();
void progress(MPI_Comm comm, long step, double t, double t_end, double dt, long newton, long krylov,
              double step_s, double elapsed, double t0);

} // namespace fsi
