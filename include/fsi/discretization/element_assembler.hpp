// Adds element matrices straight into the AIJ value arrays of the Jacobian at positions found
// once per matrix pattern (reset() when the pattern is rebuilt), instead of a MatSetValues search
// per entry, which was ~80 % of the Jacobian time.  Rows owned by another rank go through
// MatSetValues; Dirichlet rows are skipped.  Positions are stored as 16-bit offsets within the row.
#pragma once
#include "fsi/discretization/space.hpp"
#include <cstdint>
#include <vector>

namespace fsi {

class ElementAssembler {
public:
  // dofs: n local dof indices per element (n <= 64), elements in the order add() is called.
  void setup(Mat J, const Space &space, const std::vector<PetscInt> &dofs, int n,
             const std::vector<char> &is_dirichlet);
  bool ready() const { return n_ > 0; }
  void reset() { n_ = 0; }                    // a new matrix: find the positions again
  void begin(Mat J);                          // get the value arrays
  void add(Mat J, size_t e, const double *K); // K: n x n row-major, element dof order
  void end(Mat J);                            // restore the arrays (then assemble J as usual)

private:
  static constexpr uint16_t SKIP = 0xFFFF, REMOTE = 0xFFFE;
  int n_ = 0;
  const Space *space_ = nullptr;
  const std::vector<PetscInt> *dofs_ = nullptr;
  Mat A_ = nullptr, B_ = nullptr;   // diagonal and off-diagonal blocks
  std::vector<PetscInt> iaA_, iaB_; // row starts (owned rows)
  std::vector<uint16_t> pos_;       // n*n per element; or SKIP / REMOTE per row
  PetscScalar *va_ = nullptr, *vb_ = nullptr;
};

} // namespace fsi
