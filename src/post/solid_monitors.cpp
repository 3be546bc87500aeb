#include "fsi/post/solid_monitors.hpp"
#include "fsi/scene/option_doc.hpp"
#include "fsi/scene/options.hpp"

#include <cmath>

namespace fsi {

void SolidMonitors::setup(const Space &space, const SolidModule *solid, const ExactSolid *exact) {
  space_ = &space;
  solid_ = solid;
  exact_ = solid ? exact : nullptr;
  const auto pts = parse_points("solid_probe_points");
  energy_ = opt::flag("monitor_solid_energy", false);
  if (!solid && (!pts.empty() || energy_))
    throw InputError("-solid_probe_points / -monitor_solid_energy need a solid in the scene");
  for (auto &x : pts) {
    PointLocation loc = locate_point(space, solid->cells(), x.data(), solid->material_X().data());
    if (loc.owner < 0)
      throw InputError("solid probe point " + std::to_string(x[0]) + "," + std::to_string(x[1]) +
                       "," + std::to_string(x[2]) + " lies outside the solid");
    probes_.push_back(loc);
  }
}

std::vector<std::string> SolidMonitors::columns() const {
  std::vector<std::string> c;
  for (size_t k = 0; k < probes_.size(); ++k)
    for (auto q : {"ux", "uy", "uz"})
      c.push_back("solid_probe" + std::to_string(k) + "_" + q);
  if (energy_)
    for (auto q : {"energy_kinetic", "energy_strain", "energy_total"})
      c.push_back(q);
  if (exact_)
    for (auto q : {"err_u_l2", "err_u_rel"})
      c.push_back(q);
  return c;
}

std::vector<double> SolidMonitors::evaluate(const FieldView &view) {
  std::vector<double> out;
  if (!solid_) return out;
  MPI_Comm comm = PetscObjectComm((PetscObject)space_->dm);
  int rank;
  MPI_Comm_rank(comm, &rank);
  const PetscScalar *D = view.d, *V = view.u;
  for (auto &p : probes_) {
    double val[3] = {}, g[3];
    if (p.owner == rank) {
      double N[10], dN[10][3], gl[4][3] = {};
      p2_tet(p.lambda, gl, N, dN);
      for (int a = 0; a < 10; ++a)
        for (int i = 0; i < 3; ++i)
          val[i] += N[a] * PetscRealPart(D[space_->cell_vdof[10 * p.cell + a] + i]);
    }
    MPI_Allreduce(val, g, 3, MPI_DOUBLE, MPI_SUM, comm);
    out.insert(out.end(), g, g + 3);
  }
  if (energy_) {
    const SolidEnergy e = solid_->energy(V, D);
    out.insert(out.end(), {e.kinetic, e.strain, e.total()});
  }
  if (exact_) {
    static const QuadRule rule = tet_rule(6);
    double acc[2] = {}, glob[2];
    for (PetscInt k : solid_->cells()) {
      double X[4][3];
      space_->cell_points(k, space_->X.data(), X);
      TetGeometry g;
      g.set(X);
      for (size_t q = 0; q < rule.weight.size(); ++q) {
        const double *l = rule.lambda[q].data();
        double N[10], dN[10][3], x[3] = {0, 0, 0}, uh[3] = {0, 0, 0}, ue[3];
        p2_tet(l, g.grad_lambda, N, dN);
        for (int i = 0; i < 4; ++i)
          for (int d = 0; d < 3; ++d)
            x[d] += l[i] * X[i][d];
        for (int a = 0; a < 10; ++a)
          for (int d = 0; d < 3; ++d)
            uh[d] += N[a] * PetscRealPart(D[space_->cell_vdof[10 * k + a] + d]);
        exact_->displacement(x, view.t, ue);
        const double w = rule.weight[q] * g.absdet;
        for (int d = 0; d < 3; ++d) {
          acc[0] += w * (uh[d] - ue[d]) * (uh[d] - ue[d]);
          acc[1] += w * ue[d] * ue[d];
        }
      }
    }
    MPI_Allreduce(acc, glob, 2, MPI_DOUBLE, MPI_SUM, comm);
    err_ = std::sqrt(glob[0]);
    err_rel_ = err_ / std::max(std::sqrt(glob[1]), 1e-300);
    out.insert(out.end(), {err_, err_rel_});
  }
  return out;
}

void SolidMonitors::summarize(Json &j, bool stepped) const {
  if (!exact_ || !stepped) return;
  Json err;
  err.set("displacement_l2", err_).set("displacement_l2_relative", err_rel_);
  j.set("error_final", err);
}

std::unique_ptr<Monitor> make_solid_monitors(const MonitorSetup &m) {
  auto s = std::make_unique<SolidMonitors>();
  s->setup(m.space, m.solid, m.exact_solid);
  if (!s->active()) return nullptr;
  return s;
}

// Its options, for -help and docs/options.md (option_doc.hpp).
OptionSection solid_monitor_options() {
  return {"Solid monitors",
          {{"solid_probe_points", "", "m", "solid displacement probes at material points"},
           {"monitor_solid_energy", "false", "-", "kinetic and stored energy of the solid"}}};
}

} // namespace fsi
