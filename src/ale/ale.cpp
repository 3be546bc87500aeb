#include "fsi/ale/ale.hpp"
#include "fsi/run/stages.hpp"
#include "fsi/scene/option_doc.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <cmath>

namespace fsi {

Ale::Ale(const Space &space, std::unique_ptr<MeshMotion> motion,
         const std::vector<PetscInt> *fluid_cells)
    : space_(space), motion_(std::move(motion)), fluid_cells_(fluid_cells) {
  geometry_iterations_ = (int)opt::integer_at_least("ale_geometry_iterations", 0, 0);
  geometry_rtol_ = opt::positive("ale_geometry_rtol", 1e-6);
  min_jacobian_ = opt::real("ale_min_jacobian", 0.0);
  max_skewness_ = opt::positive("ale_max_skewness", 0.99);
  remesh_skewness_ = opt::nonnegative("ale_remesh_skewness", 0.9);
  remesh_min_ratio_ = opt::nonnegative("ale_remesh_min_volume_ratio", 0.1);
  ignore_sealed_ = opt::flag("ale_remesh_ignore_sealed", false);
  if (remesh_skewness_ >= 1)
    throw InputError("-ale_remesh_skewness must be below 1 (0 turns remeshing off)");
  fresh_cap_ = opt::nonnegative("ale_remesh_skewness_fresh", 0.0);
  if (fresh_cap_ >= 1)
    throw InputError("option -ale_remesh_skewness_fresh must be below 1 (0: off), e.g. 0.95");
  trigger_ = remesh_skewness_;
  Xn_ = space.X;
  dn_.assign(space.X.size(), 0.0);
}

void Ale::mesh_at(double t, std::vector<double> &d) const {
  if (motion_ && !motion_->follows_solid()) // the solid is at rest at t = 0
    motion_->displacement(t, nullptr, d);
  else
    d.assign(3 * space_.n_vertices(), 0.0);
}

void Ale::initialize() {
  std::vector<double> d;
  mesh_at(0.0, d);
  restore(d);
}

void Ale::restore(const std::vector<double> &dn) {
  dn_ = dn;
  for (size_t i = 0; i < Xn_.size(); ++i)
    Xn_[i] = space_.X[i] + dn_[i];
}

void Ale::move(double t_np1, const PetscScalar *solid, std::vector<double> &d) {
  if (!motion_) {
    d.assign(3 * space_.n_vertices(), 0.0);
    return;
  }
  FSI_CALL(PetscLogStagePush(Stages::get().mesh_motion));
  const double t0 = MPI_Wtime();
  motion_->displacement(t_np1, motion_->follows_solid() ? solid : nullptr, d);
  seconds_ += MPI_Wtime() - t0;
  FSI_CALL(PetscLogStagePop());
}

void Ale::begin_step() {
  // The mesh solver starts from the last accepted mesh (a retried or restarted step starts
  // exactly where the uninterrupted run did).
  if (motion_) motion_->set_guess(dn_);
}

void Ale::set_geometry(const std::vector<double> &d, double alpha_f, double dt, bool steady) {
  dnp1_ = d;
  const size_t nd = d.size();
  Xaf_.resize(nd);
  W_.resize(nd);
  Xnp1_.resize(nd);
  const double af = steady ? 1.0 : alpha_f;
  for (size_t i = 0; i < nd; ++i) {
    Xaf_[i] = space_.X[i] + dn_[i] + af * (dnp1_[i] - dn_[i]);
    W_[i] = steady ? 0.0 : (dnp1_[i] - dn_[i]) / dt;
    Xnp1_[i] = space_.X[i] + dnp1_[i];
  }
  has_velocity_ = motion_ && !steady;
}

void Ale::fill_context(StepContext &ctx) const {
  ctx.X_af = Xaf_.data();
  // Without mesh motion both configurations are the same array: kernels then skip the second
  // geometry (pointer equality).
  ctx.X_np1 = motion_ ? Xnp1_.data() : Xaf_.data();
  ctx.W = has_velocity_ ? W_.data() : nullptr;
}

double Ale::relative_change(const std::vector<double> &d) const {
  double change = 0, size = 0;
  for (size_t i = 0; i < d.size(); ++i) {
    change = std::max(change, std::fabs(d[i] - dnp1_[i]));
    size = std::max(size, std::fabs(d[i]));
  }
  double loc[2] = {change, size}, glob[2];
  MPI_Allreduce(loc, glob, 2, MPI_DOUBLE, MPI_MAX, PetscObjectComm((PetscObject)space_.dm));
  return glob[1] > 0 ? glob[0] / glob[1] : 0.0;
}

void Ale::check(const char *when, long step) {
  if (!motion_ || !fluid_cells_) return;
  const bool remesh = remeshing() && !fresh_;
  if (remeshing() && skewness0_.empty()) {
    for (PetscInt k : *fluid_cells_) {
      double P[4][3];
      space_.cell_points(k, space_.X.data(), P);
      skewness0_.push_back(tet_skewness(P));
    }
    // A new mesh of this boundary is no better than its worst cell: a degraded cell that is not
    // worse than that would only buy another mesh with the same worst cell (and a remesh's
    // interpolation and projection, which take 1-4 % of the kinetic energy each time).
    if (fresh_cap_ > 0) {
      double worst = 0, global = 0;
      for (double s : skewness0_)
        worst = std::max(worst, s);
      MPI_Allreduce(&worst, &global, 1, MPI_DOUBLE, MPI_MAX,
                    PetscObjectComm((PetscObject)space_.dm));
      trigger_ = std::max(remesh_skewness_, std::min(fresh_cap_, global));
    }
  }
  std::vector<char> sealed;
  if (remeshing() && ignore_sealed_ && sealed_) sealed_(sealed);
  quality_ = mesh_quality(space_, *fluid_cells_, Xnp1_, remeshing() ? &skewness0_ : nullptr,
                          sealed.empty() ? nullptr : &sealed);
  // With remeshing the skewness limit applies to what the motion did to a cell: a sliver the
  // mesher had to make between boundary triangles that nearly face each other (four boundary
  // vertices across a thin gap) is as good as any mesh of that boundary gets, and a new mesh
  // would make it again.  Its volume ratio still counts.
  const double skew = remeshing() ? quality_.max_degraded_skewness : quality_.max_skewness;
  const bool hard = quality_.min_jacobian <= min_jacobian_ || skew >= max_skewness_;
  const bool before = std::string(when) == "before";
  const bool soft = before && (quality_.max_degraded_open > trigger_ ||
                               quality_.min_jacobian < remesh_min_ratio_);
  char msg[500];
  if (remesh && (hard || soft)) {
    std::snprintf(msg, sizeof msg,
                  "mesh %s step %ld: worst skewness %.3f (degraded %.3f%s at %.4g,%.4g,%.4g m, "
                  "%s %.3g), smallest volume ratio %.3g at %.4g,%.4g,%.4g m "
                  "(-ale_remesh_min_volume_ratio %.3g)",
                  when, step, quality_.max_skewness, quality_.max_degraded_open,
                  sealed.empty() ? "" : " outside sealed gaps", quality_.where_degraded_open[0],
                  quality_.where_degraded_open[1], quality_.where_degraded_open[2],
                  trigger_ > remesh_skewness_ ? "trigger: this mesh's worst cell"
                                              : "-ale_remesh_skewness",
                  trigger_, quality_.min_jacobian, quality_.where[0], quality_.where[1],
                  quality_.where[2], remesh_min_ratio_);
    throw RemeshNeeded(msg);
  }
  if (hard) {
    std::snprintf(msg, sizeof msg,
                  "fluid mesh too distorted %s step %ld: smallest volume ratio %.3g (limit "
                  "-ale_min_jacobian %.3g), worst %sskewness %.3f (limit -ale_max_skewness %.3f)%s",
                  when, step, quality_.min_jacobian, min_jacobian_, remeshing() ? "degraded " : "",
                  skew, max_skewness_,
                  fresh_ ? " on a mesh just remeshed: reduce the time step"
                         : "; remeshing is off (-ale_remesh_skewness 0 or a prescribed motion): "
                           "turn it on, refine the mesh or stiffen the motion (-ale_stiffening 1)");
    if (fresh_) throw FreshMeshDistortion(msg);
    throw DistortionError(msg);
  }
}

void Ale::accept() {
  fresh_ = false;
  dn_ = dnp1_;
  Xn_ = Xnp1_;
}

void Ale::add_to(MonitorRow &row, int geometry_iterations, double geometry_change) const {
  if (!moving()) return;
  row.add("mesh_min_jacobian", quality_.min_jacobian);
  row.add("mesh_max_skewness", quality_.max_skewness);
  row.add("mesh_min_jacobian_x", quality_.where[0]);
  row.add("mesh_min_jacobian_y", quality_.where[1]);
  row.add("mesh_min_jacobian_z", quality_.where[2]);
  row.add("geometry_iterations", (double)geometry_iterations);
  row.add("geometry_change", geometry_change);
  // What the remesh trigger judges: the worst skewness among cells the motion degraded, and with
  // -ale_remesh_ignore_sealed the same outside the sealed gaps (the one it acts on).
  if (remeshing()) row.add("mesh_max_degraded_skewness", quality_.max_degraded_skewness);
  if (remeshing() && ignores_sealed())
    row.add("mesh_max_degraded_skewness_unsealed", quality_.max_degraded_open);
}

// Its options, for -help and docs/options.md (option_doc.hpp).
OptionSection ale_options() {
  return {
      "Mesh motion (ALE)",
      {{"ale_motion", "none", "-",
        "none | prescribed (verification) | laplace (follows the solid)"},
       {"ale_amplitude", "0.1", "m", "prescribed: bubble amplitude"},
       {"ale_time", "1", "s", "prescribed: time over which the amplitude is reached"},
       {"ale_stiffening", "0", "-", "chi in k = (V_max/V_e)^chi (0 Laplace, 1 Jacobian-stiffened)"},
       {"ale_slip_boundaries", "", "-", "planes where the mesh slides (inlet/outlet)"},
       {"ale_geometry_iterations", "0", "-", "0: geometry lagged; N: iterate the mesh in the step"},
       {"ale_geometry_rtol", "1e-6", "-", "relative mesh change that ends geometry iterations"},
       {"ale_geometry_monitor", "false", "-",
        "print each geometry pass's Newton count and mesh change"},
       {"ale_interface", "", "-",
        "mass-conservative fluid-solid interface (its physical name); not for thin light "
        "structures such as leaflets (a two-step sawtooth grows: docs/valve.md)"},
       {"ale_min_jacobian", "0", "-", "stop when a fluid cell's volume ratio reaches this"},
       {"ale_max_skewness", "0.99", "-", "stop when a fluid cell's skewness reaches this"},
       {"ale_remesh_skewness", "0.9", "-",
        "remesh the fluid when a degraded cell's skewness passes this (0: off)"},
       {"ale_remesh_skewness_fresh", "0", "-",
        "raise -ale_remesh_skewness to the current mesh's worst cell, up to this (0: off)"},
       {"ale_remesh_min_volume_ratio", "0.1", "-",
        "remesh when a fluid cell is squeezed below this fraction of its volume"},
       {"ale_remesh_ignore_sealed", "false", "-",
        "the skewness trigger leaves out cells a gap seal holds shut (a closed valve's hold)"},
       {"ale_remesh_hmax", "0 (from the boundary)", "m", "largest cell of a new fluid mesh"},
       {"ale_remesh_every", "0", "steps", "also remesh after every N steps (tests, studies)"},
       {"ale_remesh_gap_cells", "2", "-",
        "cells across a fluid gap thinner than its boundary triangles (0: no gap sizing)"},
       {"ale_remesh_flip_skewness", "0.8", "-",
        "edge/face flips on new fluid cells worse than this (0: off)"},
       {"ale_remesh_project", "true", "-",
        "project the remeshed velocity onto discretely divergence-free fields (false: measure)"},
       {"ale_remesh_verbose", "0", "-", "1: show gmsh's messages while remeshing"},
       {"ale_remesh_test_fault", "0", "-",
        "1: corrupt the boundary given to gmsh; 2: fail on the new mesh (tests)"},
       {"ale_ksp_*, ale_pc_*", "cg, gamg", "-", "the mesh-motion linear solver"}}};
}

} // namespace fsi
