// A Brinkman (Darcy) resistance that seals the fluid gap between coapting leaflets without
// collapsing its cells: on a fluid cell whose centroid lies between two pieces of the contact
// surface (contact_surface.hpp) closer than gap_open, the momentum equation gains
//   alpha (v - w),   alpha = alpha_max S((gap_open - g) / (gap_open - gap_closed)),
// g = d_1 + d_2 the distances from the centroid to the two nearest pieces (the local width of
// the gap), S(s) = s^2 (3 - 2 s) on [0, 1] (smooth in the distance), w the mesh velocity (the
// resistance acts on the flow through the moving gap, not on the gap's own motion).  alpha is
// computed per cell at the start of each solve on the configuration of t_{n+alpha_f} and held
// during the solve (exact Jacobian for it); with ramp_time tau > 0 it follows its target
// through a first-order lag, alpha <- alpha + (target - alpha)(1 - exp(-dt / tau)) per step, so
// that sealing and unsealing are not abrupt (pressure spikes).
// Options (prefix -gap_seal_): resistance alpha_max [Pa s/m^2] (default 1e8), gap_closed [m]
// (default 1.25 x -contact_offset), gap_open [m] (default 2 x -contact_offset), ramp_time [s]
// (default 0: none).
// With the contact's axis rod (contact.hpp, radius R) the rod counts as one more piece, at the
// signed distance r - R from a centroid r from the axis: the fluid column the rod keeps open
// between three leaflets' corners seals when they close on it, as a gap between two does.
#pragma once
#include "fsi/discretization/p2tet.hpp"
#include "fsi/physics/contact_geometry.hpp"
#include "fsi/physics/contact_surface.hpp"
#include "fsi/physics/physics_module.hpp"
#include <memory>

namespace fsi {

struct GapSealParams {
  double resistance = 1e8, gap_closed = 0, gap_open = 0, ramp_time = 0;
  AxisLine axis; // the contact's axis rod (radius 0: none)
  static GapSealParams from_options(double contact_offset, const AxisLine &axis);
};

struct GapSealStats {
  int sealing_cells = 0; // cells with alpha > alpha_max / 2 (this rank + others, summed)
  double max_alpha = 0;
};

class GapSeal : public PhysicsModule {
public:
  GapSeal(const Space &space, const std::vector<PetscInt> &fluid_cells,
          std::shared_ptr<ContactSurface> surface, const GapSealParams &p);
  std::string name() const override;
  void begin_solve(const StepContext &ctx) override;
  void add_residual(const StepContext &ctx, PetscScalar *F) override;
  void add_jacobian(const StepContext &ctx, Mat J) override;
  PetscInt n_cells() const override { return 0; }
  void element_dofs(std::vector<PetscInt> &dofs, int &n) const override { // the fluid's own
    dofs.clear();
    n = 0;
  }
  const GapSealStats &stats() const { return stats_; }
  void add_to(MonitorRow &row) const override; // sealing cells, largest resistance
  // Resistance [Pa s/m^2] of every local fluid cell (0 where open), for output.
  const std::vector<double> &alpha() const { return alpha_; }
  const std::vector<PetscInt> &cells() const { return cells_; }
  // Cell c of cells() held shut: alpha > alpha_max / 2 (what GapSealStats counts).
  bool sealed(size_t c) const { return alpha_[c] > 0.5 * p_.resistance; }

private:
  // Target resistance at point c from its distances to the two nearest pieces (best: scratch).
  double target(const double c[3], std::vector<double> &best) const;
  double reach() const; // how far from a centroid pieces count
  double absdet_af(const StepContext &ctx, PetscInt k) const; // |det J| of cell k at t_{n+af}
  const Space &space_;
  std::vector<PetscInt> cells_;
  std::shared_ptr<ContactSurface> surface_;
  GapSealParams p_;
  std::vector<double> alpha_, alpha_prev_; // per cell of cells_
  double t_last_ = -1e300;
  double M_[10][10]; // P2 mass matrix per unit |det J|
  GapSealStats stats_;
};

} // namespace fsi
