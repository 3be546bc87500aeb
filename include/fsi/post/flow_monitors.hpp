// Per-step monitors written as columns of monitor.csv:
//   -monitor_surfaces a,b   flux  Q = int v.n dA [m^3/s] (n outward of the fluid), area [m^2],
//                           force on the surface by the fluid F = -int sigma n dA [N],
//                           mean pressure [Pa], all on the current (deformed) configuration;
//   -probe_points x,y,z;... velocity and pressure at points of the reference mesh;
//   -monitor_fluid_volume   the fluid's volume on the current mesh [m^3];
//   -monitor_fluid_energy   kinetic energy int rho/2 |v|^2 [J], viscous dissipation
//                           int 2 mu D(v):D(v) [W] and the power the convective form puts in,
//                           int rho/2 (div v)|v|^2 [W] (weakly divergence-free velocity; the
//                           skew-symmetric form cancels it), on the current mesh;
//   with -exact_solution: L2 errors of velocity (at t_{n+1}) and pressure (at t_{n+alpha_f}, where
//   the generalized-alpha pressure lives; up to its mean where the flow does not fix the level)
//   and, at probes, the exact velocity.
#pragma once
#include "fsi/analytic/analytic.hpp"
#include "fsi/physics/fluid.hpp"
#include "fsi/post/monitor.hpp"
#include <string>
#include <vector>

namespace fsi {

struct ErrorNorms {
  double v_l2 = 0, p_l2 = 0, v_norm = 0, p_norm = 0;
  double div_l2 = 0; // ||div v_h||: the exact flow is divergence-free
};

class FlowMonitors : public Monitor {
public:
  void setup(const Mesh &mesh, const Space &space, const FluidModule *fluid,
             const ExactFlow *exact);
  bool active() const { return fluid_ != nullptr; }
  std::vector<std::string> columns() const;
  void add_to(MonitorRow &row, const FieldView &view) override {
    row.add(columns(), [&] { return evaluate(view); });
  }
  // The last errors against the exact flow (error_final).
  void summarize(Json &j, bool stepped) const override;

private:
  std::vector<double> evaluate(const FieldView &view);
  struct Probe {
    double x[3];
    int owner = -1;        // rank that evaluates it
    PetscInt cell = -1;    // local cell index on the owner
    double lambda[4] = {}; // barycentric coordinates in that cell
  };
  void energy(const PetscScalar *u, const std::vector<double> &Xc, double e[3]) const;
  ErrorNorms errors(const PetscScalar *u, const std::vector<double> &Xv, double tv,
                    const std::vector<double> &Xp, double tp) const;
  const Space *space_ = nullptr;
  const FluidModule *fluid_ = nullptr;
  const ExactFlow *exact_ = nullptr;
  std::vector<std::string> surf_names_;
  std::vector<std::vector<BoundaryFace>> surf_faces_;
  std::vector<Probe> probes_;
  ErrorNorms err_;
  bool volume_ = false, energy_ = false;
  MPI_Comm comm_ = MPI_COMM_NULL;
};

} // namespace fsi
