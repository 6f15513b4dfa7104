// KinematicsMemo: while one lives, Model::kinematics at its (t, z) computes each body's kinematics
// once; what it returns must be the bits of the computation without it, and nothing it kept may
// outlive its scope (z changed between two scopes, an inner scope at another t) or leak to
// another z or t.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "io/scene/scene_parser.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/startup.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::bearing {
namespace {

bool same_bits(const contact::SpatialKinematics& a, const contact::SpatialKinematics& b) {
  return std::memcmp(a.position.data(), b.position.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(a.rotation.data(), b.rotation.data(), 9 * sizeof(double)) == 0 &&
         std::memcmp(a.velocity.data(), b.velocity.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(a.angular_velocity.data(), b.angular_velocity.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(&a.spin_angle, &b.spin_angle, sizeof(double)) == 0;
}

struct Seated {
  Model m;
  std::vector<double> z;
  int cage = -1, ball = -1, inner = -1;
};

// 6309 R3 as shipped (the balls' orbital frame, a driven inner ring, a tilting outer ring), seated.
Seated seated() {
  Seated s{build_model(test::load_job_scene("6309_R3.toml")), {}};
  s.z = initial_state(s.m, 0.0).state;
  for (std::size_t b = 0; b < s.m.bodies.size(); ++b) {
    const BodyKind k = s.m.bodies[b].kind;
    if (k == BodyKind::cage) s.cage = static_cast<int>(b);
    if (k == BodyKind::inner_ring) s.inner = static_cast<int>(b);
    if (k == BodyKind::rolling_element && s.ball < 0) s.ball = static_cast<int>(b);
  }
  return s;
}

TEST(KinematicsMemo, SameBitsAsWithout) {
  Seated s = seated();
  ASSERT_TRUE(s.cage >= 0 && s.ball >= 0 && s.inner >= 0);
  const double t = 1.25e-3;
  std::vector<contact::SpatialKinematics> plain;
  for (std::size_t b = 0; b < s.m.bodies.size(); ++b) plain.push_back(s.m.kinematics(static_cast<int>(b), t, s.z.data()));
  const KinematicsMemo memo(s.m, t, s.z.data());
  for (int pass = 0; pass < 2; ++pass)  // computed, then kept
    for (std::size_t b = 0; b < s.m.bodies.size(); ++b)
      EXPECT_TRUE(same_bits(s.m.kinematics(static_cast<int>(b), t, s.z.data()), plain[b])) << "body " << b;
}

// Another z (a copy, moved) or another t in the scope: computed there, not taken from the memo.
TEST(KinematicsMemo, OtherStateOrTimeComputed) {
  Seated s = seated();
  const double t = 1.25e-3;
  const KinematicsMemo memo(s.m, t, s.z.data());
  const contact::SpatialKinematics ball = s.m.kinematics(s.ball, t, s.z.data());
  const contact::SpatialKinematics inner = s.m.kinematics(s.inner, t, s.z.data());
  std::vector<double> moved = s.z;
  moved[static_cast<std::size_t>(s.m.bodies[static_cast<std::size_t>(s.ball)].slot[sx])] += 1e-6;
  EXPECT_NEAR(s.m.kinematics(s.ball, t, moved.data()).position.x() - ball.position.x(), 1e-6, 1e-15);
  // The driven inner ring turns: its angle about its axis at a later time.
  const double later = t + 1e-3;
  const double turned = s.m.kinematics(s.inner, later, s.z.data()).spin_angle - inner.spin_angle;
  EXPECT_NEAR(turned, 1e-3 * s.m.ring_spin(s.inner, t, s.z.data()), 1e-9);
  EXPECT_GT(turned, 0.0);
}

// The same z changed between two scopes, and an inner scope at another time: every scope starts
// empty, and the outer one computes again after the inner one.
TEST(KinematicsMemo, NothingOutlivesItsScope) {
  Seated s = seated();
  const double t = 1.25e-3;
  const auto x = static_cast<std::size_t>(s.m.bodies[static_cast<std::size_t>(s.cage)].slot[sx]);
  double before = 0;
  {
    const KinematicsMemo memo(s.m, t, s.z.data());
    before = s.m.kinematics(s.cage, t, s.z.data()).position.x();
  }
  s.z[x] += 2e-6;
  {
    const KinematicsMemo memo(s.m, t, s.z.data());
    EXPECT_NEAR(s.m.kinematics(s.cage, t, s.z.data()).position.x() - before, 2e-6, 1e-15);
    const contact::SpatialKinematics outer = s.m.kinematics(s.inner, t, s.z.data());
    {
      const KinematicsMemo inner_scope(s.m, t + 1e-3, s.z.data());
      EXPECT_GT(s.m.kinematics(s.inner, t + 1e-3, s.z.data()).spin_angle, outer.spin_angle);
    }
    EXPECT_TRUE(same_bits(s.m.kinematics(s.inner, t, s.z.data()), outer));
    EXPECT_TRUE(same_bits(s.m.kinematics(s.inner, t, s.z.data()), s.m.kinematics(s.inner, t, std::vector<double>(s.z).data())));
  }
}

// A scope at a copy of z (Equations::rhs' context, `copy_of` the caller's z) answers at both
// pointers; nested in a scope at z of the same time it continues that scope's entries (the output's
// sample: its right-hand side, then its rows), which hold the bits computed at z. Nested at another
// time, or at values of its own, it starts empty and leaves the outer scope empty.
TEST(KinematicsMemo, ACopyOfTheStateContinuesTheScopeAtTheState) {
  Seated s = seated();
  const double t = 1.25e-3;
  std::vector<contact::SpatialKinematics> plain;
  for (std::size_t b = 0; b < s.m.bodies.size(); ++b) plain.push_back(s.m.kinematics(static_cast<int>(b), t, s.z.data()));
  const KinematicsMemo outer(s.m, t, s.z.data());
  {
    const std::vector<double> copy = s.z;
    const KinematicsMemo inner(s.m, t, copy.data(), s.z.data());
    for (std::size_t b = 0; b < s.m.bodies.size(); ++b) {
      EXPECT_TRUE(same_bits(s.m.kinematics(static_cast<int>(b), t, copy.data()), plain[b])) << "body " << b;
      EXPECT_TRUE(same_bits(s.m.kinematics(static_cast<int>(b), t, s.z.data()), plain[b])) << "body " << b;
    }
  }
  for (std::size_t b = 0; b < s.m.bodies.size(); ++b)
    EXPECT_TRUE(same_bits(s.m.kinematics(static_cast<int>(b), t, s.z.data()), plain[b])) << "body " << b;
  // Another time: the driven inner ring's angle there, and the outer scope's own again after it.
  const double later = t + 1e-3;
  {
    const std::vector<double> copy = s.z;
    const KinematicsMemo inner(s.m, later, copy.data(), s.z.data());
    EXPECT_TRUE(same_bits(s.m.kinematics(s.inner, later, copy.data()), s.m.body_kinematics(s.inner, later, s.z.data())));
  }
  EXPECT_TRUE(same_bits(s.m.kinematics(s.inner, t, s.z.data()), plain[static_cast<std::size_t>(s.inner)]));
  // A copy of other values (the cage moved), declared a copy of another vector: its own bits.
  std::vector<double> moved = s.z, other = s.z;
  moved[static_cast<std::size_t>(s.m.bodies[static_cast<std::size_t>(s.cage)].slot[sx])] += 2e-6;
  {
    const KinematicsMemo inner(s.m, t, moved.data(), other.data());
    EXPECT_TRUE(same_bits(s.m.kinematics(s.cage, t, moved.data()), s.m.body_kinematics(s.cage, t, moved.data())));
  }
  EXPECT_TRUE(same_bits(s.m.kinematics(s.cage, t, s.z.data()), plain[static_cast<std::size_t>(s.cage)]));
}

}  // namespace
}  // namespace raceway::bearing
