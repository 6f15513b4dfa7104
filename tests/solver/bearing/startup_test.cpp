// The consistent initial state (solver/bearing/startup.hpp) of seed 002 at 40 Hz: the inner ring in
// equilibrium under its load, every roller seated at the epicyclic orbit (its net radial force is
// the centripetal force of that orbit), rollers and cage at the epicyclic speed, pure rolling.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "contact/segments/roller_segments.hpp"
#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/startup.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::bearing {
namespace {

using test::pi;

struct StartFixture {
  scene::Scene scene;
  Model model;
  StartupReport start;
  scheduler::SerialExecutor executor;
  std::vector<double> zdot;

  explicit StartFixture(scene::Scene s) : scene(std::move(s)), model(build_model(scene)) {
    start = initial_state(model, 0.0);
    zdot.resize(start.state.size());
  }
};

/// The independent expectation: w_c = w_i * r_i / (r_i + r_o) with the race radii from the geometry
/// (outer ring fixed, inner ring driven), i.e. w_i/2 (1 - D/d_m) at zero clearance.
double epicyclic(const scene::Scene& s) {
  const double ri = 0.5 * (s.bearing.pitch_diameter - s.bearing.roller_diameter - 0.5 * s.bearing.radial_clearance);
  const double ro = 0.5 * (s.bearing.pitch_diameter + s.bearing.roller_diameter + 0.5 * s.bearing.radial_clearance);
  return s.inner_ring.speed(0.0) * ri / (ri + ro);
}

void check_start(const scene::Scene& scene_in, double radial_tolerance) {
  StartFixture f(scene_in);
  const Model& m = f.model;
  const auto& z = f.start.state;
  Equations eq(m, f.executor);
  ASSERT_EQ(eq.rhs(0.0, z.data(), f.zdot.data()), 0);

  // 1. The inner ring's net force (contacts + load + weight) vanishes.
  const double load = std::hypot(f.scene.inner_ring.load.fx(0), f.scene.inner_ring.load.fy(0));
  const auto& ring = eq.body_loads()[m.inner_ring];
  EXPECT_LT(std::hypot(ring.force.x(), ring.force.y()), 1e-6 * load)
      << "net force on the inner ring (" << ring.force.x() << ", " << ring.force.y() << ") N for a load of " << load
      << " N";
  // ... and it is not trivially so: the rollers carry the load.
  double contact_fy = 0;
  const auto& rec = eq.segment_records();
  for (std::size_t s = 0; s < m.segments.size(); ++s)
    if (m.segments[s].kind == SegmentKind::roller_inner_race) contact_fy += rec[s * SegmentRecord::size + SegmentRecord::on_a + 1];
  EXPECT_GT(contact_fy, 0.99 * load);

  // 2. Rollers at the epicyclic orbit, seated: radial acceleration -w_c^2 r, tangential velocity w_c r.
  const double wc = epicyclic(f.scene);
  EXPECT_NEAR(m.epicyclic_cage_speed(0.0), wc, 1e-12 * wc);
  double worst = 0;
  for (int k = 0; k < m.element_count; ++k) {
    const Body& b = m.bodies[m.first_element + k];
    const double x = z[b.slot[sx]], y = z[b.slot[sy]];
    const double r = std::hypot(x, y);
    const double er[2] = {x / r, y / r}, et[2] = {-y / r, x / r};
    const double ar = f.zdot[b.slot[svx]] * er[0] + f.zdot[b.slot[svy]] * er[1];
    const double expected = -wc * wc * r;
    const double rel = std::abs(ar - expected) / std::abs(expected);
    worst = std::max(worst, rel);
    EXPECT_LT(rel, radial_tolerance) << "roller " << k << " at " << std::atan2(y, x) / test::deg << " deg: radial "
                                      << "acceleration " << ar << " m/s^2, -w_c^2 r = " << expected;
    const double vt = z[b.slot[svx]] * et[0] + z[b.slot[svy]] * et[1];
    const double vr = z[b.slot[svx]] * er[0] + z[b.slot[svy]] * er[1];
    EXPECT_NEAR(vt, wc * r, 1e-9 * wc * r) << "roller " << k;
    EXPECT_NEAR(vr, 0.0, 1e-9 * wc * r) << "roller " << k;
    // Seated between the races: within the elastic approaches (~1 um) of the pitch circle.
    EXPECT_NEAR(r, m.pitch_radius, 1e-4 * m.pitch_radius);
  }
  std::printf("[ startup ] worst relative error of the roller radial accelerations: %.3g\n", worst);
  // Equal spacing: the rollers sit at the pocket pitch.
  for (int k = 0; k < m.element_count; ++k) {
    const Body& a = m.bodies[m.first_element + k];
    const Body& b = m.bodies[m.first_element + (k + 1) % m.element_count];
    const double da = test::wrap_angle(std::atan2(z[b.slot[sy]], z[b.slot[sx]]) -
                                       std::atan2(z[a.slot[sy]], z[a.slot[sx]]));
    EXPECT_NEAR(da, 2 * pi / m.element_count, 1e-9);
  }
  // Cage at the epicyclic speed.
  EXPECT_NEAR(z[m.bodies[m.cage].slot[swz]], wc, 1e-12 * wc);
}

scene::Scene seed002(bool gravity, bool damping_and_traction) {
  scene::Scene s = test::load_seed002_former_solver();
  s.gravity = gravity;
  if (!damping_and_traction) {
    for (scene::ContactSpec* c : {&s.roller_race, &s.roller_cage, &s.cage_land}) {
      c->damping.id = contact::LawId::no_damping;
      c->damping.factor = 0;
      c->traction.id = contact::LawId::no_traction;
      c->traction.friction_coefficient = 0;
    }
  }
  return s;
}

// The scene as it is (gravity, damping and traction on): ring force below 1e-6 of the load, roller
// radial accelerations within 1e-3 of -w_c^2 r (measured: 2e-8). For this the seating in
// solver/bearing/roller_startup.cpp must include, as the two tests below isolate, the rollers'
// weight (m g = 0.051 N against F_c = 1.21 N: 4.3 % at the bottom roller) and the contacts at the
// velocities of the rolling state it returns, so that Hunt-Crossley damping (approach rate w_c x ring
// offset, +-1.2 % of F_c off the load line) and traction are balanced too. Without them the net ring
// force was 0.042 N along x (4.2e-5 of the load) and the radial accelerations were off by up to 4.9 %.
TEST(Startup, Seed002At40HzIsInEquilibrium) { check_start(seed002(true, true), 1e-3); }

// Elastic contacts only, no gravity: what the seating does balance must balance to round-off.
TEST(Startup, Seed002ElasticWithoutGravityIsInEquilibrium) { check_start(seed002(false, false), 1e-3); }

// Elastic contacts only, gravity on: the rollers' weight must be part of the seating balance.
TEST(Startup, Seed002ElasticWithGravityIsInEquilibrium) { check_start(seed002(true, false), 1e-3); }

}  // namespace
}  // namespace raceway::bearing
