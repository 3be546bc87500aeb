// The output contract (shared/design.md): in -out_dir DIR (default results/<scene>):
//   options.txt   every option in effect
//   monitor.csv   step,time,newton,krylov,step_seconds,dt, then the scene's monitors
//   fields.h5 + fields.xdmf   vertex fields every -out_fields_every steps (0 = never, the
//                             default), see field_writer.hpp
//   hemo.h5 + hemo.xdmf       wall shear and its indices (-hemo_surfaces), see wall_shear.hpp
//   checkpoint.h5             the state to resume from (checkpoint.hpp)
//   summary.json  written last: physics, ranks, sizes, iterations, times, converged, reason
// Files are written under temporary names and renamed when complete; a stale summary.json from an
// earlier run is removed at start, so a run that dies leaves no summary claiming success.
#pragma once
#include "fsi/common.hpp"
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace fsi {

// Minimal ordered JSON object writer.
class Json {
public:
  Json &set(const std::string &k, double v);
  Json &set(const std::string &k, long v);
  Json &set(const std::string &k, int v) { return set(k, (long)v); }
  Json &set(const std::string &k, bool v);
  Json &set(const std::string &k, const std::string &v);
  Json &set(const std::string &k, const char *v) { return set(k, std::string(v)); }
  Json &set(const std::string &k, const Json &v);
  Json &set(const std::string &k, const std::vector<std::string> &v);
  std::string str(int indent = 0) const;

private:
  std::vector<std::pair<std::string, std::string>> items_;
};

class Output {
public:
  Output(MPI_Comm comm, const std::string &dir);
  ~Output();
  const std::string &dir() const { return dir_; }
  void write_options() const;
  // resume_step >= 0 (a restart): keep this directory's earlier rows up to that step.
  void open_monitor(const std::vector<std::string> &columns, long resume_step = -1);
  void monitor_row(const std::vector<double> &values);
  void close_monitor();
  void write_summary(const Json &j) const;
  // A small text file in the output directory, written atomically by rank 0.
  void write_file(const std::string &name, const std::string &content) const {
    write_atomic(name, content);
  }

private:
  void write_atomic(const std::string &name, const std::string &content) const;
  MPI_Comm comm_;
  int rank_ = 0;
  std::string dir_;
  FILE *monitor_ = nullptr;
};

} // namespace fsi
