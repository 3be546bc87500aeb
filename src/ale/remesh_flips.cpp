// Sliver removal by local flips on the new fluid mesh (remesh_internal.hpp).
//
// gmsh's Delaunay mesher with a fixed boundary leaves flat cells whose four vertices all lie on
// the boundary (measured on the opening valve: a cell on two nearly coplanar interface
// triangles, skewness 0.9999, that gmsh's optimiser keeps).  No vertex of such a cell can
// move, but its interior edges and faces can be swapped: an edge shared by a closed ring of
// cells is removed and the ring's polygon triangulated again (the best triangulation by dynamic
// programming; a 3-2 flip is the ring of three), and a face between two cells is replaced by
// the three cells around the segment joining their far vertices (2-3 flip).  Only interior
// edges and faces change, so the boundary triangles -- and the conformity with the solid --
// stay as they are; a flip is taken only if it raises the worst quality of the cells it
// replaces.  Quality: V / V_regular(circumradius) = 1 - skewness, negative when inverted.
#include "fsi/ale/mesh_motion.hpp"
#include "remesh_internal.hpp"

#include <cmath>
#include <limits>

namespace fsi::remeshing {

namespace {

double orient(const Point &a, const Point &b, const Point &c, const Point &d) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
         u[2] * (v[0] * w[1] - v[1] * w[0]);
}

// Signed quality of (a, b, c, d): 1 - skewness (the remesh trigger's measure), negative when
// orient < 0.
double quality(const Point &a, const Point &b, const Point &c, const Point &d) {
  const double P[4][3] = {
      {a[0], a[1], a[2]}, {b[0], b[1], b[2]}, {c[0], c[1], c[2]}, {d[0], d[1], d[2]}};
  const double q = 1 - tet_skewness(P);
  return orient(a, b, c, d) < 0 ? -q : q;
}

// Pattern search from `at` for the point where worst(p) is largest: steps along the axes, halved
// when none helps.  Returns the value at the final point.
template <class F> double best_point(Point &at, double scale, F worst) {
  double best = worst(at);
  for (double step = 0.25 * scale; step > 1e-3 * scale; step *= 0.5)
    for (bool moved = true; moved;) {
      moved = false;
      for (int k = 0; k < 3; ++k)
        for (double sgn : {-1.0, 1.0}) {
          Point p = at;
          p[k] += sgn * step;
          const double w = worst(p);
          if (w > best) best = w, at = p, moved = true;
        }
    }
  return best;
}

struct Flipper {
  std::vector<Point> &x;
  std::vector<Tet> &tets;
  std::vector<char> alive;
  std::vector<std::vector<int>> of_vertex; // cells per vertex, dead ones included (alive says)

  Flipper(std::vector<Point> &x_, std::vector<Tet> &t) : x(x_), tets(t) {
    alive.assign(tets.size(), 1);
    of_vertex.resize(x.size());
    for (size_t k = 0; k < tets.size(); ++k)
      for (int v : tets[k])
        of_vertex[v].push_back((int)k);
  }
  double q(const Tet &t) const { return quality(x[t[0]], x[t[1]], x[t[2]], x[t[3]]); }
  double q(int k) const { return q(tets[k]); }

  std::vector<int> cells_with(int a, int b) {
    std::vector<int> out;
    for (int k : of_vertex[a])
      if (alive[k] && std::find(tets[k].begin(), tets[k].end(), b) != tets[k].end())
        out.push_back(k);
    return out;
  }
  void replace(const std::vector<int> &old, const std::vector<Tet> &fresh,
               std::vector<int> &added) {
    for (int k : old)
      alive[k] = 0;
    for (auto t : fresh) {
      if (orient(x[t[0]], x[t[1]], x[t[2]], x[t[3]]) < 0) std::swap(t[2], t[3]);
      tets.push_back(t);
      alive.push_back(1);
      for (int v : t)
        of_vertex[v].push_back((int)tets.size() - 1);
      added.push_back((int)tets.size() - 1);
    }
  }

  // The cells around edge (a, d) and the ring of their other vertices, turning positively about
  // a -> d; false if the ring is open (a boundary edge).
  bool ring_of(int a, int d, std::vector<int> &old, std::vector<int> &ring) {
    old = cells_with(a, d);
    const size_t n = old.size();
    if (n < 3) return false;
    // The ring: the two other vertices of each cell, chained; open chain = boundary edge.
    std::vector<std::array<int, 2>> pairs;
    for (int k : old) {
      std::array<int, 2> p{};
      int m = 0;
      for (int v : tets[k])
        if (v != a && v != d) p[m++] = v;
      pairs.push_back(p);
    }
    ring = {pairs[0][0], pairs[0][1]};
    std::vector<char> used(n, 0);
    used[0] = 1;
    while (ring.size() < n) {
      bool found = false;
      for (size_t i = 0; i < n && !found; ++i)
        if (!used[i] && (pairs[i][0] == ring.back() || pairs[i][1] == ring.back())) {
          ring.push_back(pairs[i][0] == ring.back() ? pairs[i][1] : pairs[i][0]);
          used[i] = 1, found = true;
        }
      if (!found) return false;
    }
    {
      bool closes = false; // the last unused pair joins the ends
      for (size_t i = 0; i < n; ++i)
        if (!used[i])
          closes = (pairs[i][0] == ring.back() && pairs[i][1] == ring.front()) ||
                   (pairs[i][1] == ring.back() && pairs[i][0] == ring.front());
      if (!closes) return false;
    }
    if (orient(x[a], x[d], x[ring[0]], x[ring[1]]) < 0) std::reverse(ring.begin(), ring.end());
    return true;
  }

  // Edge removal of (a, d): the new cells and their worst quality, or -inf if not possible.
  double edge_removal(int a, int d, std::vector<int> &old, std::vector<Tet> &fresh) {
    std::vector<int> ring;
    if (!ring_of(a, d, old, ring) || old.size() > 9) return -1e300;
    const size_t n = ring.size();
    // best[i][j]: the best worst quality of the polygon ring[i..j] with the chord (i, j).
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<std::vector<double>> best(n, std::vector<double>(n, inf));
    std::vector<std::vector<int>> split(n, std::vector<int>(n, -1));
    for (size_t len = 2; len < n; ++len)
      for (size_t i = 0; i + len < n; ++i) {
        const size_t j = i + len;
        best[i][j] = -inf;
        for (size_t k = i + 1; k < j; ++k) {
          const Point &pi = x[ring[i]], &pk = x[ring[k]], &pj = x[ring[j]];
          const double m = std::min(
              {best[i][k], best[k][j], quality(x[a], pi, pk, pj), quality(x[d], pi, pj, pk)});
          if (m > best[i][j]) best[i][j] = m, split[i][j] = (int)k;
        }
      }
    fresh.clear();
    std::vector<std::array<size_t, 2>> stack{{0, n - 1}};
    while (!stack.empty()) {
      auto [i, j] = stack.back();
      stack.pop_back();
      if (j - i < 2) continue;
      const size_t k = (size_t)split[i][j];
      fresh.push_back({a, ring[i], ring[k], ring[j]});
      fresh.push_back({d, ring[i], ring[j], ring[k]});
      stack.push_back({i, k});
      stack.push_back({k, j});
    }
    return best[0][n - 1];
  }

  // Edge split of (a, d) by a new vertex m placed where the worst of its cells is best (a
  // pattern search from the ring's centre): the move that removes a sliver on four boundary
  // vertices whose ring is not convex enough for edge removal.  Appends m to x when taken.
  double edge_split(int a, int d, std::vector<int> &old, std::vector<Tet> &fresh, Point &at) {
    std::vector<int> ring;
    if (!ring_of(a, d, old, ring)) return -1e300;
    const size_t n = ring.size();
    auto worst_at = [&](const Point &m) {
      double w = 1e300;
      for (size_t i = 0; i < n; ++i) {
        const Point &u = x[ring[i]], &v = x[ring[(i + 1) % n]];
        w = std::min({w, quality(x[a], m, u, v), quality(m, x[d], u, v)});
      }
      return w;
    };
    Point m, c{0, 0, 0};
    double len = 0;
    for (int v : ring)
      for (int k = 0; k < 3; ++k)
        c[k] += x[v][k] / n;
    for (int k = 0; k < 3; ++k) {
      m[k] = 0.5 * (x[a][k] + x[d][k]);
      len += (x[a][k] - x[d][k]) * (x[a][k] - x[d][k]);
    }
    double best = worst_at(m);
    at = m;
    for (double t : {0.25, 0.5, 0.75, 1.0}) {
      Point p;
      for (int k = 0; k < 3; ++k)
        p[k] = m[k] + t * (c[k] - m[k]);
      const double w = worst_at(p);
      if (w > best) best = w, at = p;
    }
    best = best_point(at, std::sqrt(len), worst_at);
    const int mi = (int)x.size(); // the index m will have
    fresh.clear();
    for (size_t i = 0; i < n; ++i) {
      fresh.push_back({a, mi, ring[i], ring[(i + 1) % n]});
      fresh.push_back({mi, d, ring[i], ring[(i + 1) % n]});
    }
    return best;
  }

  // Moving interior vertex v to where the worst of its cells is best; returns that worst (the
  // cells keep their vertices: old = fresh = the star).
  double smooth(int v, std::vector<int> &old, std::vector<Tet> &fresh, Point &at) {
    old.clear();
    double scale = 0;
    for (int k : of_vertex[v])
      if (alive[k]) {
        old.push_back(k);
        for (int u : tets[k])
          for (int d = 0; d < 3; ++d)
            scale = std::max(scale, std::abs(x[u][d] - x[v][d]));
      }
    fresh.clear();
    for (int k : old)
      fresh.push_back(tets[k]);
    const Point keep = x[v];
    auto worst_at = [&](const Point &p) {
      x[v] = p;
      double w = 1e300;
      for (int k : old)
        w = std::min(w, q(k));
      x[v] = keep;
      return w;
    };
    at = keep;
    return best_point(at, scale, worst_at);
  }

  // 2-3 flip of face f of cell k: the new cells and their worst quality, or -inf.
  double face_flip(int k, int f, std::vector<int> &old, std::vector<Tet> &fresh) {
    const Tet &t = tets[k];
    const int p = t[TET_FACE[f][0]], r = t[TET_FACE[f][1]], s = t[TET_FACE[f][2]], a = t[f];
    int other = -1;
    for (int c : cells_with(p, r))
      if (c != k && std::find(tets[c].begin(), tets[c].end(), s) != tets[c].end()) other = c;
    if (other < 0) return -1e300; // a boundary face
    int b = -1;
    for (int v : tets[other])
      if (v != p && v != r && v != s) b = v;
    old = {k, other};
    fresh = {{a, b, p, r}, {a, b, r, s}, {a, b, s, p}};
    double sign = 0, worst = 1e300;
    for (auto &c : fresh) {
      const double o = orient(x[c[0]], x[c[1]], x[c[2]], x[c[3]]);
      if (o == 0 || (sign != 0 && (o > 0) != (sign > 0))) return -1e300; // ab misses the face
      sign = o;
    }
    for (auto &c : fresh)
      worst = std::min(worst, std::abs(q(c)));
    return worst;
  }
};

} // namespace

FlipReport remove_slivers(std::vector<Point> &x, std::vector<Tet> &tets, double threshold) {
  FlipReport rep;
  Flipper F(x, tets);
  std::vector<char> on_boundary(x.size(), 0); // vertices of faces with one cell: they stay
  {
    std::map<Tri, int> count;
    for (auto &t : tets)
      for (auto &f : TET_FACE)
        ++count[sorted(t[f[0]], t[f[1]], t[f[2]])];
    for (auto &[f, c] : count)
      if (c == 1)
        for (int v : f)
          on_boundary[v] = 1;
  }
  auto bad = [&](int k) { return F.alive[k] && F.q(k) < 1 - threshold; };
  std::vector<int> queue;
  for (size_t k = 0; k < tets.size(); ++k)
    if (bad((int)k)) queue.push_back((int)k);
  // Each accepted flip raises the worst quality of the cells it touches, so this ends; the cap
  // on passes bounds the time on a pathological boundary.
  for (int pass = 0; pass < 20 && !queue.empty(); ++pass) {
    std::vector<int> next;
    for (int k : queue) {
      if (!bad(k)) continue;
      double gain_best = 0;
      std::vector<int> old_best;
      std::vector<Tet> fresh_best;
      std::vector<int> old;
      std::vector<Tet> fresh;
      auto consider = [&](double new_worst) {
        double old_worst = 1e300;
        for (int c : old)
          old_worst = std::min(old_worst, F.q(c));
        if (new_worst > old_worst + 1e-12 && new_worst - old_worst > gain_best)
          gain_best = new_worst - old_worst, old_best = old, fresh_best = fresh;
      };
      const Tet t = tets[k];
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
          consider(F.edge_removal(t[i], t[j], old, fresh));
      for (int f = 0; f < 4; ++f)
        consider(F.face_flip(k, f, old, fresh));
      Point at{}, at_best{};
      int moved = -1;       // 0..3: a smoothed vertex of t; 4: a split
      if (old_best.empty()) // no flip helps: move a free vertex
        for (int i = 0; i < 4; ++i)
          if (!on_boundary[t[i]]) {
            const double before = gain_best;
            consider(F.smooth(t[i], old, fresh, at));
            if (gain_best > before) moved = i, at_best = at;
          }
      if (old_best.empty()) // nor a move: split an interior edge
        for (int i = 0; i < 4; ++i)
          for (int j = i + 1; j < 4; ++j) {
            const double before = gain_best;
            consider(F.edge_split(t[i], t[j], old, fresh, at));
            if (gain_best > before) moved = 4, at_best = at;
          }
      if (old_best.empty()) continue;
      if (moved == 4) {
        x.push_back(at_best), F.of_vertex.emplace_back(), on_boundary.push_back(0);
        ++rep.splits;
      } else if (moved >= 0) {
        x[t[moved]] = at_best; // the star keeps its cells
        ++rep.moves;
        for (int c : old_best)
          if (bad(c)) next.push_back(c);
        continue;
      }
      std::vector<int> added;
      F.replace(old_best, fresh_best, added);
      ++rep.flips;
      for (int c : added)
        if (bad(c)) next.push_back(c);
    }
    queue.swap(next);
  }
  std::vector<Tet> kept;
  kept.reserve(tets.size());
  for (size_t k = 0; k < tets.size(); ++k)
    if (F.alive[k]) kept.push_back(tets[k]);
  tets.swap(kept);
  return rep;
}

} // namespace fsi::remeshing
