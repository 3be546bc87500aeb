#include "fsi/post/locate.hpp"
#include "fsi/discretization/p2tet.hpp"
#include "fsi/scene/options.hpp"
#include <cmath>

#include <sstream>

namespace fsi {

PointLocation locate_point(const Space &space, const std::vector<PetscInt> &cells,
                           const double x[3], const double *Xv) {
  if (!Xv) Xv = space.X.data();
  MPI_Comm comm = PetscObjectComm((PetscObject)space.dm);
  int rank;
  MPI_Comm_rank(comm, &rank);
  double best = -1e300, bl[4] = {};
  PetscInt best_cell = -1;
  for (PetscInt cell : cells) {
    double X[4][3];
    space.cell_points(cell, Xv, X);
    TetGeometry g;
    g.set(X);
    double l[4], s = 0;
    for (int i = 1; i < 4; ++i) {
      l[i] = 0;
      for (int d = 0; d < 3; ++d)
        l[i] += g.grad_lambda[i][d] * (x[d] - X[0][d]);
      s += l[i];
    }
    l[0] = 1 - s;
    const double mn = std::min(std::min(l[0], l[1]), std::min(l[2], l[3]));
    if (mn > best) {
      best = mn;
      best_cell = cell;
      for (int i = 0; i < 4; ++i)
        bl[i] = l[i];
    }
  }
  int mine = best > -1e-8 ? rank : 1 << 30, owner;
  MPI_Allreduce(&mine, &owner, 1, MPI_INT, MPI_MIN, comm);
  PointLocation p;
  if (owner == 1 << 30) return p;
  p.owner = owner;
  if (owner == rank) {
    p.cell = best_cell;
    for (int i = 0; i < 4; ++i)
      p.lambda[i] = bl[i];
  }
  return p;
}

std::vector<std::array<double, 3>> parse_points(const std::string &name) {
  std::vector<std::array<double, 3>> pts;
  std::stringstream ss(opt::string(name, ""));
  std::string item;
  while (std::getline(ss, item, ';')) {
    if (item.empty()) continue;
    std::stringstream is(item);
    std::string c;
    std::array<double, 3> p{};
    int k = 0;
    while (std::getline(is, c, ',')) {
      char *end = nullptr;
      const double v = std::strtod(c.c_str(), &end);
      if (k >= 3 || end == c.c_str() || *end || !std::isfinite(v))
        throw InputError("-" + name + " expects x,y,z;x,y,z;... [m], got '" + item + "'");
      p[k++] = v;
    }
    if (k != 3) throw InputError("-" + name + " expects x,y,z;x,y,z;... [m], got '" + item + "'");
    pts.push_back(p);
  }
  return pts;
}

} // namespace fsi
