#include "solver/driver/campaign_plan.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

namespace raceway::driver {

namespace {

// The fit of perf/calibration/campaign_cost_model.py to the QJ215 speed sweep (docs/campaigns/qj215_speed: 8
// scenes, 1000..8000 r/min, 20 revolutions each, one rank; perf/calibration/results/campaign_cost_model.txt).
constexpr double kReferenceRpm = 1000;
constexpr double kStepsPerRevolutionAtReference = 6.17e3;  // steps per revolution at 1000 r/min
constexpr double kStepsPerRevolutionExponent = -0.905;     // ~ 1 / speed: steps follow the simulated time
constexpr double kWallPerStepAtReference = 4.21e-4;        // s per step at 1000 r/min, 15 balls
constexpr double kWallPerStepExponent = 0.541;
constexpr double kReferenceElements = 15;  // QJ215

/// The makespan of the costs, longest first, each on the group free first.
double makespan(std::vector<double> costs, int groups) {
  std::sort(costs.begin(), costs.end(), std::greater<>());
  std::vector<double> busy(static_cast<std::size_t>(std::max(groups, 1)), 0.0);
  for (const double c : costs) *std::min_element(busy.begin(), busy.end()) += c;
  return *std::max_element(busy.begin(), busy.end());
}

}  // namespace

SceneCost predict_scene_cost(double revolutions, double speed_rpm, int rolling_elements) {
  // A ring at rest still takes steps: below 1 r/min the speed of 1 r/min is taken.
  const double x = std::max(std::abs(speed_rpm), 1.0) / kReferenceRpm;
  SceneCost cost;
  cost.steps = std::max(revolutions, 0.0) * kStepsPerRevolutionAtReference * std::pow(x, kStepsPerRevolutionExponent);
  cost.wall_seconds = cost.steps * kWallPerStepAtReference * std::pow(x, kWallPerStepExponent) *
                      std::max(rolling_elements, 1) / kReferenceElements;
  return cost;
}

GroupSizeChoice choose_group_size(int world_size, const std::vector<double>& costs, const SpeedupPrediction& speedup) {
  GroupSizeChoice choice;
  const double serial = makespan(costs, world_size);
  double best = INFINITY;
  std::vector<int> unknown;
  for (int g = 1; g <= std::max(world_size, 1); ++g) {
    const double s = g == 1 ? 1.0 : speedup(g);
    const int groups = std::max(world_size, 1) / g;
    if (!(s > 0) || !std::isfinite(s)) {
      unknown.push_back(g);
      continue;
    }
    std::vector<double> scaled(costs);
    for (double& c : scaled) c /= s;
    const double span = makespan(scaled, groups);
    const double at_once = static_cast<double>(std::min<std::size_t>(costs.size(), static_cast<std::size_t>(groups)));
    choice.reasons.push_back(fmt::format(
        "{} ranks per scene: {} groups, speed-up {:.2f} (efficiency {:.2f}), {} scenes at once x speed-up = {:.2f}, "
        "predicted campaign {:.3g} of the 1-rank-per-scene one", g, groups, s, s / g, at_once, at_once * s,
        serial > 0 ? span / serial : 1.0));
    if (span < best * (1 - 1e-9)) best = span, choice.ranks_per_group = g;
  }
  if (!unknown.empty())
    choice.reasons.push_back(fmt::format("ranks per scene without a predicted speed-up, not considered: {}",
                                         fmt::join(unknown, ", ")));
  choice.reasons.push_back(fmt::format(
      "chosen: {} ranks per scene, the shortest predicted campaign ({} scenes on {} ranks){}", choice.ranks_per_group,
      costs.size(), world_size,
      choice.ranks_per_group == 1 ? "" : ": the scenes are too few, or too unequal, to keep every rank busy alone"));
  return choice;
}

}  // namespace raceway::driver
