#include "fsi/analytic/analytic.hpp"
#include "fsi/scene/option_doc.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

namespace fsi {

void ExactFlow::stress(const double x[3], double t, double mu, double s[3][3]) const {
  double g[3][3];
  velocity_gradient(x, t, g);
  const double p = pressure(x, t);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      s[i][j] = mu * (g[i][j] + g[j][i]) - (i == j ? p : 0.0);
}

namespace {

// Ethier & Steinman (1994), rho = constant, nu = mu/rho, a = pi/4, d = pi/2.  The pressure
// carries the minus sign of the original paper and is scaled by rho.
struct EthierSteinman : ExactFlow {
  double a = M_PI / 4, d = M_PI / 2, nu, rho;
  EthierSteinman(double rho_, double mu) : nu(mu / rho_), rho(rho_) {}
  // Component i of the velocity uses the cyclic permutation (x, y, z) -> (y, z, x).
  void velocity(const double x[3], double t, double v[3]) const override {
    const double decay = std::exp(-nu * d * d * t);
    for (int i = 0; i < 3; ++i) {
      const double X = x[i], Y = x[(i + 1) % 3], Z = x[(i + 2) % 3];
      v[i] =
          -a *
          (std::exp(a * X) * std::sin(a * Y + d * Z) + std::exp(a * Z) * std::cos(a * X + d * Y)) *
          decay;
    }
  }
  void velocity_gradient(const double x[3], double t, double g[3][3]) const override {
    const double decay = std::exp(-nu * d * d * t);
    for (int i = 0; i < 3; ++i) {
      const int iX = i, iY = (i + 1) % 3, iZ = (i + 2) % 3;
      const double X = x[iX], Y = x[iY], Z = x[iZ];
      const double e1 = std::exp(a * X), s1 = std::sin(a * Y + d * Z), c1 = std::cos(a * Y + d * Z);
      const double e2 = std::exp(a * Z), c2 = std::cos(a * X + d * Y), s2 = std::sin(a * X + d * Y);
      g[i][iX] = -a * (a * e1 * s1 - a * e2 * s2) * decay;
      g[i][iY] = -a * (a * e1 * c1 - d * e2 * s2) * decay;
      g[i][iZ] = -a * (d * e1 * c1 + a * e2 * c2) * decay;
    }
  }
  double pressure(const double x[3], double t) const override {
    const double X = x[0], Y = x[1], Z = x[2];
    const double s = std::exp(2 * a * X) + std::exp(2 * a * Y) + std::exp(2 * a * Z) +
                     2 * std::sin(a * X + d * Y) * std::cos(a * Z + d * X) * std::exp(a * (Y + Z)) +
                     2 * std::sin(a * Y + d * Z) * std::cos(a * X + d * Y) * std::exp(a * (Z + X)) +
                     2 * std::sin(a * Z + d * X) * std::cos(a * Y + d * Z) * std::exp(a * (X + Y));
    return -rho * a * a / 2 * s * std::exp(-2 * nu * d * d * t);
  }
  bool pressure_level_defined() const override { return false; }
};

// Steady Poiseuille flow along +z, driven by -dp/dz = G; p = G (L - z).
struct Poiseuille : ExactFlow {
  double G, R, mu, L;
  Poiseuille(double G_, double R_, double mu_, double L_) : G(G_), R(R_), mu(mu_), L(L_) {}
  void velocity(const double x[3], double, double v[3]) const override {
    const double r2 = x[0] * x[0] + x[1] * x[1];
    v[0] = v[1] = 0;
    v[2] = G * (R * R - r2) / (4 * mu);
  }
  void velocity_gradient(const double x[3], double, double g[3][3]) const override {
    for (int i = 0; i < 3; ++i)
      g[i][0] = g[i][1] = g[i][2] = 0;
    g[2][0] = -G * x[0] / (2 * mu);
    g[2][1] = -G * x[1] / (2 * mu);
  }
  double pressure(const double x[3], double) const override { return G * (L - x[2]); }
};

using cplx = std::complex<double>;

// Bessel functions of the first kind, orders 0 and 1, complex argument (power series; accurate
// for |z| < 20, ample for Womersley numbers up to ~15).
cplx bessel_j(int n, cplx z) {
  cplx term = std::pow(z / 2.0, n), sum = 0;
  for (int k = 1; k <= n; ++k)
    term /= double(k);
  const cplx q = -(z * z) / 4.0;
  for (int k = 0; k < 200; ++k) {
    sum += term;
    term *= q / (double(k + 1) * double(k + 1 + n));
    if (std::abs(term) < 1e-18 * std::abs(sum)) break;
  }
  return sum;
}

// Womersley flow along +z driven by -dp/dz = A cos(omega t); p = A (L - z) cos(omega t).
struct Womersley : ExactFlow {
  double A, omega, R, rho, mu, L;
  cplx Lambda, J0L;
  Womersley(double A_, double period, double R_, double rho_, double mu_, double L_)
      : A(A_), omega(2 * M_PI / period), R(R_), rho(rho_), mu(mu_), L(L_) {
    const double alpha = R * std::sqrt(omega * rho / mu);
    Lambda = std::pow(cplx(0, 1), 1.5) * alpha;
    J0L = bessel_j(0, Lambda);
  }
  cplx coef(double t) const {
    return A / (cplx(0, 1) * omega * rho) * std::exp(cplx(0, omega * t));
  }
  void velocity(const double x[3], double t, double v[3]) const override {
    const double r = std::sqrt(x[0] * x[0] + x[1] * x[1]);
    v[0] = v[1] = 0;
    v[2] = std::real(coef(t) * (1.0 - bessel_j(0, Lambda * r / R) / J0L));
  }
  void velocity_gradient(const double x[3], double t, double g[3][3]) const override {
    for (int i = 0; i < 3; ++i)
      g[i][0] = g[i][1] = g[i][2] = 0;
    const double r = std::sqrt(x[0] * x[0] + x[1] * x[1]);
    if (r < 1e-300) return;
    // d/dr [1 - J0(k r)/J0(Lambda)] = k J1(k r) / J0(Lambda), k = Lambda / R
    const cplx k = Lambda / R;
    const double dwdr = std::real(coef(t) * k * bessel_j(1, k * r) / J0L);
    g[2][0] = dwdr * x[0] / r;
    g[2][1] = dwdr * x[1] / r;
  }
  double pressure(const double x[3], double t) const override {
    return A * (L - x[2]) * std::cos(omega * t);
  }
};

} // namespace

std::unique_ptr<ExactFlow> make_exact_flow(double rho, double mu) {
  const std::string kind =
      opt::choice("exact_solution", "none", {"none", "ethier_steinman", "poiseuille", "womersley"});
  if (kind == "ethier_steinman") return std::make_unique<EthierSteinman>(rho, mu);
  if (kind == "poiseuille")
    return std::make_unique<Poiseuille>(opt::required_positive("exact_G"),
                                        opt::required_positive("exact_R"), mu,
                                        opt::nonnegative("exact_L", 0));
  if (kind == "womersley")
    return std::make_unique<Womersley>(
        opt::required_positive("exact_A"), opt::required_positive("exact_period"),
        opt::required_positive("exact_R"), rho, mu, opt::nonnegative("exact_L", 0));
  return nullptr;
}

double Waveform::operator()(double t) const {
  double ramp = (ramp_time > 0 && t < ramp_time) ? 0.5 * (1 - std::cos(M_PI * t / ramp_time)) : 1.0;
  switch (kind) {
  case Step:
    return t <= t_off + 1e-12 * std::fabs(t_off) ? 1.0 : 0.0;
  case Pulse: { // sin^2 bump over [0, t_off]: value and slope continuous (second order)
    if (t >= t_off) return 0.0;
    const double s = std::sin(M_PI * t / t_off);
    return s * s;
  }
  case Cosine:
    return ramp * (offset + std::cos(2 * M_PI * t / period));
  case Sine:
    return ramp * (offset + std::sin(2 * M_PI * t / period));
  case Linear:
    return ramp * t / period;
  case Table:
    return ramp * (*table)(t);
  case Formula:
    return ramp * formula->scalar(t);
  default:
    return ramp;
  }
}

Waveform Waveform::from_options(const std::string &prefix) {
  Waveform w;
  const std::vector<std::string> kinds = {"constant", "step",   "pulse", "cosine",
                                          "sine",     "linear", "table", "expression"};
  const std::string k = opt::choice(prefix + "waveform", "constant", kinds);
  w.kind = Kind(std::find(kinds.begin(), kinds.end(), k) - kinds.begin()); // resolved once
  if (w.kind == Step || w.kind == Pulse) w.t_off = opt::required_positive(prefix + "t_off");
  if (w.kind == Linear) w.period = opt::required_positive(prefix + "period");
  if (w.kind == Cosine || w.kind == Sine) {
    w.period = opt::required_positive(prefix + "period");
    w.offset = opt::real(prefix + "offset", 0.0);
  }
  if (w.kind == Table)
    w.table = std::make_shared<const WaveTable>(
        WaveTable::read(opt::required_string(prefix + "table"), prefix + "table",
                        opt::flag(prefix + "periodic", false)));
  if (w.kind == Formula)
    w.formula = std::make_shared<const Expression>(opt::required_string(prefix + "expr"),
                                                   prefix + "expr", 1);
  w.ramp_time = opt::nonnegative(prefix + "ramp", 0);
  return w;
}

// Its options, for -help and docs/options.md (option_doc.hpp).
OptionSection exact_flow_options() {
  return {"Verification (exact flows)",
          {{"exact_solution", "none", "-", "none | ethier_steinman | poiseuille | womersley"},
           {"exact_G", "", "Pa/m", "poiseuille: pressure gradient"},
           {"exact_A", "", "Pa/m", "womersley: pressure-gradient amplitude"},
           {"exact_period", "", "s", "womersley: period"},
           {"exact_R", "", "m", "pipe radius"},
           {"exact_L", "0", "m", "pipe length (pressure level)"}}};
}

} // namespace fsi
