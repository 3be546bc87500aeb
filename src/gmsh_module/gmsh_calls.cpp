// The gmsh module (libfsi_gmsh.so): the only code that calls the gmsh API (include/fsi/mesh/
// gmsh_module.hpp says why it is loaded apart).  Exported as C symbols, looked up by
// src/mesh/gmsh_loader.cpp.
#include "fsi/mesh/gmsh_module.hpp"

#include <cmath>
#include <gmsh.h>
#include <map>

using fsi::gmsh_module::Status;

namespace {

std::string last_error() {
  std::string err;
  try {
    gmsh::logger::getLastError(err);
  } catch (...) {
  }
  return err;
}

} // namespace

extern "C" void fsi_gmsh_mesh_geo(const std::vector<std::string> *args, const std::string *geo,
                                  double h, double max_cells, const std::string *out, Status *st) {
  std::vector<char *> argv;
  for (auto &a : *args)
    argv.push_back(const_cast<char *>(a.c_str()));
  gmsh::initialize((int)argv.size(), argv.data(), false);
  try {
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 1);
    gmsh::open(*geo);
    // Refuse sizes that would swamp memory (gmsh aborts, or the machine swaps) before meshing:
    // the bounding box filled with regular tetrahedra of edge h (volume h^3 / (6 sqrt 2)), an
    // upper estimate of the cell count.
    double x0, y0, z0, x1, y1, z1;
    gmsh::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
    st->cells = (x1 - x0) * (y1 - y0) * (z1 - z0) * 6 * std::sqrt(2.0) / (h * h * h);
    if (!(st->cells <= max_cells)) {
      st->code = 1;
    } else {
      gmsh::model::mesh::generate(3);
      gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
      gmsh::option::setNumber("Mesh.Binary", 1);
      gmsh::write(*out);
    }
  } catch (...) { // gmsh throws std::string as well as std::exception
    st->code = 2;
    st->message = last_error();
  }
  gmsh::finalize();
}

extern "C" void fsi_gmsh_mesh_volume(std::vector<std::array<double, 3>> *xp,
                                     const std::vector<std::vector<std::array<int, 3>>> *surfaces,
                                     const std::vector<std::array<double, 4>> *gapsp, double hmax,
                                     bool verbose, std::vector<std::array<int, 4>> *tets,
                                     Status *st) {
  auto &x = *xp;
  const auto &gaps = *gapsp;
  gmsh::initialize(0, nullptr, false);
  try {
    gmsh::option::setNumber("General.Terminal", verbose ? 1 : 0);
    gmsh::option::setNumber("Mesh.MeshOnlyEmpty", 1);
    gmsh::option::setNumber("Mesh.Algorithm3D", 1); // Delaunay, sizes from the boundary
    if (hmax > 0) gmsh::option::setNumber("Mesh.MeshSizeMax", hmax);
    gmsh::model::add("fluid");
    std::vector<char> added(x.size(), 0);
    std::vector<int> surface_tags;
    for (size_t s = 0; s < surfaces->size(); ++s) {
      const int tag = (int)s + 1;
      gmsh::model::addDiscreteEntity(2, tag);
      std::vector<std::size_t> ntags, etags;
      std::vector<double> coords;
      for (const auto &tri : (*surfaces)[s])
        for (int v : tri) {
          etags.push_back(v + 1);
          if (added[v]) continue;
          added[v] = 1;
          ntags.push_back(v + 1);
          coords.insert(coords.end(), x[v].begin(), x[v].end());
        }
      gmsh::model::mesh::addNodes(2, tag, ntags, coords);
      gmsh::model::mesh::addElementsByType(tag, 2, {}, etags);
      surface_tags.push_back(tag);
    }
    gmsh::model::addDiscreteEntity(3, 1, surface_tags);
    if (!gaps.empty()) // sizes grow away from a gap at 1/2 per unit distance
      gmsh::model::mesh::setSizeCallback([&gaps](int, int, double px, double py, double pz) {
        double s = 1e22;
        for (auto &g : gaps) {
          const double r = std::sqrt((px - g[0]) * (px - g[0]) + (py - g[1]) * (py - g[1]) +
                                     (pz - g[2]) * (pz - g[2]));
          s = std::min(s, g[3] + 0.5 * r);
        }
        return s;
      });
    gmsh::model::mesh::createGeometry({{3, 1}});
    gmsh::model::mesh::generate(3);
    // gmsh's tetrahedron optimiser once more, forced: generate() leaves flat slivers on four
    // boundary vertices across a thin gap (measured: skewness 1.000 between two plates' top
    // edges 0.5 mm apart), which its swaps remove (0.903 there).
    gmsh::model::mesh::optimize("", true, 3);
    // Nodes come back renumbered: tell the kept ones by their (exact) coordinates; new nodes
    // are those of the new cells.
    std::vector<std::size_t> etags, enodes;
    gmsh::model::mesh::getElementsByType(4, etags, enodes, 1);
    std::vector<std::size_t> ntags;
    std::vector<double> coords, param;
    gmsh::model::mesh::getNodes(ntags, coords, param, -1, -1, false, false);
    std::map<std::size_t, std::array<double, 3>> pos;
    for (size_t i = 0; i < ntags.size(); ++i)
      pos[ntags[i]] = {coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]};
    std::map<std::array<double, 3>, int> known;
    for (size_t v = 0; v < x.size(); ++v)
      if (added[v]) known[x[v]] = (int)v;
    auto index = [&](std::size_t tag) {
      const auto &p = pos.at(tag);
      auto it = known.find(p);
      if (it != known.end()) return it->second;
      x.push_back(p);
      return known[p] = (int)x.size() - 1;
    };
    for (size_t k = 0; k < etags.size(); ++k)
      tets->push_back({index(enodes[4 * k]), index(enodes[4 * k + 1]), index(enodes[4 * k + 2]),
                       index(enodes[4 * k + 3])});
  } catch (...) {
    st->code = 2;
    st->message = last_error();
    if (st->message.empty()) st->message = "no message";
  }
  gmsh::finalize();
}
