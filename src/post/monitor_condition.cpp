#include "fsi/post/monitor_condition.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace fsi {

MonitorCondition MonitorCondition::from_option(const std::string &option) {
  MonitorCondition c;
  c.option = option;
  if (!opt::has(option)) return c;
  const std::string all = opt::required_string(option);
  const std::string bad = "option -" + option + " '" + all +
                          "': give a monitor column, < or >, and a number (e.g. contact_pairs>20), "
                          "several joined by &";
  size_t from = 0;
  while (true) {
    const size_t amp = all.find('&', from);
    const std::string s = all.substr(from, amp == std::string::npos ? amp : amp - from);
    const size_t at = s.find_first_of("<>");
    Term t;
    if (at == std::string::npos || at == 0 || at + 1 >= s.size()) throw InputError(bad);
    t.column = s.substr(0, at);
    t.op = s[at];
    if (!opt::to_real(s.substr(at + 1), t.value) || !std::isfinite(t.value)) throw InputError(bad);
    if (!c.op)
      c.column = t.column, c.op = t.op, c.value = t.value;
    else
      c.more.push_back(t);
    if (amp == std::string::npos) break;
    from = amp + 1;
  }
  return c;
}

void MonitorCondition::bind(const std::vector<std::string> &columns) {
  if (!op) return;
  auto place = [&](const std::string &name) -> long {
    auto it = std::find(columns.begin(), columns.end(), name);
    if (it == columns.end())
      throw InputError("option -" + option + ": the run has no monitor column '" + name +
                       "'; its columns: " + opt::join(columns));
    return it - columns.begin();
  };
  index = place(column);
  for (Term &t : more)
    t.index = place(t.column);
}

std::string MonitorCondition::rest() const {
  std::string r;
  for (const Term &t : more) {
    char v[64];
    std::snprintf(v, sizeof v, "%g", t.value);
    r += " & " + t.column + t.op + v;
  }
  return r;
}

bool MonitorCondition::holds(const std::vector<double> &row, MPI_Comm comm, double *seen) const {
  if (!op || index < 0) return false;
  std::vector<double> m{row[index]};
  for (const Term &t : more)
    m.push_back(row[t.index]);
  // one decision on every rank, whatever the columns
  MPI_Bcast(m.data(), (int)m.size(), MPI_DOUBLE, 0, comm);
  if (seen) *seen = m[0];
  bool all = op == '<' ? m[0] < value : m[0] > value;
  for (size_t k = 0; k < more.size(); ++k)
    all = all && (more[k].op == '<' ? m[k + 1] < more[k].value : m[k + 1] > more[k].value);
  return all;
}

} // namespace fsi
