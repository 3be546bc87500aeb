#include "fsi/physics/gap_seal.hpp"
#include "fsi/physics/contact_geometry.hpp"
#include "fsi/physics/fluid.hpp"
#include "fsi/physics/physics_registry.hpp"
#include "fsi/scene/option_doc.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <cmath>

namespace fsi {

GapSealParams GapSealParams::from_options(double offset, const AxisLine &axis) {
  GapSealParams p;
  p.axis = axis;
  p.resistance = opt::positive("gap_seal_resistance", p.resistance);
  p.gap_closed = opt::positive("gap_seal_gap_closed", 1.25 * offset);
  p.gap_open = opt::positive("gap_seal_gap_open", 2 * offset);
  p.ramp_time = opt::nonnegative("gap_seal_ramp_time", 0);
  if (p.gap_open <= p.gap_closed)
    throw InputError("option -gap_seal_gap_open (" + std::to_string(p.gap_open) +
                     " m) must be larger than -gap_seal_gap_closed (" +
                     std::to_string(p.gap_closed) + " m)");
  return p;
}

GapSeal::GapSeal(const Space &space, const std::vector<PetscInt> &fluid_cells,
                 std::shared_ptr<ContactSurface> surface, const GapSealParams &p)
    : space_(space), cells_(fluid_cells), surface_(std::move(surface)), p_(p) {
  alpha_.assign(cells_.size(), 0.0);
  alpha_prev_.assign(cells_.size(), -1.0); // none yet: the first step takes its target
  const QuadRule rule = tet_rule(4);
  double gl[4][3] = {}, N[10], dN[10][3];
  for (auto &row : M_)
    for (double &m : row)
      m = 0;
  for (size_t q = 0; q < rule.weight.size(); ++q) {
    p2_tet(rule.lambda[q].data(), gl, N, dN);
    for (int a = 0; a < 10; ++a)
      for (int b = 0; b < 10; ++b)
        M_[a][b] += rule.weight[q] * N[a] * N[b];
  }
}

std::string GapSeal::name() const {
  char s[200];
  std::snprintf(s, sizeof s, "gap seal (Brinkman %g Pa s/m^2 below a %g-%g m gap%s)", p_.resistance,
                p_.gap_closed, p_.gap_open, p_.axis.on() ? ", the axis rod a piece" : "");
  return s;
}

// Search radius around a centroid: a gap can be open at most gap_open wide, and a centroid
// inside the axis rod sees the rod at -R.
double GapSeal::reach() const {
  return p_.gap_open + p_.axis.radius;
}

// Target resistance at point c: from the two nearest pieces of the surface (the axis rod one).
double GapSeal::target(const double c[3], std::vector<double> &best) const {
  const ContactSurface &S = *surface_;
  double d1 = reach(), d2 = reach();
  int c1 = -1;
  best.assign(S.n_components() + (p_.axis.on() ? 1 : 0), reach());
  if (p_.axis.on()) best.back() = p_.axis.distance(c) - p_.axis.radius;
  S.near(c, [&](int t) {
    const auto &tr = S.triangle(t);
    TriRegion r;
    const double d = point_triangle_distance(c, S.x(tr[0]), S.x(tr[1]), S.x(tr[2]), r);
    double &b = best[S.triangle_component(t)];
    b = std::min(b, d);
  });
  for (int k = 0; k < (int)best.size(); ++k)
    if (best[k] < d1) {
      d1 = best[k];
      c1 = k;
    }
  for (int k = 0; k < (int)best.size(); ++k)
    if (k != c1) d2 = std::min(d2, best[k]);
  const double g = std::max(0.0, d1 + d2);
  double s = (p_.gap_open - g) / (p_.gap_open - p_.gap_closed);
  s = std::clamp(s, 0.0, 1.0);
  return p_.resistance * s * s * (3 - 2 * s);
}

void GapSeal::begin_solve(const StepContext &ctx) {
  surface_->update(ctx);
  surface_->bin(reach());
  if (ctx.t_n != t_last_) { // a new step: the last one's resistance is the lag's start
    if (t_last_ > -1e300) alpha_prev_ = alpha_;
    t_last_ = ctx.t_n;
  }
  const double relax = p_.ramp_time > 0 ? 1 - std::exp(-ctx.dt / p_.ramp_time) : 1.0;
  int sealing = 0;
  double amax = 0;
  std::vector<double> best; // distance to each piece, reused for every cell
  for (size_t c = 0; c < cells_.size(); ++c) {
    double x[3] = {0, 0, 0};
    for (int i = 0; i < 4; ++i)
      for (int d = 0; d < 3; ++d)
        x[d] += 0.25 * ctx.X_af[3 * space_.cell_vertex[4 * cells_[c] + i] + d];
    const double a = target(x, best), prev = alpha_prev_[c];
    alpha_[c] = prev < 0 ? a : prev + (a - prev) * relax;
    sealing += sealed(c);
    amax = std::max(amax, alpha_[c]);
  }
  MPI_Comm comm = PetscObjectComm((PetscObject)space_.dm);
  MPI_Allreduce(&sealing, &stats_.sealing_cells, 1, MPI_INT, MPI_SUM, comm);
  MPI_Allreduce(&amax, &stats_.max_alpha, 1, MPI_DOUBLE, MPI_MAX, comm);
}

// Velocity of the mesh at P2 node a of cell k (vertices: W; edges: the mean of their ends).
static double mesh_velocity(const Space &sp, const StepContext &ctx, PetscInt k, int a, int i) {
  if (!ctx.W) return 0.0;
  if (a < 4) return ctx.W[3 * sp.cell_vertex[4 * k + a] + i];
  const int va = sp.cell_vertex[4 * k + TET_EDGE[a - 4][0]];
  const int vb = sp.cell_vertex[4 * k + TET_EDGE[a - 4][1]];
  return 0.5 * (ctx.W[3 * va + i] + ctx.W[3 * vb + i]);
}

double GapSeal::absdet_af(const StepContext &ctx, PetscInt k) const {
  double X[4][3];
  space_.cell_points(k, ctx.X_af, X);
  TetGeometry geo;
  geo.set(X);
  return geo.absdet;
}

void GapSeal::add_residual(const StepContext &ctx, PetscScalar *F) {
  for (size_t c = 0; c < cells_.size(); ++c) {
    if (alpha_[c] <= 0) continue;
    const PetscInt k = cells_[c];
    const double s = alpha_[c] * absdet_af(ctx, k);
    const PetscInt *vd = &space_.cell_vdof[10 * k];
    double r[10][3];
    for (int b = 0; b < 10; ++b)
      for (int i = 0; i < 3; ++i)
        r[b][i] = ctx.v_af(vd[b] + i) - mesh_velocity(space_, ctx, k, b, i);
    for (int a = 0; a < 10; ++a)
      for (int i = 0; i < 3; ++i) {
        double v = 0;
        for (int b = 0; b < 10; ++b)
          v += M_[a][b] * r[b][i];
        F[vd[a] + i] += s * v;
      }
  }
}

void GapSeal::add_jacobian(const StepContext &ctx, Mat J) {
  const std::vector<char> &bc = *ctx.is_dirichlet;
  for (size_t c = 0; c < cells_.size(); ++c) {
    if (alpha_[c] <= 0) continue;
    const PetscInt k = cells_[c];
    const double s = alpha_[c] * absdet_af(ctx, k) * ctx.stiff_shift();
    const PetscInt *vd = &space_.cell_vdof[10 * k];
    PetscInt rows[30], cols[30];
    double K[30][30] = {};
    for (int a = 0; a < 10; ++a)
      for (int i = 0; i < 3; ++i) {
        cols[3 * a + i] = vd[a] + i;
        rows[3 * a + i] = bc[vd[a] + i] ? -1 : vd[a] + i;
        for (int b = 0; b < 10; ++b)
          K[3 * a + i][3 * b + i] = s * M_[a][b];
      }
    FSI_CALL(MatSetValuesLocal(J, 30, rows, 30, cols, &K[0][0], ADD_VALUES));
  }
}

void GapSeal::add_to(MonitorRow &row) const {
  row.add("seal_cells", (double)stats_.sealing_cells);
  row.add("seal_max_alpha", stats_.max_alpha);
}

// A resistance that seals the fluid in the gaps between the contact surface's pieces.
void make_gap_seal(PhysicsBuild &b) {
  const ContactParams &cp = b.contact_params();
  auto g = std::make_unique<GapSeal>(b.space, b.fluid->cells(), b.contact_surface(),
                                     GapSealParams::from_options(cp.offset, cp.axis));
  b.seal = g.get();
  b.modules.push_back(std::move(g));
}

// Its options, for -help and docs/options.md (option_doc.hpp).
OptionSection gap_seal_options() {
  return {
      "Gap seal (-physics gap_seal)",
      {{"gap_seal_resistance", "1e8", "Pa s/m^2", "Brinkman resistance of a closed gap"},
       {"gap_seal_gap_closed", "1.25 offset", "m", "gap width at full resistance"},
       {"gap_seal_gap_open", "2 offset", "m", "gap width where the resistance starts"},
       {"gap_seal_ramp_time", "0", "s",
        "time lag of the resistance (0: none); the lag starts afresh after a remesh or restart"}}};
}

} // namespace fsi
