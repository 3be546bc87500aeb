// The physics a scene switches on with -physics a,b,...: each registered by name in
// src/physics/registry.cpp, the way boundary conditions are, with the physics it needs and its
// make_ function.  Modules are built in the registry's order whatever the list's, so that a
// module finds the ones it needs already built.  A new physics: one module file with its make_
// function, and one line there.
#pragma once
#include "fsi/analytic/exact_solid.hpp"
#include "fsi/physics/contact.hpp"
#include "fsi/physics/physics_module.hpp"
#include "fsi/scene/option_doc.hpp"
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace fsi {

class FluidModule;
class SolidModule;
class GapSeal;

// What the modules of a scene are built from, and what those built so far left for the next.
struct PhysicsBuild {
  PhysicsBuild(const Mesh &m, Space &s, const std::vector<double> &X)
      : mesh(m), space(s), material_X(X) {}
  const Mesh &mesh;
  Space &space;
  const std::vector<double> &material_X; // the solid's material reference per vertex
  const FluidModule *fluid = nullptr;
  const SolidModule *solid = nullptr;
  ContactModule *contact = nullptr; // not const: asking who touches re-bins its surface
  const GapSeal *seal = nullptr;
  std::unique_ptr<ExactSolid> exact_solid;             // -exact_displacement (solid)
  std::vector<std::unique_ptr<PhysicsModule>> modules; // in the order built
  // The contact options and the solid's surface pieces, read and built once for the modules
  // that act between the pieces (contact, gap_seal).
  const ContactParams &contact_params();
  std::shared_ptr<ContactSurface> contact_surface();

private:
  std::optional<ContactParams> contact_params_;
  std::shared_ptr<ContactSurface> surface_;
};

using PhysicsFactory = void (*)(PhysicsBuild &);
struct PhysicsType {
  const char *name;
  std::vector<const char *> needs; // physics that must be switched on with it
  const char *help;
  PhysicsFactory make;
  OptionSection (*options)(); // its options, declared next to their reader
};
// Every registered physics, in build order (src/physics/registry.cpp).
const std::vector<PhysicsType> &physics_types();
// The physics list checked: every name registered, every need met; an InputError otherwise.
void check_physics(const std::vector<std::string> &physics);

} // namespace fsi
