// fsi_app's calls into gmsh, built as a separate shared module (libfsi_gmsh.so, next to the
// executable) and loaded on first use.
//
// Why: libgmsh brings ~90 shared libraries (OpenCASCADE among them) whose loading and symbol
// binding cost every process ~0.17 s of CPU at start (measured: PetscInitialize alone 0.48 s
// wall, with libgmsh linked 0.65 s), while most runs read a cached mesh and never call gmsh (the
// option fuzz test's 147 starts: 128 -> 83 s).
//
// The module's functions report failures as a status and a message (no exceptions cross the
// module boundary); the callers turn them into fsi_app's own errors.
#pragma once
#include <array>
#include <string>
#include <vector>

namespace fsi::gmsh_module {

struct Status {
  int code = 0;        // 0: done; 1: refused, too many cells; 2: gmsh failed
  double cells = 0;    // code 1: the estimated cell count
  std::string message; // code 2: gmsh's last error
};

// Mesh a .geo (gmsh's command-line arguments in args, e.g. -setnumber h 0.001) into the file
// out, unless its bounding box holds more than max_cells regular tetrahedra of edge h.
Status mesh_geo(const std::vector<std::string> &args, const std::string &geo, double h,
                double max_cells, const std::string &out);

// The volume inside closed discrete surfaces (each a list of triangles of the points x, which
// gets the new interior points), sizes from the boundary, grading away from gap points
// (x, y, z, size), at most hmax where hmax > 0; the tetrahedra as indices into x.
Status mesh_volume(std::vector<std::array<double, 3>> &x,
                   const std::vector<std::vector<std::array<int, 3>>> &surfaces,
                   const std::vector<std::array<double, 4>> &gaps, double hmax, bool verbose,
                   std::vector<std::array<int, 4>> &tets);

} // namespace fsi::gmsh_module
