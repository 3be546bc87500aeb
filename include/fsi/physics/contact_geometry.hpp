// The distance from a point to a triangle, with its exact gradient and Hessian in the 12
// coordinates (point, then the three corners): the gap function of node-to-surface contact.
// The closest point lies in one of seven regions (the face, an edge, a corner: Ericson,
// Real-Time Collision Detection, 5.1.5); inside a region the distance is smooth and is
// differentiated by Jet (jet.hpp); across regions it is C1, which is what a Newton tangent needs.
#pragma once

namespace fsi {

enum class TriRegion { face, edge01, edge02, edge12, corner0, corner1, corner2 };

// Distance |p - closest point of triangle (a, b, c)| and the region of the closest point.
double point_triangle_distance(const double p[3], const double a[3], const double b[3],
                               const double c[3], TriRegion &region);

// The same distance d with g = dd/dx and H = d2d/dx2, x = (p, a, b, c) (12 numbers), inside the
// given region.  Requires d > 0.
void point_triangle_distance_derivatives(const double p[3], const double a[3], const double b[3],
                                         const double c[3], TriRegion region, double &d,
                                         double g[12], double H[12][12]);

// A straight line (the valve's axis): its distance from a point with the exact gradient and
// Hessian, for contact against a virtual rod of radius `radius` around it.
struct AxisLine {
  double point[3] = {0, 0, 0};
  double dir[3] = {0, 0, 1}; // unit
  double radius = 0;         // rod radius [m]; 0: no rod
  bool on() const { return radius > 0; }
  // Distance r from p to the line; with g non-null also dr/dp (3) and, with H, d2r/dp2 (3x3).
  // The derivatives require r > 0.
  double distance(const double p[3], double g[3] = nullptr, double H[3][3] = nullptr) const;
};

} // namespace fsi
