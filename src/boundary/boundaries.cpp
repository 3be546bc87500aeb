#include "fsi/boundary/boundaries.hpp"
#include "fsi/scene/option_doc.hpp"
#include "fsi/scene/options.hpp"

namespace fsi {

static std::string type_list(const char *physics) {
  std::vector<std::string> names;
  for (auto &t : boundary_types())
    if (std::string(t.physics) == physics) names.push_back(t.name);
  return opt::join(names, "|");
}

Boundaries::Boundaries(const Mesh &mesh, const Space &space, const ExactFlow *exact,
                       const ExactSolid *exact_solid, double mu, double rho,
                       const std::vector<double> &material_X,
                       const std::vector<PetscInt> *fluid_cells)
    : space_(space), material_X_(material_X), exact_(exact) {
  mask_.assign(space.n_local, 0);
  owner_.assign(space.n_local, -1);
  const auto names = opt::list("bc_names");
  mesh.require_groups(names, "-bc_names");
  std::vector<std::string> all_types;
  for (auto &t : boundary_types())
    all_types.push_back(t.name);
  bool level_fixed = false;
  for (auto &n : names) {
    const std::string pre = "bc_" + n + "_";
    if (!opt::has(pre + "type"))
      throw InputError("boundary '" + n + "' is listed in -bc_names but has no -" + pre +
                       "type: give " + type_list("fluid") + " (fluid) or " + type_list("solid") +
                       " (solid)");
    const std::string type = opt::choice(pre + "type", "", all_types);
    BoundarySetup setup{mesh, space, exact, exact_solid, mu, rho, material_X, n};
    for (auto &t : boundary_types())
      if (type == t.name) bcs_.push_back(t.make(setup));
    const BoundaryCondition &bc = *bcs_.back();
    level_fixed = level_fixed || bc.fixes_pressure_level();
    // Precedence at shared nodes (see the header): the first BC listed with the highest rank.
    const int index = (int)bcs_.size() - 1;
    for (auto &nd : bc.nodes())
      for (int i = 0; i < 3; ++i) {
        if (!bc.fixed(i)) continue;
        const PetscInt dof = nd.dof + i;
        mask_[dof] = 1;
        if (owner_[dof] < 0 || bcs_[owner_[dof]]->precedence() < bc.precedence())
          owner_[dof] = index;
      }
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
    mine += space_.owned(i);
  MPI_Allreduce(&mine, &all, 1, MPI_LONG, MPI_SUM, PetscObjectComm((PetscObject)space_.dm));
  return all;
}

// Values of one BC's nodes that it owns, at node positions X (vertices, edge midpoints).
void Boundaries::node_values(const BoundaryCondition &bc, size_t index, double t, const double *X,
                             std::vector<std::pair<PetscInt, double>> &out) const {
  for (auto &nd : bc.nodes()) {
    double x[3], v[3];
    for (int d = 0; d < 3; ++d)
      x[d] = nd.vb < 0 ? X[3 * nd.va + d] : 0.5 * (X[3 * nd.va + d] + X[3 * nd.vb + d]);
    bc.value(x, t, v);
    for (int d = 0; d < 3; ++d)
      if (bc.fixed(d) && owner_[nd.dof + d] == (int)index) out.emplace_back(nd.dof + d, v[d]);
  }
}

void Boundaries::displacement_values(double t,
                                     std::vector<std::pair<PetscInt, double>> &out) const {
  out.clear();
  // Displacements are given at the nodes' material positions.
  for (size_t k = 0; k < bcs_.size(); ++k)
    if (bcs_[k]->data() == BoundaryCondition::Data::displacement)
      node_values(*bcs_[k], k, t, material_X_.data(), out);
}

void Boundaries::dirichlet_values(double t, const double *X,
                                  std::vector<std::pair<PetscInt, double>> &out) const {
  out.clear();
  const BoundaryCondition::OtherValues others = [&](int k, const double *x, double *v) {
    bcs_[k]->value(x, t, v);
  };
  for (size_t k = 0; k < bcs_.size(); ++k)
    if (bcs_[k]->data() == BoundaryCondition::Data::velocity)
      bcs_[k]->prepare_values(t, X, owner_, (int)k, others);
  for (size_t k = 0; k < bcs_.size(); ++k)
    if (bcs_[k]->data() == BoundaryCondition::Data::velocity) node_values(*bcs_[k], k, t, X, out);
  for (PetscInt i : outside_fluid_)
    out.emplace_back(i, 0.0);
  if (pin_dof_ >= 0) {
    double p = 0;
    if (exact_) p = exact_->pressure(&X[3 * pin_vertex_], t);
    out.emplace_back(pin_dof_, p);
  }
}

void Boundaries::add_residual(const StepContext &ctx, PetscScalar *F) const {
  for (auto &bc : bcs_)
    bc->add_residual(ctx, F);
}

void Boundaries::add_jacobian(const StepContext &ctx, Mat J) const {
  for (auto &bc : bcs_)
    bc->add_jacobian(ctx, J);
}

void Boundaries::accept_step() {
  for (auto &bc : bcs_)
    bc->accept_step();
}

void Boundaries::save_state(std::map<std::string, double> &s) const {
  for (auto &bc : bcs_)
    bc->save_state(s);
}

void Boundaries::restore_state(const std::map<std::string, double> &s) {
  for (auto &bc : bcs_)
    bc->restore_state(s);
}

std::vector<std::string> Boundaries::monitor_columns() const {
  std::vector<std::string> c;
  for (auto &bc : bcs_)
    for (auto &n : bc->monitor_columns())
      c.push_back(n);
  return c;
}

std::vector<double> Boundaries::monitor_values() const {
  std::vector<double> v;
  for (auto &bc : bcs_)
    for (double x : bc->monitor_values())
      v.push_back(x);
  return v;
}

void Boundaries::bind_monitors(const std::vector<std::string> &columns) {
  for (auto &bc : bcs_)
    bc->bind_monitors(columns);
}

void Boundaries::observe(double t, const std::vector<double> &row) {
  for (auto &bc : bcs_)
    bc->observe(t, row);
}

std::vector<std::vector<PetscInt>> Boundaries::dense_couplings() const {
  std::vector<std::vector<PetscInt>> blocks;
  for (auto &bc : bcs_) {
    auto b = bc->dense_coupling();
    if (!b.empty()) blocks.push_back(std::move(b));
  }
  return blocks;
}

// Its options, for -help and docs/options.md (option_doc.hpp).
OptionSection boundary_options() {
  return {
      "Boundary conditions (per boundary <b> in -bc_names)",
      {{"bc_names", "", "-", "boundaries with a condition; unlisted ones are traction-free"},
       {"bc_<b>_type", "(required)", "-", "one of the types listed below"},
       {"bc_<b>_components", "all (Dirichlet types)", "-", "velocity components fixed: x,y,z"},
       {"bc_<b>_value", "0 (flow_rate, expression: 1)", "m/s | Pa | m | m^3/s",
        "velocity scale, pressure, traction, displacement or flow rate (into the fluid)"},
       {"bc_<b>_direction", "flow_rate: inward normal", "-",
        "direction x,y,z (velocity, flow_rate, displacement, traction)"},
       {"bc_<b>_profile", "uniform (flow_rate: plug)", "-",
        "velocity: uniform | parabolic | exact | expression; flow_rate: plug | parabolic | "
        "expression; displacement: uniform | exact"},
       {"bc_<b>_expr", "", "m/s",
        "expression profile in x, y, z, t: 3 values (flow_rate: 1 or 3); "
        "expression waveform: 1 value in t"},
       {"bc_<b>_center", "flow_rate: area centroid", "m", "parabolic: a point on the axis"},
       {"bc_<b>_radius", "flow_rate: farthest vertex", "m", "parabolic: the radius"},
       {"bc_<b>_stop_backflow_when", "", "-",
        "flow_rate: COLUMN<VALUE or COLUMN>VALUE of monitor.csv (e.g. contact_pairs>20): the "
        "backflow stops once it holds (valve closed), until the flow turns forward"},
       {"bc_<b>_stop_ramp", "0.005", "s", "flow_rate: the stop's smooth ramp to zero"},
       {"bc_<b>_backflow_beta", "1", "-", "pressure, windkessel: backflow stabilisation (0 off)"},
       {"bc_<b>_R_p", "(required)", "Pa s/m^3", "windkessel: proximal resistance"},
       {"bc_<b>_C", "(required)", "m^3/Pa", "windkessel: compliance"},
       {"bc_<b>_R_d", "(required)", "Pa s/m^3", "windkessel: distal resistance"},
       {"bc_<b>_p_distal", "0", "Pa", "windkessel: distal (venous) pressure"},
       {"bc_<b>_p0", "p_distal", "Pa", "windkessel: initial capacitor pressure"},
       {"bc_<b>_jacobian", "auto", "-",
        "windkessel: full (dense outlet block), lagged, auto (full up to 3000 dofs)"},
       {"bc_<b>_waveform", "constant", "-",
        "constant | step | pulse | cosine | sine | linear | table | expression"},
       {"bc_<b>_table", "", "-", "table: file of 't value' rows, linear interpolation"},
       {"bc_<b>_periodic", "false", "-", "table: repeat with period t_last - t_first"},
       {"bc_<b>_t_off", "", "s", "step, pulse: end time"},
       {"bc_<b>_period", "", "s", "cosine, sine, linear: period"},
       {"bc_<b>_offset", "0", "-", "cosine, sine: offset + cos(2 pi t / period)"},
       {"bc_<b>_ramp", "0", "s", "smooth start over this time"}}};
}

} // namespace fsi
