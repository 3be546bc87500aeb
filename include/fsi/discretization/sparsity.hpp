// The nonzero pattern of a matrix assembled from element dof lists, counted directly as CSR
// from each row's element incidence: every dof of an element couples with every other.  It
// replaces PETSc's MATPREALLOCATOR, whose hash tables of the pattern held ~170 MB per rank on
// the paper-size tube at setup and whose n x n insertions per element were 12 % of a valve
// remesh (every remesh and every new contact pattern builds one).
//
// Rows whose dof another rank owns (elements on a partition boundary) are sent to that rank.
// The matrix gets exactly this pattern plus its diagonal, zero-filled and assembled.
#pragma once
#include <petscmat.h>
#include <vector>

namespace fsi {

class SparsityPattern {
public:
  // Rows and columns: the local dofs 0..n_local-1 with global indices local_to_global (kept by
  // reference); this rank owns the global rows [rstart, rstart + n_owned).
  SparsityPattern(MPI_Comm comm, const std::vector<PetscInt> &local_to_global, PetscInt rstart,
                  PetscInt n_owned);
  // n local dofs per element (negative entries skipped); the list is kept by reference until
  // preallocate().
  void add_elements(const std::vector<PetscInt> &dofs, int n);
  // Global row `row` couples with the global columns cols[0..n) (only rows this rank owns).
  void add_row(PetscInt row, const PetscInt *cols, int n);
  // Preallocates J (AIJ, sizes set, no pattern yet) with the pattern, values zero, assembled.
  void preallocate(Mat J);

private:
  struct ElementSet {
    const std::vector<PetscInt> *dofs;
    int n;
  };
  MPI_Comm comm_;
  const std::vector<PetscInt> &l2g_;
  PetscInt rstart_, n_owned_;
  std::vector<ElementSet> sets_;
  std::vector<PetscInt> extra_; // (owned row - rstart, global column) pairs
};

} // namespace fsi
