#pragma once
// A condition on a monitor.csv column, given as an option value COLUMN<VALUE or COLUMN>VALUE
// (e.g. contact_pairs>20), or several joined by & that must all hold
// (inlet_flow_factor<1&contact_pairs<1): what a run may react to once a step is accepted (a flow
// that stops when the valve has closed, more numerical damping from then on).
#include <mpi.h>

#include <string>
#include <vector>

namespace fsi {

struct MonitorCondition {
  std::string option; // the option that gave it, for messages
  // The first term (named in messages); `more`: the terms after &.
  std::string column;
  char op = 0; // '<' or '>'; 0: no condition (the option was not given)
  double value = 0;
  long index = -1; // the column's place in a monitor row, once bound
  struct Term {
    std::string column;
    char op;
    double value;
    long index = -1;
  };
  std::vector<Term> more;

  // Reads -option if given (a malformed value is an InputError naming the option and the form).
  static MonitorCondition from_option(const std::string &option);
  explicit operator bool() const { return op != 0; }
  // Finds the column among the run's monitor columns (an InputError listing them if absent).
  void bind(const std::vector<std::string> &columns);
  // The terms after the first as text (" & contact_pairs<1"), for messages; "" for one term.
  std::string rest() const;
  // Whether rank 0's row meets the condition (one decision on every rank); `seen`: the value.
  bool holds(const std::vector<double> &row, MPI_Comm comm, double *seen = nullptr) const;
};

} // namespace fsi
