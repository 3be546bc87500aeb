#include "fsi/boundary/boundary_condition.hpp"
#include "fsi/scene/options.hpp"

#include <array>
#include <cmath>

namespace fsi {

void read_direction(const std::string &name, double dir[3]) {
  auto d = opt::reals(name);
  if (d.size() != 3) throw InputError("option -" + name + " needs 3 numbers x,y,z");
  const double nrm = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (nrm == 0) throw InputError("option -" + name + " must be non-zero");
  for (int i = 0; i < 3; ++i)
    dir[i] = d[i] / nrm;
}

std::array<double, 3> read_point(const std::string &name) {
  auto c = opt::reals(name);
  if (c.size() != 3) throw InputError("option -" + name + " needs 3 numbers x,y,z");
  return {c[0], c[1], c[2]};
}

double axis_distance2(const double x[3], const std::array<double, 3> &center,
                      const std::array<double, 3> &dir) {
  double r[3], along = 0, r2 = 0;
  for (int d = 0; d < 3; ++d)
    r[d] = x[d] - center[d], along += r[d] * dir[d];
  for (int d = 0; d < 3; ++d)
    r2 += (r[d] - along * dir[d]) * (r[d] - along * dir[d]);
  return r2;
}

std::function<void(const double *, double, double *)> uniform_profile(const std::string &pre) {
  const double value = opt::real(pre + "value", 0);
  std::array<double, 3> dir;
  read_direction(pre + "direction", dir.data());
  const Waveform wave = Waveform::from_options(pre);
  return [=](const double *, double t, double *v) {
    const double scale = value * wave(t);
    for (int d = 0; d < 3; ++d)
      v[d] = scale * dir[d];
  };
}

// -bc_<name>_components x,y: the velocity components the boundary fixes (default: all for a
// Dirichlet type, none otherwise).
BoundaryCondition::BoundaryCondition(const BoundarySetup &s, Data data, bool dirichlet_default,
                                     bool faces)
    : name_(s.name), data_(data) {
  const std::string pre = s.prefix();
  const auto comps = opt::list(pre + "components");
  for (int i = 0; i < 3; ++i)
    fixed_[i] = dirichlet_default && comps.empty();
  for (auto &c : comps) {
    if (c != "x" && c != "y" && c != "z")
      throw InputError("option -" + pre + "components takes x, y, z; got '" + c + "'");
    fixed_[c[0] - 'x'] = true;
  }
  if (fixed_[0] || fixed_[1] || fixed_[2]) nodes_ = s.space.boundary_velocity_nodes(s.mesh, name_);
  if (faces) faces_ = s.space.boundary_faces(s.mesh, name_);
}

void add_fluid_face_traction(
    const BoundaryFace &f, const StepContext &ctx, const QuadRule &rule, double beta, double rho,
    const std::function<void(const double x[3], const double n[3], double t[3])> &traction,
    PetscScalar *F) {
  double X[3][3], n[3];
  for (int i = 0; i < 3; ++i)
    for (int d = 0; d < 3; ++d)
      X[i][d] = ctx.X_af[3 * f.vertex[i] + d];
  const double area2 = outward_normal(f, ctx.X_af, n); // 2 * area
  double Fe[6][3] = {};
  for (size_t q = 0; q < rule.weight.size(); ++q) {
    const double *l = rule.lambda[q].data();
    double N[6], x[3] = {0, 0, 0}, tr[3];
    p2_tri(l, N);
    for (int i = 0; i < 3; ++i)
      for (int d = 0; d < 3; ++d)
        x[d] += l[i] * X[i][d];
    traction(x, n, tr);
    const double w = rule.weight[q] * area2; // reference triangle measure 1/2
    if (beta > 0) {                          // backflow: traction += beta rho/2 min(v.n, 0) v
      double v[3] = {0, 0, 0};
      for (int a = 0; a < 6; ++a)
        for (int d = 0; d < 3; ++d)
          v[d] += N[a] * ctx.v_af(f.vdof[a] + d);
      const double vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
      if (vn < 0)
        for (int d = 0; d < 3; ++d)
          tr[d] += 0.5 * beta * rho * vn * v[d];
    }
    for (int a = 0; a < 6; ++a)
      for (int d = 0; d < 3; ++d)
        Fe[a][d] -= w * N[a] * tr[d];
  }
  for (int a = 0; a < 6; ++a)
    for (int d = 0; d < 3; ++d)
      F[f.vdof[a] + d] += Fe[a][d];
}

void add_face_block(Mat J, const BoundaryFace &f, const std::vector<char> &mask,
                    const double K[18][18]) {
  PetscInt rows[18], cols[18];
  for (int a = 0; a < 6; ++a)
    for (int i = 0; i < 3; ++i) {
      cols[3 * a + i] = f.vdof[a] + i;
      rows[3 * a + i] = mask[f.vdof[a] + i] ? -1 : f.vdof[a] + i;
    }
  FSI_CALL(MatSetValuesLocal(J, 18, rows, 18, cols, &K[0][0], ADD_VALUES));
}

void add_fluid_pressure(const std::vector<BoundaryFace> &faces, const StepContext &ctx,
                        const QuadRule &rule, double beta, double rho, double p, PetscScalar *F) {
  auto traction = [p](const double *, const double *n, double *t) {
    for (int d = 0; d < 3; ++d)
      t[d] = -p * n[d];
  };
  for (auto &f : faces)
    add_fluid_face_traction(f, ctx, rule, beta, rho, traction, F);
}

void add_backflow_jacobian(const std::vector<BoundaryFace> &faces, const StepContext &ctx,
                           const QuadRule &rule, double beta, double rho, Mat J) {
  if (beta <= 0) return;
  const std::vector<char> &mask = *ctx.is_dirichlet;
  const double c = 0.5 * beta * rho * ctx.stiff_shift();
  for (auto &f : faces) {
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
              K[3 * a + i][3 * b + j] -= w * c * N[a] * N[b] * (n[j] * v[i] + (i == j ? vn : 0.0));
    }
    if (any) add_face_block(J, f, mask, K);
  }
}

} // namespace fsi
