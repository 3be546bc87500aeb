// Shared helpers: PETSc error checking that throws, and the input-error exception that main()
// turns into one clear line and a non-zero exit.
#pragma once
#include <petsc.h>
#include <stdexcept>
#include <string>

namespace fsi {

// A user mistake (bad option, missing file, ...): reported as one line, exit code 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A numerical failure (diverged Newton, inverted cell): exit code 3.
struct SolveError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A fluid mesh too distorted to continue: a smaller step does not help (remeshing would).
struct DistortionError : SolveError {
  using SolveError::SolveError;
};

// The predicted (or iterated) fluid mesh calls for remeshing: the step is retried on a new mesh.
struct RemeshNeeded : DistortionError {
  using DistortionError::DistortionError;
};

struct PetscFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] void throw_petsc(PetscErrorCode ierr, const char *file, int line);

// This process's peak resident memory so far [MB].
double peak_memory_mb();

// Sum of n over the lower ranks of comm: where this rank's entries start in a distributed
// numbering (0 on rank 0).
inline PetscInt rank_offset(MPI_Comm comm, PetscInt n) {
  PetscInt start = 0;
  MPI_Exscan(&n, &start, 1, MPIU_INT, MPI_SUM, comm);
  int rank;
  MPI_Comm_rank(comm, &rank);
  return rank == 0 ? 0 : start;
}

} // namespace fsi

// Call a PETSc function from C++ code that does not return PetscErrorCode.
#define FSI_CALL(expr)                                                                             \
  do {                                                                                             \
    PetscErrorCode fsi_ierr_ = (expr);                                                             \
    if (fsi_ierr_) ::fsi::throw_petsc(fsi_ierr_, __FILE__, __LINE__);                              \
  } while (0)
