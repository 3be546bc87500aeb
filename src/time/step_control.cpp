#include "fsi/time/step_control.hpp"
#include "fsi/scene/option_doc.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <cmath>

namespace fsi {

// The estimate v_{n+1} - (v_n + dt a_n) = gamma dt (a_{n+1} - a_n) shrinks like dt^2: the
// controller's exponents are those of an error of order 2 (Gustafsson's PI: kI = 0.3/2,
// kP = 0.4/2; a rejection uses the plain 1/2).
static constexpr double order = 2, kI = 0.3 / order, kP = 0.4 / order;

StepControl StepControl::from_options(double nominal_dt) {
  StepControl c;
  const std::string type = opt::choice("ts_adapt_type", "cut", {"cut", "error", "none"});
  c.mode = type == "error" ? error : type == "cut" ? cut_only : none;
  c.enabled = c.mode != none;
  c.nominal = c.dt = nominal_dt;
  c.factor = opt::positive("ts_adapt_scale_solve_failed", 0.5);
  if (c.factor >= 1)
    throw InputError("option -ts_adapt_scale_solve_failed must be in (0, 1), e.g. 0.5");
  c.dt_min = opt::positive("ts_adapt_dt_min", nominal_dt / 1000);
  if (c.dt_min > nominal_dt)
    throw InputError("option -ts_adapt_dt_min is larger than the time step -ts_dt");
  c.grow_after = opt::integer_at_least("step_grow_after", 3, 1);
  c.easy_newton = opt::integer_at_least("step_easy_newton", 4, 1);
  // -ts_adapt_switch_when: cut mode, error control while a monitor condition holds.
  const bool switch_given = opt::has("ts_adapt_switch_when");
  c.switchable = c.mode == cut_only && switch_given;
  if (switch_given && c.mode != cut_only)
    throw InputError("option -ts_adapt_switch_when needs -ts_adapt_type cut (the default): it "
                     "switches error control on while its condition holds");
  if (c.mode == error || c.switchable) {
    c.tol.rtol = opt::positive("ts_rtol", 0.01);
    c.tol.atol = opt::positive("ts_atol", 1e-3);
    c.tol.rms = opt::choice("ts_adapt_wnormtype", "infinity", {"infinity", "2"}) == "2";
    c.dt_max = opt::positive("ts_adapt_dt_max", 10 * nominal_dt);
    if (c.dt_max < nominal_dt)
      throw InputError("option -ts_adapt_dt_max is smaller than the time step -ts_dt");
    c.safety = opt::positive("ts_adapt_safety", 0.9);
    c.max_rejections = opt::integer_at_least("ts_adapt_max_rejections", 5, 0);
    if (c.safety > 1) throw InputError("option -ts_adapt_safety must be in (0, 1], e.g. 0.9");
    c.period = opt::nonnegative("ts_adapt_period", 0.0);
    if (c.period > 0 && c.period < c.dt_max)
      throw InputError("option -ts_adapt_period (the cycle length to land on) is shorter than "
                       "the largest step -ts_adapt_dt_max");
  } else if (opt::has("ts_adapt_period"))
    throw InputError("option -ts_adapt_period needs error-controlled steps (-ts_adapt_type error "
                     "or -ts_adapt_switch_when)");
  return c;
}

// Periods are counted with a relative slack of 1e-9 so that a step that landed on k T, to
// rounding, counts as being there.
double StepControl::landing(double t) const {
  if (mode != error || period <= 0) return dt;
  const double next = (std::floor(t / period + 1e-9) + 1) * period;
  return next - t < dt * (1 - 1e-9) ? next - t : dt;
}

bool StepControl::period_start(double t) const {
  if (period <= 0) return false;
  const double k = std::round(t / period);
  return k >= 1 && std::abs(t / period - k) < 1e-9;
}

void StepControl::set_error_control(bool on) {
  if (!switchable || on == (mode == error)) return;
  mode = on ? error : cut_only;
  error_prev = 0; // the PI memory starts afresh
  easy_run = 0;
  if (!on) dt = std::min(dt, nominal); // back to the scene's step at once
}

bool StepControl::cut() {
  easy_run = 0;
  if (!enabled || dt * factor < dt_min * (1 - 1e-12)) return false;
  dt *= factor;
  ++cuts;
  return true;
}

bool StepControl::reject(double e) {
  const double f = std::clamp(safety * std::pow(e, -1 / order), 0.1, 0.9);
  if (dt * f < dt_min * (1 - 1e-12)) return false;
  dt *= f;
  ++rejections;
  ++step_rejections;
  return true;
}

void StepControl::accepted(long newton, double e) {
  dt_smallest = dt_smallest > 0 ? std::min(dt_smallest, dt) : dt;
  dt_largest = std::max(dt_largest, dt);
  if (mode == error) {
    step_rejections = 0;
    if (e > 1) ++accepted_above;
    if (e < 0) return; // no estimate (first step, first on a new mesh): keep dt
    e = std::max(e, 1e-8);
    double f = safety * std::pow(e, -kI) * (error_prev > 0 ? std::pow(error_prev / e, kP) : 1.0);
    error_prev = e;
    f = std::clamp(f, 0.2, 2.0);
    // Small growth is not worth it: an unchanged dt keeps a lagged preconditioner valid.
    if (f >= 1 && f < 1.2) return;
    const double next = std::clamp(dt * f, dt_min, dt_max);
    if (next > dt) ++grows;
    dt = next;
    return;
  }
  if (dt >= nominal) return;
  easy_run = newton <= easy_newton ? easy_run + 1 : 0;
  if (easy_run < grow_after) return;
  dt = std::min(nominal, dt / factor);
  easy_run = 0;
  ++grows;
}

// Its options, for -help and docs/options.md (option_doc.hpp).
OptionSection time_options() {
  return {
      "Time integration (PETSc TS names)",
      {{"ts_type", "alpha", "-", "alpha (generalized-alpha) | steady (static load steps)"},
       {"ts_dt", "1e-3", "s", "time step"},
       {"ts_max_steps", "10 (alpha), 1 (steady)", "-",
        "number of steps (wins over ts_max_time; with -ts_adapt_type error: the last step)"},
       {"ts_max_time", "", "s", "end time (a whole number of steps)"},
       {"ts_alpha_radius", "0.5", "-", "spectral radius rho_inf in [0, 1]"},
       {"ts_alpha_radius_switch_when", "", "-",
        "COLUMN<VALUE or COLUMN>VALUE on a monitor.csv column or time: after a step where it "
        "holds "
        "rho_inf is -ts_alpha_radius_switch_to, after one where it does not -ts_alpha_radius"},
       {"ts_alpha_radius_switch_to", "0", "-", "rho_inf after the switch, in [0, 1]"},
       {"ts_predictor", "constant", "-",
        "Newton's first iterate: constant (V_n) | extrapolated (V_n + dt A_n)"},
       {"ts_adapt_type", "cut", "-",
        "cut: retry a failed step with a smaller dt | error: also choose dt by a local error "
        "estimate (PI controller) | none"},
       {"ts_rtol", "0.01", "-", "error: relative tolerance on the velocity's local error"},
       {"ts_atol", "1e-3", "m/s", "error: absolute tolerance on the velocity's local error"},
       {"ts_adapt_wnormtype", "infinity", "-",
        "error: norm of the local error over the velocity dofs, infinity (largest) | 2 (root "
        "mean square)"},
       {"ts_adapt_switch_when", "", "-",
        "COLUMN<VALUE or COLUMN>VALUE (with -ts_adapt_type cut): after a step where it holds dt "
        "is chosen by the error estimate (-ts_rtol, -ts_atol, ...), after one where it does not "
        "it is -ts_dt"},
       {"ts_adapt_dt_max", "10 ts_dt", "s", "error: largest step"},
       {"ts_adapt_period", "0 (none)", "s",
        "error: steps land on every multiple of it (a cardiac cycle's start); with "
        "-ts_adapt_switch_when each new period starts at -ts_dt"},
       {"ts_adapt_safety", "0.9", "-", "error: safety factor of the step-size controller"},
       {"ts_adapt_max_rejections", "5", "-", "error: rejections of one step before it is taken"},
       {"ts_adapt_scale_solve_failed", "0.5", "-", "dt factor after a failed step, in (0, 1)"},
       {"ts_adapt_dt_min", "dt/1000", "s", "below this step size the run stops (exit 3)"},
       {"step_grow_after", "3", "steps", "easy steps before dt grows back by 1/factor"},
       {"step_easy_newton", "4", "-", "a step with at most this many Newton iterations is easy"}}};
}

} // namespace fsi
