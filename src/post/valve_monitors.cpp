#include "fsi/post/valve_monitors.hpp"
#include "fsi/boundary/boundary_condition.hpp"
#include "fsi/scene/option_doc.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <cmath>

namespace fsi {

void ValveMonitors::setup(const Space &space, const FluidModule *fluid, const SolidModule *solid,
                          ContactModule *contact) {
  active_ = opt::has("valve_annulus_radius");
  if (!active_) return;
  contact_ = contact;
  touching_gap_ = contact ? contact->params().offset : 0.0;
  space_ = &space;
  solid_ = solid;
  fluid_ = fluid;
  comm_ = PetscObjectComm((PetscObject)space.dm);
  if (!fluid || !solid)
    throw InputError("-valve_annulus_radius needs a fluid and a solid (-physics fluid,solid)");
  // One radius: a circle.  N >= 3: a closed polar curve, radius k at angle 2 pi k / N from e1
  // (an annulus that is not round, e.g. a patient's: scripts/make_scene writes it).
  radii_ = opt::reals("valve_annulus_radius");
  if (radii_.size() == 2 || radii_.empty() || *std::min_element(radii_.begin(), radii_.end()) <= 0)
    throw InputError("option -valve_annulus_radius needs one radius [m] or N >= 3 positive radii "
                     "at equal angles from the annulus frame's first axis");
  R_ = *std::max_element(radii_.begin(), radii_.end());
  annulus_area_ = 0;
  for (size_t k = 0; k < radii_.size(); ++k) { // 1/2 integral of r(phi)^2, r linear in phi
    const double a = radii_[k], b = radii_[(k + 1) % radii_.size()];
    annulus_area_ += M_PI / radii_.size() * (a * a + a * b + b * b) / 3;
  }
  if (opt::has("valve_center")) c_ = read_point("valve_center");
  axis_ = {0, 0, 1};
  if (opt::has("valve_axis")) read_direction("valve_axis", axis_.data());
  // An orthonormal frame (e1, e2, axis) of the annulus plane.
  const std::array<double, 3> t =
      std::fabs(axis_[0]) < 0.9 ? std::array<double, 3>{1, 0, 0} : std::array<double, 3>{0, 1, 0};
  double dot = t[0] * axis_[0] + t[1] * axis_[1] + t[2] * axis_[2], n = 0;
  for (int d = 0; d < 3; ++d)
    e1_[d] = t[d] - dot * axis_[d], n += e1_[d] * e1_[d];
  for (int d = 0; d < 3; ++d)
    e1_[d] /= std::sqrt(n);
  e2_ = {axis_[1] * e1_[2] - axis_[2] * e1_[1], axis_[2] * e1_[0] - axis_[0] * e1_[2],
         axis_[0] * e1_[1] - axis_[1] * e1_[0]};
  pixels_ = (int)opt::integer_at_least("valve_goa_pixels", 400, 10);

  auto planes = opt::reals("valve_dp_planes");
  if (planes.size() != 2 || !(planes[0] < 0 && planes[1] > 0))
    throw InputError("option -valve_dp_planes needs two axial positions a,b [m] from the annulus "
                     "centre, upstream a < 0 and downstream b > 0");
  down_at_ = planes[1];
  const double rp =
      opt::positive("valve_dp_radius", 0.8 * *std::min_element(radii_.begin(), radii_.end()));
  // Disc samples: rings of equal width, 6 i points on ring i, each with its ring area share.
  const int rings = 6;
  for (int side = 0; side < 2; ++side) {
    auto &plane = side == 0 ? up_ : down_;
    for (int i = 0; i < rings; ++i) {
      const double r0 = rp * i / rings, r1 = rp * (i + 1) / rings, r = 0.5 * (r0 + r1);
      const int m = i == 0 ? 1 : 6 * i;
      for (int j = 0; j < m; ++j) {
        const double a = 2 * M_PI * (j + 0.5 * (i % 2)) / m, rr = i == 0 ? 0 : r;
        double x[3];
        for (int d = 0; d < 3; ++d)
          x[d] =
              c_[d] + planes[side] * axis_[d] + rr * (std::cos(a) * e1_[d] + std::sin(a) * e2_[d]);
        Sample s;
        s.at = locate_point(space, fluid->cells(), x);
        if (s.at.owner < 0)
          throw InputError("-valve_dp_planes: the point " + std::to_string(x[0]) + "," +
                           std::to_string(x[1]) + "," + std::to_string(x[2]) +
                           " lies outside the fluid: check the planes and -valve_dp_radius");
        s.weight = M_PI * (r1 * r1 - r0 * r0) / m;
        plane.push_back(s);
      }
    }
  }
}

std::vector<std::string> ValveMonitors::columns() const {
  if (!active_) return {};
  std::vector<std::string> c = {"valve_p_up",
                                "valve_p_down",
                                "valve_dp",
                                "valve_goa",
                                "valve_goa_ratio",
                                "valve_leaflet_umax",
                                "valve_leaflet_vm_max",
                                "valve_peak_velocity",
                                "valve_peak_velocity_axial"};
  if (touching_gap_ > 0) c.push_back("valve_goa_contact_ratio");
  return c;
}

double ValveMonitors::plane_mean_pressure(const std::vector<Sample> &plane,
                                          const PetscScalar *u) const {
  int rank;
  MPI_Comm_rank(comm_, &rank);
  double acc[2] = {0, 0}, glob[2];
  for (auto &s : plane) {
    if (s.at.owner != rank) continue;
    double p = 0;
    for (int i = 0; i < 4; ++i)
      p += s.at.lambda[i] * PetscRealPart(u[space_->cell_pdof[4 * s.at.cell + i]]);
    acc[0] += s.weight * p;
    acc[1] += s.weight;
  }
  MPI_Allreduce(acc, glob, 2, MPI_DOUBLE, MPI_SUM, comm_);
  return glob[0] / glob[1];
}

// Every P2 velocity node of every fluid cell (a node shared by cells is seen more than once: the
// maximum does not mind); edge nodes sit at their edge's midpoint (cells are affine).
std::array<double, 2> ValveMonitors::peak_velocity(const PetscScalar *u,
                                                   const std::vector<double> &x) const {
  double best[2] = {0, 0};
  for (PetscInt k : fluid_->cells()) {
    double X[4][3], p[10][3];
    space_->cell_points(k, x.data(), X);
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d)
        p[a][d] = X[a][d];
    for (int e = 0; e < 6; ++e)
      for (int d = 0; d < 3; ++d)
        p[4 + e][d] = 0.5 * (X[TET_EDGE[e][0]][d] + X[TET_EDGE[e][1]][d]);
    for (int a = 0; a < 10; ++a) {
      double s = 0, v2 = 0;
      for (int d = 0; d < 3; ++d)
        s += (p[a][d] - c_[d]) * axis_[d];
      if (s < 0 || s > down_at_) continue;
      const PetscInt off = space_->cell_vdof[10 * k + a];
      for (int d = 0; d < 3; ++d)
        v2 += std::pow(PetscRealPart(u[off + d]), 2);
      if (v2 > best[0] * best[0]) best[0] = std::sqrt(v2), best[1] = s;
    }
  }
  // The largest speed over the ranks, and the axial position where it is.
  struct {
    double v;
    int rank;
  } mine{best[0], 0}, top;
  MPI_Comm_rank(comm_, &mine.rank);
  MPI_Allreduce(&mine, &top, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm_);
  double at = best[1];
  MPI_Bcast(&at, 1, MPI_DOUBLE, top.rank, comm_);
  return {top.v, at};
}

std::vector<double> ValveMonitors::coaptation(const std::vector<ContactModule::Touch> &touch,
                                              int pieces) const {
  const double bin = 0.001; // [m] radial bin width
  double height = -1, length = -1;
  for (int a = 0; a < pieces; ++a)
    for (int b = a + 1; b < pieces; ++b) {
      // Per radial bin: the lowest and highest touching node of this seam (either side).
      std::vector<std::array<double, 2>> span;
      double rmin = 1e300, rmax = -1e300;
      for (const auto &t : touch) {
        if (!((t.piece == a && t.other == b) || (t.piece == b && t.other == a))) continue;
        double s = 0, r2 = 0, q[3];
        for (int d = 0; d < 3; ++d)
          q[d] = t.x[d] - c_[d], s += q[d] * axis_[d];
        for (int d = 0; d < 3; ++d)
          r2 += std::pow(q[d] - s * axis_[d], 2);
        const double r = std::sqrt(r2);
        rmin = std::min(rmin, r), rmax = std::max(rmax, r);
        const size_t i = (size_t)(r / bin);
        if (span.size() <= i) span.resize(i + 1, {1e300, -1e300});
        span[i] = {std::min(span[i][0], s), std::max(span[i][1], s)};
      }
      std::vector<double> h;
      for (auto &sp : span)
        if (sp[1] >= sp[0]) h.push_back(sp[1] - sp[0]);
      double seam_h = 0, seam_l = 0;
      if (!h.empty()) {
        std::nth_element(h.begin(), h.begin() + h.size() / 2, h.end());
        seam_h = h[h.size() / 2], seam_l = rmax - rmin;
      }
      height = height < 0 ? seam_h : std::min(height, seam_h);
      length = length < 0 ? seam_l : std::min(length, seam_l);
    }
  return {std::max(height, 0.0), std::max(length, 0.0)};
}

bool ValveMonitors::in_annulus(double px, double py) const {
  const double r2 = px * px + py * py;
  if (radii_.size() == 1) return r2 < R_ * R_;
  double s = std::atan2(py, px) / (2 * M_PI);
  s = (s < 0 ? s + 1 : s) * radii_.size();
  const size_t k = std::min((size_t)s, radii_.size() - 1);
  const double w = s - k, r = (1 - w) * radii_[k] + w * radii_[(k + 1) % radii_.size()];
  return r2 < r * r;
}

// Raster of the annulus disc (or polar curve); a pixel is covered when its centre lies in the
// projection of a face of a deformed leaflet cell (the union of a tetrahedron's face projections is
// its shadow).
std::array<double, 2> ValveMonitors::orifice_area(const std::vector<double> &x) const {
  const int n = pixels_;
  const double hpix = 2 * R_ / n;
  std::vector<unsigned char> covered(size_t(n) * n, 0), all(size_t(n) * n);
  auto project = [&](const double *p, double q[2]) {
    double r[3];
    for (int d = 0; d < 3; ++d)
      r[d] = p[d] - c_[d];
    q[0] = r[0] * e1_[0] + r[1] * e1_[1] + r[2] * e1_[2];
    q[1] = r[0] * e2_[0] + r[1] * e2_[1] + r[2] * e2_[2];
  };
  static const int FACE[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  const auto &cells = solid_->cells();
  for (size_t c = 0; c < cells.size(); ++c) {
    double q[4][2];
    for (int i = 0; i < 4; ++i)
      project(&x[12 * c + 3 * i], q[i]);
    for (auto &f : FACE) {
      const double *a = q[f[0]], *b = q[f[1]], *cc = q[f[2]];
      const double det = (b[0] - a[0]) * (cc[1] - a[1]) - (b[1] - a[1]) * (cc[0] - a[0]);
      if (std::fabs(det) < 1e-30) continue;
      const double lo0 = std::min({a[0], b[0], cc[0]}), hi0 = std::max({a[0], b[0], cc[0]});
      const double lo1 = std::min({a[1], b[1], cc[1]}), hi1 = std::max({a[1], b[1], cc[1]});
      const int i0 = std::max(0, (int)std::floor((lo0 + R_) / hpix - 0.5));
      const int i1 = std::min(n - 1, (int)std::ceil((hi0 + R_) / hpix - 0.5));
      const int j0 = std::max(0, (int)std::floor((lo1 + R_) / hpix - 0.5));
      const int j1 = std::min(n - 1, (int)std::ceil((hi1 + R_) / hpix - 0.5));
      for (int i = i0; i <= i1; ++i)
        for (int j = j0; j <= j1; ++j) {
          const double px = -R_ + (i + 0.5) * hpix, py = -R_ + (j + 0.5) * hpix;
          const double l1 = ((px - a[0]) * (cc[1] - a[1]) - (py - a[1]) * (cc[0] - a[0])) / det;
          const double l2 = ((b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0])) / det;
          if (l1 >= 0 && l2 >= 0 && l1 + l2 <= 1) covered[size_t(i) * n + j] = 1;
        }
    }
  }
  MPI_Allreduce(covered.data(), all.data(), n * n, MPI_UNSIGNED_CHAR, MPI_MAX, comm_);
  // The shadow grown by half the touching gap: a disc of that radius about every covered pixel
  // (pixels within it of a covered one), so that a gap narrower than the touching gap closes.
  const int m = (int)std::floor(0.5 * touching_gap_ / hpix);
  std::vector<unsigned char> grown = all;
  if (m > 0)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        if (!all[size_t(i) * n + j]) continue;
        for (int a = std::max(0, i - m); a <= std::min(n - 1, i + m); ++a)
          for (int b = std::max(0, j - m); b <= std::min(n - 1, j + m); ++b)
            if ((a - i) * (a - i) + (b - j) * (b - j) <= m * m) grown[size_t(a) * n + b] = 1;
      }
  long open = 0, open_grown = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double px = -R_ + (i + 0.5) * hpix, py = -R_ + (j + 0.5) * hpix;
      if (!in_annulus(px, py)) continue;
      open += !all[size_t(i) * n + j];
      open_grown += !grown[size_t(i) * n + j];
    }
  return {open * hpix * hpix, open_grown * hpix * hpix};
}

void ValveMonitors::add_to(MonitorRow &row, const FieldView &view) {
  row.add(columns(), [&] { return evaluate(view); });
  // The seams of a valve of two or three leaflets.
  const int pieces = contact_ ? contact_->n_pieces() : 0;
  if (pieces == 2 || pieces == 3)
    row.add({"valve_coaptation_height", "valve_coaptation_length"},
            [&] { return coaptation(contact_->touching(), pieces); });
}

std::vector<double> ValveMonitors::evaluate(const FieldView &view) {
  if (!active_) return {};
  const PetscScalar *u = view.u, *D = view.d;
  const double pu = plane_mean_pressure(up_, u), pd = plane_mean_pressure(down_, u);
  const std::array<double, 2> vpeak = peak_velocity(u, *view.x);

  // Deformed leaflet vertices, the largest displacement and the largest von Mises stress (at the
  // cell centres: P2 displacement, linear stress).
  const auto &cells = solid_->cells();
  const auto &X0 = solid_->material_X();
  std::vector<double> x(12 * cells.size());
  double umax = 0, vm = 0;
  for (size_t c = 0; c < cells.size(); ++c) {
    const PetscInt k = cells[c];
    double X[4][3], uc[10][3];
    space_->cell_points(k, X0.data(), X);
    for (int a = 0; a < 10; ++a)
      for (int d = 0; d < 3; ++d)
        uc[a][d] = PetscRealPart(D[space_->cell_vdof[10 * k + a] + d]);
    for (int i = 0; i < 4; ++i) {
      double m = 0;
      for (int d = 0; d < 3; ++d)
        x[12 * c + 3 * i + d] = X[i][d] + uc[i][d], m += uc[i][d] * uc[i][d];
      umax = std::max(umax, std::sqrt(m));
    }
    TetGeometry g;
    g.set(X);
    const double l[4] = {0.25, 0.25, 0.25, 0.25};
    double N[10], dN[10][3], F[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, P[3][3];
    p2_tet(l, g.grad_lambda, N, dN);
    for (int a = 0; a < 10; ++a)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          F[i][j] += uc[a][i] * dN[a][j];
    const double Xc[3] = {0.25 * (X[0][0] + X[1][0] + X[2][0] + X[3][0]),
                          0.25 * (X[0][1] + X[1][1] + X[2][1] + X[3][1]),
                          0.25 * (X[0][2] + X[1][2] + X[2][2] + X[3][2])};
    solid_->stress(F, Xc, P);
    const double J = F[0][0] * (F[1][1] * F[2][2] - F[1][2] * F[2][1]) -
                     F[0][1] * (F[1][0] * F[2][2] - F[1][2] * F[2][0]) +
                     F[0][2] * (F[1][0] * F[2][1] - F[1][1] * F[2][0]);
    double s[3][3] = {}; // Cauchy: P F^T / J
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        for (int m = 0; m < 3; ++m)
          s[i][j] += P[i][m] * F[j][m];
        s[i][j] /= J;
      }
    const double v =
        std::sqrt(0.5 * (std::pow(s[0][0] - s[1][1], 2) + std::pow(s[1][1] - s[2][2], 2) +
                         std::pow(s[2][2] - s[0][0], 2)) +
                  3 * (s[0][1] * s[0][1] + s[1][2] * s[1][2] + s[0][2] * s[0][2]));
    vm = std::max(vm, v);
  }
  double loc[2] = {umax, vm}, glob[2];
  MPI_Allreduce(loc, glob, 2, MPI_DOUBLE, MPI_MAX, comm_);
  const std::array<double, 2> goa = orifice_area(x);
  const double disc = annulus_area_;
  std::vector<double> v = {pu,      pd,      pu - pd,  goa[0],  goa[0] / disc,
                           glob[0], glob[1], vpeak[0], vpeak[1]};
  if (touching_gap_ > 0) v.push_back(goa[1] / disc);
  return v;
}

std::unique_ptr<Monitor> make_valve_monitors(const MonitorSetup &m) {
  auto v = std::make_unique<ValveMonitors>();
  v->setup(m.space, m.fluid, m.solid, m.contact);
  if (!v->active()) return nullptr;
  return v;
}

// Its options, for -help and docs/options.md (option_doc.hpp).
OptionSection valve_monitor_options() {
  return {"Valve monitors",
          {{"valve_annulus_radius", "", "m",
            "valve monitors on: dp, orifice area, leaflet u and stress; N >= 3 radii: a polar "
            "annulus, radius k at 2 pi k/N from the frame's first axis"},
           {"valve_center", "0,0,0", "m", "annulus centre"},
           {"valve_axis", "0,0,1", "-", "valve axis (flow direction)"},
           {"valve_dp_planes", "", "m", "axial positions a < 0 < b of the pressure discs"},
           {"valve_dp_radius", "0.8 R", "m", "radius of the pressure discs"},
           {"valve_goa_pixels", "400", "-", "orifice-area raster size per side"}}};
}

} // namespace fsi
