// Step-size control on failure (-ts_adapt_type cut|none, default cut): a step whose Newton diverges
// or whose solid element would invert is retried from the last converged state with dt <-
// -ts_adapt_scale_solve_failed dt (default 0.5); after -step_grow_after consecutive easy steps
// (Newton iterations <= -step_easy_newton) dt grows back by 1 / cut_factor, never above the scene's
// dt. Below -ts_adapt_dt_min (default dt / 1000) the run stops: checkpoint, reason, non-zero exit.
// Steps that end on a distorted fluid mesh are not retried (a smaller step does not help there).
#pragma once
#include "fsi/common.hpp"

namespace fsi {

struct StepControl {
  bool enabled = true;
  double nominal = 1, dt = 1, factor = 0.5, dt_min = 1e-3;
  long grow_after = 3, easy_newton = 4;
  long easy_run = 0, cuts = 0, grows = 0;
  static StepControl from_options(double nominal_dt);
  void resume(double dt_, long easy_run_) { dt = dt_, easy_run = easy_run_; }
  // After a failed step: the next dt, or false when it would fall below dt_min (or adapt off).
  bool cut();
  // After an accepted step with `newton` iterations: may grow dt back toward the nominal one.
  void accepted(long newton);
};

} // namespace fsi
