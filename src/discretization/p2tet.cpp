#include "fsi/discretization/p2tet.hpp"
#include <cmath>

namespace fsi {

static QuadRule simplex_rule(int dim, int degree) {
  PetscQuadrature q;
  FSI_CALL(PetscDTSimplexQuadrature(dim, degree, PETSCDTSIMPLEXQUAD_MINSYM, &q));
  PetscInt qdim, nc, np;
  const PetscReal *x, *w;
  FSI_CALL(PetscQuadratureGetData(q, &qdim, &nc, &np, &x, &w));
  // PETSc's reference simplex is the bi-unit one: vertices (-1,..), (1,-1,..), ...
  QuadRule r;
  double wsum = 0;
  for (PetscInt p = 0; p < np; ++p)
    wsum += w[p];
  const double ref_measure = dim == 3 ? 1.0 / 6.0 : 0.5;
  for (PetscInt p = 0; p < np; ++p) {
    std::array<double, 4> l{0, 0, 0, 0};
    double s = 0;
    for (int d = 0; d < dim; ++d) {
      l[d + 1] = 0.5 * (x[p * dim + d] + 1.0);
      s += l[d + 1];
    }
    l[0] = 1.0 - s;
    r.lambda.push_back(l);
    r.weight.push_back(w[p] * ref_measure / wsum);
  }
  FSI_CALL(PetscQuadratureDestroy(&q));
  return r;
}

QuadRule tet_rule(int degree) {
  return simplex_rule(3, degree);
}
QuadRule tri_rule(int degree) {
  return simplex_rule(2, degree);
}

P2Integrals::P2Integrals(const QuadRule &rule) {
  for (size_t q = 0; q < rule.weight.size(); ++q) {
    const double w = rule.weight[q], *l = rule.lambda[q].data();
    double N[10], dN[10][3], D[10][4];
    const double gl[4][3] = {};
    p2_tet(l, gl, N, dN);
    p2_tet_dlambda(l, D);
    for (int a = 0; a < 10; ++a) {
      for (int b = 0; b < 10; ++b) {
        M[a][b] += w * N[a] * N[b];
        for (int k = 0; k < 4; ++k)
          T[k][a][b] += w * l[k] * N[a] * N[b];
      }
      for (int k = 0; k < 4; ++k)
        for (int b = 0; b < 4; ++b)
          P[k][a][b] += w * l[b] * D[a][k];
    }
  }
}

void TetGeometry::set(const double X[4][3]) {
  double J[3][3]; // columns: X1-X0, X2-X0, X3-X0
  for (int d = 0; d < 3; ++d)
    for (int k = 0; k < 3; ++k)
      J[d][k] = X[k + 1][d] - X[0][d];
  detJ = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
         J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
         J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
  absdet = std::fabs(detJ);
  const double inv = 1.0 / detJ;
  // Rows of J^{-1} are the gradients of lambda_1..3.
  double Ji[3][3];
  Ji[0][0] = (J[1][1] * J[2][2] - J[1][2] * J[2][1]) * inv;
  Ji[0][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) * inv;
  Ji[0][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) * inv;
  Ji[1][0] = (J[1][2] * J[2][0] - J[1][0] * J[2][2]) * inv;
  Ji[1][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) * inv;
  Ji[1][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) * inv;
  Ji[2][0] = (J[1][0] * J[2][1] - J[1][1] * J[2][0]) * inv;
  Ji[2][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) * inv;
  Ji[2][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) * inv;
  for (int d = 0; d < 3; ++d) {
    grad_lambda[0][d] = -(Ji[0][d] + Ji[1][d] + Ji[2][d]);
    for (int k = 0; k < 3; ++k)
      grad_lambda[k + 1][d] = Ji[k][d];
  }
}

} // namespace fsi
