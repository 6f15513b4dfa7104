// Helpers of the scene tests: scene texts to edit, parsing and the error a broken one gives.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <string_view>

#include "io/scene/scene_parser.hpp"

namespace raceway::test {

namespace fs = std::filesystem;
inline constexpr double pi = std::numbers::pi;
inline const fs::path kSourceDir = RACEWAY_SOURCE_DIR;

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// `text` with one substring replaced (it must occur), or with `to` appended when `from` is empty.
inline std::string replaced(std::string text, std::string_view from, std::string_view to) {
  if (from.empty()) return text + std::string(to);
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

/// The default scene text with one substring replaced (it must occur).
inline std::string edited(std::string_view from, std::string_view to) {
  return replaced(scene::default_scene_text(), from, to);
}

inline scene::Scene parse(const std::string& text) { return scene::parse_scene(text, "edited.toml"); }

inline scene::SceneError error_of(const std::string& text) {
  try {
    (void)parse(text);
  } catch (const scene::SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "no scene::SceneError";
  return scene::SceneError("", 0, "", "");
}

/// A small cylindrical roller bearing scene with nothing but required keys (and a few more).
inline constexpr const char* kPlanarMinimal = R"(
[scene]
name = "minimal"
model = "planar"
end_time = "0.01 s"
output_interval = "0.001 s"
[bearing]
type = "cylindrical_roller"
rolling_elements = 10
roller_diameter = "5 mm"
roller_length = "8 mm"
pitch_diameter = "40 mm"
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

/// A small deep groove ball bearing scene with nothing but required keys.
inline constexpr const char* kSpatialMinimal = R"([scene]
name = "minimal spatial"
model = "spatial"
end_time = "0.01 s"
output_interval = "1 ms"
[bearing]
type = "deep_groove_ball"
rolling_elements = 8
ball_diameter = "17.462 mm"
inner_conformity = 0.52
outer_conformity = 0.53
pitch_diameter = "72.5 mm"
radial_clearance = "15 um"
ring_width = "25 mm"
[cage]
guidance = "rolling_element"
pocket_clearance = "0.4 mm"
pocket_shape = "spherical"
[inner_ring]
motion = "driven"
speed = "3000 rpm"
load = { fy = "-1000 N" }
[outer_ring]
motion = "fixed"
)";

/// (Its ball-guided cage has spherical pockets: in cylindrical ones nothing would hold it radially,
/// scene_rules.cpp check_cage_held.)
/// The minimal spatial scene with one substring replaced (it must occur) or text appended.
inline std::string spatial(std::string_view from = {}, std::string_view to = {}) {
  return replaced(kSpatialMinimal, from, to);
}

}  // namespace raceway::test
