#include "io/scene/scene_overrides.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include "io/scene/scene_parser.hpp"

namespace raceway::scene {

namespace {

/// "--set TEXT" for messages, line breaks shown as \n (a value may carry them: parsed_value).
std::string label(std::string_view text) {
  std::string shown;
  for (const char c : text) shown += c == '\n' ? std::string("\\n") : c == '\r' ? std::string("\\r") : std::string(1, c);
  return fmt::format("--set {}", shown);
}

/// The parts of a dotted key; empty parts are an error.
std::vector<std::string> parts_of(std::string_view key, std::string_view text) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key.find('.', start);
    const std::string_view part = key.substr(start, dot == std::string_view::npos ? dot : dot - start);
    if (part.empty())
      throw SceneError(label(text), 0, std::string(key), "the key has an empty part; expected section.key=VALUE");
    parts.emplace_back(part);
    if (dot == std::string_view::npos) return parts;
    start = dot + 1;
  }
}

/// VALUE as a TOML value, or as a string when it is not one (3000 rpm, erk). One value only: text
/// after it that TOML reads as more keys or tables (a newline and more TOML) would otherwise be
/// dropped without a word, and a line break in a bare string is no value of any key.
toml::node_view<toml::node> parsed_value(toml::table& holder, const SceneOverride& o) {
  const auto more_than_one = [&](const std::string& what) {
    return SceneError(label(o.text()), 0, o.key,
                      fmt::format("the value holds {}: one value per --set (quote a string: {}=\"...\")", what, o.key));
  };
  try {
    holder = toml::parse("v = " + o.value, std::string_view(label(o.text())));
  } catch (const toml::parse_error&) {
    if (o.value.find_first_of("\n\r") != std::string::npos)
      throw more_than_one("a line break, and what follows it is not part of one TOML value");
    holder = toml::table{};
    holder.insert("v", o.value);
  }
  if (holder.size() != 1) {
    std::string extra;
    for (const auto& [name, node] : holder)
      if (name.str() != "v") extra += (extra.empty() ? "'" : ", '") + std::string(name.str()) + "'";
    throw more_than_one(fmt::format("more than one TOML value (after a line break: {})", extra));
  }
  return holder["v"];
}

bool related(std::string_view a, std::string_view b) {
  const auto under = [](std::string_view key, std::string_view prefix) {
    return key.size() > prefix.size() && key.starts_with(prefix) && key[prefix.size()] == '.';
  };
  return a == b || under(a, b) || under(b, a);
}

}  // namespace

SceneOverride parse_scene_override(std::string_view text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string_view::npos)
    throw SceneError(label(text), 0, "", "expected section.key=VALUE (e.g. inner_ring.speed=\"3000 rpm\"), no '='");
  SceneOverride o{std::string(text.substr(0, eq)), std::string(text.substr(eq + 1))};
  while (!o.key.empty() && o.key.back() == ' ') o.key.pop_back();
  while (!o.value.empty() && o.value.front() == ' ') o.value.erase(0, 1);
  if (o.key.find('.') == std::string::npos)
    throw SceneError(label(text), 0, o.key,
                     "expected section.key=VALUE: a key inside a section (e.g. scene.end_time), not a section");
  if (o.value.empty()) throw SceneError(label(text), 0, o.key, "the value is empty");
  (void)parts_of(o.key, text);
  return o;
}

void apply_scene_overrides(toml::table& root, std::span<const std::string> overrides) {
  for (const std::string& text : overrides) {
    const SceneOverride o = parse_scene_override(text);
    const std::vector<std::string> parts = parts_of(o.key, text);
    toml::table* table = &root;
    std::string path;
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
      path += (i ? "." : "") + parts[i];
      toml::node* node = table->get(parts[i]);
      if (!node) node = table->insert(parts[i], toml::table{}).first->second.as_table();
      table = node->as_table();
      if (!table)
        throw SceneError(label(text), 0, o.key,
                         fmt::format("'{}' is a value in the scene, not a table: it has no key '{}'", path, parts[i + 1]));
    }
    toml::table holder;
    table->insert_or_assign(parts.back(), *parsed_value(holder, o).node());
  }
}

SceneError error_of_override(const SceneError& error, std::span<const std::string> overrides) {
  if (error.key().empty()) return error;
  for (auto it = overrides.rbegin(); it != overrides.rend(); ++it) {
    const SceneOverride o = parse_scene_override(*it);
    if (related(error.key(), o.key)) return SceneError(label(*it), 0, error.key(), error.reason());
  }
  return error;
}

std::string overrides_as_comments(std::span<const std::string> overrides) {
  std::string out;
  for (const std::string& o : overrides) out += fmt::format("\n# --set {}", o);
  return out;
}

}  // namespace raceway::scene
