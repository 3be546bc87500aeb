// pressure (fluid): traction -P(t) n with P = -bc_<name>_value [Pa] * waveform(t), plus the
// backflow stabilisation beta rho/2 min(v.n, 0) v (-bc_<name>_backflow_beta, default 1: cancels
// the convective energy influx exactly; 0 turns it off, as a pressure-driven inlet needs).  It
// fixes the pressure level.  -bc_<name>_components x,y additionally holds those velocity
// components at zero (e.g. a parallel-flow outlet).
#include "fsi/boundary/boundary_condition.hpp"
#include "fsi/scene/options.hpp"

namespace fsi {
namespace {

struct Pressure : BoundaryCondition {
  double P = 0, beta = 1, rho = 0;
  Waveform wave;
  QuadRule rule = tri_rule(4);
  explicit Pressure(const BoundarySetup &s) : BoundaryCondition(s, Data::velocity, false, true) {
    const std::string pre = s.prefix();
    P = opt::real(pre + "value", 0);
    beta = opt::nonnegative(pre + "backflow_beta", 1.0);
    wave = Waveform::from_options(pre);
    rho = s.rho;
  }
  std::string type() const override { return "pressure"; }
  bool fixes_pressure_level() const override { return true; }
  void add_residual(const StepContext &ctx, PetscScalar *F) const override {
    const double p = P * wave(ctx.t_af);
    add_fluid_pressure(faces_, ctx, rule, beta, rho, p, F);
  }
  void add_jacobian(const StepContext &ctx, Mat J) const override {
    add_backflow_jacobian(faces_, ctx, rule, beta, rho, J);
  }
};

} // namespace

std::unique_ptr<BoundaryCondition> make_pressure(const BoundarySetup &s) {
  return std::make_unique<Pressure>(s);
}

} // namespace fsi
