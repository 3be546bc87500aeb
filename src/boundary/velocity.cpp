// velocity: v = profile(x) waveform(t) on the fixed components (default all).
//   -bc_<name>_profile uniform|parabolic|exact, -bc_<name>_value [m/s] (mean speed of a
//   parabolic profile), -bc_<name>_direction x,y,z; parabolic: -bc_<name>_center x,y,z [m],
//   -bc_<name>_radius [m]: 2 (1 - r^2/R^2) times the value, r measured from the axis through the
//   centre along the direction; exact: the -exact_solution flow; expression: -bc_<name>_expr,
//   three values in x, y, z, t (expression.hpp) times -bc_<name>_value (default 1) and the
//   waveform (default 1).  Waveform: analytic.hpp.
#include "fsi/boundary/boundary_condition.hpp"
#include "fsi/scene/options.hpp"

#include <cmath>
#include <memory>

namespace fsi {
namespace {

struct Velocity : BoundaryCondition {
  std::function<void(const double *, double, double *)> profile; // resolved once
  explicit Velocity(const BoundarySetup &s) : BoundaryCondition(s, Data::velocity, true, false) {
    const std::string pre = s.prefix();
    const std::string kind =
        opt::choice(pre + "profile", "uniform", {"uniform", "parabolic", "exact", "expression"});
    if (kind == "exact") {
      const ExactFlow *exact = s.exact;
      if (!exact) throw InputError("-" + pre + "profile exact needs -exact_solution");
      profile = [exact](const double *x, double t, double *v) { exact->velocity(x, t, v); };
      return;
    }
    if (kind == "expression") {
      auto e =
          std::make_shared<const Expression>(opt::required_string(pre + "expr"), pre + "expr", 3);
      const double value = opt::real(pre + "value", 1.0);
      const Waveform wave = Waveform::from_options(pre);
      profile = [e, wave, value](const double *x, double t, double *v) {
        e->eval(x, t, v);
        const double w = value * wave(t);
        for (int d = 0; d < 3; ++d)
          v[d] *= w;
      };
      return;
    }
    if (kind == "uniform") {
      profile = uniform_profile(pre);
      return;
    }
    const double value = opt::real(pre + "value", 0);
    std::array<double, 3> dir;
    read_direction(pre + "direction", dir.data());
    const Waveform wave = Waveform::from_options(pre);
    const std::array<double, 3> center = read_point(pre + "center");
    const double R = opt::required_positive(pre + "radius");
    profile = [=](const double *x, double t, double *v) {
      const double r2 = axis_distance2(x, center, dir);
      const double mag = value * wave(t) * std::max(0.0, 2.0 * (1.0 - r2 / (R * R)));
      for (int d = 0; d < 3; ++d)
        v[d] = mag * dir[d];
    };
  }
  std::string type() const override { return "velocity"; }
  void value(const double x[3], double t, double v[3]) const override { profile(x, t, v); }
};

} // namespace

std::unique_ptr<BoundaryCondition> make_velocity(const BoundarySetup &s) {
  return std::make_unique<Velocity>(s);
}

} // namespace fsi
