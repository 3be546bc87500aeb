#include "fsi/boundary.hpp"
#include "fsi/options.hpp"

#include <cmath>

namespace fsi {

// A unit vector from option `name` (3 numbers x,y,z, not all zero).
static void read_direction(const std::string &name, double dir[3]) {
  auto d = opt::reals(name);
  if (d.size() != 3) throw InputError("option -" + name + " needs 3 numbers x,y,z");
  const double nrm = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (nrm == 0) throw InputError("option -" + name + " must be non-zero");
  for (int i = 0; i < 3; ++i)
    dir[i] = d[i] / nrm;
}

void Boundaries::setup(const Mesh &mesh, const Space &space, const ExactFlow *exact,
                       const ExactSolid *exact_solid, double mu, double rho,
                       const std::vector<PetscInt> *fluid_cells) {
  space_ = &space;
  rho_ = rho;
  exact_ = exact;
  exact_solid_ = exact_solid;
  mu_ = mu;
  face_rule_ = tri_rule(4);
  mask_.assign(space.n_local, 0);
  const auto names = opt::list("bc_names");
  mesh.require_groups(names, "-bc_names");
  bool level_fixed = false;
  for (auto &n : names) {
    BoundaryCondition bc;
    bc.name = n;
    const std::string pre = "bc_" + n + "_";
    if (!opt::has(pre + "type"))
      throw InputError("boundary '" + n + "' is listed in -bc_names but has no -" + pre +
                       "type: give noslip|velocity|pressure|traction_exact (fluid) or "
                       "clamped|displacement|traction|follower_pressure (solid)");
    const std::string type =
        opt::choice(pre + "type", "",
                    {"noslip", "velocity", "pressure", "traction_exact", "clamped", "displacement",
                     "traction", "follower_pressure"});
    if (type == "noslip") bc.type = BoundaryCondition::NoSlip;
    if (type == "clamped") bc.type = BoundaryCondition::Clamped;
    if (type == "displacement" || type == "traction") {
      bc.type = type == "traction" ? BoundaryCondition::Traction : BoundaryCondition::Displacement;
      bc.profile = type == "traction"
                       ? "uniform"
                       : opt::choice(pre + "profile", "uniform", {"uniform", "exact"});
      if (bc.profile == "exact" && !exact_solid)
        throw InputError("-" + pre + "profile exact needs -exact_displacement");
      if (bc.profile != "exact") {
        bc.value = opt::real(pre + "value", 0);
        read_direction(pre + "direction", bc.dir);
        bc.wave = Waveform::from_options(pre);
      }
    }
    if (type == "follower_pressure") {
      bc.type = BoundaryCondition::FollowerPressure;
      bc.value = opt::real(pre + "value", 0);
      bc.wave = Waveform::from_options(pre);
    }
    if (type == "velocity") {
      bc.type = BoundaryCondition::Velocity;
      bc.profile = opt::choice(pre + "profile", "uniform", {"uniform", "parabolic", "exact"});
      if (bc.profile == "exact" && !exact)
        throw InputError("-" + pre + "profile exact needs -exact_solution");
      if (bc.profile != "exact") {
        bc.value = opt::real(pre + "value", 0);
        read_direction(pre + "direction", bc.dir);
      }
      if (bc.profile == "parabolic") {
        auto c = opt::reals(pre + "center");
        if (c.size() != 3) throw InputError("option -" + pre + "center needs 3 numbers x,y,z");
        for (int i = 0; i < 3; ++i)
          bc.center[i] = c[i];
        bc.radius = opt::required_positive(pre + "radius");
      }
      bc.wave = Waveform::from_options(pre);
    }
    if (type == "pressure") {
      bc.type = BoundaryCondition::Pressure;
      bc.value = opt::real(pre + "value", 0);
      bc.beta = opt::nonnegative(pre + "backflow_beta", 1.0);
      bc.wave = Waveform::from_options(pre);
    }
    if (type == "traction_exact") {
      if (!exact) throw InputError("-" + pre + "type traction_exact needs -exact_solution");
      bc.type = BoundaryCondition::TractionExact;
    }
    const bool dirichlet = bc.dirichlet();
    const auto comps = opt::list(pre + "components");
    for (int i = 0; i < 3; ++i)
      bc.fixed[i] = dirichlet && comps.empty();
    for (auto &c : comps) {
      if (c != "x" && c != "y" && c != "z")
        throw InputError("option -" + pre + "components takes x, y, z; got '" + c + "'");
      bc.fixed[c[0] - 'x'] = true;
    }
    if (bc.fixed[0] || bc.fixed[1] || bc.fixed[2]) {
      bc.nodes = space.boundary_velocity_nodes(mesh, n);
      for (auto &nd : bc.nodes)
        for (int i = 0; i < 3; ++i)
          if (bc.fixed[i]) mask_[nd.dof + i] = 1;
    }
    if (!dirichlet) bc.faces = space.boundary_faces(mesh, n);
    if (bc.fluid_traction()) level_fixed = true;
    bcs_.push_back(bc);
  }
  // Pressure dofs outside the fluid belong to no equation: hold them at zero.
  const std::vector<char> in_fluid =
      fluid_cells ? space.pressure_dofs_of(*fluid_cells) : std::vector<char>(space.n_local, 0);
  std::vector<char> all_p(space.n_local, 0); // every local vertex belongs to a local cell
  for (PetscInt d : space.cell_pdof)
    all_p[d] = 1;
  for (PetscInt i = 0; i < space.n_local; ++i)
    if (all_p[i] && !in_fluid[i]) {
      outside_fluid_.push_back(i);
      mask_[i] = 1;
    }
  // Without a traction boundary the fluid pressure is defined up to a constant: pin one vertex.
  if (fluid_cells && !level_fixed) {
    pinned_ = true;
    pin_dof_ = space.pinned_pressure_dof(pin_vertex_, &in_fluid);
    if (pin_dof_ >= 0) mask_[pin_dof_] = 1;
  }
}

long Boundaries::pressure_dofs_outside_fluid() const {
  long mine = 0, all = 0;
  for (PetscInt i : outside_fluid_)
    mine += space_->owned(i);
  MPI_Allreduce(&mine, &all, 1, MPI_LONG, MPI_SUM, PetscObjectComm((PetscObject)space_->dm));
  return all;
}

void Boundaries::displacement_values(double t,
                                     std::vector<std::pair<PetscInt, double>> &out) const {
  out.clear();
  const std::vector<double> &X = space_->X;
  for (auto &bc : bcs_) {
    if (!bc.displacement_type()) continue;
    const double scale = bc.profile == "exact" ? 0.0 : bc.value * bc.wave(t);
    for (auto &nd : bc.nodes) {
      double x[3], u[3];
      for (int d = 0; d < 3; ++d)
        x[d] = nd.vb < 0 ? X[3 * nd.va + d] : 0.5 * (X[3 * nd.va + d] + X[3 * nd.vb + d]);
      if (bc.profile == "exact")
        exact_solid_->displacement(x, t, u);
      else
        for (int d = 0; d < 3; ++d)
          u[d] = scale * bc.dir[d];
      for (int d = 0; d < 3; ++d)
        if (bc.fixed[d]) out.emplace_back(nd.dof + d, u[d]);
    }
  }
}

void Boundaries::dirichlet_values(double t, const double *X,
                                  std::vector<std::pair<PetscInt, double>> &out) const {
  out.clear();
  for (auto &bc : bcs_) {
    if (bc.nodes.empty() || bc.displacement_type()) continue;
    const double scale = bc.type == BoundaryCondition::Velocity ? bc.wave(t) : 0.0;
    for (auto &nd : bc.nodes) {
      double x[3], v[3] = {0, 0, 0};
      for (int d = 0; d < 3; ++d)
        x[d] = nd.vb < 0 ? X[3 * nd.va + d] : 0.5 * (X[3 * nd.va + d] + X[3 * nd.vb + d]);
      if (bc.type == BoundaryCondition::Velocity) {
        if (bc.profile == "exact") {
          exact_->velocity(x, t, v);
        } else {
          double mag = bc.value * scale;
          if (bc.profile == "parabolic") {
            double r[3], along = 0, r2 = 0;
            for (int d = 0; d < 3; ++d)
              r[d] = x[d] - bc.center[d], along += r[d] * bc.dir[d];
            for (int d = 0; d < 3; ++d)
              r2 += std::pow(r[d] - along * bc.dir[d], 2);
            mag *= std::max(0.0, 2.0 * (1.0 - r2 / (bc.radius * bc.radius)));
          }
          for (int d = 0; d < 3; ++d)
            v[d] = mag * bc.dir[d];
        }
      }
      for (int d = 0; d < 3; ++d)
        if (bc.fixed[d]) out.emplace_back(nd.dof + d, v[d]);
    }
  }
  for (PetscInt i : outside_fluid_)
    out.emplace_back(i, 0.0);
  if (pin_dof_ >= 0) {
    double p = 0;
    if (exact_) p = exact_->pressure(&X[3 * pin_vertex_], t);
    out.emplace_back(pin_dof_, p);
  }
  // A node on two Dirichlet boundaries keeps the value of the one listed last.
  std::vector<int> last(space_->n_local, -1);
  for (size_t i = 0; i < out.size(); ++i)
    last[out[i].first] = (int)i;
  size_t k = 0;
  for (size_t i = 0; i < out.size(); ++i)
    if (last[out[i].first] == (int)i) out[k++] = out[i];
  out.resize(k);
}

void Boundaries::add_traction_residual(const StepContext &ctx, PetscScalar *F) const {
  for (auto &bc : bcs_) {
    if (bc.type == BoundaryCondition::Traction || bc.type == BoundaryCondition::FollowerPressure)
      add_solid_load_residual(bc, ctx, F);
    if (!bc.fluid_traction()) continue;
    const double P = bc.type == BoundaryCondition::Pressure ? bc.value * bc.wave(ctx.t_af) : 0.0;
    for (auto &f : bc.faces) {
      double X[3][3], n[3];
      for (int i = 0; i < 3; ++i)
        for (int d = 0; d < 3; ++d)
          X[i][d] = ctx.X_af[3 * f.vertex[i] + d];
      const double area2 = outward_normal(f, ctx.X_af, n); // 2 * area
      double Fe[6][3] = {};
      for (size_t q = 0; q < face_rule_.weight.size(); ++q) {
        const double *l = face_rule_.lambda[q].data();
        double N[6], x[3] = {0, 0, 0}, tr[3];
        p2_tri(l, N);
        for (int i = 0; i < 3; ++i)
          for (int d = 0; d < 3; ++d)
            x[d] += l[i] * X[i][d];
        if (bc.type == BoundaryCondition::Pressure) {
          for (int d = 0; d < 3; ++d)
            tr[d] = -P * n[d];
        } else {
          double s[3][3];
          exact_->stress(x, ctx.t_af, mu_, s);
          for (int i = 0; i < 3; ++i)
            tr[i] = s[i][0] * n[0] + s[i][1] * n[1] + s[i][2] * n[2];
        }
        const double w = face_rule_.weight[q] * area2; // reference triangle measure 1/2
        if (bc.beta > 0) { // backflow: traction += beta rho/2 min(v.n, 0) v
          double v[3] = {0, 0, 0};
          for (int a = 0; a < 6; ++a)
            for (int d = 0; d < 3; ++d)
              v[d] += N[a] * ctx.v_af(f.vdof[a] + d);
          const double vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
          if (vn < 0)
            for (int d = 0; d < 3; ++d)
              tr[d] += 0.5 * bc.beta * rho_ * vn * v[d];
        }
        for (int a = 0; a < 6; ++a)
          for (int d = 0; d < 3; ++d)
            Fe[a][d] -= w * N[a] * tr[d];
      }
      for (int a = 0; a < 6; ++a)
        for (int d = 0; d < 3; ++d)
          F[f.vdof[a] + d] += Fe[a][d];
    }
  }
}

void Boundaries::add_traction_jacobian(const StepContext &ctx, Mat J) const {
  const std::vector<char> &mask = *ctx.is_dirichlet;
  for (auto &bc : bcs_) {
    if (bc.type == BoundaryCondition::FollowerPressure) add_follower_jacobian(bc, ctx, J);
    if (bc.type != BoundaryCondition::Pressure || bc.beta <= 0) continue;
    const double c = 0.5 * bc.beta * rho_ * ctx.stiff_shift();
    for (auto &f : bc.faces) {
      double n[3];
      const double J2 = outward_normal(f, ctx.X_af, n);
      double K[18][18] = {};
      bool any = false;
      for (size_t q = 0; q < face_rule_.weight.size(); ++q) {
        double N[6], v[3] = {0, 0, 0};
        p2_tri(face_rule_.lambda[q].data(), N);
        for (int a = 0; a < 6; ++a)
          for (int d = 0; d < 3; ++d)
            v[d] += N[a] * ctx.v_af(f.vdof[a] + d);
        const double vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
        if (vn >= 0) continue;
        any = true;
        // d/dv [-(c) vn v_i] = -c (n_j v_i + vn delta_ij)
        const double w = face_rule_.weight[q] * J2;
        for (int a = 0; a < 6; ++a)
          for (int b = 0; b < 6; ++b)
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < 3; ++j)
                K[3 * a + i][3 * b + j] -=
                    w * c * N[a] * N[b] * (n[j] * v[i] + (i == j ? vn : 0.0));
      }
      if (!any) continue;
      PetscInt rows[18], cols[18];
      for (int a = 0; a < 6; ++a)
        for (int i = 0; i < 3; ++i) {
          cols[3 * a + i] = f.vdof[a] + i;
          rows[3 * a + i] = mask[f.vdof[a] + i] ? -1 : f.vdof[a] + i;
        }
      FSI_CALL(MatSetValuesLocal(J, 18, rows, 18, cols, &K[0][0], ADD_VALUES));
    }
  }
}

// Derivatives of the P2 triangle shape functions with respect to the reference coordinates
// (xi, eta), lambda = (1 - xi - eta, xi, eta).
static void p2_tri_derivs(const double l[3], double dxi[6], double deta[6]) {
  const double dl_xi[3] = {-1, 1, 0}, dl_eta[3] = {-1, 0, 1};
  for (int i = 0; i < 3; ++i) {
    dxi[i] = (4 * l[i] - 1) * dl_xi[i];
    deta[i] = (4 * l[i] - 1) * dl_eta[i];
  }
  for (int k = 0; k < 3; ++k) {
    const int a = TRI_EDGE[k][0], b = TRI_EDGE[k][1];
    dxi[3 + k] = 4 * (dl_xi[a] * l[b] + l[a] * dl_xi[b]);
    deta[3 + k] = 4 * (dl_eta[a] * l[b] + l[a] * dl_eta[b]);
  }
}

// Geometry of a solid boundary face: reference node positions (vertices, edge midpoints) and
// the sign that makes x_xi x x_eta point out of the solid.
struct SolidFace {
  double X[6][3];
  double sign;
};

static SolidFace solid_face(const Space &space, const BoundaryFace &f) {
  SolidFace s;
  const double *X = space.X.data();
  for (int i = 0; i < 3; ++i)
    for (int d = 0; d < 3; ++d)
      s.X[i][d] = X[3 * f.vertex[i] + d];
  for (int k = 0; k < 3; ++k)
    for (int d = 0; d < 3; ++d)
      s.X[3 + k][d] = 0.5 * (s.X[TRI_EDGE[k][0]][d] + s.X[TRI_EDGE[k][1]][d]);
  double n[3];
  outward_normal(f, X, n);
  double e1[3], e2[3];
  for (int d = 0; d < 3; ++d)
    e1[d] = s.X[1][d] - s.X[0][d], e2[d] = s.X[2][d] - s.X[0][d];
  double c[3];
  cross(e1, e2, c);
  s.sign = c[0] * n[0] + c[1] * n[1] + c[2] * n[2] > 0 ? 1.0 : -1.0;
  return s;
}

void Boundaries::add_solid_load_residual(const BoundaryCondition &bc, const StepContext &ctx,
                                         PetscScalar *F) const {
  const double scale = bc.value * bc.wave(ctx.t_af);
  for (auto &f : bc.faces) {
    const SolidFace sf = solid_face(*space_, f);
    double x[6][3]; // deformed node positions at t_{n+af}
    for (int a = 0; a < 6; ++a)
      for (int d = 0; d < 3; ++d)
        x[a][d] = sf.X[a][d] +
                  (bc.type == BoundaryCondition::FollowerPressure ? ctx.u_af(f.vdof[a] + d) : 0.0);
    double Fe[6][3] = {};
    for (size_t q = 0; q < face_rule_.weight.size(); ++q) {
      const double *l = face_rule_.lambda[q].data();
      double N[6], dxi[6], deta[6], gx[3] = {}, ge[3] = {};
      p2_tri(l, N);
      p2_tri_derivs(l, dxi, deta);
      for (int a = 0; a < 6; ++a)
        for (int d = 0; d < 3; ++d)
          gx[d] += dxi[a] * x[a][d], ge[d] += deta[a] * x[a][d];
      // n da / (dxi deta), outward
      double nda[3];
      cross(gx, ge, nda);
      for (int d = 0; d < 3; ++d)
        nda[d] *= sf.sign;
      const double w = face_rule_.weight[q];
      double tr[3]; // load per (dxi deta)
      if (bc.type == BoundaryCondition::FollowerPressure) {
        for (int d = 0; d < 3; ++d)
          tr[d] = -scale * nda[d];
      } else {
        const double dA = std::sqrt(nda[0] * nda[0] + nda[1] * nda[1] + nda[2] * nda[2]);
        for (int d = 0; d < 3; ++d)
          tr[d] = scale * bc.dir[d] * dA;
      }
      for (int a = 0; a < 6; ++a)
        for (int d = 0; d < 3; ++d)
          Fe[a][d] -= w * N[a] * tr[d];
    }
    for (int a = 0; a < 6; ++a)
      for (int d = 0; d < 3; ++d)
        F[f.vdof[a] + d] += Fe[a][d];
  }
}

void Boundaries::add_follower_jacobian(const BoundaryCondition &bc, const StepContext &ctx,
                                       Mat J) const {
  const std::vector<char> &mask = *ctx.is_dirichlet;
  const double p = bc.value * bc.wave(ctx.t_af), cu = ctx.disp_shift();
  for (auto &f : bc.faces) {
    const SolidFace sf = solid_face(*space_, f);
    double x[6][3];
    for (int a = 0; a < 6; ++a)
      for (int d = 0; d < 3; ++d)
        x[a][d] = sf.X[a][d] + ctx.u_af(f.vdof[a] + d);
    double K[18][18] = {};
    for (size_t q = 0; q < face_rule_.weight.size(); ++q) {
      const double *l = face_rule_.lambda[q].data();
      double N[6], dxi[6], deta[6], gx[3] = {}, ge[3] = {};
      p2_tri(l, N);
      p2_tri_derivs(l, dxi, deta);
      for (int a = 0; a < 6; ++a)
        for (int d = 0; d < 3; ++d)
          gx[d] += dxi[a] * x[a][d], ge[d] += deta[a] * x[a][d];
      // R_a,i = p sign N_a (gx x ge)_i w;  d/dx_b,j: dxi_b (e_j x ge)_i + deta_b (gx x e_j)_i
      const double c = cu * p * sf.sign * face_rule_.weight[q];
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
    PetscInt rows[18], cols[18];
    for (int a = 0; a < 6; ++a)
      for (int i = 0; i < 3; ++i) {
        cols[3 * a + i] = f.vdof[a] + i;
        rows[3 * a + i] = mask[f.vdof[a] + i] ? -1 : f.vdof[a] + i;
      }
    FSI_CALL(MatSetValuesLocal(J, 18, rows, 18, cols, &K[0][0], ADD_VALUES));
  }
}

} // namespace fsi
