#include "scheduler/cost_model.hpp"

#include <algorithm>

#include "scheduler/plan.hpp"

namespace raceway::scheduler {

EvaluationBalance evaluation_balance(std::span<const double> busy, std::span<const double> capacity) {
  EvaluationBalance b;
  double cap_sum = 0;
  for (std::size_t r = 0; r < busy.size(); ++r) {
    b.total += busy[r];
    if (capacity[r] <= 0) continue;
    cap_sum += capacity[r];
    b.worst = std::max(b.worst, busy[r] / capacity[r]);
  }
  b.mean = b.total / cap_sum;
  b.imbalance = b.total > 0 ? b.worst / b.mean : 1.0;
  return b;
}

void CostModel::measure(int phase, std::span<const double> seconds, double imbalance) {
  auto& cost = cost_[phase];
  if (cost.empty())
    cost.assign(seconds.begin(), seconds.end());
  else
    for (std::size_t t = 0; t < cost.size(); ++t)
      cost[t] += smoothing * (std::min(seconds[t], outlier_factor * cost[t] + 1e-9) - cost[t]);
  if (phase != static_cast<int>(Phase::rhs) && !cost_[static_cast<int>(Phase::rhs)].empty()) {
    // Per task, this phase's cost relative to the right-hand side's at the same time: about the
    // number of segment evaluations per task, steady while the costs themselves move.
    const auto& rhs = cost_[static_cast<int>(Phase::rhs)];
    auto& ratio = ratio_[phase];
    const bool first = ratio.empty();
    ratio.resize(rhs.size());
    for (std::size_t t = 0; t < rhs.size(); ++t) {
      const double r = seconds[t] / std::max(rhs[t], 1e-9);
      ratio[t] = first ? r : ratio[t] + smoothing * (std::min(r, outlier_factor * ratio[t]) - ratio[t]);
    }
  }
  imbalance_[phase] = evaluations_[phase] == 0 ? imbalance
                                               : imbalance_[phase] + imbalance_smoothing * (imbalance - imbalance_[phase]);
  ++evaluations_[phase];
}

void CostModel::measure_plan_seconds(int phase, double seconds) {
  double& s = plan_seconds_[phase];
  s = plans_[phase]++ == 0 ? seconds : s + smoothing * (std::min(seconds, outlier_factor * s) - s);
}

bool CostModel::follows_rhs(int phase) const {
  const auto& rhs = cost_[static_cast<int>(Phase::rhs)];
  return phase != static_cast<int>(Phase::rhs) && !ratio_[phase].empty() && rhs.size() == ratio_[phase].size();
}

std::vector<double> CostModel::model(int phase) const {
  const bool rhs_based = follows_rhs(phase);
  const auto& base = rhs_based ? cost_[static_cast<int>(Phase::rhs)] : cost_[phase];
  std::vector<double> c(base.size());
  for (std::size_t t = 0; t < c.size(); ++t) c[t] = rhs_based ? base[t] * ratio_[phase][t] : base[t];
  return c;
}

double CostModel::current_imbalance(int phase, const std::vector<std::vector<int>>& lists,
                                    std::span<const double> capacity) const {
  const bool rhs_based = follows_rhs(phase);
  const auto& base = rhs_based ? cost_[static_cast<int>(Phase::rhs)] : cost_[phase];
  if (base.empty()) return 1.0;
  const auto cost = [&](std::size_t t) { return rhs_based ? base[t] * ratio_[phase][t] : base[t]; };
  // Per rank its fixed list (with a tail) or its whole share of the plan: without a tail the
  // slowest rank is at or above the mean, and this is predicted_imbalance.
  double total = 0;
  for (std::size_t t = 0; t < base.size(); ++t) total += cost(t);
  std::vector<double> fixed_load(capacity.size(), 0.0);
  for (std::size_t r = 0; r < capacity.size(); ++r)
    for (const int t : lists[r]) fixed_load[r] += cost(static_cast<std::size_t>(t));
  return imbalance_with_tail_filling(fixed_load, total, capacity);
}

}  // namespace raceway::scheduler
