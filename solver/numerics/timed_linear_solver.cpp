#include "solver/numerics/timed_linear_solver.hpp"

#include <chrono>

#include "solver/numerics/sundials_custom.hpp"

namespace raceway::numerics::backend {

namespace {

struct TimedContent {
  SUNLinearSolver inner;
  double* setup_seconds;
  double* solve_seconds;
};

TimedContent& timed(SUNLinearSolver s) { return *static_cast<TimedContent*>(s->content); }

template <class F>
int timed_call(double* seconds, F&& f) {
  const auto start = std::chrono::steady_clock::now();
  const int flag = f();
  *seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return flag;
}

}  // namespace

SUNLinearSolver make_timed_solver(SUNContext ctx, SUNLinearSolver inner, double* setup_seconds,
                                  double* solve_seconds) {
  SUNLinearSolver s = SUNLinSolNewEmpty(ctx);
  SUNLinearSolver_Ops ops = s->ops;
  ops->gettype = [](SUNLinearSolver ls) { return SUNLinSolGetType(timed(ls).inner); };
  ops->getid = [](SUNLinearSolver ls) { return SUNLinSolGetID(timed(ls).inner); };
  ops->initialize = [](SUNLinearSolver ls) { return SUNLinSolInitialize(timed(ls).inner); };
  ops->setup = [](SUNLinearSolver ls, SUNMatrix a) {
    TimedContent& c = timed(ls);
    return timed_call(c.setup_seconds, [&] { return SUNLinSolSetup(c.inner, a); });
  };
  ops->solve = [](SUNLinearSolver ls, SUNMatrix a, N_Vector x, N_Vector b, sunrealtype tol) {
    TimedContent& c = timed(ls);
    return timed_call(c.solve_seconds, [&] { return SUNLinSolSolve(c.inner, a, x, b, tol); });
  };
  ops->lastflag = [](SUNLinearSolver ls) { return SUNLinSolLastFlag(timed(ls).inner); };
  ops->free = free_owned_content<TimedContent>;
  s->content = new TimedContent{inner, setup_seconds, solve_seconds};
  return s;
}

}  // namespace raceway::numerics::backend
