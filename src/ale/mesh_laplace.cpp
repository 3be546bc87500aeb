// Laplace (optionally Jacobian-stiffened) mesh motion: see mesh_motion.hpp.  P1 on the vertices,
// three components, one constant matrix assembled once on the reference mesh (Dirichlet rows and
// columns eliminated once); each step is one linear solve with the new boundary data.
#include "fsi/ale/mesh_motion.hpp"
#include "fsi/discretization/p2tet.hpp"
#include "fsi/discretization/sparsity.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <cmath>

namespace fsi {
namespace {

// Closure vertices of the faces of `label_name` (consistent over ranks), as a local vertex mask.
std::vector<char> face_vertices(const Mesh &mesh, const Space &space, const std::string &name) {
  std::vector<char> mask(space.n_vertices(), 0);
  for (auto &n : space.boundary_velocity_nodes(mesh, name))
    if (n.vb < 0) mask[n.va] = 1;
  return mask;
}

class LaplaceMotion : public MeshMotion {
public:
  LaplaceMotion(const Mesh &mesh, const Space &space, const std::vector<PetscInt> &fluid_cells,
                const std::vector<double> &material_X);
  ~LaplaceMotion() override;
  std::string name() const override {
    return chi_ > 0 ? "Jacobian-stiffened Laplace smoothing" : "Laplace smoothing";
  }
  bool follows_solid() const override { return true; }
  void displacement(double t, const PetscScalar *solid, std::vector<double> &d) override;
  void set_guess(const std::vector<double> &d) override;

private:
  const Space &space_;
  double chi_ = 0;
  std::vector<PetscInt> gidx_; // compact global vertex index per local vertex
  std::vector<PetscInt> vdof_; // velocity dof of each local vertex (reads the solid displacement)
  std::vector<char> solid_;    // local vertex touches a solid (non-fluid) cell
  std::vector<double> offset_; // X - material_X: where a remesh put the ALE reference of a
                               // solid vertex (0 on a first mesh)
  std::vector<PetscInt> rows_; // owned Dirichlet rows (global)
  std::vector<int> row_vc_;    // their local (3 * vertex + component)
  Mat A_ = nullptr, A0_ = nullptr;
  KSP ksp_ = nullptr;
  Vec x_ = nullptr, b_ = nullptr, g_ = nullptr, xloc_ = nullptr;
  VecScatter scatter_ = nullptr;
};

LaplaceMotion::LaplaceMotion(const Mesh &mesh, const Space &space,
                             const std::vector<PetscInt> &fluid_cells,
                             const std::vector<double> &material_X)
    : space_(space) {
  offset_.resize(space.X.size());
  for (size_t i = 0; i < offset_.size(); ++i)
    offset_[i] = space.X[i] - material_X[i];
  MPI_Comm comm = PetscObjectComm((PetscObject)space.dm);
  chi_ = opt::nonnegative("ale_stiffening", 0.0);
  const PetscInt nv = space.n_vertices();
  PetscSection ls;
  FSI_CALL(DMGetLocalSection(space.dm, &ls));
  std::vector<PetscInt> pdof(nv);
  vdof_.resize(nv);
  for (PetscInt v = 0; v < nv; ++v) {
    FSI_CALL(PetscSectionGetFieldOffset(ls, v + space.vStart, 0, &vdof_[v]));
    FSI_CALL(PetscSectionGetFieldOffset(ls, v + space.vStart, 1, &pdof[v]));
  }
  // Compact numbering of vertices: owners number theirs, ghosts learn theirs by a scatter.
  PetscInt nown = 0;
  for (PetscInt v = 0; v < nv; ++v)
    nown += space.owned(pdof[v]);
  const PetscInt start = rank_offset(comm, nown);
  {
    Vec g = space.create_global(), l = space.create_local();
    PetscScalar *ga;
    FSI_CALL(VecGetArray(g, &ga));
    PetscInt k = start;
    for (PetscInt v = 0; v < nv; ++v)
      if (space.owned(pdof[v])) ga[space.local_to_global[pdof[v]] - space.rstart] = (double)k++;
    FSI_CALL(VecRestoreArray(g, &ga));
    space.to_local(g, l);
    const PetscScalar *la;
    FSI_CALL(VecGetArrayRead(l, &la));
    gidx_.resize(nv);
    for (PetscInt v = 0; v < nv; ++v)
      gidx_[v] = (PetscInt)std::llround(PetscRealPart(la[pdof[v]]));
    FSI_CALL(VecRestoreArrayRead(l, &la));
    FSI_CALL(VecDestroy(&g));
    FSI_CALL(VecDestroy(&l));
  }

  // Which vertices are held, and how.
  std::vector<PetscInt> others;
  {
    std::vector<char> is_fluid(space.n_cells(), 0);
    for (PetscInt k : fluid_cells)
      is_fluid[k] = 1;
    for (PetscInt k = 0; k < space.n_cells(); ++k)
      if (!is_fluid[k]) others.push_back(k);
  }
  const std::vector<char> pmask = space.pressure_dofs_of(others);
  solid_.resize(nv);
  for (PetscInt v = 0; v < nv; ++v)
    solid_[v] = pmask[pdof[v]];
  // Exterior faces, split into slip faces (-ale_slip_boundaries) and fixed ones.
  DM dm = space.dm;
  const auto slip = opt::list("ale_slip_boundaries");
  mesh.require_groups(slip, "-ale_slip_boundaries");
  PetscBool has;
  FSI_CALL(DMHasLabel(dm, "__ale_fixed", &has));
  if (!has) {
    // Exterior faces: one supporting cell over all ranks.  (PETSc 3.18's DMPlexMarkBoundaryFaces
    // also marks faces on the partition boundary, which made the mesh motion partition
    // dependent.)  Support counts are summed over the point SF: leaves to roots and back.
    PetscInt pStart, pEnd, fStart, fEnd;
    FSI_CALL(DMPlexGetChart(dm, &pStart, &pEnd));
    FSI_CALL(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
    std::vector<PetscInt> local(pEnd - pStart, 0), total;
    for (PetscInt f = fStart; f < fEnd; ++f)
      FSI_CALL(DMPlexGetSupportSize(dm, f, &local[f - pStart]));
    total = local;
    PetscSF sf;
    FSI_CALL(DMGetPointSF(dm, &sf));
    FSI_CALL(PetscSFReduceBegin(sf, MPIU_INT, local.data(), total.data(), MPI_SUM));
    FSI_CALL(PetscSFReduceEnd(sf, MPIU_INT, local.data(), total.data(), MPI_SUM));
    FSI_CALL(PetscSFBcastBegin(sf, MPIU_INT, total.data(), total.data(), MPI_REPLACE));
    FSI_CALL(PetscSFBcastEnd(sf, MPIU_INT, total.data(), total.data(), MPI_REPLACE));
    DMLabel fixed;
    FSI_CALL(DMCreateLabel(dm, "__ale_fixed"));
    FSI_CALL(DMGetLabel(dm, "__ale_fixed", &fixed));
    std::vector<DMLabel> slip_labels; // fetched once: mesh.label() is collective
    for (auto &s : slip)
      slip_labels.push_back(mesh.label(s));
    for (PetscInt f = fStart; f < fEnd; ++f) {
      if (total[f - pStart] != 1) continue;
      bool on_slip = false;
      for (DMLabel sl : slip_labels) {
        PetscInt sv;
        FSI_CALL(DMLabelGetValue(sl, f, &sv));
        on_slip = on_slip || sv >= 0;
      }
      if (!on_slip) FSI_CALL(DMLabelSetValue(fixed, f, 1));
    }
  }
  const std::vector<char> fixed = face_vertices(mesh, space, "__ale_fixed");
  std::vector<int> slip_axis(nv, -1);
  for (auto &s : slip) {
    // The plane's normal axis, agreed over ranks.
    double nsum[3] = {0, 0, 0}, g[3];
    for (auto &f : space.boundary_faces(mesh, s)) {
      double n[3];
      outward_normal(f, space.X.data(), n);
      for (int d = 0; d < 3; ++d)
        nsum[d] = std::max(nsum[d], std::fabs(n[d]));
    }
    MPI_Allreduce(nsum, g, 3, MPI_DOUBLE, MPI_MAX, comm);
    const int axis = (int)(std::max_element(g, g + 3) - g);
    int bad = 0;
    for (auto &f : space.boundary_faces(mesh, s)) {
      double n[3];
      outward_normal(f, space.X.data(), n);
      bad += std::fabs(std::fabs(n[axis]) - 1) > 1e-6;
    }
    int gbad;
    MPI_Allreduce(&bad, &gbad, 1, MPI_INT, MPI_SUM, comm);
    if (gbad)
      throw InputError("-ale_slip_boundaries: boundary '" + s +
                       "' is not a plane normal to x, y or z (slip needs an axis-aligned plane)");
    const auto on = face_vertices(mesh, space, s);
    for (PetscInt v = 0; v < nv; ++v)
      if (on[v]) slip_axis[v] = axis;
  }
  for (PetscInt v = 0; v < nv; ++v) {
    if (!space.owned(pdof[v])) continue;
    for (int i = 0; i < 3; ++i)
      if (solid_[v] || fixed[v] || slip_axis[v] == i) {
        rows_.push_back(3 * gidx_[v] + i);
        row_vc_.push_back(3 * (int)v + i);
      }
  }

  // The matrix: sum over fluid cells of k_e int grad(l_a) . grad(l_b), per component.
  double vmax = 0;
  for (PetscInt k : fluid_cells) {
    double X[4][3];
    space.cell_points(k, space.X.data(), X);
    TetGeometry g;
    g.set(X);
    vmax = std::max(vmax, g.absdet / 6);
  }
  double gvmax;
  MPI_Allreduce(&vmax, &gvmax, 1, MPI_DOUBLE, MPI_MAX, comm);
  // Its pattern: every vertex of a fluid cell couples with every other (all components).
  std::vector<PetscInt> l2g(3 * nv), cell_dofs;
  for (PetscInt v = 0; v < nv; ++v)
    for (int i = 0; i < 3; ++i)
      l2g[3 * v + i] = 3 * gidx_[v] + i;
  cell_dofs.reserve(12 * fluid_cells.size());
  for (PetscInt k : fluid_cells)
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i)
        cell_dofs.push_back(3 * (PetscInt)space.cell_vertex[4 * k + a] + i);
  SparsityPattern pattern(comm, l2g, 3 * start, 3 * nown);
  pattern.add_elements(cell_dofs, 12);
  FSI_CALL(MatCreate(comm, &A0_));
  FSI_CALL(MatSetSizes(A0_, 3 * nown, 3 * nown, PETSC_DETERMINE, PETSC_DETERMINE));
  FSI_CALL(MatSetBlockSize(A0_, 3));
  FSI_CALL(MatSetType(A0_, MATAIJ));
  pattern.preallocate(A0_);
  for (PetscInt k : fluid_cells) {
    double X[4][3], K[12][12] = {};
    PetscInt idx[12];
    space.cell_points(k, space.X.data(), X);
    TetGeometry g;
    g.set(X);
    const double V = g.absdet / 6, kk = std::pow(gvmax / V, chi_);
    for (int a = 0; a < 4; ++a) {
      const PetscInt gv = gidx_[space.cell_vertex[4 * k + a]];
      for (int i = 0; i < 3; ++i)
        idx[3 * a + i] = 3 * gv + i;
      for (int b = 0; b < 4; ++b) {
        const double s =
            kk * V *
            (g.grad_lambda[a][0] * g.grad_lambda[b][0] + g.grad_lambda[a][1] * g.grad_lambda[b][1] +
             g.grad_lambda[a][2] * g.grad_lambda[b][2]);
        for (int i = 0; i < 3; ++i)
          K[3 * a + i][3 * b + i] = s;
      }
    }
    FSI_CALL(MatSetValues(A0_, 12, idx, 12, idx, &K[0][0], ADD_VALUES));
  }
  FSI_CALL(MatAssemblyBegin(A0_, MAT_FINAL_ASSEMBLY));
  FSI_CALL(MatAssemblyEnd(A0_, MAT_FINAL_ASSEMBLY));
  FSI_CALL(MatDuplicate(A0_, MAT_COPY_VALUES, &A_));
  FSI_CALL(MatZeroRowsColumns(A_, (PetscInt)rows_.size(), rows_.data(), 1.0, nullptr, nullptr));
  FSI_CALL(MatCreateVecs(A_, &x_, &b_));
  FSI_CALL(VecDuplicate(x_, &g_));
  FSI_CALL(VecZeroEntries(x_));
  FSI_CALL(KSPCreate(comm, &ksp_));
  FSI_CALL(KSPSetOptionsPrefix(ksp_, "ale_"));
  FSI_CALL(KSPSetOperators(ksp_, A_, A_));
  FSI_CALL(KSPSetType(ksp_, KSPCG));
  FSI_CALL(KSPSetTolerances(ksp_, 1e-10, 1e-30, PETSC_DEFAULT, 500));
  PC pc;
  FSI_CALL(KSPGetPC(ksp_, &pc));
  FSI_CALL(PCSetType(pc, PCGAMG));
  FSI_CALL(KSPSetInitialGuessNonzero(ksp_, PETSC_TRUE));
  FSI_CALL(KSPSetFromOptions(ksp_));
  // Global solution -> 3 values per local vertex.
  std::vector<PetscInt> from(3 * nv);
  for (PetscInt v = 0; v < nv; ++v)
    for (int i = 0; i < 3; ++i)
      from[3 * v + i] = 3 * gidx_[v] + i;
  IS isf;
  FSI_CALL(ISCreateGeneral(PETSC_COMM_SELF, 3 * nv, from.data(), PETSC_COPY_VALUES, &isf));
  FSI_CALL(VecCreateSeq(PETSC_COMM_SELF, 3 * nv, &xloc_));
  FSI_CALL(VecScatterCreate(x_, isf, xloc_, nullptr, &scatter_));
  FSI_CALL(ISDestroy(&isf));
}

LaplaceMotion::~LaplaceMotion() {
  if (ksp_) KSPDestroy(&ksp_);
  if (A_) MatDestroy(&A_);
  if (A0_) MatDestroy(&A0_);
  Vec *vs[] = {&x_, &b_, &g_, &xloc_};
  for (auto v : vs)
    if (*v) VecDestroy(v);
  if (scatter_) VecScatterDestroy(&scatter_);
}

void LaplaceMotion::set_guess(const std::vector<double> &d) {
  PetscInt lo, hi;
  FSI_CALL(VecGetOwnershipRange(x_, &lo, &hi));
  PetscScalar *x;
  FSI_CALL(VecGetArray(x_, &x));
  for (size_t v = 0; v < gidx_.size(); ++v)
    for (int i = 0; i < 3; ++i) {
      const PetscInt r = 3 * gidx_[v] + i;
      if (r >= lo && r < hi) x[r - lo] = d[3 * v + i];
    }
  FSI_CALL(VecRestoreArray(x_, &x));
}

void LaplaceMotion::displacement(double, const PetscScalar *solid, std::vector<double> &d) {
  // Boundary data g (solid displacement on solid vertices, 0 elsewhere), b = -A0 g, b_D = g_D.
  FSI_CALL(VecZeroEntries(g_));
  std::vector<PetscScalar> vals(rows_.size());
  for (size_t r = 0; r < rows_.size(); ++r) {
    const int v = row_vc_[r] / 3, i = row_vc_[r] % 3;
    // mesh displacement = current position - ALE reference = u_solid - (X - material_X)
    vals[r] = solid_[v] && solid ? solid[vdof_[v] + i] - offset_[3 * v + i] : 0.0;
  }
  FSI_CALL(VecSetValues(g_, (PetscInt)rows_.size(), rows_.data(), vals.data(), INSERT_VALUES));
  FSI_CALL(VecAssemblyBegin(g_));
  FSI_CALL(VecAssemblyEnd(g_));
  FSI_CALL(MatMult(A0_, g_, b_));
  FSI_CALL(VecScale(b_, -1.0));
  FSI_CALL(VecSetValues(b_, (PetscInt)rows_.size(), rows_.data(), vals.data(), INSERT_VALUES));
  FSI_CALL(VecAssemblyBegin(b_));
  FSI_CALL(VecAssemblyEnd(b_));
  FSI_CALL(VecSetValues(x_, (PetscInt)rows_.size(), rows_.data(), vals.data(), INSERT_VALUES));
  FSI_CALL(VecAssemblyBegin(x_));
  FSI_CALL(VecAssemblyEnd(x_));
  FSI_CALL(KSPSolve(ksp_, b_, x_));
  KSPConvergedReason reason;
  FSI_CALL(KSPGetConvergedReason(ksp_, &reason));
  if (reason < 0)
    throw SolveError(std::string("mesh motion solve failed: ") + KSPConvergedReasons[reason]);
  FSI_CALL(VecScatterBegin(scatter_, x_, xloc_, INSERT_VALUES, SCATTER_FORWARD));
  FSI_CALL(VecScatterEnd(scatter_, x_, xloc_, INSERT_VALUES, SCATTER_FORWARD));
  const PetscScalar *xa;
  FSI_CALL(VecGetArrayRead(xloc_, &xa));
  d.resize(3 * space_.n_vertices());
  for (size_t k = 0; k < d.size(); ++k)
    d[k] = PetscRealPart(xa[k]);
  FSI_CALL(VecRestoreArrayRead(xloc_, &xa));
}

} // namespace

std::unique_ptr<MeshMotion> make_laplace_motion(const Mesh &mesh, const Space &space,
                                                const std::vector<PetscInt> &fluid_cells,
                                                const std::vector<double> &material_X) {
  return std::make_unique<LaplaceMotion>(mesh, space, fluid_cells, material_X);
}

} // namespace fsi
