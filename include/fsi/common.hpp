// Shared helpers: PETSc error checking that throws, and the input-error exception that main()
// turns into one clear line and a non-zero exit.
#pragma once
#include <functional>
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

// A mesh just remeshed that its first step would already distort: the step is retried smaller
// (the surfaces move fast there; a new mesh cannot help within one step).
struct FreshMeshDistortion : DistortionError {
  using DistortionError::DistortionError;
};

// The predicted (or iterated) fluid mesh calls for remeshing: the step is retried on a new mesh.
struct RemeshNeeded : DistortionError {
  using DistortionError::DistortionError;
};

// A converged step whose local error estimate is above tolerance: retried with a smaller dt.
struct StepRejected : std::runtime_error {
  double error;
  explicit StepRejected(double e)
      : std::runtime_error("error estimate above tolerance"), error(e) {}
};

struct PetscFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An output that could not be written (disk full, directory made read-only, file-size limit):
// one line naming the file, exit code 5; the last checkpoint written before it is intact.
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Every rank throws the OutputError that any rank hit in `write` (the lowest failing rank's
// message), so that no rank is left waiting in a collective call of the next step.
void collective_output(MPI_Comm comm, const std::function<void()> &write);

[[noreturn]] void throw_petsc(PetscErrorCode ierr, const char *file, int line);

// This process's peak resident memory so far [MB].
double peak_memory_mb();
void release_free_heap(); // return freed heap pages to the system (after large temporaries)

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
