#include "fsi/solver/fluid_solid_split.hpp"
#include "fsi/scene/options.hpp"

namespace fsi {

bool FluidSolidSplit::requested(bool fluid, bool solid) {
  if (opt::string("fieldsplit_velocity_pc_type", "") != "fieldsplit") return false;
  if (!fluid || !solid)
    throw InputError("-fieldsplit_velocity_pc_type fieldsplit splits the velocity block into fluid "
                     "and solid: it needs -physics fluid,solid (use petsc_options/"
                     "fieldsplit_ilu.opts or solid_amg.opts for one physics)");
  if (opt::string("pc_type", "") != "fieldsplit")
    throw InputError("-fieldsplit_velocity_pc_type fieldsplit needs the outer -pc_type fieldsplit "
                     "(see petsc_options/fieldsplit_fsi.opts)");
  return true;
}

void FluidSolidSplit::configure(KSP ksp, Mat J) {
  done_ = true;
  MPI_Comm comm = PetscObjectComm((PetscObject)space_.dm);
  PC pc, vpc;
  FSI_CALL(KSPSetOperators(ksp, J, J));
  FSI_CALL(KSPGetPC(ksp, &pc));
  FSI_CALL(PCSetUp(pc)); // creates the velocity block's KSP and PC
  PetscInt nsub;
  KSP *subs;
  FSI_CALL(PCFieldSplitGetSubKSP(pc, &nsub, &subs));
  FSI_CALL(KSPGetPC(subs[0], &vpc));
  FSI_CALL(PetscFree(subs));

  // Velocity dofs of solid cells, marked alike on every rank that sees them.
  Vec g = space_.create_global(), loc = space_.create_local();
  PetscScalar *a;
  FSI_CALL(VecZeroEntries(loc));
  FSI_CALL(VecZeroEntries(g));
  FSI_CALL(VecGetArray(loc, &a));
  for (PetscInt k : solid_cells_)
    for (int n = 0; n < 10; ++n)
      for (int i = 0; i < 3; ++i)
        a[space_.cell_vdof[10 * k + n] + i] = 1.0;
  FSI_CALL(VecRestoreArray(loc, &a));
  space_.add_to_global(loc, g);

  // Index sets in the velocity block's numbering (is_velocity's position), node-blocked by 3.
  PetscInt n;
  FSI_CALL(ISGetLocalSize(space_.is_velocity, &n));
  const PetscInt start = rank_offset(comm, n);
  const PetscInt *idx;
  const PetscScalar *ga;
  std::vector<PetscInt> fluid, solid;
  std::vector<double> xyz; // solid node coordinates, for the rigid-body modes
  FSI_CALL(ISGetIndices(space_.is_velocity, &idx));
  FSI_CALL(VecGetArrayRead(g, &ga));
  for (PetscInt i = 0; i < n; ++i) {
    const bool in_solid = PetscRealPart(ga[idx[i] - space_.rstart]) > 0;
    (in_solid ? solid : fluid).push_back(start + i);
    if (in_solid && i % 3 == 0)
      for (int d = 0; d < 3; ++d)
        xyz.push_back(space_.velocity_node_X[i + d]);
  }
  FSI_CALL(VecRestoreArrayRead(g, &ga));
  FSI_CALL(ISRestoreIndices(space_.is_velocity, &idx));
  FSI_CALL(VecDestroy(&g));
  FSI_CALL(VecDestroy(&loc));

  IS isf, iss;
  FSI_CALL(ISCreateGeneral(comm, (PetscInt)fluid.size(), fluid.data(), PETSC_COPY_VALUES, &isf));
  FSI_CALL(ISCreateGeneral(comm, (PetscInt)solid.size(), solid.data(), PETSC_COPY_VALUES, &iss));
  FSI_CALL(ISSetBlockSize(iss, 3));
  compose_rigid_body_modes(iss, xyz);
  FSI_CALL(PCFieldSplitSetIS(vpc, "fluid", isf));
  FSI_CALL(PCFieldSplitSetIS(vpc, "solid", iss));
  FSI_CALL(ISDestroy(&isf));
  FSI_CALL(ISDestroy(&iss));
}

} // namespace fsi
