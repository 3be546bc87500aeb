// traction (solid): dead load, nominal traction value [Pa] * direction * waveform(t) per unit
// reference area, at t_{n+alpha_f}.  It does not depend on the unknown: no Jacobian.
#include "fsi/boundary/boundary_condition.hpp"
#include "fsi/boundary/solid_face.hpp"
#include "fsi/scene/options.hpp"

#include <cmath>

namespace fsi {
namespace {

struct Traction : BoundaryCondition {
  double value = 0, dir[3] = {0, 0, 1};
  Waveform wave;
  std::vector<SolidFace> geo;
  QuadRule rule = tri_rule(4);
  explicit Traction(const BoundarySetup &s) : BoundaryCondition(s, Data::none, false, true) {
    const std::string pre = s.prefix();
    value = opt::real(pre + "value", 0);
    read_direction(pre + "direction", dir);
    wave = Waveform::from_options(pre);
    for (auto &f : faces_)
      geo.push_back(solid_face(s.material_X, f));
  }
  std::string type() const override { return "traction"; }
  void add_residual(const StepContext &ctx, PetscScalar *F) const override {
    const double scale = value * wave(ctx.t_af);
    for (size_t k = 0; k < faces_.size(); ++k) {
      const BoundaryFace &f = faces_[k];
      const SolidFace &sf = geo[k];
      double Fe[6][3] = {};
      for (size_t q = 0; q < rule.weight.size(); ++q) {
        const double *l = rule.lambda[q].data();
        double N[6], dxi[6], deta[6], gx[3], ge[3], nda[3];
        p2_tri(l, N);
        p2_tri_derivs(l, dxi, deta);
        face_tangents(sf.X, dxi, deta, gx, ge);
        cross(gx, ge, nda);
        const double dA = std::sqrt(nda[0] * nda[0] + nda[1] * nda[1] + nda[2] * nda[2]);
        const double w = rule.weight[q];
        double tr[3]; // load per (dxi deta)
        for (int d = 0; d < 3; ++d)
          tr[d] = scale * dir[d] * dA;
        for (int a = 0; a < 6; ++a)
          for (int d = 0; d < 3; ++d)
            Fe[a][d] -= w * N[a] * tr[d];
      }
      for (int a = 0; a < 6; ++a)
        for (int d = 0; d < 3; ++d)
          F[f.vdof[a] + d] += Fe[a][d];
    }
  }
};

} // namespace

std::unique_ptr<BoundaryCondition> make_traction(const BoundarySetup &s) {
  return std::make_unique<Traction>(s);
}

} // namespace fsi
