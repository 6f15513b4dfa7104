#include "solver/numerics/newton_backends.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "solver/numerics/backend_factories.hpp"
#include "solver/numerics/sundials_custom.hpp"

namespace raceway::numerics {

NewtonLinearSystem::NewtonLinearSystem(scene::LinearSolverKind kind, SUNContext ctx, N_Vector y,
                                       const BorderedLayout& layout)
    : kind_(kind) {
  const LinearSolverBackend& backend = linear_solver_backend(kind);
  if (!backend.create) throw std::logic_error("NewtonLinearSystem: resolve linear_solver = auto first");
  const NewtonObjects objects = backend.create(ctx, y, layout);
  matrix_ = objects.matrix;
  solver_ = objects.solver;
  if (!matrix_ || !solver_) {
    if (solver_) SUNLinSolFree(solver_);
    if (matrix_) SUNMatDestroy(matrix_);
    throw std::runtime_error("NewtonLinearSystem: SUNDIALS could not create the matrix or solver");
  }
}

NewtonLinearSystem::~NewtonLinearSystem() {
  if (solver_) SUNLinSolFree(solver_);
  if (matrix_) SUNMatDestroy(matrix_);
}

void NewtonLinearSystem::load_jacobian(const BorderedMatrix& j, SUNMatrix a) {
  if (SUNMatGetID(a) == SUNMATRIX_DENSE)
    backend::load_dense(j, a);
  else
    backend::content(a).load(j);
}

std::string NewtonLinearSystem::last_error() const {
  if (SUNLinSolGetID(solver_) != SUNLINEARSOLVER_CUSTOM) return {};
  return backend::solver_content(solver_).last_error;
}

std::string prepare_linear_solver(const scene::SolverSpec& spec, const BorderedLayout& layout) {
  const scene::LinearSolverKind kind = resolve_linear_solver(spec.linear_solver, layout);
  std::string line = fmt::format("Newton linear solver: {}", linear_solver_name(kind));
  if (spec.linear_solver == scene::LinearSolverKind::automatic)
    line += fmt::format(" (auto: {})", linear_solver_backend(scene::LinearSolverKind::automatic).description);
  // PETSc options are validated whenever they are given, even if `auto` chose the other backend, so
  // that a typo shows at start-up and not in the first large run.
  PetscRuntime* petsc = PetscRuntime::active() ? &PetscRuntime::current() : nullptr;
  const bool options_given = !spec.petsc_options.empty() || (petsc && !petsc->command_line_options().empty());
  if (kind == scene::LinearSolverKind::petsc_bordered) {
    line += "; " + configure_petsc_options(spec, layout);
  } else if (options_given && petsc) {
    petsc->configure_options(spec, layout);
    line += "; the PETSc options given are valid but unused by this backend";
  }
  return line;
}

}  // namespace raceway::numerics
