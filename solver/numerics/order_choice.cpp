#include "solver/numerics/order_choice.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace raceway::numerics {

OrderChoice::OrderChoice(double t0, OrderChoiceSettings settings)
    : settings_(settings), current_(settings.high_order), gap_(settings.first_probe), last_t_(t0), window_t_(t0) {}

double OrderChoice::rate_since(double t0, double cost0) const {
  return cost_ > cost0 ? (last_t_ - t0) / (cost_ - cost0) : 0.0;
}

int OrderChoice::after_step(double t, long rhs, long jacobians) {
  if (order() == settings_.low_order) time_low_ += t - last_t_;
  last_t_ = t;
  cost_ += static_cast<double>(rhs) + settings_.jacobian_cost * static_cast<double>(jacobians);
  ++steps_in_phase_;
  if (phase_ == Phase::run)
    run_step(cost_);
  else
    probe_step(t, cost_);
  return order();
}

// At the current order: after `settle` steps, windows of `window` steps, each one's rate kept;
// once `gap_` steps have passed (and a window is complete) the other order is probed.
void OrderChoice::run_step(double cost) {
  const long measured = steps_in_phase_ - settings_.settle;
  if (measured == 0) window_t_ = last_t_, window_cost_ = cost;
  if (measured > 0 && measured % settings_.window == 0) {
    current_rate_ = rate_since(window_t_, window_cost_);
    window_t_ = last_t_, window_cost_ = cost;
  }
  if (steps_in_phase_ >= gap_ && current_rate_ > 0) {
    phase_ = Phase::probe_settle;
    steps_in_phase_ = 0;
    ++probes_;
  }
}

// At the other order: `settle` steps, then one window; its rate against the current order's.
void OrderChoice::probe_step(double t, double cost) {
  if (phase_ == Phase::probe_settle) {
    if (steps_in_phase_ < settings_.settle) return;
    phase_ = Phase::probe_measure;
    steps_in_phase_ = 0;
    window_t_ = t, window_cost_ = cost;
    return;
  }
  if (steps_in_phase_ < settings_.window) return;
  const double probe_rate = rate_since(window_t_, window_cost_);
  if (probe_rate > settings_.gain * current_rate_) {
    pending_.push_back({t, other(), current_rate_, probe_rate});
    current_ = other();
    ++switches_;
    last_switch_time_ = t;
    gap_ = settings_.first_probe;
  } else {
    gap_ = std::min(2 * gap_, settings_.longest_gap);
  }
  phase_ = Phase::run;
  steps_in_phase_ = 0;
  current_rate_ = 0;
}

std::vector<OrderSwitch> OrderChoice::take_switches() {
  std::vector<OrderSwitch> out;
  out.swap(pending_);
  return out;
}

std::string OrderChoice::description() const {
  return fmt::format("BDF order at most {} since t = {:.6g} s ({} switches after {} probes of the other order; "
                     "{:.6g} s at order at most {})",
                     current_, last_switch_time_, switches_, probes_, time_low_, settings_.low_order);
}

namespace {
constexpr const char* kPrefix = "order_choice.";
}

void OrderChoice::save(std::map<std::string, double>& values) const {
  const auto put = [&](const char* name, double v) { values[std::string(kPrefix) + name] = v; };
  put("phase", static_cast<double>(phase_));
  put("current", current_);
  put("steps_in_phase", static_cast<double>(steps_in_phase_));
  put("gap", static_cast<double>(gap_));
  put("last_t", last_t_);
  put("cost", cost_);
  put("window_t", window_t_);
  put("window_cost", window_cost_);
  put("current_rate", current_rate_);
  put("probes", static_cast<double>(probes_));
  put("switches", static_cast<double>(switches_));
  put("time_low", time_low_);
  put("last_switch_time", last_switch_time_);
}

void OrderChoice::restore(const std::map<std::string, double>& values) {
  const auto get = [&](const char* name) {
    const auto it = values.find(std::string(kPrefix) + name);
    return it == values.end() ? 0.0 : it->second;
  };
  if (values.find(std::string(kPrefix) + "current") == values.end()) return;  // a run without the choice
  phase_ = static_cast<Phase>(static_cast<int>(get("phase")));
  current_ = static_cast<int>(get("current"));
  steps_in_phase_ = static_cast<long>(get("steps_in_phase"));
  gap_ = static_cast<long>(get("gap"));
  last_t_ = get("last_t");
  cost_ = get("cost");
  window_t_ = get("window_t");
  window_cost_ = get("window_cost");
  current_rate_ = get("current_rate");
  probes_ = static_cast<long>(get("probes"));
  switches_ = static_cast<long>(get("switches"));
  time_low_ = get("time_low");
  last_switch_time_ = get("last_switch_time");
}

}  // namespace raceway::numerics
