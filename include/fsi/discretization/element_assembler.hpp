// Adds element matrices straight into the AIJ value arrays of the Jacobian at positions found
// once per matrix pattern (reset() when the pattern is rebuilt), instead of a MatSetValues search
// per entry, which was ~80 % of the Jacobian time.  Rows owned by another rank go through
// MatSetValues; Dirichlet rows are skipped.  Positions are stored as 16-bit offsets within the row.
#pragma once
#include "fsi/discretization/space.hpp"
#include <cstdint>
#include <vector>

namespace fsi {

// An order of the elements (dofs: n per element) by their smallest dof, so that consecutive
// elements add into nearby matrix rows (measured: the scatter into the matrix is cache-bound).
std::vector<size_t> locality_order(const std::vector<PetscInt> &dofs, int n);

class ElementAssembler {
public:
  // dofs: n local dof indices per element (n <= 64), elements indexed as add() will index them;
  // groups: the sizes of the runs of element dofs that are one node's components (e.g. 10 x 3
  // velocity, then 4 x 1 pressure): their global indices are consecutive and their rows share a
  // pattern, so one position per (row node, column node) pair serves all components (6-9x
  // fewer positions to store and read).  Checked at setup; if a run breaks either property the
  // assembler falls back to one position per entry.
  void setup(Mat J, const Space &space, const std::vector<PetscInt> &dofs, int n,
             const std::vector<char> &is_dirichlet, const std::vector<int> &groups);
  bool ready() const { return n_ > 0; }
  void reset() { n_ = 0; }                    // a new matrix: find the positions again
  void begin(Mat J);                          // get the value arrays
  void add(Mat J, size_t e, const double *K); // K: n x n row-major, element dof order
  void end(Mat J);                            // restore the arrays (then assemble J as usual)
  bool blocked() const { return (int)gsize_.size() < n_; }

private:
  static constexpr uint8_t LOCAL = 0, SKIP = 1, REMOTE = 2;
  bool find_positions(Mat J, const std::vector<char> &is_dirichlet); // false: a group broke
  int n_ = 0;
  const Space *space_ = nullptr;
  const std::vector<PetscInt> *dofs_ = nullptr;
  Mat A_ = nullptr, B_ = nullptr;   // diagonal and off-diagonal blocks
  std::vector<PetscInt> iaA_, iaB_; // row starts (owned rows)
  std::vector<int> gstart_, gsize_; // element dof groups
  std::vector<uint16_t> pos_;       // G*G per element: first column's offset within the row
  std::vector<uint8_t> row_;        // n per element: LOCAL, SKIP (Dirichlet) or REMOTE
  PetscScalar *va_ = nullptr, *vb_ = nullptr;
};

} // namespace fsi
