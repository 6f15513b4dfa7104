#include "solver/numerics/sundials_custom.hpp"

#include <sundials/sundials_nvector.h>

#include <exception>

namespace raceway::numerics::backend {

MatrixContent& content(SUNMatrix a) { return *static_cast<MatrixContent*>(a->content); }
SolverContent& solver_content(SUNLinearSolver s) { return *static_cast<SolverContent*>(s->content); }

namespace {

// The matrix ops CVODE calls return a negative flag (unrecoverable) on an exception, for example a
// PETSc error; the PETSc runtime keeps its message.
template <class F>
int guarded(F&& f) {
  try {
    f();
    return 0;
  } catch (...) {
    return -1;
  }
}

// The linear-solver ops keep the flag they return, and an exception's message.
template <class F>
int flagged(SolverContent& c, F&& f) {
  try {
    c.last_flag = f();
  } catch (const std::exception& e) {
    c.last_error = e.what();
    c.last_flag = SUNLS_PACKAGE_FAIL_UNREC;
  }
  return static_cast<int>(c.last_flag);
}

}  // namespace

SUNMatrix make_custom_matrix(SUNContext ctx, std::unique_ptr<MatrixContent> matrix_object) {
  SUNMatrix a = SUNMatNewEmpty(ctx);
  SUNMatrix_Ops ops = a->ops;
  ops->getid = [](SUNMatrix) { return SUNMATRIX_CUSTOM; };
  ops->clone = [](SUNMatrix m) -> SUNMatrix {
    try {
      return make_custom_matrix(m->sunctx, content(m).clone());
    } catch (...) {
      return nullptr;
    }
  };
  ops->destroy = [](SUNMatrix m) {
    if (!m) return;
    delete static_cast<MatrixContent*>(m->content);
    m->content = nullptr;
    SUNMatFreeEmpty(m);
  };
  ops->zero = [](SUNMatrix m) { return guarded([&] { content(m).zero(); }); };
  ops->copy = [](SUNMatrix from, SUNMatrix to) { return guarded([&] { content(from).copy_to(content(to)); }); };
  ops->scaleaddi = [](sunrealtype c, SUNMatrix m) { return guarded([&] { content(m).scale_add_identity(c); }); };
  ops->matvec = [](SUNMatrix m, N_Vector x, N_Vector y) {
    return guarded([&] { content(m).multiply(N_VGetArrayPointer(x), N_VGetArrayPointer(y)); });
  };
  a->content = matrix_object.release();
  return a;
}

SUNLinearSolver make_custom_solver(SUNContext ctx, std::unique_ptr<SolverContent> solver_object) {
  SUNLinearSolver s = SUNLinSolNewEmpty(ctx);
  SUNLinearSolver_Ops ops = s->ops;
  ops->gettype = [](SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; };
  ops->getid = [](SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; };
  ops->initialize = [](SUNLinearSolver) { return 0; };
  ops->setup = [](SUNLinearSolver ls, SUNMatrix a) {
    SolverContent& sc = solver_content(ls);
    return flagged(sc, [&] { return sc.setup(a); });
  };
  ops->solve = [](SUNLinearSolver ls, SUNMatrix, N_Vector x, N_Vector b, sunrealtype) {
    SolverContent& sc = solver_content(ls);
    return flagged(sc, [&] { return sc.solve(N_VGetArrayPointer(b), N_VGetArrayPointer(x)); });
  };
  ops->lastflag = [](SUNLinearSolver ls) { return solver_content(ls).last_flag; };
  ops->free = free_owned_content<SolverContent>;
  s->content = solver_object.release();
  return s;
}

}  // namespace raceway::numerics::backend
