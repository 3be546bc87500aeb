// Closed-form flows used as boundary data, initial conditions and references for error norms:
// Ethier-Steinman (3D exact Navier-Stokes), Poiseuille and Womersley pipe flow (axis z, centre
// x = y = 0).  See shared/reference/benchmarks.md section 3 for the formulas.
#pragma once
#include "fsi/analytic/expression.hpp"
#include <memory>
#include <string>
#include <vector>

namespace fsi {

struct ExactFlow {
  virtual ~ExactFlow() = default;
  virtual void velocity(const double x[3], double t, double v[3]) const = 0;
  virtual double pressure(const double x[3], double t) const = 0;
  // grad[i][j] = d v_i / d x_j
  virtual void velocity_gradient(const double x[3], double t, double g[3][3]) const = 0;
  // Does the flow fix the pressure level (else the pressure is compared up to a constant)?
  virtual bool pressure_level_defined() const { return true; }
  // Cauchy stress sigma = -p I + mu (grad v + grad v^T).
  void stress(const double x[3], double t, double mu, double s[3][3]) const;
};

// Reads -exact_solution none|ethier_steinman|poiseuille|womersley and its -exact_* parameters.
// rho, mu: the fluid's.  Returns nullptr for none.
std::unique_ptr<ExactFlow> make_exact_flow(double rho, double mu);

// Scalar time functions for boundary data: -<prefix>waveform
// constant|step|pulse|cosine|sine|linear|table|expression, with -<prefix>t_off (step: 1 until
// t_off; pulse: sin^2(pi t / t_off) until t_off, a smooth bump whose value and slope vanish at
// both ends), -<prefix>period and -<prefix>offset (cosine/sine: offset + cos(2 pi t/T)),
// linear: t / period (a load factor for load stepping); table: -<prefix>table FILE of "t value"
// rows (# comments), linearly interpolated, held at its end values outside its range, or
// repeated with period t_last - t_first with -<prefix>periodic; expression: -<prefix>expr, a
// formula in t (expression.hpp); and an optional smooth start -<prefix>ramp [s].
struct WaveTable {
  std::vector<double> t, v;
  bool periodic = false;
  double operator()(double time) const;
  // Reads `file` (path as given by `option`); every defect is an InputError naming the file.
  static WaveTable read(const std::string &file, const std::string &option, bool periodic);
};

struct Waveform {
  enum Kind { Constant, Step, Pulse, Cosine, Sine, Linear, Table, Formula } kind = Constant;
  double t_off = 0, period = 1, ramp_time = 0, offset = 0;
  std::shared_ptr<const WaveTable> table;
  std::shared_ptr<const Expression> formula;
  double operator()(double t) const;
  static Waveform from_options(const std::string &prefix);
};

} // namespace fsi
