// The physics a scene can switch on with -physics.  A new physics: one module file with its
// make_ function, and one line here.
#include "fsi/physics/physics_registry.hpp"
#include "fsi/physics/solid.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>

namespace fsi {

void make_fluid(PhysicsBuild &);
void make_solid(PhysicsBuild &);
void make_contact(PhysicsBuild &);
void make_gap_seal(PhysicsBuild &);
OptionSection fluid_options();
OptionSection solid_options();
OptionSection contact_options();
OptionSection gap_seal_options();

const std::vector<PhysicsType> &physics_types() {
  static const std::vector<PhysicsType> types = {
      {"fluid",
       {},
       "incompressible Navier-Stokes on the ALE mesh (P2/P1)",
       make_fluid,
       fluid_options},
      {"solid", {}, "total-Lagrangian hyperelastic solid (P2)", make_solid, solid_options},
      {"contact",
       {"solid"},
       "penalty contact between the solid's surface pieces",
       make_contact,
       contact_options},
      {"gap_seal",
       {"fluid", "solid"},
       "a resistance sealing the fluid in a closing solid gap",
       make_gap_seal,
       gap_seal_options},
  };
  return types;
}

void check_physics(const std::vector<std::string> &physics) {
  std::vector<std::string> names;
  for (auto &t : physics_types())
    names.push_back(t.name);
  auto on = [&](const std::string &n) {
    return std::find(physics.begin(), physics.end(), n) != physics.end();
  };
  for (auto &p : physics) {
    if (p == "ale")
      throw InputError("-physics ale is not a physics: the mesh motion is chosen by -ale_motion "
                       "none|prescribed|laplace");
    if (std::find(names.begin(), names.end(), p) == names.end())
      throw InputError("-physics has unknown value '" + p + "'; use: " + opt::join(names));
  }
  for (auto &t : physics_types()) {
    if (!on(t.name)) continue;
    std::vector<std::string> missing;
    for (const char *n : t.needs)
      if (!on(n)) missing.push_back(n);
    if (!missing.empty())
      throw InputError("-physics " + std::string(t.name) + " needs " + opt::join(missing, " and ") +
                       ": add " + opt::join(missing, ",") + " to -physics (e.g. -physics " +
                       "fluid,solid,contact,gap_seal for a closing valve)");
  }
}

const ContactParams &PhysicsBuild::contact_params() {
  if (!contact_params_) contact_params_ = ContactParams::from_options();
  return *contact_params_;
}

std::shared_ptr<ContactSurface> PhysicsBuild::contact_surface() {
  if (surface_) return surface_;
  const ContactParams &cp = contact_params();
  mesh.require_groups({cp.surface}, "the contact surface (-contact_surface)");
  surface_ = std::make_shared<ContactSurface>(space, mesh, cp.surface, solid->cells(), material_X);
  if (surface_->n_components() < 2)
    throw InputError("the contact surface '" + cp.surface + "' has " +
                     std::to_string(surface_->n_components()) +
                     " connected piece(s): contact acts between pieces (no self-contact), so "
                     "it needs at least 2; check -contact_surface");
  return surface_;
}

} // namespace fsi
