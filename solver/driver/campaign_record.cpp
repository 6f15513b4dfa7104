#include "solver/driver/campaign_record.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <vector>

#include "io/scene/scene_parser.hpp"

namespace raceway::driver {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kHeader =
    "# raceway campaign identity: what the results in this folder were computed from (docs/campaigns.md).\n"
    "# A resume (campaign FILE -o DIR --resume) is refused when FILE's identity differs.\n";
constexpr std::size_t kDifferencesNamed = 4;

/// One line per entry: newlines and backslashes escaped.
std::string escaped(const std::string& text) {
  std::string out;
  for (const char ch : text) out += ch == '\n' ? std::string("\\n") : ch == '\\' ? std::string("\\\\") : std::string(1, ch);
  return out;
}

/// An identity's entries in order: label, value, and where the campaign file gives it (key, line).
struct Entry {
  std::string label, value, key;
  int line = 1;
};

std::vector<Entry> entries_of(const Campaign& c) {
  const auto line = [&](const std::string& key) { return c.key_lines.contains(key) ? c.key_lines.at(key) : 1; };
  std::vector<Entry> out;
  const auto add = [&](std::string label, std::string value, std::string key, int at) {
    out.push_back({std::move(label), escaped(value), std::move(key), at});
  };
  add("campaign.name", c.name, "campaign.name", line("campaign.name"));
  add("campaign.sweep", c.sweep, "campaign.sweep", line("campaign.sweep"));
  for (std::size_t a = 0; a < c.axes.size(); ++a) {
    const std::string key = fmt::format("axis[{}]", a);
    add(key, fmt::format("name {}, key {}", c.axes[a].name, c.axes[a].key), key, line(key));
  }
  std::istringstream base(c.base_text);
  std::string text;
  int n = 0;
  while (std::getline(base, text)) add(fmt::format("base scene line {}", ++n), text, "campaign.scene", line("campaign.scene"));
  add("base scene lines", std::to_string(n), "campaign.scene", line("campaign.scene"));
  add("scenes", std::to_string(c.scenes.size()), "campaign", line("campaign"));
  for (const CampaignScene& s : c.scenes) {
    for (std::size_t i = 0; i < s.overrides.size(); ++i) {
      const std::string& o = s.overrides[i];
      const std::size_t eq = o.find('=');
      add(fmt::format("{} --set {}", s.id, o.substr(0, eq)), o.substr(eq + 1), s.override_keys[i], s.override_lines[i]);
    }
    add(fmt::format("{} settling_time", s.id), fmt::format("{:.17g} s", s.settling_time), "campaign.settling_time",
        line(c.key_lines.contains("campaign.settling_revolutions") ? "campaign.settling_revolutions" : "campaign.settling_time"));
  }
  return out;
}

/// The folder's identity: label -> value; empty when there is none.
std::map<std::string, std::string> read_identity(const std::string& path) {
  std::map<std::string, std::string> out;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t eq = line.find(" = ");
    if (line.empty() || line[0] == '#' || eq == std::string::npos) continue;
    out.emplace(line.substr(0, eq), line.substr(eq + 3));
  }
  return out;
}

/// Scene outputs of any campaign in DIR (s000.h5, s012.h5.partial, ...).
bool holds_scene_outputs(const std::string& dir) {
  static const std::regex output("s[0-9]+\\.h5(\\.partial)?");
  std::error_code error;
  for (const auto& e : fs::directory_iterator(dir, error))
    if (std::regex_match(e.path().filename().string(), output)) return true;
  return false;
}

}  // namespace

std::string identity_path(const std::string& dir) { return (fs::path(dir) / "campaign_identity.txt").string(); }

std::string campaign_identity(const Campaign& c) {
  std::string out(kHeader);
  for (const Entry& e : entries_of(c)) out += fmt::format("{} = {}\n", e.label, e.value);
  return out;
}

void check_identity(const Campaign& c, const std::string& dir) {
  const std::string path = identity_path(dir);
  if (!fs::exists(path)) {
    if (fs::is_directory(dir) && holds_scene_outputs(dir))
      throw scene::SceneError(c.file, 1, "campaign",
                           fmt::format("{} holds scene outputs but no record of the campaign they belong to ({}): "
                                       "not a folder of this campaign, or one begun by an older raceway; give "
                                       "another folder (-o)", dir, path));
    return;
  }
  std::map<std::string, std::string> folder = read_identity(path);
  std::vector<std::string> differences;
  const Entry* first = nullptr;
  for (const Entry& e : entries_of(c)) {
    const auto it = folder.find(e.label);
    if (it != folder.end() && it->second == e.value) {
      folder.erase(it);
      continue;
    }
    if (!first) first = &e;  // entries_of's order: the file's order
    differences.push_back(it == folder.end() ? fmt::format("{}: '{}' here, none in the folder", e.label, e.value)
                                             : fmt::format("{}: '{}' here, '{}' in the folder", e.label, e.value, it->second));
    if (it != folder.end()) folder.erase(it);
  }
  for (const auto& [label, value] : folder)
    differences.push_back(fmt::format("{}: none here, '{}' in the folder", label, value));
  if (differences.empty()) return;
  const std::size_t named = std::min(differences.size(), kDifferencesNamed);
  const std::string more = differences.size() > named ? fmt::format("; and {} more", differences.size() - named) : "";
  throw scene::SceneError(
      c.file, first ? first->line : 1, first ? first->key : "campaign",
      fmt::format("{} holds another campaign, or this one before an edit ({} difference(s) from {}: {}{}); its results "
                  "would be labelled with this file's values: resume with the campaign file it was begun with, or "
                  "give another folder (-o)", dir, differences.size(), path,
                  fmt::join(differences.begin(), differences.begin() + static_cast<long>(named), "; "), more));
}

void record_identity(const Campaign& c, const std::string& dir) {
  const std::string path = identity_path(dir);
  if (fs::exists(path)) return;
  const fs::path own = fs::path(dir) / fmt::format(".campaign_identity_{}.txt", getpid());
  {
    std::ofstream out(own);
    out << campaign_identity(c);
    if (!out.flush()) throw std::runtime_error(fmt::format("campaign: cannot write {}", own.string()));
  }
  fs::rename(own, path);
}

}  // namespace raceway::driver
