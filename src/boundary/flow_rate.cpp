// flow_rate: v = s(t) shape(x) on all components, with s(t) chosen every time the values are
// set so that the flux of the imposed (P2-interpolated) velocity through the boundary, on its
// current position, is Q(t) = value * waveform(t) [m^3/s] (positive into the fluid) to
// round-off.  Nodes of the boundary held by another type (a wall's rim) keep that type's
// value; their flux is accounted for.  Shapes, -bc_<name>_profile:
//   plug (default): the direction; parabolic: 1 - r^2/R^2 along the direction, r measured from
//   the axis through -bc_<name>_center (default: the face's area centroid), R = -bc_<name>_radius
//   (default: the largest vertex distance from that axis); expression: -bc_<name>_expr, one
//   value (speed along the direction) or three (a vector) in x, y, z, t.
// Direction: -bc_<name>_direction (default: the boundary's mean inward normal).
#include "fsi/boundary/boundary_condition.hpp"
#include "fsi/scene/options.hpp"

#include <array>
#include <cmath>
#include <memory>

namespace fsi {
namespace {

struct FlowRate : BoundaryCondition {
  double value_ = 1;
  Waveform wave_;
  std::array<double, 3> dir_ = {0, 0, 0};
  std::function<void(const double *, double, double *)> shape_; // resolved once
  double scale_ = 0;                                            // s(t) of the last prepare_values
  MPI_Comm comm_;
  std::string pre_;

  explicit FlowRate(const BoundarySetup &s)
      : BoundaryCondition(s, Data::velocity, true, true),
        comm_(PetscObjectComm((PetscObject)s.space.dm)), pre_(s.prefix()) {
    if (!fixed(0) || !fixed(1) || !fixed(2))
      throw InputError("-" + pre_ + "type flow_rate fixes all velocity components: drop -" + pre_ +
                       "components");
    value_ = opt::real(pre_ + "value", 1.0);
    wave_ = Waveform::from_options(pre_);
    // Area, area-weighted normal and centroid on the reference position.
    const double *X = s.space.X.data();
    double loc[7] = {0, 0, 0, 0, 0, 0, 0}, glob[7]; // area, area n, area centroid
    for (auto &f : faces_) {
      double n[3];
      const double area = 0.5 * outward_normal(f, X, n);
      loc[0] += area;
      for (int d = 0; d < 3; ++d) {
        loc[1 + d] += area * n[d];
        for (int i = 0; i < 3; ++i)
          loc[4 + d] += area * X[3 * f.vertex[i] + d] / 3;
      }
    }
    MPI_Allreduce(loc, glob, 7, MPI_DOUBLE, MPI_SUM, comm_);
    if (!(glob[0] > 0))
      throw InputError("boundary '" + name_ + "' has zero area: -" + pre_ +
                       "type flow_rate needs a surface of the fluid");
    if (opt::has(pre_ + "direction")) {
      read_direction(pre_ + "direction", dir_.data());
    } else {
      const double nn = std::sqrt(glob[1] * glob[1] + glob[2] * glob[2] + glob[3] * glob[3]);
      if (!(nn > 1e-12 * glob[0]))
        throw InputError("boundary '" + name_ + "' has no mean normal: give -" + pre_ +
                         "direction x,y,z");
      for (int d = 0; d < 3; ++d)
        dir_[d] = -glob[1 + d] / nn;
    }
    const std::string kind =
        opt::choice(pre_ + "profile", "plug", {"plug", "parabolic", "expression"});
    const auto dir = dir_;
    if (kind == "plug") {
      shape_ = [dir](const double *, double, double *v) {
        for (int d = 0; d < 3; ++d)
          v[d] = dir[d];
      };
    } else if (kind == "parabolic") {
      const std::array<double, 3> c =
          opt::has(pre_ + "center")
              ? read_point(pre_ + "center")
              : std::array<double, 3>{glob[4] / glob[0], glob[5] / glob[0], glob[6] / glob[0]};
      auto radial2 = [c, dir](const double *x) { return axis_distance2(x, c, dir); };
      double R2 = 0;
      if (opt::has(pre_ + "radius")) {
        R2 = std::pow(opt::required_positive(pre_ + "radius"), 2);
      } else {
        double mine = 0;
        for (auto &f : faces_)
          for (int i = 0; i < 3; ++i)
            mine = std::max(mine, radial2(&X[3 * f.vertex[i]]));
        MPI_Allreduce(&mine, &R2, 1, MPI_DOUBLE, MPI_MAX, comm_);
      }
      shape_ = [=](const double *x, double, double *v) {
        const double m = std::max(0.0, 1.0 - radial2(x) / R2);
        for (int d = 0; d < 3; ++d)
          v[d] = m * dir[d];
      };
    } else {
      auto e =
          std::make_shared<const Expression>(opt::required_string(pre_ + "expr"), pre_ + "expr", 0);
      if (e->size() != 1 && e->size() != 3)
        throw InputError("option -" + pre_ + "expr gives " + std::to_string(e->size()) +
                         " values: give 1 (speed along the direction) or 3 (a vector)");
      shape_ = [e, dir](const double *x, double t, double *v) {
        e->eval(x, t, v);
        if (e->size() == 1) {
          const double m = v[0];
          for (int d = 0; d < 3; ++d)
            v[d] = m * dir[d];
        }
      };
    }
  }

  std::string type() const override { return "flow_rate"; }

  // Flux of the interpolated velocity: on a flat P2 triangle the vertex functions integrate to
  // zero and the edge functions to area / 3, so the flux is exact from the edge nodes alone.
  void prepare_values(double t, const double *X, const std::vector<int> &setter, int self,
                      const OtherValues &others) override {
    double loc[2] = {0, 0}, glob[2]; // flux of the shape (own dofs), flux of others' dofs
    for (auto &f : faces_) {
      double n[3];
      const double w = 0.5 * outward_normal(f, X, n) / 3;
      for (int m = 0; m < 3; ++m) {
        double x[3], v[3], o[3];
        const int a = f.vertex[TRI_EDGE[m][0]], b = f.vertex[TRI_EDGE[m][1]];
        for (int d = 0; d < 3; ++d)
          x[d] = 0.5 * (X[3 * a + d] + X[3 * b + d]);
        shape_(x, t, v);
        int got = -1; // the boundary whose values are in o
        for (int d = 0; d < 3; ++d) {
          const int k = setter[f.vdof[3 + m] + d];
          if (k == self) {
            loc[0] -= w * v[d] * n[d]; // inflow positive
          } else if (k >= 0) {
            if (k != got) others(k, x, o), got = k;
            loc[1] -= w * o[d] * n[d];
          }
        }
      }
    }
    MPI_Allreduce(loc, glob, 2, MPI_DOUBLE, MPI_SUM, comm_);
    if (glob[0] == 0)
      throw InputError("-" + pre_ + "type flow_rate: the profile has no flux through '" + name_ +
                       "' (zero area, or every node held by another boundary)");
    scale_ = (value_ * wave_(t) - glob[1]) / glob[0];
  }

  void value(const double x[3], double t, double v[3]) const override {
    shape_(x, t, v);
    for (int d = 0; d < 3; ++d)
      v[d] *= scale_;
  }
};

} // namespace

std::unique_ptr<BoundaryCondition> make_flow_rate(const BoundarySetup &s) {
  return std::make_unique<FlowRate>(s);
}

} // namespace fsi
