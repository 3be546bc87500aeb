#include "fsi/discretization/element_assembler.hpp"

#include <algorithm>

namespace fsi {

void ElementAssembler::setup(Mat J, const Space &space, const std::vector<PetscInt> &dofs, int n,
                             const std::vector<char> &is_dirichlet) {
  space_ = &space;
  dofs_ = &dofs;
  PetscBool mpi;
  FSI_CALL(PetscObjectTypeCompare((PetscObject)J, MATMPIAIJ, &mpi));
  const PetscInt *garray = nullptr;
  if (mpi)
    FSI_CALL(MatMPIAIJGetSeqAIJ(J, &A_, &B_, &garray));
  else
    A_ = J, B_ = nullptr;
  PetscInt nr;
  const PetscInt *ia, *ja, *ib = nullptr, *jb = nullptr;
  PetscBool done;
  FSI_CALL(MatGetRowIJ(A_, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &done));
  iaA_.assign(ia, ia + nr + 1);
  std::vector<PetscInt> jaA(ja, ja + ia[nr]), jaB;
  FSI_CALL(MatRestoreRowIJ(A_, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &done));
  PetscInt nB = 0;
  if (B_) {
    PetscInt nrb;
    FSI_CALL(MatGetRowIJ(B_, 0, PETSC_FALSE, PETSC_FALSE, &nrb, &ib, &jb, &done));
    iaB_.assign(ib, ib + nrb + 1);
    jaB.assign(jb, jb + ib[nrb]);
    FSI_CALL(MatRestoreRowIJ(B_, 0, PETSC_FALSE, PETSC_FALSE, &nrb, &ib, &jb, &done));
    FSI_CALL(MatGetSize(B_, nullptr, &nB));
  } else {
    iaB_.assign(nr + 1, 0);
  }
  const PetscInt r0 = space.rstart, r1 = space.rstart + space.n_owned;
  const size_t ne = dofs.size() / n;
  pos_.assign(ne * n * n, SKIP);
  for (size_t e = 0; e < ne; ++e) {
    const PetscInt *d = &dofs[e * n];
    for (int i = 0; i < n; ++i) {
      uint16_t *p = &pos_[(e * n + i) * n];
      if (is_dirichlet[d[i]]) continue; // SKIP
      const PetscInt g = space.local_to_global[d[i]];
      if (g < r0 || g >= r1) {
        p[0] = REMOTE;
        continue;
      }
      const PetscInt lr = g - r0, lenA = iaA_[lr + 1] - iaA_[lr];
      for (int j = 0; j < n; ++j) {
        const PetscInt gc = space.local_to_global[d[j]];
        PetscInt k;
        if (gc >= r0 && gc < r1) {
          auto it = std::lower_bound(jaA.begin() + iaA_[lr], jaA.begin() + iaA_[lr + 1], gc - r0);
          k = it - (jaA.begin() + iaA_[lr]);
        } else {
          const PetscInt *gi = std::lower_bound(garray, garray + nB, gc);
          const PetscInt cb = gi - garray;
          auto it = std::lower_bound(jaB.begin() + iaB_[lr], jaB.begin() + iaB_[lr + 1], cb);
          k = lenA + (it - (jaB.begin() + iaB_[lr]));
        }
        if (k >= REMOTE) throw PetscFailure("internal: matrix row too long for 16-bit positions");
        p[j] = (uint16_t)k;
      }
    }
  }
  n_ = n;
}

void ElementAssembler::begin(Mat J) {
  FSI_CALL(MatSeqAIJGetArray(A_, &va_));
  if (B_) FSI_CALL(MatSeqAIJGetArray(B_, &vb_));
}

void ElementAssembler::end(Mat J) {
  FSI_CALL(MatSeqAIJRestoreArray(A_, &va_));
  if (B_) FSI_CALL(MatSeqAIJRestoreArray(B_, &vb_));
}

void ElementAssembler::add(Mat J, size_t e, const double *K) {
  const int n = n_;
  const PetscInt *d = &(*dofs_)[e * n];
  const PetscInt r0 = space_->rstart;
  for (int i = 0; i < n; ++i) {
    const uint16_t *p = &pos_[(e * n + i) * n];
    if (p[0] == SKIP) continue;
    const double *Ki = K + i * n;
    if (p[0] == REMOTE) { // row owned by another rank: through the stash
      PetscInt gr = space_->local_to_global[d[i]], gc[64];
      for (int j = 0; j < n; ++j)
        gc[j] = space_->local_to_global[d[j]];
      FSI_CALL(MatSetValues(J, 1, &gr, n, gc, Ki, ADD_VALUES));
      continue;
    }
    const PetscInt lr = space_->local_to_global[d[i]] - r0;
    PetscScalar *a = va_ + iaA_[lr];
    PetscScalar *b = vb_ ? vb_ + iaB_[lr] - (iaA_[lr + 1] - iaA_[lr]) : nullptr;
    const uint16_t lenA = (uint16_t)(iaA_[lr + 1] - iaA_[lr]);
    for (int j = 0; j < n; ++j) {
      if (p[j] < lenA)
        a[p[j]] += Ki[j];
      else
        b[p[j]] += Ki[j];
    }
  }
}

} // namespace fsi
