// The fluid mesh of the ALE description, behind one object: its motion (mesh_motion.hpp), the
// configurations a step needs (X_n, X_{n+alpha_f}, X_{n+1} and the mesh velocity), the geometry
// iterations and the quality checks.
//   -ale_geometry_iterations N (default 0: geometry lagged once per step, as the paper; N:
//     re-solve on the mesh moved by the new solid displacement until it changes by less than
//     -ale_geometry_rtol, default 1e-6)
//   -ale_min_jacobian (default 0), -ale_max_skewness (default 0.99): a fluid cell past these on
//     the predicted or iterated mesh stops the step (DistortionError), unless remeshing is on.
//   -ale_remesh_skewness S (default 0.9, the paper's; 0 = off), -ale_remesh_min_volume_ratio R
//     (default 0.1): with the Laplace motion, the step whose predicted mesh has a degraded cell
//     (quality 1 - s at least halved against the reference mesh) with skewness > S, or a cell
//     squeezed below R of its reference volume, or any cell past the hard limits above, throws
//     RemeshNeeded before its solve; the run remeshes (remesh.hpp) and retries the step.  The
//     first step on a new mesh only stops at the hard limits (no remesh loop).
//   -ale_remesh_ignore_sealed (default false): the skewness trigger leaves out the cells a gap
//     seal holds shut (set_sealed): a closed valve's coaptation gap, whose thin cells the
//     leaflets keep squeezing, then asks for a remesh only at the hard limits or the volume
//     ratio, not at every step of a hold.
// Coordinates are 3 per local vertex; the fluid mesh's reference is Space::X (the ALE
// reference, where the mesh displacement is zero), not the solid's material reference.
#pragma once
#include "fsi/ale/mesh_motion.hpp"
#include "fsi/post/monitor_row.hpp"
#include "fsi/time/step_context.hpp"
#include <functional>
#include <memory>
#include <vector>

namespace fsi {

class Ale {
public:
  // motion may be null (a fixed mesh); fluid_cells: the fluid's local cells (null without fluid).
  Ale(const Space &space, std::unique_ptr<MeshMotion> motion,
      const std::vector<PetscInt> *fluid_cells);
  bool moving() const { return motion_ != nullptr; }
  bool follows_solid() const { return motion_ && motion_->follows_solid(); }
  const MeshMotion *motion() const { return motion_.get(); }
  int geometry_iterations() const { return geometry_iterations_; }
  double geometry_rtol() const { return geometry_rtol_; }

  // Mesh displacement at t_n and the configuration X_n = X + d_n.
  const std::vector<double> &displacement() const { return dn_; }
  const std::vector<double> &coordinates() const { return Xn_; }
  const std::vector<double> &coordinates_af() const { return Xaf_.empty() ? Xn_ : Xaf_; }
  const std::vector<double> &coordinates_np1() const { return Xnp1_; }
  // Initial mesh at t = 0 (a prescribed motion may start displaced), or restored at t_n.
  void initialize();
  void restore(const std::vector<double> &dn);

  // Start of a step (or of its retry): the iterative mesh solve starts from d_n.
  void begin_step();
  // Mesh displacement at t_{n+1}: solid = the solid displacement at t_{n+1} as a local array
  // (velocity layout) when the motion follows the solid, else null.
  void move(double t_np1, const PetscScalar *solid, std::vector<double> &d);
  // Mesh at t, without a solid (prescribed motions; the solid is at rest at t = 0).
  void mesh_at(double t, std::vector<double> &d) const;
  // Configurations for the step t_n -> t_n + dt with mesh displacement d at t_{n+1}, and the
  // geometric part of the kernels' context (X_af, X_np1, W).
  void set_geometry(const std::vector<double> &d, double alpha_f, double dt, bool steady);
  void fill_context(StepContext &ctx) const;
  // Largest change of d against the current d_{n+1}, relative to |d|, over all ranks.
  double relative_change(const std::vector<double> &d) const;
  // Quality of the fluid cells at t_{n+1}; throws DistortionError past the limits.
  void check(const char *when, long step);
  // Cells held shut (per fluid cell, filled by the callback) for -ale_remesh_ignore_sealed.
  void set_sealed(std::function<void(std::vector<char> &)> sealed) { sealed_ = std::move(sealed); }
  bool ignores_sealed() const { return ignore_sealed_; }
  const MeshQuality &quality() const { return quality_; }
  // Its columns of monitor.csv (with a moving mesh): quality, the last step's geometry passes
  // and, with remeshing, what the trigger judges.
  void add_to(MonitorRow &row, int geometry_iterations, double geometry_change) const;
  // Remeshing: on for this run; fresh = the mesh was just built, its first step does not ask.
  bool remeshing() const { return remesh_skewness_ > 0 && follows_solid(); }
  void set_fresh(bool fresh) { fresh_ = fresh; }
  // After a converged step: d_n <- d_{n+1}.
  void accept();
  double seconds() const { return seconds_; }

private:
  const Space &space_;
  std::unique_ptr<MeshMotion> motion_;
  const std::vector<PetscInt> *fluid_cells_;
  int geometry_iterations_ = 0;
  double geometry_rtol_ = 1e-6, min_jacobian_ = 0, max_skewness_ = 0.99;
  double remesh_skewness_ = 0.9, remesh_min_ratio_ = 0.1;
  // -ale_remesh_skewness_fresh: the trigger raised to the reference mesh's worst cell, up to this
  // (0: off); trigger_ is the skewness a degraded cell must pass.
  double fresh_cap_ = 0, trigger_ = 0.9;
  bool fresh_ = false, ignore_sealed_ = false;
  std::function<void(std::vector<char> &)> sealed_;
  std::vector<double> skewness0_; // per fluid cell, in the reference mesh
  std::vector<double> dn_, dnp1_, Xn_, Xaf_, Xnp1_, W_;
  bool has_velocity_ = false;
  MeshQuality quality_;
  double seconds_ = 0;
};

} // namespace fsi
