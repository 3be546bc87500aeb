// The monitors a scene can switch on, in monitor.csv's column order.  A new monitor: one class
// deriving from Monitor (monitor.hpp) with its make_ function, and one line here.
#include "fsi/post/monitor.hpp"

namespace fsi {

std::unique_ptr<Monitor> make_flow_monitors(const MonitorSetup &);
std::unique_ptr<Monitor> make_solid_monitors(const MonitorSetup &);
std::unique_ptr<Monitor> make_valve_monitors(const MonitorSetup &);
std::unique_ptr<Monitor> make_wall_shear(const MonitorSetup &);
OptionSection flow_monitor_options();
OptionSection solid_monitor_options();
OptionSection valve_monitor_options();
OptionSection wall_shear_options();

const std::vector<MonitorType> &monitor_types() {
  static const std::vector<MonitorType> types = {
      {"flow", "-monitor_surfaces, -probe_points, -monitor_fluid_volume/_energy, exact errors",
       make_flow_monitors, flow_monitor_options},
      {"solid", "-solid_probe_points, -monitor_solid_energy, exact displacement errors",
       make_solid_monitors, solid_monitor_options},
      {"valve",
       "-valve_annulus_radius: gradient, orifice, leaflet stress, peak velocity, coaptation",
       make_valve_monitors, valve_monitor_options},
      {"wall_shear", "-hemo_surfaces: WSS each step, TAWSS/OSI/RRT per window (hemo.h5)",
       make_wall_shear, wall_shear_options},
  };
  return types;
}

} // namespace fsi
