#include "fsi/post/wall_shear.hpp"
#include "fsi/scene/option_doc.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

namespace fsi {

void WallShear::setup(const Mesh &mesh, const Space &space, const FluidModule *fluid,
                      const ExactFlow *exact, const std::string &out_dir, double t_end,
                      const std::string &base, const std::vector<double> &material_X) {
  const auto names = opt::list("hemo_surfaces");
  window_ = opt::nonnegative("hemo_window", 0.0);
  start_ = opt::nonnegative("hemo_start", 0.0);
  if (names.empty()) {
    if (opt::has("hemo_window") || opt::has("hemo_start"))
      throw InputError("-hemo_window/-hemo_start given without -hemo_surfaces: name the walls");
    return;
  }
  if (!fluid) throw InputError("-hemo_surfaces needs a fluid in the scene (-physics fluid)");
  mesh.require_groups(names, "-hemo_surfaces");
  if (window_ == 0) window_ = t_end - start_;
  if (window_ <= 0) throw InputError("-hemo_start is at or after the end of the run");
  space_ = &space;
  fluid_ = fluid;
  exact_ = exact;
  comm_ = PetscObjectComm((PetscObject)space.dm);
  MPI_Comm_rank(comm_, &rank_);
  window_start_ = start_;
  dir_ = out_dir;
  std::vector<char> in_fluid(space.n_cells(), 0);
  for (PetscInt k : fluid->cells())
    in_fluid[k] = 1;
  base_ = base;
  collective_output(comm_, [&]() {
    if (rank_ == 0) file_ = std::make_unique<H5File>(out_dir + "/" + base_ + ".h5", H5File::create);
  });
  for (auto &n : names) {
    Surface s;
    s.name = n;
    s.faces = space.boundary_faces(mesh, n, &in_fluid);
    const size_t nf = s.faces.size();
    s.key.resize(3 * nf);
    std::vector<double> pts(18 * nf); // reference, then material points
    for (size_t i = 0; i < nf; ++i) {
      const int *v = s.faces[i].vertex;
      face_key(&space.X[3 * v[0]], &space.X[3 * v[1]], &space.X[3 * v[2]], &s.key[3 * i]);
      for (int j = 0; j < 3; ++j)
        for (int d = 0; d < 3; ++d) {
          pts[18 * i + 3 * j + d] = space.X[3 * v[j] + d];
          pts[18 * i + 9 + 3 * j + d] = material_X[3 * v[j] + d];
        }
    }
    s.tau.assign(3 * nf, 0.0);
    s.area.assign(nf, 0.0);
    s.acc.assign(4 * nf, 0.0);
    const long nl = (long)nf;
    MPI_Allreduce(&nl, &s.n_global, 1, MPI_LONG, MPI_SUM, comm_);
    if (s.n_global == 0)
      throw InputError("-hemo_surfaces: surface '" + n + "' has no face on the fluid");
    KeyedItems all = gather_sorted(comm_, s.key, pts, 3, 18);
    collective_output(comm_, [&]() {
      if (!file_) return;
      std::vector<double> ref(9 * s.n_global), mat(9 * s.n_global);
      for (long i = 0; i < s.n_global; ++i)
        for (int m = 0; m < 9; ++m) {
          ref[9 * i + m] = all.values[18 * i + m];
          mat[9 * i + m] = all.values[18 * i + 9 + m];
        }
      file_->write("/" + n + "/reference_points", ref, 3);
      file_->write("/" + n + "/material_points", mat, 3);
      std::vector<long> tri(3 * s.n_global);
      for (long i = 0; i < 3 * s.n_global; ++i)
        tri[i] = i;
      file_->write_ints("/" + n + "/triangles", tri, 3);
      file_->flush();
    });
    surf_.push_back(std::move(s));
  }
}

std::vector<std::string> WallShear::columns() const {
  std::vector<std::string> c;
  for (auto &s : surf_) {
    c.push_back(s.name + "_wss_mean");
    c.push_back(s.name + "_wss_max");
    if (exact_) {
      c.push_back(s.name + "_wss_err_l2");
      c.push_back(s.name + "_wss_exact_l2");
    }
  }
  return c;
}

// tau_w at every face centroid of s on the current configuration.
void WallShear::compute(Surface &s, const FieldView &view) {
  const auto &Xc = *view.x;
  const PetscScalar *u = view.u;
  const double mu = fluid_->params().mu;
  s.xf.resize(9 * s.faces.size());
  for (size_t i = 0; i < s.faces.size(); ++i) {
    const BoundaryFace &f = s.faces[i];
    const PetscInt k = f.cell;
    double X[4][3], l[4] = {0, 0, 0, 0};
    space_->cell_points(k, Xc.data(), X);
    for (int a = 0; a < 4; ++a)
      if (space_->cell_vertex[4 * k + a] != f.opposite) l[a] = 1.0 / 3;
    TetGeometry g;
    g.set(X);
    double N[10], dN[10][3], G[3][3] = {}, n[3];
    p2_tet(l, g.grad_lambda, N, dN);
    for (int a = 0; a < 10; ++a)
      for (int c = 0; c < 3; ++c) {
        const double ua = PetscRealPart(u[space_->cell_vdof[10 * k + a] + c]);
        for (int d = 0; d < 3; ++d)
          G[c][d] += ua * dN[a][d];
      }
    s.area[i] = 0.5 * outward_normal(f, Xc.data(), n);
    double t[3], tn = 0;
    for (int c = 0; c < 3; ++c) { // viscous traction: the pressure has no tangential part
      t[c] = 0;
      for (int d = 0; d < 3; ++d)
        t[c] += mu * (G[c][d] + G[d][c]) * n[d];
      tn += t[c] * n[c];
    }
    for (int c = 0; c < 3; ++c) // on the wall, whose normal is -n: the fluid's drag on it
      s.tau[3 * i + c] = -(t[c] - tn * n[c]);
    for (int j = 0; j < 3; ++j)
      for (int d = 0; d < 3; ++d)
        s.xf[9 * i + 3 * j + d] = Xc[3 * f.vertex[j] + d];
  }
}

void WallShear::update(const FieldView &view, double dt) {
  if (!active()) return;
  values_.clear();
  const double t = view.t;
  const bool in_window = t > start_ + 1e-12 * window_;
  for (auto &s : surf_)
    compute(s, view);
  for (auto &s : surf_) {
    // area-weighted mean and max of |tau|; exact comparison at the face centroids
    double loc[4] = {0, 0, 0, 0}, mx = 0, glob[4], gmx;
    for (size_t i = 0; i < s.faces.size(); ++i) {
      const double *tau = &s.tau[3 * i];
      const double m = std::sqrt(tau[0] * tau[0] + tau[1] * tau[1] + tau[2] * tau[2]);
      loc[0] += s.area[i] * m;
      loc[1] += s.area[i];
      mx = std::max(mx, m);
      if (in_window) {
        for (int c = 0; c < 3; ++c)
          s.acc[4 * i + c] += dt * tau[c];
        s.acc[4 * i + 3] += dt * m;
      }
      if (exact_) {
        double x[3] = {0, 0, 0}, S[3][3], n[3], te[3], tn = 0;
        for (int j = 0; j < 3; ++j)
          for (int d = 0; d < 3; ++d)
            x[d] += s.xf[9 * i + 3 * j + d] / 3;
        outward_normal(s.faces[i], view.x->data(), n);
        exact_->stress(x, t, fluid_->params().mu, S);
        for (int c = 0; c < 3; ++c) {
          te[c] = S[c][0] * n[0] + S[c][1] * n[1] + S[c][2] * n[2];
          tn += te[c] * n[c];
        }
        for (int c = 0; c < 3; ++c) {
          const double e = -(te[c] - tn * n[c]);
          loc[2] += s.area[i] * (tau[c] - e) * (tau[c] - e);
          loc[3] += s.area[i] * e * e;
        }
      }
    }
    MPI_Allreduce(loc, glob, 4, MPI_DOUBLE, MPI_SUM, comm_);
    MPI_Allreduce(&mx, &gmx, 1, MPI_DOUBLE, MPI_MAX, comm_);
    values_.push_back(glob[0] / glob[1]);
    values_.push_back(gmx);
    if (exact_) {
      values_.push_back(std::sqrt(glob[2]));
      values_.push_back(std::sqrt(glob[3]));
    }
  }
  if (in_window) window_time_ += dt;
  if (in_window && t >= window_start_ + window_ * (1 - 1e-9)) close_window();
}

void WallShear::close_window() {
  const std::string w = "window_" + std::to_string(window_index_);
  for (auto &s : surf_) {
    const size_t nf = s.faces.size();
    std::vector<double> ind(4 * nf); // tawss, wss_magnitude_mean, osi, rrt
    double loc[4] = {0, 0, 0, 0}, lmin = 0.5, lmax = 0, glob[4], gmin, gmax;
    for (size_t i = 0; i < nf; ++i) {
      const double *a = &s.acc[4 * i];
      const double T = window_time_;
      const double tawss = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) / T;
      const double mag = a[3] / T;
      const double osi = mag > 0 ? std::clamp(0.5 * (1 - tawss / mag), 0.0, 0.5) : 0.0;
      const double rrt = tawss > 0 ? 1 / tawss : INFINITY;
      ind[4 * i] = tawss;
      ind[4 * i + 1] = mag;
      ind[4 * i + 2] = osi;
      ind[4 * i + 3] = rrt;
      loc[0] += s.area[i] * tawss;
      loc[1] += s.area[i] * mag;
      loc[2] += s.area[i] * osi;
      loc[3] += s.area[i];
      lmin = std::min(lmin, osi);
      lmax = std::max(lmax, osi);
    }
    MPI_Allreduce(loc, glob, 4, MPI_DOUBLE, MPI_SUM, comm_);
    MPI_Allreduce(&lmin, &gmin, 1, MPI_DOUBLE, MPI_MIN, comm_);
    MPI_Allreduce(&lmax, &gmax, 1, MPI_DOUBLE, MPI_MAX, comm_);
    KeyedItems all = gather_sorted(comm_, s.key, ind, 3, 4);
    collective_output(comm_, [&]() {
      if (!file_) return;
      std::vector<double> col(s.n_global);
      const char *names[4] = {"tawss", "wss_magnitude_mean", "osi", "rrt"};
      for (int q = 0; q < 4; ++q) {
        for (long i = 0; i < s.n_global; ++i)
          col[i] = all.values[4 * i + q];
        file_->write("/" + s.name + "/" + w + "/" + names[q], col);
      }
      file_->write("/" + s.name + "/" + w + "/interval", {window_start_, window_start_ + window_});
      file_->flush();
    });
    Json j;
    j.set("window", window_index_)
        .set("t_start", window_start_)
        .set("t_end", window_start_ + window_time_)
        .set("tawss_area_mean", glob[0] / glob[3])
        .set("wss_magnitude_mean_area_mean", glob[1] / glob[3])
        .set("osi_area_mean", glob[2] / glob[3])
        .set("osi_min", gmin)
        .set("osi_max", gmax);
    s.last_window = j;
    std::fill(s.acc.begin(), s.acc.end(), 0.0);
  }
  windows_.push_back(window_index_);
  window_start_ += window_;
  window_time_ = 0;
  ++window_index_;
}

void WallShear::write(long step, double t) {
  if (!active()) return;
  const std::string g = "step_" + std::to_string(step);
  for (auto &s : surf_) {
    const size_t nf = s.faces.size();
    std::vector<double> v(13 * nf);
    for (size_t i = 0; i < nf; ++i) {
      const double *tau = &s.tau[3 * i];
      std::copy_n(&s.xf[9 * i], 9, &v[13 * i]);
      std::copy_n(tau, 3, &v[13 * i + 9]);
      v[13 * i + 12] = std::sqrt(tau[0] * tau[0] + tau[1] * tau[1] + tau[2] * tau[2]);
    }
    KeyedItems all = gather_sorted(comm_, s.key, v, 3, 13);
    collective_output(comm_, [&]() {
      if (!file_) return;
      std::vector<double> pts(9 * s.n_global), wss(3 * s.n_global), mag(s.n_global);
      for (long i = 0; i < s.n_global; ++i) {
        std::copy_n(&all.values[13 * i], 9, &pts[9 * i]);
        std::copy_n(&all.values[13 * i + 9], 3, &wss[3 * i]);
        mag[i] = all.values[13 * i + 12];
      }
      file_->write("/" + s.name + "/" + g + "/points", pts, 3);
      file_->write("/" + s.name + "/" + g + "/wss", wss, 3);
      file_->write("/" + s.name + "/" + g + "/wss_magnitude", mag);
      file_->flush();
    });
  }
  steps_.emplace_back(step, t);
}

// hemo.xdmf: per surface, a temporal collection of the instantaneous wss and one grid per window.
void WallShear::close() {
  if (!active()) return;
  collective_output(comm_, [&]() {
    if (!file_) return;
    file_->close();
    file_.reset();
    write_xdmf();
  });
}

void WallShear::write_xdmf() const {
  std::ofstream x(dir_ + "/" + base_ + ".xdmf");
  const std::string h5 = base_ + ".h5:/";
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n<Domain>\n";
  for (auto &s : surf_) {
    const long nf = s.n_global;
    auto topo = [&](std::ostream &o) {
      o << "  <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << nf
        << "\"><DataItem Dimensions=\"" << nf << " 3\" NumberType=\"Int\" Precision=\"8\" "
        << "Format=\"HDF\">" << h5 << s.name << "/triangles</DataItem></Topology>\n";
    };
    auto geom = [&](std::ostream &o, const std::string &ds) {
      o << "  <Geometry GeometryType=\"XYZ\"><DataItem Dimensions=\"" << 3 * nf
        << " 3\" Format=\"HDF\">" << h5 << s.name << "/" << ds << "</DataItem></Geometry>\n";
    };
    auto attr = [&](std::ostream &o, const std::string &name, const std::string &ds, int dim) {
      o << "  <Attribute Name=\"" << name << "\" AttributeType=\""
        << (dim == 3 ? "Vector" : "Scalar") << "\" Center=\"Cell\"><DataItem Dimensions=\"" << nf
        << (dim == 3 ? " 3" : "") << "\" Format=\"HDF\">" << h5 << s.name << "/" << ds
        << "</DataItem></Attribute>\n";
    };
    if (!steps_.empty()) {
      x << "<Grid Name=\"" << s.name << "_wss\" GridType=\"Collection\" "
        << "CollectionType=\"Temporal\">\n";
      for (auto &[n, t] : steps_) {
        const std::string g = "step_" + std::to_string(n);
        x << " <Grid Name=\"" << s.name << "_" << n << "\"><Time Value=\"" << t << "\"/>\n";
        topo(x);
        geom(x, g + "/points");
        attr(x, "wss", g + "/wss", 3);
        attr(x, "wss_magnitude", g + "/wss_magnitude", 1);
        x << " </Grid>\n";
      }
      x << "</Grid>\n";
    }
    for (long w : windows_) {
      const std::string g = "window_" + std::to_string(w);
      x << "<Grid Name=\"" << s.name << "_" << g << "\">\n";
      topo(x);
      geom(x, "reference_points");
      for (auto q : {"tawss", "wss_magnitude_mean", "osi", "rrt"})
        attr(x, q, g + "/" + q, 1);
      x << "</Grid>\n";
    }
  }
  x << "</Domain>\n</Xdmf>\n";
  x.close();
  if (!x) throw OutputError("cannot write " + dir_ + "/" + base_ + ".xdmf (disk full?)");
}

void WallShear::summarize(Json &out, bool) const {
  Json j;
  for (auto &s : surf_)
    j.set(s.name, s.last_window);
  out.set("hemodynamics", j);
}

std::unique_ptr<Monitor> make_wall_shear(const MonitorSetup &m) {
  auto w = std::make_unique<WallShear>();
  w->setup(m.mesh, m.space, m.fluid, m.exact, m.out_dir, m.t_end, m.hemo_base, m.material_X);
  if (!w->active()) return nullptr;
  return w;
}

void WallShear::save(RunState &st) const {
  if (!active()) return;
  for (auto &s : surf_) {
    st.hemo[s.name] = gather_sorted(comm_, s.key, s.acc, 3, 4);
    st.hemo_last_window[s.name] = s.last_window;
  }
  st.hemo_window = {window_start_, window_time_, (double)window_index_, window_};
}

void WallShear::load(const RunState &st) {
  if (!active()) return;
  if (st.hemo_window.size() != 4)
    throw InputError("the restart file has no wall-shear accumulators: it was written by a "
                     "scene without -hemo_surfaces (drop -hemo_surfaces or restart from a "
                     "matching run)");
  for (auto &s : surf_) {
    int ok = st.hemo.count(s.name) > 0;
    MPI_Bcast(&ok, 1, MPI_INT, 0, comm_);
    if (!ok)
      throw InputError("the restart file has no wall-shear data for surface '" + s.name + "'");
    const auto it = st.hemo.find(s.name); // the data live on rank 0 only
    if (scatter_by_key(comm_, it != st.hemo.end() ? it->second : KeyedItems(), s.key, s.acc, 3,
                       4) != 0)
      throw InputError("the restart file's wall-shear faces of '" + s.name +
                       "' do not match this mesh (a checkpoint of another mesh?)");
    if (st.hemo_last_window.count(s.name)) s.last_window = st.hemo_last_window.at(s.name);
  }
  window_start_ = st.hemo_window[0];
  window_time_ = st.hemo_window[1];
  window_index_ = std::lround(st.hemo_window[2]);
}

// Its options, for -help and docs/options.md (option_doc.hpp).
OptionSection wall_shear_options() {
  return {"Wall shear and hemodynamics",
          {{"hemo_surfaces", "", "-", "walls for wall shear stress, TAWSS, OSI, RRT"},
           {"hemo_window", "0 (the whole run)", "s", "averaging window"},
           {"hemo_start", "0", "s", "start of the first window"}}};
}

} // namespace fsi
