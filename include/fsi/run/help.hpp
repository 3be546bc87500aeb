// fsi_app -help: every option of every module, whether the scene switches it on or not, with
// its meaning, default and unit; exits 0 without a scene.  The option tables live in
// src/run/help.cpp, one section per module; the boundary-condition types come from their
// registry.  tests/test_help.py checks that every option the sources read is documented.
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
