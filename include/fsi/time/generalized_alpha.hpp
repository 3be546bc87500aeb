// Generalized-alpha time integration (paper eq. 9; Chung-Hulbert / Jansen-Whiting-Hulbert):
// the coefficients, the history (V_n = U_n, A_n = dU/dt at t_n, the solid displacement D_n),
// the predictor, the Newmark displacement and the update after a converged step.
//   a_{n+1} = (v_{n+1} - v_n) / (gamma dt) - (1 - gamma) / gamma a_n,
//   u_{n+1} = u_n + dt v_n + dt^2 [(1/2 - beta) a_n + beta a_{n+1}],
//   alpha_m = (3 - rho_inf) / (2 (1 + rho_inf)), alpha_f = 1 / (1 + rho_inf),
//   gamma = 1/2 + alpha_m - alpha_f, beta = (1 + alpha_m - alpha_f)^2 / 4 (second order).
// Static mode (-ts_type steady) reads the unknown as a displacement rate over a load step:
// u_{n+1} = u_n + dt v, no inertia.  Kernels see stage values and shift coefficients through
// StepContext (step_context.hpp), which this object fills.
// Options: -ts_type alpha|steady, -ts_dt [s], -ts_max_steps, -ts_max_time [s],
// -ts_alpha_radius (rho_inf in [0, 1], default 0.5); they mean what PETSc's TS means by them.
#pragma once
#include "fsi/discretization/space.hpp"
#include "fsi/time/step_context.hpp"
#include <vector>

namespace fsi {

struct TimeParams {
  bool steady = false;
  double dt = 1, t_end = 1, rho_inf = 0.5;
  long max_steps = 1;
  // With error-controlled steps (-ts_adapt_type error) the step count is not known from dt:
  // -ts_max_steps given with -ts_max_time then stops the run after that step (0: no cap).
  long step_cap = 0;
  // Newton's first iterate: V_n (constant, the default) or V_n + dt A_n (extrapolated,
  // -ts_predictor extrapolated): first order in dt closer, so that one Newton iteration can meet a
  // relative tolerance that two needed.
  bool extrapolate = false;
  static TimeParams from_options();
};

class GeneralizedAlpha {
public:
  GeneralizedAlpha(const Space &space, const TimeParams &tp);
  ~GeneralizedAlpha();
  GeneralizedAlpha(const GeneralizedAlpha &) = delete;
  GeneralizedAlpha &operator=(const GeneralizedAlpha &) = delete;

  const TimeParams &params() const { return tp_; }
  double time() const { return t_; }
  long step_index() const { return n_; }
  double dt() const { return dt_; }
  void set_dt(double dt) { dt_ = dt; }
  double alpha_f() const { return alpha_f_; }
  // Numerical damping from the next step on (the scheme's spectral radius rho_inf in [0, 1]).
  void set_rho_inf(double rho_inf);
  // t_{n+alpha_f} of the step being solved (t_{n+1} in static mode).
  double stage_time() const { return tp_.steady ? t_ + dt_ : t_ + alpha_f_ * dt_; }

  // History at t_n: V_n (the last solution), A_n, D_n (global vectors).
  Vec velocity() const { return Vn_; }
  Vec acceleration() const { return An_; }
  Vec displacement() const { return Dn_; }
  void set_time(double t, long n) { t_ = t, n_ = n; }

  // Start of a step: local copies of the history and the predictor U = V_n (or V_n + dt A_n).
  void predict(Vec U);
  // Time part of the kernels' context for the step t_n -> t_n + dt (history arrays included).
  void fill_context(StepContext &ctx) const;
  void release_context(StepContext &ctx) const;
  // Solid displacement u_{n+1}(U) as a local (ghosted) vector.
  void displacement_np1_local(Vec U, Vec loc);
  // For each (local dof i, displacement g): append (i, v_{n+1}) such that u_{n+1} = g.
  void velocities_for_displacements(const std::vector<std::pair<PetscInt, double>> &g,
                                    std::vector<std::pair<PetscInt, double>> &out) const;
  // After a converged step: A_{n+1}, D_{n+1} by Newmark, V_{n+1} = U, t += dt.
  void advance(Vec U);
  // Local error estimate of the step to U (before advance): max over the dofs in `is` of
  // |U - (V_n + dt A_n)| / (atol + rtol max|U|), the corrector against an explicit predictor.
  // rms: the root mean square over the dofs instead of the largest (-ts_adapt_wnormtype 2).
  double error_estimate(Vec U, IS is, double atol, double rtol, bool rms = false) const;

private:
  const Space &space_;
  TimeParams tp_;
  double dt_, t_ = 0;
  long n_ = 0;
  double alpha_m_ = 1, alpha_f_ = 1, gamma_ = 1, beta_ = 0.25;
  Vec Vn_ = nullptr, An_ = nullptr, Dn_ = nullptr, work_ = nullptr;
  Vec Vloc_ = nullptr, Aloc_ = nullptr, Dloc_ = nullptr;
};

} // namespace fsi
