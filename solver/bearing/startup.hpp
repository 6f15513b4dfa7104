// A consistent initial state (issue 2, item 9): rollers and cage at their epicyclic speeds and the
// rollers seated under the load, so the start-up transient is short.
#pragma once

#include <string>
#include <vector>

#include "solver/bearing/model.hpp"

namespace raceway::solver {

struct StartupReport {
  std::vector<double> state;
  int newton_iterations = 0;
  double residual = 0;       ///< N, largest unbalanced ring force at the solution
  std::string summary;
};

/// Quasi-static seating at t0: ring centres moved until the roller contact forces balance the
/// loads (each roller's radial position balancing its inner and outer contact and its centrifugal
/// force at the epicyclic orbital speed), then velocities set to pure rolling.
/// Throws std::runtime_error when no equilibrium is found.
StartupReport consistent_initial_state(const Model& model, double t0);

}  // namespace raceway::solver
