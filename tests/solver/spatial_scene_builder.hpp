// Spatial test scenes built in code (not parsed), so the solver's tests do not depend on the scene
// files' assumptions: a 6309-size deep-groove ball bearing and a QJ215-size four-point bearing.
// Nothing here computes an expected result.
#pragma once

#include <cmath>
#include <numbers>
#include <string>

#include "io/scene/scene.hpp"

namespace raceway::solver::test {

struct BallSceneOptions {
  double speed_rpm = 1000;             ///< inner ring, driven
  double fx = 0, fy = 0, fz = 0;       ///< N on the inner ring
  bool lubricated = false;             ///< limiting-shear EHL traction; else tanh curve
  double end_time = 0.01, output_interval = 1e-4;
  double rtol = 1e-6;
  double damping_factor = 0.5;         ///< s/m, ball-race Hunt-Crossley
  double friction = 0.1;               ///< tanh curve maximum
  bool gravity = false;
};

inline io::Scene ball_scene_common(const BallSceneOptions& o) {
  io::Scene s;
  s.source = "<test>";
  s.scene.name = "test ball bearing";
  s.scene.model = io::ModelKind::spatial;
  s.scene.end_time = o.end_time;
  s.scene.output_interval = o.output_interval;
  s.gravity = o.gravity;
  s.materials["steel"] = {"steel", 7850, 208e9, 0.3};
  s.materials["brass"] = {"brass", 8500, 105e9, 0.33};
  s.bearing.roller_material = "steel";
  s.bearing.ring_material = "steel";
  s.cage.material = "brass";
  s.cage.guidance = io::CageGuidance::rolling_element;
  s.cage.pocket_shape = io::PocketShape::cylindrical;
  s.cage.pocket_clearance = 0.4e-3;
  s.inner_ring.motion = io::RingMotion::driven;
  s.inner_ring.speed = io::TimeFunction::constant(o.speed_rpm * std::numbers::pi / 30.0);
  s.inner_ring.translation_free = true;
  s.inner_ring.axial_free = true;
  s.inner_ring.load.fx = io::TimeFunction::constant(o.fx);
  s.inner_ring.load.fy = io::TimeFunction::constant(o.fy);
  s.inner_ring.load.fz = io::TimeFunction::constant(o.fz);
  for (auto* f : {&s.inner_ring.load.mz, &s.inner_ring.load.mx, &s.inner_ring.load.my, &s.outer_ring.load.fx,
                  &s.outer_ring.load.fy, &s.outer_ring.load.fz, &s.outer_ring.load.mx, &s.outer_ring.load.my,
                  &s.outer_ring.load.mz, &s.outer_ring.speed, &s.inner_ring.misalignment_x,
                  &s.inner_ring.misalignment_y, &s.outer_ring.misalignment_x, &s.outer_ring.misalignment_y})
    *f = io::TimeFunction::constant(0.0);
  s.outer_ring.motion = io::RingMotion::fixed;
  auto& race = s.ball_race;
  race.normal.name = "hertz";
  race.damping.name = "hunt_crossley";
  race.damping.factor = o.damping_factor;
  race.traction.name = o.lubricated ? "limiting_shear" : "tanh";
  race.traction.friction_coefficient = o.friction;
  race.traction.slip_velocity_scale = 0.05;
  race.traction.grid_x = race.traction.grid_y = 5;
  race.traction.rolling_resistance = o.lubricated;
  s.lubricant = {"test oil", o.lubricated ? 0.03 : 0.0, 2e-8, 0.07};
  s.ball_cage.normal.name = "hertz";
  s.ball_cage.damping.name = "hunt_crossley";
  s.ball_cage.damping.factor = 0.5;
  s.ball_cage.traction.name = "tanh";
  s.ball_cage.traction.friction_coefficient = 0.05;
  s.ball_cage.traction.slip_velocity_scale = 0.05;
  s.cage_land.normal.name = "palmgren";
  s.cage_land.damping.name = "hunt_crossley";
  s.cage_land.damping.factor = 0.5;
  s.cage_land.traction.name = "tanh";
  s.cage_land.traction.friction_coefficient = 0.05;
  s.cage_land.traction.slip_velocity_scale = 0.05;
  s.solver.rtol = o.rtol;
  return s;
}

/// 6309-size deep-groove ball bearing: 8 balls of 17.462 mm, pitch 72.5 mm, f_i 0.52, f_o 0.53,
/// 15 um diametral clearance.
inline io::Scene deep_groove_scene(const BallSceneOptions& o) {
  io::Scene s = ball_scene_common(o);
  s.bearing.type = io::BearingType::deep_groove_ball;
  s.bearing.rolling_elements = 8;
  s.bearing.ball.ball_diameter = 17.462e-3;
  s.bearing.ball.inner_conformity = 0.52;
  s.bearing.ball.outer_conformity = 0.53;
  s.bearing.pitch_diameter = 72.5e-3;
  s.bearing.radial_clearance = 15e-6;
  s.bearing.inner_bore_diameter = 45e-3;
  s.bearing.outer_outside_diameter = 100e-3;
  s.bearing.ring_width = 25e-3;
  return s;
}

/// QJ215-size four-point contact bearing (seed 001 Table 1): 15 balls of 17.462 mm, pitch 102.5 mm,
/// 35 degree arcs, 27 um clearance.
inline io::Scene four_point_scene(const BallSceneOptions& o) {
  io::Scene s = ball_scene_common(o);
  s.bearing.type = io::BearingType::four_point_contact_ball;
  s.bearing.rolling_elements = 15;
  s.bearing.ball.ball_diameter = 17.462e-3;
  s.bearing.ball.inner_conformity = 0.53;
  s.bearing.ball.outer_conformity = 9.25 / 17.462;
  s.bearing.ball.arc_contact_angle = 35.0 * std::numbers::pi / 180.0;
  s.bearing.pitch_diameter = 102.5e-3;
  s.bearing.radial_clearance = 27e-6;
  s.bearing.inner_bore_diameter = 75e-3;
  s.bearing.outer_outside_diameter = 130e-3;
  s.bearing.ring_width = 25e-3;
  s.materials["steel"] = {"steel", 7810, 2.1e11, 0.29};
  s.materials["brass"] = {"brass", 8500, 1.06e11, 0.324};
  return s;
}

}  // namespace raceway::solver::test
