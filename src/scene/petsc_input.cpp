#include "fsi/scene/petsc_input.hpp"
#include "fsi/common.hpp"
#include "fsi/scene/options.hpp"

#include <cctype>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace fsi {

namespace {

// A key is "-" followed by a letter; "-1" or "-.5" is a value.
bool is_key(const std::string &t) {
  return t.size() > 1 && t[0] == '-' && std::isalpha((unsigned char)t[1]);
}

bool readable(const std::string &path) {
  return access(path.c_str(), R_OK) == 0;
}

std::string check_file(const std::string &path, const std::string &from, int depth) {
  if (!readable(path))
    return "-options_file " + path + from +
           ": no such file (paths are relative to the directory fsi_app runs in: run it from the "
           "repository root, or give the file's full path)";
  if (depth > 8) return "-options_file " + path + ": options files include each other in a loop";
  try {
    for (auto &kv : read_options_file(path))
      if (kv.first == "options_file") {
        std::string e = check_file(kv.second, " (included by " + path + ")", depth + 1);
        if (!e.empty()) return e;
      }
  } catch (InputError &e) {
    return e.what();
  }
  return "";
}

std::string preset_path(const std::string &name) {
  if (name.size() > 5 && name.compare(name.size() - 5, 5, ".opts") == 0) return name;
  const std::string here = "petsc_options/" + name + ".opts";
  if (readable(here)) return here;
  return std::string(FSI_SOURCE_DIR) + "/petsc_options/" + name + ".opts";
}

// PETSc's "unknown type" errors return without a traceback (throw_petsc makes them one line);
// every other error keeps PETSc's own handler.
PetscErrorCode quiet_unknown_type(MPI_Comm comm, int line, const char *fun, const char *file,
                                  PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx) {
  if (n == PETSC_ERR_ARG_UNKNOWN_TYPE) return n;
  return PetscTraceBackErrorHandler(comm, line, fun, file, n, p, mess, ctx);
}

} // namespace

std::vector<std::pair<std::string, std::string>> read_options_file(const std::string &path) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot read options file " + path);
  std::vector<std::string> tokens;
  std::string line;
  while (std::getline(in, line)) {
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::string w;
    while (words >> w)
      tokens.push_back(w);
  }
  std::vector<std::pair<std::string, std::string>> out;
  for (size_t i = 0; i < tokens.size(); ++i) {
    if (!is_key(tokens[i])) continue; // a stray value: PETSc ignores it too
    const std::string key = tokens[i].substr(1);
    const bool has_value = i + 1 < tokens.size() && !is_key(tokens[i + 1]);
    out.emplace_back(key, has_value ? tokens[++i] : std::string());
  }
  return out;
}

std::string check_options_files(int argc, char **argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) != "-options_file") continue;
    if (i + 1 >= argc) return "-options_file needs a file name";
    std::string e = check_file(argv[i + 1], "", 0);
    if (!e.empty()) return e;
  }
  return "";
}

bool options_files_exist(int argc, char **argv) {
  const std::string missing = check_options_files(argc, argv);
  if (missing.empty()) return true;
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0) fprintf(stderr, "fsi_app: error: %s\n", missing.c_str());
  return false;
}

void apply_solver_preset() {
  if (!opt::has("solver_preset")) return;
  const std::string name = opt::string("solver_preset", "");
  if (name.empty())
    throw InputError("option -solver_preset needs a preset name, e.g. -solver_preset direct "
                     "(the files in petsc_options/)");
  const std::string path = preset_path(name);
  if (!readable(path))
    throw InputError("option -solver_preset: no preset '" + name +
                     "' (petsc_options/NAME.opts, or a path ending in .opts); e.g. "
                     "-solver_preset direct");
  for (auto &kv : read_options_file(path)) {
    if (kv.first == "solver_preset" || opt::has(kv.first)) continue; // the scene's own wins
    const std::string key = "-" + kv.first;
    FSI_CALL(PetscOptionsSetValue(nullptr, key.c_str(),
                                  kv.second.empty() ? nullptr : kv.second.c_str()));
  }
}

void install_petsc_error_handler() {
  FSI_CALL(PetscPushErrorHandler(quiet_unknown_type, nullptr));
}

std::string petsc_unknown_type(const std::string &petsc_message) {
  // PETSc: "Unable to find requested KSP type nosuchksp" (the type is the last word).
  std::string type = petsc_message;
  while (!type.empty() && std::isspace((unsigned char)type.back()))
    type.pop_back();
  type = type.substr(type.find_last_of(" \t") + 1);
  char *all = nullptr;
  std::string option;
  if (PetscOptionsGetAll(nullptr, &all) == 0 && all) {
    std::istringstream words(all);
    std::string prev, w;
    while (words >> w) {
      if (w == type && is_key(prev)) option = prev;
      prev = w;
    }
    PetscFree(all);
  }
  return (option.empty() ? std::string("a PETSc type option") : "option " + option) +
         " has unknown value '" + type + "' (PETSc: " + petsc_message +
         "); see the PETSc manual for the types, or petsc_options/ for working presets";
}

} // namespace fsi
