// The catalogue's tapered roller bearings (302 and 322 series; io/scene/catalogue_tapered.hpp,
// docs/catalogue.md "Tapered roller bearings").
//  - every tapered designation fills a scene whose geometry is consistent, checked here with the
//    meridian-plane construction written out (not the library's): the cup's and the cone's
//    raceway lines and the roller's axis meet the bearing axis at one apex, the roller touches
//    both raceways at its mean radius, neighbouring rollers (cones about the same apex) do not
//    overlap, the cup angle lies in the size's ISO 355 angle series, the roller fits the cup width;
//  - the rules' own numbers (cup angle from e or the series' middle) and the 30206 against its
//    published values and the shipped hand-estimated scene;
//  - the designation implies the type; a ball type with a tapered designation is refused;
//  - the 32206 under a combined load seats (an equilibrium of the dynamic model: every body's
//    mass times acceleration small beside the load; the cups' axial components carry the axial
//    load) and runs 0.5 ms, its rollers' mean force on the cone balancing the load.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "contact/segments/roller_slice_segment.hpp"
#include "io/scene/catalogue.hpp"
#include "io/scene/catalogue_tapered.hpp"
#include "io/scene/scene_parser.hpp"
#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/run/run.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::scene {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180;

bool is_tapered(const std::string& d) { return d.starts_with("302") || d.starts_with("322"); }

std::vector<std::string> tapered_designations() {
  std::vector<std::string> out;
  for (const std::string& d : catalogue_designations())
    if (is_tapered(d)) out.push_back(d);
  return out;
}

/// A first scene: designation, speed, a radial load of 1 N per mm^2 of bore x cone width and an
/// axial load of `axial_share` of it pushing the cone into the cup (-z).
std::string first_scene(const std::string& designation, double fr, double axial_share, const std::string& end = "1 ms",
                        const std::string& extra = "", double rpm = 3000) {
  // At rest without gravity: an unloaded roller at rest has no place to settle under its weight.
  return fmt::format("[scene]\nend_time = \"{}\"\noutput_interval = \"0.1 ms\"\ngravity = {}\n[bearing]\ndesignation = "
                     "\"{}\"\n{}[inner_ring]\nspeed = \"{:g} rpm\"\nload = {{ fy = \"{:.6g} N\", fz = \"{:.6g} N\" }}\n",
                     end, rpm > 0, designation, extra, rpm, -fr, -axial_share * fr);
}
Scene scene_of(const std::string& designation, double axial_share = 0.75, const std::string& end = "1 ms",
               double rpm = 3000) {
  const Scene plain = parse_scene(first_scene(designation, 1, axial_share), designation + ".toml");
  const double fr = 1e6 * plain.bearing.inner_bore_diameter * plain.bearing.ring_width;
  return parse_scene(first_scene(designation, fr, axial_share, end, "", rpm), designation + ".toml");
}

/// The value `check` lists for a key of the catalogue (its text).
std::string listed(const Scene& s, const std::string& key) {
  for (const CatalogueValue& v : s.catalogue)
    if (v.key == key) return v.value;
  return "";
}

TEST(TaperedCatalogue, EveryEntryFillsAConsistentGeometry) {
  const std::vector<std::string> all = tapered_designations();
  EXPECT_EQ(all.size(), 34u);  // 30203-30220, 32205-32220
  for (const std::string& d : all) {
    SCOPED_TRACE(d);
    Scene s;
    ASSERT_NO_THROW(s = scene_of(d));
    EXPECT_EQ(s.bearing.type, BearingType::tapered_roller);
    EXPECT_EQ(s.scene.model, ModelKind::spatial);
    const bearing::Model m = bearing::build_model(s);
    const double rm = m.pitch_radius, rr = 0.5 * s.bearing.roller_diameter;
    const double ao = m.cup_angle, ai = m.cone_angle, beta = 0.5 * (ao + ai), gamma = 0.5 * (ao - ai);
    ASSERT_GT(ai, 0);
    // The normals from the roller's middle (rm, 0) to the raceway lines, and where each line and
    // the roller's axis meet the bearing axis (r = 0).
    const double so = (m.outer_race_radius - rm) / std::cos(ao), si = (rm - m.inner_race_radius) / std::cos(ai);
    const double cup_apex = -so * std::sin(ao) - m.outer_race_radius / std::tan(ao);
    const double cone_apex = si * std::sin(ai) - m.inner_race_radius / std::tan(ai);
    const double axis_apex = -rm / std::tan(beta);
    EXPECT_NEAR(cup_apex, axis_apex, 1e-9 * rm);
    EXPECT_NEAR(cone_apex, axis_apex, 1e-9 * rm);
    EXPECT_LT(axis_apex, 0);
    // The roller (a cone of half angle gamma about its axis) touches both lines with its mean radius.
    EXPECT_NEAR(so, rr * std::cos(gamma), 1e-9 * rr);
    EXPECT_NEAR(si, rr * std::cos(gamma), 1e-9 * rr);
    // Neighbouring rollers, cones about one apex, do not overlap: their axes are more than 2 gamma apart.
    const int z = s.bearing.rolling_elements;
    const double between = std::acos(std::cos(beta) * std::cos(beta) +
                                     std::sin(beta) * std::sin(beta) * std::cos(2 * kPi / z));
    EXPECT_GT(between, 2 * gamma * 1.05) << z << " rollers";
    // The cup angle lies in the size's ISO 355 angle series.
    const int series = std::stoi(listed(s, "(ISO 355 angle series)"));
    const auto range = catalogue::iso355_angle_series(series);
    ASSERT_TRUE(range.has_value());
    EXPECT_GT(ao, range->lo_deg * kDeg);
    EXPECT_LE(ao, range->hi_deg * kDeg);
    // The whole roller (its axis' length and its two end faces' lean) fits the cup's width C, the
    // narrower ring; and T = the cone's and cup's widths' overlap plus the stand-out.
    double t_width = 0, c_width = 0;
    ASSERT_EQ(std::sscanf(listed(s, "(total width T, cup width C)").c_str(), "%lf mm, %lf mm", &t_width, &c_width), 2);
    c_width *= 1e-3, t_width *= 1e-3;
    const double length = s.bearing.roller_length + 2 * s.bearing.roller.corner_radius;
    const double apex = rm / std::sin(beta);
    const double r_small = (apex - 0.5 * length) * std::tan(gamma), r_large = (apex + 0.5 * length) * std::tan(gamma);
    const double extent = length * std::cos(beta) + (r_small + r_large) * std::sin(beta);
    EXPECT_LT(extent, c_width);
    EXPECT_LT(c_width, s.bearing.ring_width);
    EXPECT_LT(s.bearing.ring_width, t_width);
    // The rings keep a wall under and over the rollers.
    EXPECT_LT(s.bearing.inner_bore_diameter, 2 * m.inner_race_radius - 2 * length * std::sin(ai));
    EXPECT_GT(s.bearing.outer_outside_diameter, 2 * m.outer_race_radius + 2 * length * std::sin(ao));
  }
}

TEST(TaperedCatalogue, RulesGiveTheirNumbers) {
  using catalogue::TaperedBoundary;
  // The cup angle: atan(e / 1.5) of a published e (0.37: 13.86 deg), else the series' middle.
  EXPECT_DOUBLE_EQ(catalogue::estimated_cup_angle(TaperedBoundary{.angle_series = 3, .published_e = 0.37}), 14.0);
  EXPECT_DOUBLE_EQ(catalogue::estimated_cup_angle(TaperedBoundary{.angle_series = 2, .published_e = std::nullopt}), 12.0);  // 10 .. 13.87
  EXPECT_DOUBLE_EQ(catalogue::estimated_cup_angle(TaperedBoundary{.angle_series = 3, .published_e = std::nullopt}), 15.0);  // 13.87 .. 15.98
  EXPECT_DOUBLE_EQ(catalogue::estimated_cup_angle(TaperedBoundary{.angle_series = 4, .published_e = std::nullopt}), 17.5);  // 15.98 .. 18.92
  EXPECT_THROW((void)catalogue::estimated_cup_angle(TaperedBoundary{.angle_series = 8, .published_e = std::nullopt}), std::invalid_argument);
  // The angle series meet end to end (ISO 355: 10 deg to 30 deg).
  for (int k = 2; k < 7; ++k)
    EXPECT_DOUBLE_EQ(catalogue::iso355_angle_series(k)->hi_deg, catalogue::iso355_angle_series(k + 1)->lo_deg);
  EXPECT_DOUBLE_EQ(catalogue::iso355_angle_series(2)->lo_deg, 10.0);
  EXPECT_DOUBLE_EQ(catalogue::iso355_angle_series(7)->hi_deg, 30.0);
  // 30206 (30 x 62 mm, C = 14 mm): 0.234 x 32 = 7.49 -> 7.5 mm; pi 46 / (1.13 x 7.5) = 17.05 -> 17.
  const catalogue::TaperedEstimate t = catalogue::estimate_tapered({30, 62, 17.25, 16, 14, 3, 0.37});
  EXPECT_DOUBLE_EQ(t.pitch_diameter, 46);
  EXPECT_DOUBLE_EQ(t.roller_diameter, 7.5);
  EXPECT_EQ(t.rollers, 17);
  EXPECT_DOUBLE_EQ(t.roller_length, 9.7);  // 0.69 x 14 = 9.66
  EXPECT_DOUBLE_EQ(t.corner_radius, 0.6);
  EXPECT_DOUBLE_EQ(t.pocket_clearance, 0.3);
}

// The 30206: ISO 355 boundary dimensions, SKF's published e, C and C_0, and the hand-estimated
// jobs/scenes/30206_tapered.toml, which the catalogue repeats except for the roller length.
TEST(TaperedCatalogue, The30206AgainstItsSourcesAndTheShippedScene) {
  const Scene s = scene_of("30206");
  EXPECT_DOUBLE_EQ(s.bearing.inner_bore_diameter, 30e-3);
  EXPECT_DOUBLE_EQ(s.bearing.outer_outside_diameter, 62e-3);
  EXPECT_DOUBLE_EQ(s.bearing.ring_width, 16e-3);
  EXPECT_EQ(listed(s, "(total width T, cup width C)"), "17.25 mm, 14 mm");
  EXPECT_EQ(listed(s, "(e, Y)"), "0.37, 1.6");
  EXPECT_DOUBLE_EQ(s.life.dynamic_load_rating, 40.2e3);
  EXPECT_DOUBLE_EQ(s.life.static_load_rating, 44e3);
  EXPECT_TRUE(std::isnan(scene_of("30207").life.dynamic_load_rating));  // no published rating: left out
  const Scene shipped = load_scene(std::string(RACEWAY_SOURCE_DIR) + "/jobs/scenes/30206_tapered.toml");
  EXPECT_EQ(s.bearing.rolling_elements, shipped.bearing.rolling_elements);
  EXPECT_NEAR(s.bearing.roller_diameter, shipped.bearing.roller_diameter, 1e-12);
  EXPECT_NEAR(s.bearing.pitch_diameter, shipped.bearing.pitch_diameter, 1e-12);
  EXPECT_NEAR(s.bearing.roller.cup_angle, shipped.bearing.roller.cup_angle, 1e-12);
  EXPECT_NEAR(s.bearing.roller.corner_radius, shipped.bearing.roller.corner_radius, 1e-12);
  EXPECT_NEAR(s.bearing.roller.end_radius, shipped.bearing.roller.end_radius, 1e-12);
  EXPECT_NEAR(s.bearing.roller.rib_angle, shipped.bearing.roller.rib_angle, 1e-12);
  EXPECT_NEAR(s.cage.pocket_clearance, shipped.cage.pocket_clearance, 1e-12);
  EXPECT_EQ(s.cage.guidance, shipped.cage.guidance);
  EXPECT_NEAR(s.bearing.roller_length, 9.7e-3, 1e-12);  // the shipped scene's 12 mm rates 20 % above C
  EXPECT_NEAR(shipped.bearing.roller_length, 12e-3, 1e-12);
}

TEST(TaperedCatalogue, TheDesignationImpliesTheTypeAndABallTypeIsRefused) {
  const Scene s = scene_of("32210");
  EXPECT_EQ(s.bearing.type, BearingType::tapered_roller);
  EXPECT_NO_THROW((void)parse_scene(first_scene("30208", 1000, 0.5, "1 ms", "type = \"tapered_roller\"\n"), "t.toml"));
  try {
    (void)parse_scene(first_scene("30208", 1000, 0.5, "1 ms", "type = \"deep_groove_ball\"\n"), "t.toml");
    FAIL() << "a ball type with a tapered designation was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "bearing.type");
    EXPECT_EQ(e.line(), 7);
    EXPECT_NE(e.reason().find("the 30208 is a tapered_roller bearing"), std::string::npos) << e.what();
  }
}

/// Every body's mass times acceleration (N) at a state: an equilibrium has none.
double largest_inertia_force(const bearing::Model& m, const std::vector<double>& state) {
  scheduler::SerialExecutor executor;
  bearing::Equations eq(m, executor);
  std::vector<double> zdot(static_cast<std::size_t>(m.state_size));
  eq.rhs(0.0, state.data(), zdot.data());
  double worst = 0;
  for (const bearing::Body& body : m.bodies) {
    if (body.kind == bearing::BodyKind::cage) continue;
    for (int c = bearing::svx; c <= bearing::svz; ++c)
      if (body.slot[c] >= 0) worst = std::max(worst, body.mass * std::abs(zdot[static_cast<std::size_t>(body.slot[c])]));
  }
  return worst;
}

/// The cup slices' normal forces at a state, per roller: their sum's axial component, and how many
/// rollers carry more than a twentieth of the largest roller load.
double cup_axial_force(const bearing::Model& m, const std::vector<double>& z, int& loaded) {
  std::vector<double> per_roller(static_cast<std::size_t>(m.element_count), 0.0);
  for (const bearing::Segment& seg : m.segments) {
    if (seg.kind != bearing::SegmentKind::roller_outer_slice) continue;
    const auto ring = m.kinematics(seg.body_a, 0.0, z.data()), roller = m.kinematics(seg.body_b, 0.0, z.data());
    per_roller[static_cast<std::size_t>(seg.element)] +=
        contact::evaluate(m.law<contact::RollerSliceSegment>(seg), ring, roller).diagnostics.normal_force;
  }
  double sum = 0;
  loaded = 0;
  const double largest = *std::max_element(per_roller.begin(), per_roller.end());
  for (const double q : per_roller) sum += q, loaded += q > 0.05 * largest;
  return sum * std::sin(m.cup_angle);
}

TEST(TaperedCatalogue, The32206SeatsAndRunsUnderACombinedLoad) {
  const Scene s = scene_of("32206", 0.35, "0.5 ms");  // Fr 600 N, Fa 210 N
  const double fr = 600, fa = 210;
  ASSERT_NEAR(-s.inner_ring.load.fy.values.at(0), fr, 1e-9);
  // At rest (and without gravity) the seating is a static equilibrium; turning, the rollers' orbit
  // needs a centripetal force.
  const bearing::Model m = bearing::build_model(scene_of("32206", 0.35, "0.5 ms", 0));
  const bearing::StartupReport start = bearing::initial_state(m, 0.0);
  int loaded = 0;
  const double axial = cup_axial_force(m, start.state, loaded);
  EXPECT_NEAR(axial, fa, 0.01 * fa);
  EXPECT_GT(loaded, 3);
  EXPECT_LT(loaded, m.element_count);  // a load zone: Fa / Fr = 0.5 leaves rollers unloaded
  const double inertia = largest_inertia_force(m, start.state);
  EXPECT_LT(inertia, 1e-3 * fr);
  test::TempDir dir;
  run::RunOptions options;
  options.output_path = dir.file("32206.h5");
  const run::RunSummary sum = run_scene(s, options);  // turning at 3000 rpm
  EXPECT_NEAR(sum.simulated_time_s, 0.5e-3, 1e-12);
  ASSERT_EQ(sum.inner_ring_contact_force_n.size(), 3u);
  double residual2 = 0;
  const double weight = m.bodies.at(0).mass * 9.80665;
  for (std::size_t k = 0; k < 3; ++k) {
    const double r = sum.inner_ring_contact_force_n[k] + sum.inner_ring_load_n[k] - (k == 1 ? weight : 0.0);
    residual2 += r * r;
  }
  std::printf("[ tapered catalogue ] 32206: %d rollers, %d loaded at the seating, cup axial %.2f N (Fa %.0f N), "
              "largest m a %.3g N; 0.5 ms in %ld steps, %.2f s wall; balance residual %.3g N\n",
              m.element_count, loaded, axial, fa, inertia, sum.stats.steps, sum.wall_time_s, std::sqrt(residual2));
  EXPECT_LT(std::sqrt(residual2), 0.02 * std::hypot(fr, fa));
}

}  // namespace
}  // namespace raceway::scene
