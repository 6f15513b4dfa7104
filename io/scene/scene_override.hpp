// A scene key set from outside the file (the command line's --method): the scene text is edited, so
// the text stored in the output says what ran, and then parsed like any scene.
#pragma once

#include <string>
#include <string_view>

namespace raceway::scene {

/// `text` with `key = value` in [section] (a top-level section): the key's line replaced if it is
/// there, added under the section's header if the section is, else the section added at the end.
/// `value` is TOML ("\"erk\"", "1e-8"). Text that is not valid TOML is returned unchanged (its
/// parse then reports the error).
std::string override_scene_key(std::string_view text, std::string_view section, std::string_view key,
                               std::string_view value);

}  // namespace raceway::scene
