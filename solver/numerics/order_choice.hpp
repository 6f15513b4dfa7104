// The automatic choice of BDF's largest order ([solver] automatic_order): orders 3 to 5 are not
// A-stable, and where a lightly damped fast mode sits near the imaginary axis (a light roller's
// contact vibration) they hold the step at their stability limit, far below what the error test
// would allow; BDF2 (A-stable) then takes tens of times fewer steps. Elsewhere (contact onsets,
// rattling) the high orders are the cheaper ones. Which regime a run is in is measured, not
// guessed: the run steps at one order, and from time to time probes the other one for a few
// steps; the order that advances the time further per unit of work wins (docs/integration_methods.md,
// "Automatic order").
//
// A deterministic function of the accepted steps' times and counts (no wall time), so the same on
// every rank count; its whole state goes into a checkpoint (values()/restore()), so a resumed run
// continues the same choices.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace raceway::numerics {

struct OrderChoiceSettings {
  int high_order = 5;   ///< the scene's max_order
  int low_order = 2;    ///< A-stable BDF2
  long settle = 50;     ///< steps after a change of order before its windows are measured
  /// Steps of a probe of the low order before it is measured: the restart's transient, the damping
  /// of what the high order kept alive. A probe of the high order is measured from its first step.
  long probe_settle = 100;
  long window = 100;    ///< steps per window of the current order (a probe covers the last one's time span)
  long first_probe = 200;    ///< steps at the high order before the first probe of the low one
  /// The gap between probes doubles after each probe, won or lost, up to this: a run of N steps
  /// makes about log2(N / first_probe) probes, and settles on the order its regime wants.
  long longest_gap = 1L << 40;
  /// The probed order is taken when it covers the current order's last window for this many times
  /// less work.
  double gain = 1.5;
  /// Work of one Jacobian in right-hand sides (its forward differences: one contact evaluation per
  /// perturbed column, about ten per contact).
  double jacobian_cost = 10;
};

/// One change of the order in force: a probe's result that moved the run to the other order.
struct OrderSwitch {
  double time = 0;             ///< s
  int to_order = 0;
  double current_rate = 0;     ///< s of simulated time per unit of work at the order left
  double probe_rate = 0;       ///< the same at the order taken
};

class OrderChoice {
 public:
  /// A choice that starts at `t0` at the high order.
  explicit OrderChoice(double t0, OrderChoiceSettings settings = {});

  /// The largest order the next step may use.
  int order() const { return phase_ == Phase::run ? current_ : other(); }
  /// After an accepted step that ended at t and cost `rhs` right-hand sides and `jacobians`
  /// Jacobians (since the previous step): the largest order for the next step.
  int after_step(double t, long rhs, long jacobians);

  int current_order() const { return current_; }
  long probes() const { return probes_; }
  long switches() const { return switches_; }
  double time_at_low_order() const { return time_low_; }  ///< s
  double last_time() const { return last_t_; }
  /// The changes of order since the last call (for the log).
  std::vector<OrderSwitch> take_switches();
  /// A line for the log and the summary: "order 2 since t = ...: 1 switch, 3 probes, ...".
  std::string description() const;

  /// Into a checkpoint's values (names prefixed "order_choice."), and back.
  void save(std::map<std::string, double>& values) const;
  void restore(const std::map<std::string, double>& values);

 private:
  enum class Phase { run, probe };
  int other() const { return current_ == settings_.high_order ? settings_.low_order : settings_.high_order; }
  void run_step(double cost);
  void probe_step(double t, double cost);

  OrderChoiceSettings settings_;
  Phase phase_ = Phase::run;
  int current_;
  long steps_in_phase_ = 0;   // accepted steps since the phase began
  long gap_;                  // steps at the current order before the next probe
  double last_t_ = 0, cost_ = 0;            // the last step's end; work so far (rhs units)
  double window_t_ = 0, window_cost_ = 0;   // where the window being measured began
  double reference_span_ = 0, reference_cost_ = 0;  // the current order's last complete window; 0: none yet
  long probes_ = 0, switches_ = 0;
  double time_low_ = 0, last_switch_time_ = 0;
  std::vector<OrderSwitch> pending_;
};

}  // namespace raceway::numerics
