// Loads the gmsh module (libfsi_gmsh.so) on first use and forwards to it
// (include/fsi/mesh/gmsh_module.hpp says why gmsh is not linked into fsi_app).
#include "fsi/common.hpp"
#include "fsi/mesh/gmsh_module.hpp"

#include <dlfcn.h>
#include <unistd.h>

#ifndef FSI_GMSH_MODULE_DIR
#define FSI_GMSH_MODULE_DIR "."
#endif

namespace fsi::gmsh_module {
namespace {

// The module next to the running executable, else in the build folder it was built in (a copy
// of the executable elsewhere still finds it).
void *module() {
  static void *handle = nullptr;
  if (handle) return handle;
  std::vector<std::string> tried;
  char exe[4096];
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n > 0) {
    std::string dir(exe, n);
    tried.push_back(dir.substr(0, dir.find_last_of('/')) + "/libfsi_gmsh.so");
  }
  const std::string built = std::string(FSI_GMSH_MODULE_DIR) + "/libfsi_gmsh.so";
  if (tried.empty() || tried[0] != built) tried.push_back(built);
  std::string why;
  for (auto &path : tried) {
    handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle) return handle;
    why += (why.empty() ? "" : "; ") + std::string(dlerror());
  }
  throw InputError("cannot load fsi_app's gmsh module (" + why +
                   "): build it with scripts/setup (it is build/libfsi_gmsh.so)");
}

template <class F> F symbol(const char *name) {
  void *f = dlsym(module(), name);
  if (!f)
    throw InputError(std::string("the gmsh module lacks ") + name + ": rebuild with scripts/setup");
  return reinterpret_cast<F>(f);
}

} // namespace

Status mesh_geo(const std::vector<std::string> &args, const std::string &geo, double h,
                double max_cells, const std::string &out) {
  using Fn = void (*)(const std::vector<std::string> *, const std::string *, double, double,
                      const std::string *, Status *);
  static const Fn fn = symbol<Fn>("fsi_gmsh_mesh_geo");
  Status st;
  fn(&args, &geo, h, max_cells, &out, &st);
  return st;
}

Status mesh_volume(std::vector<std::array<double, 3>> &x,
                   const std::vector<std::vector<std::array<int, 3>>> &surfaces,
                   const std::vector<std::array<double, 4>> &gaps, double hmax, bool verbose,
                   std::vector<std::array<int, 4>> &tets) {
  using Fn = void (*)(std::vector<std::array<double, 3>> *,
                      const std::vector<std::vector<std::array<int, 3>>> *,
                      const std::vector<std::array<double, 4>> *, double, bool,
                      std::vector<std::array<int, 4>> *, Status *);
  static const Fn fn = symbol<Fn>("fsi_gmsh_mesh_volume");
  Status st;
  fn(&x, &surfaces, &gaps, hmax, verbose, &tets, &st);
  return st;
}

} // namespace fsi::gmsh_module
