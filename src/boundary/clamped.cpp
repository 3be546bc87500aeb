// clamped (solid): u = 0, held through the velocity (v = 0).  A wall: it wins at shared nodes.
#include "fsi/boundary/boundary_condition.hpp"

namespace fsi {
namespace {

struct Clamped : BoundaryCondition {
  explicit Clamped(const BoundarySetup &s) : BoundaryCondition(s, Data::velocity, true, false) {}
  std::string type() const override { return "clamped"; }
  int precedence() const override { return wall; }
};

} // namespace

std::unique_ptr<BoundaryCondition> make_clamped(const BoundarySetup &s) {
  return std::make_unique<Clamped>(s);
}

} // namespace fsi
