// A uniform grid over a set of triangles for near-neighbour queries: near(p) lists every triangle
// whose bounding box, grown by the build radius, holds p.  Used by the contact surface (rebuilt
// as the leaflets move) and the rigid contact walls (built once per mesh).
#pragma once
#include <array>
#include <functional>
#include <vector>

namespace fsi {

class TriangleBins {
public:
  // x: 3 coordinates per node; tri: node indices of each triangle.
  void build(const std::vector<double> &x, const std::vector<std::array<int, 3>> &tri,
             double radius);
  void near(const double p[3], const std::function<void(int)> &f) const;

private:
  double lo_[3] = {0, 0, 0}, h_ = 1;
  int nb_[3] = {1, 1, 1};
  std::vector<int> start_ = {0, 0}, tri_;
};

} // namespace fsi
