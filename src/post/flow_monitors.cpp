#include "fsi/post/flow_monitors.hpp"
#include "fsi/post/locate.hpp"
#include "fsi/scene/option_doc.hpp"
#include "fsi/scene/options.hpp"

#include <cmath>

namespace fsi {

void FlowMonitors::setup(const Mesh &mesh, const Space &space, const FluidModule *fluid,
                         const ExactFlow *exact) {
  space_ = &space;
  fluid_ = fluid;
  exact_ = fluid ? exact : nullptr;
  comm_ = PetscObjectComm((PetscObject)space.dm);
  surf_names_ = opt::list("monitor_surfaces");
  if (!surf_names_.empty() && !fluid)
    throw InputError("-monitor_surfaces needs a fluid in the scene");
  mesh.require_groups(surf_names_, "-monitor_surfaces");
  std::vector<char> in_fluid(space.n_cells(), 0);
  if (fluid)
    for (PetscInt k : fluid->cells())
      in_fluid[k] = 1;
  for (auto &n : surf_names_)
    surf_faces_.push_back(space.boundary_faces(mesh, n, &in_fluid));

  volume_ = opt::flag("monitor_fluid_volume", false);
  if (volume_ && !fluid) throw InputError("-monitor_fluid_volume needs a fluid in the scene");
  energy_ = opt::flag("monitor_fluid_energy", false);
  if (energy_ && !fluid) throw InputError("-monitor_fluid_energy needs a fluid in the scene");
  for (auto &x : parse_points("probe_points")) {
    if (!fluid) throw InputError("-probe_points needs a fluid (solid points: -solid_probe_points)");
    PointLocation loc = locate_point(space, fluid->cells(), x.data());
    if (loc.owner < 0)
      throw InputError("probe point " + std::to_string(x[0]) + "," + std::to_string(x[1]) + "," +
                       std::to_string(x[2]) + " lies outside the fluid mesh");
    Probe p;
    for (int d = 0; d < 3; ++d)
      p.x[d] = x[d];
    p.owner = loc.owner;
    p.cell = loc.cell;
    for (int i = 0; i < 4; ++i)
      p.lambda[i] = loc.lambda[i];
    probes_.push_back(p);
  }
}

std::vector<std::string> FlowMonitors::columns() const {
  std::vector<std::string> c;
  for (auto &n : surf_names_)
    for (auto q : {"flux", "area", "fx", "fy", "fz", "p"})
      c.push_back(n + "_" + q);
  for (size_t k = 0; k < probes_.size(); ++k) {
    const std::string p = "probe" + std::to_string(k) + "_";
    for (auto q : {"vx", "vy", "vz", "p"})
      c.push_back(p + q);
    if (exact_)
      for (auto q : {"vx_exact", "vy_exact", "vz_exact", "p_exact"})
        c.push_back(p + q);
  }
  if (exact_)
    for (auto q : {"err_v_l2", "err_p_l2", "err_v_rel", "err_p_rel"})
      c.push_back(q);
  if (volume_) c.push_back("fluid_volume");
  if (energy_)
    for (auto q : {"fluid_energy_kinetic", "fluid_dissipation", "fluid_convective_power"})
      c.push_back(q);
  return c;
}

ErrorNorms FlowMonitors::errors(const PetscScalar *u, const std::vector<double> &Xv, double tv,
                                const std::vector<double> &Xp, double tp) const {
  static const QuadRule rule = tet_rule(6);
  // sums: |ev|^2, |v|^2, ep^2, p^2, int ep, int p, volume, (div vh)^2
  double acc[8] = {};
  for (PetscInt k : fluid_->cells()) {
    double X[4][3], XP[4][3];
    for (int i = 0; i < 4; ++i)
      for (int d = 0; d < 3; ++d) {
        X[i][d] = Xv[3 * space_->cell_vertex[4 * k + i] + d];
        XP[i][d] = Xp[3 * space_->cell_vertex[4 * k + i] + d];
      }
    TetGeometry g, gp;
    g.set(X);
    gp.set(XP);
    for (size_t q = 0; q < rule.weight.size(); ++q) {
      const double *l = rule.lambda[q].data();
      double N[10], dN[10][3], x[3] = {0, 0, 0}, xp[3] = {0, 0, 0}, vh[3] = {0, 0, 0}, ph = 0,
                               ve[3], div = 0;
      p2_tet(l, g.grad_lambda, N, dN);
      for (int i = 0; i < 4; ++i)
        for (int d = 0; d < 3; ++d) {
          x[d] += l[i] * X[i][d];
          xp[d] += l[i] * XP[i][d];
        }
      for (int a = 0; a < 10; ++a)
        for (int d = 0; d < 3; ++d) {
          const double ua = PetscRealPart(u[space_->cell_vdof[10 * k + a] + d]);
          vh[d] += N[a] * ua;
          div += dN[a][d] * ua;
        }
      for (int i = 0; i < 4; ++i)
        ph += l[i] * PetscRealPart(u[space_->cell_pdof[4 * k + i]]);
      exact_->velocity(x, tv, ve);
      const double pe = exact_->pressure(xp, tp);
      const double w = rule.weight[q] * g.absdet, wp = rule.weight[q] * gp.absdet;
      for (int d = 0; d < 3; ++d) {
        acc[0] += w * (vh[d] - ve[d]) * (vh[d] - ve[d]);
        acc[1] += w * ve[d] * ve[d];
      }
      acc[2] += wp * (ph - pe) * (ph - pe);
      acc[3] += wp * pe * pe;
      acc[4] += wp * (ph - pe);
      acc[5] += wp * pe;
      acc[6] += wp;
      acc[7] += w * div * div;
    }
  }
  double glob[8];
  MPI_Allreduce(acc, glob, 8, MPI_DOUBLE, MPI_SUM, comm_);
  ErrorNorms e;
  e.v_l2 = std::sqrt(glob[0]);
  e.div_l2 = std::sqrt(glob[7]);
  e.v_norm = std::sqrt(glob[1]);
  double ep2 = glob[2], p2 = glob[3];
  if (!exact_->pressure_level_defined()) { // compare up to a constant
    ep2 -= glob[4] * glob[4] / glob[6];
    p2 -= glob[5] * glob[5] / glob[6];
  }
  e.p_l2 = std::sqrt(std::max(ep2, 0.0));
  e.p_norm = std::sqrt(std::max(p2, 0.0));
  return e;
}

// Kinetic energy, dissipation (viscous, and grad-div's gamma (div v)^2 when on) and convective
// power of this rank's cells (sums in e[3]); degree 6: |v|^2 (div v) is degree 5 on straight-sided
// P2 cells.
void FlowMonitors::energy(const PetscScalar *u, const std::vector<double> &Xc, double e[3]) const {
  static const QuadRule rule = tet_rule(6);
  const double rho = fluid_->params().rho, mu = fluid_->params().mu, gd = fluid_->params().grad_div;
  for (PetscInt k : fluid_->cells()) {
    double X[4][3], ve[10][3];
    for (int i = 0; i < 4; ++i)
      for (int d = 0; d < 3; ++d)
        X[i][d] = Xc[3 * space_->cell_vertex[4 * k + i] + d];
    for (int a = 0; a < 10; ++a)
      for (int d = 0; d < 3; ++d)
        ve[a][d] = PetscRealPart(u[space_->cell_vdof[10 * k + a] + d]);
    TetGeometry g;
    g.set(X);
    for (size_t q = 0; q < rule.weight.size(); ++q) {
      double N[10], dN[10][3], v[3] = {0, 0, 0}, G[3][3] = {};
      p2_tet(rule.lambda[q].data(), g.grad_lambda, N, dN);
      for (int a = 0; a < 10; ++a)
        for (int i = 0; i < 3; ++i) {
          v[i] += N[a] * ve[a][i];
          for (int j = 0; j < 3; ++j)
            G[i][j] += ve[a][i] * dN[a][j];
        }
      const double w = rule.weight[q] * g.absdet, v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
      double dd = 0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const double s = 0.5 * (G[i][j] + G[j][i]);
          dd += s * s;
        }
      e[0] += w * 0.5 * rho * v2;
      const double div = G[0][0] + G[1][1] + G[2][2];
      e[1] += w * (2 * mu * dd + gd * div * div);
      e[2] += w * 0.5 * rho * div * v2;
    }
  }
}

std::vector<double> FlowMonitors::evaluate(const FieldView &view) {
  std::vector<double> out;
  if (!fluid_) return out;
  const PetscScalar *u = view.u;
  const auto &Xc = *view.x;
  const double mu = fluid_->params().mu, t = view.t;
  static const QuadRule frule = tri_rule(4);

  std::vector<double> surf;
  for (auto &faces : surf_faces_) {
    double s[6] = {}; // flux, area, fx, fy, fz, int p
    for (auto &f : faces) {
      const PetscInt k = f.cell;
      double X[4][3];
      int pos[3] = {-1, -1, -1};
      for (int i = 0; i < 4; ++i) {
        const int v = space_->cell_vertex[4 * k + i];
        for (int d = 0; d < 3; ++d)
          X[i][d] = Xc[3 * v + d];
        for (int j = 0; j < 3; ++j)
          if (f.vertex[j] == v) pos[j] = i;
      }
      TetGeometry g;
      g.set(X);
      double n[3];
      const double J2 = outward_normal(f, Xc.data(), n);
      for (size_t q = 0; q < frule.weight.size(); ++q) {
        double l[4] = {0, 0, 0, 0};
        for (int j = 0; j < 3; ++j)
          l[pos[j]] = frule.lambda[q][j];
        double N[10], dN[10][3], v[3] = {0, 0, 0}, G[3][3] = {}, p = 0;
        p2_tet(l, g.grad_lambda, N, dN);
        for (int a = 0; a < 10; ++a)
          for (int i = 0; i < 3; ++i) {
            const double ua = PetscRealPart(u[space_->cell_vdof[10 * k + a] + i]);
            v[i] += N[a] * ua;
            for (int j = 0; j < 3; ++j)
              G[i][j] += ua * dN[a][j];
          }
        for (int i = 0; i < 4; ++i)
          p += l[i] * PetscRealPart(u[space_->cell_pdof[4 * k + i]]);
        const double w = frule.weight[q] * J2;
        s[0] += w * (v[0] * n[0] + v[1] * n[1] + v[2] * n[2]);
        s[1] += w;
        for (int i = 0; i < 3; ++i) {
          double sn = -p * n[i];
          for (int j = 0; j < 3; ++j)
            sn += mu * (G[i][j] + G[j][i]) * n[j];
          s[2 + i] -= w * sn;
        }
        s[5] += w * p;
      }
    }
    double gs[6];
    MPI_Allreduce(s, gs, 6, MPI_DOUBLE, MPI_SUM, comm_);
    out.insert(out.end(), {gs[0], gs[1], gs[2], gs[3], gs[4], gs[1] > 0 ? gs[5] / gs[1] : 0.0});
  }

  int rank;
  MPI_Comm_rank(comm_, &rank);
  for (auto &p : probes_) {
    double val[8] = {};
    if (p.owner == rank) {
      double N[10], dN[10][3], gl[4][3] = {};
      p2_tet(p.lambda, gl, N, dN);
      const PetscInt k = p.cell;
      for (int a = 0; a < 10; ++a)
        for (int i = 0; i < 3; ++i)
          val[i] += N[a] * PetscRealPart(u[space_->cell_vdof[10 * k + a] + i]);
      double x[3] = {0, 0, 0};
      for (int i = 0; i < 4; ++i) {
        val[3] += p.lambda[i] * PetscRealPart(u[space_->cell_pdof[4 * k + i]]);
        for (int d = 0; d < 3; ++d)
          x[d] += p.lambda[i] * Xc[3 * space_->cell_vertex[4 * k + i] + d];
      }
      if (exact_) {
        exact_->velocity(x, t, val + 4);
        val[7] = exact_->pressure(x, t);
      }
    }
    double g[8];
    MPI_Allreduce(val, g, 8, MPI_DOUBLE, MPI_SUM, comm_);
    out.insert(out.end(), g, g + (exact_ ? 8 : 4));
  }
  if (exact_) {
    err_ = errors(u, Xc, t, *view.x_af, view.t_af);
    out.insert(out.end(), {err_.v_l2, err_.p_l2, err_.v_l2 / std::max(err_.v_norm, 1e-300),
                           err_.p_l2 / std::max(err_.p_norm, 1e-300)});
  }
  if (volume_) {
    double vol = 0, gvol;
    for (PetscInt k : fluid_->cells()) {
      double X[4][3];
      for (int i = 0; i < 4; ++i)
        for (int d = 0; d < 3; ++d)
          X[i][d] = Xc[3 * space_->cell_vertex[4 * k + i] + d];
      TetGeometry g;
      g.set(X);
      vol += g.absdet / 6;
    }
    MPI_Allreduce(&vol, &gvol, 1, MPI_DOUBLE, MPI_SUM, comm_);
    out.push_back(gvol);
  }
  if (energy_) {
    double e[3] = {0, 0, 0}, g[3];
    energy(u, Xc, e);
    MPI_Allreduce(e, g, 3, MPI_DOUBLE, MPI_SUM, comm_);
    out.insert(out.end(), g, g + 3);
  }
  return out;
}

void FlowMonitors::summarize(Json &j, bool stepped) const {
  if (!exact_ || !stepped) return;
  Json err;
  err.set("velocity_l2", err_.v_l2)
      .set("pressure_l2", err_.p_l2)
      .set("divergence_l2", err_.div_l2)
      .set("velocity_l2_relative", err_.v_l2 / err_.v_norm)
      .set("pressure_l2_relative", err_.p_l2 / err_.p_norm);
  j.set("error_final", err);
}

std::unique_ptr<Monitor> make_flow_monitors(const MonitorSetup &m) {
  auto f = std::make_unique<FlowMonitors>();
  f->setup(m.mesh, m.space, m.fluid, m.exact);
  if (!f->active()) return nullptr;
  return f;
}

// Its options, for -help and docs/options.md (option_doc.hpp).
OptionSection flow_monitor_options() {
  return {"Flow monitors",
          {{"monitor_surfaces", "", "-", "flux, area, force, mean pressure per named boundary"},
           {"monitor_fluid_volume", "false", "-", "fluid volume per step"},
           {"monitor_fluid_energy", "false", "-",
            "fluid kinetic energy, dissipation (viscous + grad-div), convective form's power per "
            "step"},
           {"probe_points", "", "m", "fluid probes x,y,z;x,y,z"}}};
}

} // namespace fsi
