// The Newton linear systems CVODE solves, M = I - gamma J with J block diagonal with borders
// (solver/numerics/bordered_matrix.hpp), behind SUNDIALS' matrix / linear-solver seam, one pair per
// backend (the table of them: solver/numerics/linear_solver_registry.hpp):
//
//  - petsc-bordered (petsc_bordered_backend.cpp): PETSc SeqAIJ matrices preallocated exactly from the
//    bordered structure, KSPPREONLY + PCFIELDSPLIT Schur with an explicit Schur complement, all
//    factorisations exact. Every choice is a PETSc option (petsc_options.cpp); PETSc itself lives in
//    a PetscRuntime (petsc_runtime.hpp).
//  - block-elimination (block_elimination_backend.cpp): the hand-written Schur complement
//    elimination of bordered_matrix.hpp, on Eigen blocks. Kept because it is several times cheaper
//    than PETSc per setup + solve for the system sizes of real bearings (numbers in README "Newton
//    linear solvers" and perf/bench/results/).
//  - sundials-dense (sundials_dense_backend.cpp): SUNDIALS dense LU of the same matrix, the baseline.
//
// Collective: nothing here communicates; all of it runs on the master rank (PETSC_COMM_SELF).
#pragma once

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nvector.h>

#include <string>

#include "io/scene/scene.hpp"
#include "solver/numerics/bordered_matrix.hpp"
#include "solver/numerics/linear_solver_registry.hpp"
#include "solver/numerics/petsc_runtime.hpp"

namespace raceway::numerics {

/// Puts the scene's and the command line's PETSc options into PETSc's database (defaults where
/// neither sets a key) and validates them by a trial setup + solve of a small system with `layout`'s
/// border and block sizes: a misspelt type, a package PETSc lacks, an option nothing reads, or a
/// combination that fails to set up or solve throws scene::SceneError (scene options) or OptionsError
/// (command line). Returns a one-line description of the solver the options build, with the trial's
/// relative residual (an inexact choice such as ILU is allowed, and said so). Cached: repeated calls
/// with the same options only return the description. Requires a PetscRuntime.
std::string configure_petsc_options(const scene::SolverSpec& spec, const BorderedLayout& layout);

/// For the run driver and `raceway check`: resolves `auto`, configures PETSc when it is chosen, and
/// returns a line saying which backend runs and why.
std::string prepare_linear_solver(const scene::SolverSpec& spec, const BorderedLayout& layout);

/// A SUNMatrix + SUNLinearSolver pair for one backend, owned. CVODE's Jacobian callback fills the
/// matrix with load_jacobian(); CVODE then forms M = I - gamma J through the matrix's ops.
class NewtonLinearSystem {
 public:
  /// `kind` must be resolved (not automatic). `y` is a template vector of the state's length.
  NewtonLinearSystem(scene::LinearSolverKind kind, SUNContext ctx, N_Vector y, const BorderedLayout& layout);
  ~NewtonLinearSystem();
  NewtonLinearSystem(const NewtonLinearSystem&) = delete;
  NewtonLinearSystem& operator=(const NewtonLinearSystem&) = delete;

  SUNMatrix matrix() const { return matrix_; }
  SUNLinearSolver solver() const { return solver_; }
  scene::LinearSolverKind kind() const { return kind_; }
  /// Writes J into `a` (this system's matrix or a clone of it, as CVODE passes them).
  static void load_jacobian(const BorderedMatrix& j, SUNMatrix a);
  /// The last error of the linear solver (PETSc's message), empty if none.
  std::string last_error() const;

 private:
  scene::LinearSolverKind kind_;
  SUNMatrix matrix_ = nullptr;
  SUNLinearSolver solver_ = nullptr;
};

}  // namespace raceway::numerics
