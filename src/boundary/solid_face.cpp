#include "fsi/boundary/solid_face.hpp"
#include "fsi/discretization/p2tet.hpp"

namespace fsi {

void p2_tri_derivs(const double l[3], double dxi[6], double deta[6]) {
  const double dl_xi[3] = {-1, 1, 0}, dl_eta[3] = {-1, 0, 1};
  for (int i = 0; i < 3; ++i) {
    dxi[i] = (4 * l[i] - 1) * dl_xi[i];
    deta[i] = (4 * l[i] - 1) * dl_eta[i];
  }
  for (int k = 0; k < 3; ++k) {
    const int a = TRI_EDGE[k][0], b = TRI_EDGE[k][1];
    dxi[3 + k] = 4 * (dl_xi[a] * l[b] + l[a] * dl_xi[b]);
    deta[3 + k] = 4 * (dl_eta[a] * l[b] + l[a] * dl_eta[b]);
  }
}

void face_tangents(const double x[6][3], const double dxi[6], const double deta[6], double gx[3],
                   double ge[3]) {
  for (int d = 0; d < 3; ++d)
    gx[d] = ge[d] = 0;
  for (int a = 0; a < 6; ++a)
    for (int d = 0; d < 3; ++d)
      gx[d] += dxi[a] * x[a][d], ge[d] += deta[a] * x[a][d];
}

SolidFace solid_face(const std::vector<double> &material_X, const BoundaryFace &f) {
  SolidFace s;
  const double *X = material_X.data();
  for (int i = 0; i < 3; ++i)
    for (int d = 0; d < 3; ++d)
      s.X[i][d] = X[3 * f.vertex[i] + d];
  for (int k = 0; k < 3; ++k)
    for (int d = 0; d < 3; ++d)
      s.X[3 + k][d] = 0.5 * (s.X[TRI_EDGE[k][0]][d] + s.X[TRI_EDGE[k][1]][d]);
  double n[3];
  outward_normal(f, X, n);
  double e1[3], e2[3];
  for (int d = 0; d < 3; ++d)
    e1[d] = s.X[1][d] - s.X[0][d], e2[d] = s.X[2][d] - s.X[0][d];
  double c[3];
  cross(e1, e2, c);
  s.sign = c[0] * n[0] + c[1] * n[1] + c[2] * n[2] > 0 ? 1.0 : -1.0;
  return s;
}

} // namespace fsi
