// The bearing catalogue (io/scene/catalogue.hpp, docs/catalogue.md).
//  - Catalogue.*: every designation gives a scene that passes what `raceway check` does (parse, build
//    the model, estimate the output); the values land where the catalogue's sources put them (ISO 15
//    boundary dimensions, published internal geometry); the scene overrides any value; an unknown
//    designation or a contradicting type is refused with file, line, key and reason.
//  - CatalogueRun/<designation>: the first scene of a user (designation, speed, load and nothing
//    else) runs 2 inner-ring revolutions: the cage turns near its epicyclic speed, its centre
//    metrics (vortex radius ratio, velocity deviation ratio) are finite, the pockets are touched,
//    and the time mean of the rolling elements' force on the inner ring balances the applied load
//    and the ring's weight (the ring's mean acceleration over the window is small).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "io/scene/catalogue.hpp"
#include "io/scene/scene_parser.hpp"
#include "solver/bearing/model.hpp"
#include "solver/run/output_writer.hpp"
#include "solver/run/run.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::scene {
namespace {

constexpr double kSpeedRpm = 3000;
constexpr double kGravity = 9.80665;

bool is_angular(const std::string& d) { return d.back() == 'B'; }
bool is_four_point(const std::string& d) { return d.starts_with("QJ"); }
bool is_tapered(const std::string& d) { return d.starts_with("302") || d.starts_with("322"); }

/// Radial load 1 N per mm^2 of bore times width (80 N for the 6000, 1875 N for the QJ215); angular
/// contact bearings carry 1.5 times it axially (all balls loaded at 40 deg), four-point ones 2 times,
/// tapered ones 0.75 times it pushing the cone into the cup (-z).
struct Loads {
  double fy = 0, fz = 0;
};
Loads loads_for(const scene::Scene& catalogue_scene, const std::string& d) {
  const double fr = 1e6 * catalogue_scene.bearing.inner_bore_diameter * catalogue_scene.bearing.ring_width;
  return {-fr, is_angular(d) ? 1.5 * fr : is_four_point(d) ? 2 * fr : is_tapered(d) ? -0.75 * fr : 0.0};
}

/// The first scene a user writes: a designation, a speed and a load.
std::string first_scene(const std::string& designation, const Loads& l, const std::string& extra = "") {
  std::string load = fmt::format("fy = \"{:.6g} N\"", l.fy);
  if (l.fz != 0) load += fmt::format(", fz = \"{:.6g} N\"", l.fz);
  return fmt::format(
      "[scene]\nend_time = \"40 ms\"\noutput_interval = \"0.2 ms\"\n[bearing]\ndesignation = \"{}\"\n{}"
      "[inner_ring]\nspeed = \"{} rpm\"\nload = {{ {} }}\n",
      designation, extra, kSpeedRpm, load);
}

scene::Scene scene_of(const std::string& designation, const std::string& extra = "") {
  const scene::Scene plain = scene::parse_scene(first_scene(designation, {-1, 0}, extra), designation + ".toml");
  return scene::parse_scene(first_scene(designation, loads_for(plain, designation), extra), designation + ".toml");
}

TEST(Catalogue, EveryBearingPassesCheck) {
  const std::vector<std::string> all = scene::catalogue_designations();
  EXPECT_GE(all.size(), 36u);
  for (const std::string& d : all) {
    SCOPED_TRACE(d);
    scene::Scene scene;
    ASSERT_NO_THROW(scene = scene_of(d));
    const bearing::Model model = bearing::build_model(scene);
    const run::OutputEstimate estimate = run::estimate_output(model, scene);
    EXPECT_NO_THROW(check_output_size(estimate, scene));
    EXPECT_EQ(model.element_count, scene.bearing.rolling_elements);
    EXPECT_FALSE(scene::describe_catalogue_values(scene).empty());
    // The boundary dimensions hold the elements: bore < inner race, outer race < outside diameter.
    EXPECT_LT(scene.bearing.inner_bore_diameter, scene.bearing.inner_race_diameter());
    EXPECT_GT(scene.bearing.outer_outside_diameter, scene.bearing.outer_race_diameter());
  }
}

// ISO 15 gives the 6205 25 x 52 x 15 mm; the CWRU data set publishes 9 balls of 0.3126 in on a
// 1.537 in pitch circle; CN clearance for a 25 mm bore is 5-20 um (its middle: 12.5 um).
TEST(Catalogue, ValuesComeFromTheirSources) {
  const scene::Scene s = scene_of("6205");
  EXPECT_DOUBLE_EQ(s.bearing.inner_bore_diameter, 25e-3);
  EXPECT_DOUBLE_EQ(s.bearing.outer_outside_diameter, 52e-3);
  EXPECT_DOUBLE_EQ(s.bearing.ring_width, 15e-3);
  EXPECT_EQ(s.bearing.rolling_elements, 9);
  EXPECT_NEAR(s.bearing.ball.ball_diameter, 0.3126 * 25.4e-3, 1e-6);
  EXPECT_NEAR(s.bearing.pitch_diameter, 1.537 * 25.4e-3, 1e-6);
  EXPECT_NEAR(s.bearing.radial_clearance, 12.5e-6, 1e-12);
  EXPECT_EQ(s.bearing.type, scene::BearingType::deep_groove_ball);
  EXPECT_TRUE(s.gravity);
  EXPECT_GT(s.lubricant.viscosity, 0);
  // SKF's published load ratings fill [life]; a bearing without published ones leaves it empty.
  EXPECT_DOUBLE_EQ(s.life.dynamic_load_rating, 14.8e3);
  EXPECT_DOUBLE_EQ(s.life.static_load_rating, 7.8e3);
  EXPECT_DOUBLE_EQ(s.life.fatigue_load_limit, 335);
  EXPECT_TRUE(std::isnan(s.life.contamination_factor));
  EXPECT_TRUE(std::isnan(scene_of("6206").life.dynamic_load_rating));
  // The QJ215 of seed 001 (Table 1): 15 balls of 17.462 mm, 27 um clearance, arcs at 35 deg.
  const scene::Scene qj = scene_of("QJ215");
  EXPECT_EQ(qj.bearing.rolling_elements, 15);
  EXPECT_NEAR(qj.bearing.ball.ball_diameter, 17.462e-3, 1e-9);
  EXPECT_NEAR(qj.bearing.radial_clearance, 27e-6, 1e-12);
  EXPECT_NEAR(qj.bearing.ball.arc_contact_angle, 35 * test::deg, 1e-12);
  // 72..B: the B suffix is a 40 deg contact angle.
  EXPECT_NEAR(scene_of("7206B").bearing.ball.free_contact_angle, 40 * test::deg, 1e-12);
  // The roller bearings are planar models.
  EXPECT_EQ(scene_of("NU206").scene.model, scene::ModelKind::planar);
}

TEST(Catalogue, TheSceneOverridesAnyValue) {
  const scene::Scene s = scene_of("6205", "ball_diameter = \"8 mm\"\nradial_clearance = \"30 um\"\n[cage]\n"
                                       "guidance = \"outer_land\"\npocket_shape = \"cylindrical\"\n");
  EXPECT_DOUBLE_EQ(s.bearing.ball.ball_diameter, 8e-3);
  EXPECT_NEAR(s.bearing.radial_clearance, 30e-6, 1e-12);
  EXPECT_EQ(s.cage.guidance, scene::CageGuidance::outer_land);
  EXPECT_GT(s.cage.land_clearance, 0);  // the catalogue's, because the scene's guidance needs one
  int given = 0;
  for (const scene::CatalogueValue& v : s.catalogue) given += v.given;
  EXPECT_EQ(given, 4);
  // A published rating the scene gives replaces the catalogue's.
  const scene::Scene rated = scene_of("6205", "[life]\ndynamic_load_rating = \"15 kN\"\n");
  EXPECT_DOUBLE_EQ(rated.life.dynamic_load_rating, 15e3);
  EXPECT_DOUBLE_EQ(rated.life.static_load_rating, 7.8e3);
  EXPECT_NE(scene::describe_catalogue_values(s).find("given by the scene"), std::string::npos);
  // An angular contact bearing given by its groove clearance: the catalogue's 40 deg stands back.
  const scene::Scene ac = scene_of("7206B", "radial_clearance = \"30 um\"\n");
  EXPECT_NEAR(ac.bearing.radial_clearance, 30e-6, 1e-12);
  EXPECT_LT(ac.bearing.ball.free_contact_angle, 40 * test::deg);
}

TEST(Catalogue, UnknownDesignationOrContradictingTypeIsRefused) {
  try {
    (void)scene::parse_scene("[scene]\nend_time = \"1 s\"\noutput_interval = \"0.2 ms\"\n[bearing]\ndesignation = "
                          "\"6206x\"\n",
                          "bad.toml");
    FAIL() << "an unknown designation was accepted";
  } catch (const scene::SceneError& e) {
    EXPECT_EQ(e.key(), "bearing.designation");
    EXPECT_EQ(e.line(), 5);
    EXPECT_NE(e.reason().find("did you mean '6206'"), std::string::npos) << e.what();
  }
  // A designation that is not a string, and sections that are not tables beside a designation: the
  // reader's errors, never a crash.
  for (const std::string& text :
       {std::string("[bearing]\ndesignation = 6205\n"), std::string("cage = 3\n[bearing]\ndesignation = \"6205\"\n"),
        std::string("outer_ring = 1\nlubricant = \"oil\"\n[bearing]\ndesignation = \"6205\"\n")})
    EXPECT_THROW((void)scene::parse_scene(text, "odd.toml"), scene::SceneError) << text;
  try {
    (void)scene_of("6205", "type = \"angular_contact_ball\"\n");
    FAIL() << "a type contradicting the designation was accepted";
  } catch (const scene::SceneError& e) {
    EXPECT_EQ(e.key(), "bearing.type");
    EXPECT_NE(e.reason().find("deep_groove_ball"), std::string::npos) << e.what();
  }
}

class CatalogueRun : public ::testing::TestWithParam<std::string> {};

TEST_P(CatalogueRun, TwoRevolutionsWithFiniteCageMetricsAndBalancedLoads) {
  const std::string d = GetParam();
  const scene::Scene scene = scene_of(d);
  const bearing::Model model = bearing::build_model(scene);
  test::TempDir dir;
  run::RunOptions options;
  options.output_path = dir.file(d + ".h5");
  const run::RunSummary sum = run_scene(scene, options);
  EXPECT_NEAR(sum.driven_ring_revolutions, 2.0, 1e-6);

  // The cage turns at its epicyclic speed within a few per cent.
  EXPECT_TRUE(std::isfinite(sum.cage_speed_rpm));
  EXPECT_LT(std::abs(sum.cage_slip), 0.03) << "cage " << sum.cage_speed_rpm << " rpm";

  // Cage centre metrics over the second half, with the definitions of `raceway report`
  // (io/report/report_metrics.py): the vortex radius about the window's mean centre, its ratio
  // (max - min) / mean, and sigma_v = std / mean of the centre's speed.
  const auto time = test::read_dataset(options.output_path, "/time").values;
  const auto pos = test::read_dataset(options.output_path, "/cage/position");
  const auto vel = test::read_dataset(options.output_path, "/cage/velocity");
  const std::size_t dims = pos.shape.at(1);
  const double half = 0.5 * (time.front() + time.back());
  std::vector<std::size_t> window;
  for (std::size_t i = 0; i < time.size(); ++i)
    if (time[i] >= half) window.push_back(i);
  ASSERT_GE(window.size(), 3u);
  double cx = 0, cy = 0;
  for (std::size_t i : window) cx += pos.values[i * dims], cy += pos.values[i * dims + 1];
  cx /= static_cast<double>(window.size()), cy /= static_cast<double>(window.size());
  std::vector<double> radius, speed;
  for (std::size_t i : window) {
    radius.push_back(std::hypot(pos.values[i * dims] - cx, pos.values[i * dims + 1] - cy));
    speed.push_back(std::hypot(vel.values[i * dims], vel.values[i * dims + 1]));
  }
  const auto mean = [](const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size()); };
  const double radius_ratio = (*std::max_element(radius.begin(), radius.end()) - *std::min_element(radius.begin(), radius.end())) / mean(radius);
  const double speed_mean = mean(speed);
  double speed_var = 0;
  for (double v : speed) speed_var += (v - speed_mean) * (v - speed_mean);
  const double sigma_v = std::sqrt(speed_var / static_cast<double>(speed.size() - 1)) / speed_mean;
  EXPECT_TRUE(std::isfinite(radius_ratio)) << "vortex radius ratio";
  EXPECT_TRUE(std::isfinite(sigma_v)) << "velocity deviation ratio";

  // The pockets are touched (the cage is driven by the elements, not floating).
  double pocket_peak = 0;
  const std::vector<std::string> pockets = scene.bearing.is_ball_bearing()
                                               ? std::vector<std::string>{"ball_pocket"}
                                               : std::vector<std::string>{"cage_bar_front", "cage_bar_rear"};
  for (const std::string& kind : pockets)
    for (double f : test::read_dataset(options.output_path, "/segments/" + kind + "/normal_force").values)
      pocket_peak = std::max(pocket_peak, f);
  EXPECT_GT(pocket_peak, 0.0) << "no pocket contact";

  // Static balance (second-half means): contact force + applied load + weight = m a, small.
  const double weight = model.bodies.at(0).mass * kGravity;
  ASSERT_GE(sum.inner_ring_contact_force_n.size(), 2u);
  const double load = std::hypot(sum.inner_ring_load_n[0], sum.inner_ring_load_n[1],
                                 sum.inner_ring_load_n.size() > 2 ? sum.inner_ring_load_n[2] : 0.0);
  double residual2 = 0;
  for (std::size_t k = 0; k < sum.inner_ring_contact_force_n.size(); ++k) {
    const double r = sum.inner_ring_contact_force_n[k] + sum.inner_ring_load_n[k] - (k == 1 ? weight : 0.0);
    residual2 += r * r;
  }
  const double residual = std::sqrt(residual2);
  std::printf("[ catalogue ] %s: %d elements, %ld steps, %.2f s wall; cage %.1f rpm (slip %.3f %%), radius ratio "
              "%.3g, sigma_v %.3g, peak pocket force %.3g N; load %.4g N, balance residual %.3g N (%.2g %%)\n",
              d.c_str(), scene.bearing.rolling_elements, sum.stats.steps, sum.wall_time_s, sum.cage_speed_rpm,
              100 * sum.cage_slip, radius_ratio, sigma_v, pocket_peak, load, residual, 100 * residual / load);
  EXPECT_LT(residual, 0.02 * load);
}

// NJ and NUP bearings differ from the NU of the same size in their ribs alone, which the planar model
// (the catalogue's first scene for rollers) does not have: their planar runs would repeat the NU's.
// The tapered bearings (spatial roller models, far dearer per revolution) are checked in
// catalogue_tapered_test.cpp, one of them seated and run.
std::vector<std::string> distinct_first_scenes() {
  std::vector<std::string> out;
  for (const std::string& d : scene::catalogue_designations())
    if (!d.starts_with("NJ") && !d.starts_with("NUP") && !is_tapered(d)) out.push_back(d);
  return out;
}

// The rib arrangement a designation names: the spatial model's roller-end on rib contacts per roller,
// NU two (the outer ring's), NJ three (and the inner ring's on one side), NUP four; the boundary
// dimensions of dimension series 03 (ISO 15: NJ308 40 x 90 x 23 mm); the planar model takes the same
// designation without ribs.
TEST(Catalogue, RollerDesignationsNameTheirRibs) {
  for (const auto& [designation, ribs] : {std::pair{"NU308", 2}, std::pair{"NJ308", 3}, std::pair{"NUP308", 4}}) {
    const std::string text = fmt::format(
        "[scene]\nend_time = \"1 ms\"\noutput_interval = \"0.1 ms\"\nmodel = \"spatial\"\n[bearing]\ndesignation = "
        "\"{}\"\n[inner_ring]\nspeed = \"1000 rpm\"\nload = {{ fy = \"-2 kN\" }}\n",
        designation);
    const scene::Scene s = scene::parse_scene(text, std::string(designation) + ".toml");
    EXPECT_DOUBLE_EQ(s.bearing.inner_bore_diameter, 40e-3) << designation;
    EXPECT_DOUBLE_EQ(s.bearing.outer_outside_diameter, 90e-3) << designation;
    EXPECT_DOUBLE_EQ(s.bearing.ring_width, 23e-3) << designation;
    const bearing::Model m = bearing::build_model(s);
    int flanges = 0;
    for (const bearing::Segment& seg : m.segments) flanges += seg.kind == bearing::SegmentKind::roller_flange;
    EXPECT_EQ(flanges, ribs * s.bearing.rolling_elements) << designation;
  }
  EXPECT_EQ(scene_of("NJ206").scene.model, scene::ModelKind::planar);
  EXPECT_DOUBLE_EQ(scene_of("NUP310").bearing.outer_outside_diameter, 110e-3);
}

INSTANTIATE_TEST_SUITE_P(Catalogue, CatalogueRun, ::testing::ValuesIn(distinct_first_scenes()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

}  // namespace
}  // namespace raceway::scene
