// One row of monitor.csv, by name: each source adds its own values under its own names
// (row.add("contact_pairs", n)), so that no value is paired with a column by its position in
// another list.  The same code fills a names-only row (the columns, before any step) and a row of
// values after a step: what a source adds is its column list by construction.
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

namespace fsi {

class MonitorRow {
public:
  enum Mode { names_only, with_values };
  explicit MonitorRow(Mode mode) : values_wanted_(mode == with_values) {}
  bool wants_values() const { return values_wanted_; }

  void add(const std::string &name, double value) {
    names_.push_back(name);
    if (values_wanted_) values_.push_back(value);
  }
  // A source with its own column list: `evaluate()` (called only when values are wanted) must
  // return one value per name.
  template <class Evaluate> void add(const std::vector<std::string> &names, Evaluate &&evaluate) {
    if (values_wanted_) {
      const std::vector<double> v = evaluate();
      if (v.size() != names.size())
        throw std::logic_error("monitor row: " + std::to_string(v.size()) + " values for " +
                               std::to_string(names.size()) + " columns starting at '" +
                               (names.empty() ? std::string("?") : names[0]) + "'");
      values_.insert(values_.end(), v.begin(), v.end());
    }
    names_.insert(names_.end(), names.begin(), names.end());
  }

  const std::vector<std::string> &names() const { return names_; }
  const std::vector<double> &values() const { return values_; }

private:
  bool values_wanted_;
  std::vector<std::string> names_;
  std::vector<double> values_;
};

} // namespace fsi
