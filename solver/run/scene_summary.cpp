#include "solver/run/scene_summary.hpp"

#include "io/scene/scene_overrides.hpp"
#include "io/scene/scene_parameters.hpp"

namespace raceway::solver {

io::JsonObject scene_parameters_json(const io::Scene& scene) {
  io::JsonObject all;
  for (const io::SceneParameter& p : io::scene_parameters(scene)) {
    io::JsonObject one;
    if (p.number) one.add("value", *p.number);
    if (p.word) one.add("value", *p.word);
    if (!p.times.empty()) one.add("time", p.times);
    if (!p.number && !p.word) one.add("value", p.values);
    if (!p.unit.empty()) one.add("unit", p.unit);
    all.add(p.key, std::move(one));
  }
  return all;
}

io::JsonObject scene_overrides_json(const io::Scene& scene) {
  io::JsonObject all;
  for (const std::string& text : scene.overrides) {
    const io::SceneOverride o = io::parse_scene_override(text);
    all.add(o.key, o.value);
  }
  return all;
}

std::string scene_overrides_text(const io::Scene& scene) {
  std::string text;
  for (const std::string& o : scene.overrides) text += o + "\n";
  return text;
}

}  // namespace raceway::solver
