// traction_exact (fluid, verification): the traction sigma_exact n of -exact_solution, on the
// configuration at t_{n+alpha_f}.  It fixes the pressure level.
#include "fsi/boundary/boundary_condition.hpp"

namespace fsi {
namespace {

struct TractionExact : BoundaryCondition {
  const ExactFlow *exact;
  double mu;
  QuadRule rule = tri_rule(4);
  explicit TractionExact(const BoundarySetup &s)
      : BoundaryCondition(s, Data::velocity, false, true), exact(s.exact), mu(s.mu) {
    if (!exact) throw InputError("-" + s.prefix() + "type traction_exact needs -exact_solution");
  }
  std::string type() const override { return "traction_exact"; }
  bool fixes_pressure_level() const override { return true; }
  void add_residual(const StepContext &ctx, PetscScalar *F) const override {
    const double t_af = ctx.t_af;
    auto traction = [&](const double *x, const double *n, double *tr) {
      double s[3][3];
      exact->stress(x, t_af, mu, s);
      for (int i = 0; i < 3; ++i)
        tr[i] = s[i][0] * n[0] + s[i][1] * n[1] + s[i][2] * n[2];
    };
    for (auto &f : faces_)
      add_fluid_face_traction(f, ctx, rule, 0.0, 0.0, traction, F);
  }
};

} // namespace

std::unique_ptr<BoundaryCondition> make_traction_exact(const BoundarySetup &s) {
  return std::make_unique<TractionExact>(s);
}

} // namespace fsi
