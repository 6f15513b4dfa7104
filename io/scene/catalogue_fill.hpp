// Internal to raceway::scene: the catalogue's values put into a scene's TOML before it is read.
#pragma once

#include <string>
#include <vector>

#include <toml++/toml.h>

#include "io/scene/scene.hpp"

namespace raceway::scene::catalogue {

/// When [bearing] has a designation: puts the catalogue's values and the first-scene defaults into
/// `root` wherever the scene does not give the key, and returns them (and the keys the scene gave
/// instead) for `check`. An unknown designation, or a type that contradicts it, is a SceneError.
std::vector<CatalogueValue> fill(toml::table& root, const std::string& file);

}  // namespace raceway::scene::catalogue
