// The automatic BDF order (solver/numerics/order_choice.hpp):
//  - the choice alone, on step streams whose cost per simulated time is known: it takes the order
//    that advances the time further per unit of work, keeps the other, and a choice restored from
//    its saved values continues with the same decisions as the one that was not interrupted;
//  - with CVODE on two small linear systems: a slow oscillation beside a nearly undamped fast one
//    (BDF orders 3-5 are unstable for it: the run goes to order 2 and takes far fewer steps than
//    order 5), and the same slow oscillation beside a fast real decay (every BDF order is stable
//    there: the run keeps order 5).
#include <gtest/gtest.h>

#include <cmath>
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

/// Border: a slow oscillator (1 kHz, lightly damped, amplitude 1). Block: a fast mode, either a
/// nearly undamped oscillator (60 kHz, damping ratio 1e-3, at rest: only rounding excites it) or a
/// real decay at the same rate.
class SlowAndFast final : public DynamicSystem {
 public:
  explicit SlowAndFast(bool oscillating) : oscillating_(oscillating) {}
  static constexpr double slow = 2 * M_PI * 1e3, fast = 2 * M_PI * 6e4;
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

/// 20 ms (20 slow periods) at rtol 1e-6: the automatic order, or a fixed one (`fixed` > 0).
Counts run(bool oscillating, int fixed) {
  SlowAndFast sys(oscillating);
  scene::SolverSpec spec;
  spec.rtol = 1e-6;
  spec.max_order = fixed > 0 ? fixed : 5;
  spec.linear_solver = scene::LinearSolverKind::sundials_dense;
  Integrator integrator(sys, spec, 0.0, {1.0, 0.0, 1e-3, 0.0});
  OrderChoice choice(0.0);
  if (fixed == 0) integrator.set_order_choice(&choice);
  std::vector<double> z;
  for (int i = 1; i <= 40; ++i) integrator.advance_to(i * 0.5e-3, z);
  EXPECT_NEAR(z[0], std::exp(-0.01 * SlowAndFast::slow * 0.02), 1e-3);  // 20 whole periods: x back near its start
  return {integrator.statistics().steps, choice.current_order(), choice.switches()};
}

TEST(OrderChoice, StiffOscillatorySystemGoesToOrderTwo) {
  const Counts automatic = run(true, 0), order5 = run(true, 5), order2 = run(true, 2);
  EXPECT_EQ(automatic.order, 2);
  EXPECT_LT(automatic.steps, order5.steps / 2) << "order 5: " << order5.steps << ", order 2: " << order2.steps;
}

TEST(OrderChoice, StiffRealDecayKeepsOrderFive) {
  const Counts automatic = run(false, 0), order5 = run(false, 5), order2 = run(false, 2);
  EXPECT_EQ(automatic.order, 5);
  EXPECT_EQ(automatic.switches, 0);
  EXPECT_LT(order5.steps, order2.steps) << "order 5: " << order5.steps << ", order 2: " << order2.steps;
  EXPECT_LE(static_cast<double>(automatic.steps), static_cast<double>(order5.steps) * 1.15);
}

}  // namespace
}  // namespace raceway::numerics
