// The cage keys of a disturbed, whirling cage (io/scene scene keys cage.initial_offset and
// cage.mass_eccentricity; solver/bearing/ball_startup.cpp, spatial_dynamics.cpp):
//  - a static unbalance m e adds the centrifugal force of the offset centre of mass, m e w^2 along
//    the cage frame's x turned by the cage angle, to the cage's equation of motion and nothing else:
//    checked against that closed form at several cage angles and speeds, every other rate unchanged,
//    and with cage.mass_eccentricity_angle the same force turned by that phase;
//  - an initial offset moves the cage's start along +x and nothing else (balls, rings, speeds).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/startup.hpp"
#include "tests/support/spatial_scene_builder.hpp"

namespace raceway::bearing {
namespace {

using contact::Vec3;

scene::Scene loaded_bearing() {
  test::BallSceneOptions o;
  o.speed_rpm = 3000;
  o.fy = 1000;
  return test::deep_groove_scene(o);
}

/// The rates of the state z under a scene.
std::vector<double> rates_of(const scene::Scene& scene, const std::vector<double>& z) {
  const Model model = build_model(scene);
  scheduler::SerialExecutor executor;
  Equations eq(model, executor);
  std::vector<double> zdot(z.size());
  EXPECT_EQ(eq.rhs(0.0, z.data(), zdot.data()), 0);
  return zdot;
}

/// The start state with the cage and its balls turned together by `turn` about the axis (the balls
/// stay in their pockets) and the cage spinning at `speed`.
std::vector<double> turned(const Model& model, const std::vector<double>& start, double turn, double speed) {
  const Body& cage = model.bodies[static_cast<std::size_t>(model.cage)];
  std::vector<double> z = start;
  z[static_cast<std::size_t>(cage.slot[saz])] += turn;
  for (int k = 0; k < model.element_count; ++k) {
    const Body& ball = model.bodies[static_cast<std::size_t>(model.first_element + k)];
    for (const int c : {sx, svx, swx}) {
      const auto i = static_cast<std::size_t>(ball.slot[c]), j = static_cast<std::size_t>(ball.slot[c + 1]);
      z[i] = std::cos(turn) * start[i] - std::sin(turn) * start[j];
      z[j] = std::sin(turn) * start[i] + std::cos(turn) * start[j];
    }
  }
  z[static_cast<std::size_t>(cage.slot[swz])] = speed;
  return z;
}

/// Checks that the unbalance e at the phase `phase` adds m e w^2 at the cage angle plus the phase to
/// the cage's equation of motion and changes no other rate.
void check_unbalance_force(double e, double phase) {
  const scene::Scene balanced = loaded_bearing();
  scene::Scene unbalanced = balanced;
  unbalanced.cage.mass_eccentricity = e;
  unbalanced.cage.mass_eccentricity_angle = phase;
  const Model model = build_model(balanced);
  const Body& cage = model.bodies[static_cast<std::size_t>(model.cage)];
  auto slot = [&](int c) { return static_cast<std::size_t>(cage.slot[c]); };
  const std::vector<double> start = initial_state(model, 0.0).state;
  for (const double turn : {0.0, 0.7, 2.0, 3.5, 5.9}) {
    for (const double speed : {150.0, -400.0}) {
      const std::vector<double> z = turned(model, start, turn, speed);
      const double angle = z[slot(saz)];
      const std::vector<double> f0 = rates_of(balanced, z), f1 = rates_of(unbalanced, z);
      const double force = cage.mass * e * speed * speed;
      const Vec3 expected(force * std::cos(angle + phase), force * std::sin(angle + phase), 0.0);
      const Vec3 added((f1[slot(svx)] - f0[slot(svx)]) * cage.mass, (f1[slot(svy)] - f0[slot(svy)]) * cage.mass,
                       (f1[slot(svz)] - f0[slot(svz)]) * cage.mass);
      EXPECT_NEAR((added - expected).norm(), 0.0, 1e-9 * force + 1e-12)
          << "cage at " << angle << " rad, unbalance at " << phase << " rad, turning at " << speed << " rad/s: added "
          << added.transpose() << " N, expected " << expected.transpose() << " N";
      for (std::size_t i = 0; i < z.size(); ++i) {
        if (i != slot(svx) && i != slot(svy) && i != slot(svz)) {
          EXPECT_EQ(f1[i], f0[i]) << "rate " << i;
        }
      }
    }
  }
}

TEST(CageUnbalance, AddsTheCentrifugalForceOfTheOffsetCentreOfMass) { check_unbalance_force(40e-6, 0.0); }

// cage.mass_eccentricity_angle puts the centre of mass at that angle from the cage frame's x: the
// force turns by it (a quarter turn, a half, a negative phase, a whole turn back to the start).
TEST(CageUnbalance, ThePhaseTurnsTheForce) {
  for (const double phase : {0.5 * std::numbers::pi, std::numbers::pi, -0.5236, 1.5 * std::numbers::pi}) {
    SCOPED_TRACE(phase);
    check_unbalance_force(40e-6, phase);
  }
}

// The force at the phase 90 deg is the force at 0 with the cage turned a quarter further: the
// same rates, not only the closed form.
TEST(CageUnbalance, APhaseIsTheCageTurnedBack) {
  scene::Scene at0 = loaded_bearing(), at90 = at0;
  at0.cage.mass_eccentricity = at90.cage.mass_eccentricity = 40e-6;
  at90.cage.mass_eccentricity_angle = 0.5 * std::numbers::pi;
  const Model model = build_model(at0);
  const Body& cage = model.bodies[static_cast<std::size_t>(model.cage)];
  const std::vector<double> start = initial_state(model, 0.0).state;
  const std::vector<double> f0 = rates_of(at0, turned(model, start, 0.5 * std::numbers::pi, 300.0));
  const std::vector<double> f90 = rates_of(at90, turned(model, start, 0.0, 300.0));
  const std::vector<double> r0 = rates_of(loaded_bearing(), turned(model, start, 0.5 * std::numbers::pi, 300.0));
  const std::vector<double> r90 = rates_of(loaded_bearing(), turned(model, start, 0.0, 300.0));
  for (const int c : {svx, svy}) {
    const auto i = static_cast<std::size_t>(cage.slot[c]);
    EXPECT_NEAR(f90[i] - r90[i], f0[i] - r0[i], 1e-9 * std::abs(f0[i] - r0[i]) + 1e-12) << "coordinate " << c;
  }
}

TEST(CageUnbalance, InitialOffsetMovesOnlyTheCage) {
  const scene::Scene centred = loaded_bearing();
  scene::Scene offset = centred;
  offset.cage.initial_offset = 30e-6;
  const Model m0 = build_model(centred), m1 = build_model(offset);
  const std::vector<double> z0 = initial_state(m0, 0.0).state, z1 = initial_state(m1, 0.0).state;
  ASSERT_EQ(z0.size(), z1.size());
  const Body& cage = m0.bodies[static_cast<std::size_t>(m0.cage)];
  const auto x = static_cast<std::size_t>(cage.slot[sx]);
  EXPECT_EQ(z1[x], z0[x] + 30e-6);
  for (std::size_t i = 0; i < z0.size(); ++i) {
    if (i != x) {
      EXPECT_EQ(z1[i], z0[i]) << "state " << i;
    }
  }
}

}  // namespace
}  // namespace raceway::bearing
