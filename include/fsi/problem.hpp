// The nonlinear problem of one time step and the generalized-alpha time integrator around it.
// Unknown U = (v, p) at t_{n+1}; history V_n = U_n, A_n = dU/dt at t_n (paper eq. 9) and the
// solid displacement D_n (Newmark update, step_context.hpp):
//   a_{n+1} = (v_{n+1} - v_n) / (gamma dt) - (1 - gamma) / gamma a_n,
//   alpha_m = (3 - rho_inf) / (2 (1 + rho_inf)), alpha_f = 1 / (1 + rho_inf),
//   gamma = 1/2 + alpha_m - alpha_f  (second order, rho_inf in [0, 1]).
// Newton (SNES) solves R(U) = 0 with our assembled exact Jacobian; every solver choice is a PETSc
// option.  Dirichlet dofs are rows u - g = 0 with identity Jacobian rows.
#pragma once
#include "fsi/analytic.hpp"
#include "fsi/boundary.hpp"
#include "fsi/fluid.hpp"
#include "fsi/fluid_solid_split.hpp"
#include "fsi/mesh_motion.hpp"
#include "fsi/pcd.hpp"
#include "fsi/physics_module.hpp"
#include "fsi/space.hpp"
#include <memory>
#include <vector>

namespace fsi {

struct TimeParams {
  bool steady = false;
  double dt = 1, t_end = 1, rho_inf = 0.5;
  long max_steps = 1;
  static TimeParams from_options();
};

struct StepStats {
  PetscInt newton = 0, krylov = 0;
  int geometry_iterations = 0; // extra solves on an updated mesh (geometry implicit)
  double geometry_change = 0;  // last relative mesh change
  SNESConvergedReason reason = SNES_CONVERGED_ITERATING;
};

struct CostCounters {
  long residuals = 0, jacobians = 0;
  double residual_time = 0, jacobian_time = 0, nonlinear_solve_time = 0, mesh_motion_time = 0;
};

class Problem {
public:
  Problem(const Space &space, const TimeParams &tp);
  ~Problem();
  void add_module(std::unique_ptr<PhysicsModule> m) { modules_.push_back(std::move(m)); }
  void set_boundaries(Boundaries *b) { bcs_ = b; }
  // Mesh motion (may be null) and the fluid cells whose quality is checked each step:
  // -ale_min_jacobian (default 0) and -ale_max_skewness (default 0.99) stop the run;
  // -ale_geometry_iterations N (default 0: geometry lagged, as the paper) re-solves the step on
  // the mesh moved by the new solid displacement until it changes by < -ale_geometry_rtol.
  void set_mesh_motion(std::unique_ptr<MeshMotion> m, const std::vector<PetscInt> *fluid_cells);
  const MeshQuality &mesh_quality_last() const { return quality_; }
  void set_exact(const ExactFlow *e) { exact_ = e; }
  // With a field split, give the velocity block the rigid-body modes as near null space.
  void set_rigid_body_modes(bool on) { rigid_modes_ = on; }
  // F_p and M_p of the pcd Schur preconditioner (pcd.hpp), assembled with each Jacobian.
  void set_pcd(std::unique_ptr<PcdOperators> p) { pcd_ = std::move(p); }
  // Velocity block split into fluid and solid (fluid_solid_split.hpp), set up on the first
  // Jacobian.
  void set_fluid_solid_split(std::unique_ptr<FluidSolidSplit> s) { split_ = std::move(s); }
  void setup_solver(); // after modules and boundaries

  // Initial state at t = 0: rest, or the exact flow (-ic rest|exact).
  void initialize(const std::string &ic);
  // Advance one step of size dt (or solve the steady problem).  Returns Newton statistics.
  StepStats step();
  // ts_scheme steady: load steps of size dt over [0, ts_max_time]; the unknown's velocity part
  // is then the displacement rate of the solid (u_{n+1} = u_n + dt v).

  // Step size of the next step (step control may cut it; the scene's is time_params().dt).
  void set_dt(double dt);
  double dt() const { return dt_; }
  // State for checkpoints: V_n, A_n, D_n (the solution of the last step is V_n) and the mesh
  // displacement (3 per local vertex); restore() resumes from them at (t, n).
  std::vector<Vec> state_vectors() const { return {Vn_, An_, Dn_}; }
  const std::vector<double> &mesh_displacement() const { return dn_; }
  void restore(double t, long n, const std::vector<double> &dn);

  double time() const { return t_; }
  long step_index() const { return n_; }
  Vec solution() const { return U_; }
  // Local (ghosted) copy of the solution, and the current vertex coordinates X + d_m(t).
  void solution_local(Vec &loc) const;
  const std::vector<double> &coordinates() const { return Xn_; }
  // The pressure unknown of the last step is the multiplier of the momentum balance at
  // t_{n+alpha_f} on that configuration: compare it there (second order in time).
  const std::vector<double> &coordinates_af() const { return Xaf_.empty() ? Xn_ : Xaf_; }
  double time_af() const { return ctx_.t_af; }
  const std::vector<std::unique_ptr<PhysicsModule>> &modules() const { return modules_; }
  const MeshMotion *mesh_motion() const { return motion_.get(); }
  const CostCounters &cost() const { return cost_; }
  const TimeParams &time_params() const { return tp_; }

  // Local copy of the solid displacement at the current time (velocity dofs).
  void displacement_local(Vec &loc) const;

  // SNES callbacks; residual() returns false where a solid element inverted.
  bool residual(Vec U, Vec F);
  void jacobian(Vec U, Mat J);

private:
  void create_matrix();
  void mesh_at(double t, std::vector<double> &disp) const;
  void set_context(double t_np1);
  void displacement_to_velocity_values(double t_np1);
  void displacement_np1_local(Vec U, Vec loc);
  void set_geometry(const std::vector<double> &dnp1);
  void move_mesh(double t_np1, Vec U, std::vector<double> &d);
  void check_mesh(const char *when, long step);
  const Space &space_;
  TimeParams tp_;
  double dt_;
  double alpha_m_ = 1, alpha_f_ = 1, gamma_ = 1, beta_ = 0.25;
  std::vector<std::unique_ptr<PhysicsModule>> modules_;
  Boundaries *bcs_ = nullptr;
  std::unique_ptr<MeshMotion> motion_;
  std::unique_ptr<PcdOperators> pcd_;
  std::unique_ptr<FluidSolidSplit> split_;
  const ExactFlow *exact_ = nullptr;

  Vec U_ = nullptr, Vn_ = nullptr, An_ = nullptr, F_ = nullptr, Dn_ = nullptr, work_ = nullptr;
  Vec Uloc_ = nullptr, Vloc_ = nullptr, Aloc_ = nullptr, Floc_ = nullptr, Dloc_ = nullptr,
      Sloc_ = nullptr;
  const std::vector<PetscInt> *fluid_cells_ = nullptr;
  MeshQuality quality_;
  int geometry_iterations_ = 0;
  double geometry_rtol_ = 1e-6, min_jacobian_ = 0, max_skewness_ = 0.99;
  Mat J_ = nullptr;
  SNES snes_ = nullptr;
  double t_ = 0;
  long n_ = 0;
  bool inverted_ = false;
  bool rigid_modes_ = false; // a residual of this step's Newton met an inverted solid element
  std::vector<double> dn_, dnp1_, Xn_, Xaf_, Xnp1_, W_;
  std::vector<std::pair<PetscInt, double>> bc_values_, disp_values_;
  StepContext ctx_;
  CostCounters cost_;
};

} // namespace fsi
