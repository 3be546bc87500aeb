#include "fsi/checkpoint.hpp"
#include "fsi/options.hpp"
#include "fsi/p2tet.hpp"

#include <csignal>
#include <cstdio>
#include <fcntl.h>
#include <unistd.h>

namespace fsi {

static const double FORMAT_VERSION = 1;

Checkpoint::Checkpoint(const Space &space, const std::string &scene)
    : comm_(PetscObjectComm((PetscObject)space.dm)), space_(space), scene_(scene) {
  MPI_Comm_rank(comm_, &rank_);
  crash_at_ = opt::integer("checkpoint_crash_test", 0);
  // Every owned dof once, keyed by its node's reference position and its component.
  std::vector<char> seen(space.n_local, 0);
  auto add = [&](PetscInt dof, const double x[3], int comp) {
    if (seen[dof] || !space.owned(dof)) return;
    seen[dof] = 1;
    dof_keys_.insert(dof_keys_.end(), {x[0], x[1], x[2], (double)comp});
    dof_index_.push_back(space.local_to_global[dof] - space.rstart);
  };
  for (PetscInt k = 0; k < space.n_cells(); ++k) {
    double P[4][3];
    space.cell_points(k, space.X.data(), P);
    for (int a = 0; a < 10; ++a) {
      double x[3];
      for (int d = 0; d < 3; ++d)
        x[d] = a < 4 ? P[a][d] : 0.5 * (P[TET_EDGE[a - 4][0]][d] + P[TET_EDGE[a - 4][1]][d]);
      for (int c = 0; c < 3; ++c)
        add(space.cell_vdof[10 * k + a] + c, x, c);
    }
    for (int i = 0; i < 4; ++i) {
      const PetscInt p = space.cell_pdof[4 * k + i];
      if (seen[p] || !space.owned(p)) continue;
      add(p, P[i], 3); // a vertex is owned where its pressure dof is: list it once, here
      vertex_keys_.insert(vertex_keys_.end(), {P[i][0], P[i][1], P[i][2]});
      vertex_local_.push_back(space.cell_vertex[4 * k + i]);
    }
  }
}

void Checkpoint::write(const std::string &path, const Problem &pb, const StepControl &c,
                       const WallShear &w) const {
  // Gather everything to rank 0 first (collective), then write.
  const auto vecs = pb.state_vectors();
  const size_t nd = dof_index_.size(), nv = vecs.size();
  std::vector<double> vals(nv * nd);
  for (size_t j = 0; j < nv; ++j) {
    const PetscScalar *a;
    FSI_CALL(VecGetArrayRead(vecs[j], &a));
    for (size_t i = 0; i < nd; ++i)
      vals[nv * i + j] = PetscRealPart(a[dof_index_[i]]);
    FSI_CALL(VecRestoreArrayRead(vecs[j], &a));
  }
  KeyedItems dofs = gather_sorted(comm_, dof_keys_, vals, 4, (int)nv);
  std::vector<double> dm(3 * vertex_local_.size());
  for (size_t i = 0; i < vertex_local_.size(); ++i)
    for (int d = 0; d < 3; ++d)
      dm[3 * i + d] = pb.mesh_displacement()[3 * vertex_local_[i] + d];
  KeyedItems verts = gather_sorted(comm_, vertex_keys_, dm, 3, 3);

  const std::string partial = path + ".partial";
  int ok = 1;
  std::string err;
  std::unique_ptr<H5File> f;
  if (rank_ == 0) {
    try {
      f = std::make_unique<H5File>(partial, H5File::create);
      f->set("format", "fsi_app checkpoint");
      f->set("version", FORMAT_VERSION);
      f->set("scene", scene_);
      f->set("step", (double)pb.step_index());
      f->set("time", pb.time());
      f->set("dt", c.dt);
      f->set("easy_run", (double)c.easy_run);
      f->write("/dofs/keys", dofs.keys, 4);
      f->write("/dofs/state", dofs.values, nv);
      if (++writes_ == crash_at_) raise(SIGKILL); // a run killed while writing (tests)
      f->write("/vertices/keys", verts.keys, 3);
      f->write("/vertices/mesh_displacement", verts.values, 3);
    } catch (std::exception &e) {
      ok = 0;
      err = e.what();
    }
  }
  w.save(ok ? f.get() : nullptr);
  if (rank_ == 0 && ok) {
    f.reset(); // close
    const int fd = open(partial.c_str(), O_RDONLY);
    if (fd >= 0) {
      fsync(fd);
      close(fd);
    }
    if (std::rename(partial.c_str(), path.c_str()) != 0) {
      ok = 0;
      err = "cannot rename " + partial + " to " + path;
    }
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, comm_);
  if (!ok) throw InputError("checkpoint not written: " + err);
}

void Checkpoint::read(const std::string &path, Problem &pb, StepControl &c, WallShear &w) const {
  std::unique_ptr<H5File> f;
  KeyedItems dofs, verts;
  double meta[4] = {0, 0, 0, 0}; // step, time, dt, easy_run
  long counts[2] = {0, 0};
  std::string err;
  if (rank_ == 0) {
    try {
      f = std::make_unique<H5File>(path, H5File::open_read);
      if (f->get_string("format") != "fsi_app checkpoint" || f->get("version") != FORMAT_VERSION)
        throw InputError("'" + path + "' is not an fsi_app checkpoint of this version");
      if (f->get_string("scene") != scene_)
        throw InputError("restart file '" + path + "' was written by another scene (" +
                         f->get_string("scene") + "; this one: " + scene_ +
                         "): restart with the options of the run that wrote it");
      meta[0] = f->get("step");
      meta[1] = f->get("time");
      meta[2] = f->get("dt");
      meta[3] = f->get("easy_run");
      dofs.keys = f->read("/dofs/keys");
      dofs.values = f->read("/dofs/state");
      verts.keys = f->read("/vertices/keys");
      verts.values = f->read("/vertices/mesh_displacement");
      counts[0] = (long)dofs.keys.size() / 4;
      counts[1] = (long)verts.keys.size() / 3;
    } catch (InputError &e) {
      err = e.what();
    }
  }
  int len = (int)err.size();
  MPI_Bcast(&len, 1, MPI_INT, 0, comm_);
  if (len) {
    err.resize(len);
    MPI_Bcast(err.data(), len, MPI_CHAR, 0, comm_);
    throw InputError(err);
  }
  MPI_Bcast(meta, 4, MPI_DOUBLE, 0, comm_);
  MPI_Bcast(counts, 2, MPI_LONG, 0, comm_);
  const long n_dofs = space_.n_velocity + space_.n_pressure;
  const auto vecs = pb.state_vectors();
  const int nv = (int)vecs.size();
  std::vector<double> vals, dm;
  long missing = counts[0] != n_dofs ? 1 : 0;
  if (!missing) missing = scatter_by_key(comm_, dofs, dof_keys_, vals, 4, nv);
  if (!missing) missing = scatter_by_key(comm_, verts, vertex_keys_, dm, 3, 3);
  if (missing)
    throw InputError("restart file '" + path + "' was written for another mesh (" +
                     std::to_string(counts[0]) + " dofs there, " + std::to_string(n_dofs) +
                     " here, or node positions differ): restart with the same mesh options");
  for (int j = 0; j < nv; ++j) {
    PetscScalar *a;
    FSI_CALL(VecGetArray(vecs[j], &a));
    for (size_t i = 0; i < dof_index_.size(); ++i)
      a[dof_index_[i]] = vals[nv * i + j];
    FSI_CALL(VecRestoreArray(vecs[j], &a));
  }
  // Mesh displacement on every local vertex: owned ones from the file, ghosts from their owner
  // through a dof-sized vector (the pressure dof of each vertex).
  std::vector<double> d(3 * space_.n_vertices(), 0.0);
  {
    Vec g = space_.create_global(), l = space_.create_local();
    PetscSection ls;
    FSI_CALL(DMGetLocalSection(space_.dm, &ls));
    for (int comp = 0; comp < 3; ++comp) {
      PetscScalar *ga;
      FSI_CALL(VecGetArray(g, &ga));
      for (size_t i = 0; i < vertex_local_.size(); ++i) {
        PetscInt off;
        FSI_CALL(PetscSectionGetFieldOffset(ls, space_.vStart + vertex_local_[i], 1, &off));
        ga[space_.local_to_global[off] - space_.rstart] = dm[3 * i + comp];
      }
      FSI_CALL(VecRestoreArray(g, &ga));
      space_.to_local(g, l);
      const PetscScalar *la;
      FSI_CALL(VecGetArrayRead(l, &la));
      for (PetscInt v = 0; v < space_.n_vertices(); ++v) {
        PetscInt off;
        FSI_CALL(PetscSectionGetFieldOffset(ls, space_.vStart + v, 1, &off));
        d[3 * v + comp] = PetscRealPart(la[off]);
      }
      FSI_CALL(VecRestoreArrayRead(l, &la));
    }
    FSI_CALL(VecDestroy(&g));
    FSI_CALL(VecDestroy(&l));
  }
  pb.restore(meta[1], std::lround(meta[0]), d);
  c.dt = meta[2];
  c.easy_run = std::lround(meta[3]);
  w.load(f.get());
}

} // namespace fsi
