// The boundary-condition types a scene can name with -bc_<name>_type.  A new type: one file with
// its make_ function, and one line here.
#include "fsi/boundary/boundary_condition.hpp"

namespace fsi {

std::unique_ptr<BoundaryCondition> make_noslip(const BoundarySetup &);
std::unique_ptr<BoundaryCondition> make_velocity(const BoundarySetup &);
std::unique_ptr<BoundaryCondition> make_flow_rate(const BoundarySetup &);
std::unique_ptr<BoundaryCondition> make_pressure(const BoundarySetup &);
std::unique_ptr<BoundaryCondition> make_windkessel(const BoundarySetup &);
std::unique_ptr<BoundaryCondition> make_traction_exact(const BoundarySetup &);
std::unique_ptr<BoundaryCondition> make_clamped(const BoundarySetup &);
std::unique_ptr<BoundaryCondition> make_displacement(const BoundarySetup &);
std::unique_ptr<BoundaryCondition> make_traction(const BoundarySetup &);
std::unique_ptr<BoundaryCondition> make_follower_pressure(const BoundarySetup &);

const std::vector<BoundaryType> &boundary_types() {
  static const std::vector<BoundaryType> types = {
      {"noslip", "fluid", "v = 0 (a wall)", make_noslip},
      {"velocity", "fluid", "v = profile(x) waveform(t) [m/s]", make_velocity},
      {"flow_rate", "fluid", "v = s(t) profile(x), flux = value waveform(t) [m^3/s] inwards",
       make_flow_rate},
      {"pressure", "fluid", "traction -p(t) n [Pa] with backflow stabilisation", make_pressure},
      {"windkessel", "fluid",
       "three-element Windkessel (RCR) outlet: traction -(R_p Q + P_c) n, C dP_c/dt = Q - "
       "(P_c - p_distal)/R_d",
       make_windkessel},
      {"traction_exact", "fluid", "traction of -exact_solution (verification)",
       make_traction_exact},
      {"clamped", "solid", "u = 0", make_clamped},
      {"displacement", "solid", "u = value direction waveform(t) [m] (or exact)",
       make_displacement},
      {"traction", "solid", "dead nominal traction [Pa]", make_traction},
      {"follower_pressure", "solid", "pressure on the deformed face [Pa] (p < 0 pulls)",
       make_follower_pressure},
  };
  return types;
}

} // namespace fsi
