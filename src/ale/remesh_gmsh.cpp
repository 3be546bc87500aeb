// Remeshing: the new fluid volume with gmsh 4.8 and the new mesh file (remesh_internal.hpp).
#include "fsi/ale/mesh_motion.hpp"
#include "fsi/discretization/p2tet.hpp"
#include "fsi/mesh/gmsh_module.hpp"
#include "remesh_internal.hpp"

#include <cmath>
#include <cstdio>
#include <functional>
#include <numeric>
#include <set>

namespace fsi::remeshing {

// The fluid boundary split into surfaces for gmsh: one per (group mask, connected piece), so
// that every closed shell of the boundary is its own surface (gmsh then tells holes apart).
static std::vector<std::vector<int>> boundary_surfaces(const std::vector<Tri> &tris,
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
static double point_triangle(const double *p, const double *a, const double *b, const double *c,
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
static std::vector<std::array<double, 4>>
gap_sizes(const std::vector<std::array<double, 3>> &x, const std::vector<Tri> &tris,
          const std::vector<std::array<double, 3>> &inward, double cells_across) {
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

// gmsh: the volume inside the boundary triangles, with the gap sizes.
static std::vector<Tet> gmsh_volume(std::vector<std::array<double, 3>> &x,
                                    const std::vector<Tri> &tris, const std::vector<double> &mask,
                                    const std::vector<std::array<double, 4>> &gaps,
                                    const RemeshOptions &o) {
  std::vector<std::vector<std::array<int, 3>>> surfaces;
  for (const auto &list : boundary_surfaces(tris, mask)) {
    surfaces.emplace_back();
    for (int t : list)
      surfaces.back().push_back(tris[t]);
  }
  std::vector<Tet> tets;
  const gmsh_module::Status st =
      gmsh_module::mesh_volume(x, surfaces, gaps, o.hmax, o.verbose, tets);
  if (st.code)
    throw RemeshError("gmsh could not mesh the deformed fluid boundary (" + st.message + ")");
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

std::vector<Tet> mesh_volume(std::vector<std::array<double, 3>> &x, const std::vector<Tri> &tris,
                             const std::vector<double> &mask,
                             const std::vector<std::array<double, 3>> &inward,
                             const RemeshOptions &o, RemeshReport &rep) {
  const auto gaps = o.gap_cells > 0 ? gap_sizes(x, tris, inward, o.gap_cells)
                                    : std::vector<std::array<double, 4>>();
  rep.gap_vertices = (long)gaps.size();
  auto tets = gmsh_volume(x, tris, mask, gaps, o);
  rep.skewness_gmsh = 0;
  for (auto &t : tets)
    rep.skewness_gmsh = std::max(rep.skewness_gmsh, skewness_of(x, t));
  if (o.flip_skewness > 0) {
    const FlipReport f = remove_slivers(x, tets, o.flip_skewness);
    rep.flips = f.flips + f.moves, rep.splits = f.splits;
  }
  return tets;
}

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

} // namespace fsi::remeshing
