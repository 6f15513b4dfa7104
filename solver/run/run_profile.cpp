#include "solver/run/run_profile.hpp"

#include <algorithm>
#include <map>

namespace raceway::run {

namespace {

/// "roller[3].vx" -> "roller.vx": the body's index dropped.
std::string class_of(const std::string& state_name) {
  const auto open = state_name.find('[');
  const auto close = state_name.find(']');
  if (open == std::string::npos || close == std::string::npos || close < open) return state_name;
  return state_name.substr(0, open) + state_name.substr(close + 1);
}

}  // namespace

std::vector<StateClassShare> step_limiting_classes(const bearing::Model& model, const numerics::StepLimitingStates& limiting) {
  std::map<std::string, StateClassShare> by_name;
  std::map<std::string, int> members;
  const double steps = static_cast<double>(std::max(1L, limiting.steps));
  for (std::size_t i = 0; i < limiting.share_sum.size() && i < model.state_name.size(); ++i) {
    const std::string name = class_of(model.state_name[i]);
    StateClassShare& c = by_name[name];
    c.name = name;
    c.error_share += limiting.share_sum[i] / steps;
    c.largest_fraction += static_cast<double>(limiting.largest[i]) / steps;
    c.mean_weighted_error += limiting.weighted_error_sum[i] / steps;
    ++members[name];
  }
  std::vector<StateClassShare> out;
  for (auto& [name, c] : by_name) {
    c.mean_weighted_error /= members[name];
    out.push_back(c);
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const StateClassShare& a, const StateClassShare& b) { return a.error_share > b.error_share; });
  return out;
}

json::JsonObject step_limiting_json(const std::vector<StateClassShare>& classes) {
  json::JsonObject j;
  for (const StateClassShare& c : classes) {
    json::JsonObject k;
    k.add("error_share", c.error_share);
    k.add("largest_fraction", c.largest_fraction);
    k.add("mean_weighted_error", c.mean_weighted_error);
    j.add(c.name, std::move(k));
  }
  return j;
}

json::JsonObject time_split_json(const numerics::IntegratorTiming& timing, double output_seconds, double wall_seconds) {
  json::JsonObject j;
  j.add("rhs", timing.rhs);
  j.add("jacobian", timing.jacobian);
  j.add("linear_setup", timing.linear_setup);
  j.add("linear_solve", timing.linear_solve);
  j.add("integrator", timing.integrator());
  j.add("accounting", timing.accounting);
  j.add("output", output_seconds);
  j.add("other", wall_seconds - timing.total - output_seconds);
  return j;
}

}  // namespace raceway::run
