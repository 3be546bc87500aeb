// Remeshing the fluid: see remesh.hpp.  This file drives it: the old mesh on rank 0 from the
// gathered cells and the state, the fluid boundary and the vertices that survive, gmsh
// (remesh_gmsh.cpp), the new mesh file, the state transfer (remesh_transfer.cpp).  Vertices are
// identified by their reference coordinates (the keys of the state), so no global numbering of
// the distributed mesh is needed.
#include "fsi/ale/remesh.hpp"
#include "fsi/discretization/p2tet.hpp"
#include "fsi/discretization/space.hpp"
#include "fsi/scene/options.hpp"
#include "remesh_internal.hpp"

#include <cmath>
#include <cstdio>
#include <set>

namespace fsi {
namespace remeshing {
namespace {

// Rank 0: the remesh proper.  Returns the new state.
RunState remesh_on_root(const Gathered &gm, const Groups &g, const RunState &old,
                        const RemeshOptions &o, const std::string &msh_path, RemeshReport &rep) {
  OldMesh om;
  // Old vertices: the state's vertex items (sorted by reference position).
  const KeyedItems &V = old.vertices;
  const size_t nv = V.size(3);
  std::vector<Point> &Xref = om.Xref, &x = om.x;
  Xref.resize(nv), x.resize(nv);
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
  std::vector<Tet> &cells = om.cells;
  std::vector<char> &fluid = om.fluid;
  std::vector<double> &cmask = om.cell_mask;
  cells.resize(nc), fluid.resize(nc), cmask.resize(nc);
  for (size_t k = 0; k < nc; ++k) {
    for (int a = 0; a < 4; ++a)
      cells[k][a] = vertex_of(&gm.cells.keys[12 * k + 3 * a]);
    fluid[k] = gm.cells.values[2 * k] != 0;
    cmask[k] = gm.cells.values[2 * k + 1];
  }
  // Labelled faces (partition-boundary duplicates merged).
  std::map<Tri, double> &face_mask = om.face_mask;
  for (size_t f = 0; f < gm.faces.size(9); ++f) {
    int v[3];
    for (int a = 0; a < 3; ++a)
      v[a] = vertex_of(&gm.faces.keys[9 * f + 3 * a]);
    face_mask[sorted(v[0], v[1], v[2])] = gm.faces.values[f];
  }
  // The fluid boundary: faces of fluid cells not shared with another fluid cell.
  std::map<Tri, int> count, opposite;
  std::vector<Tet> &old_fluid = om.fluid_cells;
  double fluid_mask = -1;
  for (size_t k = 0; k < nc; ++k) {
    if (!fluid[k]) continue;
    old_fluid.push_back(cells[k]);
    if (fluid_mask >= 0 && cmask[k] != fluid_mask)
      throw InputError("remeshing needs the fluid in one set of physical volumes");
    fluid_mask = cmask[k];
    for (int i = 0; i < 4; ++i) {
      const Tri t =
          sorted(cells[k][TET_FACE[i][0]], cells[k][TET_FACE[i][1]], cells[k][TET_FACE[i][2]]);
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
  NewMesh nm;
  std::vector<char> keep(nv, 0);
  std::vector<char> &in_solid = nm.in_solid;
  in_solid.assign(nv, 0);
  for (size_t k = 0; k < nc; ++k)
    if (!fluid[k])
      for (int v : cells[k])
        keep[v] = in_solid[v] = 1;
  for (auto &t : boundary)
    for (int v : t)
      keep[v] = 1;
  std::vector<int> &new_index = nm.new_index, &old_of = nm.old_of;
  new_index.assign(nv, -1);
  std::vector<Point> &y = nm.y; // new vertex positions (= the new reference)
  // A solid vertex goes where the solid is: its material position plus the converged
  // displacement D_n.  The mesh followed the step's predicted displacement (the geometry is
  // explicit), which misses D_n by the predictor's error; a new reference there would make the
  // next step's mesh move by that error however small the step (a fresh sliver inverted at any
  // dt).  Here the next step's mesh moves by dt V_n + O(dt^2).
  double shift = 0;
  for (size_t v = 0; v < nv; ++v)
    if (keep[v]) {
      new_index[v] = (int)y.size();
      Point p = x[v];
      double vals[9];
      if (in_solid[v]) {
        if (!node_values(old.dofs, Xref[v].data(), vals))
          throw std::logic_error("remesh: a solid vertex has no displacement in the state");
        double s2 = 0;
        for (int d = 0; d < 3; ++d) {
          p[d] = V.values[6 * v + 3 + d] + vals[6 + d];
          s2 += (p[d] - x[v][d]) * (p[d] - x[v][d]);
        }
        shift = std::max(shift, std::sqrt(s2));
      }
      y.push_back(p);
      old_of.push_back((int)v);
    }
  rep.solid_shift = shift;
  nm.n_kept = y.size();
  std::vector<Tri> btris;
  std::vector<Point> inward; // unit normal into the fluid per boundary triangle
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
  std::vector<Tet> new_fluid = mesh_volume(y, btris, bmask, inward, o, rep);
  rep.mesh_seconds = MPI_Wtime() - m0;

  // The new fluid cells' boundary must be the old boundary, triangle for triangle.
  {
    std::map<Tri, int> c2;
    for (auto &t : new_fluid)
      for (auto &f : TET_FACE)
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
  std::vector<Tet> &tets = nm.cells;
  tets = new_fluid;
  nm.n_fluid = new_fluid.size();
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
  return transfer_state(om, nm, old, rep);
}

} // namespace
} // namespace remeshing

using namespace remeshing;

RemeshOptions RemeshOptions::from_options() {
  RemeshOptions o;
  o.hmax = opt::nonnegative("ale_remesh_hmax", 0.0);
  o.verbose = opt::integer_at_least("ale_remesh_verbose", 0, 0) != 0;
  o.test_fault = (int)opt::integer_at_least("ale_remesh_test_fault", 0, 0);
  o.gap_cells = opt::nonnegative("ale_remesh_gap_cells", 2.0);
  o.flip_skewness = opt::nonnegative("ale_remesh_flip_skewness", 0.8);
  o.project = opt::flag("ale_remesh_project", true);
  if (o.flip_skewness >= 1)
    throw InputError("-ale_remesh_flip_skewness must be below 1 (0 turns the flips off)");
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
  s.lumped = state.lumped; // boundary models (a Windkessel) do not see the mesh
  long counts[3] = {rep.gap_vertices, rep.flips, rep.splits};
  MPI_Bcast(counts, 3, MPI_LONG, 0, comm);
  rep.gap_vertices = counts[0], rep.flips = counts[1], rep.splits = counts[2];
  double r[13] = {rep.skewness_gmsh,
                  (double)rep.fluid_cells_before,
                  (double)rep.fluid_cells_after,
                  rep.skewness_before,
                  rep.skewness_after,
                  rep.volume_before,
                  rep.volume_after,
                  rep.kinetic_before,
                  rep.kinetic_after,
                  rep.divergence_before,
                  rep.divergence_after,
                  rep.mesh_seconds,
                  rep.solid_shift};
  MPI_Bcast(r, 13, MPI_DOUBLE, 0, comm);
  rep.skewness_gmsh = r[0];
  rep.fluid_cells_before = std::lround(r[1]), rep.fluid_cells_after = std::lround(r[2]);
  rep.skewness_before = r[3], rep.skewness_after = r[4], rep.volume_before = r[5];
  rep.volume_after = r[6], rep.kinetic_before = r[7], rep.kinetic_after = r[8];
  rep.divergence_before = r[9], rep.divergence_after = r[10], rep.mesh_seconds = r[11];
  rep.solid_shift = r[12];
  rep.memory_mb = peak_memory_mb();
  return s;
}

} // namespace fsi
