// Time integration with CVODE: BDF (or Adams) with Newton iteration, tolerances per variable class,
// and the Newton solve through one of the backends of solver/numerics/newton_backends.hpp (PETSc
// bordered, hand-written block elimination, SUNDIALS dense baseline). CVODE sees a state vector, a
// right-hand side, a Jacobian and a linear solve, through the seam of
// solver/numerics/dynamic_system.hpp; it knows nothing of rollers.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/scene/scene.hpp"
#include "solver/numerics/dynamic_system.hpp"
#include "solver/numerics/newton_backends.hpp"

namespace raceway::solver {

struct IntegratorStatistics {
  long steps = 0;
  long rhs_evaluations = 0;        ///< by CVODE (Newton iterations and output)
  long jacobian_evaluations = 0;
  long linear_setups = 0;
  long newton_iterations = 0;
  long newton_failures = 0;        ///< nonlinear convergence failures
  long error_test_failures = 0;
  int last_order = 0;
  double last_step = 0;            ///< s
};

/// A failed integration, with its diagnosis (time, step size, which state and which contact).
class IntegrationFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Integrator {
 public:
  Integrator(DynamicSystem& equations, const io::SolverSpec& spec, double t0, const std::vector<double>& z0);
  ~Integrator();
  Integrator(const Integrator&) = delete;
  Integrator& operator=(const Integrator&) = delete;

  /// Integrates to t_out and returns the state there, interpolated (not at a solver step).
  /// Throws IntegrationFailure with a diagnosis.
  void advance_to(double t_out, std::vector<double>& z);
  IntegratorStatistics statistics() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace raceway::solver
