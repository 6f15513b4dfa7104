// The automatic BDF order (solver/numerics/order_choice.hpp):
//  - the choice alone, on step streams whose cost per simulated time is known: it takes the order
//    that advances the time further per unit of work, keeps the other, and a choice restored from
//    its saved values continues with the same decisions as the one that was not interrupted;
//  - with CVODE on a small linear system, a slow oscillation beside a fast real decay (every BDF
//    order is stable there): the run keeps order 5. (A linear fast oscillator does not hold order 5
//    at its stability limit the way the default scene's contacts do: it is excited too weakly, and
//    order 5 steps over the unstable band; tests/solver/run/order_choice_run_test.cpp runs the
//    default scene for that.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "solver/numerics/integrator.hpp"
#include "solver/numerics/order_choice.hpp"

namespace raceway::numerics {
namespace {

/// Feeds `steps` steps to `choice`, each advancing `dt_of(order)` for one right-hand side.
template <class Dt>
void feed(OrderChoice& choice, double& t, long steps, Dt dt_of) {
  for (long i = 0; i < steps; ++i) {
    t += dt_of(choice.order());
    choice.after_step(t, 1, 0);
  }
}

TEST(OrderChoice, TakesTheLowOrderWhereItCoversMoreTimePerWork) {
  OrderChoice choice(0.0);
  double t = 0;
  feed(choice, t, 2000, [](int order) { return order == 2 ? 1e-4 : 1e-6; });  // order 2: 100 times further
  EXPECT_EQ(choice.current_order(), 2);
  EXPECT_EQ(choice.switches(), 1);
  EXPECT_GE(choice.probes(), 2);  // it probed order 5 again after the switch, and kept order 2
  EXPECT_GT(choice.time_at_low_order(), 0.9 * t);
}

TEST(OrderChoice, KeepsTheHighOrderWhereItIsCheaper) {
  OrderChoice choice(0.0);
  double t = 0;
  feed(choice, t, 20000, [](int order) { return order == 2 ? 0.7e-6 : 1e-6; });
  EXPECT_EQ(choice.current_order(), 5);
  EXPECT_EQ(choice.switches(), 0);
  // The gaps between probes double: 200, 400, ... steps; the probes are a small share of the steps.
  EXPECT_LE(choice.probes(), 7);
  EXPECT_LT(choice.time_at_low_order() / t, 0.1);
}

TEST(OrderChoice, NoSwitchBelowTheGain) {
  OrderChoice choice(0.0);  // gain 1.5: an order 1.3 times better is not worth the switches
  double t = 0;
  feed(choice, t, 5000, [](int order) { return order == 2 ? 1.3e-6 : 1e-6; });
  EXPECT_EQ(choice.switches(), 0);
}

// A regime change: order 2 is better first, then order 5: the choice follows both.
TEST(OrderChoice, FollowsARegimeChange) {
  OrderChoice choice(0.0);
  double t = 0;
  long step = 0;
  feed(choice, t, 6000, [&](int order) { return (++step < 1000) == (order == 2) ? 1e-5 : 1e-6; });
  EXPECT_EQ(choice.current_order(), 5);
  EXPECT_EQ(choice.switches(), 2);
}

// A checkpoint in the middle of a probe: the restored choice decides as the uninterrupted one.
TEST(OrderChoice, RestoredChoiceContinuesTheSameWay) {
  const auto dt_of = [](int order) { return order == 2 ? 3e-6 : 1e-6; };
  OrderChoice whole(0.0), first(0.0);
  double t_whole = 0, t_first = 0;
  feed(whole, t_whole, 260, dt_of);
  feed(first, t_first, 260, dt_of);
  ASSERT_NE(first.order(), first.current_order());  // inside the first probe
  std::map<std::string, double> values;
  first.save(values);
  OrderChoice resumed(123.0);  // its start time is restored too
  resumed.restore(values);
  for (int i = 0; i < 3000; ++i) {
    t_whole += dt_of(whole.order());
    t_first += dt_of(resumed.order());
    ASSERT_EQ(whole.after_step(t_whole, 1, 0), resumed.after_step(t_first, 1, 0)) << "step " << i;
  }
  EXPECT_EQ(whole.switches(), resumed.switches());
  EXPECT_EQ(whole.probes(), resumed.probes());
  EXPECT_EQ(whole.description(), resumed.description());
}

/// Border: a slow oscillator (lightly damped, amplitude 1). Block: a fast mode that follows it
/// quasi-statically, a nearly undamped oscillator (damping ratio 1e-3, started at its quasi-static
/// position) or a real decay.
class SlowAndFast final : public DynamicSystem {
 public:
  SlowAndFast(bool oscillating, double slow_hz, double fast_hz)
      : slow(2 * M_PI * slow_hz), fast(2 * M_PI * fast_hz), oscillating_(oscillating) {}
  const double slow, fast;
  int state_size() const override { return 4; }
  int border_size() const override { return 2; }
  int block_count() const override { return 1; }
  int block_size() const override { return 2; }
  std::vector<double> absolute_tolerance() const override { return {1e-8, 1e-8 * slow, 1e-8, 1e-8 * slow}; }
  int rhs(double, const double* z, double* zdot) override {
    zdot[0] = z[1];
    zdot[1] = -slow * slow * z[0] - 2 * 0.01 * slow * z[1];
    if (oscillating_) {
      zdot[2] = z[3];
      zdot[3] = -fast * fast * z[2] - 2 * 1e-3 * fast * z[3] + 1e-3 * z[0] * slow * slow;  // driven by the slow one
    } else {
      zdot[2] = -fast * (z[2] - 1e-3 * z[0]);
      zdot[3] = -fast * z[3];
    }
    return 0;
  }
  int jacobian(double, const double*, BorderedMatrix& j) override {
    j.set_zero();
    j.add(0, 1, 1);
    j.add(1, 0, -slow * slow);
    j.add(1, 1, -2 * 0.01 * slow);
    if (oscillating_) {
      j.add(2, 3, 1);
      j.add(3, 2, -fast * fast);
      j.add(3, 3, -2 * 1e-3 * fast);
      j.add(3, 0, 1e-3 * slow * slow);
    } else {
      j.add(2, 2, -fast);
      j.add(2, 0, 1e-3 * fast);
      j.add(3, 3, -fast);
    }
    return 0;
  }
  std::string explain_state(int index) const override { return "state " + std::to_string(index); }

 private:
  bool oscillating_;
};

struct Counts {
  long steps;
  int order;
  long switches;
};

/// 20 ms at `rtol`: the automatic order, or a fixed one (`fixed` > 0).
Counts run(bool oscillating, double slow_hz, double rtol, int fixed, double fast_hz = 6e4) {
  SlowAndFast sys(oscillating, slow_hz, fast_hz);
  scene::SolverSpec spec;
  spec.rtol = rtol;
  spec.max_order = fixed > 0 ? fixed : 5;
  spec.linear_solver = scene::LinearSolverKind::sundials_dense;
  const double q0 = oscillating ? 1e-3 * sys.slow * sys.slow / (sys.fast * sys.fast) : 1e-3;
  Integrator integrator(sys, spec, 0.0, {1.0, 0.0, q0, 0.0});
  OrderChoice choice(0.0);
  if (fixed == 0) integrator.set_order_choice(&choice);
  std::vector<double> z;
  for (int i = 1; i <= 40; ++i) integrator.advance_to(i * 0.5e-3, z);
  EXPECT_NEAR(z[0], std::exp(-0.01 * sys.slow * 0.02), 1e-3);  // whole periods: x back near its start
  return {integrator.statistics().steps, choice.current_order(), choice.switches()};
}

TEST(OrderChoice, StiffRealDecayKeepsOrderFive) {
  // 1 kHz at rtol 1e-6: order 5 is 14 times cheaper than order 2.
  const Counts automatic = run(false, 1000, 1e-6, 0), order5 = run(false, 1000, 1e-6, 5),
               order2 = run(false, 1000, 1e-6, 2);
  std::printf("[ order choice ] slow oscillator, fast decay: automatic %ld steps, order 5 %ld, order 2 %ld\n",
              automatic.steps, order5.steps, order2.steps);
  EXPECT_EQ(automatic.order, 5);
  EXPECT_EQ(automatic.switches, 0);
  EXPECT_LT(order5.steps, order2.steps) << "order 5: " << order5.steps << ", order 2: " << order2.steps;
  // What the three losing probes of order 2 cost (after 200, 400 and 800 steps), in a run of only
  // 1,254 steps at order 5: measured 1,620 steps.
  EXPECT_LE(static_cast<double>(automatic.steps), static_cast<double>(order5.steps) * 1.35);
}

/// The oscillating system's trajectory (samples every 0.5 ms over 2 ms) with the automatic order,
/// started at order 2 (a choice that already switched, as after a checkpoint) and probing order 5
/// after `first_probe` steps, after the heap's blocks of the state vector's size were filled with
/// `pattern` and freed: CVODE's vectors are then carved out of them.
std::vector<double> run_from_order_two_after_heap(long first_probe, double pattern) {
  std::vector<double*> blocks(4000);
  for (double*& b : blocks) {
    b = static_cast<double*>(std::malloc(4 * sizeof(double)));
    std::fill(b, b + 4, pattern);
  }
  for (double* b : blocks) std::free(b);
  OrderChoiceSettings settings;
  settings.first_probe = 40, settings.window = 20, settings.settle = 5, settings.probe_settle = 10;
  OrderChoice choice(-1.0, settings);
  double t = -1.0;
  while (choice.current_order() != 2 && t < -0.9) feed(choice, t, 1, [](int order) { return order == 2 ? 1e-4 : 1e-6; });
  EXPECT_EQ(choice.current_order(), 2);
  std::map<std::string, double> values;  // the choice as a checkpoint holds it, its next probe `first_probe` steps on
  choice.save(values);
  values["order_choice.steps_in_phase"] = 0, values["order_choice.gap"] = static_cast<double>(first_probe);
  choice.restore(values);
  SlowAndFast sys(true, 1000, 6e4);
  scene::SolverSpec spec;
  spec.rtol = 1e-6;
  spec.linear_solver = scene::LinearSolverKind::sundials_dense;
  Integrator integrator(sys, spec, 0.0, {1.0, 0.0, 1e-3 * sys.slow * sys.slow / (sys.fast * sys.fast), 0.0});
  integrator.set_order_choice(&choice);
  std::vector<double> z, trajectory;
  for (int i = 1; i <= 4; ++i) {
    integrator.advance_to(i * 0.5e-3, z);
    trajectory.insert(trajectory.end(), z.begin(), z.end());
  }
  EXPECT_GE(choice.probes(), 2);  // order 5 probed from order 2: the largest order raised in the run
  return trajectory;
}

// Raising the largest order without a restart must not read memory no step has written (CVODE's
// estimate at order q+1 takes a history vector saved only at the previous largest order; its
// first raise after the instance is made reads it when the order-2 steps left the estimate due
// at the next step): the run is the same whatever the heap held before it. The first probe at
// 20 successive step counts meets every phase of CVODE's wait between order changes.
TEST(OrderChoice, RaisedOrderGivesTheSameRunWhateverTheHeapHeld) {
  for (long first_probe = 20; first_probe < 40; ++first_probe) {
    const std::vector<double> zeros = run_from_order_two_after_heap(first_probe, 0.0),
                              halves = run_from_order_two_after_heap(first_probe, 0.5),
                              nans = run_from_order_two_after_heap(first_probe, std::nan(""));
    ASSERT_EQ(zeros.size(), halves.size());
    EXPECT_EQ(0, std::memcmp(zeros.data(), halves.data(), zeros.size() * sizeof(double))) << first_probe;
    EXPECT_EQ(0, std::memcmp(zeros.data(), nans.data(), zeros.size() * sizeof(double))) << first_probe;
  }
}

}  // namespace
}  // namespace raceway::numerics
