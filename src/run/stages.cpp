#include "fsi/run/stages.hpp"
#include "fsi/common.hpp"

namespace fsi {

Stages &Stages::get() {
  static Stages s;
  static bool done = false;
  if (!done) {
    FSI_CALL(PetscLogStageRegister("FSI setup", &s.setup));
    FSI_CALL(PetscLogStageRegister("FSI assembly", &s.assembly));
    FSI_CALL(PetscLogStageRegister("FSI solve", &s.solve));
    FSI_CALL(PetscLogStageRegister("FSI mesh motion", &s.mesh_motion));
    FSI_CALL(PetscLogStageRegister("FSI output", &s.output));
    done = true;
  }
  return s;
}

} // namespace fsi
