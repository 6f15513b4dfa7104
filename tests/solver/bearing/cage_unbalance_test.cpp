// The cage keys of a disturbed, whirling cage (io/scene scene keys cage.initial_offset and
// cage.mass_eccentricity; solver/bearing/ball_startup.cpp, spatial_dynamics.cpp):
//  - a static unbalance m e adds the centrifugal force of the offset centre of mass, m e w^2 along
//    the cage frame's x turned by the cage angle, to the cage's equation of motion and nothing else:
//    checked against that closed form at several cage angles and speeds, every other rate unchanged;
//  - an initial offset moves the cage's start along +x and nothing else (balls, rings, speeds).
#include <gtest/gtest.h>

#include <cmath>
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

TEST(CageUnbalance, AddsTheCentrifugalForceOfTheOffsetCentreOfMass) {
  const scene::Scene balanced = loaded_bearing();
  scene::Scene unbalanced = balanced;
  const double e = 40e-6;
  unbalanced.cage.mass_eccentricity = e;
  const Model model = build_model(balanced);
  const Body& cage = model.bodies[static_cast<std::size_t>(model.cage)];
  auto slot = [&](int c) { return static_cast<std::size_t>(cage.slot[c]); };
  const std::vector<double> start = initial_state(model, 0.0).state;
  for (const double turn : {0.0, 0.7, 2.0, 3.5, 5.9}) {
    for (const double speed : {150.0, -400.0}) {
      // The cage and its balls turned together about the axis (the balls stay in their pockets).
      std::vector<double> z = start;
      const double angle = start[slot(saz)] + turn;
      z[slot(saz)] = angle;
      for (int k = 0; k < model.element_count; ++k) {
        const Body& ball = model.bodies[static_cast<std::size_t>(model.first_element + k)];
        for (const int c : {sx, svx, swx}) {
          const auto i = static_cast<std::size_t>(ball.slot[c]), j = static_cast<std::size_t>(ball.slot[c + 1]);
          z[i] = std::cos(turn) * start[i] - std::sin(turn) * start[j];
          z[j] = std::sin(turn) * start[i] + std::cos(turn) * start[j];
        }
      }
      z[slot(swz)] = speed;
      const std::vector<double> f0 = rates_of(balanced, z), f1 = rates_of(unbalanced, z);
      const double force = cage.mass * e * speed * speed;
      const Vec3 expected(force * std::cos(angle), force * std::sin(angle), 0.0);
      const Vec3 added((f1[slot(svx)] - f0[slot(svx)]) * cage.mass, (f1[slot(svy)] - f0[slot(svy)]) * cage.mass,
                       (f1[slot(svz)] - f0[slot(svz)]) * cage.mass);
      EXPECT_NEAR((added - expected).norm(), 0.0, 1e-9 * force + 1e-12)
          << "cage at " << angle << " rad turning at " << speed << " rad/s: added " << added.transpose()
          << " N, expected " << expected.transpose() << " N";
      for (std::size_t i = 0; i < z.size(); ++i) {
        if (i != slot(svx) && i != slot(svy) && i != slot(svz)) {
          EXPECT_EQ(f1[i], f0[i]) << "rate " << i;
        }
      }
    }
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
