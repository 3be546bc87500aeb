// Walls that hold their nodes: noslip (fluid, v = 0) and clamped (solid, u = 0 through v = 0), on
// the fixed components (default all).  A wall wins at nodes it shares with another Dirichlet
// boundary.
#include "fsi/boundary/boundary_condition.hpp"

namespace fsi {
namespace {

struct Wall : BoundaryCondition {
  std::string kind;
  Wall(const BoundarySetup &s, const char *k)
      : BoundaryCondition(s, Data::velocity, true, false), kind(k) {}
  std::string type() const override { return kind; }
  int precedence() const override { return wall; }
};

} // namespace

std::unique_ptr<BoundaryCondition> make_noslip(const BoundarySetup &s) {
  return std::make_unique<Wall>(s, "noslip");
}

std::unique_ptr<BoundaryCondition> make_clamped(const BoundarySetup &s) {
  return std::make_unique<Wall>(s, "clamped");
}

} // namespace fsi
