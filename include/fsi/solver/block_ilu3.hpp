// ILU(0) of a velocity block with 3x3 node blocks, taken straight from the rows of an on-rank
// SeqAIJ matrix (the Jacobian's diagonal block), with no copy of the block in between.
//
// Why: the velocity block's triangular solves stream the factor from memory once per Krylov
// iteration.  AIJ reads 12 bytes per nonzero (value + column index); 3x3 blocks read 8 + 4/9,
// and blocks stored in single precision 4 + 4/9: 2.7x less than AIJ.  ILU(0) is an
// approximation whose own error is far above float rounding; the factorisation itself runs in
// double (each row eliminated in a double work row) and only the stored factor is rounded.
// With a pattern made of whole node blocks (what the P2 assembler makes) it is the same
// preconditioner as PETSc's point ILU(0) on that pattern.
#pragma once
#include <petscmat.h>

#include <cstddef>
#include <vector>

namespace fsi {

class BlockIlu3 {
public:
  explicit BlockIlu3(bool single_precision = true) : single_(single_precision) {}

  // Block pattern: velocity dof v (0..nv-1, a node's 3 dofs consecutive) is row rows[v] of A;
  // column c of A is velocity dof cols[c], or -1 when it is not a velocity dof.
  void analyse(Mat A, const std::vector<PetscInt> &rows, const std::vector<PetscInt> &cols);
  // Numeric factorisation of A's current values on the analysed pattern; the velocity block's
  // diagonal into diag (nv entries) when not null.  False on a singular 3x3 pivot.
  bool factor(Mat A, std::vector<double> *diag);
  // x = (LU)^-1 b, nv entries each; x may be b.
  void solve(const double *b, double *x) const;

  PetscInt nodes() const { return nb_; }
  size_t blocks() const { return bj_.size(); }
  size_t bytes() const; // the factor's storage
  bool single_precision() const { return single_; }

private:
  template <class T> bool factor_rows(std::vector<T> &v, std::vector<double> *diag);
  template <class T> void solve_rows(const std::vector<T> &v, const double *b, double *x) const;
  void fill(double *w, std::vector<double> *diag, PetscInt I) const;

  bool single_;
  PetscInt nb_ = 0;
  std::vector<PetscInt> rows_, cols_; // as given to analyse
  std::vector<int> bi_, bj_, diag_;   // block CSR and each row's diagonal position
  std::vector<float> vf_;             // 9 values per block, row-major (single precision)
  std::vector<double> vd_;            // the same in double precision
  // analyse() and factor() scratch: a block row's position by block column (-1 when absent)
  std::vector<int> where_;
  const PetscInt *ia_ = nullptr, *ja_ = nullptr; // A's rows while factor() runs
  const PetscScalar *a_ = nullptr;
};

} // namespace fsi
