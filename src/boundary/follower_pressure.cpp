// follower_pressure (solid): pressure value [Pa] * waveform(t) on the deformed surface at
// t_{n+alpha_f}: traction -p n da (p < 0 pulls), with its Jacobian (the surface moves with u).
#include "fsi/boundary/boundary_condition.hpp"
#include "fsi/boundary/solid_face.hpp"
#include "fsi/scene/options.hpp"

namespace fsi {
namespace {

struct FollowerPressure : BoundaryCondition {
  double value = 0;
  Waveform wave;
  std::vector<SolidFace> geo;
  QuadRule rule = tri_rule(4);
  explicit FollowerPressure(const BoundarySetup &s)
      : BoundaryCondition(s, Data::none, false, true) {
    const std::string pre = s.prefix();
    value = opt::real(pre + "value", 0);
    wave = Waveform::from_options(pre);
    for (auto &f : faces_)
      geo.push_back(solid_face(s.material_X, f));
  }
  std::string type() const override { return "follower_pressure"; }
  // Deformed node positions at t_{n+af}.
  void deformed(const StepContext &ctx, size_t k, double x[6][3]) const {
    for (int a = 0; a < 6; ++a)
      for (int d = 0; d < 3; ++d)
        x[a][d] = geo[k].X[a][d] + ctx.u_af(faces_[k].vdof[a] + d);
  }
  void add_residual(const StepContext &ctx, PetscScalar *F) const override {
    const double p = value * wave(ctx.t_af);
    for (size_t k = 0; k < faces_.size(); ++k) {
      double x[6][3], Fe[6][3] = {};
      deformed(ctx, k, x);
      for (size_t q = 0; q < rule.weight.size(); ++q) {
        const double *l = rule.lambda[q].data();
        double N[6], dxi[6], deta[6], gx[3], ge[3], nda[3];
        p2_tri(l, N);
        p2_tri_derivs(l, dxi, deta);
        face_tangents(x, dxi, deta, gx, ge);
        cross(gx, ge, nda); // n da / (dxi deta), outward with the sign
        const double w = rule.weight[q];
        double tr[3];
        for (int d = 0; d < 3; ++d)
          tr[d] = -p * (nda[d] * geo[k].sign);
        for (int a = 0; a < 6; ++a)
          for (int d = 0; d < 3; ++d)
            Fe[a][d] -= w * N[a] * tr[d];
      }
      for (int a = 0; a < 6; ++a)
        for (int d = 0; d < 3; ++d)
          F[faces_[k].vdof[a] + d] += Fe[a][d];
    }
  }
  void add_jacobian(const StepContext &ctx, Mat J) const override {
    const std::vector<char> &mask = *ctx.is_dirichlet;
    const double p = value * wave(ctx.t_af), cu = ctx.disp_shift();
    for (size_t k = 0; k < faces_.size(); ++k) {
      const BoundaryFace &f = faces_[k];
      double x[6][3], K[18][18] = {};
      deformed(ctx, k, x);
      for (size_t q = 0; q < rule.weight.size(); ++q) {
        const double *l = rule.lambda[q].data();
        double N[6], dxi[6], deta[6], gx[3], ge[3];
        p2_tri(l, N);
        p2_tri_derivs(l, dxi, deta);
        face_tangents(x, dxi, deta, gx, ge);
        // R_a,i = p sign N_a (gx x ge)_i w;  d/dx_b,j: dxi_b (e_j x ge)_i + deta_b (gx x e_j)_i
        const double c = cu * p * geo[k].sign * rule.weight[q];
        for (int b = 0; b < 6; ++b)
          for (int j = 0; j < 3; ++j) {
            double e[3] = {0, 0, 0}, d1[3], d2[3];
            e[j] = 1;
            cross(e, ge, d1);
            cross(gx, e, d2);
            for (int a = 0; a < 6; ++a)
              for (int i = 0; i < 3; ++i)
                K[3 * a + i][3 * b + j] += c * N[a] * (dxi[b] * d1[i] + deta[b] * d2[i]);
          }
      }
      add_face_block(J, f, mask, K);
    }
  }
};

} // namespace

std::unique_ptr<BoundaryCondition> make_follower_pressure(const BoundarySetup &s) {
  return std::make_unique<FollowerPressure>(s);
}

} // namespace fsi
