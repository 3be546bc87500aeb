#include "fsi/time/step_control.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>

namespace fsi {

StepControl StepControl::from_options(double nominal_dt) {
  StepControl c;
  c.enabled = opt::choice("ts_adapt_type", "cut", {"cut", "none"}) == "cut";
  c.nominal = c.dt = nominal_dt;
  c.factor = opt::positive("ts_adapt_scale_solve_failed", 0.5);
  if (c.factor >= 1)
    throw InputError("option -ts_adapt_scale_solve_failed must be in (0, 1), e.g. 0.5");
  c.dt_min = opt::positive("ts_adapt_dt_min", nominal_dt / 1000);
  if (c.dt_min > nominal_dt)
    throw InputError("option -ts_adapt_dt_min is larger than the time step -ts_dt");
  c.grow_after = opt::integer("step_grow_after", 3);
  c.easy_newton = opt::integer("step_easy_newton", 4);
  if (c.grow_after < 1) throw InputError("option -step_grow_after must be >= 1");
  return c;
}

bool StepControl::cut() {
  easy_run = 0;
  if (!enabled || dt * factor < dt_min * (1 - 1e-12)) return false;
  dt *= factor;
  ++cuts;
  return true;
}

void StepControl::accepted(long newton) {
  if (dt >= nominal) return;
  easy_run = newton <= easy_newton ? easy_run + 1 : 0;
  if (easy_run < grow_after) return;
  dt = std::min(nominal, dt / factor);
  easy_run = 0;
  ++grows;
}

} // namespace fsi
