// The Newton linear systems CVODE solves, M = I - gamma J with J block diagonal with borders
// (DESIGN.md 4.3), behind SUNDIALS' matrix / linear-solver seam, one pair per backend:
//
//  - petsc-bordered: J and M are PETSc SeqAIJ matrices preallocated exactly from the bordered
//    structure; CVODE's jok path copies the saved J into M (MatCopy SAME_NONZERO_PATTERN) and forms
//    M = I - gamma J (MatScale + MatShift); the solve is KSPPREONLY + PCFIELDSPLIT Schur (split 0 =
//    rolling-element blocks, exact LU; split 1 = border; Schur complement formed explicitly and
//    factored by LU; full factorisation, so the solve is exact). Every choice is a PETSc option.
//  - block-elimination: the hand-written Schur complement elimination of solver/bordered_matrix.hpp,
//    on Eigen blocks. Kept because it is several times cheaper than PETSc per setup + solve for the
//    system sizes of real bearings (numbers in README "Newton linear solvers" and perf/results/).
//  - sundials-dense: SUNDIALS dense LU of the same matrix, the baseline.
//
// Collective: nothing here communicates; all of it runs on the master rank (PETSC_COMM_SELF).
#pragma once

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nvector.h>

#include <stdexcept>
#include <string>

#include "io/scene/scene.hpp"
#include "solver/numerics/bordered_matrix.hpp"

namespace raceway::solver {

/// Sizes of a bordered system: border states (rings, cage), rolling elements, states per element.
struct BorderedLayout {
  int border = 0, blocks = 0, block_size = 0;
  int size() const { return border + blocks * block_size; }
};

/// The backend `linear_solver = "auto"` stands for: block elimination (the measured reason is at its
/// definition and in README "Newton linear solvers"). Any other kind is returned as is.
io::LinearSolverKind resolve_linear_solver(io::LinearSolverKind kind, const BorderedLayout& layout);
/// "petsc-bordered", "block-elimination", "sundials-dense", "auto".
const char* linear_solver_name(io::LinearSolverKind kind);

/// Bad PETSc options given on the command line (--petsc-options): exit code 2, like a bad scene.
/// Bad options from the scene are io::SceneError naming the file, line and key solver.petsc_options.
class OptionsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// PETSc for the lifetime of the object. Create it after MPI_Init (PETSc then leaves MPI_Finalize to
/// the caller) and before any petsc-bordered solver; destroy it before MPI_Finalize. One per process.
/// PETSc's own argv parsing is not used: options come from the scene ([solver] petsc_options) and
/// from `command_line_options` (raceway run --petsc-options "..."), which override the scene's.
class PetscRuntime {
 public:
  explicit PetscRuntime(std::string command_line_options = "");
  ~PetscRuntime();
  PetscRuntime(const PetscRuntime&) = delete;
  PetscRuntime& operator=(const PetscRuntime&) = delete;
  static bool active();
  /// Replaces the command-line options (tests).
  static void set_command_line_options(std::string options);
};

/// Puts the scene's and the command line's PETSc options into PETSc's database (defaults where
/// neither sets a key) and validates them by a trial setup + solve of a small system with `layout`'s
/// border and block sizes: a misspelt type, a package PETSc lacks, an option nothing reads, or a
/// combination that fails to set up or solve throws io::SceneError (scene options) or OptionsError
/// (command line). Returns a one-line description of the solver the options build, with the trial's
/// relative residual (an inexact choice such as ILU is allowed, and said so). Cached: repeated calls
/// with the same options only return the description. Requires a PetscRuntime.
std::string configure_petsc_options(const io::SolverSpec& spec, const BorderedLayout& layout);

/// For the run driver and `raceway check`: resolves `auto`, configures PETSc when it is chosen, and
/// returns a line saying which backend runs and why.
std::string prepare_linear_solver(const io::SolverSpec& spec, const BorderedLayout& layout);

/// A SUNMatrix + SUNLinearSolver pair for one backend, owned. CVODE's Jacobian callback fills the
/// matrix with load_jacobian(); CVODE then forms M = I - gamma J through the matrix's ops.
class NewtonLinearSystem {
 public:
  /// `kind` must be resolved (not automatic). `y` is a template vector of the state's length.
  NewtonLinearSystem(io::LinearSolverKind kind, SUNContext ctx, N_Vector y, const BorderedLayout& layout);
  ~NewtonLinearSystem();
  NewtonLinearSystem(const NewtonLinearSystem&) = delete;
  NewtonLinearSystem& operator=(const NewtonLinearSystem&) = delete;

  SUNMatrix matrix() const { return matrix_; }
  SUNLinearSolver solver() const { return solver_; }
  io::LinearSolverKind kind() const { return kind_; }
  /// Writes J into `a` (this system's matrix or a clone of it, as CVODE passes them).
  static void load_jacobian(const BorderedMatrix& j, SUNMatrix a);
  /// The last error of the linear solver (PETSc's message), empty if none.
  std::string last_error() const;

 private:
  io::LinearSolverKind kind_;
  SUNMatrix matrix_ = nullptr;
  SUNLinearSolver solver_ = nullptr;
};

}  // namespace raceway::solver
