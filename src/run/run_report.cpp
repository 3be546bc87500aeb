#include "fsi/run/run_report.hpp"
#include "fsi/run/stages.hpp"

#include <algorithm>

namespace fsi {

static double max_over_ranks(MPI_Comm comm, double v) {
  double m;
  MPI_Allreduce(&v, &m, 1, MPI_DOUBLE, MPI_MAX, comm);
  return m;
}

RunReport::RunReport(MPI_Comm comm, const Scene &scene, const std::vector<std::string> &columns)
    : comm_(comm), scene_(scene), names_(columns) {}

void RunReport::step(const StepStats &s, double t, const std::vector<double> &v) {
  ++steps_;
  newton_ += s.newton;
  krylov_ += s.krylov;
  newton_max_ = std::max<long>(newton_max_, s.newton);
  krylov_max_ = std::max<long>(krylov_max_, s.krylov);
  if (min_.empty()) {
    min_ = max_ = last_ = v;
    t_min_.assign(v.size(), t);
    t_max_ = t_min_;
  }
  for (size_t k = 0; k < v.size() && k < min_.size(); ++k) {
    if (v[k] < min_[k]) min_[k] = v[k], t_min_[k] = t;
    if (v[k] > max_[k]) max_[k] = v[k], t_max_[k] = t;
    last_[k] = v[k];
  }
}

void RunReport::record(Output &out, Simulation &sim, const StepStats &s, double dt, double step_s) {
  const double o0 = MPI_Wtime();
  FSI_CALL(PetscLogStagePush(Stages::get().output));
  std::vector<double> values = sim.after_step(dt, s);
  step(s, sim.time(), values);
  values.insert(values.begin(), {(double)sim.step_index(), sim.time(), (double)s.newton,
                                 (double)s.krylov, step_s, dt});
  out.monitor_row(values);
  FSI_CALL(PetscLogStagePop());
  output_time_ += MPI_Wtime() - o0;
}

void RunReport::absorb(const Simulation &sim) {
  const CostCounters &c = sim.system().cost();
  jacobians_ += c.jacobians;
  residuals_ += c.residuals;
  pattern_builds_ += c.pattern_builds;
  pc_rebuilds_ += c.preconditioner_rebuilds;
  jacobian_time_ += c.jacobian_time;
  for (auto &[name, t] : c.module_jacobian_time)
    module_jacobian_time_[name] += t;
  residual_time_ += c.residual_time;
  solve_time_ += c.nonlinear_solve_time;
  mesh_motion_time_ += sim.ale().seconds();
}

void RunReport::write(const Output &out, const Mesh &mesh, const Simulation &sim,
                      const StepControl &control, const RunOutcome &o, double wall,
                      const std::string &restart, long first_step, double first_time,
                      const std::string &checkpoint) const {
  int size;
  MPI_Comm_size(comm_, &size);
  const Space &space = sim.space();
  const double mem_max = max_over_ranks(comm_, peak_memory_mb());
  const double mem_min = -max_over_ranks(comm_, -peak_memory_mb());
  const double jt = max_over_ranks(comm_, jacobian_time_),
               rt = max_over_ranks(comm_, residual_time_);
  // Linear solver time (factorisation / preconditioner setup and Krylov) = Newton time less
  // assembly.
  const double ls = max_over_ranks(comm_, solve_time_ - jacobian_time_ - residual_time_);
  PetscInt cc[2] = {sim.fluid() ? sim.fluid()->n_cells() : 0,
                    sim.solid() ? sim.solid()->n_cells() : 0},
           cg[2];
  MPI_Allreduce(cc, cg, 2, MPIU_INT, MPI_SUM, comm_);
  const PetscInt fc_g = cg[0], sc_g = cg[1];
  const double per_step = steps_ ? (wall - setup_time_) / steps_ : 0.0;
  // What holds the memory: the Jacobian's own share (values, column indices and row starts as
  // allocated; PETSc's MatInfo.memory is not tracked in this build) and the peak per dof.
  double mat_nz = 0, mat_mb = 0;
  if (Mat J = sim.system().matrix()) {
    MatInfo global, local;
    FSI_CALL(MatGetInfo(J, MAT_GLOBAL_SUM, &global));
    FSI_CALL(MatGetInfo(J, MAT_LOCAL, &local));
    mat_nz = global.nz_allocated;
    PetscInt rows;
    FSI_CALL(MatGetLocalSize(J, &rows, nullptr));
    mat_mb = max_over_ranks(comm_, (local.nz_allocated * (sizeof(PetscScalar) + sizeof(PetscInt)) +
                                    double(rows) * sizeof(PetscInt)) /
                                       1048576.0);
  }
  const double dofs_per_rank = double(space.n_velocity + space.n_pressure) / size;
  const double kb_per_dof = dofs_per_rank > 0 ? mem_max * 1024 / dofs_per_rank : 0.0;

  std::vector<std::string> active;
  for (auto &m : sim.system().modules())
    active.push_back(m->name());
  if (sim.ale().moving()) active.push_back("mesh motion: " + sim.ale().motion()->name());
  Json dofs, times, iters, cost, j;
  // Each module's element loop (its add_jacobian: kernels and the scatter into the matrix):
  // seconds (max over ranks) and cells per second per rank, from the last mesh's cell counts (a
  // remeshing run's rate is approximate).  The same modules on every rank.
  Json by_module;
  for (auto &m : sim.system().modules()) {
    auto it = module_jacobian_time_.find(m->name());
    if (it == module_jacobian_time_.end()) continue;
    const double t = max_over_ranks(comm_, it->second);
    PetscInt nc = m->n_cells(), ncg;
    MPI_Allreduce(&nc, &ncg, 1, MPIU_INT, MPI_SUM, comm_);
    Json e;
    e.set("seconds", t).set("cells", (long)ncg);
    e.set("cells_per_second_per_rank", t > 0 ? double(ncg) / size * jacobians_ / t : 0.0);
    by_module.set(m->name(), e);
  }
  double remesh_time = 0, remesh_gmsh = 0, remesh_mem = 0;
  for (auto &r : remeshes_)
    remesh_time += r.seconds, remesh_gmsh += r.mesh_seconds,
        remesh_mem = std::max(remesh_mem, r.memory_mb);
  dofs.set("velocity", (long)space.n_velocity)
      .set("pressure", (long)space.n_pressure)
      .set("pressure_held_outside_fluid", sim.boundaries().pressure_dofs_outside_fluid())
      .set("total", (long)(space.n_velocity + space.n_pressure));
  times.set("total", wall)
      .set("setup", setup_time_)
      .set("jacobian_assembly", jt)
      .set("residual_assembly", rt)
      .set("linear_solver", ls)
      .set("mesh_motion", mesh_motion_time_)
      .set("rebuild", rebuild_time_)
      .set("remesh", remesh_time)
      .set("output", output_time_)
      .set("per_step", per_step);
  iters.set("newton_total", newton_)
      .set("newton_max_per_step", newton_max_)
      .set("krylov_total", krylov_)
      .set("krylov_max_per_step", krylov_max_)
      .set("newton_mean_per_step", steps_ ? double(newton_) / steps_ : 0.0)
      .set("krylov_mean_per_step", steps_ ? double(krylov_) / steps_ : 0.0)
      .set("krylov_mean_per_newton", newton_ ? double(krylov_) / newton_ : 0.0);
  cost.set("jacobians", jacobians_)
      .set("residuals", residuals_)
      .set("matrix_patterns", pattern_builds_)
      .set("preconditioner_rebuilds_forced", pc_rebuilds_)
      .set("linear_solver_seconds_per_newton", newton_ ? ls / newton_ : 0.0)
      .set("jacobian_tets_per_second_per_rank",
           jt > 0 ? double(fc_g + sc_g) / size * jacobians_ / jt : 0.0)
      .set("residual_tets_per_second_per_rank",
           rt > 0 ? double(fc_g + sc_g) / size * residuals_ / rt : 0.0)
      .set("peak_memory_mb_per_rank_max", mem_max)
      .set("peak_memory_mb_per_rank_min", mem_min)
      .set("peak_memory_kb_per_dof", kb_per_dof)
      .set("jacobian_by_module", by_module)
      .set("jacobian_nonzeros", mat_nz)
      .set("jacobian_mb_per_rank_max", mat_mb);
  const TimeParams &tp = scene_.time;
  j.set("scene", scene_.name)
      .set("physics", active)
      .set("ranks", size)
      .set("mesh", mesh.source)
      .set("cells", (long)mesh.cells_global)
      .set("fluid_cells", (long)fc_g)
      .set("solid_cells", (long)sc_g)
      .set("vertices", (long)mesh.vertices_global)
      .set("partitioner", mesh.partition.method)
      .set("partition_edge_cut", mesh.partition.edge_cut)
      .set("partition_faces", mesh.partition.faces)
      .set("partition_imbalance", mesh.partition.imbalance)
      .set("dofs", dofs)
      .set("time_scheme", tp.steady ? "steady" : "generalized-alpha")
      .set("dt", tp.dt)
      .set("rho_inf", tp.rho_inf)
      .set("steps", steps_)
      .set("final_step", sim.step_index())
      .set("final_time", sim.time())
      .set("rebuilds", rebuilds_)
      .set("iterations", iters)
      .set("wall_time", times)
      .set("cost", cost)
      .set("converged", o.converged)
      .set("reason", o.reason);
  Json sc;
  sc.set("adapt", control.mode == StepControl::error      ? "error"
                  : control.mode == StepControl::cut_only ? "cut"
                                                          : "none")
      .set("failed_steps", failed_)
      .set("cuts", control.cuts)
      .set("grows", control.grows)
      .set("dt_final", control.dt)
      .set("dt_smallest", control.dt_smallest)
      .set("dt_largest", control.dt_largest);
  if (control.mode == StepControl::error)
    sc.set("rejections", control.rejections)
        .set("accepted_above_tolerance", control.accepted_above)
        .set("rtol", control.tol.rtol)
        .set("atol", control.tol.atol)
        .set("dt_max", control.dt_max);
  j.set("step_control", sc);
  if (!remeshes_.empty() || sim.ale().remeshing()) {
    Json r;
    r.set("count", (long)remeshes_.size())
        .set("seconds", remesh_time)
        .set("gmsh_seconds", remesh_gmsh)
        .set("share_of_wall", wall > 0 ? remesh_time / wall : 0.0)
        .set("peak_memory_mb_rank0", remesh_mem)
        .set("log", "remesh.csv");
    j.set("remesh", r);
  }
  if (!restart.empty()) {
    Json r;
    r.set("file", restart).set("step", first_step).set("time", first_time);
    j.set("restarted_from", r);
  }
  if (!checkpoint.empty()) j.set("checkpoint", checkpoint);
  for (auto &m : sim.monitors()) // error_final, hemodynamics
    m->summarize(j, steps_ > 0);
  if (steps_ > 0) {
    Json m;
    for (size_t k = 0; k < min_.size() && k < names_.size(); ++k) {
      Json c;
      c.set("min", min_[k]).set("t_min", t_min_[k]).set("max", max_[k]).set("t_max", t_max_[k]);
      c.set("final", last_[k]);
      m.set(names_[k], c);
    }
    j.set("monitors", m);
  }
  out.write_summary(j);
  // The cost line: what this run paid, per stage (max over ranks), per step and per iteration.
  const char *status = o.converged ? "done" : o.exit_code == 3 ? "FAILED" : "STOPPED";
  PetscPrintf(
      comm_,
      "fsi_app: %s: %ld steps, %.3g s/step; Newton %.2f/step (max %ld), Krylov %.1f/Newton "
      "(max %ld/step); wall %.2f s = setup %.2f + Jacobian %.2f + residual %.2f + linear "
      "solver %.2f + mesh motion %.2f + rebuild/remesh %.2f + output %.2f + other %.2f; %ld dofs "
      "(velocity %ld, pressure %ld); peak memory %.0f MB/rank (Jacobian %.0f MB, %.2f kB per "
      "dof); results in %s\n",
      status, steps_, per_step, steps_ ? double(newton_) / steps_ : 0.0, newton_max_,
      newton_ ? double(krylov_) / newton_ : 0.0, krylov_max_, wall, setup_time_, jt, rt, ls,
      mesh_motion_time_, rebuild_time_ + remesh_time, output_time_,
      std::max(0.0, wall - setup_time_ - jt - rt - ls - mesh_motion_time_ - rebuild_time_ -
                        remesh_time - output_time_),
      (long)(space.n_velocity + space.n_pressure), (long)space.n_velocity, (long)space.n_pressure,
      mem_max, mat_mb, kb_per_dof, out.dir().c_str());
}

void RunReport::remeshed(const Output &out, const RemeshReport &r) {
  remeshes_.push_back(r);
  PetscPrintf(comm_,
              "fsi_app: remesh %zu at step %ld, t = %.6e s: worst fluid skewness %.3f -> %.3f "
              "(gmsh %.3f, %ld flips/moves, %ld splits), "
              "fluid cells %ld -> %ld (%ld boundary vertices at gaps), solid vertices moved to the "
              "converged solid by up to %.2g m, volume "
              "change %.1e, kinetic "
              "energy change %.2e, "
              "div/grad %.1e -> %.1e, weak divergence %.1e -> %.1e (projected in %.2f s); %.2f s "
              "(gmsh %.2f s)\n",
              remeshes_.size(), r.step, r.time, r.skewness_before, r.skewness_after,
              r.skewness_gmsh, r.flips, r.splits, r.fluid_cells_before, r.fluid_cells_after,
              r.gap_vertices, r.solid_shift, r.volume_after / r.volume_before - 1,
              r.kinetic_after / r.kinetic_before - 1, r.divergence_before, r.divergence_after,
              r.weak_divergence, r.weak_divergence_projected, r.projection_seconds, r.seconds,
              r.mesh_seconds);
  std::string csv = "remesh,step,time,skewness_before,skewness_after,fluid_cells_before,"
                    "fluid_cells_after,volume_before,volume_after,kinetic_before,kinetic_after,"
                    "divergence_before,divergence_after,gmsh_seconds,seconds,peak_memory_mb,"
                    "gap_vertices,skewness_gmsh,flips,splits,weak_divergence,"
                    "weak_divergence_projected,projection_seconds,solid_shift\n";
  char row[600];
  for (size_t i = 0; i < remeshes_.size(); ++i) {
    const RemeshReport &q = remeshes_[i];
    std::snprintf(row, sizeof row,
                  "%zu,%ld,%.10e,%.6f,%.6f,%ld,%ld,%.12e,%.12e,%.12e,%.12e,%.6e,%.6e,%.4f,%.4f,"
                  "%.1f,%ld,%.6f,%ld,%ld,%.6e,%.6e,%.4f,%.4e\n",
                  i + 1, q.step, q.time, q.skewness_before, q.skewness_after, q.fluid_cells_before,
                  q.fluid_cells_after, q.volume_before, q.volume_after, q.kinetic_before,
                  q.kinetic_after, q.divergence_before, q.divergence_after, q.mesh_seconds,
                  q.seconds, q.memory_mb, q.gap_vertices, q.skewness_gmsh, q.flips, q.splits,
                  q.weak_divergence, q.weak_divergence_projected, q.projection_seconds,
                  q.solid_shift);
    csv += row;
  }
  out.write_file("remesh.csv", csv);
}

} // namespace fsi
