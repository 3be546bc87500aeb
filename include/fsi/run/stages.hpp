// -log_view stages, registered once: where the time of a run goes.
#pragma once
#include <petsc.h>

namespace fsi {
struct Stages {
  PetscLogStage setup, assembly, solve, mesh_motion, output;
  static Stages &get();
};
} // namespace fsi
