#include "fsi/run/help.hpp"
#include "fsi/boundary/boundary_condition.hpp"
#include "fsi/physics/physics_registry.hpp"
#include "fsi/post/monitor.hpp"
#include "fsi/run/simulation.hpp"
#include "fsi/scene/option_doc.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace fsi {

bool wants_help() {
  PetscBool h = PETSC_FALSE, h2 = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, "-help", &h);
  PetscOptionsHasName(nullptr, nullptr, "-h", &h2);
  return h || h2;
}

int print_help(MPI_Comm comm) {
  PetscPrintf(comm, "fsi_app: monolithic ALE fluid-structure interaction (P2P1 Navier-Stokes, "
                    "hyperelastic solid, generalized-alpha, Newton).\n"
                    "usage: mpirun -n 2 fsi_app -options_file scene.opts [-options_file "
                    "petsc_options/preset.opts] [-option value ...]\n"
                    "Every option: -name <default> [unit] meaning.  SI units throughout.\n");
  // Each part's declared options (option_doc.hpp), in the order a scene file is written.
  std::vector<OptionSection> sections = {scene_options(), mesh_options(), time_options()};
  for (auto &t : physics_types())
    sections.push_back(t.options());
  sections.push_back(ale_options());
  sections.push_back(boundary_options());
  for (auto &t : monitor_types())
    sections.push_back(t.options());
  for (auto f : {exact_flow_options, exact_solid_options, solver_options})
    sections.push_back(f());
  for (auto &sec : sections) {
    PetscPrintf(comm, "\n%s:\n", sec.title);
    for (auto &o : sec.options)
      PetscPrintf(comm, "  -%-30s <%s> [%s] %s\n", o.name, o.def, o.unit, o.meaning);
  }
  PetscPrintf(comm, "\nPhysics (-physics a,b,...):\n");
  for (auto &t : physics_types()) {
    std::string needs;
    for (const char *n : t.needs)
      needs += (needs.empty() ? " (needs " : ", ") + std::string(n);
    if (!needs.empty()) needs += ")";
    PetscPrintf(comm, "  %-20s %s%s\n", t.name, t.help, needs.c_str());
  }
  PetscPrintf(comm, "\nMonitors (on when their options are given):\n");
  for (auto &t : monitor_types())
    PetscPrintf(comm, "  %-20s %s\n", t.name, t.help);
  PetscPrintf(comm, "\nBoundary-condition types (-bc_<b>_type):\n");
  for (auto &t : boundary_types())
    PetscPrintf(comm, "  %-20s (%s) %s\n", t.name, t.physics, t.help);
  return 0;
}

void print_run_header(MPI_Comm comm, const Scene &scene, const Mesh &mesh, const Simulation &sim) {
  int size;
  MPI_Comm_size(comm, &size);
  const Space &space = sim.space();
  PetscPrintf(comm,
              "fsi_app: scene '%s', %d rank(s), mesh %s: %d cells, %d vertices; dofs velocity %d, "
              "pressure %d\n",
              scene.name.c_str(), size, mesh.source.c_str(), (int)mesh.cells_global,
              (int)mesh.vertices_global, (int)space.n_velocity, (int)space.n_pressure);
  const PartitionQuality &pq = mesh.partition;
  if (size > 1 && pq.edge_cut >= 0)
    PetscPrintf(comm,
                "  partition: %s, %ld of %ld cell faces cut (%.2f %%), largest part %.3f x mean\n",
                pq.method.c_str(), pq.edge_cut, pq.faces,
                100.0 * pq.edge_cut / std::max(1L, pq.faces), pq.imbalance);
  for (auto &m : sim.system().modules())
    PetscPrintf(comm, "  physics: %s on %d local cells (rank 0)\n", m->name().c_str(),
                (int)m->n_cells());
}

} // namespace fsi
