// Tabulated waveforms: "t value" rows, linear interpolation, optional periodic repeat.
#include "fsi/analytic/analytic.hpp"
#include "fsi/common.hpp"
#include "fsi/mesh/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace fsi {

WaveTable WaveTable::read(const std::string &file, const std::string &option, bool periodic) {
  const std::string path = resolve_path(file);
  std::ifstream in(path);
  if (!in)
    throw InputError("waveform table " + file + " (option -" + option +
                     ") cannot be read: check the path (relative to the run directory or the "
                     "project)");
  WaveTable w;
  w.periodic = periodic;
  std::string line;
  for (int row = 1; std::getline(in, line); ++row) {
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream ss(line);
    std::string a, b, extra;
    if (!(ss >> a)) continue; // blank or comment
    const std::string where = file + " line " + std::to_string(row) + " (option -" + option + ")";
    if (!(ss >> b) || (ss >> extra))
      throw InputError("waveform table " + where + ": expected two numbers 't value'");
    double t, v;
    try {
      size_t na, nb;
      t = std::stod(a, &na);
      v = std::stod(b, &nb);
      if (na != a.size() || nb != b.size()) throw std::invalid_argument("trailing");
    } catch (std::exception &) {
      throw InputError("waveform table " + where + ": '" + a + " " + b + "' is not two numbers");
    }
    if (!std::isfinite(t) || !std::isfinite(v))
      throw InputError("waveform table " + where + ": not a finite number");
    if (!w.t.empty() && t <= w.t.back())
      throw InputError("waveform table " + where + ": times must increase (" + a + " follows " +
                       std::to_string(w.t.back()) + ")");
    w.t.push_back(t);
    w.v.push_back(v);
  }
  if (w.t.size() < 2)
    throw InputError("waveform table " + file + " (option -" + option +
                     "): needs at least two rows of 't value'");
  return w;
}

double WaveTable::operator()(double time) const {
  if (periodic) { // map into [t_0, t_last)
    const double T = t.back() - t.front();
    time = t.front() + std::fmod(std::fmod(time - t.front(), T) + T, T);
  }
  if (time <= t.front()) return v.front();
  if (time >= t.back()) return v.back();
  const size_t i = std::upper_bound(t.begin(), t.end(), time) - t.begin(); // t[i-1] <= time < t[i]
  const double s = (time - t[i - 1]) / (t[i] - t[i - 1]);
  return (1 - s) * v[i - 1] + s * v[i];
}

} // namespace fsi
