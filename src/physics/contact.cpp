#include "fsi/physics/contact.hpp"
#include "fsi/physics/fluid.hpp"
#include "fsi/physics/physics_registry.hpp"
#include "fsi/physics/solid.hpp"
#include "fsi/scene/option_doc.hpp"
#include "fsi/scene/options.hpp"

#include <cmath>

namespace fsi {

ContactParams ContactParams::from_options() {
  ContactParams p;
  p.surface = opt::string("contact_surface", p.surface);
  if (!opt::has("contact_offset"))
    throw InputError("-physics contact needs -contact_offset [m]: the gap the leaflets keep "
                     "(e.g. 3/4 of the geometric gap between them)");
  p.offset = opt::positive("contact_offset", 1);
  p.penalty = opt::positive("contact_penalty", p.penalty);
  p.ramp = opt::positive("contact_ramp", 0.25 * p.offset);
  p.margin = opt::positive("contact_pattern_margin", p.offset);
  p.walls = opt::list("contact_walls");
  p.wall_offset = opt::positive("contact_wall_offset", p.offset);
  p.wall_exclude = opt::positive("contact_wall_exclude", 2 * p.wall_offset);
  p.axis.radius = opt::nonnegative("contact_axis_radius", 0);
  if (opt::has("contact_axis")) {
    const std::vector<double> a = opt::reals("contact_axis");
    const double n = a.size() == 6 ? std::sqrt(a[3] * a[3] + a[4] * a[4] + a[5] * a[5]) : 0;
    if (n == 0)
      throw InputError("option -contact_axis takes a point and a direction, X,Y,Z,EX,EY,EZ (6 "
                       "numbers, the direction not zero), e.g. 0,0,0,0,0,1");
    for (int i = 0; i < 3; ++i) {
      p.axis.point[i] = a[i];
      p.axis.dir[i] = a[3 + i] / n;
    }
  }
  if (p.axis.on() && p.ramp > p.axis.radius)
    throw InputError("option -contact_ramp (" + std::to_string(p.ramp) +
                     ") must not exceed -contact_axis_radius (" + std::to_string(p.axis.radius) +
                     ")");
  if (p.ramp > p.offset)
    throw InputError("option -contact_ramp (" + std::to_string(p.ramp) +
                     ") must not exceed -contact_offset (" + std::to_string(p.offset) + ")");
  if (!p.walls.empty() && p.ramp > p.wall_offset)
    throw InputError("option -contact_ramp (" + std::to_string(p.ramp) +
                     ") must not exceed -contact_wall_offset (" + std::to_string(p.wall_offset) +
                     ")");
  return p;
}

double ContactParams::pressure(double p) const {
  if (p <= 0) return 0;
  return p < ramp ? penalty * p * p / (2 * ramp) : penalty * (p - 0.5 * ramp);
}

double ContactParams::pressure_slope(double p) const {
  if (p <= 0) return 0;
  return p < ramp ? penalty * p / ramp : penalty;
}

ContactModule::ContactModule(std::shared_ptr<ContactSurface> surface, const ContactParams &p,
                             std::shared_ptr<ContactWall> wall)
    : surface_(std::move(surface)), p_(p), wall_(std::move(wall)) {
  if (!wall_) return;
  // The surface as built is its reference configuration: nodes near the walls there (along
  // the attachment) are held by the wall already and take no wall contact.
  const ContactSurface &S = *surface_;
  wall_node_.assign(S.n_nodes(), 0);
  for (int n = 0; n < S.n_nodes(); ++n) {
    int t;
    TriRegion r;
    wall_node_[n] = wall_->nearest(S.x(n), t, r) > p_.wall_exclude;
  }
}

std::string ContactModule::name() const {
  char s[200];
  std::snprintf(s, sizeof s, "contact (penalty %g Pa/m, offset %g m, %d pieces)", p_.penalty,
                p_.offset, surface_->n_components());
  std::string name = s;
  if (wall_) {
    int n = 0;
    for (char c : wall_node_)
      n += c;
    std::snprintf(s, sizeof s, "; rigid walls %s (%d triangles, offset %g m, %d of %d nodes)",
                  opt::join(p_.walls).c_str(), wall_->n_triangles(), p_.wall_offset, n,
                  surface_->n_nodes());
    name += s;
  }
  if (p_.axis.on()) {
    const double *a = p_.axis.point, *e = p_.axis.dir;
    std::snprintf(s, sizeof s, "; axis rod radius %g m through (%g, %g, %g) along (%g, %g, %g)",
                  p_.axis.radius, a[0], a[1], a[2], e[0], e[1], e[2]);
    name += s;
  }
  return name;
}

std::vector<ContactModule::Pair> ContactModule::pairs_within(double radius, bool all) {
  ContactSurface &S = *surface_;
  S.bin(radius);
  std::vector<Pair> pairs;
  const int nc = S.n_components();
  std::vector<Pair> best(nc);
  for (int n = 0; n < S.n_nodes(); ++n) {
    for (auto &b : best)
      b = {n, -1, radius, TriRegion::face};
    const int cn = S.component(n);
    S.near(S.x(n), [&](int t) {
      const int ct = S.triangle_component(t);
      if (ct == cn) return;
      const auto &tr = S.triangle(t);
      TriRegion region;
      const double d = point_triangle_distance(S.x(n), S.x(tr[0]), S.x(tr[1]), S.x(tr[2]), region);
      if (all && d < radius) pairs.push_back({n, t, d, region});
      if (d < best[ct].d) best[ct] = {n, t, d, region};
    });
    if (!all)
      for (const Pair &b : best)
        if (b.tri >= 0) pairs.push_back(b);
  }
  return pairs;
}

std::vector<ContactModule::Touch> ContactModule::touching() {
  const ContactSurface &S = *surface_;
  std::vector<Touch> out;
  for (const Pair &pr : pairs_within(p_.offset)) {
    const double *x = S.x(pr.node);
    out.push_back({{x[0], x[1], x[2]}, S.component(pr.node), S.triangle_component(pr.tri)});
  }
  return out;
}

double ContactModule::smallest_gap(double radius) {
  double d = radius;
  for (const Pair &pr : pairs_within(radius))
    d = std::min(d, pr.d);
  return d;
}

void ContactModule::pick_pairs() {
  picked_ = pairs_within(p_.offset + p_.margin);
  picked_valid_ = true;
}

void ContactModule::pick_wall_triangles() {
  if (!wall_) return;
  const ContactSurface &S = *surface_;
  wall_pick_.assign(S.n_nodes(), WallPick{});
  for (int n = 0; n < S.n_nodes(); ++n)
    if (wall_node_[n]) wall_->nearest(S.x(n), wall_pick_[n].t, wall_pick_[n].region);
}

template <class F> void ContactModule::for_each_active(F &&f) {
  const ContactSurface &S = *surface_;
  if (!picked_valid_) pick_pairs(); // no solve begun yet
  for (const Pair &pr : picked_) {
    const auto &tr = S.triangle(pr.tri);
    double d, g[12], H[12][12];
    point_triangle_distance_derivatives(S.x(pr.node), S.x(tr[0]), S.x(tr[1]), S.x(tr[2]), pr.region,
                                        d, g, H);
    if (d >= p_.offset || d <= 1e-9 * p_.offset) continue; // out of reach, or passed through
    const int nodes[4] = {pr.node, tr[0], tr[1], tr[2]};
    f(nodes, p_.offset - d, 0.5 * S.area(pr.node), g, H);
  }
  if (p_.axis.on()) {
    const double R = p_.axis.radius;
    axis_min_distance_ = 1e300;
    for (int n = 0; n < S.n_nodes(); ++n) {
      const double r = p_.axis.distance(S.x(n));
      axis_min_distance_ = std::min(axis_min_distance_, r);
      if (r >= R || r <= 1e-9 * R) continue;
      double g[12] = {}, H[12][12] = {}, g3[3], H3[3][3];
      p_.axis.distance(S.x(n), g3, H3);
      for (int i = 0; i < 3; ++i) {
        g[i] = g3[i];
        for (int j = 0; j < 3; ++j)
          H[i][j] = H3[i][j];
      }
      const int nodes[4] = {n, -2, -2, -2};
      f(nodes, R - r, S.area(n), g, H); // one way: the whole node area
    }
  }
  if (!wall_) return;
  wall_min_gap_ = wall_->radius();
  if (wall_pick_.size() != (size_t)S.n_nodes()) pick_wall_triangles(); // no solve begun yet
  for (int n = 0; n < S.n_nodes(); ++n) {
    if (!wall_node_[n] || wall_pick_[n].t < 0) continue;
    const int t = wall_pick_[n].t;
    double d, g[12], H[12][12];
    point_triangle_distance_derivatives(S.x(n), wall_->corner(t, 0), wall_->corner(t, 1),
                                        wall_->corner(t, 2), wall_pick_[n].region, d, g, H);
    wall_min_gap_ = std::min(wall_min_gap_, d);
    if (d >= p_.wall_offset || d <= 1e-9 * p_.wall_offset) continue;
    const int nodes[4] = {n, -1, -1, -1};
    f(nodes, p_.wall_offset - d, S.area(n), g, H); // one way: the whole node area
  }
}

void ContactModule::begin_solve(const StepContext &ctx) {
  surface_->update(ctx);
  pick_wall_triangles();
  // Each node's nearest triangle (and the part of it that is nearest) is picked once per solve,
  // among the nodes within offset + margin: the distance to a faceted surface has a kink where
  // two triangles (or a face and an edge) are equally near, and a node on it that switched from
  // one iterate to the next stalled Newton at a linear rate (the pressure-driven valve's closure
  // at 364.3 ms, at any step size), as the wall's facets did at 102.5 ms.
  pick_pairs();
  // The pattern must hold every pair within offset + margin (each node's nearest triangle per
  // piece).  When it lacks one, it grows to every node-triangle pair within offset + 2 margin,
  // nearest or not, so that it does not grow again until the surfaces have moved by a margin:
  // each new pattern is a new matrix and a new factorisation (the opening valve rebuilt it 9
  // times in 6 steps, as nodes slid from one nearest triangle to the next).
  int grew = 0, any;
  for (const Pair &pr : picked_) // the pairs within offset + margin, just picked
    for (int k : surface_->triangle(pr.tri))
      grew = grew || !pattern_.count(key(pr.node, k));
  MPI_Allreduce(&grew, &any, 1, MPI_INT, MPI_MAX, surface_->comm());
  changed_ = any != 0;
  pending_ = pattern_;
  if (changed_)
    for (const Pair &pr : pairs_within(p_.offset + 2 * p_.margin, true))
      for (int k : surface_->triangle(pr.tri))
        pending_.insert(key(pr.node, k));
}

void ContactModule::pattern_built() {
  pattern_ = pending_;
  changed_ = false;
}

void ContactModule::global_couplings(std::vector<PetscInt> &pairs) const {
  pairs.clear();
  for (unsigned long long k : pending_) {
    pairs.push_back(surface_->global_dof((int)(k >> 32)));
    pairs.push_back(surface_->global_dof((int)(k & 0xffffffffu)));
  }
}

void ContactModule::add_residual(const StepContext &, PetscScalar *F) {
  const ContactSurface &S = *surface_;
  stats_ = ContactStats{0, 0, 0, stats_.pattern_misses};
  for_each_active([&](const int *nodes, double pen, double w, const double *g, auto &) {
    const double f = w * p_.pressure(pen);
    if (nodes[1] == -1)
      stats_.wall_pairs++;
    else if (nodes[1] == -2)
      stats_.axis_pairs++;
    else
      stats_.active_pairs++;
    stats_.max_penetration = std::max(stats_.max_penetration, pen);
    stats_.force += f;
    for (int a = 0; a < 4 && nodes[a] >= 0; ++a) {
      const PetscInt l = S.owned_local_dof(nodes[a]);
      if (l < 0) continue;
      for (int i = 0; i < 3; ++i)
        F[l + i] -= f * g[3 * a + i]; // dE/dx = psi'(p) dp/dx = -psi'(p) dd/dx
    }
  });
  stats_.wall_min_gap = wall_min_gap_;
  stats_.axis_min_distance = axis_min_distance_;
}

void ContactModule::add_jacobian(const StepContext &ctx, Mat J) {
  const ContactSurface &S = *surface_;
  const std::vector<char> &bc = *ctx.is_dirichlet;
  const double cu = ctx.disp_shift();
  for_each_active([&](const int *nodes, double pen, double w, const double *g,
                      const double(&H)[12][12]) {
    const double f = w * p_.pressure(pen), fs = w * p_.pressure_slope(pen);
    // d2E/dx2 = psi'' g g^T - psi' H
    double K[12][12];
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j)
        K[i][j] = cu * (fs * g[i] * g[j] - f * H[i][j]);
    for (int a = 0; a < 4 && nodes[a] >= 0; ++a) {
      const PetscInt l = S.owned_local_dof(nodes[a]);
      if (l < 0 || bc[l]) continue;
      PetscInt rows[3], cols[12];
      double vals[3][12];
      int nc = 0;
      for (int b = 0; b < 4 && nodes[b] >= 0; ++b) {
        const bool coupled = a == b || (a > 0 && b > 0) || pattern_.count(key(nodes[a], nodes[b]));
        if (!coupled) {
          stats_.pattern_misses++;
          continue;
        }
        for (int j = 0; j < 3; ++j) {
          cols[nc + j] = S.global_dof(nodes[b]) + j;
          for (int i = 0; i < 3; ++i)
            vals[i][nc + j] = K[3 * a + i][3 * b + j];
        }
        nc += 3;
      }
      for (int i = 0; i < 3; ++i)
        rows[i] = S.global_dof(nodes[a]) + i;
      double packed[3 * 12];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < nc; ++j)
          packed[i * nc + j] = vals[i][j];
      FSI_CALL(MatSetValues(J, 3, rows, nc, cols, packed, ADD_VALUES));
    }
  });
}

void ContactModule::add_to(MonitorRow &row) const {
  row.add("contact_pairs", (double)stats_.active_pairs);
  row.add("contact_max_penetration", stats_.max_penetration);
  row.add("contact_force", stats_.force);
  if (!p_.walls.empty()) {
    row.add("contact_wall_pairs", (double)stats_.wall_pairs);
    row.add("contact_wall_min_gap", stats_.wall_min_gap);
  }
  if (p_.axis.on()) {
    row.add("contact_axis_pairs", (double)stats_.axis_pairs);
    row.add("contact_axis_min_distance", stats_.axis_min_distance);
  }
}

// Leaflets touching: a penalty between the pieces of the solid's surface, optionally against
// rigid fluid walls and an axis rod.
void make_contact(PhysicsBuild &b) {
  const ContactParams &cp = b.contact_params();
  auto surface = b.contact_surface();
  std::shared_ptr<ContactWall> wall;
  if (!cp.walls.empty()) {
    if (!b.fluid)
      throw InputError("-contact_walls needs a fluid: the walls are fluid boundary groups");
    b.mesh.require_groups(cp.walls, "the rigid contact walls (-contact_walls)");
    wall = std::make_shared<ContactWall>(b.space, b.mesh, cp.walls, b.fluid->cells(),
                                         std::max(cp.wall_exclude, 3 * cp.wall_offset));
  }
  auto c = std::make_unique<ContactModule>(surface, cp, wall);
  // With a fluid between them, pieces closer than the offset at rest would be pushed apart
  // through the fluid at the first step: the offset is the gap touching pieces keep, it must
  // fit in the mesh's.  (A solid alone may start pressed: a preloaded contact.)
  const double g = b.fluid ? c->smallest_gap(2 * cp.offset) : 2 * cp.offset;
  if (g <= cp.offset)
    throw InputError("-contact_offset " + std::to_string(cp.offset) +
                     " m is not below the smallest gap between the contact pieces of the "
                     "mesh as built (" +
                     std::to_string(g) +
                     " m): at rest they would be pushed apart; use a smaller offset or "
                     "mesh a wider gap (valve.geo: gap, and gapw for the strip leaflets)");
  b.contact = c.get();
  b.modules.push_back(std::move(c));
}

// Its options, for -help and docs/options.md (option_doc.hpp).
OptionSection contact_options() {
  return {
      "Contact between solid pieces (-physics contact; its surface and rod also serve gap_seal)",
      {{"contact_surface", "interface", "-", "boundary group of the solid's contact surface"},
       {"contact_offset", "(required)", "m", "gap the pieces keep (penalty acts below it)"},
       {"contact_penalty", "1e8", "Pa/m", "contact pressure per metre of penetration"},
       {"contact_ramp", "offset/4", "m", "width over which the contact pressure ramps in"},
       {"contact_pattern_margin", "offset", "m",
        "pairs this much beyond the offset are kept in the Jacobian's pattern"},
       {"contact_walls", "(none)", "-",
        "rigid fluid boundary groups the contact surface keeps away from, e.g. root_wall"},
       {"contact_wall_offset", "offset", "m", "gap the surface keeps from the walls"},
       {"contact_wall_exclude", "2 wall_offset", "m",
        "surface nodes this close to a wall in the reference shape (attachment) take no wall "
        "contact"},
       {"contact_axis_radius", "0 (none)", "m",
        "a virtual rigid rod of this radius along the axis: the surface keeps it from the "
        "line (the fluid where three leaflets meet), and the gap seal counts it as a piece"},
       {"contact_axis", "0,0,0,0,0,1", "m,-", "the rod's axis: a point X,Y,Z and a direction"}}};
}

} // namespace fsi
