#include "fsi/physics/contact_surface.hpp"
#include "fsi/discretization/p2tet.hpp"
#include "fsi/mpi_gather.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace fsi {

namespace {

int find_root(std::vector<int> &parent, int i) {
  while (parent[i] != i)
    i = parent[i] = parent[parent[i]];
  return i;
}

} // namespace

ContactSurface::ContactSurface(const Space &space, const Mesh &mesh, const std::string &group,
                               const std::vector<PetscInt> &solid_cells,
                               const std::vector<double> &material_X)
    : space_(space), material_X_(material_X) {
  comm_ = PetscObjectComm((PetscObject)space.dm);
  std::vector<char> in_solid(space.n_cells(), 0);
  for (PetscInt k : solid_cells)
    in_solid[k] = 1;
  const auto faces = space.boundary_faces(mesh, group, &in_solid);

  // This rank's nodes (unique by local dof) and faces as global dofs.
  std::map<PetscInt, int> mine;
  std::vector<long long> my_faces;
  for (auto &f : faces)
    for (int b = 0; b < 6; ++b) {
      const PetscInt vd = f.vdof[b];
      if (!mine.count(vd)) {
        mine[vd] = (int)my_vdof_.size();
        my_vdof_.push_back(vd);
        if (b < 3)
          my_vertices_.push_back({f.vertex[b], -1});
        else
          my_vertices_.push_back({f.vertex[TRI_EDGE[b - 3][0]], f.vertex[TRI_EDGE[b - 3][1]]});
      }
      my_faces.push_back(space.local_to_global[vd]);
    }
  for (PetscInt vd :
       my_vdof_) // the pattern and the Jacobian address a node's 3 dofs as g, g+1, g+2
    if (space.local_to_global[vd + 1] != space.local_to_global[vd] + 1 ||
        space.local_to_global[vd + 2] != space.local_to_global[vd] + 2)
      throw PetscFailure(
          "internal: a velocity node's dofs are not consecutive in the global numbering");
  std::vector<long long> my_g(my_vdof_.size());
  std::vector<double> my_X(3 * my_vdof_.size());
  for (size_t i = 0; i < my_vdof_.size(); ++i) {
    my_g[i] = space.local_to_global[my_vdof_[i]];
    for (int d = 0; d < 3; ++d) {
      const auto &v = my_vertices_[i];
      my_X[3 * i + d] = v[1] < 0 ? material_X[3 * v[0] + d]
                                 : 0.5 * (material_X[3 * v[0] + d] + material_X[3 * v[1] + d]);
    }
  }
  const auto all_g = all_gather(comm_, my_g, MPI_LONG_LONG);
  const auto all_X = all_gather(comm_, my_X, MPI_DOUBLE);
  const auto all_faces = all_gather(comm_, my_faces, MPI_LONG_LONG);
  counts_ = counts_of(comm_, 3 * (int)my_vdof_.size());
  displs_ = displacements(counts_);

  // The gathered node list, in rank order; a node seen by several ranks appears once.
  std::unordered_map<long long, int> index;
  std::vector<double> X0;
  my_index_.resize(all_g.size());
  for (size_t i = 0; i < all_g.size(); ++i) {
    auto it = index.find(all_g[i]);
    if (it == index.end()) {
      it = index.emplace(all_g[i], (int)gdof_.size()).first;
      gdof_.push_back((PetscInt)all_g[i]);
      X0.insert(X0.end(), &all_X[3 * i], &all_X[3 * i] + 3);
    }
    my_index_[i] = it->second; // position i of the gathered array is node my_index_[i]
  }
  x_ = X0;
  const int nn = (int)gdof_.size();

  // Each P2 face as 4 flat triangles through its 6 nodes (edges 01, 02, 12 are nodes 3, 4, 5).
  static const int SUB[4][3] = {{0, 3, 4}, {3, 1, 5}, {4, 5, 2}, {3, 5, 4}};
  area_.assign(nn, 0.0);
  std::vector<int> parent(nn);
  std::iota(parent.begin(), parent.end(), 0);
  for (size_t f = 0; f < all_faces.size() / 6; ++f) {
    int node[6];
    for (int b = 0; b < 6; ++b)
      node[b] = index.at(all_faces[6 * f + b]);
    for (auto &s : SUB) {
      std::array<int, 3> t = {node[s[0]], node[s[1]], node[s[2]]};
      tri_.push_back(t);
      double e1[3], e2[3];
      for (int d = 0; d < 3; ++d) {
        e1[d] = X0[3 * t[1] + d] - X0[3 * t[0] + d];
        e2[d] = X0[3 * t[2] + d] - X0[3 * t[0] + d];
      }
      const double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
                   cz = e1[0] * e2[1] - e1[1] * e2[0];
      const double a = 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
      for (int k = 0; k < 3; ++k)
        area_[t[k]] += a / 3;
    }
    for (int b = 1; b < 6; ++b)
      parent[find_root(parent, node[b])] = find_root(parent, node[0]);
  }
  std::map<int, int> comp_id; // roots numbered in node order: the same on every rank
  comp_.resize(nn);
  for (int i = 0; i < nn; ++i) {
    const int r = find_root(parent, i);
    if (!comp_id.count(r)) comp_id[r] = (int)comp_id.size();
    comp_[i] = comp_id[r];
  }
  n_components_ = (int)comp_id.size();

  // Rows this rank owns.
  std::unordered_map<PetscInt, PetscInt> g2l;
  for (PetscInt i = 0; i < space.n_local; ++i)
    if (space.owned(i)) g2l[space.local_to_global[i]] = i;
  owned_.assign(nn, -1);
  for (int i = 0; i < nn; ++i) {
    auto it = g2l.find(gdof_[i]);
    if (it != g2l.end()) owned_[i] = it->second;
  }
}

void ContactSurface::update(const StepContext &ctx) {
  std::vector<double> mine(3 * my_vdof_.size());
  for (size_t i = 0; i < my_vdof_.size(); ++i) {
    const auto &v = my_vertices_[i];
    for (int d = 0; d < 3; ++d) {
      const double X = v[1] < 0 ? material_X_[3 * v[0] + d]
                                : 0.5 * (material_X_[3 * v[0] + d] + material_X_[3 * v[1] + d]);
      mine[3 * i + d] = X + ctx.u_af(my_vdof_[i] + d);
    }
  }
  std::vector<double> all(displs_.back() + counts_.back());
  MPI_Allgatherv(mine.data(), (int)mine.size(), MPI_DOUBLE, all.data(), counts_.data(),
                 displs_.data(), MPI_DOUBLE, comm_);
  for (size_t i = 0; i < my_index_.size(); ++i)
    for (int d = 0; d < 3; ++d)
      x_[3 * my_index_[i] + d] = all[3 * i + d];
}

void ContactSurface::bin(double radius) {
  bins_.build(x_, tri_, radius);
}

void ContactSurface::near(const double p[3], const std::function<void(int)> &f) const {
  bins_.near(p, f);
}

} // namespace fsi
