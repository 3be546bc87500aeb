#include "fsi/problem/coupled_system.hpp"
#include "fsi/discretization/sparsity.hpp"
#include "fsi/run/stages.hpp"
#include "fsi/scene/option_doc.hpp"
#include "fsi/scene/options.hpp"
#include "fsi/solver/schur_bilu.hpp"

#include <cmath>

namespace fsi {

static PetscErrorCode residual_cb(SNES snes, Vec U, Vec F, void *ctx) {
  try {
    if (!static_cast<CoupledSystem *>(ctx)->residual(U, F))
      PetscCall(SNESSetFunctionDomainError(snes));
  } catch (std::exception &e) {
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "%s", e.what());
  }
  return 0;
}

static PetscErrorCode jacobian_cb(SNES, Vec U, Mat J, Mat, void *ctx) {
  try {
    static_cast<CoupledSystem *>(ctx)->jacobian(U, J);
  } catch (std::exception &e) {
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "%s", e.what());
  }
  return 0;
}

CoupledSystem::CoupledSystem(const Space &space) : space_(space) {
  inexact_gamma_ = opt::nonnegative("newton_inexact_gamma", 0.0);
  pattern_every_ = opt::integer_at_least("sim_pattern_rebuild_every", 0, 0);
  pc_rebuild_krylov_ = opt::integer_at_least("newton_pc_rebuild_krylov", 0, 0);
  fault_residual_ = opt::integer_at_least("test_fault_residual", 0, 0); // 0: off
  F_ = space.create_global();
  Uloc_ = space.create_local();
  FSI_CALL(VecDuplicate(Uloc_, &Floc_));
}

CoupledSystem::~CoupledSystem() {
  for (Vec *v : {&F_, &Uloc_, &Floc_})
    if (*v) VecDestroy(v);
  if (J_) MatDestroy(&J_);
  if (snes_) SNESDestroy(&snes_);
}

// The Jacobian's nonzero pattern from the modules' element dof lists (every dof of an element
// couples with every other) plus the diagonal: exact for the modules the scene switched on (a
// solid cell has no pressure coupling).
void CoupledSystem::build_pattern() {
  MPI_Comm comm = PetscObjectComm((PetscObject)space_.dm);
  ISLocalToGlobalMapping l2g = space_.l2g;
  SparsityPattern pattern(comm, space_.local_to_global, space_.rstart, space_.n_owned);
  std::vector<std::vector<PetscInt>> element_dofs(modules_.size());
  for (size_t k = 0; k < modules_.size(); ++k) {
    auto &m = modules_[k];
    int n = 0;
    m->element_dofs(element_dofs[k], n);
    if (n > max_element_dofs)
      throw PetscFailure("internal: module '" + m->name() + "' has " + std::to_string(n) +
                         " dofs per element; CoupledSystem::max_element_dofs is " +
                         std::to_string(max_element_dofs));
    pattern.add_elements(element_dofs[k], n);
    std::vector<PetscInt> pairs;
    m->global_couplings(pairs);
    for (size_t p = 0; p + 1 < pairs.size(); p += 2)
      for (int s = 0; s < 2; ++s) {
        const PetscInt r0 = pairs[p + s], c0 = pairs[p + 1 - s];
        const PetscInt cols[3] = {c0, c0 + 1, c0 + 2};
        for (int i = 0; i < 3; ++i)
          pattern.add_row(r0 + i, cols, 3);
      }
  }
  if (bcs_) // boundary terms coupling all their dofs with all (a Windkessel outlet)
    for (auto &block : bcs_->dense_couplings())
      for (PetscInt r : block)
        pattern.add_row(r, block.data(), (int)block.size());
  if (J_) FSI_CALL(MatDestroy(&J_));
  FSI_CALL(MatCreate(comm, &J_));
  FSI_CALL(MatSetSizes(J_, space_.n_owned, space_.n_owned, PETSC_DETERMINE, PETSC_DETERMINE));
  FSI_CALL(MatSetType(J_, MATAIJ));
  FSI_CALL(MatSetOptionsPrefix(J_, "jac_"));
  FSI_CALL(MatSetLocalToGlobalMapping(J_, l2g, l2g));
  pattern.preallocate(J_);
  FSI_CALL(MatSetOption(J_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  for (auto &m : modules_)
    m->pattern_built();
  ++cost_.pattern_builds;
}

// SNES and its preconditioner for the current matrix.  A new pattern gets a new solver: a field
// split (and a split of its velocity block) is set up for one matrix structure.
void CoupledSystem::create_solver() {
  MPI_Comm comm = PetscObjectComm((PetscObject)space_.dm);
  if (snes_) FSI_CALL(SNESDestroy(&snes_));
  if (split_) split_->reset();
  FSI_CALL(SNESCreate(comm, &snes_));
  FSI_CALL(SNESSetFunction(snes_, F_, residual_cb, this));
  FSI_CALL(SNESSetJacobian(snes_, J_, J_, jacobian_cb, this));
  // PETSc's default stops Newton when the residual grows 1e4-fold, which large-deformation
  // solves do on their way to converging (a drooping cantilever: 7 iterations without the
  // test, DIVERGED_DTOL with it).  Failed steps are caught by -snes_max_it and step cutting;
  // -snes_divergence_tolerance still sets it.
  FSI_CALL(SNESSetDivergenceTolerance(snes_, -1.0));
  opt::choice("pc_schur_bilu_precision", "single", {"single", "double"}); // one line, not PETSc's
  FSI_CALL(SNESSetFromOptions(snes_));
  KSP ksp;
  PC pc;
  FSI_CALL(SNESGetKSP(snes_, &ksp));
  if (inexact_gamma_ > 0) {
    PetscReal atol, dtol;
    PetscInt maxit;
    FSI_CALL(KSPGetTolerances(ksp, &ksp_rtol_min_, &atol, &dtol, &maxit));
    FSI_CALL(SNESMonitorSet(snes_, inexact_monitor, this, nullptr));
  }
  if (pc_rebuild_krylov_ > 0) FSI_CALL(SNESMonitorSet(snes_, pc_rebuild_monitor, this, nullptr));
  FSI_CALL(KSPGetPC(ksp, &pc));
  PetscBool fs;
  FSI_CALL(PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &fs));
  // An ILU factored in place (-fieldsplit_velocity_sub_pc_factor_in_place) is found by looking
  // at the block, not at the option: reading the option would mark it used where nothing else does.
  factored_state_ = -1;
  if (fs) FSI_CALL(KSPSetPreSolve(ksp, in_place_presolve, this));
  if (fs) {
    // The solid's elasticity operator: GAMG builds its coarse spaces from the rigid-body modes.
    if (rigid_modes_) compose_rigid_body_modes(space_.is_velocity, space_.velocity_node_X);
    FSI_CALL(PCFieldSplitSetIS(pc, "velocity", space_.is_velocity));
    FSI_CALL(PCFieldSplitSetIS(pc, "pressure", space_.is_pressure));
  }
  set_schur_bilu_fields(pc, space_.is_velocity, space_.is_pressure);
}

// Called with each Newton residual norm, before that iteration's linear solve.  Near the
// solution the first solve must be accurate (the Newton step is only as good as it), later ones
// only need to reach the Newton target: with the paper's 1e-4 the second solve of a step needs
// ~0.1 instead of -ksp_rtol (tube: 20 -> 5 Krylov iterations).
PetscErrorCode CoupledSystem::inexact_monitor(SNES snes, PetscInt it, PetscReal fnorm, void *ctx) {
  auto *self = static_cast<CoupledSystem *>(ctx);
  if (it == 0) self->newton_f0_ = fnorm;
  PetscReal rtol, atol, stol, kr, ka, kd;
  PetscInt maxit, maxf, kmax;
  PetscCall(SNESGetTolerances(snes, &atol, &rtol, &stol, &maxit, &maxf));
  KSP ksp;
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPGetTolerances(ksp, &kr, &ka, &kd, &kmax));
  const double target = std::max(rtol * self->newton_f0_, atol);
  double eta = fnorm > 0 ? self->inexact_gamma_ * target / fnorm : 0.5;
  eta = std::min(0.5, std::max(self->ksp_rtol_min_, eta));
  PetscCall(KSPSetTolerances(ksp, eta, ka, kd, kmax));
  return 0;
}

// Called before each Newton iteration's Jacobian: the previous linear solve (of this step, or of
// the last one at iteration 0) is how well the lagged preconditioner still works.
PetscErrorCode CoupledSystem::pc_rebuild_monitor(SNES snes, PetscInt, PetscReal, void *ctx) {
  auto *self = static_cast<CoupledSystem *>(ctx);
  KSP ksp;
  PetscInt its, lag;
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPGetIterationNumber(ksp, &its));
  PetscCall(SNESGetLagPreconditioner(snes, &lag));
  if (lag > 1 && its > self->pc_rebuild_krylov_) {
    self->lag_to_restore_ = lag;
    PetscCall(SNESSetLagPreconditioner(snes, -2)); // at the next Jacobian, then kept
    ++self->cost_.preconditioner_rebuilds;
  }
  return 0;
}

// Before each outer linear solve, after SNES has said whether the preconditioner is reused: a
// rebuild (not reused, and a Jacobian PETSc's setup has not seen) refills the split's velocity
// block, which the last setup factored in place.
PetscErrorCode CoupledSystem::in_place_presolve(KSP ksp, Vec, Vec, void *ctx) {
  auto *self = static_cast<CoupledSystem *>(ctx);
  PC pc;
  PetscBool reuse;
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(KSPGetReusePreconditioner(ksp, &reuse));
  const long state = self->cost_.jacobians; // a new Jacobian is a new matrix state
  const bool first = self->factored_state_ < 0;
  if (reuse && !first) return 0;
  if (state == self->factored_state_) return 0; // PETSc keeps the preconditioner as it is
  self->factored_state_ = state;
  if (first) return 0; // nothing factored yet
  KSP *sub;
  PetscInt n;
  PetscCall(PCFieldSplitGetSubKSP(pc, &n, &sub));
  Mat A00, block;
  PetscCall(KSPGetOperators(sub[0], nullptr, &A00));
  PetscCall(PetscFree(sub));
  if (!A00) return 0;
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)A00), &size));
  MatFactorType type;
  PetscCall(MatGetFactorType(A00, &type));
  block = A00; // on 1 rank the block-Jacobi block is the split's matrix itself
  if (size > 1 && type == MAT_FACTOR_NONE) {
    PetscBool mpi;
    PetscCall(PetscObjectTypeCompare((PetscObject)A00, MATMPIAIJ, &mpi));
    if (!mpi) return 0; // not a block-Jacobi-able AIJ block: nothing of ours to unfactor
    PetscCall(MatGetDiagonalBlock(A00, &block));
    PetscCall(MatGetFactorType(block, &type));
  }
  if (type != MAT_FACTOR_NONE) PetscCall(MatSetUnfactored(block));
  return 0;
}

void CoupledSystem::setup_solver() {
  build_pattern();
  create_solver();
}

void CoupledSystem::step_size_changed(double dt) {
  PetscInt lag;
  FSI_CALL(SNESGetLagJacobian(snes_, &lag));
  if (lag == -1) FSI_CALL(SNESSetLagJacobian(snes_, -2));
  FSI_CALL(SNESGetLagPreconditioner(snes_, &lag));
  if (lag == -1) FSI_CALL(SNESSetLagPreconditioner(snes_, -2));
  // A preconditioner lagged over steps (a factorisation reused by GMRES) was built for the old
  // step's matrix, and a cut step follows a failed solve: build it anew in the next solve.
  // Error-controlled steps change dt by small factors nearly every step: that old LU still
  // preconditions well, a halved or doubled step's does not.
  if (lag > 1 &&
      !(preconditioner_dt_ > 0 && std::fabs(std::log(dt / preconditioner_dt_)) < std::log(1.5))) {
    rebuild_preconditioner_ = true;
    preconditioner_dt_ = dt;
  }
}

SolveStats CoupledSystem::solve(Vec U) {
  if (preconditioner_dt_ == 0) preconditioner_dt_ = ctx_.dt; // the first one is built for it
  bool changed = pattern_every_ > 0 && ++solves_ % pattern_every_ == 0;
  // Dirichlet values into the initial guess.
  PetscScalar *u;
  FSI_CALL(VecGetArray(U, &u));
  for (auto &[dof, val] : bc_values_)
    if (space_.owned(dof)) u[space_.local_to_global[dof] - space_.rstart] = val;
  FSI_CALL(VecRestoreArray(U, &u));
  {
    // Modules that look at the configuration (contact) see the initial guess, then say
    // whether their couplings changed.
    space_.to_local(U, Uloc_);
    const PetscScalar *ul;
    FSI_CALL(VecGetArrayRead(Uloc_, &ul));
    ctx_.U = ul;
    for (auto &m : modules_)
      m->begin_solve(ctx_);
    ctx_.U = nullptr;
    FSI_CALL(VecRestoreArrayRead(Uloc_, &ul));
  }
  for (auto &m : modules_)
    changed = changed || m->couplings_changed();
  if (changed) { // before the solve: a new matrix and a solver set up for it
    build_pattern();
    create_solver();
  }

  FSI_CALL(PetscLogStagePush(Stages::get().solve));
  inverted_ = false;
  lag_to_restore_ = 0;
  if (rebuild_preconditioner_) { // -2: at the next Jacobian, then back to the lag
    FSI_CALL(SNESGetLagPreconditioner(snes_, &lag_to_restore_));
    FSI_CALL(SNESSetLagPreconditioner(snes_, -2));
    rebuild_preconditioner_ = false;
  }
  const double t0 = MPI_Wtime();
  FSI_CALL(SNESSolve(snes_, nullptr, U));
  if (lag_to_restore_ > 1) {
    PetscInt now;
    FSI_CALL(SNESGetLagPreconditioner(snes_, &now));
    if (now == -2) rebuild_preconditioner_ = true; // asked for after the last Jacobian: next solve
    FSI_CALL(SNESSetLagPreconditioner(snes_, lag_to_restore_));
  }
  cost_.nonlinear_solve_time += MPI_Wtime() - t0;
  FSI_CALL(PetscLogStagePop());
  SolveStats s;
  FSI_CALL(SNESGetIterationNumber(snes_, &s.newton));
  FSI_CALL(SNESGetLinearSolveIterations(snes_, &s.krylov));
  FSI_CALL(SNESGetConvergedReason(snes_, &s.reason));
  s.inverted = inverted_;
  return s;
}

bool CoupledSystem::residual(Vec U, Vec F) {
  FSI_CALL(PetscLogStagePush(Stages::get().assembly));
  const double t0 = MPI_Wtime();
  space_.to_local(U, Uloc_);
  FSI_CALL(VecZeroEntries(Floc_));
  const PetscScalar *u;
  PetscScalar *f;
  FSI_CALL(VecGetArrayRead(Uloc_, &u));
  FSI_CALL(VecGetArray(Floc_, &f));
  ctx_.U = u;
  for (auto &m : modules_)
    m->prepare(ctx_);
  // An inverted solid element puts U outside the residual's domain (SolveError).  Every rank
  // still adds every other term: the boundaries' terms are collective (a Windkessel sums its
  // outflow over the ranks), and a rank that skipped them left the others waiting in that sum
  // for ever (the pressure-driven valve hung at 123 ms in a line search that inverted an
  // element on one rank only).
  bool valid = true;
  const bool fault = fault_residual_ > 0 && cost_.residuals + 1 == fault_residual_ &&
                     space_.rstart == 0; // -test_fault_residual: rank 0 only
  auto guarded = [&](auto &&add) {
    try {
      add();
    } catch (SolveError &) {
      valid = false;
    }
  };
  for (auto &m : modules_)
    guarded([&] {
      // thrown from inside a module's term, as the material does, so that a test of the fault
      // also catches a guard that covers more than one term again
      if (fault && &m == &modules_.front()) throw SolveError("test fault: inverted element");
      m->add_residual(ctx_, f);
    });
  guarded([&] { bcs_->add_residual(ctx_, f); });
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
  ctx_.U = nullptr;
  cost_.residuals++;
  cost_.residual_time += MPI_Wtime() - t0;
  FSI_CALL(PetscLogStagePop());
  int ok = valid, all_ok;
  MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, PetscObjectComm((PetscObject)F));
  if (!all_ok) inverted_ = true;
  return all_ok;
}

void CoupledSystem::jacobian(Vec U, Mat J) {
  FSI_CALL(PetscLogStagePush(Stages::get().assembly));
  const double t0 = MPI_Wtime();
  space_.to_local(U, Uloc_);
  FSI_CALL(MatZeroEntries(J));
  const PetscScalar *u;
  FSI_CALL(VecGetArrayRead(Uloc_, &u));
  ctx_.U = u;
  for (auto &m : modules_)
    m->prepare(ctx_);
  for (auto &m : modules_) {
    const double tm = MPI_Wtime();
    m->add_jacobian(ctx_, J);
    cost_.module_jacobian_time[m->name()] += MPI_Wtime() - tm;
  }
  bcs_->add_jacobian(ctx_, J);
  for (auto &[dof, val] : bc_values_)
    if (space_.owned(dof))
      FSI_CALL(MatSetValue(J, space_.local_to_global[dof], space_.local_to_global[dof], 1.0,
                           ADD_VALUES));
  FSI_CALL(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  FSI_CALL(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  if (pcd_) pcd_->assemble(ctx_);
  FSI_CALL(VecRestoreArrayRead(Uloc_, &u));
  ctx_.U = nullptr;
  cost_.jacobians++;
  cost_.jacobian_time += MPI_Wtime() - t0;
  FSI_CALL(PetscLogStagePop());
  if (split_ && !split_->configured()) { // the preconditioner's first setup: solver time
    KSP ksp;
    FSI_CALL(SNESGetKSP(snes_, &ksp));
    split_->configure(ksp, J_);
  }
}

// Its options, for -help and docs/options.md (option_doc.hpp).
OptionSection solver_options() {
  return {
      "Solver (PETSc; presets in petsc_options/)",
      {{"solver_preset", "(the scene's)", "-",
        "NAME: petsc_options/NAME.opts (or a path ending in .opts) sets every solver option "
        "the scene and command line leave unset; the last one given wins"},
       {"snes_*, ksp_*, pc_*", "PETSc's", "-", "Newton and linear solver of the coupled system"},
       {"fieldsplit_velocity_pc_type", "", "-", "fieldsplit: split velocity into fluid | solid"},
       {"fieldsplit_pressure_pc_type", "", "-", "pcd: convection-aware Schur preconditioner"},
       {"pc_schur_bilu_precision", "single", "-",
        "-pc_type schur_bilu (Schur + block ILU, no block copies): velocity factor storage"},
       {"schur_*", "hypre", "-", "schur_bilu's Sp preconditioner (-schur_pc_type, ...)"},
       {"jac_*", "", "-", "options of the Jacobian matrix (prefix jac_)"},
       {"newton_inexact_gamma", "0 (off)", "-",
        "linear solves only to gamma x the Newton target (|F0| snes_rtol), >= ksp_rtol"},
       {"newton_pc_rebuild_krylov", "0 (off)", "-",
        "a lagged preconditioner is rebuilt when a linear solve took more Krylov iterations"},
       {"sim_pattern_rebuild_every", "0", "solves",
        "rebuild the Jacobian's nonzero pattern every N solves (checks the rebuild path)"},
       {"test_fault_residual", "0", "-",
        "N: the N-th residual evaluation meets an inverted solid element on rank 0 (tests)"}}};
}

} // namespace fsi
