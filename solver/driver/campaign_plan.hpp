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

/// The cost model's constants: two power laws of the speed n, fitted to a measured speed sweep,
///   steps per revolution = steps_per_revolution (n / reference_rpm)^steps_exponent
///   wall per step        = wall_per_step_s (n / reference_rpm)^wall_exponent x elements / reference_elements
/// The product ships them in data/campaign_cost_model.csv (share/raceway/data), written by
/// perf/calibration/campaign_cost_model.py --table.
struct CostModel {
  double reference_rpm = 0, reference_elements = 0;
  double steps_per_revolution = 0, steps_exponent = 0;
  double wall_per_step_s = 0, wall_exponent = 0;
};

/// The cost model in the CSV file at PATH (a header line naming the six constants, one line of
/// values; '#' lines are comments). Throws numerics::OptionsError naming the file, the line and what
/// is wrong (exit 2: before a campaign does anything).
CostModel read_cost_model(const std::string& path);

/// The shipped cost model: campaign_cost_model.csv of the data beside the executable
/// (solver/driver/data_files.hpp), read once.
const CostModel& shipped_cost_model();

/// The prediction for `revolutions` turns of the driven ring at `speed_rpm` (relative to the other
/// ring) of a bearing with `rolling_elements`: steps = revolutions x steps per revolution(speed),
/// wall = steps x wall per step(speed), MODEL's power laws (fitted to the QJ215 speed sweep:
/// perf/calibration/campaign_cost_model.py, perf/calibration/results/campaign_cost_model.txt): the
/// steps per revolution fall with speed (the step size is set by the contacts' time scales, not by
/// the turning), the wall per step rises (more Newton work per step).
SceneCost predict_scene_cost(const CostModel& model, double revolutions, double speed_rpm, int rolling_elements);

/// The same with the shipped model.
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
