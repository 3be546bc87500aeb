#include "fsi/discretization/sparsity.hpp"
#include "fsi/common.hpp"

#include <algorithm>
#include <iterator>

namespace fsi {

SparsityPattern::SparsityPattern(MPI_Comm comm, const std::vector<PetscInt> &local_to_global,
                                 PetscInt rstart, PetscInt n_owned)
    : comm_(comm), l2g_(local_to_global), rstart_(rstart), n_owned_(n_owned) {}

void SparsityPattern::add_elements(const std::vector<PetscInt> &dofs, int n) {
  if (n > 0 && !dofs.empty()) sets_.push_back({&dofs, n});
}

void SparsityPattern::add_row(PetscInt row, const PetscInt *cols, int n) {
  if (row < rstart_ || row >= rstart_ + n_owned_) return;
  for (int k = 0; k < n; ++k) {
    extra_.push_back(row - rstart_);
    extra_.push_back(cols[k]);
  }
}

void SparsityPattern::preallocate(Mat J) {
  const PetscInt nl = (PetscInt)l2g_.size();
  // Element incidence of every local dof: elements numbered across the sets.
  std::vector<PetscInt> base{0};
  for (auto &s : sets_)
    base.push_back(base.back() + (PetscInt)(s.dofs->size() / s.n));
  std::vector<PetscInt> off(nl + 1, 0);
  for (auto &s : sets_)
    for (PetscInt d : *s.dofs)
      if (d >= 0) ++off[d + 1];
  for (PetscInt d = 0; d < nl; ++d)
    off[d + 1] += off[d];
  std::vector<PetscInt> inc(off[nl]);
  {
    std::vector<PetscInt> next(off.begin(), off.end() - 1);
    for (size_t k = 0; k < sets_.size(); ++k) {
      const auto &dofs = *sets_[k].dofs;
      const int n = sets_[k].n;
      for (size_t i = 0; i < dofs.size(); ++i)
        if (dofs[i] >= 0) inc[next[dofs[i]]++] = base[k] + (PetscInt)(i / n);
    }
  }

  PetscMPIInt size;
  MPI_Comm_size(comm_, &size);
  std::vector<PetscInt> ranges(size + 1, 0);
  MPI_Allgather(&rstart_, 1, MPIU_INT, ranges.data(), 1, MPIU_INT, comm_);
  PetscInt n_global = 0;
  MPI_Allreduce(&n_owned_, &n_global, 1, MPIU_INT, MPI_SUM, comm_);
  ranges[size] = n_global;

  // Each row's columns: the union of its elements' dofs (a marker per local dof), sorted.  The
  // components of one node share their elements, so a row whose incidence equals the previous
  // row's reuses its columns.
  std::vector<PetscInt> mark(nl, -1), cols, rowcols, row_at(n_owned_, -1), row_len(n_owned_, 0);
  std::vector<std::vector<PetscInt>> send(size);
  for (PetscInt d = 0; d < nl; ++d) {
    const PetscInt b = off[d], e = off[d + 1];
    if (b == e) continue;
    const bool same = d > 0 && e - b == b - off[d - 1] &&
                      std::equal(inc.begin() + b, inc.begin() + e, inc.begin() + off[d - 1]);
    if (!same) {
      cols.clear();
      for (PetscInt k = b; k < e; ++k) {
        const PetscInt el = inc[k];
        const size_t s = std::upper_bound(base.begin(), base.end(), el) - base.begin() - 1;
        const int n = sets_[s].n;
        const PetscInt *dofs = sets_[s].dofs->data() + (size_t)(el - base[s]) * n;
        for (int a = 0; a < n; ++a) {
          const PetscInt x = dofs[a];
          if (x < 0 || mark[x] == d) continue;
          mark[x] = d;
          cols.push_back(l2g_[x]);
        }
      }
      std::sort(cols.begin(), cols.end());
    }
    const PetscInt g = l2g_[d];
    if (g >= rstart_ && g < rstart_ + n_owned_) {
      row_at[g - rstart_] = (PetscInt)rowcols.size();
      row_len[g - rstart_] = (PetscInt)cols.size();
      rowcols.insert(rowcols.end(), cols.begin(), cols.end());
    } else {
      const int owner =
          (int)(std::upper_bound(ranges.begin(), ranges.end(), g) - ranges.begin() - 1);
      auto &buf = send[owner];
      buf.push_back(g);
      buf.push_back((PetscInt)cols.size());
      buf.insert(buf.end(), cols.begin(), cols.end());
    }
  }
  std::vector<PetscInt>().swap(inc);
  std::vector<PetscInt>().swap(mark);

  // Rows of another rank's dofs go to their owner, as (row, column) pairs there.
  if (size > 1) {
    std::vector<int> scount(size), rcount(size), sdispl(size + 1, 0), rdispl(size + 1, 0);
    for (int p = 0; p < size; ++p)
      scount[p] = (int)send[p].size();
    MPI_Alltoall(scount.data(), 1, MPI_INT, rcount.data(), 1, MPI_INT, comm_);
    for (int p = 0; p < size; ++p) {
      sdispl[p + 1] = sdispl[p] + scount[p];
      rdispl[p + 1] = rdispl[p] + rcount[p];
    }
    std::vector<PetscInt> sbuf(sdispl[size]), rbuf(rdispl[size]);
    for (int p = 0; p < size; ++p)
      std::copy(send[p].begin(), send[p].end(), sbuf.begin() + sdispl[p]);
    std::vector<std::vector<PetscInt>>().swap(send);
    MPI_Alltoallv(sbuf.data(), scount.data(), sdispl.data(), MPIU_INT, rbuf.data(), rcount.data(),
                  rdispl.data(), MPIU_INT, comm_);
    for (size_t k = 0; k < rbuf.size();) {
      const PetscInt g = rbuf[k], n = rbuf[k + 1];
      add_row(g, &rbuf[k + 2], (int)n);
      k += 2 + n;
    }
  }

  // The extra (row, column) pairs by row.
  std::vector<PetscInt> eoff(n_owned_ + 1, 0);
  for (size_t k = 0; k < extra_.size(); k += 2)
    ++eoff[extra_[k] + 1];
  for (PetscInt r = 0; r < n_owned_; ++r)
    eoff[r + 1] += eoff[r];
  std::vector<PetscInt> ecol(eoff[n_owned_]);
  {
    std::vector<PetscInt> next(eoff.begin(), eoff.end() - 1);
    for (size_t k = 0; k < extra_.size(); k += 2)
      ecol[next[extra_[k]]++] = extra_[k + 1];
  }
  std::vector<PetscInt>().swap(extra_);

  // CSR of the owned rows: element columns, extra columns and the diagonal.
  std::vector<PetscInt> ia(n_owned_ + 1, 0), ja;
  ja.reserve(rowcols.size() + ecol.size() + n_owned_);
  std::vector<PetscInt> more;
  for (PetscInt r = 0; r < n_owned_; ++r) {
    more.assign(ecol.begin() + eoff[r], ecol.begin() + eoff[r + 1]);
    more.push_back(rstart_ + r);
    std::sort(more.begin(), more.end());
    more.erase(std::unique(more.begin(), more.end()), more.end());
    const PetscInt *c = row_at[r] >= 0 ? rowcols.data() + row_at[r] : nullptr;
    std::set_union(c, c + row_len[r], more.begin(), more.end(), std::back_inserter(ja));
    ia[r + 1] = (PetscInt)ja.size();
  }
  std::vector<PetscInt>().swap(rowcols);
  sets_.clear();
  FSI_CALL(MatSeqAIJSetPreallocationCSR(J, ia.data(), ja.data(), nullptr));
  FSI_CALL(MatMPIAIJSetPreallocationCSR(J, ia.data(), ja.data(), nullptr));
}

} // namespace fsi
