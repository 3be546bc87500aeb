// How a run is steered from outside: SIGTERM, SIGINT and SIGUSR1 (mpirun forwards SIGUSR1) ask
// for a checkpoint and a clean stop after the current step; options nobody read after the first
// step are typos in a scene (an error before any result is written, unless
// -allow_unused_options); a progress line per step.
#pragma once
#include "fsi/common.hpp"

namespace fsi {

void install_stop_handlers();
// The signal any rank received (0 if none), collective.
int stop_requested(MPI_Comm comm);
const char *signal_name(int sig);
void check_unused_options();
void progress(MPI_Comm comm, long step, double t, double t_end, double dt, long newton,
              long krylov, double step_s, double elapsed, double t0);

} // namespace fsi
