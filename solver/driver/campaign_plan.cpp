#include "solver/driver/campaign_plan.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iterator>
#include <numeric>

#include "solver/driver/data_files.hpp"
#include "solver/numerics/petsc_runtime.hpp"

namespace raceway::driver {

namespace {

using numerics::OptionsError;

constexpr const char* kCostModelColumns[] = {"reference_rpm", "reference_rolling_elements", "steps_per_revolution",
                                             "steps_per_revolution_exponent", "wall_per_step_s",
                                             "wall_per_step_exponent"};

/// The comma-separated fields of a line (the file is plain numbers and names: no quoting).
std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> out(1);
  for (const char c : line)
    if (c == ',') out.emplace_back();
    else if (c != '\r' && c != ' ') out.back() += c;
  return out;
}

/// The makespan of the costs, longest first, each on the group free first.
double makespan(std::vector<double> costs, int groups) {
  std::sort(costs.begin(), costs.end(), std::greater<>());
  std::vector<double> busy(static_cast<std::size_t>(std::max(groups, 1)), 0.0);
  for (const double c : costs) *std::min_element(busy.begin(), busy.end()) += c;
  return *std::max_element(busy.begin(), busy.end());
}

}  // namespace

CostModel read_cost_model(const std::string& path) {
  std::ifstream in(path);
  if (!in)
    throw OptionsError(fmt::format("{}: cannot read the campaign cost model (shipped in share/raceway/data beside the "
                                   "executable: reinstall; written by perf/calibration/campaign_cost_model.py "
                                   "--table)", path));
  std::vector<std::string> header;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    const auto f = fields_of(line);
    if (header.empty()) {
      header = f;
      if (!std::equal(std::begin(kCostModelColumns), std::end(kCostModelColumns), header.begin(), header.end()))
        throw OptionsError(fmt::format("{}:{}: expected the header {}", path, number, fmt::join(kCostModelColumns, ",")));
      continue;
    }
    std::vector<double> v;
    for (const auto& text : f) {
      char* end = nullptr;
      const double x = text.empty() ? NAN : std::strtod(text.c_str(), &end);
      v.push_back(end && *end == '\0' && std::isfinite(x) ? x : NAN);
    }
    if (v.size() != header.size() || !(v[0] > 0) || !(v[1] > 0) || !(v[2] > 0) || !(v[4] > 0) ||
        !std::isfinite(v[3]) || !std::isfinite(v[5]))
      throw OptionsError(fmt::format("{}:{}: expected six numbers (positive, the exponents finite), found '{}'", path,
                                     number, line));
    return {v[0], v[1], v[2], v[3], v[4], v[5]};
  }
  throw OptionsError(fmt::format("{}: no line of values after the header", path));
}

const CostModel& shipped_cost_model() {
  static const CostModel model = read_cost_model(data_file_path("campaign_cost_model.csv"));
  return model;
}

SceneCost predict_scene_cost(const CostModel& model, double revolutions, double speed_rpm, int rolling_elements) {
  // A ring at rest still takes steps: below 1 r/min the speed of 1 r/min is taken.
  const double x = std::max(std::abs(speed_rpm), 1.0) / model.reference_rpm;
  SceneCost cost;
  cost.steps = std::max(revolutions, 0.0) * model.steps_per_revolution * std::pow(x, model.steps_exponent);
  cost.wall_seconds = cost.steps * model.wall_per_step_s * std::pow(x, model.wall_exponent) *
                      std::max(rolling_elements, 1) / model.reference_elements;
  return cost;
}

SceneCost predict_scene_cost(double revolutions, double speed_rpm, int rolling_elements) {
  return predict_scene_cost(shipped_cost_model(), revolutions, speed_rpm, rolling_elements);
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
