// Per-step solid monitors (columns of monitor.csv), only those the scene asks for:
//   -solid_probe_points x,y,z;...  displacement [m] at points of the reference configuration;
//   -monitor_solid_energy          kinetic, stored and total energy [J] (energy.{kinetic,...});
//   with -exact_displacement:      L2 error of the displacement at t_{n+1} and its relative size.
#pragma once
#include "fsi/analytic/exact_solid.hpp"
#include "fsi/physics/fluid.hpp"
#include "fsi/physics/solid.hpp"
#include "fsi/post/locate.hpp"
#include "fsi/post/monitor.hpp"

namespace fsi {

class SolidMonitors : public Monitor {
public:
  void setup(const Space &space, const SolidModule *solid, const ExactSolid *exact);
  bool active() const { return solid_ != nullptr; }
  std::vector<std::string> columns() const;
  void add_to(MonitorRow &row, const FieldView &view) override {
    row.add(columns(), [&] { return evaluate(view); });
  }
  // The last displacement error, absolute and relative (error_final).
  void summarize(Json &j, bool stepped) const override;

private:
  std::vector<double> evaluate(const FieldView &view);
  const Space *space_ = nullptr;
  const SolidModule *solid_ = nullptr;
  const ExactSolid *exact_ = nullptr;
  std::vector<PointLocation> probes_;
  bool energy_ = false;
  double err_ = 0, err_rel_ = 0;
};

} // namespace fsi
