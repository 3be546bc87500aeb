// Per-step monitors of a heart valve (columns of monitor.csv), on when the scene gives
// -valve_annulus_radius R [m]:
//   valve_p_up, valve_p_down, valve_dp   area-mean pressure [Pa] on two discs normal to the
//       axis, -valve_dp_planes a,b [m] along the axis from the annulus centre (upstream a < 0,
//       downstream b > 0), radius -valve_dp_radius (default 0.8 R); their points are located
//       once in the reference mesh and follow it; dp = p_up - p_down (transvalvular drop)
//   valve_goa, valve_goa_ratio           geometric orifice area [m^2]: the part of the annulus
//       disc that no deformed leaflet covers when projected along the axis, and its ratio to
//       pi R^2 (a -valve_goa_pixels^2 raster, default 400)
//   valve_leaflet_umax                   largest displacement magnitude of a leaflet node [m]
//       (the free edge's), valve_leaflet_vm_max the largest von Mises Cauchy stress [Pa]
// Axis: -valve_center x,y,z (annulus centre, default 0,0,0) and -valve_axis (default 0,0,1).
#pragma once
#include "fsi/discretization/space.hpp"
#include "fsi/physics/fluid.hpp"
#include "fsi/physics/solid.hpp"
#include "fsi/post/locate.hpp"
#include <array>
#include <string>
#include <vector>

namespace fsi {

class Simulation;

class ValveMonitors {
public:
  void setup(const Space &space, const FluidModule *fluid, const SolidModule *solid);
  bool active() const { return active_; }
  std::vector<std::string> columns() const;
  std::vector<double> evaluate(const Simulation &pb);

private:
  struct Sample {
    PointLocation at;
    double weight; // area [m^2]
  };
  double plane_mean_pressure(const std::vector<Sample> &plane, const PetscScalar *u) const;
  double orifice_area(const std::vector<double> &x) const; // x: deformed solid vertices
  const Space *space_ = nullptr;
  const SolidModule *solid_ = nullptr;
  bool active_ = false;
  double R_ = 0;
  std::array<double, 3> c_{}, axis_{}, e1_{}, e2_{};
  std::vector<Sample> up_, down_;
  int pixels_ = 400;
  MPI_Comm comm_;
};

} // namespace fsi
