// Time integration of a DynamicSystem: CVODE's BDF (stiff, orders 1-5, optional stability-limit
// detection) and Adams methods, ARKODE's explicit Runge-Kutta pairs (erk) and diagonally implicit
// Runge-Kutta methods (ark), chosen by the scene's [solver] method. Tolerances per variable class;
// the implicit methods solve their Newton systems through one of the backends of
// solver/numerics/newton_backends.hpp (PETSc bordered, hand-written block elimination, SUNDIALS
// dense baseline). The integrators see a state vector, a right-hand side, a Jacobian and a linear
// solve, through the seam of solver/numerics/dynamic_system.hpp; they know nothing of rollers.
//
// The integrator steps one internal step at a time and interpolates at the output times (what
// CVODE's normal mode does inside), so that after every accepted step it can record which states
// carry the error estimate that limits the step (StepLimitingStates).
#pragma once

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/scene/scene.hpp"
#include "solver/numerics/dynamic_system.hpp"
#include "solver/numerics/newton_backends.hpp"
#include "solver/numerics/order_choice.hpp"

namespace raceway::numerics {

struct IntegratorStatistics {
  long steps = 0;
  long rhs_evaluations = 0;        ///< by the integrator (Newton iterations, stages and output)
  long jacobian_evaluations = 0;
  long linear_setups = 0;
  long newton_iterations = 0;
  long newton_failures = 0;        ///< nonlinear convergence failures
  long error_test_failures = 0;
  long stability_order_reductions = 0;  ///< bdf with stability-limit detection: orders lowered by it
  int last_order = 0;              ///< bdf, adams: last order used; erk, ark: the pair's order
  double last_step = 0;            ///< s
};

/// Which states limit the step: over the accepted steps, each state's share of the squared weighted
/// RMS norm of the estimated local error (the quantity the error test compares with 1), and how often
/// it was the state with the largest weighted error. Per state, in state order.
struct StepLimitingStates {
  long steps = 0;                      ///< accepted steps recorded
  std::vector<double> share_sum;       ///< sum over steps of (w_i e_i)^2 / sum_j (w_j e_j)^2
  std::vector<long> largest;           ///< steps in which state i had the largest |w_i e_i|
  std::vector<double> weighted_error_sum;  ///< sum over steps of |w_i e_i| (mean = / steps)
};

/// Where the integrator's time goes (wall seconds, on the integrating rank).
struct IntegratorTiming {
  double total = 0;          ///< inside advance_to: steps, interpolation and the accounting
  double rhs = 0;            ///< right-hand sides called by the integrator
  double jacobian = 0;       ///< Jacobians, including loading them into the backend's matrix
  double linear_setup = 0;   ///< factorisations of I - gamma J (includes forming it)
  double linear_solve = 0;   ///< solves with them
  double accounting = 0;     ///< the step-limiting-state accounting
  /// What is left: the integrator's own work (predictor, error test, step and order selection,
  /// Newton updates, interpolation).
  double integrator() const { return total - rhs - jacobian - linear_setup - linear_solve - accounting; }
};

/// A failed integration, with its diagnosis (time, step size, which state and which contact).
class IntegrationFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Integrator {
 public:
  Integrator(DynamicSystem& equations, const scene::SolverSpec& spec, double t0, const std::vector<double>& z0);
  ~Integrator();
  Integrator(const Integrator&) = delete;
  Integrator& operator=(const Integrator&) = delete;

  /// Integrates to t_out and returns the state there, interpolated (not at a solver step).
  /// Throws IntegrationFailure with a diagnosis.
  void advance_to(double t_out, std::vector<double>& z);
  /// The time the integration has reached (the last step's end).
  double time() const;
  /// The last step's interpolant at t (within that step, e.g. from a step observer): the state
  /// (derivative 0) or its time derivative (1), into out.
  void interpolate(double t, int derivative, std::vector<double>& out);
  /// Called after every accepted step, on the integrating thread, before the next one: the
  /// system's last right-hand side is then the step's own (a BDF step's last Newton iterate at the
  /// step's time, a Runge-Kutta step's last stage). Jacobians do not touch a system's rhs records;
  /// nothing is evaluated for the observer.
  void set_step_observer(std::function<void()> observer);
  /// BDF: the largest order follows `choice` (not owned; solver/numerics/order_choice.hpp), which
  /// sees every accepted step's time and work. Before the first step. Lowering the order below the
  /// one in use restarts CVODE at the last step (statistics() counts on across it).
  void set_order_choice(OrderChoice* choice);
  IntegratorStatistics statistics() const;
  const StepLimitingStates& step_limiting_states() const;
  const IntegratorTiming& timing() const;
  /// "CVODE BDF", "ARKODE ERKStep Dormand-Prince 5(4)", ...
  std::string method_name() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace raceway::numerics
