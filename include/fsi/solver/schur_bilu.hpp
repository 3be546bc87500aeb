// PC "schur_bilu" (-pc_type schur_bilu): the coupled system's (velocity | pressure) Schur
// preconditioner in upper-triangular form, as the field split's
//   -pc_fieldsplit_type schur -pc_fieldsplit_schur_fact_type upper
//   -pc_fieldsplit_schur_precondition selfp, block-Jacobi ILU(0) on velocity, preonly solves,
// but built from the Jacobian without copying its velocity block:
//  * velocity: ILU(0) of each rank's on-rank velocity block with 3x3 node blocks (BlockIlu3),
//    read straight from the Jacobian's rows; the factor is stored in single precision by default
//    (-pc_schur_bilu_precision double keeps it in double: the field split's preconditioner);
//  * pressure: Sp = A11 - A10 diag(A00)^-1 A01 (PETSc's selfp), solved by a PC with the prefix
//    schur_ (default: hypre BoomerAMG, one V-cycle; -schur_pc_type and its options change it);
//  * only A01 (velocity rows, pressure columns) is kept between rebuilds; A10 and A11 are taken
//    only to form Sp.
// The field split keeps a copy of all four blocks and a separate AIJ factor of A00: on the
// paper-size tube ~220 MB per rank that this PC does not hold (docs/speed.md).
#pragma once
#include <petscpc.h>

namespace fsi {

// Register the PC type with PETSc (once, after PetscInitialize).
void register_schur_bilu_preconditioner();

// Hands a schur_bilu PC the owned velocity and pressure dofs (global numbers, the velocity's
// node triples consecutive); does nothing for another PC type.
void set_schur_bilu_fields(PC pc, IS velocity, IS pressure);

} // namespace fsi
