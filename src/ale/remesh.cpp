// Remeshing the fluid: see remesh.hpp.  Rank 0 does the work on the gathered mesh: the old
// mesh's vertices are identified by their reference coordinates (the keys of the state), so no
// global numbering of the distributed mesh is needed.
#include "fsi/ale/remesh.hpp"
#include "fsi/ale/mesh_motion.hpp"
#include "fsi/discretization/p2tet.hpp"
#include "fsi/discretization/space.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <gmsh.h>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <sys/resource.h>

namespace fsi {
namespace {

using Tri = std::array<int, 3>;
using Tet = std::array<int, 4>;

Tri sorted(int a, int b, int c) {
  Tri t{a, b, c};
  std::sort(t.begin(), t.end());
  return t;
}

// Physical groups of the mesh (user labels, not PETSc's own): name and dimension (3 or 2).
struct Groups {
  std::vector<std::string> names;
  std::vector<int> dim;
};

bool builtin_label(const std::string &n) {
  return n == "depth" || n == "celltype" || n == "Cell Sets" || n == "Face Sets" ||
         n == "Vertex Sets" || n == "Edge Sets" || n.rfind("__", 0) == 0;
}

Groups mesh_groups(const Mesh &mesh) {
  MPI_Comm comm = PetscObjectComm((PetscObject)mesh.dm);
  int rank;
  MPI_Comm_rank(comm, &rank);
  std::string all;
  PetscInt n;
  FSI_CALL(DMGetNumLabels(mesh.dm, &n));
  for (PetscInt i = 0; i < n; ++i) {
    const char *name;
    FSI_CALL(DMGetLabelName(mesh.dm, i, &name));
    if (!builtin_label(name)) all += std::string(name) + "\n";
  }
  int len = rank == 0 ? (int)all.size() : 0;
  MPI_Bcast(&len, 1, MPI_INT, 0, comm);
  all.resize(len);
  MPI_Bcast(all.data(), len, MPI_CHAR, 0, comm);
  Groups g;
  std::istringstream in(all);
  std::string name;
  PetscInt cStart, cEnd, fStart, fEnd;
  FSI_CALL(DMPlexGetHeightStratum(mesh.dm, 0, &cStart, &cEnd));
  FSI_CALL(DMPlexGetHeightStratum(mesh.dm, 1, &fStart, &fEnd));
  while (std::getline(in, name)) {
    long count[2] = {0, 0}, total[2];
    PetscBool has;
    FSI_CALL(DMHasLabel(mesh.dm, name.c_str(), &has));
    if (has) {
      DMLabel l;
      FSI_CALL(DMGetLabel(mesh.dm, name.c_str(), &l));
      IS is;
      FSI_CALL(DMLabelGetValueIS(l, &is));
      PetscInt nv;
      const PetscInt *vals;
      FSI_CALL(ISGetLocalSize(is, &nv));
      FSI_CALL(ISGetIndices(is, &vals));
      for (PetscInt j = 0; j < nv; ++j) {
        IS pts;
        FSI_CALL(DMLabelGetStratumIS(l, vals[j], &pts));
        if (!pts) continue;
        PetscInt np;
        const PetscInt *p;
        FSI_CALL(ISGetLocalSize(pts, &np));
        FSI_CALL(ISGetIndices(pts, &p));
        for (PetscInt k = 0; k < np; ++k) {
          count[0] += p[k] >= cStart && p[k] < cEnd;
          count[1] += p[k] >= fStart && p[k] < fEnd;
        }
        FSI_CALL(ISRestoreIndices(pts, &p));
        FSI_CALL(ISDestroy(&pts));
      }
      FSI_CALL(ISRestoreIndices(is, &vals));
      FSI_CALL(ISDestroy(&is));
    }
    MPI_Allreduce(count, total, 2, MPI_LONG, MPI_SUM, comm);
    if (total[0] > 0 || total[1] > 0) {
      g.names.push_back(name);
      g.dim.push_back(total[0] > 0 ? 3 : 2);
    }
  }
  if (g.names.size() > 50) throw InputError("remeshing supports at most 50 physical groups");
  return g;
}

bool in_label(DMLabel l, PetscInt p) {
  if (!l) return false;
  PetscInt v;
  FSI_CALL(DMLabelGetValue(l, p, &v));
  return v >= 0;
}

// The whole mesh on rank 0: cells (vertex reference coordinates, fluid flag and group mask) and
// the faces of surface groups (vertex coordinates, group mask).
struct Gathered {
  KeyedItems cells; // key: 12 coordinates; value: fluid (0/1), group mask
  KeyedItems faces; // key: 9 coordinates; value: group mask
};

Gathered gather_mesh(const Mesh &mesh, const Space &space, const std::vector<PetscInt> &fluid_cells,
                     const Groups &g) {
  MPI_Comm comm = PetscObjectComm((PetscObject)mesh.dm);
  std::vector<DMLabel> labels(g.names.size(), nullptr);
  for (size_t i = 0; i < g.names.size(); ++i) {
    PetscBool has;
    FSI_CALL(DMHasLabel(mesh.dm, g.names[i].c_str(), &has));
    if (has) FSI_CALL(DMGetLabel(mesh.dm, g.names[i].c_str(), &labels[i]));
  }
  std::vector<char> fluid(space.n_cells(), 0);
  for (PetscInt k : fluid_cells)
    fluid[k] = 1;
  std::vector<double> ck, cv;
  for (PetscInt k = 0; k < space.n_cells(); ++k) {
    double mask = 0;
    for (size_t i = 0; i < labels.size(); ++i)
      if (g.dim[i] == 3 && in_label(labels[i], space.cStart + k)) mask += std::ldexp(1.0, (int)i);
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d)
        ck.push_back(space.X[3 * space.cell_vertex[4 * k + a] + d]);
    cv.insert(cv.end(), {(double)fluid[k], mask});
  }
  std::vector<double> fk, fv;
  PetscInt fStart, fEnd;
  FSI_CALL(DMPlexGetHeightStratum(mesh.dm, 1, &fStart, &fEnd));
  for (PetscInt f = fStart; f < fEnd; ++f) {
    double mask = 0;
    for (size_t i = 0; i < labels.size(); ++i)
      if (g.dim[i] == 2 && in_label(labels[i], f)) mask += std::ldexp(1.0, (int)i);
    if (mask == 0) continue;
    PetscInt *clos = nullptr, nc;
    FSI_CALL(DMPlexGetTransitiveClosure(mesh.dm, f, PETSC_TRUE, &nc, &clos));
    int nvert = 0;
    for (PetscInt j = 0; j < nc; ++j) {
      const PetscInt p = clos[2 * j];
      if (p >= space.vStart && p < space.vEnd && nvert < 3) {
        for (int d = 0; d < 3; ++d)
          fk.push_back(space.X[3 * (p - space.vStart) + d]);
        ++nvert;
      }
    }
    FSI_CALL(DMPlexRestoreTransitiveClosure(mesh.dm, f, PETSC_TRUE, &nc, &clos));
    fv.push_back(mask);
  }
  Gathered out;
  out.cells = gather_sorted(comm, ck, cv, 12, 2);
  out.faces = gather_sorted(comm, fk, fv, 9, 1);
  return out;
}

// Finds points in the old fluid cells (current configuration) through a uniform grid of bins.
class Locator {
public:
  Locator(const std::vector<std::array<double, 3>> &x, const std::vector<Tet> &cells) : x_(x) {
    cells_ = cells;
    lo_ = {1e300, 1e300, 1e300};
    std::array<double, 3> hi{-1e300, -1e300, -1e300};
    for (auto &c : cells)
      for (int v : c)
        for (int d = 0; d < 3; ++d)
          lo_[d] = std::min(lo_[d], x[v][d]), hi[d] = std::max(hi[d], x[v][d]);
    const double n = std::max(1.0, std::cbrt((double)cells.size() / 2));
    double ext = 0;
    for (int d = 0; d < 3; ++d)
      ext = std::max(ext, hi[d] - lo_[d]);
    h_ = ext / n * 1.0001 + 1e-300;
    for (int d = 0; d < 3; ++d)
      n_[d] = std::max(1, (int)std::ceil((hi[d] - lo_[d]) / h_) + 1);
    bins_.assign((size_t)n_[0] * n_[1] * n_[2], {});
    for (size_t k = 0; k < cells.size(); ++k) {
      int b0[3], b1[3];
      for (int d = 0; d < 3; ++d) {
        double mn = 1e300, mx = -1e300;
        for (int v : cells[k])
          mn = std::min(mn, x[v][d]), mx = std::max(mx, x[v][d]);
        b0[d] = bin(mn, d), b1[d] = bin(mx, d);
      }
      for (int i = b0[0]; i <= b1[0]; ++i)
        for (int j = b0[1]; j <= b1[1]; ++j)
          for (int l = b0[2]; l <= b1[2]; ++l)
            bins_[index(i, j, l)].push_back((int)k);
    }
  }
  // The cell that contains p best (largest smallest barycentric coordinate) and p's barycentric
  // coordinates in it; searches rings of bins until a candidate is found.
  int find(const double p[3], double lambda[4]) const {
    int c[3];
    for (int d = 0; d < 3; ++d)
      c[d] = bin(p[d], d);
    int best = -1;
    double score = -1e300;
    for (int r = 0; r < std::max({n_[0], n_[1], n_[2]}); ++r) {
      for (int i = c[0] - r; i <= c[0] + r; ++i)
        for (int j = c[1] - r; j <= c[1] + r; ++j)
          for (int l = c[2] - r; l <= c[2] + r; ++l) {
            if (std::max({std::abs(i - c[0]), std::abs(j - c[1]), std::abs(l - c[2])}) != r)
              continue; // the shell of ring r only
            if (i < 0 || j < 0 || l < 0 || i >= n_[0] || j >= n_[1] || l >= n_[2]) continue;
            for (int k : bins_[index(i, j, l)]) {
              double lam[4];
              barycentric(k, p, lam);
              const double s = *std::min_element(lam, lam + 4);
              if (s > score) score = s, best = k, std::copy(lam, lam + 4, lambda);
            }
          }
      if (best >= 0 && (score > -1e-9 || r >= 1)) break; // inside, or the nearest ring done
    }
    return best;
  }
  void barycentric(int k, const double p[3], double lam[4]) const {
    double P[4][3];
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d)
        P[a][d] = x_[cells_[k][a]][d];
    TetGeometry g;
    g.set(P);
    for (int a = 0; a < 4; ++a) {
      lam[a] = a == 0 ? 1.0 : 0.0;
      for (int d = 0; d < 3; ++d)
        lam[a] += g.grad_lambda[a][d] * (p[d] - P[0][d]);
    }
  }

private:
  int bin(double v, int d) const {
    return std::min(n_[d] - 1, std::max(0, (int)std::floor((v - lo_[d]) / h_)));
  }
  size_t index(int i, int j, int l) const { return ((size_t)i * n_[1] + j) * n_[2] + l; }
  const std::vector<std::array<double, 3>> &x_;
  std::vector<Tet> cells_;
  std::array<double, 3> lo_;
  double h_;
  int n_[3];
  std::vector<std::vector<int>> bins_;
};

// P2 field values (V, A, D: 3 components each) and P1 pressure at the nodes of one mesh, for
// evaluation: nodal values of cell k (10 velocity nodes, 4 pressure vertices).
struct NodalFields {
  std::vector<std::array<double, 9>> vel; // per cell node: V, A, D (x, y, z each)
  std::vector<double> p;
};

// The dof values of a node with reference position X (3 comps x 3 histories), from the state.
bool node_values(const KeyedItems &dofs, const double X[3], double out[9]) {
  for (int c = 0; c < 3; ++c) {
    const double key[4] = {X[0], X[1], X[2], (double)c};
    const long i = find_key(dofs, key, 4);
    if (i < 0) return false;
    for (int h = 0; h < 3; ++h)
      out[3 * h + c] = dofs.values[3 * i + h];
  }
  return true;
}

// The pressure dof's three histories (its V is the pressure).
bool pressure_value(const KeyedItems &dofs, const double X[3], double out[3]) {
  const double key[4] = {X[0], X[1], X[2], 3.0};
  const long i = find_key(dofs, key, 4);
  if (i < 0) return false;
  std::copy_n(&dofs.values[3 * i], 3, out);
  return true;
}

// Integrals over fluid cells: volume, int |v|^2 / 2, ||div v||, ||grad v|| (velocity V).
struct Integrals {
  double volume = 0, kinetic = 0, div2 = 0, grad2 = 0;
};

void integrate(const double P[4][3], const double v[10][3], Integrals &s) {
  static const QuadRule rule = tet_rule(4);
  TetGeometry g;
  g.set(P);
  s.volume += g.absdet / 6;
  for (size_t q = 0; q < rule.weight.size(); ++q) {
    double N[10], dN[10][3];
    p2_tet(rule.lambda[q].data(), g.grad_lambda, N, dN);
    const double w = rule.weight[q] * g.absdet;
    double u[3] = {0, 0, 0}, G[3][3] = {};
    for (int a = 0; a < 10; ++a)
      for (int i = 0; i < 3; ++i) {
        u[i] += N[a] * v[a][i];
        for (int j = 0; j < 3; ++j)
          G[i][j] += v[a][i] * dN[a][j];
      }
    const double div = G[0][0] + G[1][1] + G[2][2];
    s.kinetic += 0.5 * w * (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    s.div2 += w * div * div;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        s.grad2 += w * G[i][j] * G[i][j];
  }
}

double peak_memory_mb() {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;
}

// The fluid boundary split into surfaces for gmsh: one per (group mask, connected piece), so
// that every closed shell of the boundary is its own surface (gmsh then tells holes apart).
std::vector<std::vector<int>> boundary_surfaces(const std::vector<Tri> &tris,
                                                const std::vector<double> &mask) {
  const size_t n = tris.size();
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> root = [&](int i) {
    return parent[i] == i ? i : parent[i] = root(parent[i]);
  };
  std::map<std::pair<int, int>, int> edge_owner;
  for (size_t t = 0; t < n; ++t)
    for (int e = 0; e < 3; ++e) {
      int a = tris[t][e], b = tris[t][(e + 1) % 3];
      if (a > b) std::swap(a, b);
      auto it = edge_owner.find({a, b});
      if (it == edge_owner.end())
        edge_owner[{a, b}] = (int)t;
      else if (mask[it->second] == mask[t])
        parent[root((int)t)] = root(it->second);
    }
  std::map<int, std::vector<int>> pieces;
  for (size_t t = 0; t < n; ++t)
    pieces[root((int)t)].push_back((int)t);
  std::vector<std::vector<int>> out;
  for (auto &[r, list] : pieces)
    out.push_back(list);
  return out;
}

// Closest distance from p to triangle (a, b, c) and the closest point q.
double point_triangle(const double *p, const double *a, const double *b, const double *c,
                      double q[3]) {
  double ab[3], ac[3], ap[3];
  for (int d = 0; d < 3; ++d)
    ab[d] = b[d] - a[d], ac[d] = c[d] - a[d], ap[d] = p[d] - a[d];
  auto dot = [](const double *u, const double *v) {
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  };
  // Barycentric coordinates of the projection, clamped to the triangle by a small search over
  // its regions (Ericson, Real-Time Collision Detection, 5.1.5).
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  double u = 0, v = 0;
  double bp[3], cp[3];
  for (int d = 0; d < 3; ++d)
    bp[d] = p[d] - b[d], cp[d] = p[d] - c[d];
  const double d3 = dot(ab, bp), d4 = dot(ac, bp), d5 = dot(ab, cp), d6 = dot(ac, cp);
  const double va = d3 * d6 - d5 * d4, vb = d5 * d2 - d1 * d6, vc = d1 * d4 - d3 * d2;
  if (d1 <= 0 && d2 <= 0) {
    u = v = 0;
  } else if (d3 >= 0 && d4 <= d3) {
    u = 1, v = 0;
  } else if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    u = d1 / (d1 - d3), v = 0;
  } else if (d6 >= 0 && d5 <= d6) {
    u = 0, v = 1;
  } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    u = 0, v = d2 / (d2 - d6);
  } else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    u = 1 - w, v = w;
  } else {
    const double den = 1 / (va + vb + vc);
    u = vb * den, v = vc * den;
  }
  double r = 0;
  for (int d = 0; d < 3; ++d) {
    q[d] = a[d] + u * ab[d] + v * ac[d];
    r += (p[d] - q[d]) * (p[d] - q[d]);
  }
  return std::sqrt(r);
}

// Where the fluid boundary comes close to itself across the fluid (a thin gap between two
// leaflets, or a leaflet and the wall), closer than its own triangles are large, a mesh with
// only boundary vertices there would span the gap with one layer of slivers; there the size is
// set to the gap over -ale_remesh_gap_cells, so that gmsh puts nodes inside the gap.  Returns
// the gap vertices (position, size).
std::vector<std::array<double, 4>> gap_sizes(const std::vector<std::array<double, 3>> &x,
                                             const std::vector<Tri> &tris,
                                             const std::vector<std::array<double, 3>> &inward,
                                             double cells_across) {
  const size_t nt = tris.size();
  std::map<int, std::set<int>> nbr;
  std::map<int, std::vector<int>> vtris;
  for (size_t t = 0; t < nt; ++t)
    for (int e = 0; e < 3; ++e) {
      nbr[tris[t][e]].insert(tris[t][(e + 1) % 3]);
      nbr[tris[t][e]].insert(tris[t][(e + 2) % 3]);
      vtris[tris[t][e]].push_back((int)t);
    }
  // Triangles in bins (size: the largest edge), for the search within one edge length.
  double hmax = 0;
  std::array<double, 3> lo{1e300, 1e300, 1e300};
  for (auto &[v, ns] : nbr)
    for (int w : ns) {
      double l = 0;
      for (int d = 0; d < 3; ++d)
        l += (x[v][d] - x[w][d]) * (x[v][d] - x[w][d]), lo[d] = std::min(lo[d], x[v][d]);
      hmax = std::max(hmax, std::sqrt(l));
    }
  auto key = [&](const double *p, int d) { return (long)std::floor((p[d] - lo[d]) / hmax); };
  std::map<std::array<long, 3>, std::vector<int>> bins;
  for (size_t t = 0; t < nt; ++t) {
    long b0[3], b1[3];
    for (int d = 0; d < 3; ++d) {
      b0[d] = b1[d] = key(x[tris[t][0]].data(), d);
      for (int a = 1; a < 3; ++a)
        b0[d] = std::min(b0[d], key(x[tris[t][a]].data(), d)),
        b1[d] = std::max(b1[d], key(x[tris[t][a]].data(), d));
    }
    for (long i = b0[0]; i <= b1[0]; ++i)
      for (long j = b0[1]; j <= b1[1]; ++j)
        for (long k = b0[2]; k <= b1[2]; ++k)
          bins[{i, j, k}].push_back((int)t);
  }
  std::vector<std::array<double, 4>> gaps;
  for (auto &[v, ns] : nbr) {
    double h = 0, n[3] = {0, 0, 0};
    for (int w : ns) {
      double l = 0;
      for (int d = 0; d < 3; ++d)
        l += (x[v][d] - x[w][d]) * (x[v][d] - x[w][d]);
      h += std::sqrt(l) / ns.size();
    }
    for (int t : vtris[v])
      for (int d = 0; d < 3; ++d)
        n[d] += inward[t][d];
    std::set<int> ring = ns; // two rings of neighbours: not across a gap
    for (int w : ns)
      ring.insert(nbr[w].begin(), nbr[w].end());
    ring.insert(v);
    double gap = 1e300;
    const double *p = x[v].data();
    long c[3];
    for (int d = 0; d < 3; ++d)
      c[d] = key(p, d);
    std::set<int> seen;
    for (long i = c[0] - 1; i <= c[0] + 1; ++i)
      for (long j = c[1] - 1; j <= c[1] + 1; ++j)
        for (long k = c[2] - 1; k <= c[2] + 1; ++k) {
          auto it = bins.find({i, j, k});
          if (it == bins.end()) continue;
          for (int t : it->second) {
            if (!seen.insert(t).second) continue;
            if (ring.count(tris[t][0]) || ring.count(tris[t][1]) || ring.count(tris[t][2]))
              continue;
            double q[3];
            const double r = point_triangle(p, x[tris[t][0]].data(), x[tris[t][1]].data(),
                                            x[tris[t][2]].data(), q);
            if (r >= gap || r <= 0) continue;
            // Across the fluid: q lies on v's fluid side and t faces v.
            double a = 0, b = 0;
            for (int d = 0; d < 3; ++d)
              a += (q[d] - p[d]) * n[d], b += (p[d] - q[d]) * inward[t][d];
            if (a > 0 && b > 0) gap = r;
          }
        }
    if (gap / cells_across < h) gaps.push_back({p[0], p[1], p[2], gap / cells_across});
  }
  return gaps;
}

// gmsh: the fluid volume inside the given boundary triangles (node k at x[k], tag k + 1).  Returns
// the new tetrahedra in node indices; new nodes are appended to x.
// gmsh: the volume inside the boundary triangles, with the gap sizes.
std::vector<Tet> gmsh_volume(std::vector<std::array<double, 3>> &x, const std::vector<Tri> &tris,
                             const std::vector<double> &mask,
                             const std::vector<std::array<double, 4>> &gaps,
                             const RemeshOptions &o) {
  const double hmax = o.hmax;
  gmsh::initialize(0, nullptr, false);
  std::vector<Tet> tets;
  try {
    gmsh::option::setNumber("General.Terminal", o.verbose ? 1 : 0);
    gmsh::option::setNumber("Mesh.MeshOnlyEmpty", 1);
    gmsh::option::setNumber("Mesh.Algorithm3D", 1); // Delaunay, sizes from the boundary
    if (hmax > 0) gmsh::option::setNumber("Mesh.MeshSizeMax", hmax);
    gmsh::model::add("fluid");
    const auto surfaces = boundary_surfaces(tris, mask);
    std::vector<char> added(x.size(), 0);
    std::vector<int> surface_tags;
    for (size_t s = 0; s < surfaces.size(); ++s) {
      const int tag = (int)s + 1;
      gmsh::model::addDiscreteEntity(2, tag);
      std::vector<std::size_t> ntags, etags;
      std::vector<double> coords;
      for (int t : surfaces[s])
        for (int v : tris[t]) {
          etags.push_back(v + 1);
          if (added[v]) continue;
          added[v] = 1;
          ntags.push_back(v + 1);
          coords.insert(coords.end(), x[v].begin(), x[v].end());
        }
      gmsh::model::mesh::addNodes(2, tag, ntags, coords);
      gmsh::model::mesh::addElementsByType(tag, 2, {}, etags);
      surface_tags.push_back(tag);
    }
    gmsh::model::addDiscreteEntity(3, 1, surface_tags);
    if (!gaps.empty()) // sizes grow away from a gap at 1/2 per unit distance
      gmsh::model::mesh::setSizeCallback([&gaps](int, int, double px, double py, double pz) {
        double s = 1e22;
        for (auto &g : gaps) {
          const double r = std::sqrt((px - g[0]) * (px - g[0]) + (py - g[1]) * (py - g[1]) +
                                     (pz - g[2]) * (pz - g[2]));
          s = std::min(s, g[3] + 0.5 * r);
        }
        return s;
      });
    gmsh::model::mesh::createGeometry({{3, 1}});
    gmsh::model::mesh::generate(3);
    // Nodes come back renumbered: tell the kept ones by their (exact) coordinates; new nodes
    // are those of the new cells.
    std::vector<std::size_t> etags, enodes;
    gmsh::model::mesh::getElementsByType(4, etags, enodes, 1);
    std::vector<std::size_t> ntags;
    std::vector<double> coords, param;
    gmsh::model::mesh::getNodes(ntags, coords, param, -1, -1, false, false);
    std::map<std::size_t, std::array<double, 3>> pos;
    for (size_t i = 0; i < ntags.size(); ++i)
      pos[ntags[i]] = {coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]};
    std::map<std::array<double, 3>, int> known;
    for (size_t v = 0; v < x.size(); ++v)
      if (added[v]) known[x[v]] = (int)v;
    auto index = [&](std::size_t tag) {
      const auto &p = pos.at(tag);
      auto it = known.find(p);
      if (it != known.end()) return it->second;
      x.push_back(p);
      return known[p] = (int)x.size() - 1;
    };
    for (size_t k = 0; k < etags.size(); ++k)
      tets.push_back({index(enodes[4 * k]), index(enodes[4 * k + 1]), index(enodes[4 * k + 2]),
                      index(enodes[4 * k + 3])});
  } catch (...) { // gmsh throws std::string as well as std::exception
    std::string err;
    try {
      gmsh::logger::getLastError(err);
    } catch (...) {
    }
    gmsh::finalize();
    throw RemeshError("gmsh could not mesh the deformed fluid boundary (" +
                      (err.empty() ? std::string("no message") : err) + ")");
  }
  gmsh::finalize();
  if (tets.empty()) throw RemeshError("gmsh returned no fluid cells for the deformed boundary");
  return tets;
}

double skewness_of(const std::vector<std::array<double, 3>> &x, const Tet &t) {
  double P[4][3];
  for (int a = 0; a < 4; ++a)
    for (int d = 0; d < 3; ++d)
      P[a][d] = x[t[a]][d];
  return tet_skewness(P);
}

// The fluid volume inside the boundary triangles (node k at x[k], new nodes appended to x).
std::vector<Tet> mesh_volume(std::vector<std::array<double, 3>> &x, const std::vector<Tri> &tris,
                             const std::vector<double> &mask,
                             const std::vector<std::array<double, 3>> &inward,
                             const RemeshOptions &o, long &gap_vertices) {
  const auto gaps = o.gap_cells > 0 ? gap_sizes(x, tris, inward, o.gap_cells)
                                    : std::vector<std::array<double, 4>>();
  gap_vertices = (long)gaps.size();
  return gmsh_volume(x, tris, mask, gaps, o);
}

// A gmsh 2.2 ASCII mesh (exact coordinates with 17 digits), written atomically.
void write_msh(const std::string &path, const std::vector<std::array<double, 3>> &x,
               const std::vector<Tet> &tets, const std::vector<double> &tet_mask,
               const std::vector<Tri> &tris, const std::vector<double> &tri_mask, const Groups &g) {
  const std::string tmp = path + ".partial";
  FILE *f = std::fopen(tmp.c_str(), "w");
  if (!f) throw InputError("cannot write the remeshed mesh " + path);
  std::fprintf(f, "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n%zu\n", g.names.size());
  for (size_t i = 0; i < g.names.size(); ++i)
    std::fprintf(f, "%d %zu \"%s\"\n", g.dim[i], i + 1, g.names[i].c_str());
  std::fprintf(f, "$EndPhysicalNames\n$Nodes\n%zu\n", x.size());
  for (size_t v = 0; v < x.size(); ++v)
    std::fprintf(f, "%zu %.17g %.17g %.17g\n", v + 1, x[v][0], x[v][1], x[v][2]);
  std::fprintf(f, "$EndNodes\n$Elements\n");
  std::vector<std::string> lines;
  char buf[200];
  auto groups_of = [&](double mask, int dim, auto emit) {
    for (size_t i = 0; i < g.names.size(); ++i)
      if (g.dim[i] == dim && std::fmod(std::floor(mask / std::ldexp(1.0, (int)i)), 2.0) == 1.0)
        emit((int)i + 1);
  };
  for (size_t t = 0; t < tris.size(); ++t)
    groups_of(tri_mask[t], 2, [&](int phys) {
      std::snprintf(buf, sizeof buf, "2 2 %d %d %d %d %d", phys, phys, tris[t][0] + 1,
                    tris[t][1] + 1, tris[t][2] + 1);
      lines.push_back(buf);
    });
  for (size_t k = 0; k < tets.size(); ++k)
    groups_of(tet_mask[k], 3, [&](int phys) {
      std::snprintf(buf, sizeof buf, "4 2 %d %d %d %d %d %d", phys, phys, tets[k][0] + 1,
                    tets[k][1] + 1, tets[k][2] + 1, tets[k][3] + 1);
      lines.push_back(buf);
    });
  std::fprintf(f, "%zu\n", lines.size());
  for (size_t i = 0; i < lines.size(); ++i)
    std::fprintf(f, "%zu %s\n", i + 1, lines[i].c_str());
  std::fprintf(f, "$EndElements\n");
  const bool ok = std::fflush(f) == 0 && !std::ferror(f);
  std::fclose(f);
  if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0)
    throw InputError("cannot write the remeshed mesh " + path + " (disk full?)");
}

// Rank 0: the remesh proper.  Returns the new state.
RunState remesh_on_root(const Gathered &gm, const Groups &g, const RunState &old,
                        const RemeshOptions &o, const std::string &msh_path, RemeshReport &rep) {
  // Old vertices: the state's vertex items (sorted by reference position).
  const KeyedItems &V = old.vertices;
  const size_t nv = V.size(3);
  std::vector<std::array<double, 3>> Xref(nv), x(nv);
  for (size_t v = 0; v < nv; ++v)
    for (int d = 0; d < 3; ++d) {
      Xref[v][d] = V.keys[3 * v + d];
      x[v][d] = Xref[v][d] + V.values[6 * v + d]; // current position
    }
  auto vertex_of = [&](const double *X) {
    const long i = find_key(V, X, 3);
    if (i < 0) throw std::logic_error("remesh: a cell vertex is not in the state");
    return (int)i;
  };
  // Old cells.
  const size_t nc = gm.cells.size(12);
  std::vector<Tet> cells(nc);
  std::vector<char> fluid(nc);
  std::vector<double> cmask(nc);
  for (size_t k = 0; k < nc; ++k) {
    for (int a = 0; a < 4; ++a)
      cells[k][a] = vertex_of(&gm.cells.keys[12 * k + 3 * a]);
    fluid[k] = gm.cells.values[2 * k] != 0;
    cmask[k] = gm.cells.values[2 * k + 1];
  }
  // Labelled faces (partition-boundary duplicates merged).
  std::map<Tri, double> face_mask;
  for (size_t f = 0; f < gm.faces.size(9); ++f) {
    int v[3];
    for (int a = 0; a < 3; ++a)
      v[a] = vertex_of(&gm.faces.keys[9 * f + 3 * a]);
    face_mask[sorted(v[0], v[1], v[2])] = gm.faces.values[f];
  }
  // The fluid boundary: faces of fluid cells not shared with another fluid cell.
  std::map<Tri, int> count, opposite;
  std::vector<Tet> old_fluid;
  double fluid_mask = -1;
  static const int FACE[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  for (size_t k = 0; k < nc; ++k) {
    if (!fluid[k]) continue;
    old_fluid.push_back(cells[k]);
    if (fluid_mask >= 0 && cmask[k] != fluid_mask)
      throw InputError("remeshing needs the fluid in one set of physical volumes");
    fluid_mask = cmask[k];
    for (int i = 0; i < 4; ++i) {
      const Tri t = sorted(cells[k][FACE[i][0]], cells[k][FACE[i][1]], cells[k][FACE[i][2]]);
      ++count[t];
      opposite[t] = cells[k][i];
    }
  }
  std::vector<Tri> boundary;
  std::vector<double> bmask;
  for (auto &[t, n] : count) {
    if (n != 1) continue;
    auto it = face_mask.find(t);
    if (it == face_mask.end()) {
      char msg[300];
      std::snprintf(msg, sizeof msg,
                    "remeshing needs every fluid boundary face in a physical surface; the face "
                    "at (%.4g, %.4g, %.4g) is in none: add it to a Physical Surface in the .geo",
                    x[t[0]][0], x[t[0]][1], x[t[0]][2]);
      throw InputError(msg);
    }
    boundary.push_back(t);
    bmask.push_back(it->second);
  }
  // Kept vertices: the solid's and the fluid boundary's; the fluid's inner ones are dropped.
  std::vector<char> keep(nv, 0), in_solid(nv, 0);
  for (size_t k = 0; k < nc; ++k)
    if (!fluid[k])
      for (int v : cells[k])
        keep[v] = in_solid[v] = 1;
  for (auto &t : boundary)
    for (int v : t)
      keep[v] = 1;
  std::vector<int> new_index(nv, -1);
  std::vector<std::array<double, 3>> y; // new vertex positions (= the new reference)
  std::vector<int> old_of;              // old vertex of each kept new vertex
  for (size_t v = 0; v < nv; ++v)
    if (keep[v]) {
      new_index[v] = (int)y.size();
      y.push_back(x[v]);
      old_of.push_back((int)v);
    }
  const size_t n_kept = y.size();
  std::vector<Tri> btris;
  std::vector<std::array<double, 3>> inward; // unit normal into the fluid per boundary triangle
  for (auto &t : boundary) {
    btris.push_back({new_index[t[0]], new_index[t[1]], new_index[t[2]]});
    double e1[3], e2[3], n[3], o = 0, len = 0;
    for (int d = 0; d < 3; ++d)
      e1[d] = x[t[1]][d] - x[t[0]][d], e2[d] = x[t[2]][d] - x[t[0]][d];
    cross(e1, e2, n);
    for (int d = 0; d < 3; ++d)
      o += n[d] * (x[opposite[t]][d] - x[t[0]][d]), len += n[d] * n[d];
    const double sgn = (o > 0 ? 1.0 : -1.0) / std::sqrt(len);
    inward.push_back({sgn * n[0], sgn * n[1], sgn * n[2]});
  }
  if (o.test_fault == 1 && !btris.empty()) {
    // A test of the failure path: one boundary vertex thrown across the domain.
    auto &p = y[btris[btris.size() / 2][0]];
    for (int d = 0; d < 3; ++d)
      p[d] = -p[d];
  }

  const double m0 = MPI_Wtime();
  std::vector<Tet> new_fluid = mesh_volume(y, btris, bmask, inward, o, rep.gap_vertices);
  rep.mesh_seconds = MPI_Wtime() - m0;

  // The new fluid cells' boundary must be the old boundary, triangle for triangle.
  {
    std::map<Tri, int> c2;
    for (auto &t : new_fluid)
      for (auto &f : FACE)
        ++c2[sorted(t[f[0]], t[f[1]], t[f[2]])];
    std::set<Tri> got, want;
    for (auto &[t, n] : c2)
      if (n == 1) got.insert(t);
    for (auto &t : btris)
      want.insert(sorted(t[0], t[1], t[2]));
    if (got != want)
      throw RemeshError("gmsh changed the fluid boundary (" + std::to_string(want.size()) +
                        " triangles given, " + std::to_string(got.size()) +
                        " on the new mesh): the interface would not conform");
  }

  // New mesh: fluid cells, then the old solid cells; the labelled faces whose vertices survive.
  std::vector<Tet> tets = new_fluid;
  std::vector<double> tmask(new_fluid.size(), fluid_mask);
  for (size_t k = 0; k < nc; ++k)
    if (!fluid[k]) {
      tets.push_back({new_index[cells[k][0]], new_index[cells[k][1]], new_index[cells[k][2]],
                      new_index[cells[k][3]]});
      tmask.push_back(cmask[k]);
    }
  std::vector<Tri> ftris;
  std::vector<double> fmask;
  long dropped = 0;
  for (auto &[t, m] : face_mask) {
    if (!keep[t[0]] || !keep[t[1]] || !keep[t[2]]) {
      ++dropped; // a labelled surface inside the fluid cannot survive a new fluid mesh
      continue;
    }
    ftris.push_back({new_index[t[0]], new_index[t[1]], new_index[t[2]]});
    fmask.push_back(m);
  }
  if (dropped)
    PetscPrintf(PETSC_COMM_SELF,
                "fsi_app: remesh: %ld labelled faces inside the fluid are not carried over\n",
                dropped);
  write_msh(msh_path, y, tets, tmask, ftris, fmask, g);

  // ---- State transfer ----
  const KeyedItems &dofs = old.dofs;
  Locator locate(x, old_fluid);
  auto old_cell_nodes = [&](const Tet &t, double vals[10][9], double p[4][3]) {
    for (int a = 0; a < 10; ++a) {
      double X[3];
      for (int d = 0; d < 3; ++d)
        X[d] = a < 4 ? Xref[t[a]][d]
                     : 0.5 * (Xref[t[TET_EDGE[a - 4][0]]][d] + Xref[t[TET_EDGE[a - 4][1]]][d]);
      if (!node_values(dofs, X, vals[a]))
        throw std::logic_error("remesh: an old velocity node is not in the state");
      if (a < 4 && !pressure_value(dofs, X, p[a]))
        throw std::logic_error("remesh: an old pressure node is not in the state");
    }
  };
  auto interpolate = [&](const double q[3], double out[9], double *pressure) {
    double lam[4];
    const int k = locate.find(q, lam);
    double vals[10][9], p[4][3], N[10], dN[10][3], gl[4][3] = {};
    old_cell_nodes(old_fluid[k], vals, p);
    p2_tet(lam, gl, N, dN);
    for (int i = 0; i < 9; ++i) {
      out[i] = 0;
      for (int a = 0; a < 10; ++a)
        out[i] += N[a] * vals[a][i];
    }
    if (pressure)
      for (int h = 0; h < 3; ++h)
        pressure[h] = lam[0] * p[0][h] + lam[1] * p[1][h] + lam[2] * p[2][h] + lam[3] * p[3][h];
  };
  RunState s;
  s.scene = old.scene;
  s.step = old.step;
  s.time = old.time;
  s.dt = old.dt;
  s.easy_run = old.easy_run;
  s.hemo_window = old.hemo_window;
  s.hemo_last_window = old.hemo_last_window;
  // Vertices: mesh displacement 0 (the new reference is the current mesh); the solid keeps its
  // material reference, fluid vertices get theirs at their new position.
  for (size_t v = 0; v < y.size(); ++v) {
    s.vertices.keys.insert(s.vertices.keys.end(), y[v].begin(), y[v].end());
    const bool solid = v < n_kept && in_solid[old_of[v]];
    for (int d = 0; d < 3; ++d)
      s.vertices.values.push_back(0.0);
    for (int d = 0; d < 3; ++d)
      s.vertices.values.push_back(solid ? V.values[6 * old_of[v] + 3 + d] : y[v][d]);
  }
  // Nodes: vertices, then the edges of the new cells.
  long copied = 0, interpolated = 0;
  auto add_node = [&](const double key[3], const double vals[9]) {
    for (int c = 0; c < 3; ++c) {
      s.dofs.keys.insert(s.dofs.keys.end(), {key[0], key[1], key[2], (double)c});
      for (int h = 0; h < 3; ++h)
        s.dofs.values.push_back(vals[3 * h + c]);
    }
  };
  for (size_t v = 0; v < y.size(); ++v) {
    double vals[9], p[3];
    const bool kept = v < n_kept;
    if (kept && node_values(dofs, Xref[old_of[v]].data(), vals) &&
        pressure_value(dofs, Xref[old_of[v]].data(), p)) {
      ++copied;
    } else {
      interpolate(y[v].data(), vals, p);
      ++interpolated;
    }
    add_node(y[v].data(), vals);
    s.dofs.keys.insert(s.dofs.keys.end(), {y[v][0], y[v][1], y[v][2], 3.0});
    s.dofs.values.insert(s.dofs.values.end(), p, p + 3);
  }
  std::set<std::pair<int, int>> edges;
  for (auto &t : tets)
    for (auto &e : TET_EDGE)
      edges.insert({std::min(t[e[0]], t[e[1]]), std::max(t[e[0]], t[e[1]])});
  for (auto &[a, b] : edges) {
    double key[3], vals[9];
    for (int d = 0; d < 3; ++d)
      key[d] = 0.5 * (y[a][d] + y[b][d]);
    bool done = false;
    if ((size_t)a < n_kept && (size_t)b < n_kept) {
      double X[3];
      for (int d = 0; d < 3; ++d)
        X[d] = 0.5 * (Xref[old_of[a]][d] + Xref[old_of[b]][d]);
      done = node_values(dofs, X, vals); // an old edge: its values exactly
    }
    if (done)
      ++copied;
    else
      interpolate(key, vals, nullptr), ++interpolated;
    add_node(key, vals);
  }
  s.n_dofs = (long)(3 * (y.size() + edges.size()) + y.size());
  sort_items(s.dofs, 4, 3);
  sort_items(s.vertices, 3, 6);
  // Wall-shear accumulators follow their faces (keys: canonical centroids, old -> new).
  KeyedItems moved; // key: old centroid; value: new centroid
  for (auto &[t, m] : face_mask)
    if (keep[t[0]] && keep[t[1]] && keep[t[2]]) {
      double k0[3], k1[3];
      face_key(Xref[t[0]].data(), Xref[t[1]].data(), Xref[t[2]].data(), k0);
      face_key(y[new_index[t[0]]].data(), y[new_index[t[1]]].data(), y[new_index[t[2]]].data(), k1);
      moved.keys.insert(moved.keys.end(), k0, k0 + 3);
      moved.values.insert(moved.values.end(), k1, k1 + 3);
    }
  sort_items(moved, 3, 3);
  for (auto &[name, items] : old.hemo) {
    KeyedItems out;
    for (size_t i = 0; i < items.size(3); ++i) {
      const long j = find_key(moved, &items.keys[3 * i], 3);
      if (j < 0) throw RemeshError("remesh: a wall-shear face of '" + name + "' was lost");
      out.keys.insert(out.keys.end(), &moved.values[3 * j], &moved.values[3 * j + 3]);
      out.values.insert(out.values.end(), &items.values[4 * i], &items.values[4 * i + 4]);
    }
    sort_items(out, 3, 4);
    s.hemo[name] = out;
  }

  // Measures: quality, volume, kinetic energy and divergence before and after.
  Integrals before, after;
  rep.skewness_before = rep.skewness_after = 0;
  for (auto &t : old_fluid) {
    double P[4][3], vals[10][9], p[4][3], v[10][3];
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d)
        P[a][d] = x[t[a]][d];
    old_cell_nodes(t, vals, p);
    for (int a = 0; a < 10; ++a)
      for (int d = 0; d < 3; ++d)
        v[a][d] = vals[a][d];
    integrate(P, v, before);
    rep.skewness_before = std::max(rep.skewness_before, skewness_of(x, t));
  }
  for (auto &t : new_fluid) {
    double P[4][3], v[10][3];
    for (int a = 0; a < 10; ++a) {
      double key[4];
      for (int d = 0; d < 3; ++d) {
        key[d] =
            a < 4 ? y[t[a]][d] : 0.5 * (y[t[TET_EDGE[a - 4][0]]][d] + y[t[TET_EDGE[a - 4][1]]][d]);
        if (a < 4) P[a][d] = y[t[a]][d];
      }
      for (int c = 0; c < 3; ++c) {
        key[3] = c;
        v[a][c] = s.dofs.values[3 * find_key(s.dofs, key, 4)];
      }
    }
    integrate(P, v, after);
    rep.skewness_after = std::max(rep.skewness_after, skewness_of(y, t));
  }
  rep.fluid_cells_before = (long)old_fluid.size();
  rep.fluid_cells_after = (long)new_fluid.size();
  rep.volume_before = before.volume, rep.volume_after = after.volume;
  rep.kinetic_before = before.kinetic, rep.kinetic_after = after.kinetic;
  rep.divergence_before = before.grad2 > 0 ? std::sqrt(before.div2 / before.grad2) : 0;
  rep.divergence_after = after.grad2 > 0 ? std::sqrt(after.div2 / after.grad2) : 0;
  (void)copied;
  (void)interpolated;
  return s;
}

} // namespace

RemeshOptions RemeshOptions::from_options() {
  RemeshOptions o;
  o.hmax = opt::nonnegative("ale_remesh_hmax", 0.0);
  o.verbose = opt::integer("ale_remesh_verbose", 0) != 0;
  o.test_fault = (int)opt::integer("ale_remesh_test_fault", 0);
  o.gap_cells = opt::nonnegative("ale_remesh_gap_cells", 2.0);
  return o;
}

RunState remesh_fluid(const Mesh &mesh, const Space &space,
                      const std::vector<PetscInt> &fluid_cells, const RunState &state,
                      const RemeshOptions &o, const std::string &msh_path, RemeshReport &rep) {
  MPI_Comm comm = PetscObjectComm((PetscObject)mesh.dm);
  int rank;
  MPI_Comm_rank(comm, &rank);
  const Groups g = mesh_groups(mesh);
  const Gathered gm = gather_mesh(mesh, space, fluid_cells, g);
  RunState s;
  int code = 0; // 0 ok, 2 input error, 3 remesh error
  std::string err;
  if (rank == 0) {
    try {
      s = remesh_on_root(gm, g, state, o, msh_path, rep);
    } catch (InputError &e) {
      code = 2, err = e.what();
    } catch (RemeshError &e) {
      code = 3, err = e.what();
    }
  }
  MPI_Bcast(&code, 1, MPI_INT, 0, comm);
  if (code) {
    int len = (int)err.size();
    MPI_Bcast(&len, 1, MPI_INT, 0, comm);
    err.resize(len);
    MPI_Bcast(err.data(), len, MPI_CHAR, 0, comm);
    if (code == 2) throw InputError(err);
    throw RemeshError(err);
  }
  // Scalars on every rank (items stay on rank 0, as in a state read from a file).
  double meta[4] = {(double)s.step, s.time, s.dt, (double)s.n_dofs};
  MPI_Bcast(meta, 4, MPI_DOUBLE, 0, comm);
  s.step = std::lround(meta[0]), s.time = meta[1], s.dt = meta[2], s.n_dofs = std::lround(meta[3]);
  s.scene = state.scene;
  s.easy_run = state.easy_run;
  s.hemo_window = state.hemo_window;
  MPI_Bcast(&rep.gap_vertices, 1, MPI_LONG, 0, comm);
  double r[11] = {(double)rep.fluid_cells_before,
                  (double)rep.fluid_cells_after,
                  rep.skewness_before,
                  rep.skewness_after,
                  rep.volume_before,
                  rep.volume_after,
                  rep.kinetic_before,
                  rep.kinetic_after,
                  rep.divergence_before,
                  rep.divergence_after,
                  rep.mesh_seconds};
  MPI_Bcast(r, 11, MPI_DOUBLE, 0, comm);
  rep.fluid_cells_before = std::lround(r[0]), rep.fluid_cells_after = std::lround(r[1]);
  rep.skewness_before = r[2], rep.skewness_after = r[3], rep.volume_before = r[4];
  rep.volume_after = r[5], rep.kinetic_before = r[6], rep.kinetic_after = r[7];
  rep.divergence_before = r[8], rep.divergence_after = r[9], rep.mesh_seconds = r[10];
  rep.memory_mb = peak_memory_mb();
  return s;
}

} // namespace fsi
