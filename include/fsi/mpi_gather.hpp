// Gathering a vector from every rank onto every rank (MPI_Allgatherv with its counts): the
// contact surface and the rigid contact walls hold their whole surface on each rank.
#pragma once
#include <mpi.h>
#include <vector>

namespace fsi {

// Each rank's count n, in rank order.
inline std::vector<int> counts_of(MPI_Comm comm, int n) {
  int size;
  MPI_Comm_size(comm, &size);
  std::vector<int> c(size);
  MPI_Allgather(&n, 1, MPI_INT, c.data(), 1, MPI_INT, comm);
  return c;
}

// Offsets of the ranks' blocks from their counts.
inline std::vector<int> displacements(const std::vector<int> &counts) {
  std::vector<int> d(counts.size(), 0);
  for (size_t r = 1; r < counts.size(); ++r)
    d[r] = d[r - 1] + counts[r - 1];
  return d;
}

// Every rank's `mine`, concatenated in rank order, on every rank.
template <class T>
std::vector<T> all_gather(MPI_Comm comm, const std::vector<T> &mine, MPI_Datatype type) {
  const auto counts = counts_of(comm, (int)mine.size());
  const auto displs = displacements(counts);
  std::vector<T> all(displs.back() + counts.back());
  MPI_Allgatherv(mine.data(), (int)mine.size(), type, all.data(), counts.data(), displs.data(),
                 type, comm);
  return all;
}

} // namespace fsi
