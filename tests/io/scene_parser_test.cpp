// Scene parser: the default scene, defaults and conversions, and every broken scene in
// tests/bad_scenes (each names its expected reason, key and line in its first three comment lines).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "io/scene_parser.hpp"

namespace raceway::io {
namespace {

namespace fs = std::filesystem;
constexpr double pi = std::numbers::pi;
const fs::path kSourceDir = RACEWAY_SOURCE_DIR;

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The default scene text with one substring replaced (it must occur).
std::string edited(std::string_view from, std::string_view to) {
  std::string text = default_scene_text();
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

Scene parse(const std::string& text) { return parse_scene(text, "edited.toml"); }

SceneError error_of(const std::string& text) {
  try {
    (void)parse(text);
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "no SceneError";
  return SceneError("", 0, "", "");
}

TEST(DefaultScene, Parses) {
  const Scene s = default_scene();
  EXPECT_EQ(s.source, "<built-in default>");
  EXPECT_EQ(s.text, default_scene_text());
  EXPECT_EQ(s.scene.name, "default");
  EXPECT_EQ(s.scene.model, ModelKind::planar);
  EXPECT_DOUBLE_EQ(s.scene.end_time, 0.1);
  EXPECT_DOUBLE_EQ(s.scene.output_interval, 5e-4);
  EXPECT_FALSE(s.gravity);

  const BearingGeometry& b = s.bearing;
  EXPECT_EQ(b.type, BearingType::cylindrical_roller);
  EXPECT_EQ(b.rolling_elements, 8);
  EXPECT_DOUBLE_EQ(b.roller_diameter, 6e-3);
  EXPECT_DOUBLE_EQ(b.roller_length, 6e-3);
  EXPECT_DOUBLE_EQ(b.pitch_diameter, 30e-3);
  EXPECT_DOUBLE_EQ(b.radial_clearance, 0.0);
  EXPECT_NEAR(b.inner_bore_diameter, 18e-3, 1e-15);     // default: inner race - D
  EXPECT_NEAR(b.outer_outside_diameter, 42e-3, 1e-15);  // default: outer race + D
  EXPECT_DOUBLE_EQ(b.ring_width, 6e-3);
  EXPECT_EQ(b.roller_material, "steel");
  EXPECT_EQ(b.ring_material, "steel");
  EXPECT_DOUBLE_EQ(s.material("steel").youngs_modulus, 208e9);
  EXPECT_DOUBLE_EQ(s.material("brass").density, 8500.0);
  EXPECT_DOUBLE_EQ(s.material("polyamide").poisson_ratio, 0.4);

  EXPECT_EQ(s.cage.guidance, CageGuidance::inner_land);
  EXPECT_DOUBLE_EQ(s.cage.pocket_clearance, 0.2e-3);
  EXPECT_DOUBLE_EQ(s.cage.land_clearance, 0.3e-3);
  EXPECT_DOUBLE_EQ(s.cage.bar_width, 6e-3);
  EXPECT_DOUBLE_EQ(s.cage.land_width, 3e-3);
  EXPECT_EQ(s.cage.material, "brass");
  EXPECT_EQ(s.cage.mass, 0.0);

  EXPECT_EQ(s.inner_ring.motion, RingMotion::driven);
  EXPECT_NEAR(s.inner_ring.speed(0.0), 1500.0 * pi / 30.0, 1e-12);
  EXPECT_TRUE(s.inner_ring.translation_free);
  EXPECT_TRUE(s.inner_ring.load.fx.is_zero());
  EXPECT_DOUBLE_EQ(s.inner_ring.load.fy(0.05), -500.0);
  EXPECT_TRUE(s.inner_ring.load.mz.is_zero());
  EXPECT_EQ(s.inner_ring.support.stiffness, 0.0);
  EXPECT_EQ(s.outer_ring.motion, RingMotion::fixed);
  EXPECT_FALSE(s.outer_ring.translation_free);

  EXPECT_EQ(s.roller_race.normal.name, "palmgren");
  EXPECT_EQ(s.roller_race.normal.slices, 1);
  EXPECT_EQ(s.roller_race.damping.name, "hunt_crossley");
  EXPECT_DOUBLE_EQ(s.roller_race.damping.factor, 0.5);
  EXPECT_EQ(s.roller_race.traction.name, "tanh");
  EXPECT_DOUBLE_EQ(s.roller_race.traction.friction_coefficient, 0.1);
  EXPECT_DOUBLE_EQ(s.roller_race.traction.slip_velocity_scale, 0.05);
  EXPECT_DOUBLE_EQ(s.cage_land.traction.friction_coefficient, 0.05);

  EXPECT_EQ(s.solver.method, IntegrationMethod::bdf);
  EXPECT_EQ(s.solver.max_order, 5);
  EXPECT_DOUBLE_EQ(s.solver.rtol, 1e-6);
  EXPECT_EQ(s.solver.atol_position, 0.0);
  EXPECT_EQ(s.solver.linear_solver, LinearSolverKind::bordered);
  EXPECT_TRUE(s.output.segments);
}

TEST(DefaultScene, JobFileEqualsBuiltInText) {
  const fs::path job = kSourceDir / "jobs" / "scenes" / "default.toml";
  EXPECT_EQ(read_file(job), default_scene_text());
  const Scene s = load_scene(job.string());
  EXPECT_EQ(s.source, job.string());
  EXPECT_EQ(s.text, default_scene_text());
  EXPECT_EQ(s.bearing.rolling_elements, 8);
}

TEST(SceneParser, MinimalSceneGetsDocumentedDefaults) {
  const std::string text = R"(
[scene]
name = "minimal"
model = "planar"
end_time = 0.01
output_interval = 0.001
[bearing]
type = "cylindrical_roller"
rolling_elements = 10
roller_diameter = 0.005
roller_length = 0.008
pitch_diameter = 0.04
radial_clearance = "20 um"
[cage]
guidance = "rolling_element"
pocket_clearance = "0.1 mm"
[inner_ring]
motion = "free"
load = { mz = "0.5 N m" }
support = { stiffness = "1e8 N/m" }
[outer_ring]
motion = "driven"
speed = { time = ["0 s", "10 ms"], value = [0, "600 rpm"] }
translation = "fixed"
)";
  const Scene s = parse(text);
  EXPECT_NEAR(s.bearing.inner_race_diameter(), 0.04 - 0.005 - 10e-6, 1e-15);
  EXPECT_NEAR(s.bearing.inner_bore_diameter, 0.04 - 0.005 - 10e-6 - 0.005, 1e-15);
  EXPECT_NEAR(s.bearing.outer_outside_diameter, 0.04 + 0.005 + 10e-6 + 0.005, 1e-15);
  EXPECT_DOUBLE_EQ(s.bearing.ring_width, 0.008);
  EXPECT_EQ(s.cage.guidance, CageGuidance::rolling_element);
  EXPECT_EQ(s.cage.land_clearance, 0.0);
  EXPECT_DOUBLE_EQ(s.cage.land_width, 0.004);
  EXPECT_EQ(s.cage.material, "brass");
  EXPECT_EQ(s.inner_ring.motion, RingMotion::free);
  EXPECT_TRUE(s.inner_ring.translation_free);
  EXPECT_DOUBLE_EQ(s.inner_ring.load.mz(1.0), 0.5);
  EXPECT_DOUBLE_EQ(s.inner_ring.support.stiffness, 1e8);
  EXPECT_DOUBLE_EQ(s.inner_ring.support.damping, 0.0);
  EXPECT_EQ(s.outer_ring.motion, RingMotion::driven);
  EXPECT_FALSE(s.outer_ring.translation_free);
  EXPECT_NEAR(s.outer_ring.speed(0.005), 10.0 * pi, 1e-12);
  EXPECT_NEAR(s.outer_ring.speed(1.0), 20.0 * pi, 1e-12);
  EXPECT_NEAR(s.outer_ring.speed.derivative(0.005), 20.0 * pi / 0.01, 1e-9);
  EXPECT_EQ(s.lubricant.viscosity, 0.0);
  EXPECT_EQ(s.roller_cage.normal.name, "palmgren");
  EXPECT_DOUBLE_EQ(s.roller_cage.traction.friction_coefficient, 0.1);
  EXPECT_EQ(s.solver.max_steps, 500000000);
  EXPECT_DOUBLE_EQ(s.solver.jacobian_perturbation, 1e-7);
}

TEST(SceneParser, OptionalSectionsAndUserMaterials) {
  std::string text = edited("\n[output]\n", R"(
[lubricant]
name = "ISO VG 32"
viscosity = "30 mPa s"
pressure_viscosity = "20 1/GPa"

[materials.steel]
density = "7.8 g/cm^3"
youngs_modulus = "200 GPa"
poisson_ratio = 0.29

[materials.bronze]
density = "8800 kg/m^3"
youngs_modulus = "110 GPa"
poisson_ratio = 0.34

[output]
)");
  auto replace = [&](std::string_view from, std::string_view to) {
    const auto pos = text.find(from);
    ASSERT_NE(pos, std::string::npos) << from;
    text.replace(pos, from.size(), to);
  };
  replace("material = \"brass\"", "material = \"bronze\"");
  replace("method = \"bdf\"", "method = \"adams\"\natol = { position = \"1 nm\", angular_velocity = \"0.01 rpm\" }");
  replace("traction = \"tanh\"\nfriction_coefficient = 0.05\nslip_velocity_scale = \"0.05 m/s\"", "traction = \"none\"");
  replace("damping = \"hunt_crossley\"\ndamping_factor = \"0.5 s/m\"\ntraction = \"none\"",
          "damping = \"none\"\ntraction = \"none\"");
  const Scene s = parse(text);
  EXPECT_EQ(s.lubricant.name, "ISO VG 32");
  EXPECT_NEAR(s.lubricant.viscosity, 0.03, 1e-15);
  EXPECT_NEAR(s.lubricant.pressure_viscosity, 2e-8, 1e-20);
  EXPECT_NEAR(s.material("steel").density, 7800.0, 1e-9);
  EXPECT_DOUBLE_EQ(s.material("steel").youngs_modulus, 200e9);
  EXPECT_EQ(s.material("bronze").name, "bronze");
  EXPECT_EQ(s.cage.material, "bronze");
  EXPECT_EQ(s.solver.method, IntegrationMethod::adams);
  EXPECT_EQ(s.solver.max_order, 12);
  EXPECT_DOUBLE_EQ(s.solver.atol_position, 1e-9);
  EXPECT_NEAR(s.solver.atol_angular_velocity, 0.01 * pi / 30.0, 1e-15);
  EXPECT_EQ(s.solver.atol_angle, 0.0);
  EXPECT_EQ(s.cage_land.traction.name, "none");
  EXPECT_EQ(s.cage_land.traction.friction_coefficient, 0.0);
  EXPECT_EQ(s.cage_land.damping.name, "none");
  EXPECT_EQ(s.cage_land.damping.factor, 0.0);
  EXPECT_EQ(s.roller_race.traction.name, "tanh");
}

TEST(SceneParser, ErrorFormat) {
  const SceneError e = error_of(edited("roller_diameter = \"6 mm\"", "roller_diameter = \"6 rpm\""));
  EXPECT_EQ(e.file(), "edited.toml");
  EXPECT_EQ(e.key(), "bearing.roller_diameter");
  EXPECT_EQ(e.reason(), "'6 rpm' is an angular speed; expected a length (m, mm, um)");
  EXPECT_EQ(std::string(e.what()),
            "edited.toml:" + std::to_string(e.line()) + ": key 'bearing.roller_diameter': " + e.reason());
  // the line is that of the value
  const std::string text = default_scene_text();
  const auto pos = text.find("roller_diameter = ");
  EXPECT_EQ(e.line(), 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(pos), '\n')));
}

TEST(SceneParser, MoreRules) {
  // parameters of a law that is switched off are rejected, not ignored
  EXPECT_EQ(error_of(edited("damping = \"hunt_crossley\"", "damping = \"none\"")).key(),
            "contact.roller_race.damping_factor");
  // translation is meaningless for a fixed ring
  EXPECT_EQ(error_of(edited("motion = \"fixed\"", "motion = \"fixed\"\ntranslation = \"free\"")).key(),
            "outer_ring.translation");
  // a driven ring needs a speed
  EXPECT_EQ(error_of(edited("speed = \"1500 rpm\"", "")).key(), "inner_ring.speed");
  // a supported floating outer ring holds the bearing
  const Scene s = parse(edited("motion = \"fixed\"", "motion = \"free\"\nsupport = { stiffness = \"2e8 N/m\", damping = \"1e3 N s/m\" }"));
  EXPECT_DOUBLE_EQ(s.outer_ring.support.damping, 1e3);
  EXPECT_EQ(error_of(edited("rtol = 1e-6", "rtol = 0.1")).key(), "solver.rtol");
  EXPECT_EQ(error_of(edited("slices = 1", "slices = 0")).key(), "contact.roller_race.slices");
  EXPECT_EQ(error_of(edited("friction_coefficient = 0.1", "friction_coefficient = 1.5")).key(),
            "contact.roller_race.friction_coefficient");
  EXPECT_EQ(error_of(edited("gravity = false", "gravity = \"no\"")).key(), "scene.gravity");
  EXPECT_EQ(error_of(edited("\n[output]\n", "\n[output]\nframes = 3\n")).reason(),
            "unknown key 'frames' in [output]; allowed keys: segments");
}

TEST(SceneParser, UnreadableFile) {
  const std::string path = (kSourceDir / "tests" / "bad_scenes" / "no_such_file.toml").string();
  try {
    (void)load_scene(path);
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 0);
    EXPECT_EQ(e.key(), "");
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
    EXPECT_NE(e.reason().find("cannot read the scene file"), std::string::npos);
  }
}

// ---- tests/bad_scenes/*.toml ------------------------------------------------------------------

std::vector<std::string> bad_scenes() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(kSourceDir / "tests" / "bad_scenes"))
    if (entry.path().extension() == ".toml") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// The text after "# tag:" on the given line of the file, trimmed.
std::string header(const std::string& text, int line, std::string_view tag) {
  std::istringstream in(text);
  std::string l;
  for (int i = 0; i < line; ++i) std::getline(in, l);
  const std::string prefix = "# " + std::string(tag) + ":";
  if (l.rfind(prefix, 0) != 0) return "<missing '" + prefix + "' on line " + std::to_string(line) + ">";
  l = l.substr(prefix.size());
  const auto b = l.find_first_not_of(' ');
  return b == std::string::npos ? std::string() : l.substr(b);
}

class BadScene : public ::testing::TestWithParam<std::string> {};

TEST_P(BadScene, IsRejectedWithFileLineKeyAndReason) {
  const fs::path path = kSourceDir / "tests" / "bad_scenes" / (GetParam() + ".toml");
  const std::string text = read_file(path);
  const std::string expect = header(text, 1, "expect");
  const std::string key = header(text, 2, "key");
  const int line = std::stoi(header(text, 3, "line"));
  ASSERT_FALSE(expect.empty());
  try {
    (void)load_scene(path.string());
    FAIL() << path << " was accepted";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    SCOPED_TRACE(what);
    EXPECT_EQ(e.file(), path.string());
    EXPECT_NE(what.find(path.string()), std::string::npos);
    EXPECT_GT(e.line(), 0);
    EXPECT_EQ(e.line(), line);
    EXPECT_NE(what.find(":" + std::to_string(line) + ":"), std::string::npos);
    EXPECT_EQ(e.key(), key);
    if (!key.empty()) {
      EXPECT_NE(what.find("key '" + key + "'"), std::string::npos);
    }
    EXPECT_NE(e.reason().find(expect), std::string::npos) << "expected: " << expect;
    EXPECT_NE(what.find(expect), std::string::npos);
  }
}

INSTANTIATE_TEST_SUITE_P(Files, BadScene, ::testing::ValuesIn(bad_scenes()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

TEST(BadScenes, CoverTheRequiredCases) { EXPECT_GE(bad_scenes().size(), 14u); }

}  // namespace
}  // namespace raceway::io
