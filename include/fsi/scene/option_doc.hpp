// Options documented where they are read: each part declares its options (name, default, unit,
// meaning) as an OptionSection in the file that reads them, and fsi_app -help (hence
// docs/options.md, scripts/options_doc) is generated from these declarations.  The unit "-": a
// dimensionless number, a name or a switch.  tests/test_help.py checks that every option read is
// declared in its reader's folder and that literal defaults agree with the readers.
#pragma once
#include <vector>

namespace fsi {

struct OptionDoc {
  const char *name, *def, *unit, *meaning;
};
struct OptionSection {
  const char *title;
  std::vector<OptionDoc> options;
};

// The parts that are not registered by name (physics and monitors carry theirs in their
// registries: physics_registry.hpp, post/monitor.hpp).
OptionSection scene_options();       // src/run/simulation.cpp
OptionSection mesh_options();        // src/mesh/mesh.cpp
OptionSection time_options();        // src/time/step_control.cpp
OptionSection ale_options();         // src/ale/ale.cpp
OptionSection boundary_options();    // src/boundary/boundaries.cpp
OptionSection exact_flow_options();  // src/analytic/exact_flows.cpp
OptionSection exact_solid_options(); // src/analytic/exact_solid.cpp
OptionSection solver_options();      // src/problem/coupled_system.cpp

} // namespace fsi
