#include "fsi/ale/velocity_projection.hpp"
#include "fsi/discretization/p2tet.hpp"

#include <cmath>
#include <cstring>
#include <string>
#include <utility>

namespace fsi {

namespace {

// P2 reference integrals (mass, pressure coupling), exact with a degree-4 rule.
const P2Integrals &reference() {
  static const P2Integrals ref(tet_rule(4));
  return ref;
}

struct Cell {
  TetGeometry g;
  PetscInt vdof[10], pdof[4];
  double B[10][3][4]; // int lambda_b dN_a/dx_i
};

void cell(const Space &space, PetscInt k, const std::vector<double> &X, const P2Integrals &ref,
          Cell &c) {
  double P[4][3];
  for (int i = 0; i < 4; ++i) {
    const int v = space.cell_vertex[4 * k + i];
    for (int d = 0; d < 3; ++d)
      P[i][d] = X[3 * v + d];
    c.pdof[i] = space.cell_pdof[4 * k + i];
  }
  c.g.set(P);
  for (int a = 0; a < 10; ++a) {
    c.vdof[a] = space.cell_vdof[10 * k + a];
    for (int i = 0; i < 3; ++i)
      for (int b = 0; b < 4; ++b) {
        double s = 0;
        for (int kk = 0; kk < 4; ++kk)
          s += c.g.grad_lambda[kk][i] * ref.P[kk][a][b];
        c.B[a][i][b] = c.g.absdet * s;
      }
  }
}

// The weak divergence (see the header) of the velocity in the local vector v.
double weak_divergence(const Space &space, const std::vector<PetscInt> &cells,
                       const std::vector<double> &X, const P2Integrals &ref, const PetscScalar *v,
                       MPI_Comm comm) {
  std::vector<double> r(space.n_local, 0.0), m(space.n_local, 0.0);
  double grad2 = 0, volume = 0;
  static const QuadRule rule = tet_rule(2);
  for (PetscInt k : cells) {
    Cell c;
    cell(space, k, X, ref, c);
    for (int b = 0; b < 4; ++b) {
      m[c.pdof[b]] += c.g.absdet / 24; // int lambda_b
      for (int a = 0; a < 10; ++a)
        for (int i = 0; i < 3; ++i)
          r[c.pdof[b]] += c.B[a][i][b] * PetscRealPart(v[c.vdof[a] + i]);
    }
    volume += c.g.absdet / 6;
    for (size_t q = 0; q < rule.weight.size(); ++q) {
      double N[10], dN[10][3];
      p2_tet(rule.lambda[q].data(), c.g.grad_lambda, N, dN);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          double G = 0;
          for (int a = 0; a < 10; ++a)
            G += PetscRealPart(v[c.vdof[a] + i]) * dN[a][j];
          grad2 += rule.weight[q] * c.g.absdet * G * G;
        }
    }
  }
  // Pressure dofs shared between ranks: sum their pieces on the owner through the global vector.
  Vec rg, mg, rl, ml;
  rl = space.create_local();
  FSI_CALL(VecDuplicate(rl, &ml));
  rg = space.create_global();
  FSI_CALL(VecDuplicate(rg, &mg));
  PetscScalar *a;
  FSI_CALL(VecGetArray(rl, &a));
  std::copy(r.begin(), r.end(), a);
  FSI_CALL(VecRestoreArray(rl, &a));
  FSI_CALL(VecGetArray(ml, &a));
  std::copy(m.begin(), m.end(), a);
  FSI_CALL(VecRestoreArray(ml, &a));
  FSI_CALL(VecSet(rg, 0));
  FSI_CALL(VecSet(mg, 0));
  space.add_to_global(rl, rg);
  space.add_to_global(ml, mg);
  double s[4] = {0, 0, grad2, volume}, t[4];
  FSI_CALL(VecDot(rg, rg, &s[0]));
  FSI_CALL(VecDot(mg, mg, &s[1]));
  for (Vec *w : {&rg, &mg, &rl, &ml})
    VecDestroy(w);
  MPI_Allreduce(&s[2], &t[2], 2, MPI_DOUBLE, MPI_SUM, comm);
  t[0] = s[0], t[1] = s[1]; // VecDot is global already
  if (t[1] <= 0 || t[2] <= 0) return 0;
  return std::sqrt(t[0] / t[1]) / std::sqrt(t[2] / t[3]);
}

} // namespace

double measure_weak_divergence(const Space &space, const std::vector<PetscInt> &cells,
                               const std::vector<double> &X, Vec V) {
  const P2Integrals &ref = reference();
  Vec Vl = space.create_local();
  space.to_local(V, Vl);
  const PetscScalar *vl;
  FSI_CALL(VecGetArrayRead(Vl, &vl));
  const double d = weak_divergence(space, cells, X, ref, vl, PetscObjectComm((PetscObject)V));
  FSI_CALL(VecRestoreArrayRead(Vl, &vl));
  FSI_CALL(VecDestroy(&Vl));
  return d;
}

ProjectionReport project_divergence_free(const Space &space, const std::vector<PetscInt> &cells,
                                         const std::vector<double> &X,
                                         const std::vector<char> &fixed_local, Mat pattern, Vec V) {
  const double t0 = MPI_Wtime();
  const P2Integrals &ref = reference();
  MPI_Comm comm = PetscObjectComm((PetscObject)V);
  ProjectionReport rep;
  Vec Vl = space.create_local();
  space.to_local(V, Vl);
  const PetscScalar *vl;
  FSI_CALL(VecGetArrayRead(Vl, &vl));
  rep.before = weak_divergence(space, cells, X, ref, vl, comm);

  // Which local dofs take part: velocity dofs of fluid cells (free unless fixed) and the
  // pressure dofs of fluid vertices; every other row is an identity.
  std::vector<char> in_fluid(space.n_local, 0), velocity(space.n_local, 0);
  for (PetscInt k : cells) {
    for (int a = 0; a < 10; ++a)
      for (int i = 0; i < 3; ++i)
        in_fluid[space.cell_vdof[10 * k + a] + i] = velocity[space.cell_vdof[10 * k + a] + i] = 1;
    for (int b = 0; b < 4; ++b)
      in_fluid[space.cell_pdof[4 * k + b]] = 1;
  }
  // The same marks on every rank that sees a dof (its owner may hold no fluid or solid cell).
  in_fluid = space.mark_on_all_ranks(in_fluid);
  velocity = space.mark_on_all_ranks(velocity);
  const std::vector<char> keep_value = space.mark_on_all_ranks(fixed_local);
  Mat A;
  FSI_CALL(MatDuplicate(pattern, MAT_DO_NOT_COPY_VALUES, &A));
  FSI_CALL(MatSetOption(A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  std::vector<PetscInt> dofs(34);
  Vec b, x, bl;
  FSI_CALL(VecDuplicate(V, &b));
  FSI_CALL(VecDuplicate(V, &x));
  bl = space.create_local();
  PetscScalar *bla;
  FSI_CALL(VecGetArray(bl, &bla));
  constexpr double eps = 1e-9;
  double K[34][34];
  for (PetscInt k : cells) {
    Cell c;
    cell(space, k, X, ref, c);
    std::memset(K, 0, sizeof K);
    for (int a = 0; a < 10; ++a)
      for (int i = 0; i < 3; ++i) {
        const PetscInt d = c.vdof[a] + i;
        if (keep_value[d]) continue; // its row is an identity (below)
        double rhs = 0;
        for (int bb = 0; bb < 10; ++bb) {
          const double m = c.g.absdet * ref.M[a][bb];
          K[3 * a + i][3 * bb + i] = m;
          rhs += m * PetscRealPart(vl[c.vdof[bb] + i]);
        }
        bla[d] += rhs;
        for (int p = 0; p < 4; ++p)
          K[3 * a + i][30 + p] = c.B[a][i][p];
      }
    for (int p = 0; p < 4; ++p) {
      for (int a = 0; a < 10; ++a)
        for (int i = 0; i < 3; ++i)
          K[30 + p][3 * a + i] = c.B[a][i][p];
      for (int q = 0; q < 4; ++q) // -eps |det| int lambda_p lambda_q
        K[30 + p][30 + q] = -eps * c.g.absdet * (p == q ? 1.0 / 60 : 1.0 / 120);
    }
    for (int a = 0; a < 10; ++a)
      for (int i = 0; i < 3; ++i)
        dofs[3 * a + i] = c.vdof[a] + i;
    for (int p = 0; p < 4; ++p)
      dofs[30 + p] = c.pdof[p];
    FSI_CALL(MatSetValuesLocal(A, 34, dofs.data(), 34, dofs.data(), &K[0][0], ADD_VALUES));
  }
  FSI_CALL(VecRestoreArray(bl, &bla));
  FSI_CALL(VecSet(b, 0));
  space.add_to_global(bl, b);
  FSI_CALL(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  FSI_CALL(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  // Identity rows: fixed velocity dofs keep their value, dofs outside the fluid their own
  // (pressure included: the multiplier's solution there is discarded anyway).
  // A multiplier whose every neighbouring velocity dof is fixed (a vertex of cells squeezed
  // between the leaflets and the wall, all their nodes on the interface) constrains nothing: its
  // row would be a zero pivot (measured on the valve at 381 ms: MUMPS failed).  It is held at 0.
  std::vector<char> coupled(space.n_local, 0);
  for (PetscInt k : cells) {
    bool free = false;
    for (int a = 0; a < 10 && !free; ++a)
      for (int i = 0; i < 3; ++i)
        free = free || !keep_value[space.cell_vdof[10 * k + a] + i];
    if (free)
      for (int b = 0; b < 4; ++b)
        coupled[space.cell_pdof[4 * k + b]] = 1;
  }
  coupled = space.mark_on_all_ranks(coupled);
  // Only the free rows and columns are solved for: the held dofs' values move to the right-hand
  // side (b_f - A_fk x_k), and the factorisation sees neither the solid's nor the contact pairs'
  // part of the Jacobian's pattern (explicit zeros that a factorisation would fill in).
  // held, is_v: per owned row (global index - rstart).
  std::vector<char> held(space.n_owned, 0), is_v(space.n_owned, 0);
  for (PetscInt i = 0; i < space.n_local; ++i) {
    if (!space.owned(i)) continue;
    const PetscInt r = space.local_to_global[i] - space.rstart;
    const bool idle_multiplier = in_fluid[i] && !velocity[i] && !coupled[i];
    held[r] = !in_fluid[i] || keep_value[i] || idle_multiplier;
    is_v[r] = velocity[i];
  }
  std::vector<PetscInt> free_rows;
  for (PetscInt r = 0; r < space.n_owned; ++r)
    if (!held[r]) free_rows.push_back(space.rstart + r);
  IS is_free;
  FSI_CALL(ISCreateGeneral(comm, (PetscInt)free_rows.size(), free_rows.data(), PETSC_COPY_VALUES,
                           &is_free));
  Vec xk, r;
  FSI_CALL(VecDuplicate(V, &xk));
  FSI_CALL(VecDuplicate(V, &r));
  {
    const PetscScalar *va;
    PetscScalar *xa;
    FSI_CALL(VecGetArrayRead(V, &va));
    FSI_CALL(VecGetArray(xk, &xa));
    for (PetscInt i = 0; i < space.n_owned; ++i)
      xa[i] = held[i] ? va[i] : 0.0;
    FSI_CALL(VecRestoreArray(xk, &xa));
    FSI_CALL(VecRestoreArrayRead(V, &va));
  }
  FSI_CALL(MatMult(A, xk, r));
  FSI_CALL(VecAXPY(b, -1.0, r));
  Mat Af;
  FSI_CALL(MatCreateSubMatrix(A, is_free, is_free, MAT_INITIAL_MATRIX, &Af));
  FSI_CALL(MatDestroy(&A));
  Vec bf, xf;
  FSI_CALL(VecGetSubVector(b, is_free, &bf));
  FSI_CALL(MatCreateVecs(Af, &xf, nullptr));

  KSP ksp;
  FSI_CALL(KSPCreate(comm, &ksp));
  FSI_CALL(KSPSetOptionsPrefix(ksp, "remesh_projection_"));
  FSI_CALL(KSPSetOperators(ksp, Af, Af));
  // Default: MUMPS LU (exact: the run is the same on any rank count, restarts reproduce).
  // -remesh_projection_pc_type fieldsplit solves it iteratively, to its tolerance (FGMRES on a
  // Schur factorisation: the velocity mass by CG + Jacobi, the P1 Schur complement
  // B diag(M)^-1 B^T by BoomerAMG; docs/remeshing.md): 2x faster on the CI valve, 5x on the
  // paper-size one, where the LU needs 9 GB per rank (the preset fieldsplit_fsi_lu does this).
  FSI_CALL(KSPSetType(ksp, KSPPREONLY));
  PC pc;
  FSI_CALL(KSPGetPC(ksp, &pc));
  FSI_CALL(PCSetType(pc, PCLU));
  FSI_CALL(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  FSI_CALL(KSPSetFromOptions(ksp));
  PetscBool fs;
  FSI_CALL(PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &fs));
  if (fs) {      // the velocity mass, then the multiplier, numbered within the free dofs
    PetscInt lo; // the free dofs' numbering: this rank's start
    FSI_CALL(VecGetOwnershipRange(xf, &lo, nullptr));
    std::vector<PetscInt> v, p;
    for (size_t k = 0; k < free_rows.size(); ++k)
      (is_v[free_rows[k] - space.rstart] ? v : p).push_back(lo + (PetscInt)k);
    IS iv, ip;
    FSI_CALL(ISCreateGeneral(comm, (PetscInt)v.size(), v.data(), PETSC_COPY_VALUES, &iv));
    FSI_CALL(ISCreateGeneral(comm, (PetscInt)p.size(), p.data(), PETSC_COPY_VALUES, &ip));
    FSI_CALL(PCFieldSplitSetIS(pc, "velocity", iv));
    FSI_CALL(PCFieldSplitSetIS(pc, "pressure", ip));
    FSI_CALL(ISDestroy(&iv));
    FSI_CALL(ISDestroy(&ip));
  }
  FSI_CALL(KSPSolve(ksp, bf, xf));
  FSI_CALL(VecRestoreSubVector(b, is_free, &bf));
  FSI_CALL(VecCopy(V, x)); // held dofs keep their value; the free ones from the solve
  {
    Vec xs;
    FSI_CALL(VecGetSubVector(x, is_free, &xs));
    FSI_CALL(VecCopy(xf, xs));
    FSI_CALL(VecRestoreSubVector(x, is_free, &xs));
  }
  FSI_CALL(VecDestroy(&xf));
  FSI_CALL(VecDestroy(&xk));
  FSI_CALL(VecDestroy(&r));
  FSI_CALL(ISDestroy(&is_free));
  A = Af;
  KSPConvergedReason reason;
  FSI_CALL(KSPGetConvergedReason(ksp, &reason));
  FSI_CALL(KSPDestroy(&ksp));
  FSI_CALL(MatDestroy(&A));
  FSI_CALL(VecRestoreArrayRead(Vl, &vl));
  if (reason < 0) { // the interpolated velocity stays (its divergence is reported)
    for (Vec *w : {&b, &x, &bl, &Vl})
      VecDestroy(w);
    rep.after = rep.before;
    rep.failure = KSPConvergedReasons[reason];
    rep.seconds = MPI_Wtime() - t0;
    return rep;
  }
  // New velocities into V (owned, free fluid velocity dofs); pressure and the rest unchanged.
  PetscScalar *va;
  const PetscScalar *xa;
  FSI_CALL(VecGetArray(V, &va));
  FSI_CALL(VecGetArrayRead(x, &xa));
  for (PetscInt i = 0; i < space.n_local; ++i) {
    if (!space.owned(i) || !velocity[i] || keep_value[i]) continue;
    const PetscInt g = space.local_to_global[i] - space.rstart;
    va[g] = xa[g];
  }
  FSI_CALL(VecRestoreArrayRead(x, &xa));
  FSI_CALL(VecRestoreArray(V, &va));
  space.to_local(V, Vl);
  FSI_CALL(VecGetArrayRead(Vl, &vl));
  rep.after = weak_divergence(space, cells, X, ref, vl, comm);
  FSI_CALL(VecRestoreArrayRead(Vl, &vl));
  for (Vec *w : {&b, &x, &bl, &Vl})
    VecDestroy(w);
  rep.seconds = MPI_Wtime() - t0;
  return rep;
}

} // namespace fsi
