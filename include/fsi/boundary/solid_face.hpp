// Geometry of a solid boundary face for loads on the deformed surface: the P2 triangle's node
// positions in the material reference and the derivatives of its shape functions.
#pragma once
#include "fsi/discretization/space.hpp"
#include <vector>

namespace fsi {

struct SolidFace {
  double X[6][3]; // material positions of the 6 nodes (vertices, edge midpoints)
  double sign;    // makes x_xi x x_eta point out of the solid
};
SolidFace solid_face(const std::vector<double> &material_X, const BoundaryFace &f);
// Derivatives of the P2 triangle shape functions with respect to (xi, eta),
// lambda = (1 - xi - eta, xi, eta).
void p2_tri_derivs(const double l[3], double dxi[6], double deta[6]);
// Tangents x_xi, x_eta of the deformed face x (6 nodes) at barycentric point l.
void face_tangents(const double x[6][3], const double dxi[6], const double deta[6], double gx[3],
                   double ge[3]);

} // namespace fsi
