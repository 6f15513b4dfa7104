// Spatial test scenes built in code (not parsed), so the solver's tests do not depend on the scene
// files' assumptions: a 6309-size deep-groove ball bearing and a QJ215-size four-point bearing.
// Nothing here computes an expected result.
#pragma once

#include <cmath>
#include <numbers>
#include <string>

#include "io/scene/scene.hpp"

namespace raceway::test {

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

/// The dimensions of a ball bearing, m (radial_clearance: the diametral clearance P_d).
struct BallBearingSize {
  scene::BearingType type = scene::BearingType::deep_groove_ball;
  int balls = 0;
  scene::BallGeometry ball;
  double pitch_diameter = 0, radial_clearance = 0;
  double inner_bore_diameter = 0, outer_outside_diameter = 0, ring_width = 0;
};

/// A contact of the cage (ball-pocket or cage-land): normal law `normal`, Hunt-Crossley damping
/// 0.5 s/m, tanh traction with friction 0.05 and slip scale 0.05 m/s.
inline scene::ContactSpec cage_contact(contact::LawId normal) {
  scene::ContactSpec c;
  c.normal.id = normal;
  c.damping.id = contact::LawId::hunt_crossley;
  c.damping.factor = 0.5;
  c.traction.id = contact::LawId::tanh_traction;
  c.traction.friction_coefficient = 0.05;
  c.traction.slip_velocity_scale = 0.05;
  return c;
}

/// A ball bearing of `size` with the contact laws, materials, loads and solver settings of `o`.
inline scene::Scene ball_scene(const BallSceneOptions& o, const BallBearingSize& size) {
  scene::Scene s;
  s.source = "<test>";
  s.scene.name = "test ball bearing";
  s.scene.model = scene::ModelKind::spatial;
  s.scene.end_time = o.end_time;
  s.scene.output_interval = o.output_interval;
  s.gravity = o.gravity;
  s.materials["steel"] = {"steel", 7850, 208e9, 0.3};
  s.materials["brass"] = {"brass", 8500, 105e9, 0.33};
  s.bearing.roller_material = "steel";
  s.bearing.ring_material = "steel";
  s.cage.material = "brass";
  s.cage.guidance = scene::CageGuidance::rolling_element;
  s.cage.pocket_shape = scene::PocketShape::cylindrical;
  s.cage.pocket_clearance = 0.4e-3;
  s.inner_ring.motion = scene::RingMotion::driven;
  s.inner_ring.speed = scene::TimeFunction::constant(o.speed_rpm * std::numbers::pi / 30.0);
  s.inner_ring.translation_free = true;
  s.inner_ring.axial_free = true;
  s.inner_ring.load.fx = scene::TimeFunction::constant(o.fx);
  s.inner_ring.load.fy = scene::TimeFunction::constant(o.fy);
  s.inner_ring.load.fz = scene::TimeFunction::constant(o.fz);
  for (auto* f : {&s.inner_ring.load.mz, &s.inner_ring.load.mx, &s.inner_ring.load.my, &s.outer_ring.load.fx,
                  &s.outer_ring.load.fy, &s.outer_ring.load.fz, &s.outer_ring.load.mx, &s.outer_ring.load.my,
                  &s.outer_ring.load.mz, &s.outer_ring.speed, &s.inner_ring.misalignment_x,
                  &s.inner_ring.misalignment_y, &s.outer_ring.misalignment_x, &s.outer_ring.misalignment_y})
    *f = scene::TimeFunction::constant(0.0);
  s.outer_ring.motion = scene::RingMotion::fixed;
  auto& race = s.ball_race;
  race.normal.id = contact::LawId::hertz;
  race.damping.id = contact::LawId::hunt_crossley;
  race.damping.factor = o.damping_factor;
  race.traction.id = o.lubricated ? contact::LawId::limiting_shear : contact::LawId::tanh_traction;
  race.traction.friction_coefficient = o.friction;
  race.traction.slip_velocity_scale = 0.05;
  race.traction.grid_x = race.traction.grid_y = 5;
  race.traction.rolling_resistance = o.lubricated;
  s.lubricant = {"test oil", o.lubricated ? 0.03 : 0.0, 2e-8, 0.07};
  s.ball_cage = cage_contact(contact::LawId::hertz);
  s.cage_land = cage_contact(contact::LawId::palmgren);
  s.solver.rtol = o.rtol;
  s.bearing.type = size.type;
  s.bearing.rolling_elements = size.balls;
  s.bearing.ball = size.ball;
  s.bearing.pitch_diameter = size.pitch_diameter;
  s.bearing.radial_clearance = size.radial_clearance;
  s.bearing.inner_bore_diameter = size.inner_bore_diameter;
  s.bearing.outer_outside_diameter = size.outer_outside_diameter;
  s.bearing.ring_width = size.ring_width;
  return s;
}

/// 6309-size deep-groove ball bearing: 8 balls of 17.462 mm, pitch 72.5 mm, f_i 0.52, f_o 0.53,
/// 15 um diametral clearance.
inline scene::Scene deep_groove_scene(const BallSceneOptions& o) {
  return ball_scene(o, {.type = scene::BearingType::deep_groove_ball, .balls = 8,
                        .ball = {.ball_diameter = 17.462e-3, .inner_conformity = 0.52, .outer_conformity = 0.53},
                        .pitch_diameter = 72.5e-3, .radial_clearance = 15e-6, .inner_bore_diameter = 45e-3,
                        .outer_outside_diameter = 100e-3, .ring_width = 25e-3});
}

/// QJ215-size four-point contact bearing (seed 001 Table 1): 15 balls of 17.462 mm, pitch 102.5 mm,
/// 35 degree arcs, 27 um clearance.
inline scene::Scene four_point_scene(const BallSceneOptions& o) {
  scene::Scene s = ball_scene(o, {.type = scene::BearingType::four_point_contact_ball, .balls = 15,
                               .ball = {.ball_diameter = 17.462e-3, .inner_conformity = 0.53,
                                        .outer_conformity = 9.25 / 17.462,
                                        .arc_contact_angle = 35.0 * std::numbers::pi / 180.0},
                               .pitch_diameter = 102.5e-3, .radial_clearance = 27e-6, .inner_bore_diameter = 75e-3,
                               .outer_outside_diameter = 130e-3, .ring_width = 25e-3});
  s.materials["steel"] = {"steel", 7810, 2.1e11, 0.29};
  s.materials["brass"] = {"brass", 8500, 1.06e11, 0.324};
  return s;
}

}  // namespace raceway::test
