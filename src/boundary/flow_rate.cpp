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
// Backflow stop (the paper's rule: "diastole starts when the valve is closed and the inflow is
// set to zero"): -bc_<name>_stop_backflow_when COLUMN<VALUE (or >) names a monitor column
// (monitor.csv) and a threshold, e.g. contact_pairs>20 or valve_goa_ratio<0.1.  At the end of
// an accepted step in which the waveform's flow is backwards (Q < 0) and the condition holds,
// the flow is ramped to zero over -bc_<name>_stop_ramp seconds (default 5 ms; a smooth step,
// since an abrupt stop of a moving column is a pressure spike) and held there until the
// waveform's flow turns forward again (the next systole).  Monitored as <name>_flow_factor
// (1: the waveform's flow, 0: stopped); the state is kept in checkpoints and rebuilt runs.
#include "fsi/boundary/boundary_condition.hpp"
#include "fsi/post/monitor_condition.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <string>

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

  // Backflow stop: the condition on a monitor column, the ramp, the latch.
  MonitorCondition stop_;
  double stop_ramp_ = 0.005;
  bool stopped_ = false;
  double stop_time_ = 0;
  double factor_last_ = 1; // of the last prepared time, monitored

  explicit FlowRate(const BoundarySetup &s)
      : BoundaryCondition(s, Data::velocity, true, true),
        comm_(PetscObjectComm((PetscObject)s.space.dm)), pre_(s.prefix()) {
    if (!fixed(0) || !fixed(1) || !fixed(2))
      throw InputError("-" + pre_ + "type flow_rate fixes all velocity components: drop -" + pre_ +
                       "components");
    value_ = opt::real(pre_ + "value", 1.0);
    wave_ = Waveform::from_options(pre_);
    read_stop_condition();
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
      double mine = 0, far2 = 0; // the farthest vertex from the axis
      for (auto &f : faces_)
        for (int i = 0; i < 3; ++i)
          mine = std::max(mine, radial2(&X[3 * f.vertex[i]]));
      MPI_Allreduce(&mine, &far2, 1, MPI_DOUBLE, MPI_MAX, comm_);
      const double R2 =
          opt::has(pre_ + "radius") ? std::pow(opt::required_positive(pre_ + "radius"), 2) : far2;
      check_disc(glob[0], R2, far2);
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

  // A parabolic profile needs the face to be (nearly) the disc it describes: its area at least
  // 80 % of pi R^2 (a disc meshed with 8 segments has 90 %) and every vertex inside the circle,
  // or the profile carries its flux on part of the face or on none of it.
  void check_disc(double area, double R2, double far2) const {
    if (far2 > R2 * (1 + 1e-6) || area < 0.8 * M_PI * R2)
      throw InputError("boundary '" + name_ + "': the parabolic profile's circle (radius " +
                       std::to_string(std::sqrt(R2)) + " m) does not match the face (area " +
                       std::to_string(area) + " m^2, farthest vertex " +
                       std::to_string(std::sqrt(far2)) + " m from the axis): give -" + pre_ +
                       "center and -" + pre_ + "radius of the disc, or -" + pre_ + "profile plug");
  }

  void read_stop_condition() {
    stop_ramp_ = opt::nonnegative(pre_ + "stop_ramp", 0.005);
    stop_ = MonitorCondition::from_option(pre_ + "stop_backflow_when");
  }
  void bind_monitors(const std::vector<std::string> &columns) override { stop_.bind(columns); }
  // The waveform's flow times the stop's factor: 1 open, a smooth step down to 0 over the ramp
  // once stopped, back to 1 as soon as the waveform's flow is forward.
  double flow_factor(double t) const {
    if (!stopped_ || value_ * wave_(t) > 0) return 1;
    if (stop_ramp_ <= 0) return 0;
    const double x = std::clamp((t - stop_time_) / stop_ramp_, 0.0, 1.0);
    return 1 - x * x * (3 - 2 * x);
  }
  void observe(double t, const std::vector<double> &row) override {
    if (!stop_) return;
    const double q = value_ * wave_(t);
    double m = 0;
    const bool met = stop_.holds(row, comm_, &m);
    if (stopped_ && q > 0) {
      stopped_ = false;
      PetscPrintf(comm_, "  boundary '%s': the flow turns forward at t = %.6g s: inflow on\n",
                  name_.c_str(), t);
    } else if (!stopped_ && q < 0 && met) {
      stopped_ = true, stop_time_ = t;
      PetscPrintf(comm_,
                  "  boundary '%s': %s = %g %c %g during backflow at t = %.6g s: the inflow "
                  "stops (ramp %g s)\n",
                  name_.c_str(), stop_.column.c_str(), m, stop_.op, stop_.value, t, stop_ramp_);
    }
  }
  void save_state(std::map<std::string, double> &s) const override {
    if (!stop_) return;
    s[name_ + "_stopped"] = stopped_;
    s[name_ + "_stop_time"] = stop_time_;
  }
  // A state written without the stop (a systole run continued with it) resumes open.
  void restore_state(const std::map<std::string, double> &s) override {
    auto a = s.find(name_ + "_stopped"), b = s.find(name_ + "_stop_time");
    if (!stop_ || a == s.end() || b == s.end()) return;
    stopped_ = a->second != 0, stop_time_ = b->second;
  }
  std::vector<std::string> monitor_columns() const override {
    if (!stop_) return {};
    return {name_ + "_flow_factor"};
  }
  std::vector<double> monitor_values() const override {
    if (!stop_) return {};
    return {factor_last_};
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
    factor_last_ = flow_factor(t);
    scale_ = (value_ * wave_(t) * factor_last_ - glob[1]) / glob[0];
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
