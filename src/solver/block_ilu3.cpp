#include "fsi/solver/block_ilu3.hpp"
#include "fsi/common.hpp"

#include <algorithm>
#include <cmath>
#include <immintrin.h>

namespace fsi {
namespace {

// The on-rank matrix's rows, read in place (restored on every return).
struct Rows {
  Mat A;
  PetscInt n = 0;
  const PetscInt *ia = nullptr, *ja = nullptr;
  explicit Rows(Mat a) : A(a) {
    PetscBool done;
    FSI_CALL(MatGetRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
    if (!done) throw PetscFailure("internal: the velocity block's rows are not readable");
  }
  ~Rows() {
    PetscBool done;
    PetscInt m = n;
    MatRestoreRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &m, &ia, &ja, &done);
  }
};

// y -= a * b for row-major 3x3 blocks.
inline void sub_mul(double *y, const double *a, const double *b) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      y[3 * i + j] -= a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
}

// Inverse of a 3x3 block by its cofactors; false when it is singular to working precision.
bool invert3(const double *a, double *inv) {
  const double c00 = a[4] * a[8] - a[5] * a[7], c01 = a[5] * a[6] - a[3] * a[8],
               c02 = a[3] * a[7] - a[4] * a[6];
  const double det = a[0] * c00 + a[1] * c01 + a[2] * c02;
  double scale = 0;
  for (int k = 0; k < 9; ++k)
    scale = std::max(scale, std::fabs(a[k]));
  if (!(std::fabs(det) > 1e-14 * scale * scale * scale)) return false;
  const double d = 1.0 / det;
  inv[0] = c00 * d, inv[3] = c01 * d, inv[6] = c02 * d;
  inv[1] = (a[2] * a[7] - a[1] * a[8]) * d;
  inv[4] = (a[0] * a[8] - a[2] * a[6]) * d;
  inv[7] = (a[1] * a[6] - a[0] * a[7]) * d;
  inv[2] = (a[1] * a[5] - a[2] * a[4]) * d;
  inv[5] = (a[2] * a[3] - a[0] * a[5]) * d;
  inv[8] = (a[0] * a[4] - a[1] * a[3]) * d;
  return true;
}

// Block q of the factor as row-major doubles, and back.  Single precision stores each block by
// columns (9 floats), the layout the vectorised solve loads; double precision 9 row-major doubles.
inline void get_block(const std::vector<float> &v, size_t q, double *m) {
  const float *c = &v[9 * q];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      m[3 * i + j] = c[3 * j + i];
}
inline void get_block(const std::vector<double> &v, size_t q, double *m) {
  std::copy(&v[9 * q], &v[9 * q] + 9, m);
}
inline void put_block(std::vector<float> &v, size_t q, const double *m) {
  float *c = &v[9 * q];
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      c[3 * j + i] = (float)m[3 * i + j];
}
inline void put_block(std::vector<double> &v, size_t q, const double *m) {
  std::copy(m, m + 9, &v[9 * q]);
}

// The two triangular sweeps on single-precision blocks with AVX2 + FMA: a block's three columns
// (each loaded as 4 floats, the 4th lane the next column's first entry and never stored) widened
// to doubles and multiplied by the three broadcast entries of x, into three accumulators (so
// that consecutive blocks do not wait on one another's additions).  The factor is read from
// memory once per sweep: prefetched ahead, backwards in the second sweep.
__attribute__((target("avx2,fma"))) void solve_avx2(PetscInt nb, const int *bi, const int *bj,
                                                    const int *dg, const float *v, const double *b,
                                                    double *x) {
  alignas(32) double t[4];
  for (PetscInt I = 0; I < nb; ++I) { // L y = b, L unit lower
    __m256d a0 = _mm256_set_pd(0.0, b[3 * I + 2], b[3 * I + 1], b[3 * I]);
    __m256d a1 = _mm256_setzero_pd(), a2 = _mm256_setzero_pd();
    for (int p = bi[I]; p < dg[I]; ++p) {
      const float *l = v + 9 * (size_t)p;
      _mm_prefetch((const char *)(l + 9 * 32), _MM_HINT_T0);
      const double *y = x + 3 * (size_t)bj[p];
      a0 = _mm256_fnmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(l)), _mm256_broadcast_sd(y), a0);
      a1 = _mm256_fnmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(l + 3)), _mm256_broadcast_sd(y + 1), a1);
      a2 = _mm256_fnmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(l + 6)), _mm256_broadcast_sd(y + 2), a2);
    }
    _mm256_store_pd(t, _mm256_add_pd(a0, _mm256_add_pd(a1, a2)));
    x[3 * I] = t[0], x[3 * I + 1] = t[1], x[3 * I + 2] = t[2];
  }
  for (PetscInt I = nb - 1; I >= 0; --I) { // U x = y, pivots stored inverted
    if (I >= 2) // this sweep walks the factor backwards: fetch the row after next ahead
      for (const char *c = (const char *)(v + 9 * (size_t)dg[I - 2]),
                      *e = (const char *)(v + 9 * (size_t)bi[I - 1]);
           c < e; c += 64)
        _mm_prefetch(c, _MM_HINT_T0);
    __m256d a0 = _mm256_set_pd(0.0, x[3 * I + 2], x[3 * I + 1], x[3 * I]);
    __m256d a1 = _mm256_setzero_pd(), a2 = _mm256_setzero_pd();
    for (int p = dg[I] + 1; p < bi[I + 1]; ++p) {
      const float *u = v + 9 * (size_t)p;
      const double *y = x + 3 * (size_t)bj[p];
      a0 = _mm256_fnmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(u)), _mm256_broadcast_sd(y), a0);
      a1 = _mm256_fnmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(u + 3)), _mm256_broadcast_sd(y + 1), a1);
      a2 = _mm256_fnmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(u + 6)), _mm256_broadcast_sd(y + 2), a2);
    }
    _mm256_store_pd(t, _mm256_add_pd(a0, _mm256_add_pd(a1, a2)));
    const float *d = v + 9 * (size_t)dg[I];
    __m256d r = _mm256_mul_pd(_mm256_cvtps_pd(_mm_loadu_ps(d)), _mm256_set1_pd(t[0]));
    r = _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(d + 3)), _mm256_set1_pd(t[1]), r);
    r = _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(d + 6)), _mm256_set1_pd(t[2]), r);
    _mm256_store_pd(t, r);
    x[3 * I] = t[0], x[3 * I + 1] = t[1], x[3 * I + 2] = t[2];
  }
}

bool has_avx2() {
  static const bool yes = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return yes;
}

} // namespace

void BlockIlu3::analyse(Mat A, const std::vector<PetscInt> &rows,
                        const std::vector<PetscInt> &cols) {
  if (rows.size() % 3) throw PetscFailure("internal: block ILU needs 3 velocity dofs per node");
  rows_ = rows;
  cols_ = cols;
  nb_ = (PetscInt)rows.size() / 3;
  Rows m(A);
  where_.assign(nb_, -1);
  bi_.assign(nb_ + 1, 0);
  diag_.assign(nb_, 0);
  bj_.clear();
  std::vector<int> list;
  for (PetscInt I = 0; I < nb_; ++I) {
    list.assign(1, (int)I); // the diagonal block, present even if the pattern lacks it
    where_[I] = 0;
    for (int i = 0; i < 3; ++i) {
      const PetscInt r = rows_[3 * I + i];
      for (PetscInt k = m.ia[r]; k < m.ia[r + 1]; ++k) {
        const PetscInt v = cols_[m.ja[k]];
        if (v < 0 || where_[v / 3] >= 0) continue;
        where_[v / 3] = 0;
        list.push_back((int)(v / 3));
      }
    }
    std::sort(list.begin(), list.end());
    for (int b : list)
      where_[b] = -1;
    diag_[I] =
        (int)bj_.size() + (int)(std::lower_bound(list.begin(), list.end(), (int)I) - list.begin());
    bj_.insert(bj_.end(), list.begin(), list.end());
    bi_[I + 1] = (int)bj_.size();
  }
  std::vector<float>().swap(vf_); // the old pattern's factor freed before the new one
  std::vector<double>().swap(vd_);
  if (single_) // + 1: the last block's third column is loaded as 4 floats
    vf_.assign(9 * bj_.size() + 1, 0.0f);
  else
    vd_.assign(9 * bj_.size(), 0.0);
}

size_t BlockIlu3::bytes() const {
  return (vf_.size() * sizeof(float) + vd_.size() * sizeof(double)) +
         (bj_.size() + bi_.size() + diag_.size()) * sizeof(int);
}

bool BlockIlu3::factor(Mat A, std::vector<double> *diag) {
  if (diag) diag->assign(rows_.size(), 0.0);
  Rows m(A);
  const PetscScalar *a;
  FSI_CALL(MatSeqAIJGetArrayRead(A, &a));
  ia_ = m.ia, ja_ = m.ja, a_ = a;
  const bool ok = single_ ? factor_rows(vf_, diag) : factor_rows(vd_, diag);
  ia_ = ja_ = nullptr, a_ = nullptr;
  FSI_CALL(MatSeqAIJRestoreArrayRead(A, &a));
  return ok;
}

// Block row I of A into the double work row w (its blocks in the order of bj_), and the
// velocity diagonal into diag.
void BlockIlu3::fill(double *w, std::vector<double> *diag, PetscInt I) const {
  for (int i = 0; i < 3; ++i) {
    const PetscInt r = rows_[3 * I + i];
    for (PetscInt k = ia_[r]; k < ia_[r + 1]; ++k) {
      const PetscInt v = cols_[ja_[k]];
      if (v < 0) continue;
      w[9 * where_[v / 3] + 3 * i + v % 3] += PetscRealPart(a_[k]);
      if (diag && v == 3 * I + i) (*diag)[v] = PetscRealPart(a_[k]);
    }
  }
}

// ILU(0) by rows (IKJ): row I's blocks left of the diagonal are multiplied by the inverse pivots
// of the rows above and eliminate into row I's own pattern only; pivots are stored inverted.
template <class T> bool BlockIlu3::factor_rows(std::vector<T> &v, std::vector<double> *diag) {
  int maxlen = 0;
  for (PetscInt I = 0; I < nb_; ++I)
    maxlen = std::max(maxlen, bi_[I + 1] - bi_[I]);
  std::vector<double> w(9 * (size_t)maxlen);
  for (PetscInt I = 0; I < nb_; ++I) {
    const int b0 = bi_[I], len = bi_[I + 1] - b0;
    for (int p = 0; p < len; ++p)
      where_[bj_[b0 + p]] = p;
    std::fill(w.begin(), w.begin() + 9 * len, 0.0);
    fill(w.data(), diag, I);
    for (int p = 0; b0 + p < diag_[I]; ++p) {
      const int K = bj_[b0 + p];
      double m[9], L[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
      get_block(v, diag_[K], m);
      sub_mul(L, &w[9 * p], m); // L = -w_p D_K^-1
      for (int k = 0; k < 9; ++k)
        w[9 * p + k] = -L[k];
      for (int q = diag_[K] + 1; q < bi_[K + 1]; ++q) {
        const int t = where_[bj_[q]];
        if (t < 0) continue;
        get_block(v, q, m);
        sub_mul(&w[9 * t], &w[9 * p], m);
      }
    }
    double inv[9];
    const int d = diag_[I] - b0;
    if (!invert3(&w[9 * d], inv)) {
      for (int p = 0; p < len; ++p)
        where_[bj_[b0 + p]] = -1;
      return false;
    }
    std::copy(inv, inv + 9, &w[9 * d]);
    for (int p = 0; p < len; ++p)
      put_block(v, b0 + p, &w[9 * p]);
    for (int p = 0; p < len; ++p)
      where_[bj_[b0 + p]] = -1;
  }
  return true;
}

// The sweeps without AVX2 (and in double precision): the same arithmetic, block by block.
template <class T>
void BlockIlu3::solve_rows(const std::vector<T> &v, const double *b, double *x) const {
  double m[9];
  for (PetscInt I = 0; I < nb_; ++I) { // L y = b, L unit lower
    double s[3] = {b[3 * I], b[3 * I + 1], b[3 * I + 2]};
    for (int p = bi_[I]; p < diag_[I]; ++p) {
      get_block(v, p, m);
      const double *y = &x[3 * bj_[p]];
      for (int i = 0; i < 3; ++i)
        s[i] -= m[3 * i] * y[0] + m[3 * i + 1] * y[1] + m[3 * i + 2] * y[2];
    }
    x[3 * I] = s[0], x[3 * I + 1] = s[1], x[3 * I + 2] = s[2];
  }
  for (PetscInt I = nb_ - 1; I >= 0; --I) { // U x = y, pivots stored inverted
    double s[3] = {x[3 * I], x[3 * I + 1], x[3 * I + 2]};
    for (int p = diag_[I] + 1; p < bi_[I + 1]; ++p) {
      get_block(v, p, m);
      const double *y = &x[3 * bj_[p]];
      for (int i = 0; i < 3; ++i)
        s[i] -= m[3 * i] * y[0] + m[3 * i + 1] * y[1] + m[3 * i + 2] * y[2];
    }
    get_block(v, diag_[I], m);
    for (int i = 0; i < 3; ++i)
      x[3 * I + i] = m[3 * i] * s[0] + m[3 * i + 1] * s[1] + m[3 * i + 2] * s[2];
  }
}

void BlockIlu3::solve(const double *b, double *x) const {
  if (single_ && has_avx2())
    solve_avx2(nb_, bi_.data(), bj_.data(), diag_.data(), vf_.data(), b, x);
  else if (single_)
    solve_rows(vf_, b, x);
  else
    solve_rows(vd_, b, x);
}

} // namespace fsi
