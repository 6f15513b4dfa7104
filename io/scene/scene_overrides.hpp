// Scene keys set on the command line: `raceway run|check SCENE --set section.key=VALUE ...`.
//
// An override is an edit of the parsed TOML table before the schema walk (scene_parser.cpp), so it
// is validated exactly like the key in the file: its type, unit, bounds and the rules that tie keys
// together. An error about an overridden key names the override, not the file:
//   "--set inner_ring.speed=fast: key 'inner_ring.speed': expected a quantity ...".
// The scene text stays the file's; the overrides are kept beside it (Scene::overrides), stored in
// the output and the summary and part of a checkpoint's fingerprint.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

namespace raceway::scene {

class SceneError;

/// One `section.key=VALUE` as given. VALUE is TOML ("\"3000 rpm\"", "0.5", "{ fz = \"100 N\" }") or,
/// when it is not, text: `inner_ring.speed=3000 rpm` sets the string "3000 rpm".
struct SceneOverride {
  std::string key;    ///< dotted: "inner_ring.speed", "contact.ball_race.normal_law"
  std::string value;  ///< as given
  std::string text() const { return key + "=" + value; }
};

/// Splits "section.key=VALUE"; a malformed one is a SceneError naming it (no '=', no section, an
/// empty part of the key).
SceneOverride parse_scene_override(std::string_view text);

/// Sets every override in `root` (later ones win); a key under a value that is not a table is an
/// error naming the override.
void apply_scene_overrides(toml::table& root, std::span<const std::string> overrides);

/// `error` about an overridden key (the key, a table holding it or a key inside it) as an error of
/// the override ("--set KEY=VALUE: key 'KEY': reason"); otherwise `error` itself.
SceneError error_of_override(const SceneError& error, std::span<const std::string> overrides);

/// The overrides as scene-text comment lines ("# --set key=value"), appended to the scene text of a
/// checkpoint's fingerprint so that a resume with other overrides is refused; "" when none.
std::string overrides_as_comments(std::span<const std::string> overrides);

}  // namespace raceway::scene
