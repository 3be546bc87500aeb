// SparsityPattern (the Jacobian's pattern counted as CSR) against PETSc's MATPREALLOCATOR fed
// the same element lists: random elements over owned and ghost dofs (node triples whose rows
// share their elements, single dofs, skipped -1 entries), rows owned by another rank, extra
// (row, columns) couplings; every owned row's columns must be equal.  Run on 1 and 2+ ranks.
#include "fsi/common.hpp"
#include "fsi/discretization/sparsity.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <random>

using namespace fsi;

static void fill_reference(Mat pre, const std::vector<std::vector<PetscInt>> &sets,
                           const std::vector<int> &n, const std::vector<PetscInt> &extra_rows,
                           const std::vector<PetscInt> &extra_cols, int ncols, PetscInt rstart,
                           PetscInt nown) {
  std::vector<double> zeros(64 * 64, 0.0);
  for (size_t s = 0; s < sets.size(); ++s)
    for (size_t e = 0; e < sets[s].size() / n[s]; ++e)
      FSI_CALL(MatSetValuesLocal(pre, n[s], &sets[s][n[s] * e], n[s], &sets[s][n[s] * e],
                                 zeros.data(), INSERT_VALUES));
  for (size_t k = 0; k < extra_rows.size(); ++k)
    if (extra_rows[k] >= rstart && extra_rows[k] < rstart + nown)
      FSI_CALL(MatSetValues(pre, 1, &extra_rows[k], ncols, &extra_cols[ncols * k], zeros.data(),
                            INSERT_VALUES));
  for (PetscInt r = rstart; r < rstart + nown; ++r)
    FSI_CALL(MatSetValue(pre, r, r, 0.0, INSERT_VALUES));
}

int main(int argc, char **argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  int failures = 0;
  {
    MPI_Comm comm = PETSC_COMM_WORLD;
    PetscMPIInt rank, size;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &size);
    std::mt19937 rng(7 + rank);
    // Owned: 3 * nodes + singles dofs per rank (sizes differ by rank).
    const PetscInt nodes = 40 + 7 * rank, singles = 15 + 3 * rank, nown = 3 * nodes + singles;
    PetscInt rstart = 0, N = 0;
    MPI_Exscan(&nown, &rstart, 1, MPIU_INT, MPI_SUM, comm);
    if (rank == 0) rstart = 0;
    MPI_Allreduce(&nown, &N, 1, MPIU_INT, MPI_SUM, comm);
    // Local dofs: the owned ones in a shuffled order, then ghosts of other ranks' dofs.
    std::vector<PetscInt> l2g(nown);
    std::iota(l2g.begin(), l2g.end(), rstart);
    std::vector<PetscInt> node_first, single_dofs; // local indices
    for (PetscInt a = 0; a < nodes; ++a)
      node_first.push_back(3 * a);
    for (PetscInt a = 0; a < singles; ++a)
      single_dofs.push_back(3 * nodes + a);
    // ghost triples: any other rank's first 3 * nodes dofs, aligned on their triples
    for (int g = 0; size > 1 && g < 12; ++g) {
      const int other = (rank + 1 + g % (size - 1)) % size;
      PetscInt ostart = 0;
      for (int p = 0; p < other; ++p)
        ostart += 3 * (40 + 7 * p) + 15 + 3 * p;
      const PetscInt onode = (PetscInt)(rng() % (40 + 7 * other));
      bool dup = false;
      for (size_t k = nown; k < l2g.size(); k += 3)
        dup = dup || l2g[k] == ostart + 3 * onode;
      if (dup) continue;
      node_first.push_back((PetscInt)l2g.size());
      for (int i = 0; i < 3; ++i)
        l2g.push_back(ostart + 3 * onode + i);
    }
    std::vector<std::vector<PetscInt>> sets(2);
    std::vector<int> n = {14, 9};
    auto pick = [&](const std::vector<PetscInt> &from) { return from[rng() % from.size()]; };
    for (int e = 0; e < 60; ++e) { // 4 nodes + 2 singles (one sometimes skipped)
      for (int a = 0; a < 4; ++a) {
        const PetscInt f = pick(node_first);
        for (int i = 0; i < 3; ++i)
          sets[0].push_back(f + i);
      }
      sets[0].push_back(pick(single_dofs));
      sets[0].push_back(rng() % 4 == 0 ? -1 : pick(single_dofs));
    }
    for (int e = 0; e < 40; ++e) // 3 nodes
      for (int a = 0; a < 3; ++a) {
        const PetscInt f = pick(node_first);
        for (int i = 0; i < 3; ++i)
          sets[1].push_back(f + i);
      }
    // Extra couplings: 3 columns each, rows anywhere (only owned ones count).
    const int ncols = 3;
    std::vector<PetscInt> extra_rows, extra_cols;
    for (int k = 0; k < 30; ++k) {
      extra_rows.push_back((PetscInt)(rng() % N));
      for (int c = 0; c < ncols; ++c)
        extra_cols.push_back((PetscInt)(rng() % N));
    }

    ISLocalToGlobalMapping map;
    FSI_CALL(ISLocalToGlobalMappingCreate(comm, 1, (PetscInt)l2g.size(), l2g.data(),
                                          PETSC_COPY_VALUES, &map));
    Mat pre, ref, A;
    FSI_CALL(MatCreate(comm, &pre));
    FSI_CALL(MatSetSizes(pre, nown, nown, N, N));
    FSI_CALL(MatSetType(pre, MATPREALLOCATOR));
    FSI_CALL(MatSetLocalToGlobalMapping(pre, map, map));
    FSI_CALL(MatSetUp(pre));
    fill_reference(pre, sets, n, extra_rows, extra_cols, ncols, rstart, nown);
    FSI_CALL(MatAssemblyBegin(pre, MAT_FINAL_ASSEMBLY));
    FSI_CALL(MatAssemblyEnd(pre, MAT_FINAL_ASSEMBLY));
    FSI_CALL(MatCreate(comm, &ref));
    FSI_CALL(MatSetSizes(ref, nown, nown, N, N));
    FSI_CALL(MatSetType(ref, MATAIJ));
    FSI_CALL(MatPreallocatorPreallocate(pre, PETSC_TRUE, ref));
    FSI_CALL(MatDestroy(&pre));

    SparsityPattern pattern(comm, l2g, rstart, nown);
    for (size_t s = 0; s < sets.size(); ++s)
      pattern.add_elements(sets[s], n[s]);
    for (size_t k = 0; k < extra_rows.size(); ++k)
      pattern.add_row(extra_rows[k], &extra_cols[ncols * k], ncols);
    FSI_CALL(MatCreate(comm, &A));
    FSI_CALL(MatSetSizes(A, nown, nown, N, N));
    FSI_CALL(MatSetType(A, MATAIJ));
    pattern.preallocate(A);

    long differ = 0, entries = 0, ghost_rows = 0;
    for (PetscInt r = rstart; r < rstart + nown; ++r) {
      PetscInt na, nb;
      const PetscInt *ca, *cb;
      FSI_CALL(MatGetRow(A, r, &na, &ca, nullptr));
      std::vector<PetscInt> a(ca, ca + na);
      FSI_CALL(MatRestoreRow(A, r, &na, &ca, nullptr));
      FSI_CALL(MatGetRow(ref, r, &nb, &cb, nullptr));
      std::vector<PetscInt> b(cb, cb + nb);
      FSI_CALL(MatRestoreRow(ref, r, &nb, &cb, nullptr));
      differ += a != b;
      entries += (long)a.size();
    }
    for (size_t k = nown; k < l2g.size(); ++k)
      ++ghost_rows;
    long g[3] = {differ, entries, ghost_rows}, sum[3];
    MPI_Allreduce(g, sum, 3, MPI_LONG, MPI_SUM, comm);
    PetscBool assembled;
    FSI_CALL(MatAssembled(A, &assembled));
    if (rank == 0) {
      std::printf("%s: %ld of %ld rows differ from MATPREALLOCATOR's pattern (%ld entries, %ld "
                  "ghost rows sent to their owners, %d rank(s))\n",
                  sum[0] == 0 ? "PASS" : "FAIL", sum[0], (long)N, sum[1], sum[2], size);
      std::printf("%s: the matrix is assembled\n", assembled ? "PASS" : "FAIL");
    }
    failures += sum[0] != 0 || !assembled || sum[1] <= N;
    FSI_CALL(MatDestroy(&A));
    FSI_CALL(MatDestroy(&ref));
    FSI_CALL(ISLocalToGlobalMappingDestroy(&map));
  }
  PetscCall(PetscFinalize());
  return failures ? 1 : 0;
}
