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
    auto traction = [p](const double *, const double *n, double *t) {
      for (int d = 0; d < 3; ++d)
        t[d] = -p * n[d];
    };
    for (auto &f : faces_)
      add_fluid_face_traction(f, ctx, rule, beta, rho, traction, F);
  }
  // d/dv of the backflow term -(beta rho/2) min(v.n, 0) v.
  void add_jacobian(const StepContext &ctx, Mat J) const override {
    if (beta <= 0) return;
    const std::vector<char> &mask = *ctx.is_dirichlet;
    const double c = 0.5 * beta * rho * ctx.stiff_shift();
    for (auto &f : faces_) {
      double n[3];
      const double J2 = outward_normal(f, ctx.X_af, n);
      double K[18][18] = {};
      bool any = false;
      for (size_t q = 0; q < rule.weight.size(); ++q) {
        double N[6], v[3] = {0, 0, 0};
        p2_tri(rule.lambda[q].data(), N);
        for (int a = 0; a < 6; ++a)
          for (int d = 0; d < 3; ++d)
            v[d] += N[a] * ctx.v_af(f.vdof[a] + d);
        const double vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
        if (vn >= 0) continue;
        any = true;
        // d/dv [-(c) vn v_i] = -c (n_j v_i + vn delta_ij)
        const double w = rule.weight[q] * J2;
        for (int a = 0; a < 6; ++a)
          for (int b = 0; b < 6; ++b)
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < 3; ++j)
                K[3 * a + i][3 * b + j] -=
                    w * c * N[a] * N[b] * (n[j] * v[i] + (i == j ? vn : 0.0));
      }
      if (!any) continue;
      add_face_block(J, f, mask, K);
    }
  }
};

} // namespace

std::unique_ptr<BoundaryCondition> make_pressure(const BoundarySetup &s) {
  return std::make_unique<Pressure>(s);
}

} // namespace fsi
