#include "fsi/physics/interface_flux.hpp"

#include <cmath>

namespace fsi {

InterfaceMassFlux::InterfaceMassFlux(const Space &space, const Mesh &mesh, const std::string &name,
                                     const std::vector<PetscInt> &fluid_cells,
                                     const std::vector<double> &material_X)
    : space_(space), material_X_(material_X), name_(name), rule_(tri_rule(4)) {
  mesh.require_groups({name}, "-ale_interface");
  std::vector<char> in_fluid(space.n_cells(), 0);
  for (PetscInt k : fluid_cells)
    in_fluid[k] = 1;
  faces_ = space.boundary_faces(mesh, name, &in_fluid);
}

void InterfaceMassFlux::element_dofs(std::vector<PetscInt> &dofs, int &n) const {
  n = 21;
  dofs.clear();
  for (auto &f : faces_) {
    for (int a = 0; a < 3; ++a)
      dofs.push_back(f.pdof[a]);
    for (int b = 0; b < 6; ++b)
      for (int i = 0; i < 3; ++i)
        dofs.push_back(f.vdof[b] + i);
  }
}

// K[a][3b+i] = int_F(n+1) lambda_a N_b n_i dA, so that sum_b,i K v = int lambda_a v.n dA.
void InterfaceMassFlux::wall_flux(const StepContext &ctx, const BoundaryFace &f,
                                  double K[3][18]) const {
  double n[3];
  const double J2 = outward_normal(f, ctx.X_np1, n);
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 18; ++c)
      K[a][c] = 0;
  for (size_t q = 0; q < rule_.weight.size(); ++q) {
    const double *l = rule_.lambda[q].data();
    double N[6];
    p2_tri(l, N);
    const double w = rule_.weight[q] * J2;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 6; ++b)
        for (int i = 0; i < 3; ++i)
          K[a][3 * b + i] += w * l[a] * N[b] * n[i];
  }
}

// Swept volume of the face from X_n to X_n + delta (delta at the 3 vertices), weighted by
// lambda_a (S[a], outward positive), and its derivative dS[a][3 c + i] / d delta_c,i.
void InterfaceMassFlux::swept(const StepContext &ctx, const BoundaryFace &f, double S[3],
                              double dS[3][9]) const {
  // delta = X + u_{n+1}(U) - X_n: the wall follows the solid displacement of this iterate.
  double Xn[3][3], dl[3][3];
  for (int a = 0; a < 3; ++a)
    for (int d = 0; d < 3; ++d) {
      const int v = f.vertex[a];
      Xn[a][d] = ctx.X_np1[3 * v + d] - ctx.dt * ctx.W[3 * v + d];
      dl[a][d] = material_X_[3 * v + d] + ctx.u_np1(f.vdof[a] + d) - Xn[a][d];
    }
  double A[3], B[3], C[3], D[3];
  for (int d = 0; d < 3; ++d) {
    A[d] = Xn[1][d] - Xn[0][d], C[d] = Xn[2][d] - Xn[0][d];
    B[d] = dl[1][d] - dl[0][d], D[d] = dl[2][d] - dl[0][d];
  }
  // int_0^1 (x_xi x x_eta) ds = A x C + (A x D + B x C) / 2 + B x D / 3
  double AC[3], AD[3], BC[3], BD[3], m[3];
  cross(A, C, AC);
  cross(A, D, AD);
  cross(B, C, BC);
  cross(B, D, BD);
  for (int d = 0; d < 3; ++d)
    m[d] = AC[d] + 0.5 * (AD[d] + BC[d]) + BD[d] / 3;
  double n[3], e1[3], e2[3], c1[3];
  outward_normal(f, space_.X.data(), n); // orientation from the reference mesh
  for (int d = 0; d < 3; ++d) {
    e1[d] = space_.X[3 * f.vertex[1] + d] - space_.X[3 * f.vertex[0] + d];
    e2[d] = space_.X[3 * f.vertex[2] + d] - space_.X[3 * f.vertex[0] + d];
  }
  cross(e1, e2, c1);
  const double sign = c1[0] * n[0] + c1[1] * n[1] + c1[2] * n[2] > 0 ? 1.0 : -1.0;
  for (int a = 0; a < 3; ++a) {
    double g[3] = {0, 0, 0}; // sum_b M_ab delta_b, M = int_ref lambda_a lambda_b
    for (int b = 0; b < 3; ++b) {
      const double mab = a == b ? 1.0 / 12 : 1.0 / 24;
      for (int d = 0; d < 3; ++d)
        g[d] += mab * dl[b][d];
    }
    S[a] = sign * (g[0] * m[0] + g[1] * m[1] + g[2] * m[2]);
    double Cg[3], Dg[3], gA[3], gB[3], pB[3], pD[3];
    cross(C, g, Cg);
    cross(D, g, Dg);
    cross(g, A, gA);
    cross(g, B, gB);
    for (int d = 0; d < 3; ++d) {
      pB[d] = 0.5 * Cg[d] + Dg[d] / 3;
      pD[d] = 0.5 * gA[d] + gB[d] / 3;
    }
    for (int c = 0; c < 3; ++c) {
      const double mac = a == c ? 1.0 / 12 : 1.0 / 24;
      for (int d = 0; d < 3; ++d) {
        double v = mac * m[d];
        if (c == 0) v -= pB[d] + pD[d];
        if (c == 1) v += pB[d];
        if (c == 2) v += pD[d];
        dS[a][3 * c + d] = sign * v;
      }
    }
  }
}

void InterfaceMassFlux::add_residual(const StepContext &ctx, PetscScalar *F) {
  if (ctx.steady || !ctx.W) return;
  for (auto &f : faces_) {
    // + int q v.n on this face (cancels the wall flux in -int q div v) - swept volume / dt.
    double K[3][18], S[3], dS[3][9];
    wall_flux(ctx, f, K);
    swept(ctx, f, S, dS);
    for (int a = 0; a < 3; ++a) {
      double flux = 0;
      for (int c = 0; c < 18; ++c)
        flux += K[a][c] * PetscRealPart(ctx.U[f.vdof[c / 3] + c % 3]);
      F[f.pdof[a]] += flux - S[a] / ctx.dt;
    }
  }
}

void InterfaceMassFlux::add_jacobian(const StepContext &ctx, Mat J) {
  if (ctx.steady || !ctx.W) return;
  const std::vector<char> &mask = *ctx.is_dirichlet;
  const double du = ctx.beta * ctx.dt / ctx.gamma; // d u_{n+1} / d v_{n+1}
  for (auto &f : faces_) {
    double K[3][18], S[3], dS[3][9];
    wall_flux(ctx, f, K);
    swept(ctx, f, S, dS);
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 9; ++c) // vertex nodes are the face's first 3 velocity nodes
        K[a][c] -= dS[a][c] * du / ctx.dt;
    PetscInt rows[3], cols[18];
    for (int a = 0; a < 3; ++a)
      rows[a] = mask[f.pdof[a]] ? -1 : f.pdof[a];
    for (int c = 0; c < 18; ++c)
      cols[c] = f.vdof[c / 3] + c % 3;
    FSI_CALL(MatSetValuesLocal(J, 3, rows, 18, cols, &K[0][0], ADD_VALUES));
  }
}

} // namespace fsi
