#include "fsi/problem.hpp"
#include "fsi/options.hpp"
#include "fsi/stages.hpp"

#include <cmath>

namespace fsi {

Stages &Stages::get() {
  static Stages s;
  static bool done = false;
  if (!done) {
    FSI_CALL(PetscLogStageRegister("FSI setup", &s.setup));
    FSI_CALL(PetscLogStageRegister("FSI assembly", &s.assembly));
    FSI_CALL(PetscLogStageRegister("FSI solve", &s.solve));
    FSI_CALL(PetscLogStageRegister("FSI mesh motion", &s.mesh_motion));
    FSI_CALL(PetscLogStageRegister("FSI output", &s.output));
    done = true;
  }
  return s;
}

TimeParams TimeParams::from_options() {
  TimeParams tp;
  tp.steady = opt::choice("ts_scheme", "alpha", {"alpha", "steady"}) == "steady";
  if (tp.steady) { // load steps over the pseudo-time [0, ts_max_time]
    tp.t_end = opt::positive("ts_max_time", 1.0);
    tp.max_steps = opt::integer("ts_max_steps", 1);
    if (tp.max_steps < 1) throw InputError("option -ts_max_steps must be >= 1");
    tp.dt = tp.t_end / tp.max_steps;
    return tp;
  }
  tp.dt = opt::positive("ts_dt", 1e-3);
  tp.rho_inf = opt::real("ts_alpha_radius", 0.5);
  if (tp.rho_inf < 0 || tp.rho_inf > 1)
    throw InputError("option -ts_alpha_radius (spectral radius rho_inf) must be in [0, 1]");
  // -ts_max_steps, when given, wins over the scene's -ts_max_time (handy to shorten a run).
  const bool by_time = opt::has("ts_max_time");
  const double t_end = by_time ? opt::positive("ts_max_time", 1.0) : 0.0;
  if (opt::has("ts_max_steps") || !by_time) {
    tp.max_steps = opt::integer("ts_max_steps", 10);
    if (tp.max_steps < 1) throw InputError("option -ts_max_steps must be >= 1");
    tp.t_end = tp.max_steps * tp.dt;
  } else {
    tp.t_end = t_end;
    tp.max_steps = std::lround(tp.t_end / tp.dt);
    if (tp.max_steps < 1 || std::fabs(tp.max_steps * tp.dt - tp.t_end) > 1e-9 * tp.t_end)
      throw InputError("-ts_max_time is not a whole number of steps -ts_dt: adjust one of them");
  }
  return tp;
}

static PetscErrorCode residual_cb(SNES snes, Vec U, Vec F, void *ctx) {
  try {
    if (!static_cast<Problem *>(ctx)->residual(U, F)) PetscCall(SNESSetFunctionDomainError(snes));
  } catch (std::exception &e) {
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "%s", e.what());
  }
  return 0;
}

static PetscErrorCode jacobian_cb(SNES, Vec U, Mat J, Mat, void *ctx) {
  try {
    static_cast<Problem *>(ctx)->jacobian(U, J);
  } catch (std::exception &e) {
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "%s", e.what());
  }
  return 0;
}

Problem::Problem(const Space &space, const TimeParams &tp) : space_(space), tp_(tp), dt_(tp.dt) {
  if (!tp.steady) {
    const double r = tp.rho_inf;
    alpha_m_ = (3 - r) / (2 * (1 + r));
    alpha_f_ = 1 / (1 + r);
    gamma_ = 0.5 + alpha_m_ - alpha_f_;
    beta_ = 0.25 * (1 + alpha_m_ - alpha_f_) * (1 + alpha_m_ - alpha_f_);
  }
  U_ = space.create_global();
  FSI_CALL(PetscObjectSetName((PetscObject)U_, "solution"));
  FSI_CALL(VecDuplicate(U_, &Vn_));
  FSI_CALL(VecDuplicate(U_, &An_));
  FSI_CALL(VecDuplicate(U_, &F_));
  FSI_CALL(VecDuplicate(U_, &Dn_));
  FSI_CALL(VecDuplicate(U_, &work_));
  Uloc_ = space.create_local();
  FSI_CALL(VecDuplicate(Uloc_, &Sloc_));
  FSI_CALL(VecDuplicate(Uloc_, &Dloc_));
  FSI_CALL(VecDuplicate(Uloc_, &Vloc_));
  FSI_CALL(VecDuplicate(Uloc_, &Aloc_));
  FSI_CALL(VecDuplicate(Uloc_, &Floc_));
  Xn_ = space.X;
}

// The Jacobian's nonzero pattern from the modules' element dof lists (every dof of an element
// couples with every other) plus the diagonal: exact for the modules the scene switched on (a
// solid cell has no pressure coupling), built once for the whole run.
void Problem::create_matrix() {
  MPI_Comm comm = PetscObjectComm((PetscObject)space_.dm);
  ISLocalToGlobalMapping l2g = space_.l2g;
  Mat pre;
  FSI_CALL(MatCreate(comm, &pre));
  FSI_CALL(MatSetSizes(pre, space_.n_owned, space_.n_owned, PETSC_DETERMINE, PETSC_DETERMINE));
  FSI_CALL(MatSetType(pre, MATPREALLOCATOR));
  FSI_CALL(MatSetLocalToGlobalMapping(pre, l2g, l2g));
  FSI_CALL(MatSetUp(pre));
  std::vector<double> zeros(64 * 64, 0.0);
  for (auto &m : modules_) {
    std::vector<PetscInt> dofs;
    int n = 0;
    m->element_dofs(dofs, n);
    for (size_t e = 0; n > 0 && e < dofs.size() / n; ++e)
      FSI_CALL(
          MatSetValuesLocal(pre, n, &dofs[n * e], n, &dofs[n * e], zeros.data(), INSERT_VALUES));
  }
  for (PetscInt r = space_.rstart; r < space_.rstart + space_.n_owned; ++r)
    FSI_CALL(MatSetValue(pre, r, r, 0.0, INSERT_VALUES));
  FSI_CALL(MatAssemblyBegin(pre, MAT_FINAL_ASSEMBLY));
  FSI_CALL(MatAssemblyEnd(pre, MAT_FINAL_ASSEMBLY));
  FSI_CALL(MatCreate(comm, &J_));
  FSI_CALL(MatSetSizes(J_, space_.n_owned, space_.n_owned, PETSC_DETERMINE, PETSC_DETERMINE));
  FSI_CALL(MatSetType(J_, MATAIJ));
  FSI_CALL(MatSetOptionsPrefix(J_, "jac_"));
  FSI_CALL(MatSetLocalToGlobalMapping(J_, l2g, l2g));
  FSI_CALL(MatPreallocatorPreallocate(pre, PETSC_TRUE, J_));
  FSI_CALL(MatDestroy(&pre));
  FSI_CALL(MatSetOption(J_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
}

Problem::~Problem() {
  Vec *vs[] = {&U_, &Vn_, &An_, &F_, &Dn_, &work_, &Uloc_, &Dloc_, &Sloc_, &Vloc_, &Aloc_, &Floc_};
  for (auto v : vs)
    if (*v) VecDestroy(v);
  if (J_) MatDestroy(&J_);
  if (snes_) SNESDestroy(&snes_);
}

void Problem::setup_solver() {
  MPI_Comm comm = PetscObjectComm((PetscObject)space_.dm);
  create_matrix();
  FSI_CALL(SNESCreate(comm, &snes_));
  FSI_CALL(SNESSetFunction(snes_, F_, residual_cb, this));
  FSI_CALL(SNESSetJacobian(snes_, J_, J_, jacobian_cb, this));
  FSI_CALL(SNESSetFromOptions(snes_));
  KSP ksp;
  PC pc;
  FSI_CALL(SNESGetKSP(snes_, &ksp));
  FSI_CALL(KSPGetPC(ksp, &pc));
  PetscBool fs;
  FSI_CALL(PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &fs));
  if (fs) {
    // The solid's elasticity operator: GAMG builds its coarse spaces from the rigid-body modes.
    if (rigid_modes_) compose_rigid_body_modes(space_.is_velocity, space_.velocity_node_X);
    FSI_CALL(PCFieldSplitSetIS(pc, "velocity", space_.is_velocity));
    FSI_CALL(PCFieldSplitSetIS(pc, "pressure", space_.is_pressure));
  }
}

void Problem::mesh_at(double t, std::vector<double> &disp) const {
  if (motion_ && !motion_->follows_solid()) // the solid is at rest at t = 0
    motion_->displacement(t, nullptr, disp);
  else
    disp.assign(3 * space_.n_vertices(), 0.0);
}

void Problem::set_mesh_motion(std::unique_ptr<MeshMotion> m, const std::vector<PetscInt> *fluid) {
  motion_ = std::move(m);
  fluid_cells_ = fluid;
  geometry_iterations_ = (int)opt::integer("ale_geometry_iterations", 0);
  if (geometry_iterations_ < 0) throw InputError("option -ale_geometry_iterations must be >= 0");
  geometry_rtol_ = opt::positive("ale_geometry_rtol", 1e-6);
  min_jacobian_ = opt::real("ale_min_jacobian", 0.0);
  max_skewness_ = opt::positive("ale_max_skewness", 0.99);
}

// A new step size invalidates a Jacobian or preconditioner the scene computes once for the run
// (-snes_lag_jacobian -2): have it recomputed at the next solve.
void Problem::set_dt(double dt) {
  if (dt == dt_) return;
  dt_ = dt;
  PetscInt lag;
  FSI_CALL(SNESGetLagJacobian(snes_, &lag));
  if (lag == -1) FSI_CALL(SNESSetLagJacobian(snes_, -2));
  FSI_CALL(SNESGetLagPreconditioner(snes_, &lag));
  if (lag == -1) FSI_CALL(SNESSetLagPreconditioner(snes_, -2));
}

void Problem::restore(double t, long n, const std::vector<double> &dn) {
  t_ = t;
  n_ = n;
  dn_ = dn;
  for (size_t i = 0; i < Xn_.size(); ++i)
    Xn_[i] = space_.X[i] + dn_[i];
  FSI_CALL(VecCopy(Vn_, U_));
}

void Problem::solution_local(Vec &loc) const {
  space_.to_local(U_, loc);
}

void Problem::displacement_local(Vec &loc) const {
  space_.to_local(Dn_, loc);
}

void Problem::initialize(const std::string &ic) {
  t_ = 0;
  n_ = 0;
  mesh_at(0.0, dn_);
  for (size_t i = 0; i < Xn_.size(); ++i)
    Xn_[i] = space_.X[i] + dn_[i];
  FSI_CALL(VecZeroEntries(U_));
  FSI_CALL(VecZeroEntries(Vn_));
  FSI_CALL(VecZeroEntries(An_));
  FSI_CALL(VecZeroEntries(Dn_));
  if (ic == "velocity") {
    // A uniform initial velocity (-ic_velocity x,y,z [m/s]) on every node that no Dirichlet
    // condition holds: e.g. a clamped block set vibrating.  u_0 = 0 and no load give a_0 = 0.
    auto v0 = opt::reals("ic_velocity");
    if (v0.size() != 3) throw InputError("-ic velocity needs -ic_velocity vx,vy,vz [m/s]");
    PetscScalar *u;
    FSI_CALL(VecGetArray(U_, &u));
    const std::vector<char> &mask = bcs_->dirichlet_mask();
    for (PetscInt v = space_.vStart; v < space_.eEnd; ++v) {
      PetscSection ls;
      PetscInt off, dof;
      FSI_CALL(DMGetLocalSection(space_.dm, &ls));
      FSI_CALL(PetscSectionGetFieldDof(ls, v, 0, &dof));
      if (dof != 3) continue;
      FSI_CALL(PetscSectionGetFieldOffset(ls, v, 0, &off));
      for (int d = 0; d < 3; ++d)
        if (space_.owned(off + d) && !mask[off + d])
          u[space_.local_to_global[off + d] - space_.rstart] = v0[d];
    }
    FSI_CALL(VecRestoreArray(U_, &u));
    FSI_CALL(VecCopy(U_, Vn_));
  } else if (ic == "exact") {
    if (!exact_) throw InputError("-ic exact needs -exact_solution");
    // Values on every local node; the nodal time derivative follows the node along its mesh
    // trajectory x(t) = X + d_m(t) (ALE), by a central difference of the exact flow.
    PetscSection ls;
    FSI_CALL(DMGetLocalSection(space_.dm, &ls));
    std::vector<double> dm_m, dm_p;
    const double eps = 1e-6 * (tp_.steady ? 1.0 : dt_) + 1e-9;
    mesh_at(-eps, dm_m);
    mesh_at(eps, dm_p);
    PetscScalar *u, *a;
    FSI_CALL(VecZeroEntries(Uloc_));
    FSI_CALL(VecZeroEntries(Aloc_));
    FSI_CALL(VecGetArray(Uloc_, &u));
    FSI_CALL(VecGetArray(Aloc_, &a));
    auto pos = [&](const std::vector<double> &d, int va, int vb, double x[3]) {
      for (int k = 0; k < 3; ++k) {
        x[k] = space_.X[3 * va + k] + d[3 * va + k];
        if (vb >= 0) x[k] = 0.5 * (x[k] + space_.X[3 * vb + k] + d[3 * vb + k]);
      }
    };
    auto set_node = [&](PetscInt off, int va, int vb) {
      double x0[3], xm[3], xp[3], v0[3], vm[3], vp[3];
      pos(dn_, va, vb, x0);
      pos(dm_m, va, vb, xm);
      pos(dm_p, va, vb, xp);
      exact_->velocity(x0, 0.0, v0);
      exact_->velocity(xm, -eps, vm);
      exact_->velocity(xp, eps, vp);
      for (int k = 0; k < 3; ++k) {
        u[off + k] = v0[k];
        a[off + k] = (vp[k] - vm[k]) / (2 * eps);
      }
    };
    for (PetscInt v = space_.vStart; v < space_.vEnd; ++v) {
      PetscInt off;
      const int iv = (int)(v - space_.vStart);
      FSI_CALL(PetscSectionGetFieldOffset(ls, v, 0, &off));
      set_node(off, iv, -1);
      FSI_CALL(PetscSectionGetFieldOffset(ls, v, 1, &off));
      double x0[3] = {Xn_[3 * iv], Xn_[3 * iv + 1], Xn_[3 * iv + 2]};
      u[off] = exact_->pressure(x0, 0.0);
    }
    for (PetscInt e = space_.eStart; e < space_.eEnd; ++e) {
      PetscInt off;
      const PetscInt *cone;
      FSI_CALL(DMPlexGetCone(space_.dm, e, &cone));
      FSI_CALL(PetscSectionGetFieldOffset(ls, e, 0, &off));
      set_node(off, (int)(cone[0] - space_.vStart), (int)(cone[1] - space_.vStart));
    }
    // Owned entries straight into the global vectors (every rank computed the same values).
    PetscScalar *ug, *ag;
    FSI_CALL(VecGetArray(U_, &ug));
    FSI_CALL(VecGetArray(An_, &ag));
    for (PetscInt i = 0; i < space_.n_local; ++i)
      if (space_.owned(i)) {
        ug[space_.local_to_global[i] - space_.rstart] = u[i];
        ag[space_.local_to_global[i] - space_.rstart] = a[i];
      }
    FSI_CALL(VecRestoreArray(U_, &ug));
    FSI_CALL(VecRestoreArray(An_, &ag));
    FSI_CALL(VecRestoreArray(Uloc_, &u));
    FSI_CALL(VecRestoreArray(Aloc_, &a));
    FSI_CALL(VecCopy(U_, Vn_));
  } else if (ic != "rest") {
    throw InputError("option -ic has unknown value '" + ic +
                     "'; use one of: rest, exact, velocity");
  }
}

void Problem::set_context(double t_np1) {
  ctx_.t_n = t_;
  ctx_.dt = dt_;
  ctx_.t_np1 = t_np1;
  ctx_.steady = tp_.steady;
  ctx_.alpha_m = alpha_m_;
  ctx_.alpha_f = alpha_f_;
  ctx_.gamma = gamma_;
  ctx_.beta = beta_;
  ctx_.t_af = tp_.steady ? t_np1 : t_ + alpha_f_ * dt_;
  ctx_.X_af = Xaf_.data();
  // Without mesh motion both configurations are the same array: kernels then skip the second
  // geometry (pointer equality).
  ctx_.X_np1 = motion_ ? Xnp1_.data() : Xaf_.data();
  ctx_.W = motion_ && !tp_.steady ? W_.data() : nullptr;
  ctx_.is_dirichlet = &bcs_->dirichlet_mask();
}

// Solid displacement at t_{n+1} for the velocity U (all velocity dofs), as a local array.
void Problem::displacement_np1_local(Vec U, Vec loc) {
  const double dt = dt_;
  FSI_CALL(VecCopy(Dn_, work_));
  if (tp_.steady) {
    FSI_CALL(VecAXPY(work_, dt, U));
  } else {
    // u_n + dt v_n + dt^2 [(1/2 - beta) a_n + beta a_{n+1}(U)]
    const double g = gamma_;
    FSI_CALL(VecAXPY(work_, dt, Vn_));
    FSI_CALL(VecAXPY(work_, dt * dt * ((0.5 - beta_) - beta_ * (1 - g) / g), An_));
    FSI_CALL(VecAXPY(work_, dt * beta_ / g, U));
    FSI_CALL(VecAXPY(work_, -dt * beta_ / g, Vn_));
  }
  space_.to_local(work_, loc);
}

void Problem::set_geometry(const std::vector<double> &dnp1) {
  dnp1_ = dnp1;
  const size_t nd = dnp1_.size();
  Xaf_.resize(nd);
  W_.resize(nd);
  Xnp1_.resize(nd);
  const double af = tp_.steady ? 1.0 : alpha_f_;
  for (size_t i = 0; i < nd; ++i) {
    Xaf_[i] = space_.X[i] + dn_[i] + af * (dnp1_[i] - dn_[i]);
    W_[i] = tp_.steady ? 0.0 : (dnp1_[i] - dn_[i]) / dt_;
    Xnp1_[i] = space_.X[i] + dnp1_[i];
  }
}

// Mesh displacement at t_{n+1} for the velocity iterate U (the solid displacement it implies).
void Problem::move_mesh(double t_np1, Vec U, std::vector<double> &d) {
  Stages &st = Stages::get();
  FSI_CALL(PetscLogStagePush(st.mesh_motion));
  const double t0 = MPI_Wtime();
  if (motion_->follows_solid()) {
    displacement_np1_local(U, Sloc_);
    const PetscScalar *sa;
    FSI_CALL(VecGetArrayRead(Sloc_, &sa));
    motion_->displacement(t_np1, sa, d);
    FSI_CALL(VecRestoreArrayRead(Sloc_, &sa));
  } else {
    motion_->displacement(t_np1, nullptr, d);
  }
  cost_.mesh_motion_time += MPI_Wtime() - t0;
  FSI_CALL(PetscLogStagePop());
}

void Problem::check_mesh(const char *when, long step) {
  if (!motion_ || !fluid_cells_) return;
  quality_ = mesh_quality(space_, *fluid_cells_, Xnp1_);
  if (quality_.min_jacobian <= min_jacobian_ || quality_.max_skewness >= max_skewness_) {
    char msg[400];
    std::snprintf(msg, sizeof msg,
                  "fluid mesh too distorted %s step %ld: smallest volume ratio %.3g (limit "
                  "-ale_min_jacobian %.3g), worst skewness %.3f (limit -ale_max_skewness %.3f); "
                  "remeshing is not available yet: refine the mesh, stiffen the motion "
                  "(-ale_stiffening 1) or reduce the load",
                  when, step, quality_.min_jacobian, min_jacobian_, quality_.max_skewness,
                  max_skewness_);
    throw DistortionError(msg);
  }
}

StepStats Problem::step() {
  Stages &st = Stages::get();
  const double t_np1 = t_ + dt_;

  // History in local form, predictor U = V_n; the mesh solver starts from the last accepted
  // mesh (a retried or restarted step starts exactly where the uninterrupted run did).
  if (motion_) motion_->set_guess(dn_);
  space_.to_local(Vn_, Vloc_);
  space_.to_local(An_, Aloc_);
  space_.to_local(Dn_, Dloc_);
  FSI_CALL(VecCopy(Vn_, U_));
  // Mesh configuration at n+1 (from the predicted solid displacement), at n+alpha_f, and the
  // mesh velocity; a cell that would invert stops the run before the solve.
  std::vector<double> d;
  if (motion_)
    move_mesh(t_np1, U_, d);
  else
    d.assign(3 * space_.n_vertices(), 0.0);
  set_geometry(d);
  check_mesh("before", n_ + 1);
  set_context(t_np1);

  // Dirichlet data at t_{n+1}.
  bcs_->dirichlet_values(t_np1, Xnp1_.data(), bc_values_);
  displacement_to_velocity_values(t_np1);
  PetscScalar *u;
  FSI_CALL(VecGetArray(U_, &u));
  for (auto &[dof, val] : bc_values_)
    if (space_.owned(dof)) u[space_.local_to_global[dof] - space_.rstart] = val;
  FSI_CALL(VecRestoreArray(U_, &u));

  StepStats s;
  for (int pass = 0;; ++pass) {
    FSI_CALL(PetscLogStagePush(st.solve));
    inverted_ = false;
    const double ts0 = MPI_Wtime();
    FSI_CALL(SNESSolve(snes_, nullptr, U_));
    cost_.nonlinear_solve_time += MPI_Wtime() - ts0;
    FSI_CALL(PetscLogStagePop());
    PetscInt it, kit;
    FSI_CALL(SNESGetIterationNumber(snes_, &it));
    FSI_CALL(SNESGetLinearSolveIterations(snes_, &kit));
    FSI_CALL(SNESGetConvergedReason(snes_, &s.reason));
    s.newton += it;
    s.krylov += kit;
    if (s.reason < 0 || !motion_ || !motion_->follows_solid() || pass >= geometry_iterations_)
      break;
    // Geometry implicit: move the mesh with the solid displacement just found and solve again
    // until the mesh stops changing.
    std::vector<double> d2;
    move_mesh(t_np1, U_, d2);
    double change = 0, size = 0;
    for (size_t i = 0; i < d2.size(); ++i) {
      change = std::max(change, std::fabs(d2[i] - dnp1_[i]));
      size = std::max(size, std::fabs(d2[i]));
    }
    double loc[2] = {change, size}, glob[2];
    MPI_Allreduce(loc, glob, 2, MPI_DOUBLE, MPI_MAX, PetscObjectComm((PetscObject)space_.dm));
    s.geometry_iterations = pass + 1;
    s.geometry_change = glob[1] > 0 ? glob[0] / glob[1] : 0.0;
    if (s.geometry_change <= geometry_rtol_) break;
    set_geometry(d2);
    check_mesh("during", n_ + 1);
    set_context(t_np1);
  }
  if (s.reason < 0 && inverted_)
    throw SolveError("a solid element inverted (det F <= 0) at step " + std::to_string(n_ + 1) +
                     " (t = " + std::to_string(t_np1) +
                     "): the load or time step is too large for this mesh; use more steps");
  if (s.reason < 0)
    throw SolveError(std::string("Newton did not converge at step ") + std::to_string(n_ + 1) +
                     " (t = " + std::to_string(t_np1) + "): " + SNESConvergedReasons[s.reason] +
                     "; try a smaller -ts_dt (or more load steps -ts_max_steps)");
  const double dt = dt_;
  if (tp_.steady) {
    FSI_CALL(VecAXPY(Dn_, dt, U_)); // u_{n+1} = u_n + dt v
  } else {
    // a_{n+1} = (v_{n+1} - v_n) / (gamma dt) - (1 - gamma) / gamma a_n, then the Newmark update
    // u_{n+1} = u_n + dt v_n + dt^2 [(1/2 - beta) a_n + beta a_{n+1}].
    FSI_CALL(VecCopy(An_, work_));
    FSI_CALL(VecAXPBYPCZ(An_, 1.0 / (gamma_ * dt), -1.0 / (gamma_ * dt), -(1 - gamma_) / gamma_, U_,
                         Vn_));
    FSI_CALL(VecAXPBYPCZ(Dn_, dt, dt * dt * (0.5 - beta_), 1.0, Vn_, work_));
    FSI_CALL(VecAXPY(Dn_, dt * dt * beta_, An_));
  }
  FSI_CALL(VecCopy(U_, Vn_));
  dn_ = dnp1_;
  Xn_ = Xnp1_;
  t_ = t_np1;
  ++n_;
  return s;
}

// Prescribed displacements g at t_{n+1} become velocity values through the Newmark relation
// (step_context.hpp) solved for v_{n+1}, so that u_{n+1} = g exactly.
void Problem::displacement_to_velocity_values(double t_np1) {
  bcs_->displacement_values(t_np1, disp_values_);
  if (disp_values_.empty()) return;
  const PetscScalar *v, *a, *d;
  FSI_CALL(VecGetArrayRead(Vloc_, &v));
  FSI_CALL(VecGetArrayRead(Aloc_, &a));
  FSI_CALL(VecGetArrayRead(Dloc_, &d));
  PetscScalar *u;
  FSI_CALL(VecGetArray(U_, &u));
  const double dt = dt_;
  for (auto &[i, g] : disp_values_) {
    double val;
    if (tp_.steady)
      val = (g - PetscRealPart(d[i])) / dt;
    else
      val = PetscRealPart(v[i]) +
            gamma_ / (beta_ * dt) *
                (g - PetscRealPart(d[i]) - dt * PetscRealPart(v[i]) -
                 dt * dt * ((0.5 - beta_) - beta_ * (1 - gamma_) / gamma_) * PetscRealPart(a[i]));
    bc_values_.emplace_back(i, val);
    if (space_.owned(i)) u[space_.local_to_global[i] - space_.rstart] = val;
  }
  FSI_CALL(VecRestoreArray(U_, &u));
  FSI_CALL(VecRestoreArrayRead(Vloc_, &v));
  FSI_CALL(VecRestoreArrayRead(Aloc_, &a));
  FSI_CALL(VecRestoreArrayRead(Dloc_, &d));
}

bool Problem::residual(Vec U, Vec F) {
  Stages &st = Stages::get();
  FSI_CALL(PetscLogStagePush(st.assembly));
  const double t0 = MPI_Wtime();
  space_.to_local(U, Uloc_);
  FSI_CALL(VecZeroEntries(Floc_));
  const PetscScalar *u, *v, *a, *dn;
  PetscScalar *f;
  FSI_CALL(VecGetArrayRead(Dloc_, &dn));
  ctx_.Dn = dn;
  FSI_CALL(VecGetArrayRead(Uloc_, &u));
  FSI_CALL(VecGetArrayRead(Vloc_, &v));
  FSI_CALL(VecGetArrayRead(Aloc_, &a));
  FSI_CALL(VecGetArray(Floc_, &f));
  ctx_.U = u;
  ctx_.Vn = v;
  ctx_.An = a;
  bool valid = true;
  try {
    for (auto &m : modules_)
      m->add_residual(ctx_, f);
    bcs_->add_traction_residual(ctx_, f);
  } catch (SolveError &) { // an inverted solid element: outside the domain of the residual
    valid = false;
  }
  FSI_CALL(VecRestoreArray(Floc_, &f));
  FSI_CALL(VecZeroEntries(F));
  space_.add_to_global(Floc_, F);
  // Dirichlet rows: u - g.
  PetscScalar *fg;
  FSI_CALL(VecGetArray(F, &fg));
  for (auto &[dof, val] : bc_values_)
    if (space_.owned(dof)) fg[space_.local_to_global[dof] - space_.rstart] = u[dof] - val;
  FSI_CALL(VecRestoreArray(F, &fg));
  FSI_CALL(VecRestoreArrayRead(Uloc_, &u));
  FSI_CALL(VecRestoreArrayRead(Vloc_, &v));
  FSI_CALL(VecRestoreArrayRead(Aloc_, &a));
  FSI_CALL(VecRestoreArrayRead(Dloc_, &dn));
  cost_.residuals++;
  cost_.residual_time += MPI_Wtime() - t0;
  FSI_CALL(PetscLogStagePop());
  int ok = valid, all_ok;
  MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, PetscObjectComm((PetscObject)F));
  if (!all_ok) inverted_ = true;
  return all_ok;
}

void Problem::jacobian(Vec U, Mat J) {
  Stages &st = Stages::get();
  FSI_CALL(PetscLogStagePush(st.assembly));
  const double t0 = MPI_Wtime();
  space_.to_local(U, Uloc_);
  FSI_CALL(MatZeroEntries(J));
  const PetscScalar *u, *v, *a, *dn;
  FSI_CALL(VecGetArrayRead(Dloc_, &dn));
  ctx_.Dn = dn;
  FSI_CALL(VecGetArrayRead(Uloc_, &u));
  FSI_CALL(VecGetArrayRead(Vloc_, &v));
  FSI_CALL(VecGetArrayRead(Aloc_, &a));
  ctx_.U = u;
  ctx_.Vn = v;
  ctx_.An = a;
  for (auto &m : modules_)
    m->add_jacobian(ctx_, J);
  bcs_->add_traction_jacobian(ctx_, J);
  for (auto &[dof, val] : bc_values_)
    if (space_.owned(dof))
      FSI_CALL(MatSetValue(J, space_.local_to_global[dof], space_.local_to_global[dof], 1.0,
                           ADD_VALUES));
  FSI_CALL(VecRestoreArrayRead(Uloc_, &u));
  FSI_CALL(VecRestoreArrayRead(Vloc_, &v));
  FSI_CALL(VecRestoreArrayRead(Aloc_, &a));
  FSI_CALL(VecRestoreArrayRead(Dloc_, &dn));
  FSI_CALL(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  FSI_CALL(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  if (pcd_) pcd_->assemble(ctx_);
  cost_.jacobians++;
  cost_.jacobian_time += MPI_Wtime() - t0;
  FSI_CALL(PetscLogStagePop());
  if (split_ && !split_->configured()) { // the preconditioner's first setup: solver time
    KSP ksp;
    FSI_CALL(SNESGetKSP(snes_, &ksp));
    split_->configure(ksp, J_);
  }
}

} // namespace fsi
