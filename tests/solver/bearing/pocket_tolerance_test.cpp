// [solver] pocket_tolerance_factor (Equations::adjust_error_weights): while a ball (a roller) touches its pocket,
// or is within 1e-4 of its radius of it, the error weights of its translational velocities are
// multiplied by the factor; every other weight is left as it was, and a factor of 1 leaves
// SUNDIALS' own weights in place (no weight function at all).
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <string>
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

// Seed 002 as shipped (the orbital frame, K = 10 with the cage's rate; its bars judged by their gap
// alone): with the cage turned through its pocket clearance both ways in steps of 0.23 um at the
// pitch radius, the weights tighten exactly the rollers one of whose bars has its evaluated approach
// (the right-hand side's record) within 1e-4 of the roller radius, their v_theta alone, and the cage's
// rate when any does: each roller crosses that line within a step.
TEST(PocketTolerance, PlanarRollersByTheirBarsEvaluatedApproach) {
  const scene::Scene s = test::load_job_scene("seed002_40hz.toml");
  const double factor = s.solver.pocket_tolerance_factor;
  ASSERT_GT(factor, 1.0);
  ASSERT_TRUE(s.solver.pocket_tolerance_cage);
  const Model m = build_model(s);
  scheduler::SerialExecutor executor;
  Equations eq(m, executor);
  executor.attach(eq.task_catalogue());
  const std::vector<double> z = initial_state(m, 0.0).state;
  std::vector<double> zdot(z.size()), w(z.size());
  const Body& cage = m.bodies[static_cast<std::size_t>(m.cage)];
  const double margin = 1e-4 * m.element_radius;
  int touching = 0, clear = 0, wrong = 0;
  std::string first_wrong;
  for (int k = -1200; k <= 1200; ++k) {
    std::vector<double> state = z;
    state[static_cast<std::size_t>(cage.slot[saz])] += 1e-5 * k;  // the half clearance: 0.1 mm / 22.87 mm
    eq.rhs(0.0, state.data(), zdot.data());
    std::vector<int> touches(m.bodies.size(), 0);
    for (std::size_t g = 0; g < m.segments.size(); ++g) {
      const SegmentKind kind = m.segments[g].kind;
      if ((kind == SegmentKind::cage_bar_front || kind == SegmentKind::cage_bar_rear) &&
          eq.diagnostic(g, approach_field) > -margin)
        touches[static_cast<std::size_t>(m.segments[g].body_b)] = 1;
    }
    std::fill(w.begin(), w.end(), 1.0);
    eq.adjust_error_weights(0.0, state.data(), w.data());
    bool any = false;
    const auto expect = [&](int i, bool tight, const Body& body) {
      if (w[static_cast<std::size_t>(i)] == (tight ? factor : 1.0)) return;
      if (wrong++ == 0) first_wrong = "turn " + std::to_string(k) + ", body " + std::to_string(&body - m.bodies.data());
    };
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      const Body& body = m.bodies[b];
      if (body.kind != BodyKind::rolling_element) continue;
      any = any || touches[b];
      (touches[b] ? touching : clear) += 1;
      for (int i = body.offset; i < body.offset + body.size; ++i) expect(i, touches[b] && i == body.slot[svy], body);
    }
    for (int i = cage.offset; i < cage.offset + cage.size; ++i) expect(i, any && i == cage.slot[swz], cage);
  }
  EXPECT_EQ(wrong, 0) << "first: " << first_wrong;
  EXPECT_GT(touching, 13 * 200);  // the turns bring every roller to a bar
  EXPECT_GT(clear, 13 * 200);
}
}  // namespace
}  // namespace raceway::bearing
