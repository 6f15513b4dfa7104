// raceway scene parser: TOML scene file -> validated, SI-unit scene::Scene.
//
// The schema (sections, keys, units, bounds, defaults) is the table in io/scene/scene_schema.cpp,
// printed as docs/scene_keys.md; the rules that tie keys together are io/scene/scene_rules.cpp.
// Commented examples: jobs/scenes/default.toml (planar: cylindrical roller bearings) and
// jobs/scenes/6309_R3.toml (spatial: ball bearings). Every problem is a SceneError that names the
// file, the line, the dotted key and the reason.
#pragma once

#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "io/scene/scene.hpp"

namespace raceway::scene {

/// A scene that cannot be read, parsed or validated.
/// what() is "FILE:LINE: key 'section.key': reason", or "FILE:LINE: reason" when no key applies
/// (TOML syntax errors), or "FILE: reason" when the file cannot be read (line 0).
class SceneError : public std::runtime_error {
 public:
  SceneError(std::string file, int line, std::string key, std::string reason);
  const std::string& file() const noexcept { return file_; }
  /// Line of the offending value; of the section header for a missing key; 1 for a missing
  /// section; 0 when the file could not be read.
  int line() const noexcept { return line_; }
  /// Dotted key, e.g. "bearing.roller_diameter"; empty for syntax errors and unreadable files.
  const std::string& key() const noexcept { return key_; }
  const std::string& reason() const noexcept { return reason_; }

 private:
  std::string file_;
  int line_;
  std::string key_;
  std::string reason_;
};

/// Reads and parses a scene file. Scene::source = path, Scene::text = the file contents.
Scene load_scene(const std::string& path);
/// The same with keys set on the command line (scene_overrides.hpp); "" reads the built-in default.
Scene load_scene(const std::string& path, std::span<const std::string> overrides);

/// Parses scene text; source_name is used in errors and stored in Scene::source.
Scene parse_scene(std::string_view text, const std::string& source_name);

/// Parses scene text with keys set on the command line ("section.key=VALUE", scene_overrides.hpp),
/// validated like the file's; they are kept in Scene::overrides.
Scene parse_scene(std::string_view text, const std::string& source_name, std::span<const std::string> overrides);

/// The built-in default scene (a small bearing that runs in seconds).
Scene default_scene();

/// TOML text of the default scene (identical to jobs/scenes/default.toml).
std::string default_scene_text();

/// "inner_ring.load.fy (line 31), bearing.radial_clearance (line 20)": the keys of the scene text
/// at or under the given dotted keys ("inner_ring.load"), in the order of the text; "" when none
/// is in it. For errors found after parsing (start-up) that name the keys involved.
std::string keys_with_lines(const Scene& scene, std::span<const std::string_view> keys);

}  // namespace raceway::scene
