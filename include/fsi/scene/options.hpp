// Typed access to PETSc options with validation. Every reader records the option as used, so
// -options_left reports only options nobody reads; every failure is an InputError naming the
// option and what would be accepted.
#pragma once
#include "fsi/common.hpp"
#include <string>
#include <vector>

namespace fsi::opt {

bool has(const std::string &name);
double real(const std::string &name, double def);
double positive(const std::string &name, double def);    // > 0
double nonnegative(const std::string &name, double def); // >= 0
double required_positive(const std::string &name);
long integer(const std::string &name, long def);
long integer_at_least(const std::string &name, long def, long min); // >= min
bool flag(const std::string &name, bool def);
std::string string(const std::string &name, const std::string &def);
std::string required_string(const std::string &name);
// One of `choices`; anything else is an InputError listing them.
std::string choice(const std::string &name, const std::string &def,
                   const std::vector<std::string> &choices);
std::vector<std::string> list(const std::string &name); // comma separated, may be empty
std::vector<double> reals(const std::string &name);     // comma separated numbers
bool to_real(const std::string &text, double &v);       // the whole text is one number

std::string join(const std::vector<std::string> &v, const std::string &sep = ", ");

} // namespace fsi::opt
