// The Newton linear-solver backends, in one table: for each scene::LinearSolverKind of the scene its
// name (as [solver] linear_solver spells it), the older alias the scene parser also accepts, a
// description, and the function that creates its SUNDIALS matrix and linear solver. The scene
// parser (io/scene/scene_parser.cpp) maps the names to the kinds; a test checks that it agrees
// with this table (tests/solver/numerics/newton_backends_test.cpp).
#pragma once

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nvector.h>

#include <span>

#include "io/scene/scene.hpp"
#include "solver/numerics/bordered_matrix.hpp"

namespace raceway::numerics {

/// A backend's SUNDIALS matrix and linear solver, for the caller to own.
struct NewtonObjects {
  SUNMatrix matrix = nullptr;
  SUNLinearSolver solver = nullptr;
};

struct LinearSolverBackend {
  scene::LinearSolverKind kind;
  const char* name;         ///< [solver] linear_solver = "name"
  const char* alias;        ///< an older name the scene parser accepts too, or nullptr
  const char* description;  ///< what it is, one line
  /// Creates the matrix and solver for states of `layout` (`y`: a template vector of that length);
  /// nullptr for `auto`, which stands for another backend (resolve_linear_solver).
  NewtonObjects (*create)(SUNContext ctx, N_Vector y, const BorderedLayout& layout);
};

/// Every entry, `auto` first.
std::span<const LinearSolverBackend> linear_solver_backends();
/// The entry of `kind`.
const LinearSolverBackend& linear_solver_backend(scene::LinearSolverKind kind);

/// The backend `linear_solver = "auto"` stands for: block elimination (the measured reason is at its
/// definition and in README "Newton linear solvers"). Any other kind is returned as is.
scene::LinearSolverKind resolve_linear_solver(scene::LinearSolverKind kind, const BorderedLayout& layout);
/// "petsc-bordered", "block-elimination", "sundials-dense", "auto".
const char* linear_solver_name(scene::LinearSolverKind kind);

}  // namespace raceway::numerics
