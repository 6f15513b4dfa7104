// Internal to solver/numerics: a SUNLinearSolver that forwards every call to another one and adds
// the wall time of its setups and solves to two counters, so the integrator can say how much of a
// step the Newton linear algebra costs whichever backend runs. SUNDIALS has no such hook; the
// wrapper changes no number (the same calls in the same order reach the backend).
#pragma once

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

namespace raceway::numerics::backend {

/// A wrapper around `inner` (not owned: the caller frees `inner` after the wrapper). Adds seconds to
/// *setup_seconds and *solve_seconds, which must outlive it.
SUNLinearSolver make_timed_solver(SUNContext ctx, SUNLinearSolver inner, double* setup_seconds,
                                  double* solve_seconds);

}  // namespace raceway::numerics::backend
