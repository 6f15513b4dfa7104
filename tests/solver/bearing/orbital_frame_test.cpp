// The balls' in-plane velocities in their orbital frame ([solver] element_velocity_frame =
// "orbital", solver/bearing/orbital_frame.hpp): the same physics as the bearing frame's states.
//  - at one state: the start-up's physical state, every rate but the balls' velocity rates, the
//    energy and the output's acceleration equal the bearing frame's to round-off, and the balls'
//    v_r', v_theta' equal the time derivatives of (x vx + y vy) / r and (x vy - y vx) / r along the
//    bearing frame's motion (central differences in time: independent of the frame's formulas);
//  - a short run in both frames at a tight tolerance: the same trajectory to the integration's error
//    (against a tighter run);
//  - the radial velocity tolerance factor scales v_r's absolute tolerance alone.
// (The Jacobian in the orbital frame: spatial_newton_test; the pocket factor on v_theta alone:
// pocket_tolerance_test.)
//  - without damping and traction the energy is conserved as in the bearing frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/numerics/integrator.hpp"
#include "tests/support/engaged_bearing.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::bearing {
namespace {

using contact::Vec3;
using test::EngagedBearing;
constexpr auto orbital = scene::ElementVelocityFrame::orbital;

/// A body's velocity states (vz 0 where it is none).
Vec3 state_velocity(const Body& body, const std::vector<double>& z) {
  Vec3 v = Vec3::Zero();
  for (int d = 0; d < 3; ++d)
    if (body.slot[svx + d] >= 0) v[d] = z[static_cast<std::size_t>(body.slot[svx + d])];
  return v;
}

/// The bearing model's state z as the orbital model's states (the balls' velocities turned).
std::vector<double> as_orbital(const Model& orbital_model, const Model& bearing_model, const std::vector<double>& z) {
  std::vector<double> out = z;
  for (int k = 0; k < bearing_model.element_count; ++k) {
    const Body& body = bearing_model.bodies[static_cast<std::size_t>(bearing_model.first_element + k)];
    orbital_model.set_velocity(body.index + bearing_model.first_element, state_velocity(body, z), out.data());
  }
  return out;
}

/// v_r and v_theta of ball b from the bearing frame's states, written out here.
Vec3 orbital_velocity(const Body& ball, const std::vector<double>& z) {
  const double x = z[static_cast<std::size_t>(ball.slot[sx])], y = z[static_cast<std::size_t>(ball.slot[sy])];
  const Vec3 v = state_velocity(ball, z);
  const double r = std::sqrt(x * x + y * y);
  return {(x * v.x() + y * v.y()) / r, (x * v.y() - y * v.x()) / r, v.z()};
}

/// At the same physical state zc (bearing model) and its orbital states: the energy, every rate but
/// the rolling elements' velocity rates equal to round-off; those equal the time derivatives of
/// v_r, v_theta along the bearing frame's motion, and Model::acceleration gives the bearing frame's.
void check_rates(Equations& ce, const Model& mc, Equations& oe, const Model& mo, double t, const std::vector<double>& zc) {
  const std::vector<double> zo = as_orbital(mo, mc, zc);
  std::vector<double> fc(zc.size()), fo(zc.size());
  ASSERT_EQ(ce.rhs(t, zc.data(), fc.data()), 0);
  ASSERT_EQ(oe.rhs(t, zo.data(), fo.data()), 0);
  EXPECT_NEAR(oe.energy(t, zo.data()), ce.energy(t, zc.data()), 1e-12 * std::abs(ce.energy(t, zc.data())));
  double largest[4] = {0, 0, 0, 0};  // per class, for the round-off scale
  for (std::size_t i = 0; i < fc.size(); ++i)
    largest[static_cast<int>(mc.state_class[i])] = std::max(largest[static_cast<int>(mc.state_class[i])], std::abs(fc[i]));
  const double a_scale = largest[static_cast<int>(VariableClass::velocity)];
  for (std::size_t i = 0; i < fc.size(); ++i) {
    const bool element_velocity = static_cast<int>(i) >= mc.border_size && mc.state_class[i] == VariableClass::velocity;
    if (element_velocity) continue;  // below
    // The positions' rates: the velocity itself; the rest: the same forces.
    EXPECT_NEAR(fo[i], fc[i], 1e-9 * largest[static_cast<int>(mc.state_class[i])]) << mc.state_name[i];
  }
  // The velocity rates: d/dt of v_r, v_theta along the bearing frame's motion, by central
  // differences over +-h along its rates (h: 1 ns, a few nm of the orbit).
  const double h = 1e-9;
  std::vector<double> ahead = zc, behind = zc;
  for (std::size_t i = 0; i < zc.size(); ++i) ahead[i] += h * fc[i], behind[i] -= h * fc[i];
  double worst = 0;
  for (int k = 0; k < mc.element_count; ++k) {
    const Body& element = mc.bodies[static_cast<std::size_t>(mc.first_element + k)];
    const Vec3 expected = (orbital_velocity(element, ahead) - orbital_velocity(element, behind)) / (2 * h);
    worst = std::max(worst, (state_velocity(element, fo) - expected).norm() / a_scale);
    // The output's acceleration (bearing frame) from the orbital rates: the bearing frame's rates.
    const Vec3 a = mo.acceleration(mc.first_element + k, zo.data(), fo.data());
    EXPECT_LT((a - state_velocity(element, fc)).norm(), 1e-9 * a_scale) << "element " << k;
  }
  std::printf("[ orbital ] %s: velocity rates against d/dt (v_r, v_theta, vz): worst %.3g of the largest "
              "acceleration (%.4g m/s^2)\n",
              mc.params().scene_name.c_str(), worst, a_scale);
  EXPECT_LT(worst, 1e-7);
}

// The start-up seats the balls and sets their rolling velocities in the frame of the states: the
// same physical state. At the engaged state (pockets, land and grooves closed) the rates agree.
TEST(OrbitalFrame, SameStartRatesAndEnergyAsTheBearingFrame) {
  EngagedBearing cart, orb(0.0, orbital);
  const Model& mc = cart.model;
  const Model& mo = orb.model;
  ASSERT_TRUE(mo.orbital_velocities);
  ASSERT_EQ(mo.state_size, mc.state_size);
  // Start: the same positions, spins, cage and ring states; each ball's velocity the same vector.
  for (int k = 0; k < mc.element_count; ++k) {
    const int b = mc.first_element + k;
    const auto kc = mc.kinematics(b, 0.0, cart.start.data()), ko = mo.kinematics(b, 0.0, orb.start.data());
    EXPECT_LT((kc.position - ko.position).norm(), 1e-15) << "ball " << k;
    EXPECT_LT((kc.velocity - ko.velocity).norm(), 1e-12 * kc.velocity.norm()) << "ball " << k;
    EXPECT_LT((kc.angular_velocity - ko.angular_velocity).norm(), 1e-12 * kc.angular_velocity.norm()) << "ball " << k;
  }
  for (int i = 0; i < mc.border_size; ++i)
    EXPECT_EQ(cart.start[static_cast<std::size_t>(i)], orb.start[static_cast<std::size_t>(i)]) << mc.state_name[i];

  check_rates(cart.eq, mc, orb.eq, mo, 0.0, cart.engaged);
}

// The planar roller bearings: the start-up's rollers and, 10 ms into the bearing frame's run, the
// rates; seed 002 at 40 Hz (rollers on the bars) and seed 003 on its planet carrier (the carrier
// frame's Coriolis force takes the rollers' velocities in the bearing frame).
class PlanarRollers : public ::testing::TestWithParam<const char*> {};
TEST_P(PlanarRollers, SameStartAndRatesInTheOrbitalFrame) {
  // Seed 002 ships the orbital frame: its former solver (the bearing frame) is the comparison's.
  scene::Scene s = std::string(GetParam()) == "seed002_40hz.toml" ? test::load_seed002_former_solver()
                                                                  : test::load_job_scene(GetParam());
  ASSERT_EQ(s.solver.element_velocity_frame, scene::ElementVelocityFrame::bearing);
  const Model mc = build_model(s);
  s.solver.element_velocity_frame = orbital;
  const Model mo = build_model(s);
  ASSERT_TRUE(mo.orbital_velocities);
  scheduler::SerialExecutor ec, eo;
  Equations ce(mc, ec), oe(mo, eo);
  const std::vector<double> start_c = initial_state(mc, 0.0).state, start_o = initial_state(mo, 0.0).state;
  for (int k = 0; k < mc.element_count; ++k) {
    const auto kc = mc.planar_kinematics(mc.first_element + k, 0.0, start_c.data());
    const auto ko = mo.planar_kinematics(mo.first_element + k, 0.0, start_o.data());
    EXPECT_EQ(kc.x, ko.x);
    EXPECT_EQ(kc.y, ko.y);
    EXPECT_EQ(kc.omega, ko.omega);
    EXPECT_NEAR(ko.vx, kc.vx, 1e-12 * std::hypot(kc.vx, kc.vy)) << "roller " << k;
    EXPECT_NEAR(ko.vy, kc.vy, 1e-12 * std::hypot(kc.vx, kc.vy)) << "roller " << k;
  }
  numerics::Integrator integrator(ce, s.solver, 0.0, start_c);
  std::vector<double> z;
  integrator.advance_to(0.01, z);
  check_rates(ce, mc, oe, mo, 0.01, z);
}
INSTANTIATE_TEST_SUITE_P(OrbitalFrame, PlanarRollers, ::testing::Values("seed002_40hz.toml", "seed003_planet_carrier.toml"));

/// The run of EngagedBearing from its start to t_end at rtol: every ball's position and velocity
/// (bearing frame) and the inner ring's centre at the end.
struct RunEnd {
  std::vector<Vec3> position, velocity;
  Vec3 ring = Vec3::Zero();
  double pitch_radius = 0;
  long steps = 0;
};
RunEnd run(scene::ElementVelocityFrame frame, double rtol, double t_end) {
  EngagedBearing b(0.0, frame);
  b.scene.solver.rtol = rtol;
  numerics::Integrator integrator(b.eq, b.scene.solver, 0.0, b.start);
  std::vector<double> z;
  integrator.advance_to(t_end, z);
  RunEnd out;
  for (int k = 0; k < b.model.element_count; ++k) {
    const auto kin = b.model.kinematics(b.model.first_element + k, t_end, z.data());
    out.position.push_back(kin.position), out.velocity.push_back(kin.velocity);
  }
  out.ring = b.model.kinematics(b.model.inner_ring, t_end, z.data()).position;
  out.pitch_radius = b.model.pitch_radius;
  out.steps = integrator.statistics().steps;
  return out;
}

/// Largest distance of p from q: balls' positions (m), velocities (m/s), the inner ring's centre (m).
struct Gap {
  double position = 0, velocity = 0, ring = 0;
};
Gap gap(const RunEnd& p, const RunEnd& q) {
  Gap g;
  for (std::size_t k = 0; k < p.position.size(); ++k) {
    g.position = std::max(g.position, (p.position[k] - q.position[k]).norm());
    g.velocity = std::max(g.velocity, (p.velocity[k] - q.velocity[k]).norm());
  }
  g.ring = (p.ring - q.ring).norm();
  return g;
}

// 5 ms of the combined-load run (the balls through the load zone) in both frames at rtol 1e-9,
// against the bearing frame at 1e-11. The orbital run integrates the same equations in other
// coordinates: its error is the integration's, of the bearing frame's own error's size (within 3
// times it). Measured: bearing frame 1.2e-8 m, 8.2e-4 m/s (the balls' nearly undamped contact
// vibration, whose phase the global error follows), ring 3.9e-10 m; orbital 6.5e-9 m, 1.9e-4 m/s,
// 1.3e-10 m. (A wrong turning term moves a ball by its orbit's curvature: millimetres in 5 ms.)
TEST(OrbitalFrame, SameTrajectoryAsTheBearingFrame) {
  const double t_end = 5e-3, rtol = 1e-9;
  const RunEnd tight = run(scene::ElementVelocityFrame::bearing, 1e-11, t_end);
  const RunEnd cart = run(scene::ElementVelocityFrame::bearing, rtol, t_end);
  const RunEnd orb = run(orbital, rtol, t_end);
  const Gap e_cart = gap(cart, tight), e_orb = gap(orb, tight);
  double speed = 0;
  for (const Vec3& v : tight.velocity) speed = std::max(speed, v.norm());
  std::printf("[ orbital ] t = 5 ms, rtol 1e-9, against rtol 1e-11: bearing frame %.3g m, %.3g m/s, ring %.3g m "
              "(%ld steps); orbital frame %.3g m, %.3g m/s, ring %.3g m (%ld steps)\n",
              e_cart.position, e_cart.velocity, e_cart.ring, cart.steps, e_orb.position, e_orb.velocity, e_orb.ring,
              orb.steps);
  EXPECT_LT(e_orb.position, 3 * e_cart.position + rtol * tight.pitch_radius);
  EXPECT_LT(e_orb.velocity, 3 * e_cart.velocity + rtol * speed);
  EXPECT_LT(e_orb.ring, 3 * e_cart.ring + rtol * tight.pitch_radius);
}

/// Largest |E(t) - E(0)| / E(0) over 50 samples of `t_end` of the combined-load bearing with damping
/// and traction off in every contact (conservative: the driven ring's spin does no work without
/// traction, the loads are constant; energy_test), at rtol 1e-8.
double energy_drift(scene::ElementVelocityFrame frame, double t_end) {
  scene::Scene s = EngagedBearing::make_scene(0.0, frame);
  for (scene::ContactSpec* c : {&s.ball_race, &s.ball_cage, &s.cage_land}) {
    c->damping.id = contact::LawId::no_damping, c->damping.factor = 0;
    c->traction.id = contact::LawId::no_traction, c->traction.friction_coefficient = 0;
  }
  s.solver.rtol = 1e-8;
  const Model m = build_model(s);
  scheduler::SerialExecutor executor;
  Equations eq(m, executor);
  const std::vector<double> start = initial_state(m, 0.0).state;
  std::vector<double> z = start, f(start.size());
  eq.rhs(0.0, z.data(), f.data());
  const double e0 = eq.energy(0.0, z.data());
  numerics::Integrator integrator(eq, s.solver, 0.0, start);
  double drift = 0;
  for (int i = 1; i <= 50; ++i) {
    const double t = t_end * i / 50;
    integrator.advance_to(t, z);
    eq.rhs(t, z.data(), f.data());
    drift = std::max(drift, std::abs(eq.energy(t, z.data()) - e0) / e0);
  }
  return drift;
}

// The orbital frame's equations conserve the energy as the bearing frame's do: its drift no more
// than twice the bearing frame's (the integrators' errors differ) and below 1e-7 of E0.
TEST(OrbitalFrame, ConservesEnergyWithoutDampingAndTraction) {
  const double t_end = 5e-3;
  const double cart = energy_drift(scene::ElementVelocityFrame::bearing, t_end);
  const double orb = energy_drift(orbital, t_end);
  std::printf("[ orbital ] energy drift over 5 ms at rtol 1e-8: bearing frame %.3g, orbital frame %.3g of E0\n", cart, orb);
  EXPECT_LT(orb, std::max(2 * cart, 1e-9));
  EXPECT_LT(orb, 1e-7);
}

TEST(OrbitalFrame, RadialToleranceFactorScalesVrAlone) {
  scene::Scene s = EngagedBearing::make_scene(0.0, orbital);
  const std::vector<double> plain = build_model(s).absolute_tolerance();
  s.solver.radial_velocity_tolerance_factor = 3;
  const Model m = build_model(s);
  const std::vector<double> loose = m.absolute_tolerance();
  for (std::size_t i = 0; i < plain.size(); ++i) {
    const Body* owner = nullptr;
    for (const Body& b : m.bodies)
      if (static_cast<int>(i) >= b.offset && static_cast<int>(i) < b.offset + b.size) owner = &b;
    const bool radial = owner && owner->kind == BodyKind::rolling_element && static_cast<int>(i) == owner->slot[svx];
    EXPECT_EQ(loose[i], radial ? 3 * plain[i] : plain[i]) << m.state_name[i];
  }
  EXPECT_EQ(m.state_name[static_cast<std::size_t>(m.bodies[static_cast<std::size_t>(m.first_element)].slot[svx])],
            "ball[0].v_r");
}

}  // namespace
}  // namespace raceway::bearing
