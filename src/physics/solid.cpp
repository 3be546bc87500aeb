#include "fsi/physics/solid.hpp"
#include "fsi/physics/material.hpp"
#include "fsi/physics/physics_registry.hpp"
#include "fsi/scene/option_doc.hpp"
#include "fsi/scene/options.hpp"

#include <cstring>
#include <numeric>

namespace fsi {

SolidParams SolidParams::from_options() {
  SolidParams p;
  p.region = opt::string("solid_region", "solid");
  p.rho = opt::positive("solid_rho", p.rho);
  if (opt::has("solid_gravity")) {
    auto g = opt::reals("solid_gravity");
    if (g.size() != 3) throw InputError("option -solid_gravity needs 3 numbers gx,gy,gz [m/s^2]");
    for (int i = 0; i < 3; ++i)
      p.gravity[i] = g[i];
    // Gravity's own waveform (-solid_gravity_waveform ...); in steady load stepping it ramps
    // with the load steps by default (linear over [0, ts_max_time]), as boundary loads do
    // with a linear waveform: full gravity on the first step defeats load stepping.
    const bool steady = opt::choice("ts_type", "alpha", {"alpha", "steady"}) == "steady";
    if (steady && !opt::has("solid_gravity_waveform")) {
      p.gravity_wave.kind = Waveform::Linear;
      p.gravity_wave.period = opt::positive("ts_max_time", 1.0);
    } else {
      p.gravity_wave = Waveform::from_options("solid_gravity_");
    }
  }
  p.quad_degree = (int)opt::integer("solid_quad_degree", 3);
  if (p.quad_degree < 2 || p.quad_degree > 10)
    throw InputError("option -solid_quad_degree must be in [2, 10]");
  p.direct_insertion = opt::flag("solid_direct_insertion", true);
  p.fibres = FibreFamily::from_options(opt::string("solid_material", "linear"));
  return p;
}

SolidModule::SolidModule(const Space &space, const Mesh &mesh,
                         const std::vector<double> &material_X, const SolidParams &p,
                         std::unique_ptr<Material> material, const ExactSolid *exact)
    : space_(space), material_X_(material_X), p_(p), material_(std::move(material)), exact_(exact) {
  comm_ = PetscObjectComm((PetscObject)space.dm);
  mesh.require_groups({p.region}, "the solid (-solid_region)");
  cells_ = mesh.cells_in(p.region);
  for (auto &c : cells_)
    c -= space.cStart;
  rule_ = tet_rule(p.quad_degree);
  ref_ = P2Integrals(rule_);
  // A constant tangent's stiffness is quadratic on an affine cell: 4 points instead of 11-14.
  jacobian_rule_ = material_->constant_tangent() ? tet_rule(2) : rule_;
  dofs_.resize(30 * cells_.size());
  for (size_t c = 0; c < cells_.size(); ++c)
    for (int a = 0; a < 10; ++a)
      for (int i = 0; i < 3; ++i)
        dofs_[30 * c + 3 * a + i] = space.cell_vdof[10 * cells_[c] + a] + i;
  jacobian_order_ = locality_order(dofs_, 30);
  for (auto &l : rule_.lambda) {
    std::array<double, 10> n;
    double gl[4][3] = {}, dn[10][3];
    p2_tet(l.data(), gl, n.data(), dn);
    N_.push_back(n);
  }
}

void SolidModule::stress(const double F[3][3], const double X[3], double P[3][3]) const {
  material_->stress(F, P);
  if (!p_.fibres.active()) return;
  double a[3];
  p_.fibres.direction(X, a);
  p_.fibres.add_stress(F, a, P);
}

void SolidModule::fibre_direction(const double *l, const double X[4][3], double a[3]) const {
  double x[3]; // the reference point at barycentric coordinates l of the affine cell
  for (int d = 0; d < 3; ++d)
    x[d] = l[0] * X[0][d] + l[1] * X[1][d] + l[2] * X[2][d] + l[3] * X[3][d];
  p_.fibres.direction(x, a);
}

void SolidModule::reference_geometry(PetscInt k, TetGeometry &g, double X[4][3]) const {
  space_.cell_points(k, material_X_.data(), X);
  g.set(X);
}

void SolidModule::add_residual(const StepContext &ctx, PetscScalar *R) {
  const double rho = p_.rho;
  const bool inertia = !ctx.steady;
  const double g_scale = p_.gravity_wave(ctx.t_af);
  for (PetscInt k : cells_) {
    TetGeometry geo;
    double X[4][3], u[10][3], acc[10][3] = {};
    reference_geometry(k, geo, X);
    const PetscInt *vd = &space_.cell_vdof[10 * k];
    for (int a = 0; a < 10; ++a)
      for (int i = 0; i < 3; ++i) {
        u[a][i] = ctx.u_af(vd[a] + i);
        if (inertia) acc[a][i] = ctx.a_am(vd[a] + i);
      }
    double Re[10][3] = {};
    for (size_t q = 0; q < rule_.weight.size(); ++q) {
      const double *l = rule_.lambda[q].data();
      const double *N = N_[q].data();
      double Nd[10], dN[10][3];
      p2_tet(l, geo.grad_lambda, Nd, dN);
      double F[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, a[3] = {}, P[3][3];
      for (int b = 0; b < 10; ++b)
        for (int i = 0; i < 3; ++i) {
          a[i] += N[b] * acc[b][i];
          for (int J = 0; J < 3; ++J)
            F[i][J] += u[b][i] * dN[b][J];
        }
      material_->stress(F, P);
      if (p_.fibres.active()) {
        double fa[3];
        fibre_direction(l, X, fa);
        p_.fibres.add_stress(F, fa, P);
      }
      double f[3]; // inertia minus body force, per unit reference volume
      for (int i = 0; i < 3; ++i)
        f[i] = rho * (a[i] - g_scale * p_.gravity[i]);
      if (exact_) {
        double x[3] = {0, 0, 0}, b[3];
        for (int v = 0; v < 4; ++v)
          for (int d = 0; d < 3; ++d)
            x[d] += l[v] * X[v][d];
        exact_->body_force(*material_, rho, x, ctx.t_af, b);
        for (int i = 0; i < 3; ++i)
          f[i] -= b[i];
      }
      const double w = rule_.weight[q] * geo.absdet;
      for (int a2 = 0; a2 < 10; ++a2)
        for (int i = 0; i < 3; ++i)
          Re[a2][i] +=
              w * (N[a2] * f[i] + P[i][0] * dN[a2][0] + P[i][1] * dN[a2][1] + P[i][2] * dN[a2][2]);
    }
    for (int a = 0; a < 10; ++a)
      for (int i = 0; i < 3; ++i)
        R[vd[a] + i] += Re[a][i];
  }
}

// Per quadrature point the material stiffness K_ab,ik += w dN_a,J A_iJkL dN_b,L is formed in
// two contractions over arrays with the node index innermost (Y over a, then K over b), which
// the compiler vectorises, for the (i, k) blocks with i <= k only (the tangent's major symmetry
// gives the others); the mass is the reference mass matrix times rho cm |det|.
void SolidModule::add_jacobian(const StepContext &ctx, Mat Jmat) {
  const double cm = ctx.mass_shift() * p_.rho, cu = ctx.disp_shift();
  const std::vector<char> &bc = *ctx.is_dirichlet;
  constexpr int n = 30;
  const bool fast = p_.direct_insertion;
  static const std::vector<int> groups(10, 3); // the 10 nodes' components
  if (fast && !assembler_.ready()) assembler_.setup(Jmat, space_, dofs_, n, bc, groups);
  if (fast) assembler_.begin(Jmat);
  double K[n][n];
  double Kb[3][3][10][10]; // (i, k, a, b)
  const bool constant = material_->constant_tangent();
  double A[3][3][3][3], P[3][3];
  if (constant) {
    const double I[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    material_->tangent(I, P, A);
  }
  for (size_t c : jacobian_order_) {
    const PetscInt k = cells_[c];
    TetGeometry geo;
    double X[4][3], u[10][3];
    reference_geometry(k, geo, X);
    const PetscInt *vd = &space_.cell_vdof[10 * k];
    if (!constant) // a constant tangent needs no displacement
      for (int a = 0; a < 10; ++a)
        for (int i = 0; i < 3; ++i)
          u[a][i] = ctx.u_af(vd[a] + i);
    std::memset(Kb, 0, sizeof Kb);
    for (size_t q = 0; q < jacobian_rule_.weight.size(); ++q) {
      const double *l = jacobian_rule_.lambda[q].data();
      double Nd[10], dN[10][3], dNT[3][10];
      p2_tet(l, geo.grad_lambda, Nd, dN);
      for (int b = 0; b < 10; ++b)
        for (int J = 0; J < 3; ++J)
          dNT[J][b] = dN[b][J];
      if (!constant) {
        double F[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        for (int b = 0; b < 10; ++b)
          for (int J = 0; J < 3; ++J)
            for (int i = 0; i < 3; ++i)
              F[i][J] += u[b][i] * dN[b][J];
        material_->tangent(F, P, A);
        if (p_.fibres.active()) {
          double a[3];
          fibre_direction(l, X, a);
          p_.fibres.add_tangent(F, a, P, A);
        }
      }
      const double wk = jacobian_rule_.weight[q] * geo.absdet * cu;
      for (int i = 0; i < 3; ++i)
        for (int kk = i; kk < 3; ++kk) { // K_ba,ki = K_ab,ik (A's major symmetry)
          double Y[3][10];               // Y[L][a] = wk sum_J dN_a,J A_iJkL
          for (int L = 0; L < 3; ++L) {
            const double c0 = wk * A[i][0][kk][L], c1 = wk * A[i][1][kk][L],
                         c2 = wk * A[i][2][kk][L];
            for (int a = 0; a < 10; ++a)
              Y[L][a] = c0 * dNT[0][a] + c1 * dNT[1][a] + c2 * dNT[2][a];
          }
          for (int a = 0; a < 10; ++a) {
            const double y0 = Y[0][a], y1 = Y[1][a], y2 = Y[2][a];
            double *kr = Kb[i][kk][a];
            for (int b = 0; b < 10; ++b)
              kr[b] += y0 * dNT[0][b] + y1 * dNT[1][b] + y2 * dNT[2][b];
          }
        }
    }
    const double sm = cm * geo.absdet;
    for (int a = 0; a < 10; ++a)
      for (int i = 0; i < 3; ++i)
        for (int b = 0; b < 10; ++b)
          for (int kk = 0; kk < 3; ++kk)
            K[3 * a + i][3 * b + kk] =
                (i <= kk ? Kb[i][kk][a][b] : Kb[kk][i][b][a]) + (i == kk ? sm * ref_.M[a][b] : 0.0);
    if (fast) {
      assembler_.add(Jmat, c, &K[0][0]);
      continue;
    }
    PetscInt rows[n], cols[n];
    for (int a = 0; a < n; ++a) {
      cols[a] = dofs_[n * c + a];
      rows[a] = bc[cols[a]] ? -1 : cols[a];
    }
    FSI_CALL(MatSetValuesLocal(Jmat, n, rows, n, cols, &K[0][0], ADD_VALUES));
  }
  if (fast) assembler_.end(Jmat);
}

SolidEnergy SolidModule::energy(const PetscScalar *V, const PetscScalar *D) const {
  SolidEnergy e;
  for (PetscInt k : cells_) { // cells are not shared between ranks (no overlap)
    TetGeometry geo;
    double X[4][3];
    reference_geometry(k, geo, X);
    const PetscInt *vd = &space_.cell_vdof[10 * k];
    for (size_t q = 0; q < rule_.weight.size(); ++q) {
      const double *N = N_[q].data();
      double Nd[10], dN[10][3];
      p2_tet(rule_.lambda[q].data(), geo.grad_lambda, Nd, dN);
      double F[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, v[3] = {};
      for (int b = 0; b < 10; ++b)
        for (int i = 0; i < 3; ++i) {
          v[i] += N[b] * PetscRealPart(V[vd[b] + i]);
          for (int J = 0; J < 3; ++J)
            F[i][J] += PetscRealPart(D[vd[b] + i]) * dN[b][J];
        }
      const double w = rule_.weight[q] * geo.absdet;
      e.kinetic += 0.5 * w * p_.rho * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      e.strain += w * material_->energy(F);
      if (p_.fibres.active()) {
        double a[3];
        fibre_direction(rule_.lambda[q].data(), X, a);
        e.strain += w * p_.fibres.energy(F, a);
      }
    }
  }
  double loc[2] = {e.kinetic, e.strain}, glob[2];
  MPI_Allreduce(loc, glob, 2, MPI_DOUBLE, MPI_SUM, comm_);
  e.kinetic = glob[0];
  e.strain = glob[1];
  return e;
}

void make_solid(PhysicsBuild &b) {
  b.exact_solid = make_exact_solid();
  auto s = std::make_unique<SolidModule>(b.space, b.mesh, b.material_X, SolidParams::from_options(),
                                         make_material(), b.exact_solid.get());
  b.solid = s.get();
  b.modules.push_back(std::move(s));
}

// Its options, for -help and docs/options.md (option_doc.hpp).
OptionSection solid_options() {
  return {
      "Solid (-physics solid)",
      {{"solid_region", "solid", "-", "physical volume of the solid"},
       {"solid_rho", "1000", "kg/m^3", "reference density"},
       {"solid_gravity", "0,0,0", "m/s^2", "body acceleration gx,gy,gz"},
       {"solid_gravity_waveform", "constant (steady: linear over ts_max_time)", "-",
        "gravity's time dependence; its _period, _ramp, ... as for bc_<b>_"},
       {"solid_material", "linear", "-", "linear | svk | neo_hookean | mooney_rivlin"},
       {"solid_E", "(required: linear, svk)", "Pa", "Young's modulus"},
       {"solid_nu", "0.3", "-", "Poisson's ratio"},
       {"solid_mu", "(neo_hookean)", "Pa", "shear modulus"},
       {"solid_kappa", "(neo_hookean, mooney_rivlin)", "Pa", "bulk modulus"},
       {"solid_C10", "(mooney_rivlin)", "Pa", "Mooney-Rivlin C10"},
       {"solid_C01", "0", "Pa", "Mooney-Rivlin C01"},
       {"solid_exp_c1", "0", "Pa",
        "neo_hookean/mooney_rivlin + c1/2 (exp(c2 (I1bar-3)^2) - 1): collagen-like stiffening"},
       {"solid_exp_c2", "0", "-", "exponent c2 of that term (both 0 or both positive)"},
       {"solid_fibres", "none", "-",
        "none | circumferential | chord: a fibre family c1/2 (exp(c2 (I4-1)^2) - 1), I4 > 1, "
        "about "
        "the z axis"},
       {"solid_fibre_c1", "(with solid_fibres)", "Pa", "fibre modulus c1"},
       {"solid_fibre_c2", "(with solid_fibres)", "-", "fibre exponent c2"},
       {"solid_fibre_tension_only", "true", "-",
        "fibres carry no compression (I4 < 1); false: the same law on both sides"},
       {"solid_fibre_commissures", "(chord)", "deg",
        "commissure angles about z; fibres run along the chord of each sector between them"},
       {"solid_quad_degree", "3", "-", "quadrature degree (3: 8 points, 4: 14, 2: 4)"},
       {"solid_direct_insertion", "true", "-", "element matrices straight into the AIJ arrays"}}};
}

} // namespace fsi
