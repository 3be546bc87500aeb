// fsi_app -help: every option of every part, whether the scene switches it on or not, with
// its meaning, default and unit; exits 0 without a scene.  Each part declares its options next to
// the code that reads them (scene/option_doc.hpp); the physics, monitors and boundary-condition
// types come from their registries.  tests/test_help.py checks that every option the sources
// read is declared in its reader's folder.
#pragma once
#include "fsi/mesh/mesh.hpp"

namespace fsi {

struct Scene;
class Simulation;

bool wants_help(); // -help or -h given
int print_help(MPI_Comm comm);
// The run's first lines: scene, ranks, mesh, dofs, physics.
void print_run_header(MPI_Comm comm, const Scene &scene, const Mesh &mesh, const Simulation &sim);

} // namespace fsi
