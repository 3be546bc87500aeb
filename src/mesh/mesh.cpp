#include "fsi/mesh/mesh.hpp"
#include "fsi/mesh/gmsh_module.hpp"
#include "fsi/scene/option_doc.hpp"
#include "fsi/scene/options.hpp"

#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

#ifndef FSI_SOURCE_DIR
#define FSI_SOURCE_DIR "."
#endif

namespace fsi {

Mesh::~Mesh() {
  if (dm) DMDestroy(&dm);
}

static bool file_exists(const std::string &p) {
  struct stat st;
  return stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

std::string resolve_path(const std::string &path) {
  if (path.empty() || path[0] == '/' || file_exists(path)) return path;
  std::string alt = std::string(FSI_SOURCE_DIR) + "/" + path;
  return file_exists(alt) ? alt : path;
}

bool Mesh::has_group(const std::string &name) const {
  PetscBool has = PETSC_FALSE;
  FSI_CALL(DMHasLabel(dm, name.c_str(), &has));
  int local = has ? 1 : 0, global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_INT, MPI_MAX, PetscObjectComm((PetscObject)dm));
  return global != 0;
}

DMLabel Mesh::label(const std::string &name) const {
  if (!has_group(name))
    throw InputError("mesh " + source + " has no physical group '" + name + "'");
  PetscBool has = PETSC_FALSE;
  FSI_CALL(DMHasLabel(dm, name.c_str(), &has));
  if (!has) FSI_CALL(DMCreateLabel(dm, name.c_str())); // empty on this rank
  DMLabel l;
  FSI_CALL(DMGetLabel(dm, name.c_str(), &l));
  return l;
}

void Mesh::require_groups(const std::vector<std::string> &names, const std::string &why) const {
  std::vector<std::string> missing;
  for (auto &n : names)
    if (!has_group(n)) missing.push_back(n);
  if (!missing.empty())
    throw InputError("mesh " + source + " lacks physical group(s) " + opt::join(missing) +
                     " needed by " + why +
                     ": add them to the .geo (Physical Volume/Surface) or fix the name");
}

std::vector<PetscInt> Mesh::cells_in(const std::string &name) const {
  PetscInt cStart, cEnd;
  FSI_CALL(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  std::vector<PetscInt> cells;
  if (name.empty()) {
    for (PetscInt c = cStart; c < cEnd; ++c)
      cells.push_back(c);
    return cells;
  }
  DMLabel l = label(name);
  for (PetscInt c = cStart; c < cEnd; ++c) {
    PetscInt v;
    FSI_CALL(DMLabelGetValue(l, c, &v));
    if (v >= 0) cells.push_back(c);
  }
  return cells;
}

static std::string opt_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// Mesh a .geo with the gmsh API (rank 0) into `out`, atomically.
static void generate_with_gmsh(const std::string &geo, double h,
                               const std::vector<std::string> &params, const std::string &out,
                               double max_cells) {
  std::vector<std::string> args = {"fsi_app", "-setnumber", "h", std::to_string(h)};
  for (auto &p : params) {
    auto eq = p.find('=');
    if (eq == std::string::npos)
      throw InputError("option -mesh_params expects NAME=VALUE items, got '" + p + "'");
    args.insert(args.end(), {"-setnumber", p.substr(0, eq), p.substr(eq + 1)});
  }
  std::string tmp = out.substr(0, out.size() - 4) + ".tmp" + std::to_string(getpid()) + ".msh";
  const gmsh_module::Status st = gmsh_module::mesh_geo(args, geo, h, max_cells, tmp);
  if (st.code == 1) {
    char msg[256];
    std::snprintf(msg, sizeof msg, "%.3g cells (at most; limit -mesh_max_cells %.3g)", st.cells,
                  max_cells);
    throw InputError("option -mesh_h " + opt_number(h) + " would mesh " + geo + " into up to " +
                     msg + ": give a larger -mesh_h (or raise -mesh_max_cells)");
  }
  if (st.code) {              // gmsh's own last error (a .geo's Error(...) names the bad parameter)
    std::remove(tmp.c_str()); // whatever gmsh left
    throw InputError("gmsh failed to mesh " + geo + " at h = " + std::to_string(h) +
                     (st.message.empty() ? "" : " (" + st.message + ")") +
                     ": check the .geo and the size");
  }
  if (std::rename(tmp.c_str(), out.c_str()) != 0)
    throw InputError("cannot write mesh cache file " + out);
}

static std::string cached_mesh(MPI_Comm comm, const std::string &geo, double h,
                               const std::vector<std::string> &params) {
  std::ifstream in(geo);
  std::stringstream content;
  content << in.rdbuf();
  std::string key = content.str() + "|h=" + std::to_string(h) + "|" + opt::join(params);
  char hash[32];
  std::snprintf(hash, sizeof hash, "%016zx", std::hash<std::string>{}(key));
  std::string dir = opt::string("mesh_cache_dir", "results/.mesh_cache");
  std::string stem = geo.substr(geo.find_last_of('/') + 1);
  stem = stem.substr(0, stem.find('.'));
  std::string out = dir + "/" + stem + "_" + hash + ".msh";
  const double max_cells = opt::positive("mesh_max_cells", 5e7);
  int rank;
  MPI_Comm_rank(comm, &rank);
  int ok = 1;
  std::string err;
  if (rank == 0 && !file_exists(out)) {
    std::string cmd = "mkdir -p '" + dir + "'";
    if (std::system(cmd.c_str()) != 0) {
      ok = 0;
      err = "cannot create mesh cache directory " + dir + " (set -mesh_cache_dir)";
    } else {
      try {
        generate_with_gmsh(geo, h, params, out, max_cells);
      } catch (InputError &e) {
        ok = 0;
        err = e.what();
      }
    }
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, comm);
  if (!ok) throw InputError(rank == 0 ? err : "mesh generation failed");
  return out;
}

void load_mesh(MPI_Comm comm, Mesh &mesh) {
  std::string file;
  if (opt::has("mesh_file")) {
    file = resolve_path(opt::required_string("mesh_file"));
    // A ready mesh overrides a .geo that an included scene file names (scripts/make_scene's
    // scenes include the idealised valve's options).
    for (auto name : {"mesh_geo", "mesh_h", "mesh_params", "mesh_cache_dir"})
      if (opt::has(name)) opt::string(name, "");
  } else if (opt::has("mesh_geo")) {
    std::string geo = resolve_path(opt::required_string("mesh_geo"));
    if (!file_exists(geo)) throw InputError("mesh source " + geo + " not found: check -mesh_geo");
    double h = opt::positive("mesh_h", 0.1);
    file = cached_mesh(comm, geo, h, opt::list("mesh_params"));
  } else {
    throw InputError(
        "the scene names no mesh: give -mesh_file FILE.msh or -mesh_geo FILE.geo -mesh_h SIZE");
  }
  if (!file_exists(file))
    throw InputError("mesh file " + file + " not found: check -mesh_file (or run scripts/setup)");
  load_mesh_file(comm, mesh, file);
}

void skip_scene_mesh_options() {
  for (auto name : {"mesh_file", "mesh_geo", "mesh_h", "mesh_params", "mesh_cache_dir"})
    if (opt::has(name)) opt::string(name, "");
}

void load_mesh_file(MPI_Comm comm, Mesh &mesh, const std::string &file) {
  if (!file_exists(file)) throw InputError("mesh file " + file + " not found");
  mesh.source = file;

  // Physical names become labels; read errors become one line instead of a PETSc traceback.
  FSI_CALL(PetscOptionsSetValue(nullptr, "-dm_plex_gmsh_use_regions", "1"));
  DM dm;
  FSI_CALL(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr));
  PetscErrorCode ierr = DMPlexCreateFromFile(comm, file.c_str(), "fsi", PETSC_TRUE, &dm);
  FSI_CALL(PetscPopErrorHandler());
  if (ierr)
    throw InputError("mesh file " + file + " could not be read as a gmsh .msh mesh: regenerate it");
  PetscInt dim;
  FSI_CALL(DMGetDimension(dm, &dim));
  if (dim != 3)
    throw InputError("mesh " + file + " is not 3D (dimension " + std::to_string(dim) + ")");
  FSI_CALL(PetscObjectSetName((PetscObject)dm, "mesh"));

  // Bandwidth-reducing point order (before distribution, on the serial mesh): the dofs follow
  // the points, so nearby points give nearby matrix rows (assembly scatter, matrix-vector
  // products and ILU touch fewer cache lines).
  const std::string order = opt::choice("mesh_reorder", "rcm", {"none", "rcm"});
  if (order == "rcm") {
    IS perm;
    DM permuted;
    FSI_CALL(DMPlexGetOrdering(dm, MATORDERINGRCM, nullptr, &perm));
    FSI_CALL(DMPlexPermute(dm, perm, &permuted));
    FSI_CALL(ISDestroy(&perm));
    FSI_CALL(DMDestroy(&dm));
    dm = permuted;
    FSI_CALL(PetscObjectSetName((PetscObject)dm, "mesh"));
  }
  mesh.partition = set_partition(dm);
  DM dist = nullptr;
  FSI_CALL(DMPlexDistribute(dm, 0, nullptr, &dist));
  if (dist) {
    FSI_CALL(DMDestroy(&dm));
    dm = dist;
  }
  mesh.dm = dm;

  PetscInt cStart, cEnd, vStart, vEnd;
  FSI_CALL(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  FSI_CALL(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  // Count owned points only (shared vertices belong to one rank through the point SF).
  PetscSF sf;
  FSI_CALL(DMGetPointSF(dm, &sf));
  const PetscInt *leaves = nullptr;
  PetscInt nleaves = 0;
  FSI_CALL(PetscSFGetGraph(sf, nullptr, &nleaves, &leaves, nullptr));
  PetscInt ghostV = 0;
  for (PetscInt i = 0; i < (nleaves > 0 ? nleaves : 0); ++i) {
    PetscInt p = leaves ? leaves[i] : i;
    if (p >= vStart && p < vEnd) ++ghostV;
  }
  PetscInt loc[2] = {cEnd - cStart, vEnd - vStart - ghostV}, glob[2];
  MPI_Allreduce(loc, glob, 2, MPIU_INT, MPI_SUM, comm);
  mesh.cells_global = glob[0];
  mesh.vertices_global = glob[1];
}

// Its options, for -help and docs/options.md (option_doc.hpp).
OptionSection mesh_options() {
  return {
      "Mesh",
      {{"mesh_file", "", "-", "a ready gmsh .msh; physical names become regions/boundaries"},
       {"mesh_geo", "", "-", "or a gmsh .geo source, meshed with the gmsh API"},
       {"mesh_h", "0.1", "m", "mesh size passed to the .geo as h"},
       {"mesh_params", "", "-", "further .geo parameters name=value,..."},
       {"mesh_cache_dir", "results/.mesh_cache", "-", "where meshed .geo files are cached"},
       {"mesh_partitioner", "ptscotch", "-",
        "cell partition over the ranks: ptscotch or metis (edge cut and balance in the header)"},
       {"mesh_reorder", "rcm", "-",
        "rcm | none: mesh points (hence dofs) in reverse Cuthill-McKee order before "
        "distribution (assembly 25-35 % faster) or as read"},
       {"mesh_max_cells", "5e7", "-",
        "refuse a -mesh_h whose cell estimate (bounding box / h^3) exceeds this"}}};
}

} // namespace fsi
