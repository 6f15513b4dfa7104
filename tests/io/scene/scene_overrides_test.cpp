// --set overrides (io/scene/scene_overrides.hpp) and the resolved parameters
// (io/scene/scene_parameters.hpp): an override gives the scene the same edit of the file would
// give; its errors name it; the parameters hold every value that ran, in SI.
#include <numbers>
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "io/scene/scene_override.hpp"
#include "io/scene/scene_overrides.hpp"
#include "io/scene/scene_parameters.hpp"
#include "tests/support/scene_test_util.hpp"

namespace raceway::scene {
namespace {

/// The parameters as "key=value unit" lines, for comparisons.
std::vector<std::string> lines_of(const Scene& scene) {
  std::vector<std::string> out;
  for (const SceneParameter& p : scene_parameters(scene)) {
    std::string line = p.key + "=";
    if (p.number) line += std::to_string(*p.number);
    if (p.word) line += *p.word;
    for (const double v : p.times) line += " t" + std::to_string(v);
    for (const double v : p.values) line += " v" + std::to_string(v);
    out.push_back(line + " " + p.unit);
  }
  return out;
}

struct Case {
  const char* section;
  const char* key;    // inside the section (dotted for nested tables)
  const char* value;  // TOML
};

// Each override gives the parameters that editing the file's text gives (the text edit is the
// older, independent mechanism of --method: it rewrites the key's line).
TEST(SceneOverrides, SameAsEditingTheFile) {
  const std::string text = default_scene_text();
  const Case cases[] = {{"bearing", "pitch_diameter", "\"32 mm\""},
                        {"inner_ring", "speed", "\"2400 rpm\""},
                        {"cage", "guidance", "\"outer_land\""},
                        {"scene", "gravity", "true"},
                        {"solver", "method", "\"adams\""}};
  for (const Case& c : cases) {
    const std::string dotted = std::string(c.section) + "." + c.key;
    const std::vector<std::string> set{dotted + "=" + c.value};
    const Scene by_override = parse_scene(text, "default.toml", set);
    const Scene by_edit = parse_scene(override_scene_key(text, c.section, c.key, c.value), "default.toml");
    EXPECT_EQ(lines_of(by_override), lines_of(by_edit)) << dotted;
    EXPECT_NE(lines_of(by_override), lines_of(parse_scene(text, "default.toml"))) << dotted << " changed nothing";
    EXPECT_EQ(by_override.text, text) << "the scene text stays the file's";
    EXPECT_EQ(by_override.overrides, set);
  }
}

TEST(SceneOverrides, NestedKeysUnquotedValuesAndOrder) {
  const Scene s = parse_scene(default_scene_text(), "default.toml",
                              std::vector<std::string>{"inner_ring.load.fy=-1 kN", "contact.roller_race.slices=3",
                                                       "inner_ring.speed=1000 rpm", "inner_ring.speed=600 rpm"});
  EXPECT_DOUBLE_EQ(s.inner_ring.load.fy(0), -1000.0);
  EXPECT_EQ(s.roller_race.normal.slices, 3);
  EXPECT_DOUBLE_EQ(s.inner_ring.speed(0), 600 * 2 * std::numbers::pi / 60) << "the later override wins";
}

/// The SceneError of parsing the default scene with one override.
SceneError error_of(const std::string& set) {
  try {
    (void)parse_scene(default_scene_text(), "default.toml", std::vector<std::string>{set});
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << set << " was accepted";
  return SceneError("", 0, "", "");
}

TEST(SceneOverrides, ErrorsNameTheOverride) {
  const SceneError value = error_of("bearing.pitch_diameter=-3 mm");
  EXPECT_EQ(value.file(), "--set bearing.pitch_diameter=-3 mm");
  EXPECT_EQ(value.line(), 0);
  EXPECT_EQ(value.key(), "bearing.pitch_diameter");
  EXPECT_NE(value.reason().find("greater than zero"), std::string::npos) << value.what();
  EXPECT_NE(error_of("bearing.pich_diameter=30 mm").reason().find("did you mean 'pitch_diameter'"), std::string::npos);
  EXPECT_NE(error_of("nowhere.key=1").reason().find("unknown section 'nowhere'"), std::string::npos);
  EXPECT_NE(error_of("inner_ring.speed.x=1").reason().find("not a table"), std::string::npos);
  EXPECT_NE(error_of("bearing").reason().find("no '='"), std::string::npos);
  EXPECT_NE(error_of("bearing=1").reason().find("not a section"), std::string::npos);
  EXPECT_NE(error_of("bearing..type=1").reason().find("empty part"), std::string::npos);
  // An error the override causes in another key is the file's, at that key's line.
  const SceneError other = error_of("bearing.pitch_diameter=7 mm");
  EXPECT_EQ(other.file(), "default.toml") << other.what();
}

// A key that does not apply under the scene's other settings is accepted at the value it then takes
// (a factor of 1, a switch off: nothing changes), so a --set can take a scene back to the neutral
// setting; any other value is refused with the reason.
TEST(SceneOverrides, NeutralValueOfAKeyThatDoesNotApply) {
  for (const char* neutral : {"solver.radial_velocity_tolerance_factor=1", "solver.pocket_tolerance_cage=false"}) {
    const Scene scene = parse_scene(default_scene_text(), "default.toml", std::vector<std::string>{neutral});
    EXPECT_EQ(scene.solver.radial_velocity_tolerance_factor, 1.0) << neutral;
    EXPECT_FALSE(scene.solver.pocket_tolerance_cage) << neutral;
  }
  EXPECT_NE(error_of("solver.radial_velocity_tolerance_factor=3").reason().find("only with element_velocity_frame"),
            std::string::npos);
  EXPECT_NE(error_of("solver.pocket_tolerance_cage=true").reason().find("only with pocket_tolerance_factor > 1"),
            std::string::npos);
}

// A value that carries more TOML after a line break is refused naming the key, never cut to its
// first value; one value over several lines (an array) is still one value.
TEST(SceneOverrides, OneValuePerOverride) {
  const SceneError more = error_of("inner_ring.speed=\"3000 rpm\"\n[scene]\nend_time = \"1 s\"");
  EXPECT_EQ(more.key(), "inner_ring.speed") << more.what();
  EXPECT_NE(more.reason().find("more than one TOML value"), std::string::npos) << more.what();
  EXPECT_NE(more.reason().find("'scene'"), std::string::npos) << more.what();
  const SceneError key = error_of("scene.end_time=\"1 s\"\nname = \"x\"");
  EXPECT_EQ(key.key(), "scene.end_time") << key.what();
  EXPECT_NE(key.reason().find("'name'"), std::string::npos) << key.what();
  const SceneError bare = error_of("inner_ring.speed=3000 rpm\nend_time = 1");
  EXPECT_EQ(bare.key(), "inner_ring.speed") << bare.what();
  EXPECT_NE(bare.reason().find("line break"), std::string::npos) << bare.what();
  EXPECT_NE(error_of("scene.name=abc\rdef").reason().find("line break"), std::string::npos);
  const Scene array = parse_scene(default_scene_text(), "default.toml",
                                  std::vector<std::string>{"inner_ring.speed={ time = [\"0 s\",\n\"1 s\"], value = "
                                                           "[\"0 rpm\", \"600 rpm\"] }"});
  EXPECT_DOUBLE_EQ(array.inner_ring.speed(1.0), 600 * 2 * std::numbers::pi / 60);
}

TEST(SceneParameters, EveryValueInSiWithItsUnit) {
  const Scene s = parse_scene(default_scene_text(), "default.toml");
  const auto params = scene_parameters(s);
  const auto find = [&](const std::string& key) -> const SceneParameter* {
    for (const SceneParameter& p : params)
      if (p.key == key) return &p;
    return nullptr;
  };
  ASSERT_TRUE(find("bearing.pitch_diameter"));
  EXPECT_DOUBLE_EQ(*find("bearing.pitch_diameter")->number, 0.030);
  EXPECT_EQ(find("bearing.pitch_diameter")->unit, "m");
  EXPECT_DOUBLE_EQ(*find("inner_ring.speed")->number, 1500 * 2 * std::numbers::pi / 60);
  EXPECT_EQ(find("inner_ring.speed")->unit, "rad/s");
  EXPECT_EQ(*find("cage.guidance")->word, "inner_land");
  EXPECT_EQ(*find("contact.roller_race.normal")->word, "palmgren");
  EXPECT_DOUBLE_EQ(*find("contact.roller_race.friction_coefficient")->number, 0.1);
  EXPECT_EQ(find("contact.roller_race.friction_coefficient")->unit, "");
  EXPECT_DOUBLE_EQ(*find("materials.steel.youngs_modulus")->number, 208e9);
  EXPECT_EQ(find("bearing.ball_diameter"), nullptr) << "a ball-bearing key in a roller bearing's parameters";
  // Every given key of the file is among the parameters (keys of tables: their leaves).
  for (const auto& [key, line] : s.key_lines) {
    const bool table = std::any_of(s.key_lines.begin(), s.key_lines.end(),
                                   [&](const auto& kl) { return kl.first.starts_with(key + "."); });
    if (!table) {
      EXPECT_TRUE(find(key)) << key << " (line " << line << ") is not among the parameters";
    }
  }
  const Scene spatial = load_scene((test::kSourceDir / "jobs/scenes/qj215_validation.toml").string());
  std::size_t ball_race = 0;
  for (const SceneParameter& p : scene_parameters(spatial)) ball_race += p.key.starts_with("contact.ball_race.");
  EXPECT_GT(ball_race, 3u);
}

}  // namespace
}  // namespace raceway::scene
