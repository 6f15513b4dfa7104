// Balances of the spatial ball-bearing model at the level of its equations: the contact forces and
// moments of the whole bearing sum to zero (action = reaction), and the cage's spindle support
// only dissipates energy, at every cage angle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/numerics/integrator.hpp"
#include "tests/support/engaged_bearing.hpp"
#include "tests/support/solver_test_support.hpp"
#include "tests/support/spatial_scene_builder.hpp"

namespace raceway::bearing {
namespace {

using contact::Vec3;
using test::ball_bearing_kinds;
using test::BallSceneOptions;
using test::closed_contacts;
using test::describe_closed;
using test::EngagedBearing;
using test::pi;

// ---------------------------------------------------------------------------------------------
// Action and reaction over the whole bearing
// ---------------------------------------------------------------------------------------------

/// Sum over all bodies of the contact forces, and of the contact moments about the origin (moment at
/// the body's centre + centre x force), relative to the largest contact force (and that force times
/// the outer ring's radius).
struct Balance {
  double force = 0, moment = 0, largest = 0;
};
Balance contact_balance(Equations& eq, const Model& m, double t, const std::vector<double>& z) {
  std::vector<double> f(z.size());
  EXPECT_EQ(eq.rhs(t, z.data(), f.data()), 0);
  Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
  Balance b;
  for (std::size_t i = 0; i < m.bodies.size(); ++i) {
    const auto& w = eq.contact_loads()[i];
    const Vec3 centre = m.kinematics(static_cast<int>(i), t, z.data()).position;
    force += w.force;
    moment += w.moment + centre.cross(w.force);
  }
  const auto& rec = eq.segment_records();
  for (std::size_t s = 0; s < m.segments.size(); ++s)
    b.largest = std::max(b.largest, Vec3(rec[s * SegmentRecord::size + SegmentRecord::on_b],
                                         rec[s * SegmentRecord::size + SegmentRecord::on_b + 1],
                                         rec[s * SegmentRecord::size + SegmentRecord::on_b + 2])
                                        .norm());
  const double radius = 0.5 * m.params().bearing.outer_outside_diameter;
  b.force = force.norm() / b.largest;
  b.moment = moment.norm() / (b.largest * radius);
  return b;
}

// Every segment puts equal and opposite forces on its two bodies at one contact point (traction
// moments as couples), so the contact forces of the whole bearing sum to zero and so do their
// moments about any point: checked about the origin, with each body's moment at its centre moved
// there, at the engaged state (every kind of contact closed) and along 3 ms of the run from it (the
// cage bouncing off its land and pockets). Round-off only: 1e-12 of the largest contact force (and
// of it times the outer radius for moments); a sum of ~40 terms loses ~1e-15.
TEST(SpatialPhysics, ActionReactionOfTheWholeBearing) {
  EngagedBearing b;
  std::vector<std::vector<double>> states = {b.start, b.engaged};
  std::vector<double> times = {0.0, 0.0};
  {
    numerics::Integrator integrator(b.eq, b.scene.solver, 0.0, b.engaged);
    for (int i = 1; i <= 6; ++i) {
      std::vector<double> z;
      integrator.advance_to(0.5e-3 * i, z);
      states.push_back(z), times.push_back(0.5e-3 * i);
    }
  }
  std::vector<int> ever_closed(segment_kind_count, 0);
  double worst_force = 0, worst_moment = 0;
  for (std::size_t i = 0; i < states.size(); ++i) {
    const Balance bal = contact_balance(b.eq, b.model, times[i], states[i]);
    const auto closed = closed_contacts(b.model, b.eq);
    for (std::size_t k = 0; k < closed.size(); ++k) ever_closed[k] += closed[k];
    std::printf("[ action-reaction ] %s t = %.1f ms: largest contact force %.4g N; |sum F| / F_max %.3g, |sum M_0| / "
                "(F_max R) %.3g; closed: %s\n",
                i == 0 ? "start  " : i == 1 ? "engaged" : "run    ", 1e3 * times[i], bal.largest, bal.force, bal.moment,
                describe_closed(b.model, closed).c_str());
    worst_force = std::max(worst_force, bal.force), worst_moment = std::max(worst_moment, bal.moment);
  }
  ASSERT_EQ(ball_bearing_kinds(b.model).size(), 4u);
  for (int k : ball_bearing_kinds(b.model))
    EXPECT_GT(ever_closed[static_cast<std::size_t>(k)], 0) << segment_kind_name(static_cast<SegmentKind>(k));
  EXPECT_LT(worst_force, 1e-12);
  EXPECT_LT(worst_moment, 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Energy: the cage support
// ---------------------------------------------------------------------------------------------


// The cage's spindle support (seed 000's aerostatic spindle) may only take energy out: at any cage
// angle, the power balance of the cage body is
//   d/dt (kinetic + support spring energy) = contact power - c_r |v_xy|^2 - c_a v_z^2 - c_t |w_across|^2,
// with the tilt spring's energy k (1 - cos ax cos ay) and w_across the angular velocity across the
// cage axis. A tilt damper acting on the body-frame rates (which turn with the cage) breaks it at
// cage angles near 180 deg, where it pumps energy in: the whirl that jammed the balls in 6309 case
// A12 (jobs/scenes/6309_A12.toml).
TEST(SpatialPhysics, CageSupportOnlyDissipatesAtEveryCageAngle) {
  BallSceneOptions o;
  o.fy = 1000;
  scene::Scene scene = test::deep_groove_scene(o);
  auto& support = scene.cage.support;
  support.radial_stiffness = 2e7, support.radial_damping = 1e3;
  support.axial_stiffness = 2e7, support.axial_damping = 1e3;
  support.tilt_stiffness = 5e4, support.tilt_damping = 2.5;
  const Model model = build_model(scene);
  scheduler::SerialExecutor executor;
  Equations eq(model, executor);
  const std::vector<double> start = initial_state(model, 0.0).state;
  const Body& cage = model.bodies[static_cast<std::size_t>(model.cage)];
  auto slot = [&](int c) { return static_cast<std::size_t>(cage.slot[c]); };
  for (int c : {sx, sy, sz, sax, say, saz, svx, svy, svz, swx, swy, swz}) ASSERT_GE(cage.slot[c], 0);
  const double pocket_pitch = 2 * pi / model.element_count;
  for (int k = 0; k < model.element_count; ++k) {
    std::vector<double> z = start, zdot(z.size());
    // Turn the cage by whole pockets (the balls stay in their pockets), displace and tilt it, and
    // give it translation and tilt rates.
    z[slot(saz)] += k * pocket_pitch;
    z[slot(sx)] = 3e-6, z[slot(sy)] = -2e-6, z[slot(sz)] = 1e-6;
    z[slot(sax)] = 2e-4, z[slot(say)] = -1e-4;
    z[slot(svx)] = 0.01, z[slot(svy)] = -0.02, z[slot(svz)] = 0.005;
    z[slot(swx)] = 3.0, z[slot(swy)] = -4.0;
    eq.rhs(0.0, z.data(), zdot.data());
    const Vec3 v(z[slot(svx)], z[slot(svy)], z[slot(svz)]), a(zdot[slot(svx)], zdot[slot(svy)], zdot[slot(svz)]);
    const Vec3 w(z[slot(swx)], z[slot(swy)], z[slot(swz)]), wdot(zdot[slot(swx)], zdot[slot(swy)], zdot[slot(swz)]);
    const Vec3 inertia(cage.transverse_inertia, cage.transverse_inertia, cage.axial_inertia);
    const double energy_rate =
        cage.mass * v.dot(a) + w.dot(inertia.cwiseProduct(wdot)) +
        support.radial_stiffness * (z[slot(sx)] * v.x() + z[slot(sy)] * v.y()) + support.axial_stiffness * z[slot(sz)] * v.z() +
        support.tilt_stiffness * (std::sin(z[slot(sax)]) * std::cos(z[slot(say)]) * zdot[slot(sax)] +
                                  std::cos(z[slot(sax)]) * std::sin(z[slot(say)]) * zdot[slot(say)]);
    const auto& contact = eq.contact_loads()[static_cast<std::size_t>(model.cage)];
    const contact::Mat3 r = cardan_rotation(z[slot(sax)], z[slot(say)], z[slot(saz)]);
    const Vec3 w_fixed = r * w, axis = r.col(2);
    const Vec3 w_across = w_fixed - w_fixed.dot(axis) * axis;
    const double contact_power = contact.force.dot(v) + contact.moment.dot(w_fixed);
    const double dissipation = support.radial_damping * (v.x() * v.x() + v.y() * v.y()) +
                               support.axial_damping * v.z() * v.z() + support.tilt_damping * w_across.squaredNorm();
    const double scale = std::abs(contact_power) + dissipation;
    EXPECT_NEAR(energy_rate, contact_power - dissipation, 1e-6 * scale)
        << "cage turned by " << k << " pockets: damper power " << dissipation << " W";
  }
}
}  // namespace
}  // namespace raceway::bearing
