#include "solver/numerics/order_choice.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace raceway::numerics {

OrderChoice::OrderChoice(double t0, OrderChoiceSettings settings)
    : settings_(settings), current_(settings.high_order), gap_(settings.first_probe), last_t_(t0), window_t_(t0) {}

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

// At the current order: after `settle` steps, windows of `window` steps, the last complete one
// kept (its time span and work); once `gap_` steps have passed (and a window is complete) the
// other order is probed.
void OrderChoice::run_step(double cost) {
  const long measured = steps_in_phase_ - settings_.settle;
  if (measured == 0) window_t_ = last_t_, window_cost_ = cost;
  if (measured > 0 && measured % settings_.window == 0) {
    reference_span_ = last_t_ - window_t_, reference_cost_ = cost - window_cost_;
    window_t_ = last_t_, window_cost_ = cost;
  }
  if (steps_in_phase_ >= gap_ && reference_cost_ > 0) {
    phase_ = Phase::probe;
    steps_in_phase_ = 0;
    window_t_ = last_t_, window_cost_ = cost;
    ++probes_;
  }
}

// At the other order, over the time span of the current order's last window: the probe wins when
// it covers that span for less than the window's work divided by the gain, and loses as soon as it
// has spent that much (so a probe never costs more than a window of the current order). The
// probe's work includes its start (a restart where the order is lowered), as a switch's would.
void OrderChoice::probe_step(double t, double cost) {
  if (other() == settings_.low_order && steps_in_phase_ <= settings_.probe_settle) {
    window_t_ = t, window_cost_ = cost;  // the probe's start is not measured
    return;
  }
  const double span = t - window_t_, spent = cost - window_cost_;
  const bool lost = spent * settings_.gain >= reference_cost_;
  if (!lost && span < reference_span_) return;
  if (!lost) {
    pending_.push_back({t, other(), reference_span_ / reference_cost_, span / spent});
    current_ = other();
    ++switches_;
    last_switch_time_ = t;
  }
  gap_ = std::min(2 * gap_, settings_.longest_gap);
  phase_ = Phase::run;
  steps_in_phase_ = 0;
  reference_span_ = reference_cost_ = 0;
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
  put("reference_span", reference_span_);
  put("reference_cost", reference_cost_);
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
  reference_span_ = get("reference_span");
  reference_cost_ = get("reference_cost");
  probes_ = static_cast<long>(get("probes"));
  switches_ = static_cast<long>(get("switches"));
  time_low_ = get("time_low");
  last_switch_time_ = get("last_switch_time");
}

}  // namespace raceway::numerics
