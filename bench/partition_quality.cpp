// Partition quality without running (issue 18): the cells of a gmsh mesh split into N parts by
// PT-Scotch and by METIS, as -mesh_partitioner would for N ranks: edge cut (faces between
// parts), load imbalance (largest part / mean) and the partitioner's seconds.  One process.
//   build/fsi_partition_quality MESH.msh [N ...]        (default N: 2 8 32)
#include "fsi/mesh/partition.hpp"
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

int main(int argc, char **argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s MESH.msh [PARTS ...]\n", argv[0]);
    return 2;
  }
  if (FILE *f = std::fopen(argv[1], "r"))
    std::fclose(f);
  else {
    std::fprintf(stderr,
                 "fsi_partition_quality: error: cannot read mesh %s: give a gmsh .msh file\n",
                 argv[1]);
    return 2;
  }
  int pargc = 1;
  PetscInitialize(&pargc, &argv, nullptr, nullptr);
  int rc = 0;
  try {
    DM dm;
    FSI_CALL(DMPlexCreateFromFile(PETSC_COMM_SELF, argv[1], "mesh", PETSC_TRUE, &dm));
    const fsi::CellGraph g = fsi::cell_graph(dm);
    std::vector<int> counts;
    for (int i = 2; i < argc; ++i)
      counts.push_back(std::atoi(argv[i]));
    if (counts.empty()) counts = {2, 8, 32};
    std::printf("%s: %ld cells, graph edges (interior faces) counted per partition\n", argv[1],
                g.n());
    std::printf("%-9s %5s %9s %8s %10s %8s\n", "method", "parts", "edge cut", "cut %", "imbalance",
                "seconds");
    for (int parts : counts)
      for (const char *m : {"ptscotch", "metis"}) {
        const double t0 = MPI_Wtime();
        const auto part = fsi::partition_graph(g, parts, m);
        const double t = MPI_Wtime() - t0;
        const auto q = fsi::partition_quality(g, part, parts, m);
        std::printf("%-9s %5d %9ld %8.3f %10.4f %8.3f\n", m, parts, q.edge_cut,
                    100.0 * q.edge_cut / q.faces, q.imbalance, t);
      }
    FSI_CALL(DMDestroy(&dm));
  } catch (std::exception &e) {
    std::fprintf(stderr, "fsi_partition_quality: error: %s\n", e.what());
    rc = 2;
  }
  PetscFinalize();
  return rc;
}
