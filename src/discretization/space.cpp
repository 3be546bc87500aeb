#include "fsi/discretization/space.hpp"
#include "fsi/discretization/p2tet.hpp"

#include <algorithm>
#include <cmath>

namespace fsi {

double outward_normal(const BoundaryFace &f, const double *X, double n[3]) {
  double e1[3], e2[3];
  for (int d = 0; d < 3; ++d) {
    e1[d] = X[3 * f.vertex[1] + d] - X[3 * f.vertex[0] + d];
    e2[d] = X[3 * f.vertex[2] + d] - X[3 * f.vertex[0] + d];
  }
  n[0] = e1[1] * e2[2] - e1[2] * e2[1];
  n[1] = e1[2] * e2[0] - e1[0] * e2[2];
  n[2] = e1[0] * e2[1] - e1[1] * e2[0];
  double out = 0;
  for (int d = 0; d < 3; ++d)
    out += n[d] * (X[3 * f.vertex[0] + d] - X[3 * f.opposite + d]);
  const double J2 = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (int d = 0; d < 3; ++d)
    n[d] = (out < 0 ? -n[d] : n[d]) / J2;
  return J2;
}

// Every local dof must map to the global dof of the same node: write each node's position into
// its owned global entry, scatter back, compare.  Cheap, and it catches any numbering mistake.
void Space::check_numbering() const {
  PetscSection ls;
  FSI_CALL(DMGetLocalSection(dm, &ls));
  std::vector<double> pos(n_local, 0.0);
  for (PetscInt p = vStart; p < eEnd; ++p) {
    if (p >= vEnd && p < eStart) continue;
    double x[3];
    if (p < vEnd) {
      for (int d = 0; d < 3; ++d)
        x[d] = X[3 * (p - vStart) + d];
    } else {
      const PetscInt *cone;
      FSI_CALL(DMPlexGetCone(dm, p, &cone));
      for (int d = 0; d < 3; ++d)
        x[d] = 0.5 * (X[3 * (cone[0] - vStart) + d] + X[3 * (cone[1] - vStart) + d]);
    }
    PetscInt dof, off;
    FSI_CALL(PetscSectionGetDof(ls, p, &dof));
    FSI_CALL(PetscSectionGetOffset(ls, p, &off));
    for (PetscInt i = 0; i < dof; ++i)
      pos[off + i] = x[i % 3] + 10 * x[(i + 1) % 3] + 100 * x[(i + 2) % 3];
  }
  Vec g = create_global(), l = create_local();
  PetscScalar *ga, *la;
  FSI_CALL(VecGetArray(g, &ga));
  for (PetscInt i = 0; i < n_local; ++i)
    if (owned(i)) ga[local_to_global[i] - rstart] = pos[i];
  FSI_CALL(VecRestoreArray(g, &ga));
  to_local(g, l);
  FSI_CALL(VecGetArray(l, &la));
  int bad = 0, gbad;
  for (PetscInt i = 0; i < n_local; ++i)
    if (std::abs(PetscRealPart(la[i]) - pos[i]) > 1e-9 * (1 + std::abs(pos[i]))) ++bad;
  FSI_CALL(VecRestoreArray(l, &la));
  FSI_CALL(VecDestroy(&g));
  FSI_CALL(VecDestroy(&l));
  MPI_Allreduce(&bad, &gbad, 1, MPI_INT, MPI_SUM, PetscObjectComm((PetscObject)dm));
  if (gbad)
    throw PetscFailure("internal: " + std::to_string(gbad) +
                       " local dofs map to the wrong global dof");
}

Vec Space::create_global() const {
  Vec v;
  FSI_CALL(VecCreateMPI(PetscObjectComm((PetscObject)dm), n_owned, PETSC_DETERMINE, &v));
  return v;
}

Vec Space::create_local() const {
  Vec v;
  FSI_CALL(VecCreateSeq(PETSC_COMM_SELF, n_local, &v));
  return v;
}

void Space::to_local(Vec g, Vec l) const {
  FSI_CALL(VecScatterBegin(g2l, g, l, INSERT_VALUES, SCATTER_FORWARD));
  FSI_CALL(VecScatterEnd(g2l, g, l, INSERT_VALUES, SCATTER_FORWARD));
}

void Space::add_to_global(Vec l, Vec g) const {
  FSI_CALL(VecScatterBegin(g2l, l, g, ADD_VALUES, SCATTER_REVERSE));
  FSI_CALL(VecScatterEnd(g2l, l, g, ADD_VALUES, SCATTER_REVERSE));
}

Space::~Space() {
  if (g2l) VecScatterDestroy(&g2l);
  if (l2g) ISLocalToGlobalMappingDestroy(&l2g);
  if (is_velocity) ISDestroy(&is_velocity);
  if (is_pressure) ISDestroy(&is_pressure);
}

void Space::build(const Mesh &mesh) {
  dm = mesh.dm;
  PetscInt pStart, pEnd;
  FSI_CALL(DMPlexGetChart(dm, &pStart, &pEnd));
  FSI_CALL(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  FSI_CALL(DMPlexGetDepthStratum(dm, 1, &eStart, &eEnd));
  FSI_CALL(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));

  PetscSection s;
  FSI_CALL(PetscSectionCreate(PETSC_COMM_SELF, &s));
  FSI_CALL(PetscSectionSetNumFields(s, 2));
  FSI_CALL(PetscSectionSetFieldName(s, 0, "velocity"));
  FSI_CALL(PetscSectionSetFieldName(s, 1, "pressure"));
  FSI_CALL(PetscSectionSetFieldComponents(s, 0, 3));
  FSI_CALL(PetscSectionSetFieldComponents(s, 1, 1));
  FSI_CALL(PetscSectionSetChart(s, pStart, pEnd));
  for (PetscInt v = vStart; v < vEnd; ++v) {
    FSI_CALL(PetscSectionSetDof(s, v, 4));
    FSI_CALL(PetscSectionSetFieldDof(s, v, 0, 3));
    FSI_CALL(PetscSectionSetFieldDof(s, v, 1, 1));
  }
  for (PetscInt e = eStart; e < eEnd; ++e) {
    FSI_CALL(PetscSectionSetDof(s, e, 3));
    FSI_CALL(PetscSectionSetFieldDof(s, e, 0, 3));
  }
  FSI_CALL(PetscSectionSetUp(s));
  FSI_CALL(DMSetLocalSection(dm, s));
  FSI_CALL(PetscSectionDestroy(&s));
  FSI_CALL(DMSetUp(dm));

  // Global numbering, made here from the point SF: a point is owned unless it is a leaf of the
  // point SF; owned points are numbered in chart order; ghosts get their owner's offsets through
  // the SF.  (DMPlex's cached global section / local-to-global map from before our
  // DMSetLocalSection gave an inconsistent numbering in 3.18 on 2 ranks.)
  PetscSection ls;
  PetscSF pointSF;
  FSI_CALL(DMGetLocalSection(dm, &ls));
  FSI_CALL(DMGetPointSF(dm, &pointSF));
  FSI_CALL(PetscSectionGetStorageSize(ls, &n_local));
  MPI_Comm comm = PetscObjectComm((PetscObject)dm);
  PetscInt sf_roots;
  FSI_CALL(PetscSFGetGraph(pointSF, &sf_roots, nullptr, nullptr, nullptr));
  int rank;
  MPI_Comm_rank(comm, &rank);
  const PetscInt npts = pEnd - pStart;
  std::vector<char> ghost(npts, 0);
  {
    PetscInt nroots, nleaves;
    const PetscInt *leaves;
    const PetscSFNode *remote;
    FSI_CALL(PetscSFGetGraph(pointSF, &nroots, &nleaves, &leaves, &remote));
    for (PetscInt i = 0; i < (nleaves > 0 ? nleaves : 0); ++i) {
      const PetscInt p = leaves ? leaves[i] : i;
      if (remote[i].rank != rank) ghost[p - pStart] = 1;
    }
  }
  n_owned = 0;
  for (PetscInt p = pStart; p < pEnd; ++p) {
    PetscInt dof;
    FSI_CALL(PetscSectionGetDof(ls, p, &dof));
    if (!ghost[p - pStart]) n_owned += dof;
  }
  MPI_Scan(&n_owned, &rstart, 1, MPIU_INT, MPI_SUM, comm);
  rstart -= n_owned;
  std::vector<PetscInt> goff(npts, -1), gleaf(npts, -1);
  {
    PetscInt next = rstart;
    for (PetscInt p = pStart; p < pEnd; ++p) {
      PetscInt dof;
      FSI_CALL(PetscSectionGetDof(ls, p, &dof));
      if (!ghost[p - pStart]) goff[p - pStart] = next, next += dof;
    }
    gleaf = goff;
    if (sf_roots >= 0) {
      FSI_CALL(PetscSFBcastBegin(pointSF, MPIU_INT, goff.data(), gleaf.data(), MPI_REPLACE));
      FSI_CALL(PetscSFBcastEnd(pointSF, MPIU_INT, goff.data(), gleaf.data(), MPI_REPLACE));
    }
  }
  local_to_global.assign(n_local, -1);
  for (PetscInt p = pStart; p < pEnd; ++p) {
    PetscInt dof, loff;
    FSI_CALL(PetscSectionGetDof(ls, p, &dof));
    if (dof <= 0) continue;
    FSI_CALL(PetscSectionGetOffset(ls, p, &loff));
    const PetscInt g0 = ghost[p - pStart] ? gleaf[p - pStart] : goff[p - pStart];
    for (PetscInt i = 0; i < dof; ++i)
      local_to_global[loff + i] = g0 + i;
  }
  FSI_CALL(ISLocalToGlobalMappingCreate(PETSC_COMM_SELF, 1, n_local, local_to_global.data(),
                                        PETSC_COPY_VALUES, &l2g));
  {
    Vec gv = create_global(), lv = create_local();
    IS from, to;
    FSI_CALL(ISCreateGeneral(PETSC_COMM_SELF, n_local, local_to_global.data(), PETSC_COPY_VALUES,
                             &from));
    FSI_CALL(ISCreateStride(PETSC_COMM_SELF, n_local, 0, 1, &to));
    FSI_CALL(VecScatterCreate(gv, from, lv, to, &g2l));
    FSI_CALL(ISDestroy(&from));
    FSI_CALL(ISDestroy(&to));
    FSI_CALL(VecDestroy(&gv));
    FSI_CALL(VecDestroy(&lv));
  }

  // Field index sets over owned dofs.
  std::vector<PetscInt> iv, ip, vnode_points;
  for (PetscInt p = pStart; p < pEnd; ++p) {
    PetscInt dof;
    FSI_CALL(PetscSectionGetDof(ls, p, &dof));
    if (dof <= 0 || ghost[p - pStart]) continue;
    PetscInt fo;
    FSI_CALL(PetscSectionGetFieldOffset(ls, p, 0, &fo));
    for (int c = 0; c < 3; ++c)
      iv.push_back(local_to_global[fo + c]);
    vnode_points.push_back(p);
    if (p >= vStart && p < vEnd) {
      FSI_CALL(PetscSectionGetFieldOffset(ls, p, 1, &fo));
      ip.push_back(local_to_global[fo]);
    }
  }
  FSI_CALL(ISCreateGeneral(comm, (PetscInt)iv.size(), iv.data(), PETSC_COPY_VALUES, &is_velocity));
  FSI_CALL(ISSetBlockSize(is_velocity, 3));
  FSI_CALL(ISCreateGeneral(comm, (PetscInt)ip.size(), ip.data(), PETSC_COPY_VALUES, &is_pressure));
  FSI_CALL(ISGetSize(is_velocity, &n_velocity));
  FSI_CALL(ISGetSize(is_pressure, &n_pressure));

  // Reference coordinates of local vertices.
  Vec coords;
  PetscSection cs;
  const PetscScalar *ca;
  FSI_CALL(DMGetCoordinatesLocal(dm, &coords));
  FSI_CALL(DMGetCoordinateSection(dm, &cs));
  FSI_CALL(VecGetArrayRead(coords, &ca));
  X.resize(3 * n_vertices());
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscInt off;
    FSI_CALL(PetscSectionGetOffset(cs, v, &off));
    for (int d = 0; d < 3; ++d)
      X[3 * (v - vStart) + d] = PetscRealPart(ca[off + d]);
  }
  FSI_CALL(VecRestoreArrayRead(coords, &ca));
  // Positions of the owned velocity nodes in is_velocity order (vertex or edge midpoint).
  velocity_node_X.reserve(3 * vnode_points.size());
  for (PetscInt p : vnode_points) {
    if (p >= vStart && p < vEnd) {
      for (int d = 0; d < 3; ++d)
        velocity_node_X.push_back(X[3 * (p - vStart) + d]);
      continue;
    }
    const PetscInt *cone;
    FSI_CALL(DMPlexGetCone(dm, p, &cone));
    for (int d = 0; d < 3; ++d)
      velocity_node_X.push_back(0.5 *
                                (X[3 * (cone[0] - vStart) + d] + X[3 * (cone[1] - vStart) + d]));
  }

  check_numbering();

  // Per-cell node tables in our node order.
  const PetscInt nc = n_cells();
  cell_vertex.resize(4 * nc);
  cell_vdof.resize(10 * nc);
  cell_pdof.resize(4 * nc);
  for (PetscInt c = cStart; c < cEnd; ++c) {
    PetscInt ncl, *cl = nullptr;
    FSI_CALL(DMPlexGetTransitiveClosure(dm, c, PETSC_TRUE, &ncl, &cl));
    int nv = 0;
    PetscInt verts[4], edges[6];
    int ne = 0;
    for (PetscInt i = 0; i < ncl; ++i) {
      PetscInt p = cl[2 * i];
      if (p >= vStart && p < vEnd)
        verts[nv++] = p;
      else if (p >= eStart && p < eEnd)
        edges[ne++] = p;
    }
    FSI_CALL(DMPlexRestoreTransitiveClosure(dm, c, PETSC_TRUE, &ncl, &cl));
    if (nv != 4 || ne != 6)
      throw InputError("the mesh has a non-tetrahedral cell: fsi_app needs tetrahedra");
    const PetscInt k = c - cStart;
    for (int i = 0; i < 4; ++i) {
      cell_vertex[4 * k + i] = (int)(verts[i] - vStart);
      PetscInt off;
      FSI_CALL(PetscSectionGetFieldOffset(ls, verts[i], 0, &off));
      cell_vdof[10 * k + i] = off;
      FSI_CALL(PetscSectionGetFieldOffset(ls, verts[i], 1, &off));
      cell_pdof[4 * k + i] = off;
    }
    for (int j = 0; j < 6; ++j) {
      const PetscInt *cone;
      FSI_CALL(DMPlexGetCone(dm, edges[j], &cone));
      for (int m = 0; m < 6; ++m) {
        PetscInt a = verts[TET_EDGE[m][0]], b = verts[TET_EDGE[m][1]];
        if ((cone[0] == a && cone[1] == b) || (cone[0] == b && cone[1] == a)) {
          PetscInt off;
          FSI_CALL(PetscSectionGetFieldOffset(ls, edges[j], 0, &off));
          cell_vdof[10 * k + 4 + m] = off;
        }
      }
    }
  }
}

std::vector<BoundaryFace> Space::boundary_faces(const Mesh &mesh, const std::string &name,
                                                const std::vector<char> *region) const {
  DMLabel l = mesh.label(name);
  PetscSection ls;
  FSI_CALL(DMGetLocalSection(dm, &ls));
  PetscInt fStart, fEnd;
  FSI_CALL(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
  std::vector<BoundaryFace> out;
  for (PetscInt f = fStart; f < fEnd; ++f) {
    PetscInt val;
    FSI_CALL(DMLabelGetValue(l, f, &val));
    if (val < 0) continue;
    PetscInt ns;
    const PetscInt *supp;
    FSI_CALL(DMPlexGetSupportSize(dm, f, &ns));
    FSI_CALL(DMPlexGetSupport(dm, f, &supp));
    if (ns < 1) continue;
    // On an interface between regions the face belongs to the side in `region` (a face on a
    // partition boundary is seen by both ranks, each with its own cell).
    PetscInt cell = -1;
    for (PetscInt i = 0; i < ns; ++i)
      if (!region || (*region)[supp[i] - cStart]) {
        cell = supp[i] - cStart;
        break;
      }
    if (cell < 0) continue;
    BoundaryFace bf;
    bf.cell = cell;
    PetscInt ncl, *cl = nullptr;
    FSI_CALL(DMPlexGetTransitiveClosure(dm, f, PETSC_TRUE, &ncl, &cl));
    int nv = 0, ne = 0;
    PetscInt verts[3], edges[3];
    for (PetscInt i = 0; i < ncl; ++i) {
      PetscInt p = cl[2 * i];
      if (p >= vStart && p < vEnd)
        verts[nv++] = p;
      else if (p >= eStart && p < eEnd)
        edges[ne++] = p;
    }
    FSI_CALL(DMPlexRestoreTransitiveClosure(dm, f, PETSC_TRUE, &ncl, &cl));
    for (int i = 0; i < 3; ++i) {
      bf.vertex[i] = (int)(verts[i] - vStart);
      FSI_CALL(PetscSectionGetFieldOffset(ls, verts[i], 0, &bf.vdof[i]));
      FSI_CALL(PetscSectionGetFieldOffset(ls, verts[i], 1, &bf.pdof[i]));
    }
    for (int j = 0; j < 3; ++j) {
      const PetscInt *cone;
      FSI_CALL(DMPlexGetCone(dm, edges[j], &cone));
      for (int m = 0; m < 3; ++m) {
        PetscInt a = verts[TRI_EDGE[m][0]], b = verts[TRI_EDGE[m][1]];
        if ((cone[0] == a && cone[1] == b) || (cone[0] == b && cone[1] == a))
          FSI_CALL(PetscSectionGetFieldOffset(ls, edges[j], 0, &bf.vdof[3 + m]));
      }
    }
    bf.opposite = -1;
    for (int i = 0; i < 4; ++i) {
      int v = cell_vertex[4 * bf.cell + i];
      if (v != bf.vertex[0] && v != bf.vertex[1] && v != bf.vertex[2]) bf.opposite = v;
    }
    out.push_back(bf);
  }
  return out;
}

std::vector<DofNode> Space::boundary_velocity_nodes(const Mesh &mesh,
                                                    const std::string &name) const {
  DMLabel src = mesh.label(name);
  // A completed copy of the face label: closure points, synchronised over the point SF.
  const std::string cname = "__closure_" + name;
  PetscBool has;
  FSI_CALL(DMHasLabel(dm, cname.c_str(), &has));
  DMLabel l;
  if (!has) {
    FSI_CALL(DMCreateLabel(dm, cname.c_str()));
    FSI_CALL(DMGetLabel(dm, cname.c_str(), &l));
    PetscInt fStart, fEnd;
    FSI_CALL(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
    for (PetscInt f = fStart; f < fEnd; ++f) {
      PetscInt val;
      FSI_CALL(DMLabelGetValue(src, f, &val));
      if (val >= 0) FSI_CALL(DMLabelSetValue(l, f, 1));
    }
    FSI_CALL(DMPlexLabelComplete(dm, l));
  }
  FSI_CALL(DMGetLabel(dm, cname.c_str(), &l));
  PetscSection ls;
  FSI_CALL(DMGetLocalSection(dm, &ls));
  std::vector<DofNode> out;
  for (PetscInt p = vStart; p < vEnd; ++p) {
    PetscInt val;
    FSI_CALL(DMLabelGetValue(l, p, &val));
    if (val != 1) continue;
    DofNode n;
    FSI_CALL(PetscSectionGetFieldOffset(ls, p, 0, &n.dof));
    n.va = (int)(p - vStart);
    n.vb = -1;
    out.push_back(n);
  }
  for (PetscInt p = eStart; p < eEnd; ++p) {
    PetscInt val;
    FSI_CALL(DMLabelGetValue(l, p, &val));
    if (val != 1) continue;
    DofNode n;
    const PetscInt *cone;
    FSI_CALL(DMPlexGetCone(dm, p, &cone));
    FSI_CALL(PetscSectionGetFieldOffset(ls, p, 0, &n.dof));
    n.va = (int)(cone[0] - vStart);
    n.vb = (int)(cone[1] - vStart);
    out.push_back(n);
  }
  return out;
}

std::vector<char> Space::pressure_dofs_of(const std::vector<PetscInt> &cells) const {
  std::vector<char> marked(n_local, 0);
  for (PetscInt k : cells)
    for (int b = 0; b < 4; ++b)
      marked[cell_pdof[4 * k + b]] = 1;
  return mark_on_all_ranks(marked);
}

void compose_rigid_body_modes(IS is, const std::vector<double> &node_X) {
  MPI_Comm comm = PetscObjectComm((PetscObject)is);
  Vec X;
  FSI_CALL(
      VecCreateMPIWithArray(comm, 3, (PetscInt)node_X.size(), PETSC_DECIDE, node_X.data(), &X));
  MatNullSpace ns;
  FSI_CALL(MatNullSpaceCreateRigidBody(X, &ns));
  FSI_CALL(PetscObjectCompose((PetscObject)is, "nearnullspace", (PetscObject)ns));
  FSI_CALL(MatNullSpaceDestroy(&ns));
  FSI_CALL(VecDestroy(&X));
}

std::vector<char> Space::mark_on_all_ranks(const std::vector<char> &marked) const {
  // Mark locally, sum over ranks, read back.
  Vec l = create_local(), g = create_global();
  PetscScalar *la;
  FSI_CALL(VecZeroEntries(g));
  FSI_CALL(VecGetArray(l, &la));
  for (PetscInt d = 0; d < n_local; ++d)
    la[d] = marked[d] ? 1.0 : 0.0;
  FSI_CALL(VecRestoreArray(l, &la));
  add_to_global(l, g);
  to_local(g, l);
  std::vector<char> mask(n_local, 0);
  FSI_CALL(VecGetArray(l, &la));
  for (PetscInt d = 0; d < n_local; ++d)
    mask[d] = PetscRealPart(la[d]) > 0.5;
  FSI_CALL(VecRestoreArray(l, &la));
  FSI_CALL(VecDestroy(&l));
  FSI_CALL(VecDestroy(&g));
  return mask;
}

PetscInt Space::pinned_pressure_dof(int &vertex, const std::vector<char> *among) const {
  // The lexicographically smallest vertex (x, then y, then z): a choice that does not depend on
  // the partition, so 1 and 2 ranks solve the same discrete problem.
  MPI_Comm comm = PetscObjectComm((PetscObject)dm);
  PetscSection ls;
  FSI_CALL(DMGetLocalSection(dm, &ls));
  std::vector<char> allowed(n_vertices(), 1);
  if (among)
    for (PetscInt v = 0; v < n_vertices(); ++v) {
      PetscInt off;
      FSI_CALL(PetscSectionGetFieldOffset(ls, v + vStart, 1, &off));
      allowed[v] = (*among)[off];
    }
  double best[3];
  for (int d = 0; d < 3; ++d) {
    double mine = 1e300;
    for (PetscInt v = 0; v < n_vertices(); ++v) {
      bool ok = allowed[v];
      for (int e = 0; e < d; ++e)
        ok = ok && X[3 * v + e] == best[e];
      if (ok) mine = std::min(mine, X[3 * v + d]);
    }
    MPI_Allreduce(&mine, &best[d], 1, MPI_DOUBLE, MPI_MIN, comm);
  }
  for (PetscInt v = 0; v < n_vertices(); ++v)
    if (allowed[v] && X[3 * v] == best[0] && X[3 * v + 1] == best[1] && X[3 * v + 2] == best[2]) {
      PetscInt off;
      FSI_CALL(PetscSectionGetFieldOffset(ls, v + vStart, 1, &off));
      vertex = (int)v;
      return off;
    }
  vertex = -1;
  return -1;
}

} // namespace fsi
