// Per-step solid monitors (columns of monitor.csv), only those the scene asks for:
//   -solid_probe_points x,y,z;...  displacement [m] at points of the reference configuration;
//   -monitor_solid_energy          kinetic, stored and total energy [J] (energy.{kinetic,...});
//   with -exact_displacement:      L2 error of the displacement at t_{n+1} and its relative size.
#pragma once
#include "fsi/analytic/exact_solid.hpp"
#include "fsi/physics/fluid.hpp"
#include "fsi/physics/solid.hpp"
#include "fsi/post/locate.hpp"

namespace fsi {

class Simulation;

class SolidMonitors {
public:
  void setup(const Space &space, const SolidModule *solid, const ExactSolid *exact);
  std::vector<std::string> columns() const;
  std::vector<double> evaluate(const Simulation &pb);
  // Last displacement error (absolute, relative); valid with an exact solution.
  double error_l2() const { return err_; }
  bool has_exact() const { return exact_ != nullptr; }
  double error_relative() const { return err_rel_; }

private:
  const Space *space_ = nullptr;
  const SolidModule *solid_ = nullptr;
  const ExactSolid *exact_ = nullptr;
  std::vector<PointLocation> probes_;
  bool energy_ = false;
  double err_ = 0, err_rel_ = 0;
};

} // namespace fsi
