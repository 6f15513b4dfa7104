// Internal to solver/numerics: the custom SUNMatrix and SUNLinearSolver types the block-elimination
// and petsc-bordered backends sit behind. CVODE calls SUNDIALS' function tables; these forward the
// calls to C++ objects (MatrixContent, SolverContent) and turn exceptions into SUNDIALS' flags.
#pragma once

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <memory>
#include <string>

#include "solver/numerics/bordered_matrix.hpp"

namespace raceway::numerics::backend {

/// Content of a custom SUNMatrix: a bordered matrix in one representation or another.
class MatrixContent {
 public:
  virtual ~MatrixContent() = default;
  virtual std::unique_ptr<MatrixContent> clone() const = 0;
  virtual void zero() = 0;
  /// Copies the values into `to`, which has this object's type and layout.
  virtual void copy_to(MatrixContent& to) const = 0;
  /// this = c * this + I
  virtual void scale_add_identity(double c) = 0;
  /// y = this * x
  virtual void multiply(const double* x, double* y) const = 0;
  virtual void load(const BorderedMatrix& j) = 0;
};

/// Content of a custom SUNLinearSolver. setup and solve return SUNDIALS' flags (0, positive:
/// recoverable, negative: not); an exception they throw is a SUNLS_PACKAGE_FAIL_UNREC with its
/// message kept in last_error.
class SolverContent {
 public:
  virtual ~SolverContent() = default;
  virtual int setup(SUNMatrix a) = 0;
  virtual int solve(const double* b, double* x) = 0;
  sunindextype last_flag = 0;
  std::string last_error;
};

MatrixContent& content(SUNMatrix a);
SolverContent& solver_content(SUNLinearSolver s);

/// A SUNMatrix of type SUNMATRIX_CUSTOM owning `c`.
SUNMatrix make_custom_matrix(SUNContext ctx, std::unique_ptr<MatrixContent> c);
/// The `free` op of a SUNLinearSolver made by SUNLinSolNewEmpty whose content is a `Content` it owns.
template <class Content>
int free_owned_content(SUNLinearSolver ls) {
  if (!ls) return 0;
  delete static_cast<Content*>(ls->content);
  ls->content = nullptr;
  SUNLinSolFreeEmpty(ls);
  return 0;
}

/// A direct SUNLinearSolver of type SUNLINEARSOLVER_CUSTOM owning `c`.
SUNLinearSolver make_custom_solver(SUNContext ctx, std::unique_ptr<SolverContent> c);

}  // namespace raceway::numerics::backend
