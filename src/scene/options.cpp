#include "fsi/scene/options.hpp"
#include "fsi/scene/petsc_input.hpp"
#include <cctype>
#include <cerrno>
#include <cmath>

#include <cstdlib>
#include <malloc.h>
#include <sstream>
#include <sys/resource.h>

namespace fsi {

double peak_memory_mb() {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;
}

// Hands the heap's free pages back to the system.  After a whole run's data is freed (a remesh)
// glibc keeps most freed pages mapped and the heap fragments: without this the valve's peak
// memory grew ~100 MB per remesh (846 -> 1628 MB per rank in 7 remeshes; 850 -> 930 with it,
// at ~1 s per remesh for refaulting the pages; docs/performance.md).
void release_free_heap() {
  malloc_trim(0);
}

// PETSc's own words: the error class and the message of the call that failed.
void throw_petsc(PetscErrorCode ierr, const char *file, int line) {
  const char *text = nullptr;
  char *specific = nullptr;
  PetscErrorMessage(ierr, &text, &specific);
  // A misspelt type (-ksp_type nosuchksp) is the user's input: one line naming the option.
  if (ierr == PETSC_ERR_ARG_UNKNOWN_TYPE && specific && *specific)
    throw InputError(petsc_unknown_type(specific));
  std::string msg = "PETSc error " + std::to_string(ierr);
  if (text) msg += std::string(" (") + text + ")";
  if (specific && *specific) msg += std::string(": ") + specific;
  throw PetscFailure(msg + " at " + file + ":" + std::to_string(line));
}

void collective_output(MPI_Comm comm, const std::function<void()> &write) {
  std::string err;
  try {
    write();
  } catch (OutputError &e) {
    err = e.what();
  }
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  int mine = err.empty() ? size : rank, first;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size) return;
  int n = (int)err.size();
  MPI_Bcast(&n, 1, MPI_INT, first, comm);
  err.resize(n);
  MPI_Bcast(err.data(), n, MPI_CHAR, first, comm);
  throw OutputError(err);
}

namespace opt {

static std::string key(const std::string &name) {
  return "-" + name;
}

bool has(const std::string &name) {
  PetscBool set = PETSC_FALSE;
  FSI_CALL(PetscOptionsHasName(nullptr, nullptr, key(name).c_str(), &set));
  return set;
}

static bool raw(const std::string &name, std::string &value) {
  char buf[4096];
  PetscBool set = PETSC_FALSE;
  FSI_CALL(PetscOptionsGetString(nullptr, nullptr, key(name).c_str(), buf, sizeof buf, &set));
  if (set) value = buf;
  return set;
}

bool to_real(const std::string &text, double &v) {
  char *end = nullptr;
  v = std::strtod(text.c_str(), &end);
  return !text.empty() && *end == '\0';
}

static double parse_real(const std::string &name, const std::string &text) {
  double v;
  if (!to_real(text, v))
    throw InputError("option -" + name + " expects a number, got '" + text + "'");
  if (!std::isfinite(v))
    throw InputError("option -" + name + " expects a finite number, got '" + text + "'");
  return v;
}

// A number as given (1e-09, not 0.000000).
static std::string shortest(double v) {
  char buf[32];
  snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

double real(const std::string &name, double def) {
  std::string s;
  return raw(name, s) ? parse_real(name, s) : def;
}

double positive(const std::string &name, double def) {
  double v = real(name, def);
  if (!(v > 0))
    throw InputError("option -" + name + " must be positive, got " + shortest(v) +
                     ": give a value > 0");
  return v;
}

double nonnegative(const std::string &name, double def) {
  double v = real(name, def);
  if (!(v >= 0)) throw InputError("option -" + name + " must be >= 0, got " + shortest(v));
  return v;
}

double required_positive(const std::string &name) {
  if (!has(name)) throw InputError("missing option -" + name + " (a positive number)");
  return positive(name, 1.0);
}

long integer(const std::string &name, long def) {
  std::string s;
  if (!raw(name, s)) return def;
  char *end = nullptr;
  errno = 0;
  long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0')
    throw InputError("option -" + name + " expects an integer, got '" + s + "'");
  if (errno == ERANGE) throw InputError("option -" + name + " is out of range: '" + s + "'");
  return v;
}

long integer_at_least(const std::string &name, long def, long min) {
  const long v = integer(name, def);
  if (v < min)
    throw InputError("option -" + name + " must be >= " + std::to_string(min) + ", got " +
                     std::to_string(v));
  return v;
}

// A flag alone means true; PETSc's spellings of true and false are accepted.
bool flag(const std::string &name, bool def) {
  std::string s;
  if (!raw(name, s)) return def;
  std::string low;
  for (char c : s)
    low += (char)std::tolower((unsigned char)c);
  if (low.empty() || low == "true" || low == "yes" || low == "on" || low == "1") return true;
  if (low == "false" || low == "no" || low == "off" || low == "0") return false;
  throw InputError("option -" + name + " is a flag: give true or false (or nothing), got '" + s +
                   "'");
}

std::string string(const std::string &name, const std::string &def) {
  std::string s;
  return raw(name, s) ? s : def;
}

std::string required_string(const std::string &name) {
  std::string s;
  if (!raw(name, s) || s.empty()) throw InputError("missing option -" + name);
  return s;
}

std::string join(const std::vector<std::string> &v, const std::string &sep) {
  std::string out;
  for (size_t i = 0; i < v.size(); ++i)
    out += (i ? sep : "") + v[i];
  return out;
}

std::string choice(const std::string &name, const std::string &def,
                   const std::vector<std::string> &choices) {
  std::string s = string(name, def);
  for (auto &c : choices)
    if (c == s) return s;
  throw InputError("option -" + name + " has unknown value '" + s +
                   "'; use one of: " + join(choices));
}

std::vector<std::string> list(const std::string &name) {
  std::vector<std::string> out;
  std::string s;
  if (!raw(name, s)) return out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

std::vector<double> reals(const std::string &name) {
  std::vector<double> out;
  for (auto &s : list(name))
    out.push_back(parse_real(name, s));
  return out;
}

} // namespace opt
} // namespace fsi
