// Remeshing: the state carried to the new mesh (remesh_internal.hpp): exact where a node
// survives, P2 (velocity, acceleration, displacement) / P1 (pressure) interpolation in the old
// fluid mesh at its current position elsewhere; and the measures of the report.
#include "fsi/discretization/p2tet.hpp"
#include "remesh_internal.hpp"

#include <cmath>
#include <set>

namespace fsi::remeshing {
namespace {

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

} // namespace

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

namespace {

// The pressure dof's three histories (its V is the pressure).
static bool pressure_value(const KeyedItems &dofs, const double X[3], double out[3]) {
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

static void integrate(const double P[4][3], const double v[10][3], Integrals &s) {
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

} // namespace

RunState transfer_state(const OldMesh &om, const NewMesh &nm, const RunState &old,
                        RemeshReport &rep) {
  const std::vector<Point> &Xref = om.Xref, &x = om.x, &y = nm.y;
  const std::vector<Tet> &old_fluid = om.fluid_cells, &tets = nm.cells;
  const std::vector<Tet> new_fluid(tets.begin(), tets.begin() + nm.n_fluid);
  const std::vector<int> &old_of = nm.old_of, &new_index = nm.new_index;
  const std::vector<char> &in_solid = nm.in_solid;
  const size_t n_kept = nm.n_kept;
  const KeyedItems &V = old.vertices;
  auto kept = [&](const Tri &t) {
    return new_index[t[0]] >= 0 && new_index[t[1]] >= 0 && new_index[t[2]] >= 0;
  };
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
  s.lumped = old.lumped;
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
  auto add_node = [&](const double key[3], const double vals[9]) {
    for (int c = 0; c < 3; ++c) {
      s.dofs.keys.insert(s.dofs.keys.end(), {key[0], key[1], key[2], (double)c});
      for (int h = 0; h < 3; ++h)
        s.dofs.values.push_back(vals[3 * h + c]);
    }
  };
  for (size_t v = 0; v < y.size(); ++v) {
    double vals[9], p[3];
    const bool old_vertex = v < n_kept;
    if (!(old_vertex && node_values(dofs, Xref[old_of[v]].data(), vals) &&
          pressure_value(dofs, Xref[old_of[v]].data(), p)))
      interpolate(y[v].data(), vals, p);
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
    if (!done) interpolate(key, vals, nullptr);
    add_node(key, vals);
  }
  s.n_dofs = (long)(3 * (y.size() + edges.size()) + y.size());
  sort_items(s.dofs, 4, 3);
  sort_items(s.vertices, 3, 6);
  // Wall-shear accumulators follow their faces (keys: canonical centroids, old -> new).
  KeyedItems moved; // key: old centroid; value: new centroid
  for (auto &[t, m] : om.face_mask)
    if (kept(t)) {
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
  return s;
}

} // namespace fsi::remeshing
