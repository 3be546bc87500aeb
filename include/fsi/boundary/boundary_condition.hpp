// One boundary condition on one named boundary (physical surface).  A BC type is one file under
// src/boundary/ that derives from BoundaryCondition and is registered by name in
// src/boundary/registry.cpp (one line); the scene picks it with -bc_<name>_type TYPE.
// A type fixes velocity components on its nodes (Dirichlet: values at t_{n+1} on the nodes'
// current positions, or displacements imposed through the Newmark relation), adds a boundary
// residual and its Jacobian (tractions at t_{n+alpha_f}), or both.  Its options are read once
// at construction, so profiles and waveforms are resolved before any node loop.
#pragma once
#include "fsi/analytic/analytic.hpp"
#include "fsi/analytic/exact_solid.hpp"
#include "fsi/discretization/p2tet.hpp"
#include "fsi/discretization/space.hpp"
#include "fsi/mesh/mesh.hpp"
#include "fsi/time/step_context.hpp"
#include <array>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace fsi {

// What a BC type may use when it is built.
struct BoundarySetup {
  const Mesh &mesh;
  const Space &space;
  const ExactFlow *exact;                // -exact_solution, or null
  const ExactSolid *exact_solid;         // -exact_displacement, or null
  double mu, rho;                        // the fluid's (0 without a fluid)
  const std::vector<double> &material_X; // the solid's material reference, 3 per local vertex
  std::string name;                      // the boundary's physical name
  std::string prefix() const { return "bc_" + name + "_"; }
};

class BoundaryCondition {
public:
  // Which kind of nodal data a Dirichlet type prescribes.
  enum class Data { none, velocity, displacement };
  // Which type wins at a node that two Dirichlet boundaries fix in the same component: the
  // higher precedence (a wall holds its nodes), then the boundary listed first in -bc_names.
  enum Precedence { prescribed = 1, wall = 2 };

  BoundaryCondition(const BoundarySetup &s, Data data, bool dirichlet_default, bool faces);
  virtual ~BoundaryCondition() = default;
  virtual std::string type() const = 0;
  const std::string &name() const { return name_; }
  Data data() const { return data_; }
  virtual int precedence() const { return prescribed; }
  // Velocity (data velocity, at node position x) or displacement (data displacement, at the
  // node's material position x) at time t; only the fixed components are used.
  virtual void value(const double x[3], double t, double v[3]) const { v[0] = v[1] = v[2] = 0; }
  // Called on every rank before value() at time t with node positions X (3 per local vertex):
  // a type whose values depend on an integral over its boundary (a flow rate) computes it here.
  // setter[dof]: the index of the BC that sets each local dof (-1: none), `self` this one's;
  // others(k, x, v): the values of BC k at x.
  using OtherValues = std::function<void(int, const double *, double *)>;
  virtual void prepare_values(double t, const double *X, const std::vector<int> &setter, int self,
                              const OtherValues &others) {}
  // Boundary terms of the momentum residual and their Jacobian.
  virtual void add_residual(const StepContext &ctx, PetscScalar *F) const {}
  virtual void add_jacobian(const StepContext &ctx, Mat J) const {}
  // Does it fix the fluid's pressure level (a traction boundary)?
  virtual bool fixes_pressure_level() const { return false; }
  // A lumped (0D) model coupled to the boundary (a Windkessel): its state advances after each
  // accepted step, is saved in checkpoints and carried into rebuilt runs (keys prefixed with
  // the boundary's name), and monitored.
  virtual void accept_step() {}
  virtual void save_state(std::map<std::string, double> &) const {}
  virtual void restore_state(const std::map<std::string, double> &) {}
  virtual std::vector<std::string> monitor_columns() const { return {}; }
  virtual std::vector<double> monitor_values() const { return {}; }
  // A type that reacts to a monitored quantity (a flow that stops when the valve has closed)
  // finds its column in the run's monitor columns, once after setup (an unknown column is an
  // InputError), then sees each accepted step's monitor row at its end time t (same order).
  virtual void bind_monitors(const std::vector<std::string> &columns) {}
  virtual void observe(double t, const std::vector<double> &row) {}
  // Global velocity dofs that its Jacobian couples all with all (same list on every rank).
  virtual std::vector<PetscInt> dense_coupling() const { return {}; }

  bool fixed(int component) const { return fixed_[component]; }
  const std::vector<DofNode> &nodes() const { return nodes_; }
  const std::vector<BoundaryFace> &faces() const { return faces_; }

protected:
  std::string name_;
  Data data_;
  bool fixed_[3] = {false, false, false};
  std::vector<DofNode> nodes_;
  std::vector<BoundaryFace> faces_;
};

using BoundaryFactory = std::unique_ptr<BoundaryCondition> (*)(const BoundarySetup &);
struct BoundaryType {
  const char *name, *physics, *help;
  BoundaryFactory make;
};
// Every registered type (src/boundary/registry.cpp).
const std::vector<BoundaryType> &boundary_types();

// Helpers shared by the types.
void read_direction(const std::string &option, double dir[3]); // unit vector from x,y,z
std::array<double, 3> read_point(const std::string &option);   // x,y,z
// Squared distance of x from the axis through `center` along the unit vector `dir`.
double axis_distance2(const double x[3], const std::array<double, 3> &center,
                      const std::array<double, 3> &dir);
// value * waveform(t) * direction from -<prefix>value, _direction and the waveform options.
std::function<void(const double *, double, double *)> uniform_profile(const std::string &prefix);
// Sum -w N_a t(x) over a fluid face on the configuration X_af (t from `traction`), plus the
// backflow term beta rho/2 min(v.n, 0) v when beta > 0; into F (local).
void add_fluid_face_traction(
    const BoundaryFace &f, const StepContext &ctx, const QuadRule &rule, double beta, double rho,
    const std::function<void(const double x[3], const double n[3], double t[3])> &traction,
    PetscScalar *F);

// The uniform pressure traction -p n over `faces`, with that backflow term.
void add_fluid_pressure(const std::vector<BoundaryFace> &faces, const StepContext &ctx,
                        const QuadRule &rule, double beta, double rho, double p, PetscScalar *F);

// Jacobian of that backflow term, d/dv [-(beta rho/2) min(v.n, 0) v], over `faces` (none for
// beta = 0).
void add_backflow_jacobian(const std::vector<BoundaryFace> &faces, const StepContext &ctx,
                           const QuadRule &rule, double beta, double rho, Mat J);

// Add an 18 x 18 block K (6 face nodes x 3 components, row-major) into J, rows of Dirichlet
// dofs (mask) skipped.
void add_face_block(Mat J, const BoundaryFace &f, const std::vector<char> &mask,
                    const double K[18][18]);

} // namespace fsi
