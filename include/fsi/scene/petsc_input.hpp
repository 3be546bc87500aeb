// What reaches PETSc before the scene is read: options files, the scene's solver preset, and
// PETSc's own "unknown type" errors, each turned into one line that names the option.
//   -solver_preset NAME  petsc_options/NAME.opts (or a path ending in .opts) fills in every
//                        solver option that the scene and the command line leave unset, so a
//                        scene runs as given and a later -solver_preset (or -options_file of a
//                        preset, whose first line names it) replaces the whole preset.
#pragma once
#include <mpi.h>
#include <string>
#include <utility>
#include <vector>

namespace fsi {

// An options file read as PETSc does for our purposes: "-key value" pairs, '#' starts a comment (a
// quoted value with spaces is not kept whole: presets and includes need none); a value is the
// token after a key unless that token is itself a key (a number such as -1 is a value).
// Throws InputError when the file cannot be read.
std::vector<std::pair<std::string, std::string>> read_options_file(const std::string &path);

// Before PetscInitialize: every -options_file on the command line (and those they include)
// exists.  Returns "" or the one-line error naming the missing file.
std::string check_options_files(int argc, char **argv);
// The same, said on rank 0 as one error line (MPI initialised, PETSc not yet): false if missing.
bool options_files_exist(int argc, char **argv);

// After PetscInitialize: insert the options of -solver_preset (the last one given) that are not
// already set.  Throws InputError for an unknown preset.
void apply_solver_preset();

// PETSc's "unknown type" errors (-ksp_type nosuchksp) are returned without PETSc's traceback;
// throw_petsc turns them into an InputError that names the option (petsc_unknown_type).
void install_petsc_error_handler();
// The option whose value is the unknown type PETSc complained about, as a one-line message.
std::string petsc_unknown_type(const std::string &petsc_message);

} // namespace fsi
