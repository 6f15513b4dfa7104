#include "solver/driver/campaign_file.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "io/scene/scene_parser.hpp"
#include "io/scene/units.hpp"
#include "solver/driver/campaign_plan.hpp"

namespace raceway::driver {

namespace {

using Names = std::vector<std::string_view>;

constexpr std::string_view kCampaignKeys[] = {"name",        "scene",          "sweep",    "revolutions",
                                              "end_time",    "settling_revolutions", "settling_time",
                                              "samples_per_revolution", "ranks_per_scene", "set", "metrics"};
constexpr std::string_view kAxisKeys[] = {"key", "name", "values", "range", "unit"};

int line_of(const toml::node& n) { return std::max(static_cast<int>(n.source().begin.line), 1); }

std::string listed(std::span<const std::string_view> names) {
  std::string out;
  for (const auto n : names) out += fmt::format("{}{}", out.empty() ? "" : ", ", n);
  return out;
}

/// Reads one campaign file; every error names it.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void fail(int line, const std::string& key, const std::string& reason) const {
    throw scene::SceneError(file_, line, key, reason);
  }
  void allow(const toml::table& t, std::span<const std::string_view> keys, const std::string& where) const {
    for (const auto& [k, v] : t)
      if (std::find(keys.begin(), keys.end(), k.str()) == keys.end())
        fail(line_of(v), fmt::format("{}.{}", where, k.str()),
             fmt::format("unknown key '{}' in [{}]; allowed keys: {}", k.str(), where, listed(keys)));
  }
  /// A value given as a TOML string, or a number written as text ("1000 rpm", "2000").
  std::string text_of(const toml::node& n, const std::string& key) const {
    if (const auto* s = n.as_string()) return s->get();
    if (const auto* i = n.as_integer()) return std::to_string(i->get());
    if (const auto* d = n.as_floating_point()) return fmt::format("{}", d->get());
    if (const auto* b = n.as_boolean()) return b->get() ? "true" : "false";
    fail(line_of(n), key, "expected a string or a number");
  }
  double number(const toml::table& t, std::string_view key, const std::string& where, double lo) const {
    const toml::node* n = t.get(key);
    const std::optional<double> v = n ? n->value<double>() : std::nullopt;
    if (!v || !std::isfinite(*v) || *v <= lo)
      fail(n ? line_of(*n) : 1, fmt::format("{}.{}", where, key), fmt::format("expected a number greater than {}", lo));
    return *v;
  }
  /// A number >= lo (a settling length may be 0).
  double at_least(const toml::table& t, std::string_view key, const std::string& where, double lo) const {
    const toml::node* n = t.get(key);
    const std::optional<double> v = n ? n->value<double>() : std::nullopt;
    if (!v || !std::isfinite(*v) || *v < lo)
      fail(n ? line_of(*n) : 1, fmt::format("{}.{}", where, key), fmt::format("expected a number of at least {}", lo));
    return *v;
  }
  /// A whole number in [lo, hi], written as a TOML integer.
  int whole(const toml::table& t, std::string_view key, const std::string& where, int lo, int hi) const {
    const toml::node* n = t.get(key);
    const auto* i = n ? n->as_integer() : nullptr;
    if (!i || i->get() < lo || i->get() > hi)
      fail(n ? line_of(*n) : 1, fmt::format("{}.{}", where, key),
           fmt::format("expected a whole number from {} to {}, got {}", lo, hi,
                       n ? toml_text(*n) : std::string("nothing")));
    return static_cast<int>(i->get());
  }
  /// A time > 0, or >= 0 with `zero_allowed`.
  double seconds(const toml::table& t, std::string_view key, bool zero_allowed = false) const {
    const toml::node* n = t.get(key);
    try {
      const double v = scene::parse_quantity(*n, scene::dim::time, "0.5 s");
      if (v > 0 || (zero_allowed && v == 0)) return v;
    } catch (const std::exception& e) {
      fail(line_of(*n), fmt::format("campaign.{}", key), e.what());
    }
    fail(line_of(*n), fmt::format("campaign.{}", key), zero_allowed ? "must not be negative" : "must be greater than zero");
  }
  static std::string toml_text(const toml::node& n) {
    std::ostringstream out;
    n.visit([&](const auto& v) { out << v; });
    return out.str();
  }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

/// A scene key as `--set` takes it: dotted words, a section and at least one key.
bool is_scene_key(const std::string& key) {
  static const std::regex pattern("[A-Za-z0-9_]+(\\.[A-Za-z0-9_]+)+");
  return std::regex_match(key, pattern);
}

/// Two keys that set the same value: equal, or one a table holding the other.
bool overlapping(const std::string& a, const std::string& b) {
  const auto within = [](const std::string& inner, const std::string& outer) {
    return inner.size() > outer.size() && inner.compare(0, outer.size(), outer) == 0 && inner[outer.size()] == '.';
  };
  return a == b || within(a, b) || within(b, a);
}

/// The values of range = [from, to, step]: from, from + step, ... up to to; refused before the
/// first value when they are not finite or too many (a range to inf never ends).
void expand_range(const Reader& r, const toml::node& range, const std::string& unit, const std::string& where,
                  CampaignAxis& axis) {
  const toml::array* a = range.as_array();
  const auto at = [&](std::size_t i) { return a && i < a->size() ? a->get(i)->value<double>() : std::nullopt; };
  const auto from = at(0), to = at(1), step = at(2);
  if (!a || a->size() != 3 || !from || !to || !step)
    r.fail(line_of(range), where + ".range", "expected [from, to, step], three numbers");
  if (!std::isfinite(*from) || !std::isfinite(*to) || !std::isfinite(*step))
    r.fail(line_of(range), where + ".range", fmt::format("from, to and step must be finite numbers, got [{}, {}, {}]",
                                                         *from, *to, *step));
  if (!(*step > 0) || *to < *from)
    r.fail(line_of(range), where + ".range", "expected [from, to, step] with from <= to and step > 0");
  const double count = std::floor((*to - *from) / *step + 1e-9) + 1;
  if (!(count <= kMaxCampaignScenes))
    r.fail(line_of(range), where + ".range",
           fmt::format("{:.4g} values ({} to {} in steps of {}); a campaign has at most {:.0f} scenes", count, *from,
                       *to, *step, kMaxCampaignScenes));
  for (long i = 0; i < static_cast<long>(count) && *from + double(i) * *step <= *to + 1e-9 * *step; ++i) {
    const double v = *from + double(i) * *step;
    axis.values.push_back(unit.empty() ? fmt::format("{}", v) : fmt::format("{} {}", v, unit));
    axis.lines.push_back(line_of(range));
  }
}

CampaignAxis read_axis(const Reader& r, const toml::table& t, int index) {
  const std::string where = fmt::format("axis[{}]", index);
  r.allow(t, kAxisKeys, where);
  CampaignAxis axis;
  axis.line = line_of(t);
  const toml::node* key = t.get("key");
  if (!key || !key->is_string()) r.fail(line_of(t), where + ".key", "required: the scene key swept (e.g. \"inner_ring.speed\")");
  axis.key = key->as_string()->get();
  if (!is_scene_key(axis.key))
    r.fail(line_of(*key), where + ".key",
           fmt::format("'{}' is not a scene key: expected section.key (letters, digits, _), e.g. \"inner_ring.speed\"", axis.key));
  axis.name = t.get("name") ? r.text_of(*t.get("name"), where + ".name") : axis.key;
  // The name is a column of the table and part of the plots' file names.
  static const std::regex column("[A-Za-z0-9_.-]+");
  if (!std::regex_match(axis.name, column))
    r.fail(t.get("name") ? line_of(*t.get("name")) : axis.line, where + ".name",
           fmt::format("'{}' cannot name a column: letters, digits, '_', '.', '-' only", axis.name));
  const toml::node* values = t.get("values");
  const toml::node* range = t.get("range");
  if ((values != nullptr) == (range != nullptr))
    r.fail(line_of(t), where, "give either values = [...] or range = [from, to, step]");
  if (values) {
    if (t.get("unit"))
      r.fail(line_of(*t.get("unit")), where + ".unit",
             "unit applies to a range; give each value its unit (values = [\"1000 rpm\", ...])");
    const toml::array* a = values->as_array();
    if (!a) r.fail(line_of(*values), where + ".values", "expected an array of values");
    for (const toml::node& v : *a) axis.values.push_back(r.text_of(v, where + ".values")), axis.lines.push_back(line_of(v));
  } else {
    if (t.get("unit") && !t.get("unit")->is_string())
      r.fail(line_of(*t.get("unit")), where + ".unit", "expected a unit as text, e.g. \"rpm\"");
    expand_range(r, *range, t.get("unit") ? t.get("unit")->as_string()->get() : "", where, axis);
  }
  if (axis.values.empty()) r.fail(line_of(t), where + ".values", "the axis has no values");
  std::map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < axis.values.size(); ++i)
    if (const auto [at, fresh] = seen.emplace(axis.values[i], i); !fresh)
      r.fail(axis.lines[i], where + ".values",
             fmt::format("'{}' is given twice (values {} and {}): two scenes would be the same", axis.values[i],
                         at->second, i));
  return axis;
}

/// The settings of [campaign] that every scene shares.
struct RunLength {
  double revolutions = 0, end_time = 0, settling_revolutions = 0, settling_time = 0, samples_per_revolution = 0;
  std::vector<std::string> common;        ///< `set`, as overrides
  std::vector<std::string> common_keys;   ///< their scene keys
  std::vector<int> common_lines;          ///< their lines
  int line = 1;                           ///< [campaign]
  int length_line = 1, settling_line = 1, sampling_line = 1;
  std::string length_key = "campaign.revolutions", settling_key = "campaign.settling_time", sampling_key;
};

int line_in(const toml::table& t, std::string_view key) { return t.get(key) ? line_of(*t.get(key)) : line_of(t); }

RunLength read_run_length(const Reader& r, const toml::table& c) {
  RunLength len;
  len.line = line_of(c);
  if (c.contains("revolutions") == c.contains("end_time"))
    r.fail(len.line, "campaign.revolutions", "give either revolutions (of the driven ring) or end_time");
  if (c.contains("revolutions")) len.revolutions = r.number(c, "revolutions", "campaign", 0);
  else len.end_time = r.seconds(c, "end_time"), len.length_key = "campaign.end_time";
  len.length_line = line_in(c, len.length_key.substr(9));
  if (c.contains("settling_revolutions") && c.contains("settling_time"))
    r.fail(line_in(c, "settling_time"), "campaign.settling_time", "give either settling_revolutions or settling_time");
  if (c.contains("settling_revolutions"))
    len.settling_revolutions = r.at_least(c, "settling_revolutions", "campaign", 0),
    len.settling_key = "campaign.settling_revolutions";
  if (c.contains("settling_time")) len.settling_time = r.seconds(c, "settling_time", true);
  len.settling_line = line_in(c, len.settling_key.substr(9));
  len.sampling_key = len.length_key, len.sampling_line = len.length_line;
  if (c.contains("samples_per_revolution")) {
    len.samples_per_revolution = r.number(c, "samples_per_revolution", "campaign", 0);
    len.sampling_key = "campaign.samples_per_revolution", len.sampling_line = line_in(c, "samples_per_revolution");
  }
  if (const toml::node* set = c.get("set")) {
    const toml::table* t = set->as_table();
    if (!t) r.fail(line_of(*set), "campaign.set", "expected a table { \"section.key\" = value, ... }");
    for (const auto& [k, v] : *t) {
      const std::string key(k.str());
      if (!is_scene_key(key))
        r.fail(line_of(v), "campaign.set",
               fmt::format("'{}' is not a scene key: expected \"section.key\" (quoted), e.g. \"inner_ring.speed\"", key));
      for (std::size_t i = 0; i < len.common_keys.size(); ++i)
        if (overlapping(key, len.common_keys[i]))
          r.fail(line_of(v), "campaign.set", fmt::format("'{}' and '{}' set the same value", len.common_keys[i], key));
      len.common.push_back(fmt::format("{}={}", key, r.text_of(v, "campaign.set")));
      len.common_keys.push_back(key);
      len.common_lines.push_back(line_of(v));
    }
  }
  return len;
}

/// The keys the campaign itself sets in every scene (the run length, the sampling): neither an
/// axis nor `set` may give them, they would be overwritten.
std::vector<std::string> campaign_owned_keys(const RunLength& len) {
  std::vector<std::string> keys{"scene.end_time"};
  if (len.samples_per_revolution > 0) keys.push_back("scene.output_interval");
  return keys;
}

/// Each scene key is set once: by one axis, or by `set`, or by the campaign's run length.
void check_keys_set_once(const Reader& r, const Campaign& c, const RunLength& len) {
  const std::vector<std::string> owned = campaign_owned_keys(len);
  const auto owner = [&](const std::string& key) -> std::string {
    for (const std::string& o : owned)
      if (overlapping(key, o))
        return fmt::format("'{}' is set by the campaign's run length ({}{})", o, len.length_key,
                           o == "scene.output_interval" ? " and samples_per_revolution" : "");
    return "";
  };
  for (std::size_t i = 0; i < len.common_keys.size(); ++i)
    if (const std::string why = owner(len.common_keys[i]); !why.empty())
      r.fail(len.common_lines[i], "campaign.set", fmt::format("'{}' cannot be set: {}", len.common_keys[i], why));
  for (std::size_t a = 0; a < c.axes.size(); ++a) {
    const CampaignAxis& axis = c.axes[a];
    const std::string where = fmt::format("axis[{}]", a);
    if (const std::string why = owner(axis.key); !why.empty())
      r.fail(axis.line, where + ".key", fmt::format("'{}' cannot be swept: {}", axis.key, why));
    for (std::size_t b = 0; b < a; ++b) {
      if (overlapping(axis.key, c.axes[b].key))
        r.fail(axis.line, where + ".key",
               fmt::format("'{}' is swept by axis[{}] ('{}') already: one key, one axis", axis.key, b, c.axes[b].key));
      if (axis.name == c.axes[b].name || axis.name == c.axes[b].name + "_si" || axis.name + "_si" == c.axes[b].name)
        r.fail(axis.line, where + ".name",
               fmt::format("axis[{}] and axis[{}] have one column name '{}': give each axis its own name", b, a,
                           axis.name));
    }
    for (std::size_t i = 0; i < len.common_keys.size(); ++i)
      if (overlapping(axis.key, len.common_keys[i]))
        r.fail(len.common_lines[i], "campaign.set",
               fmt::format("'{}' is swept by {} (line {}): `set` would fix a swept key", len.common_keys[i], where,
                           axis.line));
    // The table's own columns (io/report/campaign_table.py) keep their names.
    static const std::set<std::string> reserved{"scene", "status", "attempts", "diagnosis", "window_revolutions",
                                                "window_samples", "steps", "wall_time_s"};
    if (reserved.contains(axis.name))
      r.fail(axis.line, where + ".name", fmt::format("'{}' is a column of the table already: choose another name", axis.name));
  }
}

/// The driven ring's speed relative to the other at the end of the run (rad/s).
double relative_speed(const scene::Scene& s) {
  constexpr double late = 1e9;  // time functions are held constant after their last point
  return std::abs(s.inner_ring.speed(late) - s.outer_ring.speed(late));
}

}  // namespace

namespace {

/// Index lists of the scenes: every combination (product, first axis slowest) or the i-th value of
/// every axis (zip).
std::vector<std::vector<std::size_t>> combinations(const Reader& r, const Campaign& c, int line) {
  std::vector<std::vector<std::size_t>> out;
  if (c.axes.empty()) return {{}};
  if (c.sweep == "zip")
    for (const CampaignAxis& a : c.axes)
      if (a.values.size() != c.axes[0].values.size())
        r.fail(line, "campaign.sweep", fmt::format("zip needs axes of equal length: '{}' has {} values, '{}' {}",
                                                   c.axes[0].key, c.axes[0].values.size(), a.key, a.values.size()));
  // Counted before they are listed: a product of long axes is refused, not expanded.
  double count = c.sweep == "zip" ? double(c.axes[0].values.size()) : 1;
  std::string sizes;
  for (const CampaignAxis& a : c.axes)
    sizes += fmt::format("{}{}", sizes.empty() ? "" : c.sweep == "zip" ? ", " : " x ", a.values.size());
  if (c.sweep != "zip")
    for (const CampaignAxis& a : c.axes) count *= double(a.values.size());
  if (count > kMaxCampaignScenes)
    r.fail(line, "campaign.sweep", fmt::format("the {} of the axes is {:.4g} scenes ({}); a campaign has at most {:.0f}",
                                               c.sweep, count, sizes, kMaxCampaignScenes));
  if (c.sweep == "zip") {
    for (std::size_t i = 0; i < c.axes[0].values.size(); ++i) out.emplace_back(c.axes.size(), i);
    return out;
  }
  std::vector<std::size_t> at(c.axes.size(), 0);
  while (true) {
    out.push_back(at);
    std::size_t k = c.axes.size();
    while (k > 0 && ++at[k - 1] == c.axes[k - 1].values.size()) at[--k] = 0;
    if (k == 0) return out;
  }
}

/// The override of `scene` that a scene error is about: the one whose key it names (the error's key,
/// else its text), the last that sets it; -1 for none.
int blamed_override(const CampaignScene& scene, const scene::SceneError& e) {
  for (std::size_t i = scene.overrides.size(); i-- > 0;) {
    const std::string key = scene.overrides[i].substr(0, scene.overrides[i].find('='));
    if (!e.key().empty() && overlapping(e.key(), key)) return static_cast<int>(i);
  }
  for (std::size_t i = scene.overrides.size(); i-- > 0;)
    if (std::string(e.what()).find(scene.overrides[i].substr(0, scene.overrides[i].find('='))) != std::string::npos)
      return static_cast<int>(i);
  return -1;
}

/// One scene of the campaign: its overrides (common, axes, run length), validated by parsing.
CampaignScene expand_scene(const Reader& r, const Campaign& c, const RunLength& len,
                           const std::vector<std::size_t>& at, std::size_t index) {
  CampaignScene s;
  s.id = fmt::format("s{:03}", index);
  s.overrides = len.common;
  s.override_lines = len.common_lines;
  s.override_keys.assign(len.common.size(), "campaign.set");
  for (std::size_t a = 0; a < c.axes.size(); ++a) {
    s.axis_values.push_back(c.axes[a].values[at[a]]);
    s.overrides.push_back(fmt::format("{}={}", c.axes[a].key, c.axes[a].values[at[a]]));
    s.override_lines.push_back(c.axes[a].lines[at[a]]);
    s.override_keys.push_back(fmt::format("axis[{}].values", a));
  }
  const auto parsed = [&]() {
    try {
      return scene::parse_scene(c.base_text, c.scene_path, s.overrides);
    } catch (const scene::SceneError& e) {
      // Blame the override the error names (an axis value, `set`, the run length), else the
      // campaign's own settings.
      const int i = blamed_override(s, e);
      if (i < 0) r.fail(len.line, "campaign", fmt::format("scene {} is rejected: {}", s.id, e.what()));
      const auto k = static_cast<std::size_t>(i);
      const bool axis = k >= len.common.size() && k < len.common.size() + c.axes.size();
      r.fail(s.override_lines[k], s.override_keys[k],
             fmt::format("scene {}{} is rejected: {}", s.id,
                         axis ? fmt::format(" ({})", s.axis_values[k - len.common.size()]) : "", e.what()));
    }
  };
  scene::Scene scene = parsed();
  const double omega = relative_speed(scene);
  const double period = omega > 0 ? 2 * std::numbers::pi / omega : 0;
  if (period == 0 && (len.revolutions > 0 || len.settling_revolutions > 0 || len.samples_per_revolution > 0))
    r.fail(len.revolutions > 0 ? len.length_line : len.settling_revolutions > 0 ? len.settling_line : len.sampling_line,
           len.revolutions > 0 ? len.length_key : len.settling_revolutions > 0 ? len.settling_key : len.sampling_key,
           fmt::format("scene {}: no ring turns (inner and outer ring at the same speed), so revolutions give no time", s.id));
  s.end_time = len.revolutions > 0 ? len.revolutions * period : len.end_time;
  s.overrides.push_back(fmt::format("scene.end_time={:.17g} s", s.end_time));
  s.override_lines.push_back(len.length_line), s.override_keys.push_back(len.length_key);
  if (len.samples_per_revolution > 0) {
    s.overrides.push_back(fmt::format("scene.output_interval={:.17g} s", period / len.samples_per_revolution));
    s.override_lines.push_back(len.sampling_line), s.override_keys.push_back(len.sampling_key);
  }
  scene = parsed();
  s.settling_time = len.settling_revolutions > 0 ? len.settling_revolutions * period : len.settling_time;
  if (s.settling_time >= s.end_time)
    r.fail(len.settling_line, len.settling_key,
           fmt::format("scene {}: the settling time {:.6g} s is not shorter than the run ({:.6g} s)", s.id,
                       s.settling_time, s.end_time));
  // The dispatch order's cost: the measured relation of steps and wall time to speed.
  const double revolutions = s.end_time * omega / (2 * std::numbers::pi);
  const SceneCost cost = predict_scene_cost(revolutions, omega * 60 / (2 * std::numbers::pi), scene.bearing.rolling_elements);
  s.predicted_steps = cost.steps;
  s.predicted_cost = cost.wall_seconds;
  return s;
}

}  // namespace

const std::vector<std::string>& known_campaign_metrics() {
  // The table's column groups (io/report/campaign_table.py, COLUMNS_OF).
  static const std::vector<std::string> names{"cage_speed",   "cage_slip",        "cage_whirl_radius",
                                              "vortex",       "impacts",          "pocket_force",
                                              "max_element_load", "element_load_range", "power_loss",
                                              "life",         "steps",            "wall_time"};
  return names;
}

Campaign load_campaign(const std::string& path) {
  Campaign c;
  c.file = path;
  const Reader r(path);
  toml::table root;
  try {
    root = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    r.fail(static_cast<int>(e.source().begin.line), "", fmt::format("invalid TOML: {}", e.description()));
  }
  constexpr std::string_view top[] = {"campaign", "axis"};
  for (const auto& [k, v] : root)
    if (std::find(std::begin(top), std::end(top), k.str()) == std::end(top))
      r.fail(line_of(v), std::string(k.str()), fmt::format("unknown section '{}'; allowed: [campaign], [[axis]]", k.str()));
  const toml::table* campaign = root["campaign"].as_table();
  if (!campaign) r.fail(1, "campaign", "required section [campaign] is missing");
  r.allow(*campaign, kCampaignKeys, "campaign");
  c.key_lines["campaign"] = line_of(*campaign);
  for (const auto& [k, v] : *campaign) c.key_lines["campaign." + std::string(k.str())] = line_of(v);
  c.name = campaign->get("name") ? r.text_of(*campaign->get("name"), "campaign.name")
                                 : std::filesystem::path(path).stem().string();
  if (!campaign->get("scene")) r.fail(line_of(*campaign), "campaign.scene", "required: the base scene file");
  const auto scene = std::filesystem::path(r.text_of(*campaign->get("scene"), "campaign.scene"));
  c.scene_path = (scene.is_absolute() ? scene : std::filesystem::path(path).parent_path() / scene).lexically_normal().string();
  c.base_text = scene::load_scene(c.scene_path).text;  // a SceneError names the scene file
  if (const toml::node* sweep = campaign->get("sweep")) {
    c.sweep = r.text_of(*sweep, "campaign.sweep");
    if (c.sweep != "product" && c.sweep != "zip") r.fail(line_of(*sweep), "campaign.sweep", "expected \"product\" or \"zip\"");
  }
  if (campaign->contains("ranks_per_scene")) {
    c.ranks_per_scene = r.whole(*campaign, "ranks_per_scene", "campaign", 1, kMaxRanksPerScene);
    c.ranks_line = line_of(*campaign->get("ranks_per_scene"));
  }
  c.metrics = known_campaign_metrics();
  if (const toml::node* m = campaign->get("metrics")) {
    c.metrics.clear();
    const toml::array* a = m->as_array();
    if (!a || a->empty()) r.fail(line_of(*m), "campaign.metrics", "expected a non-empty array of metric names");
    for (const toml::node& n : *a) {
      c.metrics.push_back(r.text_of(n, "campaign.metrics"));
      if (std::count(c.metrics.begin(), c.metrics.end(), c.metrics.back()) > 1)
        r.fail(line_of(n), "campaign.metrics", fmt::format("'{}' is named twice", c.metrics.back()));
      const auto& known = known_campaign_metrics();
      if (std::find(known.begin(), known.end(), c.metrics.back()) == known.end())
        r.fail(line_of(n), "campaign.metrics",
               fmt::format("unknown metric '{}'; known: {}", c.metrics.back(), fmt::join(known, ", ")));
    }
  }
  if (const toml::node* axes = root.get("axis")) {
    const toml::array* a = axes->as_array();
    if (!a || !a->is_array_of_tables()) r.fail(line_of(*axes), "axis", "expected [[axis]] tables");
    for (const toml::node& t : *a) {
      c.axes.push_back(read_axis(r, *t.as_table(), static_cast<int>(c.axes.size())));
      c.key_lines[fmt::format("axis[{}]", c.axes.size() - 1)] = c.axes.back().line;
    }
  }
  const RunLength len = read_run_length(r, *campaign);
  check_keys_set_once(r, c, len);
  std::size_t index = 0;
  for (const auto& at : combinations(r, c, line_of(*campaign))) c.scenes.push_back(expand_scene(r, c, len, at, index++));
  return c;
}

scene::Scene campaign_scene(const Campaign& campaign, const CampaignScene& scene) {
  return scene::parse_scene(campaign.base_text, campaign.scene_path, scene.overrides);
}

}  // namespace raceway::driver
