#include "fsi/discretization/element_assembler.hpp"

#include <algorithm>

namespace fsi {

std::vector<size_t> locality_order(const std::vector<PetscInt> &dofs, int n) {
  const size_t ne = dofs.size() / n;
  std::vector<PetscInt> key(ne);
  for (size_t e = 0; e < ne; ++e)
    key[e] = *std::min_element(&dofs[e * n], &dofs[e * n] + n);
  std::vector<size_t> order(ne);
  for (size_t e = 0; e < ne; ++e)
    order[e] = e;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return key[a] < key[b]; });
  return order;
}

void ElementAssembler::setup(Mat J, const Space &space, const std::vector<PetscInt> &dofs, int n,
                             const std::vector<char> &is_dirichlet,
                             const std::vector<int> &groups) {
  space_ = &space;
  dofs_ = &dofs;
  n_ = n;
  gstart_.clear();
  gsize_.clear();
  for (int g : groups) {
    gstart_.push_back(gstart_.empty() ? 0 : gstart_.back() + gsize_.back());
    gsize_.push_back(g);
  }
  if (gsize_.empty() || gstart_.back() + gsize_.back() != n)
    throw PetscFailure("internal: element dof groups do not add up to the element's dofs");
  if (find_positions(J, is_dirichlet)) return;
  gstart_.resize(n); // one dof per group: a position per entry
  gsize_.assign(n, 1);
  for (int t = 0; t < n; ++t)
    gstart_[t] = t;
  find_positions(J, is_dirichlet);
}

bool ElementAssembler::find_positions(Mat J, const std::vector<char> &is_dirichlet) {
  const Space &space = *space_;
  const std::vector<PetscInt> &dofs = *dofs_;
  const int n = n_, G = (int)gsize_.size();
  PetscBool mpi;
  FSI_CALL(PetscObjectTypeCompare((PetscObject)J, MATMPIAIJ, &mpi));
  const PetscInt *garray = nullptr;
  if (mpi)
    FSI_CALL(MatMPIAIJGetSeqAIJ(J, &A_, &B_, &garray));
  else
    A_ = J, B_ = nullptr;
  // The column indices are read in place (a copy of them would cost as much memory as the
  // pattern itself: ~37 MB per rank on the paper-size tube).
  PetscInt nr, nrb = 0;
  const PetscInt *ia, *jaA, *ib = nullptr, *jaB = nullptr;
  PetscBool done;
  FSI_CALL(MatGetRowIJ(A_, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &jaA, &done));
  iaA_.assign(ia, ia + nr + 1);
  PetscInt nB = 0;
  if (B_) {
    FSI_CALL(MatGetRowIJ(B_, 0, PETSC_FALSE, PETSC_FALSE, &nrb, &ib, &jaB, &done));
    iaB_.assign(ib, ib + nrb + 1);
    FSI_CALL(MatGetSize(B_, nullptr, &nB));
  } else {
    iaB_.assign(nr + 1, 0);
  }
  struct Restore { // the index arrays go back on every return
    Mat A, B;
    PetscInt nr, nrb;
    const PetscInt *ia, *ja, *ib, *jb;
    ~Restore() {
      PetscBool d;
      MatRestoreRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &d);
      if (B) MatRestoreRowIJ(B, 0, PETSC_FALSE, PETSC_FALSE, &nrb, &ib, &jb, &d);
    }
  } restore{A_, B_, nr, nrb, ia, jaA, ib, jaB};
  const PetscInt r0 = space.rstart, r1 = space.rstart + space.n_owned;
  const size_t ne = dofs.size() / n;
  pos_.assign(ne * G * G, 0);
  row_.assign(ne * n, SKIP);
  std::vector<PetscInt> k(n); // one row's positions
  for (size_t e = 0; e < ne; ++e) {
    const PetscInt *d = &dofs[e * n];
    for (int ga = 0; ga < G; ++ga) {
      bool first = true;
      for (int i = 0; i < gsize_[ga]; ++i) {
        const int r = gstart_[ga] + i;
        if (is_dirichlet[d[r]]) continue; // SKIP
        const PetscInt g = space.local_to_global[d[r]];
        if (g < r0 || g >= r1) {
          row_[e * n + r] = REMOTE;
          continue;
        }
        row_[e * n + r] = LOCAL;
        const PetscInt lr = g - r0, lenA = iaA_[lr + 1] - iaA_[lr];
        for (int j = 0; j < n; ++j) {
          const PetscInt gc = space.local_to_global[d[j]];
          if (gc >= r0 && gc < r1) {
            const PetscInt *it = std::lower_bound(jaA + iaA_[lr], jaA + iaA_[lr + 1], gc - r0);
            k[j] = it - (jaA + iaA_[lr]);
          } else {
            const PetscInt *gi = std::lower_bound(garray, garray + nB, gc);
            const PetscInt cb = gi - garray;
            const PetscInt *it = std::lower_bound(jaB + iaB_[lr], jaB + iaB_[lr + 1], cb);
            k[j] = lenA + (it - (jaB + iaB_[lr]));
          }
          if (k[j] >= 0xFFFF)
            throw PetscFailure("internal: matrix row too long for 16-bit positions");
        }
        uint16_t *p = &pos_[(e * G + ga) * G];
        for (int gb = 0; gb < G; ++gb) {
          const int ob = gstart_[gb], sb = gsize_[gb];
          for (int j = 1; j < sb; ++j) // consecutive, in one of the two blocks
            if (k[ob + j] != k[ob] + j || (k[ob] < lenA) != (k[ob + j] < lenA)) return false;
          if (first)
            p[gb] = (uint16_t)k[ob];
          else if (p[gb] != k[ob])
            return false; // the group's rows differ
        }
        first = false;
      }
    }
  }
  return true;
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
  const int n = n_, G = (int)gsize_.size();
  const PetscInt *d = &(*dofs_)[e * n];
  const uint8_t *flag = &row_[e * n];
  const PetscInt r0 = space_->rstart;
  for (int ga = 0; ga < G; ++ga) {
    const uint16_t *p = &pos_[(e * G + ga) * G];
    for (int i = 0; i < gsize_[ga]; ++i) {
      const int r = gstart_[ga] + i;
      if (flag[r] == SKIP) continue;
      const double *Kr = K + r * n;
      if (flag[r] == REMOTE) { // row owned by another rank: through the stash
        PetscInt gr = space_->local_to_global[d[r]], gc[64];
        for (int j = 0; j < n; ++j)
          gc[j] = space_->local_to_global[d[j]];
        FSI_CALL(MatSetValues(J, 1, &gr, n, gc, Kr, ADD_VALUES));
        continue;
      }
      const PetscInt lr = space_->local_to_global[d[r]] - r0;
      const PetscInt lenA = iaA_[lr + 1] - iaA_[lr];
      PetscScalar *a = va_ + iaA_[lr];
      PetscScalar *b = vb_ ? vb_ + iaB_[lr] - lenA : nullptr;
      for (int gb = 0; gb < G; ++gb) {
        PetscScalar *t = (p[gb] < lenA ? a : b) + p[gb];
        const double *k = Kr + gstart_[gb];
        for (int j = 0; j < gsize_[gb]; ++j)
          t[j] += k[j];
      }
    }
  }
}

} // namespace fsi
