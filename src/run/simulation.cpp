#include "fsi/run/simulation.hpp"

#include "fsi/physics/gap_seal.hpp"
#include "fsi/physics/interface_flux.hpp"
#include "fsi/physics/physics_registry.hpp"
#include "fsi/scene/option_doc.hpp"
#include "fsi/scene/options.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace fsi {

Scene Scene::from_options() {
  Scene s;
  s.name = opt::string("scene_name", "scene");
  s.physics = opt::list("physics");
  if (s.physics.empty())
    throw InputError("the scene switches no physics on: give -physics fluid, solid or both");
  check_physics(s.physics);
  s.time = TimeParams::from_options();
  return s;
}

bool Scene::has(const std::string &p) const {
  return std::find(physics.begin(), physics.end(), p) != physics.end();
}

std::string Scene::tag() const {
  char tag[200];
  std::snprintf(tag, sizeof tag, "physics %s, %s", opt::join(physics, ",").c_str(),
                time.steady
                    ? "steady"
                    : ("generalized-alpha rho_inf " + std::to_string(time.rho_inf)).c_str());
  return tag;
}

Simulation::Simulation(const Mesh &mesh, const Scene &scene, const OutputNames &out,
                       const RunState *state)
    : scene_(scene), out_(out) {
  space_.build(mesh);
  keys_ = std::make_unique<Checkpoint>(space_);
  // The solid's material reference comes with a state (the mesh may be a remeshed one);
  // a fresh run starts from the mesh as built.
  std::vector<double> dn;
  if (state)
    keys_->vertices(*state, dn, material_X_);
  else
    material_X_ = space_.X;
  build_physics(mesh);
  geometry_monitor_ = opt::flag("ale_geometry_monitor", false);
  U_ = space_.create_global();
  FSI_CALL(PetscObjectSetName((PetscObject)U_, "solution"));
  Sloc_ = space_.create_local();
  initialize(opt::choice("ic", "rest", {"rest", "exact", "velocity"}));
  if (state) {
    time_->set_time(state->time, state->step);
    keys_->dofs(*state, {time_->velocity(), time_->acceleration(), time_->displacement()});
    ale_->restore(dn);
    FSI_CALL(VecCopy(time_->velocity(), U_));
    for (auto &m : monitors_)
      m->load(*state);
    bcs_->restore_state(state->lumped);
    auto sw = state->lumped.find("rho_inf_switched");
    if (rho_switch_ && sw != state->lumped.end() && sw->second != 0)
      rho_switched_ = true, time_->set_rho_inf(rho_switch_to_);
    auto as = state->lumped.find("adapt_switched");
    adapt_switched_ = adapt_switch_ && as != state->lumped.end() && as->second != 0;
  }
}

Simulation::~Simulation() {
  if (U_) VecDestroy(&U_);
  if (Sloc_) VecDestroy(&Sloc_);
}

// Physics modules switched on by the scene, their boundary conditions, mesh motion, solver and
// monitors: what the scene does not ask for is not built.
void Simulation::build_physics(const Mesh &mesh) {
  time_ = std::make_unique<GeneralizedAlpha>(space_, scene_.time);
  system_ = std::make_unique<CoupledSystem>(space_);
  // The physics switched on, in the registry's order (each finds what it needs built).
  PhysicsBuild built(mesh, space_, material_X_);
  for (auto &t : physics_types())
    if (scene_.has(t.name)) t.make(built);
  fluid_ = built.fluid;
  solid_ = built.solid;
  const GapSeal *seal = built.seal;
  exact_solid_ = std::move(built.exact_solid);
  if (fluid_) exact_ = make_exact_flow(fluid_->params().rho, fluid_->params().mu);
  for (auto &m : built.modules)
    system_->add_module(std::move(m));
  const std::vector<PetscInt> *fluid_cells = fluid_ ? &fluid_->cells() : nullptr;
  ale_ = std::make_unique<Ale>(space_, make_mesh_motion(mesh, space_, fluid_cells, material_X_),
                               fluid_cells);
  if (ale_->ignores_sealed() && !seal)
    throw InputError("-ale_remesh_ignore_sealed needs the gap seal: -physics "
                     "fluid,solid,contact,gap_seal (or drop the option)");
  if (seal)
    ale_->set_sealed([seal](std::vector<char> &sealed) {
      sealed.resize(seal->cells().size()); // the fluid's cells, in their order
      for (size_t c = 0; c < sealed.size(); ++c)
        sealed[c] = seal->sealed(c);
    });
  const std::string iface = opt::string("ale_interface", "");
  if (!iface.empty()) {
    if (!fluid_ || !ale_->moving())
      throw InputError("-ale_interface needs a fluid and a mesh motion (-ale_motion laplace)");
    system_->add_module(
        std::make_unique<InterfaceMassFlux>(space_, mesh, iface, fluid_->cells(), material_X_));
  }
  bcs_ = std::make_unique<Boundaries>(
      mesh, space_, exact_.get(), exact_solid_.get(), fluid_ ? fluid_->params().mu : 0.0,
      fluid_ ? fluid_->params().rho : 0.0, material_X_, fluid_cells);
  system_->set_boundaries(bcs_.get());
  system_->set_rigid_body_modes(solid_ != nullptr);
  if (FluidSolidSplit::requested(fluid_ != nullptr, solid_ != nullptr))
    system_->set_fluid_solid_split(std::make_unique<FluidSolidSplit>(space_, solid_->cells()));
  if (PcdOperators::requested(fluid_ != nullptr))
    system_->set_pcd(std::make_unique<PcdOperators>(space_, mesh, *fluid_, *bcs_));
  system_->setup_solver();
  const MonitorSetup ms{mesh,
                        space_,
                        fluid_,
                        solid_,
                        built.contact,
                        exact_.get(),
                        exact_solid_.get(),
                        out_.dir,
                        out_.hemo,
                        scene_.time.t_end,
                        material_X_};
  for (auto &t : monitor_types())
    if (auto m = t.make(ms)) monitors_.push_back(std::move(m));
  if (out_.fields_every > 0) {
    FieldSet set;
    set.pressure = fluid_ != nullptr;
    set.mesh_displacement = ale_->moving();
    set.displacement = solid_ != nullptr;
    set.base = out_.fields;
    if (solid_ && fluid_) { // a cell attribute to tell the leaflets (1) from the fluid (0)
      set.region.assign(space_.n_cells(), 0);
      for (PetscInt k : solid_->cells())
        set.region[k] = 1;
    }
    fields_ = std::make_unique<FieldWriter>(space_, out_.dir, set);
  }
  bcs_->bind_monitors(monitor_columns());
  // More numerical damping while a monitor condition holds (the valve closed: its pressed leaflets
  // would ring at rho_inf 0.5; docs/valve.md).
  rho_switch_ = MonitorCondition::from_option("ts_alpha_radius_switch_when");
  rho_switch_to_ = opt::real("ts_alpha_radius_switch_to", 0.0);
  if (rho_switch_to_ < 0 || rho_switch_to_ > 1)
    throw InputError(
        "option -ts_alpha_radius_switch_to (spectral radius rho_inf) must be in [0, 1]");
  if (rho_switch_ && scene_.time.steady)
    throw InputError("option -ts_alpha_radius_switch_when needs -ts_type alpha");
  // The switches may also test the time: "time" is the column after the monitor's own.
  auto switch_columns = monitor_columns();
  switch_columns.push_back("time");
  rho_switch_.bind(switch_columns);
  // Error-controlled steps while a monitor condition holds (the valve's quiet diastole: long
  // steps where nothing moves; the scene's dt elsewhere).  StepControl checks the mode.
  adapt_switch_ = MonitorCondition::from_option("ts_adapt_switch_when");
  adapt_switch_.bind(switch_columns);
}

// Initial state at t = 0: rest, a uniform velocity, or the exact flow (-ic rest|velocity|exact).
void Simulation::initialize(const std::string &ic) {
  time_->set_time(0, 0);
  ale_->initialize();
  Vec Vn = time_->velocity(), An = time_->acceleration();
  FSI_CALL(VecZeroEntries(U_));
  FSI_CALL(VecZeroEntries(Vn));
  FSI_CALL(VecZeroEntries(An));
  FSI_CALL(VecZeroEntries(time_->displacement()));
  PetscSection ls;
  FSI_CALL(DMGetLocalSection(space_.dm, &ls));
  if (ic == "velocity") {
    // A uniform initial velocity (-ic_velocity x,y,z [m/s]) on every node that no Dirichlet
    // condition holds: e.g. a clamped block set vibrating.  u_0 = 0 and no load give a_0 = 0.
    auto v0 = opt::reals("ic_velocity");
    if (v0.size() != 3) throw InputError("-ic velocity needs -ic_velocity vx,vy,vz [m/s]");
    PetscScalar *u;
    FSI_CALL(VecGetArray(U_, &u));
    const std::vector<char> &mask = bcs_->dirichlet_mask();
    for (PetscInt v = space_.vStart; v < space_.eEnd; ++v) {
      PetscInt off, dof;
      FSI_CALL(PetscSectionGetFieldDof(ls, v, 0, &dof));
      if (dof != 3) continue;
      FSI_CALL(PetscSectionGetFieldOffset(ls, v, 0, &off));
      for (int d = 0; d < 3; ++d)
        if (space_.owned(off + d) && !mask[off + d])
          u[space_.local_to_global[off + d] - space_.rstart] = v0[d];
    }
    FSI_CALL(VecRestoreArray(U_, &u));
    FSI_CALL(VecCopy(U_, Vn));
  } else if (ic == "exact") {
    if (!exact_) throw InputError("-ic exact needs -exact_solution");
    // Values on every local node; the nodal time derivative follows the node along its mesh
    // trajectory x(t) = X + d_m(t) (ALE), by a central difference of the exact flow.
    std::vector<double> dm_m, dm_p;
    const double eps = 1e-6 * (scene_.time.steady ? 1.0 : time_->dt()) + 1e-9;
    ale_->mesh_at(-eps, dm_m);
    ale_->mesh_at(eps, dm_p);
    const std::vector<double> &d0 = ale_->displacement();
    Vec Uloc = space_.create_local(), Aloc = space_.create_local();
    PetscScalar *u, *a;
    FSI_CALL(VecGetArray(Uloc, &u));
    FSI_CALL(VecGetArray(Aloc, &a));
    auto pos = [&](const std::vector<double> &d, int va, int vb, double x[3]) {
      for (int k = 0; k < 3; ++k) {
        x[k] = space_.X[3 * va + k] + d[3 * va + k];
        if (vb >= 0) x[k] = 0.5 * (x[k] + space_.X[3 * vb + k] + d[3 * vb + k]);
      }
    };
    auto set_node = [&](PetscInt off, int va, int vb) {
      double x0[3], xm[3], xp[3], v0[3], vm[3], vp[3];
      pos(d0, va, vb, x0);
      pos(dm_m, va, vb, xm);
      pos(dm_p, va, vb, xp);
      exact_->velocity(x0, 0.0, v0);
      exact_->velocity(xm, -eps, vm);
      exact_->velocity(xp, eps, vp);
      for (int k = 0; k < 3; ++k) {
        u[off + k] = v0[k];
        a[off + k] = (vp[k] - vm[k]) / (2 * eps);
      }
    };
    const std::vector<double> &Xn = ale_->coordinates();
    for (PetscInt v = space_.vStart; v < space_.vEnd; ++v) {
      PetscInt off;
      const int iv = (int)(v - space_.vStart);
      FSI_CALL(PetscSectionGetFieldOffset(ls, v, 0, &off));
      set_node(off, iv, -1);
      FSI_CALL(PetscSectionGetFieldOffset(ls, v, 1, &off));
      double x0[3] = {Xn[3 * iv], Xn[3 * iv + 1], Xn[3 * iv + 2]};
      u[off] = exact_->pressure(x0, 0.0);
    }
    for (PetscInt e = space_.eStart; e < space_.eEnd; ++e) {
      PetscInt off;
      const PetscInt *cone;
      FSI_CALL(DMPlexGetCone(space_.dm, e, &cone));
      FSI_CALL(PetscSectionGetFieldOffset(ls, e, 0, &off));
      set_node(off, (int)(cone[0] - space_.vStart), (int)(cone[1] - space_.vStart));
    }
    // Owned entries straight into the global vectors (every rank computed the same values).
    PetscScalar *ug, *ag;
    FSI_CALL(VecGetArray(U_, &ug));
    FSI_CALL(VecGetArray(An, &ag));
    for (PetscInt i = 0; i < space_.n_local; ++i)
      if (space_.owned(i)) {
        ug[space_.local_to_global[i] - space_.rstart] = u[i];
        ag[space_.local_to_global[i] - space_.rstart] = a[i];
      }
    FSI_CALL(VecRestoreArray(U_, &ug));
    FSI_CALL(VecRestoreArray(An, &ag));
    FSI_CALL(VecRestoreArray(Uloc, &u));
    FSI_CALL(VecRestoreArray(Aloc, &a));
    FSI_CALL(VecDestroy(&Uloc));
    FSI_CALL(VecDestroy(&Aloc));
    FSI_CALL(VecCopy(U_, Vn));
  }
}

ProjectionReport Simulation::project_velocity(bool project) {
  if (!fluid_) return {};
  if (!project) {
    ProjectionReport r;
    r.before =
        measure_weak_divergence(space_, fluid_->cells(), ale_->coordinates(), time_->velocity());
    return r;
  }
  std::vector<char> fixed = bcs_->dirichlet_mask();
  if (solid_)
    for (PetscInt k : solid_->cells())
      for (int a = 0; a < 10; ++a)
        for (int i = 0; i < 3; ++i)
          fixed[space_.cell_vdof[10 * k + a] + i] = 1;
  return project_divergence_free(space_, fluid_->cells(), ale_->coordinates(), fixed,
                                 system_->matrix(), time_->velocity());
}

void Simulation::set_dt(double dt) {
  if (dt == time_->dt()) return;
  time_->set_dt(dt);
  system_->step_size_changed(dt);
}

// Dirichlet data at t_{n+1}: velocities on the nodes' positions at t_{n+1}, prescribed
// displacements as the velocities that give them through the Newmark relation.
void Simulation::dirichlet_data(double t_np1) {
  auto &values = system_->dirichlet_values();
  bcs_->dirichlet_values(t_np1, ale_->coordinates_np1().data(), values);
  bcs_->displacement_values(t_np1, disp_values_);
  time_->velocities_for_displacements(disp_values_, values);
}

StepStats Simulation::step(const StepErrorTolerance *tol) {
  const double dt = time_->dt(), t_np1 = time_->time() + dt;
  const long next = time_->step_index() + 1;
  const bool steady = scene_.time.steady;
  // Mesh displacement at t_{n+1} for the velocity U (the solid displacement it implies).
  auto move_mesh = [&](std::vector<double> &d) {
    if (!ale_->follows_solid()) return ale_->move(t_np1, nullptr, d);
    time_->displacement_np1_local(U_, Sloc_);
    const PetscScalar *sa;
    FSI_CALL(VecGetArrayRead(Sloc_, &sa));
    ale_->move(t_np1, sa, d);
    FSI_CALL(VecRestoreArrayRead(Sloc_, &sa));
  };

  // Predictor U = V_n; the mesh at n+1 from the predicted solid displacement, at n+alpha_f, and
  // the mesh velocity; a cell that would invert stops the run before the solve.
  ale_->begin_step();
  time_->predict(U_);
  std::vector<double> d;
  move_mesh(d);
  ale_->set_geometry(d, time_->alpha_f(), dt, steady);
  ale_->check("before", next);
  dirichlet_data(t_np1);

  StepContext &ctx = system_->context();
  ctx.is_dirichlet = &bcs_->dirichlet_mask();
  ale_->fill_context(ctx);
  time_->fill_context(ctx);
  time_af_ = ctx.t_af;
  struct Release { // the history arrays go back whatever happens in the solve
    const GeneralizedAlpha &t;
    StepContext &c;
    ~Release() { t.release_context(c); }
  } release{*time_, ctx};

  StepStats s;
  SolveStats r;
  for (int pass = 0;; ++pass) {
    r = system_->solve(U_);
    s.newton += r.newton;
    s.krylov += r.krylov;
    if (r.reason < 0 || !ale_->follows_solid() || pass >= ale_->geometry_iterations()) break;
    // Geometry implicit: move the mesh with the solid displacement just found and solve again
    // until the mesh stops changing.
    std::vector<double> d2;
    move_mesh(d2);
    s.geometry_iterations = pass + 1;
    s.geometry_change = ale_->relative_change(d2);
    if (geometry_monitor_)
      PetscPrintf(PETSC_COMM_WORLD, "  geometry pass %d: Newton %d, mesh change %.3e\n", pass + 1,
                  (int)r.newton, s.geometry_change);
    if (s.geometry_change <= ale_->geometry_rtol()) break;
    ale_->set_geometry(d2, time_->alpha_f(), dt, steady);
    ale_->check("during", next);
    ale_->fill_context(ctx);
  }
  if (r.reason < 0 && r.inverted)
    throw SolveError("a solid element inverted (det F <= 0) at step " + std::to_string(next) +
                     " (t = " + std::to_string(t_np1) +
                     "): the load or time step is too large for this mesh; use more steps");
  if (r.reason < 0)
    throw SolveError(std::string("Newton did not converge at step ") + std::to_string(next) +
                     " (t = " + std::to_string(t_np1) + "): " + SNESConvergedReasons[r.reason] +
                     "; try a smaller -ts_dt (or more load steps -ts_max_steps)");
  if (tol && !steady && time_->step_index() > 0 && history_exact_) {
    s.error = time_->error_estimate(U_, space_.is_velocity, tol->atol, tol->rtol, tol->rms);
    if (s.error > 1 && !tol->accept_any) throw StepRejected(s.error);
  }
  history_exact_ = true;
  bcs_->accept_step(); // lumped models advance with the converged iterate's flux
  time_->advance(U_);
  ale_->accept();
  return s;
}

// Every monitor value of a step under its column's name; with `s` null, the names only (the
// columns, before any step).  Sources add in this order: monitor.csv's column order.
void Simulation::monitor_row(MonitorRow &row, const StepStats *s, const FieldView &view) {
  for (auto &m : monitors_)
    m->add_to(row, view);
  row.add(bcs_->monitor_columns(), [&] { return bcs_->monitor_values(); });
  for (auto &m : system_->modules())
    m->add_to(row);
  ale_->add_to(row, s ? s->geometry_iterations : 0, s ? s->geometry_change : 0.0);
}

std::vector<std::string> Simulation::monitor_columns() {
  MonitorRow row(MonitorRow::names_only);
  monitor_row(row, nullptr, FieldView{});
  return row.names();
}

std::vector<double> Simulation::after_step(double dt, const StepStats &s) {
  // The view the monitors read: the fields with ghosts, the mesh, the time.  The displacement
  // only where something reads it (a solid's monitors, the field files).
  const bool fields_due = fields_ && step_index() % out_.fields_every == 0;
  Vec uloc = space_.create_local(), dloc = nullptr;
  space_.to_local(U_, uloc);
  FieldView view;
  FSI_CALL(VecGetArrayRead(uloc, &view.u));
  if (solid_ || fields_due) {
    dloc = space_.create_local();
    space_.to_local(time_->displacement(), dloc);
    FSI_CALL(VecGetArrayRead(dloc, &view.d));
  }
  view.x = &ale_->coordinates();
  // The pressure unknown of the last step is the multiplier of the momentum balance at
  // t_{n+alpha_f} on that configuration: compared there (second order in time).
  view.x_af = &ale_->coordinates_af();
  view.t = time();
  view.t_af = time_af_;
  for (auto &m : monitors_)
    m->update(view, dt);
  MonitorRow filled(MonitorRow::with_values);
  monitor_row(filled, &s, view);
  std::vector<double> row = filled.values();
  FSI_CALL(VecRestoreArrayRead(uloc, &view.u));
  if (dloc) FSI_CALL(VecRestoreArrayRead(dloc, &view.d));
  if (fields_due) {
    fields_->write(step_index(), time(), uloc, ale_->coordinates(), dloc);
    for (auto &m : monitors_)
      m->write(step_index(), time());
  }
  FSI_CALL(VecDestroy(&uloc));
  if (dloc) FSI_CALL(VecDestroy(&dloc));
  bcs_->observe(time(), row);      // a flow that stops when the valve has closed
  std::vector<double> row_t = row; // the switches' columns: the monitors and the time
  row_t.push_back(time());
  if (rho_switch_) { // rho_inf follows the condition: the switched value while it holds
    double m = 0;
    const bool on = rho_switch_.holds(row_t, PetscObjectComm((PetscObject)space_.dm), &m);
    if (on != rho_switched_) {
      const double r = on ? rho_switch_to_ : scene_.time.rho_inf;
      char msg[256]; // snprintf: PETSc's printf would write the value 0 as "0."
      std::snprintf(msg, sizeof msg,
                    "fsi_app: %s = %g (%s %c %g%s) at t = %.6g s: generalized-alpha rho_inf %g -> "
                    "%g from the next step\n",
                    rho_switch_.column.c_str(), m, on ? "now" : "no longer", rho_switch_.op,
                    rho_switch_.value, rho_switch_.rest().c_str(), time(), time_->params().rho_inf,
                    r);
      PetscPrintf(PetscObjectComm((PetscObject)space_.dm), "%s", msg);
      rho_switched_ = on;
      time_->set_rho_inf(r);
    }
  }
  if (adapt_switch_) {
    double m = 0;
    const bool on = adapt_switch_.holds(row_t, PetscObjectComm((PetscObject)space_.dm), &m);
    if (on != adapt_switched_) {
      char msg[256];
      std::snprintf(msg, sizeof msg,
                    "fsi_app: %s = %g (%s %c %g%s) at t = %.6g s: time steps %s from the next "
                    "step\n",
                    adapt_switch_.column.c_str(), m, on ? "now" : "no longer", adapt_switch_.op,
                    adapt_switch_.value, adapt_switch_.rest().c_str(), time(),
                    on ? "chosen by the error estimate" : "back to -ts_dt");
      PetscPrintf(PetscObjectComm((PetscObject)space_.dm), "%s", msg);
      adapt_switched_ = on;
    }
  }
  return row;
}

void Simulation::end_adapt_switch_for_period() {
  if (!adapt_switched_) return;
  adapt_switched_ = false;
  PetscPrintf(PetscObjectComm((PetscObject)space_.dm),
              "fsi_app: a new period (-ts_adapt_period) at t = %.6g s: time steps back to -ts_dt "
              "from the next step\n",
              time());
}

void Simulation::close_outputs() {
  if (fields_) fields_->close();
  for (auto &m : monitors_)
    m->close();
}

RunState Simulation::capture() const {
  RunState s;
  s.scene = scene_.tag();
  s.step = step_index();
  s.time = time();
  s.dt = dt();
  keys_->capture({time_->velocity(), time_->acceleration(), time_->displacement()},
                 ale_->displacement(), material_X_, s);
  for (auto &m : monitors_)
    m->save(s);
  bcs_->save_state(s.lumped);
  if (rho_switch_) s.lumped["rho_inf_switched"] = rho_switched_;
  if (adapt_switch_) s.lumped["adapt_switched"] = adapt_switched_;
  return s;
}

// Its options, for -help and docs/options.md (option_doc.hpp).
OptionSection scene_options() {
  return {
      "Scene and outputs",
      {{"scene_name", "scene", "-", "the scene's name (results/<name> by default)"},
       {"physics", "(required)", "-",
        "physics switched on: fluid, solid, contact (solid-solid), gap_seal (fluid in a closing "
        "gap), e.g. fluid,solid,contact,gap_seal"},
       {"out_dir", "results/SCENE_NAME", "-", "output folder"},
       {"out_fields_every", "0", "steps", "XDMF/HDF5 fields every N steps (0: none)"},
       {"checkpoint_every", "0", "steps",
        "write checkpoint.h5 every N steps (0: only on failure, signal, and at the end if N > 0)"},
       {"checkpoint_crash_test", "0", "-",
        "tests only: SIGKILL halfway through the K-th checkpoint"},
       {"restart", "", "-", "resume from this checkpoint (same scene options, any rank count)"},
       {"restart_reset_dt", "false", "-",
        "resume with the scene's -ts_dt and a fresh step controller, not the checkpoint's"},
       {"sim_rebuild_every", "0", "steps",
        "rebuild the whole discretisation from its state every N steps (checks state transfer)"},
       {"allow_unused_options", "false", "-", "otherwise an option nobody reads is an error"},
       {"ic", "rest", "-", "initial state: rest | velocity | exact"},
       {"ic_velocity", "", "m/s", "uniform initial velocity vx,vy,vz for -ic velocity"}}};
}

} // namespace fsi
