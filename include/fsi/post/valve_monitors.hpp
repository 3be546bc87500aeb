// Per-step monitors of a heart valve (columns of monitor.csv), on when the scene gives
// -valve_annulus_radius R [m]:
//   valve_p_up, valve_p_down, valve_dp   area-mean pressure [Pa] on two discs normal to the
//       axis, -valve_dp_planes a,b [m] along the axis from the annulus centre (upstream a < 0,
//       downstream b > 0), radius -valve_dp_radius (default 0.8 R); their points are located
//       once in the reference mesh and follow it; dp = p_up - p_down (transvalvular drop)
//   valve_goa, valve_goa_ratio           geometric orifice area [m^2]: the part of the annulus
//       disc that no deformed leaflet covers when projected along the axis, and its ratio to
//       pi R^2 (a -valve_goa_pixels^2 raster, default 400)
//   valve_goa_contact_ratio              (with leaflet contact) the same ratio with every gap
//       narrower than -contact_offset counted as closed: the contact keeps touching leaflets that
//       far apart, so such a gap is where real leaflets touch (the leaflets' shadow grown by half
//       the offset)
//   valve_leaflet_umax                   largest displacement magnitude of a leaflet node [m]
//       (the free edge's), valve_leaflet_vm_max the largest von Mises Cauchy stress [Pa]
//   valve_peak_velocity, valve_peak_velocity_axial   the largest fluid speed |v| [m/s] between
//       the annulus plane and the downstream pressure plane (what continuous-wave Doppler reads
//       through the orifice and the vena contracta: its clinical "peak transvalvular velocity"),
//       and how far downstream of the annulus it is [m]
//   valve_coaptation_height, valve_coaptation_length   with leaflet contact on a valve of two or
//       three leaflets: where two leaflets touch (surface nodes closer than -contact_offset to
//       the other leaflet), the axial extent of their touching band [m] (the median over 1 mm
//       radial bins, each bin's highest minus lowest touching node) and its radial extent [m];
//       the smallest over the seams (leaflet pairs), since a valve seals by its weakest seam
// Axis: -valve_center x,y,z (annulus centre, default 0,0,0) and -valve_axis (default 0,0,1).
#pragma once
#include "fsi/discretization/space.hpp"
#include "fsi/physics/contact.hpp"
#include "fsi/physics/fluid.hpp"
#include "fsi/physics/solid.hpp"
#include "fsi/post/locate.hpp"
#include "fsi/post/monitor.hpp"
#include <array>
#include <string>
#include <vector>

namespace fsi {

class ValveMonitors : public Monitor {
public:
  // contact: the leaflets' contact (null: none), for the coaptation and the orifice with
  // touching gaps closed.
  void setup(const Space &space, const FluidModule *fluid, const SolidModule *solid,
             ContactModule *contact);
  bool active() const { return active_; }
  std::vector<std::string> columns() const;
  void add_to(MonitorRow &row, const FieldView &view) override;
  // The coaptation columns' values from the contact's touching nodes (2 or 3 leaflets).
  std::vector<double> coaptation(const std::vector<ContactModule::Touch> &touch, int pieces) const;

private:
  std::vector<double> evaluate(const FieldView &view);
  struct Sample {
    PointLocation at;
    double weight; // area [m^2]
  };
  double plane_mean_pressure(const std::vector<Sample> &plane, const PetscScalar *u) const;
  // {area, area with gaps narrower than touching_gap_ closed} [m^2]; x: deformed solid vertices
  std::array<double, 2> orifice_area(const std::vector<double> &x) const;
  // Whether a point of the annulus plane (coordinates along e1_, e2_) lies inside the annulus.
  bool in_annulus(double px, double py) const;
  // {largest |v|, its axial position} over the fluid nodes between the annulus and down_at_.
  std::array<double, 2> peak_velocity(const PetscScalar *u, const std::vector<double> &x) const;
  const Space *space_ = nullptr;
  const SolidModule *solid_ = nullptr;
  const FluidModule *fluid_ = nullptr;
  double down_at_ = 0; // axial position of the downstream pressure plane [m]
  ContactModule *contact_ = nullptr;
  double touching_gap_ = 0; // the contact offset [m] (0: no contact)
  bool active_ = false;
  double R_ = 0;              // the annulus's largest radius (the raster's half-width)
  std::vector<double> radii_; // one (a circle) or N at equal angles from e1_ [m]
  double annulus_area_ = 0;   // [m^2]
  std::array<double, 3> c_{}, axis_{}, e1_{}, e2_{};
  std::vector<Sample> up_, down_;
  int pixels_ = 400;
  MPI_Comm comm_;
};

} // namespace fsi
