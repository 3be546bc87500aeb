// Reference P2/P1 Lagrange elements on straight-sided tetrahedra and triangles, in barycentric
// coordinates, with symmetric quadrature from PETSc (MINSYM rules).  Node numbering used by all
// our kernels: 4 vertices (0-3), then 6 edges, edge k joining vertices EDGE[k][0], EDGE[k][1].
#pragma once
#include "fsi/common.hpp"
#include <array>
#include <vector>

namespace fsi {

struct QuadRule {
  std::vector<std::array<double, 4>> lambda; // barycentric coords (3 used on triangles)
  std::vector<double> weight;                // sums to the reference measure: 1/6 tet, 1/2 tri
};

QuadRule tet_rule(int degree);
QuadRule tri_rule(int degree);

constexpr int TET_EDGE[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
constexpr int TRI_EDGE[3][2] = {{0, 1}, {0, 2}, {1, 2}};

// Affine tetrahedron: physical gradients of barycentric coordinates and |det J| (= 6 volume).
struct TetGeometry {
  double grad_lambda[4][3];
  double detJ; // signed
  double absdet;
  void set(const double X[4][3]);
};

// c = a x b
inline void cross(const double a[3], const double b[3], double c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

// P2 values and physical gradients at a point with barycentric coordinates l.
inline void p2_tet(const double l[4], const double gl[4][3], double N[10], double dN[10][3]) {
  for (int i = 0; i < 4; ++i) {
    N[i] = l[i] * (2 * l[i] - 1);
    for (int d = 0; d < 3; ++d)
      dN[i][d] = (4 * l[i] - 1) * gl[i][d];
  }
  for (int k = 0; k < 6; ++k) {
    const int a = TET_EDGE[k][0], b = TET_EDGE[k][1];
    N[4 + k] = 4 * l[a] * l[b];
    for (int d = 0; d < 3; ++d)
      dN[4 + k][d] = 4 * (l[a] * gl[b][d] + l[b] * gl[a][d]);
  }
}

// D[a][k] = dN_a/dlambda_k at a point: the P2 basis above as a function of all four barycentric
// coordinates (grad N_a = sum_k D[a][k] grad lambda_k); linear in lambda.
inline void p2_tet_dlambda(const double l[4], double D[10][4]) {
  for (int a = 0; a < 10; ++a)
    for (int k = 0; k < 4; ++k)
      D[a][k] = 0;
  for (int i = 0; i < 4; ++i)
    D[i][i] = 4 * l[i] - 1;
  for (int e = 0; e < 6; ++e) {
    D[4 + e][TET_EDGE[e][0]] = 4 * l[TET_EDGE[e][1]];
    D[4 + e][TET_EDGE[e][1]] = 4 * l[TET_EDGE[e][0]];
  }
}

// Reference-tet integrals of the P2 basis with a quadrature rule (exact where the rule's degree
// reaches the integrand's): mass M[a][b] = sum w N_a N_b (degree 4), lambda-weighted mass
// T[k][a][b] = sum w lambda_k N_a N_b (degree 5), and P[k][a][b] = sum w lambda_b dN_a/dlambda_k
// (degree 2), so that int lambda_b dN_a/dx_i = |det| sum_k grad lambda_k,i P[k][a][b] on a
// straight-sided tet.
struct P2Integrals {
  double M[10][10] = {}, T[4][10][10] = {}, P[4][10][4] = {};
  P2Integrals() = default;
  explicit P2Integrals(const QuadRule &rule);
};

inline void p2_tri(const double l[3], double N[6]) {
  for (int i = 0; i < 3; ++i)
    N[i] = l[i] * (2 * l[i] - 1);
  for (int k = 0; k < 3; ++k)
    N[3 + k] = 4 * l[TRI_EDGE[k][0]] * l[TRI_EDGE[k][1]];
}

} // namespace fsi
