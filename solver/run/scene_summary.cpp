#include "solver/run/scene_summary.hpp"

#include "io/scene/scene_overrides.hpp"
#include "io/scene/scene_parameters.hpp"

namespace raceway::run {

json::JsonObject scene_parameters_json(const scene::Scene& scene) {
  json::JsonObject all;
  for (const scene::SceneParameter& p : scene::scene_parameters(scene)) {
    json::JsonObject one;
    if (p.number) one.add("value", *p.number);
    if (p.word) one.add("value", *p.word);
    if (!p.times.empty()) one.add("time", p.times);
    if (!p.number && !p.word) one.add("value", p.values);
    if (!p.unit.empty()) one.add("unit", p.unit);
    all.add(p.key, std::move(one));
  }
  return all;
}

json::JsonObject scene_overrides_json(const scene::Scene& scene) {
  json::JsonObject all;
  for (const std::string& text : scene.overrides) {
    const scene::SceneOverride o = scene::parse_scene_override(text);
    all.add(o.key, o.value);
  }
  return all;
}

std::string scene_overrides_text(const scene::Scene& scene) {
  std::string text;
  for (const std::string& o : scene.overrides) text += o + "\n";
  return text;
}

}  // namespace raceway::run
