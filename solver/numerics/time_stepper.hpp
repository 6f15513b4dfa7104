// Internal to solver/numerics: the time steppers behind Integrator (integrator.hpp). Each wraps one
// SUNDIALS integrator (CVODE's BDF and Adams, ARKODE's ERKStep and ARKStep) behind the few calls the
// integrator makes: one internal step, interpolation inside the last step, the error estimate of the
// last step and the counters. The integrator itself owns the state vector, the callbacks, the step
// budget, the diagnosis and the step-limiting-state accounting, once for every method.
#pragma once

#include <sundials/sundials_context.h>
#include <sundials/sundials_nvector.h>

#include <memory>
#include <string>

#include "io/scene/scene.hpp"
#include "solver/numerics/integrator.hpp"
#include "solver/numerics/newton_backends.hpp"

namespace raceway::numerics::stepping {

/// The integrator's callbacks, in the signatures CVODE and ARKODE share (CVRhsFn = ARKRhsFn,
/// CVLsJacFn = ARKLsJacFn, CVErrHandlerFn = ARKErrHandlerFn).
struct Callbacks {
  int (*rhs)(sunrealtype t, N_Vector y, N_Vector ydot, void* user) = nullptr;
  int (*jacobian)(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix j, void* user, N_Vector, N_Vector,
                  N_Vector) = nullptr;
  void (*error_handler)(int code, const char* module, const char* function, char* msg, void* user) = nullptr;
  /// The error weights (CVEwtFn = ARKEwtFn); null: SUNDIALS' own from rtol and atol.
  int (*error_weights)(N_Vector y, N_Vector ewt, void* user) = nullptr;
  void* user = nullptr;
};

/// What a stepper is made from. `linear` and `linear_solver` are used by the implicit methods (bdf,
/// adams, ark) only.
struct StepperSetup {
  const scene::SolverSpec& spec;
  SUNContext ctx;
  N_Vector y0;     ///< initial state (also the template vector)
  double t0;
  N_Vector atol;   ///< absolute tolerance per state
  Callbacks callbacks;
  NewtonLinearSystem* linear;     ///< its matrix
  SUNLinearSolver linear_solver;  ///< its solver (wrapped for timing)
};

class TimeStepper {
 public:
  virtual ~TimeStepper() = default;
  /// One internal step towards t_out (the first one also estimates the initial step from t_out).
  /// Returns the SUNDIALS flag (negative: failure); `t_reached` is the time of the new step.
  virtual int step(double t_out, N_Vector y, double& t_reached) = 0;
  /// y(t) from the interpolant of the last step (t within it); derivative 1: dy/dt of it.
  virtual int interpolate(double t, N_Vector y, int derivative = 0) = 0;
  /// The next steps stop at t_stop (a step that would pass it ends there).
  virtual int stop_at(double t_stop) = 0;
  /// The time the integration has reached (the last step's end).
  virtual double time() const = 0;
  /// The last step's estimated local error and the error weights it was tested with; false if the
  /// integrator cannot give them yet.
  virtual bool local_errors(N_Vector error, N_Vector weights) const = 0;
  virtual IntegratorStatistics statistics() const = 0;
  /// BDF, Adams: the largest order of the next steps. A lower bound than the order in use restarts
  /// the method at the last step's end (its state into `y`; order 1, its first step the last step's size:
  /// CVODE lowers its order only one at a time); returns true when it restarted (the counters then
  /// start again from 0). Not for the Runge-Kutta methods (throws).
  virtual bool set_max_order(int order, N_Vector y) = 0;
  virtual double attempted_step() const = 0;
  /// SUNDIALS' name of a return flag ("CV_ERR_FAILURE", "ARK_TOO_MUCH_WORK").
  virtual std::string flag_name(int flag) const = 0;
  /// A short name of the method ("CVODE BDF", "ARKODE ERK Dormand-Prince 5(4)").
  virtual std::string method_name() const = 0;
};

std::unique_ptr<TimeStepper> make_cvode_stepper(const StepperSetup& setup);
std::unique_ptr<TimeStepper> make_arkode_stepper(const StepperSetup& setup);

/// Throws std::runtime_error naming the call when a SUNDIALS set-up call returned a negative flag.
void check(int flag, const char* what);

}  // namespace raceway::numerics::stepping
