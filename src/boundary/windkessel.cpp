// windkessel (fluid): a three-element Windkessel (RCR) outlet, the lumped model of the arterial
// tree downstream.  Traction -P n with
//   P = R_p Q + P_c,   C dP_c/dt = Q - (P_c - P_distal) / R_d,
// Q = the flow out through the boundary (v.n on its current position), R_p the proximal
// (characteristic) resistance -bc_<b>_R_p [Pa s/m^3], C the compliance -bc_<b>_C [m^3/Pa], R_d
// the distal resistance -bc_<b>_R_d [Pa s/m^3], P_distal -bc_<b>_p_distal [Pa] (venous, default
// 0) and P_c(0) = -bc_<b>_p0 [Pa] (default P_distal).
// Time discretisation: the trapezoidal rule on [t_n, t_{n+1}] (second order, A-stable),
//   C (P_c^{n+1} - P_c^n)/dt = (Q_n + Q_{n+1})/2 - ((P_c^n + P_c^{n+1})/2 - P_distal)/R_d,
// with Q_n, Q_{n+1} the fluxes of the velocities at t_n and t_{n+1}; the traction acts at the
// stage t_{n+alpha_f} where the momentum balance holds, P_af = R_p Q_af + P_c^n + alpha_f dPc,
// Q_af = (1 - alpha_f) Q_n + alpha_f Q_{n+1} (exactly the flux of v_af), so it is second order
// for every rho_inf and affine in the unknown.  Steady runs: P = P_distal + (R_p + R_d) Q.
// The residual is fully implicit in Q.  Its Jacobian has the coupling dP/dQ: with w_{a,i} =
// int N_a n_i dA (nonzero only on the P2 edge nodes of the flat faces: the vertex functions
// integrate to zero), dF_{a,i}/dU_{b,j} = dP/dQ alpha_f w_{a,i} w_{b,j}, a dense rank-one block
// over those dofs, in the pattern with -bc_<b>_jacobian full.  -bc_<b>_jacobian lagged leaves
// it out (no dense block: Newton then converges linearly, at the rate dP/dQ times the domain's
// flux response to an outlet pressure); auto (default): full up to 3000 coupled dofs.
// Backflow stabilisation as for `pressure` (-bc_<b>_backflow_beta, default 1).
// State: P_c, advanced after each accepted step, kept in checkpoints and rebuilt runs.
#include "fsi/boundary/boundary_condition.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace fsi {
namespace {

struct Windkessel : BoundaryCondition {
  double R_p = 0, C = 0, R_d = 0, p_distal = 0, beta = 1, rho = 0;
  double Pc = 0;                      // capacitor pressure at t_n [Pa]
  mutable double Q_n = 0, Q_np1 = 0;  // of the last residual evaluation (the converged iterate)
  mutable double dt = 0, alpha_f = 1; // of that evaluation's step
  mutable bool steady = false;
  double Q_last = 0, P_last = 0; // monitored: flow and pressure at t_{n+1}
  QuadRule rule = tri_rule(4);
  MPI_Comm comm;
  std::string pre;
  const Space &space;
  std::vector<PetscInt> coupled;         // global dofs of the dense block, sorted (all ranks)
  std::vector<std::array<long, 9>> slot; // per face: edge node m, component d -> coupled index
  mutable std::vector<char> held;        // per coupled dof: a Dirichlet dof (row skipped)
  mutable std::vector<double> w_loc, w;  // the weights w on the coupled dofs

  explicit Windkessel(const BoundarySetup &s)
      : BoundaryCondition(s, Data::velocity, false, true),
        comm(PetscObjectComm((PetscObject)s.space.dm)), pre(s.prefix()), space(s.space) {
    R_p = opt::required_positive(pre + "R_p");
    C = opt::required_positive(pre + "C");
    R_d = opt::required_positive(pre + "R_d");
    p_distal = opt::real(pre + "p_distal", 0.0);
    Pc = opt::real(pre + "p0", p_distal);
    beta = opt::nonnegative(pre + "backflow_beta", 1.0);
    rho = s.rho;
    const std::string jac = opt::choice(pre + "jacobian", "auto", {"auto", "full", "lagged"});
    if (jac != "lagged") find_coupled_dofs();
    if (jac == "auto" && coupled.size() > 3000) coupled.clear();
    if (!coupled.empty())
      for (auto &f : faces_) {
        std::array<long, 9> k;
        for (int m = 0; m < 3; ++m)
          for (int d = 0; d < 3; ++d)
            k[3 * m + d] = index_of(space.local_to_global[f.vdof[3 + m] + d]);
        slot.push_back(k);
      }
    PetscPrintf(comm,
                "  boundary '%s': Windkessel R_p %.3g Pa s/m^3, C %.3g m^3/Pa, R_d %.3g Pa s/m^3 "
                "(tau %.3g s), P_c(0) %.4g Pa; Jacobian %s (%zu coupled dofs)\n",
                name_.c_str(), R_p, C, R_d, R_d * C, Pc, coupled.empty() ? "lagged" : "full",
                coupled.size());
  }
  // Edge-node velocity dofs of the faces, in the components the face normals have.
  void find_coupled_dofs() {
    std::vector<PetscInt> mine;
    for (auto &f : faces_) {
      double n[3];
      outward_normal(f, space.X.data(), n);
      for (int m = 0; m < 3; ++m)
        for (int d = 0; d < 3; ++d)
          if (std::fabs(n[d]) > 1e-6) mine.push_back(space.local_to_global[f.vdof[3 + m] + d]);
    }
    int nm = (int)mine.size(), size;
    MPI_Comm_size(comm, &size);
    std::vector<int> counts(size), displs(size, 0);
    MPI_Allgather(&nm, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
    for (int r = 1; r < size; ++r)
      displs[r] = displs[r - 1] + counts[r - 1];
    coupled.resize(displs[size - 1] + counts[size - 1]);
    MPI_Allgatherv(mine.data(), nm, MPIU_INT, coupled.data(), counts.data(), displs.data(),
                   MPIU_INT, comm);
    std::sort(coupled.begin(), coupled.end());
    coupled.erase(std::unique(coupled.begin(), coupled.end()), coupled.end());
  }
  std::vector<PetscInt> dense_coupling() const override { return coupled; }
  long index_of(PetscInt g) const {
    auto it = std::lower_bound(coupled.begin(), coupled.end(), g);
    return it != coupled.end() && *it == g ? it - coupled.begin() : -1;
  }
  // dP_af/dQ_{n+1} / alpha_f, so that dP_af/dU = dP_dQ() stiff_shift() w.
  double dP_dQ() const { return steady ? R_p + R_d : R_p + 0.5 / (C / dt + 0.5 / R_d); }
  std::string type() const override { return "windkessel"; }
  bool fixes_pressure_level() const override { return true; }

  // Q_n, Q_{n+1}: int v . n of the velocities at t_n and t_{n+1} over the faces on X_af (all
  // ranks; each face lives on one rank).  A flat P2 triangle's edge functions integrate to
  // area / 3 and its vertex functions to 0.
  void outflows(const StepContext &ctx) const {
    double loc[2] = {0, 0}, glob[2];
    const PetscScalar *Vn = ctx.steady ? ctx.U : ctx.Vn;
    for (auto &f : faces_) {
      double n[3];
      const double third = outward_normal(f, ctx.X_af, n) / 6;
      for (int m = 3; m < 6; ++m)
        for (int d = 0; d < 3; ++d) {
          loc[0] += third * PetscRealPart(Vn[f.vdof[m] + d]) * n[d];
          loc[1] += third * PetscRealPart(ctx.U[f.vdof[m] + d]) * n[d];
        }
    }
    MPI_Allreduce(loc, glob, 2, MPI_DOUBLE, MPI_SUM, comm);
    Q_n = glob[0], Q_np1 = glob[1];
  }
  // P_c^{n+1} - P_c^n for the fluxes of the last evaluation (trapezoidal rule).
  double capacitor_change() const {
    return (0.5 * (Q_n + Q_np1) - (Pc - p_distal) / R_d) / (C / dt + 0.5 / R_d);
  }
  void add_residual(const StepContext &ctx, PetscScalar *F) const override {
    steady = ctx.steady, dt = ctx.dt, alpha_f = ctx.alpha_f;
    outflows(ctx);
    const double p =
        steady ? p_distal + (R_p + R_d) * Q_np1
               : R_p * ((1 - alpha_f) * Q_n + alpha_f * Q_np1) + Pc + alpha_f * capacitor_change();
    add_fluid_pressure(faces_, ctx, rule, beta, rho, p, F);
  }
  void add_jacobian(const StepContext &ctx, Mat J) const override {
    add_backflow_jacobian(faces_, ctx, rule, beta, rho, J);
    if (coupled.empty()) return;
    const size_t n = coupled.size();
    if (held.size() != n) { // which coupled dofs are Dirichlet (fixed for the run)
      std::vector<char> loc(n, 0);
      for (size_t q = 0; q < faces_.size(); ++q)
        for (int m = 0; m < 3; ++m)
          for (int d = 0; d < 3; ++d) {
            const long k = slot[q][3 * m + d];
            if (k >= 0 && (*ctx.is_dirichlet)[faces_[q].vdof[3 + m] + d]) loc[k] = 1;
          }
      held.resize(n);
      MPI_Allreduce(loc.data(), held.data(), (int)n, MPI_CHAR, MPI_MAX, comm);
    }
    // w on X_af: a flat P2 triangle's edge functions integrate to area / 3.
    w_loc.assign(n, 0.0);
    w.assign(n, 0.0);
    for (size_t q = 0; q < faces_.size(); ++q) {
      double nrm[3];
      const double third = outward_normal(faces_[q], ctx.X_af, nrm) / 6;
      for (int m = 0; m < 3; ++m)
        for (int d = 0; d < 3; ++d)
          if (slot[q][3 * m + d] >= 0) w_loc[slot[q][3 * m + d]] += third * nrm[d];
    }
    MPI_Allreduce(w_loc.data(), w.data(), (int)n, MPI_DOUBLE, MPI_SUM, comm);
    const double c = dP_dQ() * ctx.stiff_shift();
    std::vector<double> row(n);
    for (size_t i = 0; i < n; ++i) {
      const PetscInt r = coupled[i];
      if (held[i] || r < space.rstart || r >= space.rstart + space.n_owned) continue;
      for (size_t j = 0; j < n; ++j)
        row[j] = c * w[i] * w[j];
      FSI_CALL(MatSetValues(J, 1, &r, (PetscInt)n, coupled.data(), row.data(), ADD_VALUES));
    }
  }
  void accept_step() override {
    Pc = steady ? p_distal + R_d * Q_np1 : Pc + capacitor_change();
    Q_last = Q_np1, P_last = R_p * Q_np1 + Pc;
  }
  void save_state(std::map<std::string, double> &s) const override { s[name_ + "_Pc"] = Pc; }
  void restore_state(const std::map<std::string, double> &s) override {
    auto it = s.find(name_ + "_Pc");
    if (it == s.end())
      throw InputError("the state to resume has no Windkessel pressure for boundary '" + name_ +
                       "': restart with the options of the run that wrote it");
    Pc = it->second;
  }
  std::vector<std::string> monitor_columns() const override {
    return {name_ + "_wk_flow", name_ + "_wk_pressure", name_ + "_wk_capacitor_pressure"};
  }
  std::vector<double> monitor_values() const override { return {Q_last, P_last, Pc}; }
};

} // namespace

std::unique_ptr<BoundaryCondition> make_windkessel(const BoundarySetup &s) {
  return std::make_unique<Windkessel>(s);
}

} // namespace fsi
