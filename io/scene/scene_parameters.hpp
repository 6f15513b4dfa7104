// The scene's resolved parameters: every key of the schema that applies to this bearing, with the
// value the parsed scene holds (given, overridden or defaulted), numbers in SI with their unit. For
// run summaries and campaign tables, so that nothing has to read values back out of scene text.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "io/scene/scene.hpp"

namespace raceway::scene {

struct SceneParameter {
  std::string key;                ///< dotted: "inner_ring.speed", "contact.ball_race.normal_law"
  std::string unit;               ///< SI unit of the numbers ("" for plain numbers and words)
  std::optional<double> number;   ///< numbers, integers, booleans (0/1), constant time functions
  std::optional<std::string> word;  ///< choices, names, materials, laws, key lists (comma-separated)
  std::vector<double> times, values;  ///< time functions given as tables; cell grids (values only)
};

/// The schema's keys in table order for the scene's bearing and contacts ([materials.NAME] for
/// every material, built-in or given).
std::vector<SceneParameter> scene_parameters(const Scene& scene);

}  // namespace raceway::scene
