#include "fsi/io/run_state.hpp"

#include <cmath>
#include <csignal>
#include <cstdio>
#include <fcntl.h>
#include <memory>
#include <sstream>
#include <unistd.h>

namespace fsi {

// Version 2 adds the material reference per vertex; version 1 files (without it) still load.
static const double FORMAT_VERSION = 2;

// The generalized-alpha spectral radius part of a scene tag (Scene::tag: "... rho_inf R"), or "".
// The state (velocity, acceleration, displacement) is the same whatever rho_inf, so a run may
// continue with more or less numerical damping (e.g. rho_inf 0 once a valve has closed and its
// leaflets ring against each other).
static std::string rho_inf_part(const std::string &tag) {
  const size_t at = tag.find(" rho_inf ");
  return at == std::string::npos ? "" : tag.substr(at + 1);
}

void RunState::write(MPI_Comm comm, const std::string &path, long crash_at_write) const {
  static long writes = 0; // -checkpoint_crash_test K: SIGKILL halfway through the K-th write
  int rank;
  MPI_Comm_rank(comm, &rank);
  const std::string partial = path + ".partial";
  int ok = 1;
  std::string err;
  if (rank == 0) {
    try {
      {
        H5File f(partial, H5File::create);
        f.set("format", "fsi_app checkpoint");
        f.set("version", FORMAT_VERSION);
        f.set("scene", scene);
        f.set("step", (double)step);
        f.set("time", time);
        f.set("dt", dt);
        f.set("easy_run", (double)easy_run);
        f.set("error_prev", error_prev);
        f.set("remeshes", (double)remeshes);
        if (!mesh_file.empty()) f.set("mesh_file", mesh_file);
        f.write("/dofs/keys", dofs.keys, 4);
        f.write("/dofs/state", dofs.values,
                dofs.keys.empty() ? 1 : dofs.values.size() / (dofs.keys.size() / 4));
        if (++writes == crash_at_write) raise(SIGKILL); // a run killed while writing (tests)
        std::vector<double> dm, mat;
        for (size_t i = 0; i < vertices.values.size() / 6; ++i)
          for (int d = 0; d < 3; ++d) {
            dm.push_back(vertices.values[6 * i + d]);
            mat.push_back(vertices.values[6 * i + 3 + d]);
          }
        f.write("/vertices/keys", vertices.keys, 3);
        f.write("/vertices/mesh_displacement", dm, 3);
        f.write("/vertices/material_reference", mat, 3);
        std::string names;
        for (auto &[name, items] : hemo) {
          names += (names.empty() ? "" : ",") + name;
          f.write("/hemo/" + name + "/keys", items.keys, 3);
          f.write("/hemo/" + name + "/accumulators", items.values, 4);
        }
        if (!hemo_window.empty()) {
          f.set("hemo_surfaces", names);
          f.write("/hemo/window", hemo_window);
        }
        if (!lumped.empty()) {
          std::string keys;
          std::vector<double> values;
          for (auto &[k, v] : lumped) {
            keys += (keys.empty() ? "" : ",") + k;
            values.push_back(v);
          }
          f.set("lumped_keys", keys);
          f.write("/lumped/values", values);
        }
        f.close(); // a full disk shows here at the latest
      }
      const int fd = open(partial.c_str(), O_RDONLY);
      const bool synced = fd >= 0 && fsync(fd) == 0;
      if (fd >= 0) close(fd);
      if (!synced) throw OutputError("cannot flush " + partial + " to disk (disk full?)");
      if (std::rename(partial.c_str(), path.c_str()) != 0)
        throw OutputError("cannot rename " + partial + " to " + path);
    } catch (std::exception &e) {
      ok = 0;
      err = e.what();
      std::remove(partial.c_str()); // frees the space it took; the previous checkpoint stays
    }
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, comm);
  if (!ok)
    throw OutputError("checkpoint not written: " + err + "; the previous checkpoint " + path +
                      ", if any, is intact");
}

RunState RunState::read(MPI_Comm comm, const std::string &path, const std::string &scene) {
  int rank;
  MPI_Comm_rank(comm, &rank);
  RunState s;
  s.scene = scene;
  // step, time, dt, easy_run, dof count, remeshes, error_prev
  double meta[7] = {0, 0, 0, 0, 0, 0, 0};
  std::string err;
  if (rank == 0) {
    try {
      H5File f(path, H5File::open_read);
      const double version = f.get_string("format") == "fsi_app checkpoint" ? f.get("version") : 0;
      if (version != 1 && version != FORMAT_VERSION)
        throw InputError("'" + path + "' is not an fsi_app checkpoint of this version");
      const std::string written = f.get_string("scene");
      const std::string r_old = rho_inf_part(written), r_new = rho_inf_part(scene);
      if (written.substr(0, written.size() - r_old.size()) !=
          scene.substr(0, scene.size() - r_new.size()))
        throw InputError("restart file '" + path + "' was written by another scene (" + written +
                         "; this one: " + scene +
                         "): restart with the options of the run that wrote it");
      if (r_old != r_new)
        std::printf("fsi_app: restart: %s (the checkpoint's run had %s)\n", r_new.c_str(),
                    r_old.c_str());
      meta[0] = f.get("step");
      meta[1] = f.get("time");
      meta[2] = f.get("dt");
      meta[3] = f.get("easy_run");
      if (f.has_attribute("remeshes")) meta[5] = f.get("remeshes");
      if (f.has_attribute("error_prev")) meta[6] = f.get("error_prev");
      if (f.has_attribute("mesh_file")) s.mesh_file = f.get_string("mesh_file");
      s.dofs.keys = f.read("/dofs/keys");
      s.dofs.values = f.read("/dofs/state");
      meta[4] = (double)(s.dofs.keys.size() / 4);
      s.vertices.keys = f.read("/vertices/keys");
      const auto dm = f.read("/vertices/mesh_displacement");
      // Version 1: the material reference was the mesh (the vertex key).
      const auto mat = f.has("/vertices/material_reference")
                           ? f.read("/vertices/material_reference")
                           : s.vertices.keys;
      for (size_t i = 0; i < dm.size() / 3; ++i) {
        for (int d = 0; d < 3; ++d)
          s.vertices.values.push_back(dm[3 * i + d]);
        for (int d = 0; d < 3; ++d)
          s.vertices.values.push_back(mat[3 * i + d]);
      }
      if (f.has("/hemo/window")) {
        s.hemo_window = f.read("/hemo/window");
        std::stringstream names(f.get_string("hemo_surfaces"));
        std::string n;
        while (std::getline(names, n, ','))
          if (!n.empty()) {
            s.hemo[n].keys = f.read("/hemo/" + n + "/keys");
            s.hemo[n].values = f.read("/hemo/" + n + "/accumulators");
          }
      }
      if (f.has_attribute("lumped_keys")) {
        const auto values = f.read("/lumped/values");
        std::stringstream keys(f.get_string("lumped_keys"));
        std::string k;
        for (size_t i = 0; std::getline(keys, k, ',') && i < values.size(); ++i)
          s.lumped[k] = values[i];
      }
    } catch (InputError &e) {
      err = e.what();
    }
  }
  int len = (int)err.size();
  MPI_Bcast(&len, 1, MPI_INT, 0, comm);
  if (len) {
    err.resize(len);
    MPI_Bcast(err.data(), len, MPI_CHAR, 0, comm);
    throw InputError(err);
  }
  MPI_Bcast(meta, 7, MPI_DOUBLE, 0, comm);
  s.remeshes = std::lround(meta[5]);
  int nm = (int)s.mesh_file.size();
  MPI_Bcast(&nm, 1, MPI_INT, 0, comm);
  s.mesh_file.resize(nm);
  MPI_Bcast(s.mesh_file.data(), nm, MPI_CHAR, 0, comm);
  int nw = (int)s.hemo_window.size(); // scalars: on every rank
  MPI_Bcast(&nw, 1, MPI_INT, 0, comm);
  s.hemo_window.resize(nw);
  MPI_Bcast(s.hemo_window.data(), nw, MPI_DOUBLE, 0, comm);
  // Lumped-model state: "key value" lines from rank 0 to all.
  std::string lumped;
  for (auto &[k, v] : s.lumped) {
    char buf[64];
    snprintf(buf, sizeof buf, " %.17g\n", v);
    lumped += k + buf;
  }
  int nl = (int)lumped.size();
  MPI_Bcast(&nl, 1, MPI_INT, 0, comm);
  lumped.resize(nl);
  MPI_Bcast(lumped.data(), nl, MPI_CHAR, 0, comm);
  s.lumped.clear();
  std::stringstream ls(lumped);
  std::string key;
  double value;
  while (ls >> key >> value)
    s.lumped[key] = value;
  s.step = std::lround(meta[0]);
  s.time = meta[1];
  s.dt = meta[2];
  s.easy_run = std::lround(meta[3]);
  s.error_prev = meta[6];
  s.n_dofs = std::lround(meta[4]);
  return s;
}

} // namespace fsi
