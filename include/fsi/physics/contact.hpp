// Solid-solid contact between the pieces of a surface (leaflets coapting), by a penalty on the
// gap with an offset: every surface node of one piece is repelled by the nearest triangle of each
// other piece (contact_surface.hpp) when closer than the offset delta,
//   E = sum over nodes  (A_node / 2) psi(delta - d),   d = node-to-triangle distance,
//   psi'(p) = k p^2 / (2 s) for 0 < p < s,  k (p - s/2) for p >= s   (a contact pressure [Pa]
// that ramps in smoothly over the width s, then grows like k p), both ways (node of A against
// B and node of B against A, hence the 1/2).  The residual adds dE/dx on the momentum rows of
// the nodes involved; the Jacobian adds the exact Hessian (gap derivatives by automatic
// differentiation) times d(u_af)/dv: the consistent tangent.  Pairs are found on the deformed
// configuration at the start of each Newton solve (each node's nearest triangle per piece within
// delta + margin, and the nearest part of it); within the solve the gap is to that triangle, so
// that the residual is smooth where two triangles are equally near.  The matrix pattern holds the
// pairs within delta + margin of the start of each solve and is rebuilt when a pair outside it
// comes near.  Pieces are the connected parts of the surface: a piece never contacts itself (no
// self-contact). Options (prefix -contact_): surface NAME (default "interface"), offset [m]
// (required), penalty k [Pa/m], ramp s [m] (default offset / 4), pattern_margin [m] (default
// offset). Rigid walls (contact_wall.hpp): -contact_walls GROUPS (fluid boundary groups, default
// none), wall_offset [m] (default offset), wall_exclude [m] (default 2 wall_offset): the same
// pressure law against the nearest wall triangle, on the surface node alone (the wall does not
// move). Axis rod: -contact_axis_radius R [m] (default 0: none), -contact_axis X,Y,Z,EX,EY,EZ (a
// point and the direction; default the z axis): every surface node keeps R from the line, with the
// same pressure law on its whole lumped area.  Three leaflets closing meet at one point on the
// axis, where the fluid between their corners is squeezed from three sides; the rod keeps that
// column of fluid at radius R (it is the valve's minimum gap at its centre) and the gap seal
// (gap_seal.hpp) closes it.
#pragma once
#include "fsi/physics/contact_geometry.hpp"
#include "fsi/physics/contact_surface.hpp"
#include "fsi/physics/contact_wall.hpp"
#include "fsi/physics/physics_module.hpp"
#include <array>
#include <memory>
#include <unordered_set>

namespace fsi {

struct ContactParams {
  std::string surface = "interface";
  double offset = 0, penalty = 1e8, ramp = 0, margin = 0;
  std::vector<std::string> walls; // rigid fluid boundary groups the surface keeps away from
  double wall_offset = 0, wall_exclude = 0;
  AxisLine axis; // a virtual rigid rod the surface keeps away from (radius 0: none)
  static ContactParams from_options();
  // Contact pressure psi'(p) [Pa] and its derivative at penetration p = delta - d.
  double pressure(double p) const;
  double pressure_slope(double p) const;
};

struct ContactStats {
  int active_pairs = 0;         // node-triangle pairs closer than the offset
  double max_penetration = 0;   // max (offset - d) [m]
  double force = 0;             // sum of |contact force| over nodes / 2 [N]
  long pattern_misses = 0;      // Jacobian blocks left out (pair outside the pattern)
  int wall_pairs = 0;           // surface nodes closer to a rigid wall than the wall offset
  double wall_min_gap = 0;      // smallest node-to-wall distance [m] (capped at the search radius)
  int axis_pairs = 0;           // surface nodes closer to the axis than the rod radius
  double axis_min_distance = 0; // smallest node-to-axis distance [m]
};

class ContactModule : public PhysicsModule {
public:
  // wall: the rigid walls (null: none); contact with them is on for the surface nodes farther
  // than p.wall_exclude from them in the surface's reference configuration.
  ContactModule(std::shared_ptr<ContactSurface> surface, const ContactParams &p,
                std::shared_ptr<ContactWall> wall = nullptr);
  std::string name() const override;
  void prepare(const StepContext &ctx) override { surface_->update(ctx); }
  void begin_solve(const StepContext &ctx) override;
  void add_residual(const StepContext &ctx, PetscScalar *F) override;
  void add_jacobian(const StepContext &ctx, Mat J) override;
  PetscInt n_cells() const override { return 0; }
  void element_dofs(std::vector<PetscInt> &dofs, int &n) const override {
    dofs.clear();
    n = 0;
  }
  void global_couplings(std::vector<PetscInt> &pairs) const override;
  bool couplings_changed() const override { return changed_; }
  void pattern_built() override;
  const ContactStats &stats() const { return stats_; }
  void add_to(MonitorRow &row) const override; // pairs, penetration, force (walls, rod)
  // Surface nodes closer to another piece than the offset on the current positions (the same on
  // every rank): where the pieces touch, e.g. the leaflets' coaptation.
  struct Touch {
    std::array<double, 3> x;
    int piece, other;
  };
  std::vector<Touch> touching();
  int n_pieces() const { return surface_->n_components(); }
  // The smallest distance between two pieces on the current positions (the reference ones
  // before the first step), or `radius` if none is closer.
  double smallest_gap(double radius);
  const ContactParams &params() const { return p_; }

private:
  struct Pair {
    int node, tri;
    double d;         // node-to-triangle distance
    TriRegion region; // where on the triangle the closest point lies
  };
  // Node-triangle pairs closer than `radius`: the nearest triangle of each other piece.
  std::vector<Pair>
  pairs_within(double radius,
               bool all = false); // all: every triangle in range, not the nearest per piece
  // Calls f(nodes, penetration, node weight, g, H) for every pair closer than the offset, with
  // the distance's gradient g and Hessian H in the 12 coordinates of nodes (node, triangle);
  // against a wall triangle nodes[1..3] are -1, against the axis rod -2 (only the node's 3
  // coordinates count).
  template <class F> void for_each_active(F &&f);
  void pick_wall_triangles(); // wall_pick_ from the surface's current position
  void pick_pairs();          // picked_: each node's nearest triangle per piece, once per solve
  static unsigned long long key(int a, int b) {
    if (a > b) std::swap(a, b);
    return ((unsigned long long)a << 32) | (unsigned)b;
  }
  std::shared_ptr<ContactSurface> surface_;
  ContactParams p_;
  std::shared_ptr<ContactWall> wall_;
  std::vector<char> wall_node_; // surface nodes that contact the walls
  // Each wall node's nearest wall triangle and region, picked once per Newton solve (t = -1:
  // none in range).  The distance to a faceted wall is the smallest of the facets' distances,
  // with a kink where two facets are equally near; a node on it switched facets between
  // iterations and Newton stalled at a linear rate (the opening valve at 102.5 ms).
  struct WallPick {
    int t = -1;
    TriRegion region = TriRegion::face;
  };
  std::vector<WallPick> wall_pick_;
  std::vector<Pair> picked_;
  bool picked_valid_ = false;
  double wall_min_gap_ = 0, axis_min_distance_ = 0;
  std::unordered_set<unsigned long long> pattern_, pending_;
  bool changed_ = false;
  ContactStats stats_;
};

} // namespace fsi
