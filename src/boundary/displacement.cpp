// displacement (solid): u = value direction waveform(t) [m], or -bc_<name>_profile exact
// (-exact_displacement), at the nodes' material positions; imposed through the velocity by the
// Newmark relation so that u_{n+1} is exact.
#include "fsi/boundary/boundary_condition.hpp"
#include "fsi/scene/options.hpp"

namespace fsi {
namespace {

struct Displacement : BoundaryCondition {
  std::function<void(const double *, double, double *)> profile; // resolved once
  explicit Displacement(const BoundarySetup &s)
      : BoundaryCondition(s, Data::displacement, true, false) {
    const std::string pre = s.prefix();
    if (opt::choice(pre + "profile", "uniform", {"uniform", "exact"}) == "exact") {
      const ExactSolid *exact = s.exact_solid;
      if (!exact) throw InputError("-" + pre + "profile exact needs -exact_displacement");
      profile = [exact](const double *x, double t, double *u) { exact->displacement(x, t, u); };
      return;
    }
    profile = uniform_profile(pre);
  }
  std::string type() const override { return "displacement"; }
  void value(const double x[3], double t, double u[3]) const override { profile(x, t, u); }
};

} // namespace

std::unique_ptr<BoundaryCondition> make_displacement(const BoundarySetup &s) {
  return std::make_unique<Displacement>(s);
}

} // namespace fsi
