// Step-size control (-ts_adapt_type cut|error|none, default cut).
//   cut:   a step whose Newton diverges or whose solid element would invert is retried from the
//          last converged state with dt <- -ts_adapt_scale_solve_failed dt (default 0.5); after
//          -step_grow_after consecutive easy steps (Newton <= -step_easy_newton) dt grows back by
//          1 / cut_factor, never above the scene's dt.
//   error: the same retry on failure, and dt chosen by a local error estimate: the velocity
//          unknowns' distance between the corrector v_{n+1} and the explicit predictor
//          v_n + dt a_n, in the max norm over atol + rtol max|v| (-ts_atol, -ts_rtol); a step
//          above 1 is rejected and retried smaller, an accepted one sets the next dt with a PI
//          controller, between -ts_adapt_dt_min and -ts_adapt_dt_max.  A step rejected
//          -ts_adapt_max_rejections times (default 5) is taken as it is (counted): where the
//          estimate is noise (it stops shrinking with dt) it would otherwise drive dt to dt_min.
// -ts_adapt_switch_when COND (with cut): error control while a monitor condition holds (e.g. the
// valve's quiet diastole), cut mode with the scene's dt otherwise; dt returns to -ts_dt at once
// when the condition stops holding.
// -ts_adapt_period T (s, default 0: none): error-controlled steps land on every multiple of T
// (a cardiac cycle's start), and a switched run starts each new period at the scene's dt: a long
// diastolic step never crosses into the next systole.
// Below -ts_adapt_dt_min (default dt / 1000) the run stops: checkpoint, reason, non-zero exit.
// Steps that end on a distorted fluid mesh are not retried (a smaller step does not help there),
// except on a mesh just remeshed, whose first step would distort it: retried with a cut step.
#pragma once
#include "fsi/common.hpp"

namespace fsi {

// Tolerances of the error estimate, handed to the step that computes it.
struct StepErrorTolerance {
  double atol = 0, rtol = 0;
  bool rms = false;        // -ts_adapt_wnormtype 2: root mean square, else the max norm
  bool accept_any = false; // the step was rejected -ts_adapt_max_rejections times: take it
};

struct StepControl {
  enum Mode { none, cut_only, error } mode = cut_only;
  bool enabled = true;     // failed steps are retried (cut or error)
  bool switchable = false; // -ts_adapt_switch_when: error mode only while its condition holds
  double nominal = 1, dt = 1, factor = 0.5, dt_min = 1e-3, dt_max = 1;
  double period = 0; // -ts_adapt_period
  long grow_after = 3, easy_newton = 4;
  long easy_run = 0, cuts = 0, grows = 0;
  // Error control: tolerances, safety factor, the last accepted step's scaled error (PI memory),
  // rejected steps, and the range of accepted steps.
  StepErrorTolerance tol;
  double safety = 0.9, error_prev = 0, dt_smallest = 0, dt_largest = 0;
  long rejections = 0, max_rejections = 5, step_rejections = 0, accepted_above = 0;
  static StepControl from_options(double nominal_dt);
  void resume(double dt_, long easy_run_, double error_prev_) {
    dt = dt_, easy_run = easy_run_, error_prev = error_prev_;
  }
  const StepErrorTolerance *error_tolerance() {
    tol.accept_any = step_rejections >= max_rejections;
    return mode == error ? &tol : nullptr;
  }
  // The step to take from time t: dt, shortened in error mode to land on the next multiple of
  // -ts_adapt_period.
  double landing(double t) const;
  // Whether t is a multiple k >= 1 of -ts_adapt_period (to rounding).
  bool period_start(double t) const;
  // -ts_adapt_switch_when: error control on (true) or back to cut mode at the scene's dt.
  void set_error_control(bool on);
  // After a failed step: the next dt, or false when it would fall below dt_min (or adapt off).
  bool cut();
  // After a step rejected by its error estimate e > 1: the smaller dt, or false below dt_min.
  bool reject(double e);
  // After an accepted step with `newton` iterations and scaled error e (error mode; negative:
  // no estimate, the run's first step): the next dt.
  void accepted(long newton, double e = -1);
};

} // namespace fsi
