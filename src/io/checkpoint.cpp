#include "fsi/io/checkpoint.hpp"
#include "fsi/discretization/p2tet.hpp"

namespace fsi {

Checkpoint::Checkpoint(const Space &space)
    : comm_(PetscObjectComm((PetscObject)space.dm)), space_(space) {
  // Every owned dof once, keyed by its node's reference position and its component.
  std::vector<char> seen(space.n_local, 0);
  auto add = [&](PetscInt dof, const double x[3], int comp) {
    if (seen[dof] || !space.owned(dof)) return;
    seen[dof] = 1;
    dof_keys_.insert(dof_keys_.end(), {x[0], x[1], x[2], (double)comp});
    dof_index_.push_back(space.local_to_global[dof] - space.rstart);
  };
  for (PetscInt k = 0; k < space.n_cells(); ++k) {
    double P[4][3];
    space.cell_points(k, space.X.data(), P);
    for (int a = 0; a < 10; ++a) {
      double x[3];
      for (int d = 0; d < 3; ++d)
        x[d] = a < 4 ? P[a][d] : 0.5 * (P[TET_EDGE[a - 4][0]][d] + P[TET_EDGE[a - 4][1]][d]);
      for (int c = 0; c < 3; ++c)
        add(space.cell_vdof[10 * k + a] + c, x, c);
    }
    for (int i = 0; i < 4; ++i) {
      const PetscInt p = space.cell_pdof[4 * k + i];
      if (seen[p] || !space.owned(p)) continue;
      add(p, P[i], 3); // a vertex is owned where its pressure dof is: list it once, here
      vertex_keys_.insert(vertex_keys_.end(), {P[i][0], P[i][1], P[i][2]});
      vertex_local_.push_back(space.cell_vertex[4 * k + i]);
    }
  }
}

void Checkpoint::capture(const std::vector<Vec> &vecs, const std::vector<double> &dm,
                         const std::vector<double> &material_X, RunState &s) const {
  const size_t nd = dof_index_.size(), nv = vecs.size();
  std::vector<double> vals(nv * nd);
  for (size_t j = 0; j < nv; ++j) {
    const PetscScalar *a;
    FSI_CALL(VecGetArrayRead(vecs[j], &a));
    for (size_t i = 0; i < nd; ++i)
      vals[nv * i + j] = PetscRealPart(a[dof_index_[i]]);
    FSI_CALL(VecRestoreArrayRead(vecs[j], &a));
  }
  s.dofs = gather_sorted(comm_, dof_keys_, vals, 4, (int)nv);
  s.n_dofs = space_.n_velocity + space_.n_pressure;
  std::vector<double> vv(6 * vertex_local_.size());
  for (size_t i = 0; i < vertex_local_.size(); ++i)
    for (int d = 0; d < 3; ++d) {
      vv[6 * i + d] = dm[3 * vertex_local_[i] + d];
      vv[6 * i + 3 + d] = material_X[3 * vertex_local_[i] + d];
    }
  s.vertices = gather_sorted(comm_, vertex_keys_, vv, 3, 6);
}

void Checkpoint::mismatch(const RunState &s) const {
  const long n_dofs = space_.n_velocity + space_.n_pressure;
  throw InputError("the state to resume from was written for another mesh (" +
                   std::to_string(s.n_dofs) + " dofs there, " + std::to_string(n_dofs) +
                   " here, or node positions differ): restart with the same mesh options");
}

void Checkpoint::vertices(const RunState &s, std::vector<double> &dm,
                          std::vector<double> &material_X) const {
  if (s.n_dofs != space_.n_velocity + space_.n_pressure) mismatch(s);
  std::vector<double> vv;
  if (scatter_by_key(comm_, s.vertices, vertex_keys_, vv, 3, 6)) mismatch(s);
  // Every local vertex: owned ones from the state, ghosts from their owner through a dof-sized
  // vector (the pressure dof of each vertex).
  dm.assign(3 * space_.n_vertices(), 0.0);
  material_X = space_.X;
  Vec g = space_.create_global(), l = space_.create_local();
  PetscSection ls;
  FSI_CALL(DMGetLocalSection(space_.dm, &ls));
  for (int comp = 0; comp < 6; ++comp) {
    PetscScalar *ga;
    FSI_CALL(VecGetArray(g, &ga));
    for (size_t i = 0; i < vertex_local_.size(); ++i) {
      PetscInt off;
      FSI_CALL(PetscSectionGetFieldOffset(ls, space_.vStart + vertex_local_[i], 1, &off));
      ga[space_.local_to_global[off] - space_.rstart] = vv[6 * i + comp];
    }
    FSI_CALL(VecRestoreArray(g, &ga));
    space_.to_local(g, l);
    const PetscScalar *la;
    FSI_CALL(VecGetArrayRead(l, &la));
    std::vector<double> &out = comp < 3 ? dm : material_X;
    for (PetscInt v = 0; v < space_.n_vertices(); ++v) {
      PetscInt off;
      FSI_CALL(PetscSectionGetFieldOffset(ls, space_.vStart + v, 1, &off));
      out[3 * v + comp % 3] = PetscRealPart(la[off]);
    }
    FSI_CALL(VecRestoreArrayRead(l, &la));
  }
  FSI_CALL(VecDestroy(&g));
  FSI_CALL(VecDestroy(&l));
}

void Checkpoint::dofs(const RunState &s, const std::vector<Vec> &vecs) const {
  const int nv = (int)vecs.size();
  std::vector<double> vals;
  if (scatter_by_key(comm_, s.dofs, dof_keys_, vals, 4, nv)) mismatch(s);
  for (int j = 0; j < nv; ++j) {
    PetscScalar *a;
    FSI_CALL(VecGetArray(vecs[j], &a));
    for (size_t i = 0; i < dof_index_.size(); ++i)
      a[dof_index_[i]] = vals[nv * i + j];
    FSI_CALL(VecRestoreArray(vecs[j], &a));
  }
}

} // namespace fsi
