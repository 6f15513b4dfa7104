// How a campaign uses its ranks (docs/campaigns.md), without MPI: each scene's predicted cost from
// the measured relation of integration steps to speed, and the size of the groups from the scene's
// predicted speed-up.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace raceway::driver {

/// A scene's predicted integration steps and one-rank wall time.
struct SceneCost {
  double steps = 0;
  double wall_seconds = 0;
};

/// The prediction for `revolutions` turns of the driven ring at `speed_rpm` (relative to the other
/// ring) of a bearing with `rolling_elements`: steps = revolutions x steps per revolution(speed),
/// wall = steps x wall per step(speed) x rolling_elements / 15, both power laws fitted to the QJ215
/// speed sweep (perf/calibration/campaign_cost_model.py, perf/calibration/results/campaign_cost_model.txt): the steps per
/// revolution fall with speed (the step size is set by the contacts' time scales, not by the
/// turning), the wall per step rises (more Newton work per step).
SceneCost predict_scene_cost(double revolutions, double speed_rpm, int rolling_elements);

/// A scene's predicted speed-up on P ranks against one rank; NaN when there is no prediction for P.
using SpeedupPrediction = std::function<double(int ranks)>;

struct GroupSizeChoice {
  int ranks_per_group = 1;
  std::vector<std::string> reasons;  ///< one line per candidate size, then the choice and why
};

/// The group size of `world_size` ranks for scenes of the given one-rank costs (any unit) that
/// gives the shortest predicted campaign: with g ranks per scene, world_size / g groups each run a
/// scene speedup(g) times faster, the scenes longest first on the first free group (the
/// dispatcher's order); sizes without a prediction are skipped, 1 always has one. Ties go to the
/// smaller group (the higher efficiency).
GroupSizeChoice choose_group_size(int world_size, const std::vector<double>& costs, const SpeedupPrediction& speedup);

}  // namespace raceway::driver
