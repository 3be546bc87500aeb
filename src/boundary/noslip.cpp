// noslip: v = 0 on the fixed components (default all).  A wall: it wins at shared nodes.
#include "fsi/boundary/boundary_condition.hpp"

namespace fsi {
namespace {

struct NoSlip : BoundaryCondition {
  explicit NoSlip(const BoundarySetup &s) : BoundaryCondition(s, Data::velocity, true, false) {}
  std::string type() const override { return "noslip"; }
  int precedence() const override { return wall; }
};

} // namespace

std::unique_ptr<BoundaryCondition> make_noslip(const BoundarySetup &s) {
  return std::make_unique<NoSlip>(s);
}

} // namespace fsi
