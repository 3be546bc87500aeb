// A monitor: columns of monitor.csv filled after each accepted step from a narrow view of the
// step (the fields, the mesh, the time), not from the Simulation that owns it.  The kinds a
// scene can switch on are registered by name in src/post/registry.cpp, the way boundary
// conditions are; each is built only when the scene's options ask for it.  A new monitor: one
// class with its make_ function, and one line there.
#pragma once
#include "fsi/analytic/analytic.hpp"
#include "fsi/analytic/exact_solid.hpp"
#include "fsi/discretization/space.hpp"
#include "fsi/io/output.hpp"
#include "fsi/io/run_state.hpp"
#include "fsi/post/monitor_row.hpp"
#include "fsi/scene/option_doc.hpp"
#include <memory>
#include <string>
#include <vector>

namespace fsi {

class ContactModule;
class FluidModule;
class SolidModule;

// What a monitor reads after a step.  Arrays over this rank's local dofs (ghosts included).
struct FieldView {
  const PetscScalar *u = nullptr; // the solution: fluid velocity and pressure, solid velocity
  const PetscScalar *d = nullptr; // the solid displacement (null without a solid)
  const std::vector<double> *x = nullptr;    // vertex coordinates at t (current mesh)
  const std::vector<double> *x_af = nullptr; // at t_{n+alpha_f}, where the pressure lives
  double t = 0, t_af = 0;
};

class Monitor {
public:
  virtual ~Monitor() = default;
  // Its columns, and with row.wants_values() their values read from `view`.
  virtual void add_to(MonitorRow &row, const FieldView &view) = 0;
  // Before the row of an accepted step of length dt (running averages).
  virtual void update(const FieldView &, double /*dt*/) {}
  // With the field files of step `step` at time t.
  virtual void write(long /*step*/, double /*t*/) {}
  virtual void close() {}
  // Its checkpoint keys: what it carries over a restart or a remesh.
  virtual void save(RunState &) const {}
  virtual void load(const RunState &) {}
  // Its part of summary.json (`stepped`: at least one step was taken).
  virtual void summarize(Json &, bool /*stepped*/) const {}
};

// What a monitor may be built from.
struct MonitorSetup {
  const Mesh &mesh;
  const Space &space;
  const FluidModule *fluid = nullptr;
  const SolidModule *solid = nullptr;
  ContactModule *contact = nullptr; // not const: asking who touches re-bins its surface
  const ExactFlow *exact = nullptr;
  const ExactSolid *exact_solid = nullptr;
  std::string out_dir, hemo_base; // output folder; the wall-shear file's name
  double t_end = 0;
  const std::vector<double> &material_X;
};

// Null when the scene does not ask for the monitor (its options then still read, so that a
// misspelt one is reported).
using MonitorFactory = std::unique_ptr<Monitor> (*)(const MonitorSetup &);
struct MonitorType {
  const char *name, *help;
  MonitorFactory make;
  OptionSection (*options)(); // its options, declared next to their reader
};
// Every registered kind, in monitor.csv's column order (src/post/registry.cpp).
const std::vector<MonitorType> &monitor_types();

} // namespace fsi
