#include "fsi/solver/schur_bilu.hpp"
#include "fsi/common.hpp"
#include "fsi/solver/block_ilu3.hpp"

#include <petsc/private/pcimpl.h>

#include <memory>
#include <string>
#include <vector>

namespace fsi {
namespace {

PetscLogEvent ev_factor, ev_solve, ev_schur_setup, ev_schur_apply;

struct SchurBilu {
  IS isu = nullptr, isp = nullptr;
  PetscBool single = PETSC_TRUE;
  std::unique_ptr<BlockIlu3> ilu;
  PetscObjectState pattern = -1;    // the Jacobian's nonzero state the ILU was analysed for
  std::vector<PetscInt> uloc, ploc; // local rows of the velocity and pressure dofs
  std::vector<double> diag, ru;     // A00's diagonal; the velocity right-hand side
  Mat A01 = nullptr, Sp = nullptr;
  PC schur = nullptr;
  Vec bp = nullptr, xp = nullptr, tu = nullptr; // pressure rhs and solution; A01 xp
};

// The on-rank rows and columns of the Jacobian (an AIJ matrix on 1 or more ranks).
PetscErrorCode diagonal_block(Mat J, Mat *Ad) {
  PetscBool mpi, seq;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)J, MATMPIAIJ, &mpi));
  PetscCall(PetscObjectTypeCompare((PetscObject)J, MATSEQAIJ, &seq));
  PetscCheck(mpi || seq, PetscObjectComm((PetscObject)J), PETSC_ERR_ARG_WRONG,
             "-pc_type schur_bilu needs an AIJ Jacobian (the default; do not set -jac_mat_type)");
  *Ad = J;
  if (mpi) {
    Mat Ao;
    const PetscInt *cmap;
    PetscCall(MatMPIAIJGetSeqAIJ(J, Ad, &Ao, &cmap));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode local_rows(IS is, PetscInt rstart, std::vector<PetscInt> &rows) {
  PetscInt n;
  const PetscInt *idx;
  PetscFunctionBeginUser;
  PetscCall(ISGetLocalSize(is, &n));
  PetscCall(ISGetIndices(is, &idx));
  rows.resize(n);
  for (PetscInt i = 0; i < n; ++i)
    rows[i] = idx[i] - rstart;
  PetscCall(ISRestoreIndices(is, &idx));
  PetscFunctionReturn(0);
}

// Sp = A11 - A10 diag(A00)^-1 A01, anew at each rebuild (its pattern is PETSc's product's).
PetscErrorCode build_schur_matrix(SchurBilu *c, Mat J) {
  Mat A10, A11;
  Vec dinv;
  PetscScalar *d;
  PetscFunctionBeginUser;
  PetscCall(MatCreateSubMatrix(J, c->isp, c->isu, MAT_INITIAL_MATRIX, &A10));
  PetscCall(MatCreateSubMatrix(J, c->isp, c->isp, MAT_INITIAL_MATRIX, &A11));
  PetscCall(MatCreateVecs(A10, &dinv, nullptr));
  PetscCall(VecGetArray(dinv, &d));
  for (size_t i = 0; i < c->diag.size(); ++i)
    d[i] = c->diag[i] != 0 ? 1.0 / c->diag[i] : 1.0;
  PetscCall(VecRestoreArray(dinv, &d));
  PetscCall(MatDiagonalScale(A10, nullptr, dinv));
  PetscCall(MatDestroy(&c->Sp));
  PetscCall(MatMatMult(A10, c->A01, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &c->Sp));
  PetscCall(MatAYPX(c->Sp, -1.0, A11, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatDestroy(&A10));
  PetscCall(MatDestroy(&A11));
  PetscCall(VecDestroy(&dinv));
  PetscFunctionReturn(0);
}

PetscErrorCode schur_bilu_setup(PC pc) {
  auto *c = (SchurBilu *)pc->data;
  Mat J = pc->pmat, Ad;
  PetscFunctionBeginUser;
  PetscCheck(c->isu && c->isp, PetscObjectComm((PetscObject)pc), PETSC_ERR_ARG_WRONGSTATE,
             "-pc_type schur_bilu needs fsi_app's velocity and pressure fields: it "
             "preconditions the coupled system of a scene with a fluid");
  PetscCall(diagonal_block(J, &Ad));
  PetscObjectState state;
  PetscCall(MatGetNonzeroState(J, &state));
  if (state != c->pattern || !c->ilu) { // a new pattern: the block pattern and work vectors
    PetscInt rstart, nloc;
    PetscCall(MatGetOwnershipRange(J, &rstart, nullptr));
    PetscCall(MatGetLocalSize(J, &nloc, nullptr));
    PetscCall(local_rows(c->isu, rstart, c->uloc));
    PetscCall(local_rows(c->isp, rstart, c->ploc));
    std::vector<PetscInt> cols(nloc, -1);
    for (size_t i = 0; i < c->uloc.size(); ++i)
      cols[c->uloc[i]] = (PetscInt)i;
    try {
      c->ilu = std::make_unique<BlockIlu3>(c->single);
      c->ilu->analyse(Ad, c->uloc, cols);
    } catch (std::exception &e) {
      SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "%s", e.what());
    }
    PetscCall(MatDestroy(&c->A01));
    PetscCall(VecDestroy(&c->bp));
    PetscCall(VecDestroy(&c->xp));
    PetscCall(VecDestroy(&c->tu));
    c->ru.assign(c->uloc.size(), 0.0);
    c->pattern = state;
  }
  PetscCall(PetscLogEventBegin(ev_factor, pc, 0, 0, 0));
  bool ok = false;
  try {
    ok = c->ilu->factor(Ad, &c->diag);
  } catch (std::exception &e) {
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "%s", e.what());
  }
  PetscCall(PetscLogEventEnd(ev_factor, pc, 0, 0, 0));
  if (!ok) PetscCall(PCSetFailedReason(pc, PC_FACTOR_NUMERIC_ZEROPIVOT));

  PetscCall(PetscLogEventBegin(ev_schur_setup, pc, 0, 0, 0));
  PetscCall(MatCreateSubMatrix(J, c->isu, c->isp, c->A01 ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX,
                               &c->A01));
  PetscCall(build_schur_matrix(c, J));
  if (!c->xp) {
    PetscCall(MatCreateVecs(c->A01, &c->xp, &c->tu));
    PetscCall(VecDuplicate(c->xp, &c->bp));
  }
  if (!c->schur) {
    const char *prefix;
    PetscCall(PCGetOptionsPrefix(pc, &prefix));
    PetscCall(PCCreate(PetscObjectComm((PetscObject)pc), &c->schur));
    PetscCall(PCSetOptionsPrefix(c->schur, prefix));
    PetscCall(PCAppendOptionsPrefix(c->schur, "schur_"));
    PetscCall(PCSetType(c->schur, PCHYPRE));
    PetscCall(PCSetFromOptions(c->schur));
  }
  PetscCall(PCSetOperators(c->schur, c->Sp, c->Sp));
  PetscCall(PCSetUp(c->schur));
  PetscCall(PetscLogEventEnd(ev_schur_setup, pc, 0, 0, 0));
  PetscFunctionReturn(0);
}

// y = [A00 A01; 0 Sp]^-1 b: the pressure first, then the velocity with A01 y_p moved right.
PetscErrorCode schur_bilu_apply(PC pc, Vec b, Vec y) {
  auto *c = (SchurBilu *)pc->data;
  const PetscScalar *ba, *t;
  PetscScalar *ya, *p;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(b, &ba));
  PetscCall(VecGetArray(c->bp, &p));
  for (size_t i = 0; i < c->ploc.size(); ++i)
    p[i] = ba[c->ploc[i]];
  PetscCall(VecRestoreArray(c->bp, &p));
  PetscCall(PetscLogEventBegin(ev_schur_apply, pc, 0, 0, 0));
  PetscCall(PCApply(c->schur, c->bp, c->xp));
  PetscCall(PetscLogEventEnd(ev_schur_apply, pc, 0, 0, 0));
  PetscCall(MatMult(c->A01, c->xp, c->tu));
  PetscCall(VecGetArrayRead(c->tu, &t));
  for (size_t i = 0; i < c->uloc.size(); ++i)
    c->ru[i] = PetscRealPart(ba[c->uloc[i]] - t[i]);
  PetscCall(VecRestoreArrayRead(c->tu, &t));
  PetscCall(VecRestoreArrayRead(b, &ba));
  PetscCall(PetscLogEventBegin(ev_solve, pc, 0, 0, 0));
  c->ilu->solve(c->ru.data(), c->ru.data());
  PetscCall(PetscLogEventEnd(ev_solve, pc, 0, 0, 0));
  PetscCall(VecGetArray(y, &ya));
  for (size_t i = 0; i < c->uloc.size(); ++i)
    ya[c->uloc[i]] = c->ru[i];
  PetscCall(VecGetArrayRead(c->xp, &t));
  for (size_t i = 0; i < c->ploc.size(); ++i)
    ya[c->ploc[i]] = t[i];
  PetscCall(VecRestoreArrayRead(c->xp, &t));
  PetscCall(VecRestoreArray(y, &ya));
  PetscFunctionReturn(0);
}

PetscErrorCode schur_bilu_set_from_options(PC pc, PetscOptionItems *PetscOptionsObject) {
  auto *c = (SchurBilu *)pc->data;
  const char *kinds[] = {"single", "double"};
  PetscInt k = c->single ? 0 : 1;
  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "Schur preconditioner with a block ILU on velocity");
  PetscCall(PetscOptionsEList("-pc_schur_bilu_precision", "storage of the velocity ILU factor",
                              "PCSCHURBILU", kinds, 2, kinds[k], &k, nullptr));
  PetscOptionsHeadEnd();
  if ((k == 0) != (bool)c->single) c->ilu.reset(); // analysed anew with the other storage
  c->single = k == 0 ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode schur_bilu_view(PC pc, PetscViewer v) {
  auto *c = (SchurBilu *)pc->data;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(
      v, "  Schur upper factorisation, selfp; velocity: ILU(0) with 3x3 blocks in %s precision\n",
      c->single ? "single" : "double"));
  if (c->ilu)
    PetscCall(PetscViewerASCIIPrintf(
        v, "  velocity factor on rank 0: %d nodes, %zu blocks, %.1f MB\n", (int)c->ilu->nodes(),
        c->ilu->blocks(), c->ilu->bytes() / 1048576.0));
  if (c->schur) {
    PetscCall(PetscViewerASCIIPrintf(v, "  Schur complement (Sp) preconditioner:\n"));
    PetscCall(PetscViewerASCIIPushTab(v));
    PetscCall(PCView(c->schur, v));
    PetscCall(PetscViewerASCIIPopTab(v));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode schur_bilu_destroy(PC pc) {
  auto *c = (SchurBilu *)pc->data;
  PetscFunctionBeginUser;
  PetscCall(ISDestroy(&c->isu));
  PetscCall(ISDestroy(&c->isp));
  PetscCall(MatDestroy(&c->A01));
  PetscCall(MatDestroy(&c->Sp));
  PetscCall(PCDestroy(&c->schur));
  PetscCall(VecDestroy(&c->bp));
  PetscCall(VecDestroy(&c->xp));
  PetscCall(VecDestroy(&c->tu));
  delete c;
  pc->data = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode schur_bilu_create(PC pc) {
  PetscFunctionBeginUser;
  pc->data = new SchurBilu;
  pc->ops->setup = schur_bilu_setup;
  pc->ops->apply = schur_bilu_apply;
  pc->ops->setfromoptions = schur_bilu_set_from_options;
  pc->ops->view = schur_bilu_view;
  pc->ops->destroy = schur_bilu_destroy;
  PetscFunctionReturn(0);
}

} // namespace

void register_schur_bilu_preconditioner() {
  FSI_CALL(PCRegister("schur_bilu", schur_bilu_create));
  FSI_CALL(PetscLogEventRegister("BlockILUFactor", PC_CLASSID, &ev_factor));
  FSI_CALL(PetscLogEventRegister("BlockILUSolve", PC_CLASSID, &ev_solve));
  FSI_CALL(PetscLogEventRegister("SchurSpSetUp", PC_CLASSID, &ev_schur_setup));
  FSI_CALL(PetscLogEventRegister("SchurSpApply", PC_CLASSID, &ev_schur_apply));
}

void set_schur_bilu_fields(PC pc, IS velocity, IS pressure) {
  PetscBool mine;
  FSI_CALL(PetscObjectTypeCompare((PetscObject)pc, "schur_bilu", &mine));
  if (!mine) return;
  if (!velocity || !pressure)
    throw InputError("-pc_type schur_bilu needs the coupled system's velocity and pressure "
                     "fields: use petsc_options/direct.opts for this scene");
  auto *c = (SchurBilu *)pc->data;
  FSI_CALL(PetscObjectReference((PetscObject)velocity));
  FSI_CALL(PetscObjectReference((PetscObject)pressure));
  FSI_CALL(ISDestroy(&c->isu));
  FSI_CALL(ISDestroy(&c->isp));
  c->isu = velocity;
  c->isp = pressure;
  c->pattern = -1;
}

} // namespace fsi
