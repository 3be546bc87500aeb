#include "fsi/post/monitor_condition.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <cmath>

namespace fsi {

MonitorCondition MonitorCondition::from_option(const std::string &option) {
  MonitorCondition c;
  c.option = option;
  if (!opt::has(option)) return c;
  const std::string s = opt::required_string(option);
  const size_t at = s.find_first_of("<>");
  const std::string bad = "option -" + option + " '" + s +
                          "': give a monitor column, < or >, and a number (e.g. contact_pairs>20)";
  if (at == std::string::npos || at == 0 || at + 1 >= s.size()) throw InputError(bad);
  c.column = s.substr(0, at);
  c.op = s[at];
  if (!opt::to_real(s.substr(at + 1), c.value) || !std::isfinite(c.value)) throw InputError(bad);
  return c;
}

void MonitorCondition::bind(const std::vector<std::string> &columns) {
  if (!op) return;
  auto it = std::find(columns.begin(), columns.end(), column);
  if (it == columns.end())
    throw InputError("option -" + option + ": the run has no monitor column '" + column +
                     "'; its columns: " + opt::join(columns));
  index = it - columns.begin();
}

bool MonitorCondition::holds(const std::vector<double> &row, MPI_Comm comm, double *seen) const {
  if (!op || index < 0) return false;
  double m = row[index];
  MPI_Bcast(&m, 1, MPI_DOUBLE, 0, comm); // one decision on every rank, whatever the column
  if (seen) *seen = m;
  return op == '<' ? m < value : m > value;
}

} // namespace fsi
