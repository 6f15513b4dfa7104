// The scene in a run's summary and output: its command-line overrides and its resolved parameters,
// so that a table of runs reads the values that ran rather than parsing scene text.
#pragma once

#include <string>

#include "io/json/summary_json.hpp"
#include "io/scene/scene.hpp"

namespace raceway::run {

/// Every resolved parameter of the scene (io/scene/scene_parameters.hpp) as
/// {"section.key": {"value": SI number or word, "unit": "m"}}; time-function tables as
/// {"time": [...], "value": [...], "unit": ...}.
json::JsonObject scene_parameters_json(const scene::Scene& scene);
/// The scene's overrides as {"section.key": "VALUE as given"}.
json::JsonObject scene_overrides_json(const scene::Scene& scene);
/// The overrides one per line, "section.key=VALUE" as given (the root attribute scene_overrides).
std::string scene_overrides_text(const scene::Scene& scene);

}  // namespace raceway::run
