#include "io/scene/scene_override.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <sstream>
#include <vector>

namespace raceway::scene {

namespace {

std::vector<std::string> lines_of(std::string_view text) {
  std::vector<std::string> lines;
  std::istringstream in{std::string(text)};
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

bool is_header_of(std::string_view line, std::string_view section) {
  const auto first = line.find_first_not_of(" \t");
  return first != std::string_view::npos && line.substr(first).starts_with(fmt::format("[{}]", section));
}

}  // namespace

std::string override_scene_key(std::string_view text, std::string_view section, std::string_view key,
                               std::string_view value) {
  toml::table root;
  try {
    root = toml::parse(text);
  } catch (const toml::parse_error&) {
    return std::string(text);
  }
  std::vector<std::string> lines = lines_of(text);
  const std::string assignment = fmt::format("{} = {}", key, value);
  if (const toml::table* table = root[section].as_table()) {
    if (const toml::node* node = table->get(key)) {
      // The value's lines (one, or several for a multi-line array) become the one assignment.
      const auto first = static_cast<std::size_t>(node->source().begin.line) - 1;
      const auto last = static_cast<std::size_t>(node->source().end.line) - 1;
      lines[first] = assignment;
      lines.erase(lines.begin() + static_cast<long>(first) + 1, lines.begin() + static_cast<long>(last) + 1);
      return joined(lines);
    }
    const auto header = static_cast<std::size_t>(table->source().begin.line) - 1;
    if (header < lines.size() && is_header_of(lines[header], section)) {
      lines.insert(lines.begin() + static_cast<long>(header) + 1, assignment);
      return joined(lines);
    }
  }
  // No [section] header (absent, or only implied by [section.sub]): a new one at the end.
  return joined(lines) + fmt::format("\n[{}]\n{}\n", section, assignment);
}

}  // namespace raceway::scene
