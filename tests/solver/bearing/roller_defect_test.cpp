// A roller's own defect ([rolling_element] in a spatial roller bearing: spatial_roller_model.cpp,
// race_defects.cpp, spatial_dynamics.cpp):
//  1. the model: without a roller defect the rollers keep their 11 states; with one, every roller
//     gets its angle about its own axis (equal blocks), and only the defective roller's slice laws
//     carry the defect;
//  2. the angles turn with the roller: the rates the dynamics give move R = Rx Ry Rz as dR/dt =
//     [w]x R (against a finite difference of the rotation), and the axis stays R e_z of the first two;
//  3. the step limit: the roller's spall turning towards a race contact limits the step to the time
//     it takes to reach the contact's edge at the roller's spin; at the contact, a tenth of its passage;
//  4. a tapered roller's spall, turned once round with the roller seated between cone and cup, meets
//     the cone and the cup once each, half a turn apart, for as long as its length takes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "io/scene/scene_parser.hpp"
#include "solver/bearing/body_dynamics.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/race_defects.hpp"
#include "tests/support/tapered_30206_scene.hpp"
#include "solver/bearing/startup.hpp"

namespace raceway::bearing {
namespace {

using contact::Mat3;
using contact::Vec3;

constexpr const char* kScene = R"(
[scene]
end_time = "0.01 s"
output_interval = "1 ms"
model = "spatial"
[bearing]
designation = "NU205"
[inner_ring]
speed = "6000 rpm"
load = { fy = "-2000 N" }
[outer_ring]
motion = "fixed"
[contact.roller_race]
slices = 10
)";

constexpr const char* kSpall =
    "[rolling_element]\nspall = { element = 3, angle = \"30 deg\", length = \"0.5 mm\", width = \"4 mm\", depth = \"0.1 mm\" }\n";

Model model_of(const std::string& extra) { return build_model(scene::parse_scene(std::string(kScene) + extra, "test")); }

TEST(RollerDefect, SpinAngleStatesOnlyWithARollerDefect) {
  const Model plain = model_of("");
  const Model spalled = model_of(kSpall);
  EXPECT_EQ(plain.block_size, 11);
  EXPECT_EQ(spalled.block_size, 12);
  EXPECT_EQ(spalled.state_size - plain.state_size, plain.element_count);
  for (int k = 0; k < plain.element_count; ++k) {
    EXPECT_FALSE(plain.bodies[std::size_t(plain.first_element + k)].has_roller_spin_angle());
    EXPECT_TRUE(spalled.bodies[std::size_t(spalled.first_element + k)].has_roller_spin_angle());
  }
  int carrying = 0;
  for (const Segment& seg : spalled.segments) {
    if (seg.kind != SegmentKind::roller_inner_slice && seg.kind != SegmentKind::roller_outer_slice) continue;
    const auto& e = spalled.law<contact::RollerSliceSegment>(seg).roller_imperfections;
    EXPECT_EQ(e != nullptr, seg.element == 3) << seg.name;
    carrying += e != nullptr;
    if (e) {
      EXPECT_NEAR(e->spall.angle, std::numbers::pi / 6, 1e-15);
    }
  }
  EXPECT_EQ(carrying, 20);  // roller 3's 10 slices on each race
  EXPECT_TRUE(has_spall(spalled));
  EXPECT_FALSE(has_spall(plain));
}

// dR/dt = [w]x R for a tilted, skewed roller spinning about a direction off its axis.
TEST(RollerDefect, AnglesTurnWithTheRoller) {
  const Model m = model_of(kSpall);
  const int b = m.first_element + 3;
  const Body& roller = m.bodies[std::size_t(b)];
  std::vector<double> z(std::size_t(m.state_size), 0.0), zdot(z.size(), 0.0);
  const double a[3] = {0.01, -0.02, 2.0};
  const Vec3 w(15.0, -8.0, -1200.0);
  for (int d = 0; d < 3; ++d) z[std::size_t(roller.slot[sax + d])] = a[d], z[std::size_t(roller.slot[swx + d])] = w[d];
  const auto dynamics = make_body_dynamics(m);
  Wrench net;
  dynamics->rates(b, 0.0, z.data(), Wrench{}, net, zdot.data());
  const Mat3 r = cardan_rotation(a[0], a[1], a[2]);
  EXPECT_TRUE(m.kinematics(b, 0.0, z.data()).rotation.isApprox(r, 1e-15));
  EXPECT_TRUE(r.col(2).isApprox(cardan_rotation(a[0], a[1], 0.0).col(2), 1e-15));
  const double h = 1e-8;
  auto at = [&](double s) {
    const double* rate = &zdot[std::size_t(roller.slot[sax])];
    return cardan_rotation(a[0] + s * rate[0], a[1] + s * rate[1], a[2] + s * rate[2]);
  };
  const Mat3 derivative = (at(h) - at(-h)) / (2 * h);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR((derivative.col(c) - w.cross(r.col(c))).norm(), 0.0, 1e-6 * w.norm()) << c;
}

// Roller 3 at its pocket's azimuth psi on the pitch circle, aligned, spinning at w about z, its
// orbit at rest: the inner contact's frame stands still (the ring's spin and the roller's azimuth
// rate relative to the ring cancel), the outer one too. The outer contact faces e_r of psi, which in
// the roller's frame is the longitude psi - az; the spall (30 deg) trails it by 0.5 rad.
TEST(RollerDefect, StepLimitStopsAtTheContact) {
  const Model m = model_of(kSpall);
  const int b = m.first_element + 3;
  const Body& roller = m.bodies[std::size_t(b)];
  std::vector<double> z(std::size_t(m.state_size), 0.0);
  const double psi = 2 * std::numbers::pi * 3 / m.element_count, spin = 1000.0;
  z[std::size_t(roller.slot[sx])] = m.pitch_radius * std::cos(psi);
  z[std::size_t(roller.slot[sy])] = m.pitch_radius * std::sin(psi);
  z[std::size_t(roller.slot[swz])] = spin;
  const double half = 0.5 * 0.5e-3 / m.element_radius, behind = 0.5;
  z[std::size_t(roller.slot[saz])] = psi - behind - std::numbers::pi / 6;
  EXPECT_NEAR(spall_step_limit(m, 0.0, z.data()), (behind - half) / spin, 1e-12);
  z[std::size_t(roller.slot[saz])] = psi - std::numbers::pi / 6;  // the spall at the outer contact
  EXPECT_NEAR(spall_step_limit(m, 0.0, z.data()), 2 * half / spin / steps_within_spall, 1e-12);
}

// The 30206's roller 0 seated (at azimuth 0, its spall 90 degrees from both contacts), then turned
// about its axis through a whole turn in 7200 steps: the drop of its middle slice's approach (against
// the same law without the defect) on the cone and on the cup. Each is one run of turn angles, of
// the spall's angular length 0.5 mm / r (within two steps; the slice's centre sees the pit where its
// contact direction lies within it), and the two runs' centres lie half a turn apart (within two
// steps): the two contacts face each other across the roller.
TEST(RollerDefect, TaperedSpallMeetsConeAndCupOncePerTurn) {
  const std::string spall =
      "[rolling_element]\nspall = { element = 0, angle = \"90 deg\", length = \"0.5 mm\", width = \"4 mm\", "
      "depth = \"0.1 mm\" }\n";
  const Model m = build_model(scene::parse_scene(test::tapered_30206_scene("", spall), "tapered"));
  ASSERT_EQ(m.block_size, 12);
  std::vector<double> z = initial_state(m, 0.0).state;
  const Body& roller = m.bodies[std::size_t(m.first_element)];
  const double start = z[std::size_t(roller.slot[saz])];
  const int steps = 7200;
  const double step = 2 * std::numbers::pi / steps;
  std::vector<double> centres;
  for (const SegmentKind kind : {SegmentKind::roller_inner_slice, SegmentKind::roller_outer_slice}) {
    const Segment* middle = nullptr;
    for (const Segment& seg : m.segments)
      if (seg.kind == kind && seg.element == 0 && seg.name.ends_with("slice[5]")) middle = &seg;
    ASSERT_NE(middle, nullptr);
    const auto& law = m.law<contact::RollerSliceSegment>(*middle);
    ASSERT_NE(law.roller_imperfections, nullptr);
    contact::RollerSliceSegment clean = law;
    clean.roller_imperfections = nullptr;
    std::vector<int> inside;
    for (int i = 0; i < steps; ++i) {
      z[std::size_t(roller.slot[saz])] = start + i * step;
      const auto ring = m.kinematics(middle->body_a, 0.0, z.data()), body = m.kinematics(middle->body_b, 0.0, z.data());
      const double drop = contact::evaluate(clean, ring, body).diagnostics.approach -
                          contact::evaluate(law, ring, body).diagnostics.approach;
      EXPECT_GE(drop, -1e-15);
      if (drop > 1e-13) inside.push_back(i);
    }
    ASSERT_FALSE(inside.empty()) << segment_kind_name(kind) << ": the spall never met the race";
    // One contiguous run (it may wrap past the end of the turn).
    int breaks = 0;
    for (std::size_t j = 1; j < inside.size(); ++j) breaks += inside[j] != inside[j - 1] + 1;
    const bool wraps = inside.front() == 0 && inside.back() == steps - 1;
    EXPECT_EQ(breaks, wraps ? 1 : 0) << segment_kind_name(kind) << ": the spall meets the race more than once a turn";
    const double length = 0.5e-3 / law.roller_imperfections->ball_radius;
    EXPECT_NEAR(double(inside.size()) * step, length, 2 * step) << segment_kind_name(kind);
    const double centre = wraps ? 0.0 : 0.5 * (inside.front() + inside.back()) * step;
    std::printf("[ tapered spall ] %s: met over %zu steps of %d, centred at %.4f rad of turn\n",
                segment_kind_name(kind), inside.size(), steps, centre);
    centres.push_back(centre);
  }
  EXPECT_NEAR(std::abs(centres[1] - centres[0]), std::numbers::pi, 2 * step) << "cone and cup half a turn apart";
}

}  // namespace
}  // namespace raceway::bearing
