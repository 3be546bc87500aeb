#include "fsi/time/generalized_alpha.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <cmath>

namespace fsi {

TimeParams TimeParams::from_options() {
  TimeParams tp;
  tp.steady = opt::choice("ts_type", "alpha", {"alpha", "steady"}) == "steady";
  if (tp.steady) { // load steps over the pseudo-time [0, ts_max_time]
    tp.t_end = opt::positive("ts_max_time", 1.0);
    tp.max_steps = opt::integer("ts_max_steps", 1);
    if (tp.max_steps < 1) throw InputError("option -ts_max_steps must be >= 1");
    tp.dt = tp.t_end / tp.max_steps;
    return tp;
  }
  tp.dt = opt::positive("ts_dt", 1e-3);
  tp.extrapolate =
      opt::choice("ts_predictor", "constant", {"constant", "extrapolated"}) == "extrapolated";
  tp.rho_inf = opt::real("ts_alpha_radius", 0.5);
  if (tp.rho_inf < 0 || tp.rho_inf > 1)
    throw InputError("option -ts_alpha_radius (spectral radius rho_inf) must be in [0, 1]");
  // -ts_max_steps, when given, wins over the scene's -ts_max_time (handy to shorten a run).
  const bool by_time = opt::has("ts_max_time");
  const double t_end = by_time ? opt::positive("ts_max_time", 1.0) : 0.0;
  const bool adaptive = opt::choice("ts_adapt_type", "cut", {"cut", "error", "none"}) == "error";
  if (adaptive && by_time && opt::has("ts_max_steps")) {
    tp.t_end = t_end;
    tp.max_steps = tp.step_cap = opt::integer("ts_max_steps", 1);
    if (tp.step_cap < 1) throw InputError("option -ts_max_steps must be >= 1");
  } else if (opt::has("ts_max_steps") || !by_time) {
    tp.max_steps = opt::integer("ts_max_steps", 10);
    if (tp.max_steps < 1) throw InputError("option -ts_max_steps must be >= 1");
    tp.t_end = tp.max_steps * tp.dt;
  } else {
    tp.t_end = t_end;
    tp.max_steps = std::lround(tp.t_end / tp.dt);
    if (tp.max_steps < 1 || std::fabs(tp.max_steps * tp.dt - tp.t_end) > 1e-9 * tp.t_end)
      throw InputError("-ts_max_time is not a whole number of steps -ts_dt: adjust one of them");
  }
  return tp;
}

GeneralizedAlpha::GeneralizedAlpha(const Space &space, const TimeParams &tp)
    : space_(space), tp_(tp), dt_(tp.dt) {
  if (!tp.steady) set_rho_inf(tp.rho_inf);
  Vn_ = space.create_global();
  FSI_CALL(VecDuplicate(Vn_, &An_));
  FSI_CALL(VecDuplicate(Vn_, &Dn_));
  FSI_CALL(VecDuplicate(Vn_, &work_));
  Vloc_ = space.create_local();
  FSI_CALL(VecDuplicate(Vloc_, &Aloc_));
  FSI_CALL(VecDuplicate(Vloc_, &Dloc_));
}

// Jansen-Whiting-Hulbert parameters for the first-order (velocity) system, Newmark's beta for
// the displacement; the history (V_n, A_n, D_n) does not depend on them, so they may change
// between steps.
void GeneralizedAlpha::set_rho_inf(double r) {
  tp_.rho_inf = r;
  alpha_m_ = (3 - r) / (2 * (1 + r));
  alpha_f_ = 1 / (1 + r);
  gamma_ = 0.5 + alpha_m_ - alpha_f_;
  beta_ = 0.25 * (1 + alpha_m_ - alpha_f_) * (1 + alpha_m_ - alpha_f_);
}

GeneralizedAlpha::~GeneralizedAlpha() {
  for (Vec *v : {&Vn_, &An_, &Dn_, &work_, &Vloc_, &Aloc_, &Dloc_})
    if (*v) VecDestroy(v);
}

void GeneralizedAlpha::predict(Vec U) {
  space_.to_local(Vn_, Vloc_);
  space_.to_local(An_, Aloc_);
  space_.to_local(Dn_, Dloc_);
  FSI_CALL(VecCopy(Vn_, U));
  if (tp_.extrapolate) FSI_CALL(VecAXPY(U, dt_, An_));
}

void GeneralizedAlpha::fill_context(StepContext &ctx) const {
  ctx.t_n = t_;
  ctx.dt = dt_;
  ctx.t_np1 = t_ + dt_;
  ctx.steady = tp_.steady;
  ctx.alpha_m = alpha_m_;
  ctx.alpha_f = alpha_f_;
  ctx.gamma = gamma_;
  ctx.beta = beta_;
  ctx.t_af = stage_time();
  FSI_CALL(VecGetArrayRead(Vloc_, &ctx.Vn));
  FSI_CALL(VecGetArrayRead(Aloc_, &ctx.An));
  FSI_CALL(VecGetArrayRead(Dloc_, &ctx.Dn));
}

void GeneralizedAlpha::release_context(StepContext &ctx) const {
  FSI_CALL(VecRestoreArrayRead(Vloc_, &ctx.Vn));
  FSI_CALL(VecRestoreArrayRead(Aloc_, &ctx.An));
  FSI_CALL(VecRestoreArrayRead(Dloc_, &ctx.Dn));
}

void GeneralizedAlpha::displacement_np1_local(Vec U, Vec loc) {
  const double dt = dt_;
  FSI_CALL(VecCopy(Dn_, work_));
  if (tp_.steady) {
    FSI_CALL(VecAXPY(work_, dt, U));
  } else {
    // u_n + dt v_n + dt^2 [(1/2 - beta) a_n + beta a_{n+1}(U)]
    const double g = gamma_;
    FSI_CALL(VecAXPY(work_, dt, Vn_));
    FSI_CALL(VecAXPY(work_, dt * dt * ((0.5 - beta_) - beta_ * (1 - g) / g), An_));
    FSI_CALL(VecAXPY(work_, dt * beta_ / g, U));
    FSI_CALL(VecAXPY(work_, -dt * beta_ / g, Vn_));
  }
  space_.to_local(work_, loc);
}

void GeneralizedAlpha::velocities_for_displacements(
    const std::vector<std::pair<PetscInt, double>> &g,
    std::vector<std::pair<PetscInt, double>> &out) const {
  if (g.empty()) return;
  const PetscScalar *v, *a, *d;
  FSI_CALL(VecGetArrayRead(Vloc_, &v));
  FSI_CALL(VecGetArrayRead(Aloc_, &a));
  FSI_CALL(VecGetArrayRead(Dloc_, &d));
  const double dt = dt_;
  for (auto &[i, gi] : g) {
    const double vi = PetscRealPart(v[i]), ai = PetscRealPart(a[i]), di = PetscRealPart(d[i]);
    out.emplace_back(
        i, tp_.steady ? (gi - di) / dt
                      : vi + gamma_ / (beta_ * dt) *
                                 (gi - di - dt * vi -
                                  dt * dt * ((0.5 - beta_) - beta_ * (1 - gamma_) / gamma_) * ai));
  }
  FSI_CALL(VecRestoreArrayRead(Vloc_, &v));
  FSI_CALL(VecRestoreArrayRead(Aloc_, &a));
  FSI_CALL(VecRestoreArrayRead(Dloc_, &d));
}

double GeneralizedAlpha::error_estimate(Vec U, IS is, double atol, double rtol, bool rms) const {
  PetscInt n, start;
  const PetscInt *idx;
  const PetscScalar *u, *v, *a;
  FSI_CALL(VecGetOwnershipRange(U, &start, nullptr));
  FSI_CALL(ISGetLocalSize(is, &n));
  FSI_CALL(ISGetIndices(is, &idx));
  FSI_CALL(VecGetArrayRead(U, &u));
  FSI_CALL(VecGetArrayRead(Vn_, &v));
  FSI_CALL(VecGetArrayRead(An_, &a));
  double m[2] = {0, 0}, sum[2] = {0, (double)n}; // max |U - predictor|, max |U|; sum of squares
  for (PetscInt k = 0; k < n; ++k) {
    const PetscInt i = idx[k] - start;
    const double ui = PetscRealPart(u[i]);
    const double e = std::fabs(ui - PetscRealPart(v[i]) - dt_ * PetscRealPart(a[i]));
    m[0] = std::max(m[0], e);
    m[1] = std::max(m[1], std::fabs(ui));
    sum[0] += e * e;
  }
  FSI_CALL(VecRestoreArrayRead(U, &u));
  FSI_CALL(VecRestoreArrayRead(Vn_, &v));
  FSI_CALL(VecRestoreArrayRead(An_, &a));
  FSI_CALL(ISRestoreIndices(is, &idx));
  double g[2], gs[2];
  MPI_Allreduce(m, g, 2, MPI_DOUBLE, MPI_MAX, PetscObjectComm((PetscObject)U));
  MPI_Allreduce(sum, gs, 2, MPI_DOUBLE, MPI_SUM, PetscObjectComm((PetscObject)U));
  const double e = rms ? std::sqrt(gs[0] / std::max(gs[1], 1.0)) : g[0];
  return e / (atol + rtol * g[1]);
}

void GeneralizedAlpha::advance(Vec U) {
  const double dt = dt_;
  if (tp_.steady) {
    FSI_CALL(VecAXPY(Dn_, dt, U)); // u_{n+1} = u_n + dt v
  } else {
    // a_{n+1} = (v_{n+1} - v_n) / (gamma dt) - (1 - gamma) / gamma a_n, then the Newmark update
    // u_{n+1} = u_n + dt v_n + dt^2 [(1/2 - beta) a_n + beta a_{n+1}].
    FSI_CALL(VecCopy(An_, work_));
    FSI_CALL(VecAXPBYPCZ(An_, 1.0 / (gamma_ * dt), -1.0 / (gamma_ * dt), -(1 - gamma_) / gamma_, U,
                         Vn_));
    FSI_CALL(VecAXPBYPCZ(Dn_, dt, dt * dt * (0.5 - beta_), 1.0, Vn_, work_));
    FSI_CALL(VecAXPY(Dn_, dt * dt * beta_, An_));
  }
  FSI_CALL(VecCopy(U, Vn_));
  t_ += dt;
  ++n_;
}

} // namespace fsi
