// Wall shear stress and its cycle indices on named surfaces (paper eqs. 13-16, benchmarks.md
// section 5), on the deformed configuration, only when the scene asks (-hemo_surfaces a,b):
//   tau_w = t - (t.n) n,  t = sigma n, n the wall's normal pointing into the fluid: the shear the
//   fluid exerts on the wall (downstream in pipe flow).  Per face: the P2 velocity gradient at
//   the face centroid, which is the face average since grad v is linear there.
// Accumulated over windows of -hemo_window T [s] (default: the whole run) starting at
// -hemo_start [s] (default 0), with the step's length as weight:
//   tawss      = |(1/T) int tau_w dt|   (the paper's TAWSS: magnitude of the mean vector)
//   wss_magnitude_mean = (1/T) int |tau_w| dt   (what many codes call TAWSS)
//   osi        = 1/2 (1 - tawss / wss_magnitude_mean)  in [0, 1/2]
//   rrt        = 1 / ((1 - 2 osi) wss_magnitude_mean) = 1 / tawss   [1/Pa]
// Files: hemo.h5 (+ hemo.xdmf at the end; hemo_restart.* in a restarted run): per surface the faces
// sorted by reference centroid (partition independent; the reference is the current mesh's, so
// the order changes with a remesh: material_points, the vertices' material reference, identify
// a face across files), instantaneous wss with the fields, and each
// window's indices at its end.  monitor.csv gets <s>_wss_mean and <s>_wss_max (area mean and max of
// |tau_w|) and, with an exact flow, <s>_wss_err_l2 and <s>_wss_exact_l2.
#pragma once
#include "fsi/analytic/analytic.hpp"
#include "fsi/io/h5.hpp"
#include "fsi/io/output.hpp"
#include "fsi/io/run_state.hpp"
#include "fsi/physics/fluid.hpp"
#include "fsi/post/monitor.hpp"
#include <memory>
#include <string>
#include <vector>

namespace fsi {

class WallShear : public Monitor {
public:
  // material_X: the solid's material reference per vertex (the faces' identity across remeshes,
  // written as <surface>/material_points; the ALE reference changes with every new mesh).
  void setup(const Mesh &mesh, const Space &space, const FluidModule *fluid, const ExactFlow *exact,
             const std::string &out_dir, double t_end, const std::string &base,
             const std::vector<double> &material_X);
  bool active() const { return !surf_.empty(); }
  // After each accepted step of length dt: instantaneous tau_w, accumulators, window closing.
  void update(const FieldView &view, double dt) override;
  std::vector<std::string> columns() const;
  void add_to(MonitorRow &row, const FieldView &) override {
    row.add(columns(), [&] { return values_; });
  }
  void write(long step, double t) override; // instantaneous tau_w with the fields
  void close() override;
  // "hemodynamics": the last closed window per surface (area means, OSI range).
  void summarize(Json &j, bool stepped) const override;
  // Checkpoint and rebuild: accumulators and window state.
  void save(RunState &s) const override;
  void load(const RunState &s) override;

private:
  struct Surface {
    std::string name;
    std::vector<BoundaryFace> faces;
    std::vector<double> key;  // reference centroid, 3 per face
    std::vector<double> tau;  // current tau_w, 3 per face
    std::vector<double> area; // current area per face
    std::vector<double> xf;   // current vertex positions, 9 per face
    std::vector<double> acc;  // int tau dt (3), int |tau| dt (1) per face
    long n_global = 0;
    Json last_window;
  };
  void compute(Surface &s, const FieldView &view);
  void close_window();
  void write_xdmf() const; // rank 0, after the file is closed
  const Space *space_ = nullptr;
  const FluidModule *fluid_ = nullptr;
  const ExactFlow *exact_ = nullptr;
  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0;
  std::vector<Surface> surf_;
  double window_ = 0, start_ = 0, window_start_ = 0, window_time_ = 0;
  long window_index_ = 0;
  std::vector<double> values_;
  std::unique_ptr<H5File> file_;
  std::string dir_, base_;                     // output directory, file name without extension
  std::vector<std::pair<long, double>> steps_; // instantaneous outputs (step, time)
  std::vector<long> windows_;                  // windows closed in this run
};

} // namespace fsi
