// Where a run's steps and time go, for its summary: which classes of state limit the step (from the
// integrator's per-state error accounting, grouped by body kind and coordinate, "roller.vx" for
// every roller's vx) and the split of the wall time (right-hand side, Jacobian, linear setup and
// solve, the integrator's own work, output).
#pragma once

#include <string>
#include <vector>

#include "io/json/summary_json.hpp"
#include "solver/bearing/model.hpp"
#include "solver/numerics/integrator.hpp"

namespace raceway::run {

/// One class of states: the states of one coordinate of every body of a kind.
struct StateClassShare {
  std::string name;             ///< "roller.vx", "cage.omega", "inner_ring.x"
  double error_share = 0;       ///< mean over steps of the class's share of the squared WRMS local error
  double largest_fraction = 0;  ///< fraction of the steps in which a state of the class had the largest error
  double mean_weighted_error = 0;  ///< mean over steps and over the class's states of |w e| (1: at the error test's limit)
};

/// The classes of `limiting` (per state, integrator.hpp) by error share, largest first.
std::vector<StateClassShare> step_limiting_classes(const bearing::Model& model, const numerics::StepLimitingStates& limiting);

/// {"roller.vx": {"error_share": .., "largest_fraction": .., "mean_weighted_error": ..}, ...}
json::JsonObject step_limiting_json(const std::vector<StateClassShare>& classes);

/// Seconds by part: rhs, jacobian, linear_setup, linear_solve, integrator, accounting, output, and
/// other (start-up, output file, what no timer covers) = wall - the rest.
json::JsonObject time_split_json(const numerics::IntegratorTiming& timing, double output_seconds, double wall_seconds);

}  // namespace raceway::run
