// [solver] pocket_tolerance_factor (Equations::adjust_error_weights): while a ball touches its pocket,
// or is within 1e-4 of its radius of it, the error weights of its translational velocities are
// multiplied by the factor; every other weight is left as it was, and a factor of 1 leaves
// SUNDIALS' own weights in place (no weight function at all).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "io/scene/scene_parser.hpp"
#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/segment_record.hpp"
#include "solver/bearing/startup.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::bearing {
namespace {

scene::Scene scene_with_factor(double factor) {
  scene::Scene s = test::load_job_scene("6309_R3.toml");
  s.solver.pocket_tolerance_factor = factor;
  return s;
}

TEST(PocketTolerance, OffByDefault) {
  // 6309 R5 leaves the key out (6309 R3 ships 10).
  const scene::Scene s = test::load_job_scene("6309_R5.toml");
  EXPECT_EQ(s.solver.pocket_tolerance_factor, 1.0);
  const Model m = build_model(s);
  scheduler::SerialExecutor executor;
  Equations eq(m, executor);
  EXPECT_FALSE(eq.adjusts_error_weights());
}

// The cage turned until ball 0 presses into a bar of its pocket: that ball's translational
// velocities get the factor (in the orbital frame its circumferential velocity v_theta alone), its
// other states, the cage's, the other balls' and the rings' keep theirs; turned back to the pocket's
// middle, nothing changes. With pocket_tolerance_cage the cage's rotation rate gets the factor too.
void check_tightening(scene::ElementVelocityFrame frame, bool cage_rate = false) {
  const bool orbital = frame == scene::ElementVelocityFrame::orbital;
  const double factor = 30;
  scene::Scene s = scene_with_factor(factor);
  s.solver.element_velocity_frame = frame;
  s.solver.pocket_tolerance_cage = cage_rate;
  const Model m = build_model(s);
  scheduler::SerialExecutor executor;
  Equations eq(m, executor);
  executor.attach(eq.task_catalogue());
  ASSERT_TRUE(eq.adjusts_error_weights());
  std::vector<double> z = initial_state(m, 0.0).state;
  std::vector<double> zdot(z.size());

  int cage = -1, ball0 = -1;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    if (m.bodies[b].kind == BodyKind::cage) cage = static_cast<int>(b);
    if (m.bodies[b].kind == BodyKind::rolling_element && m.bodies[b].index == 0) ball0 = static_cast<int>(b);
  }
  ASSERT_GE(cage, 0);
  ASSERT_GE(ball0, 0);
  const int angle = m.bodies[static_cast<std::size_t>(cage)].slot[saz];
  ASSERT_GE(angle, 0);
  std::size_t pocket0 = m.segments.size();
  for (std::size_t k = 0; k < m.segments.size(); ++k)
    if (m.segments[k].kind == SegmentKind::ball_pocket && m.segments[k].element == 0) pocket0 = k;
  ASSERT_LT(pocket0, m.segments.size());
  const auto approach = [&](std::vector<double>& state) {
    eq.rhs(0.0, state.data(), zdot.data());
    return eq.diagnostic(pocket0, approach_field);
  };

  // Every ball clear of its pocket at the start-up's cage angle (the cage centred on the balls).
  std::vector<double> clear = z;
  const std::vector<double> ones(z.size(), 1.0);
  std::vector<double> w = ones;
  eq.adjust_error_weights(0.0, clear.data(), w.data());
  EXPECT_EQ(w, ones) << "no ball touches its pocket at the start-up state";

  // Turn the cage in small steps until ball 0 presses into a bar (0.4 mm diametral clearance:
  // within about 0.2 mm / pitch radius = 5.5 mrad).
  std::vector<double> touching = z;
  for (int k = 1; k <= 200 && approach(touching) <= 0; ++k) touching[static_cast<std::size_t>(angle)] = z[static_cast<std::size_t>(angle)] + 1e-4 * k;
  ASSERT_GT(approach(touching), 0.0);
  w = ones;
  eq.adjust_error_weights(0.0, touching.data(), w.data());
  const Body& b0 = m.bodies[static_cast<std::size_t>(ball0)];
  int tightened = 0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    const bool velocity = m.state_class[i] == VariableClass::velocity;
    const bool in_ball0 = static_cast<int>(i) >= b0.offset && static_cast<int>(i) < b0.offset + b0.size;
    const Body* owner = nullptr;
    for (const Body& b : m.bodies)
      if (static_cast<int>(i) >= b.offset && static_cast<int>(i) < b.offset + b.size) owner = &b;
    ASSERT_NE(owner, nullptr);
    const bool tightens = orbital ? static_cast<int>(i) == owner->slot[svy] : velocity;
    if (owner->kind == BodyKind::cage && static_cast<int>(i) == owner->slot[swz] && cage_rate) {
      EXPECT_EQ(w[i], factor) << "the cage's rotation rate, once";
      ++tightened;
    } else if (in_ball0 && tightens) {
      EXPECT_EQ(w[i], factor) << "state " << i;
      ++tightened;
    } else if (w[i] != 1.0) {
      // Another ball the same turn brought to its bar (the pockets are evenly spaced) is allowed,
      // and only its velocities (orbital: v_theta), only with the factor.
      EXPECT_EQ(w[i], factor) << "state " << i;
      EXPECT_TRUE(tightens && owner->kind == BodyKind::rolling_element) << "state " << i;
    }
  }
  EXPECT_EQ(tightened, (orbital ? 1 : b0.has(svz) ? 3 : 2) + (cage_rate ? 1 : 0));
}

TEST(PocketTolerance, TightensTheTouchingBallsVelocities) { check_tightening(scene::ElementVelocityFrame::bearing); }
TEST(PocketTolerance, TightensTheTouchingBallsOrbitalVelocityOnly) {
  check_tightening(scene::ElementVelocityFrame::orbital);
}
TEST(PocketTolerance, TightensTheCagesRotationRateOnRequest) {
  check_tightening(scene::ElementVelocityFrame::orbital, true);
  check_tightening(scene::ElementVelocityFrame::bearing, true);
}

}  // namespace
}  // namespace raceway::bearing
