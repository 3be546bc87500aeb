// Pressure convection-diffusion preconditioner: the operators (PcdOperators) and the PETSc PC
// type "pcd" that applies S^{-1} ~ (rho cm M_p)^{-1} F_p Sp^{-1} (see pcd.hpp).
#include "fsi/solver/pcd.hpp"
#include "fsi/discretization/sparsity.hpp"
#include "fsi/scene/options.hpp"

#include <petsc/private/pcimpl.h>

namespace fsi {

namespace {

// The operators of the running problem (one per process), read by the PC at setup: the PC is
// created by PETSc inside the field split, whose Schur preconditioning matrix it gets as pmat.
const Mat *g_Fp = nullptr;
const Vec *g_D = nullptr;

struct PcdContext {
  KSP sp = nullptr; // Sp solve
  Vec t1 = nullptr, t2 = nullptr;
};

PetscErrorCode pcd_setup(PC pc) {
  PcdContext *c = (PcdContext *)pc->data;
  PetscFunctionBeginUser;
  PetscCheck(g_Fp && g_D, PetscObjectComm((PetscObject)pc), PETSC_ERR_ARG_WRONGSTATE,
             "PC pcd needs fsi_app's fluid pressure operators (a fluid scene, "
             "-fieldsplit_pressure_pc_type pcd)");
  if (!c->sp) {
    const char *prefix;
    PetscCall(PCGetOptionsPrefix(pc, &prefix));
    PetscCall(KSPCreate(PetscObjectComm((PetscObject)pc), &c->sp));
    PetscCall(KSPSetOptionsPrefix(c->sp, prefix));
    PetscCall(KSPAppendOptionsPrefix(c->sp, "pcd_"));
    PetscCall(KSPSetType(c->sp, KSPPREONLY));
    PC sub;
    PetscCall(KSPGetPC(c->sp, &sub));
    PetscCall(PCSetType(sub, PCHYPRE));
    PetscCall(KSPSetFromOptions(c->sp));
    PetscCall(MatCreateVecs(pc->pmat, &c->t1, &c->t2));
  }
  PetscCall(KSPSetOperators(c->sp, pc->pmat, pc->pmat));
  PetscCall(KSPSetUp(c->sp));
  PetscFunctionReturn(0);
}

PetscErrorCode pcd_apply(PC pc, Vec x, Vec y) {
  PcdContext *c = (PcdContext *)pc->data;
  PetscFunctionBeginUser;
  PetscCall(KSPSolve(c->sp, x, c->t1));
  PetscCall(MatMult(*g_Fp, c->t1, c->t2));
  PetscCall(VecPointwiseDivide(y, c->t2, *g_D));
  PetscFunctionReturn(0);
}

PetscErrorCode pcd_view(PC pc, PetscViewer v) {
  PcdContext *c = (PcdContext *)pc->data;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(v, "  pressure convection-diffusion: (rho cm M_p)^-1 F_p Sp^-1; "
                                      "Sp solve:\n"));
  if (c->sp) {
    PetscCall(PetscViewerASCIIPushTab(v));
    PetscCall(KSPView(c->sp, v));
    PetscCall(PetscViewerASCIIPopTab(v));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode pcd_destroy(PC pc) {
  PcdContext *c = (PcdContext *)pc->data;
  PetscFunctionBeginUser;
  PetscCall(KSPDestroy(&c->sp));
  PetscCall(VecDestroy(&c->t1));
  PetscCall(VecDestroy(&c->t2));
  delete c;
  pc->data = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode pcd_create(PC pc) {
  PetscFunctionBeginUser;
  pc->data = new PcdContext;
  pc->ops->setup = pcd_setup;
  pc->ops->apply = pcd_apply;
  pc->ops->view = pcd_view;
  pc->ops->destroy = pcd_destroy;
  PetscFunctionReturn(0);
}

} // namespace

void register_pcd_preconditioner() {
  FSI_CALL(PCRegister("pcd", pcd_create));
}

bool PcdOperators::requested(bool fluid) {
  if (opt::string("fieldsplit_pressure_pc_type", "") != "pcd") return false;
  if (!fluid)
    throw InputError("-fieldsplit_pressure_pc_type pcd needs a fluid (-physics fluid): use "
                     "another preconditioner for a solid-only scene");
  if (opt::string("pc_fieldsplit_schur_precondition", "") != "selfp")
    throw InputError("-fieldsplit_pressure_pc_type pcd works on the selfp matrix: add "
                     "-pc_fieldsplit_schur_precondition selfp (see "
                     "petsc_options/fieldsplit_pcd.opts)");
  return true;
}

PcdOperators::PcdOperators(const Space &space, const Mesh &mesh, const FluidModule &fluid,
                           const Boundaries &bcs)
    : space_(space), fluid_(fluid) {
  MPI_Comm comm = PetscObjectComm((PetscObject)space.dm);
  PetscInt n, N;
  FSI_CALL(ISGetLocalSize(space.is_pressure, &n));
  FSI_CALL(ISGetSize(space.is_pressure, &N));
  const PetscInt start = rank_offset(comm, n);

  // Row of every local pressure dof in the pressure block (the split's ordering: is_pressure's).
  Vec g = space.create_global(), loc = space.create_local();
  const PetscInt *idx;
  PetscScalar *a;
  const PetscScalar *la;
  FSI_CALL(VecSet(g, -1.0));
  FSI_CALL(ISGetIndices(space.is_pressure, &idx));
  FSI_CALL(VecGetArray(g, &a));
  for (PetscInt i = 0; i < n; ++i)
    a[idx[i] - space.rstart] = (double)(start + i);
  FSI_CALL(VecRestoreArray(g, &a));
  FSI_CALL(ISRestoreIndices(space.is_pressure, &idx));
  space.to_local(g, loc);
  pindex_.assign(space.n_local, -1);
  FSI_CALL(VecGetArrayRead(loc, &la));
  for (PetscInt d = 0; d < space.n_local; ++d)
    pindex_[d] = (PetscInt)PetscRealPart(la[d]);
  FSI_CALL(VecRestoreArrayRead(loc, &la));
  FSI_CALL(VecDestroy(&g));
  FSI_CALL(VecDestroy(&loc));

  // Pressure dofs on the fluid's traction boundaries, marked alike on every rank that sees them.
  std::vector<char> outflow(space.n_local, 0);
  for (auto &bc : bcs.list())
    if (bc->fixes_pressure_level())
      for (auto &f : bc->faces())
        for (int i = 0; i < 3; ++i)
          outflow[f.pdof[i]] = 1;
  outflow_ = space.mark_on_all_ranks(outflow);

  std::vector<char> in_fluid(space.n_cells(), 0);
  for (PetscInt k : fluid.cells())
    in_fluid[k] = 1;
  for (auto &bc : bcs.list())
    if (bc->type() == "velocity")
      for (auto &f : space.boundary_faces(mesh, bc->name(), &in_fluid))
        inflow_.push_back(f);

  held_ = bcs.dirichlet_mask();
  for (PetscInt d = 0; d < space.n_local; ++d)
    if (pindex_[d] >= 0 && held_[d] && space.owned(d)) held_rows_.push_back(pindex_[d]);

  // Nonzero pattern: the fluid's P1 element couplings plus every diagonal.
  std::vector<PetscInt> cell_dofs; // local pressure dofs, -1 where held (no couplings)
  cell_dofs.reserve(4 * fluid.cells().size());
  for (PetscInt k : fluid.cells())
    for (int a = 0; a < 4; ++a) {
      const PetscInt d = space.cell_pdof[4 * k + a];
      cell_dofs.push_back(held_[d] ? -1 : d);
    }
  SparsityPattern pattern(comm, pindex_, start, n);
  pattern.add_elements(cell_dofs, 4);
  FSI_CALL(MatCreate(comm, &Fp_));
  FSI_CALL(MatSetSizes(Fp_, n, n, N, N));
  FSI_CALL(MatSetType(Fp_, MATAIJ));
  pattern.preallocate(Fp_);
  FSI_CALL(MatSetOption(Fp_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  FSI_CALL(MatCreateVecs(Fp_, &D_, nullptr));
  g_Fp = &Fp_;
  g_D = &D_;
}

PcdOperators::~PcdOperators() {
  if (g_Fp == &Fp_) { // a rebuilt run's operators may already have taken over
    g_Fp = nullptr;
    g_D = nullptr;
  }
  if (Fp_) MatDestroy(&Fp_);
  if (D_) VecDestroy(&D_);
}

// Pressure-block rows of a cell's 4 pressure dofs; -1 for held dofs (their rows and columns get
// only the diagonal); drop: the dof's couplings are removed (held, or Dirichlet in F_p).
void PcdOperators::element_rows(const PetscInt pdof[4], PetscInt rows[4], bool drop[4]) const {
  for (int a = 0; a < 4; ++a) {
    rows[a] = held_[pdof[a]] ? -1 : pindex_[pdof[a]];
    drop[a] = held_[pdof[a]] || outflow_[pdof[a]];
  }
}

void PcdOperators::assemble(const StepContext &ctx) {
  FSI_CALL(MatZeroEntries(Fp_));
  FSI_CALL(VecZeroEntries(D_));
  const double rcm = fluid_.params().rho * ctx.mass_shift();
  double F[4][4], d[4];
  PetscInt pdof[4], rows[4];
  bool drop[4];
  for (size_t c = 0; c < fluid_.cells().size(); ++c) {
    fluid_.pressure_operators(ctx, c, d, F, pdof);
    element_rows(pdof, rows, drop);
    for (int a = 0; a < 4; ++a) {
      d[a] *= rcm;
      for (int b = 0; b < 4; ++b)
        if (a != b && (drop[a] || drop[b])) F[a][b] = 0;
    }
    FSI_CALL(MatSetValues(Fp_, 4, rows, 4, rows, &F[0][0], ADD_VALUES));
    FSI_CALL(VecSetValues(D_, 4, rows, d, ADD_VALUES));
  }
  // Robin term on inflow faces: -rho cf (c.n) int q p, c the face's mean convective velocity.
  const double rcf = fluid_.params().rho * ctx.stiff_shift();
  for (auto &f : inflow_) {
    double n[3], c[3] = {};
    const double area = 0.5 * outward_normal(f, ctx.X_af, n);
    for (int i = 0; i < 3; ++i) {
      for (int a = 3; a < 6; ++a) // P2 triangle: vertex functions integrate to 0, edges to 1/3
        c[i] += ctx.v_af(f.vdof[a] + i) / 3.0;
      if (ctx.W)
        for (int a = 0; a < 3; ++a)
          c[i] -= ctx.W[3 * f.vertex[a] + i] / 3.0;
    }
    const double cn = c[0] * n[0] + c[1] * n[1] + c[2] * n[2];
    if (cn >= 0) continue;
    PetscInt frows[3];
    double R[3][3];
    for (int a = 0; a < 3; ++a) {
      frows[a] = held_[f.pdof[a]] ? -1 : pindex_[f.pdof[a]];
      const bool da = held_[f.pdof[a]] || outflow_[f.pdof[a]];
      for (int b = 0; b < 3; ++b) {
        const bool db = held_[f.pdof[b]] || outflow_[f.pdof[b]];
        R[a][b] = a != b && (da || db) ? 0.0 : -rcf * cn * area / 12.0 * (a == b ? 2 : 1);
      }
    }
    FSI_CALL(MatSetValues(Fp_, 3, frows, 3, frows, &R[0][0], ADD_VALUES));
  }
  // Held pressure dofs are identity rows of S and of Sp: keep the approximation the identity.
  for (PetscInt r : held_rows_) {
    FSI_CALL(MatSetValue(Fp_, r, r, 1.0, ADD_VALUES));
    FSI_CALL(VecSetValue(D_, r, 1.0, ADD_VALUES));
  }
  FSI_CALL(MatAssemblyBegin(Fp_, MAT_FINAL_ASSEMBLY));
  FSI_CALL(VecAssemblyBegin(D_));
  FSI_CALL(MatAssemblyEnd(Fp_, MAT_FINAL_ASSEMBLY));
  FSI_CALL(VecAssemblyEnd(D_));
}

} // namespace fsi
