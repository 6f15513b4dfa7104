#include "solver/driver/campaign_file.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

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
    throw io::SceneError(file_, line, key, reason);
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
  double seconds(const toml::table& t, std::string_view key) const {
    const toml::node* n = t.get(key);
    try {
      const double v = io::parse_quantity(*n, io::dim::time, "0.5 s");
      if (v > 0) return v;
    } catch (const std::exception& e) {
      fail(line_of(*n), fmt::format("campaign.{}", key), e.what());
    }
    fail(line_of(*n), fmt::format("campaign.{}", key), "must be greater than zero");
  }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

CampaignAxis read_axis(const Reader& r, const toml::table& t, int index) {
  const std::string where = fmt::format("axis[{}]", index);
  r.allow(t, kAxisKeys, where);
  CampaignAxis axis;
  const toml::node* key = t.get("key");
  if (!key || !key->is_string()) r.fail(line_of(t), where + ".key", "required: the scene key swept (e.g. \"inner_ring.speed\")");
  axis.key = key->as_string()->get();
  axis.name = t.get("name") ? r.text_of(*t.get("name"), where + ".name") : axis.key;
  const toml::node* values = t.get("values");
  const toml::node* range = t.get("range");
  if ((values != nullptr) == (range != nullptr))
    r.fail(line_of(t), where, "give either values = [...] or range = [from, to, step]");
  if (values) {
    const toml::array* a = values->as_array();
    if (!a) r.fail(line_of(*values), where + ".values", "expected an array of values");
    for (const toml::node& v : *a) axis.values.push_back(r.text_of(v, where + ".values")), axis.lines.push_back(line_of(v));
  } else {
    const toml::array* a = range->as_array();
    const auto at = [&](std::size_t i) { return a && i < a->size() ? a->get(i)->value<double>() : std::nullopt; };
    const auto from = at(0), to = at(1), step = at(2);
    if (!a || a->size() != 3 || !from || !to || !step || !(*step > 0) || *to < *from)
      r.fail(line_of(*range), where + ".range", "expected [from, to, step], numbers with from <= to and step > 0");
    const std::string unit = t.get("unit") ? r.text_of(*t.get("unit"), where + ".unit") : "";
    for (long i = 0; *from + double(i) * *step <= *to + 1e-9 * *step; ++i) {
      const double v = *from + double(i) * *step;
      axis.values.push_back(unit.empty() ? fmt::format("{}", v) : fmt::format("{} {}", v, unit));
      axis.lines.push_back(line_of(*range));
    }
  }
  if (axis.values.empty()) r.fail(line_of(t), where + ".values", "the axis has no values");
  return axis;
}

/// The settings of [campaign] that every scene shares.
struct RunLength {
  double revolutions = 0, end_time = 0, settling_revolutions = 0, settling_time = 0, samples_per_revolution = 0;
  std::vector<std::string> common;  ///< `set`
  int line = 1;
};

RunLength read_run_length(const Reader& r, const toml::table& c) {
  RunLength len;
  len.line = line_of(c);
  if (c.contains("revolutions") == c.contains("end_time"))
    r.fail(len.line, "campaign.revolutions", "give either revolutions (of the driven ring) or end_time");
  if (c.contains("revolutions")) len.revolutions = r.number(c, "revolutions", "campaign", 0);
  else len.end_time = r.seconds(c, "end_time");
  if (c.contains("settling_revolutions")) len.settling_revolutions = r.number(c, "settling_revolutions", "campaign", -1);
  if (c.contains("settling_time")) len.settling_time = r.seconds(c, "settling_time");
  if (c.contains("samples_per_revolution")) len.samples_per_revolution = r.number(c, "samples_per_revolution", "campaign", 0);
  if (const toml::node* set = c.get("set")) {
    const toml::table* t = set->as_table();
    if (!t) r.fail(line_of(*set), "campaign.set", "expected a table { \"section.key\" = value, ... }");
    for (const auto& [k, v] : *t) len.common.push_back(fmt::format("{}={}", k.str(), r.text_of(v, "campaign.set")));
  }
  return len;
}

/// The driven ring's speed relative to the other at the end of the run (rad/s).
double relative_speed(const io::Scene& s) {
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
  if (c.sweep == "zip") {
    for (const CampaignAxis& a : c.axes)
      if (a.values.size() != c.axes[0].values.size())
        r.fail(line, "campaign.sweep", fmt::format("zip needs axes of equal length: '{}' has {} values, '{}' {}",
                                                   c.axes[0].key, c.axes[0].values.size(), a.key, a.values.size()));
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

/// One scene of the campaign: its overrides (common, axes, run length), validated by parsing.
CampaignScene expand_scene(const Reader& r, const Campaign& c, const RunLength& len,
                           const std::vector<std::size_t>& at, std::size_t index) {
  CampaignScene s;
  s.id = fmt::format("s{:03}", index);
  s.overrides = len.common;
  for (std::size_t a = 0; a < c.axes.size(); ++a) {
    s.axis_values.push_back(c.axes[a].values[at[a]]);
    s.overrides.push_back(fmt::format("{}={}", c.axes[a].key, c.axes[a].values[at[a]]));
  }
  const auto parsed = [&](const std::vector<std::string>& overrides) {
    try {
      return io::parse_scene(c.base_text, c.scene_path, overrides);
    } catch (const io::SceneError& e) {
      // Blame the first axis value the error names, else the campaign's own settings.
      for (std::size_t a = 0; a < c.axes.size(); ++a)
        if (std::string(e.what()).find(c.axes[a].key) != std::string::npos)
          r.fail(c.axes[a].lines[at[a]], fmt::format("axis[{}].values", a),
                 fmt::format("scene {} ({}) is rejected: {}", s.id, c.axes[a].values[at[a]], e.what()));
      r.fail(len.line, "campaign", fmt::format("scene {} is rejected: {}", s.id, e.what()));
    }
  };
  io::Scene scene = parsed(s.overrides);
  const double omega = relative_speed(scene);
  const double period = omega > 0 ? 2 * std::numbers::pi / omega : 0;
  if (period == 0 && (len.revolutions > 0 || len.settling_revolutions > 0 || len.samples_per_revolution > 0))
    r.fail(len.line, "campaign.revolutions",
           fmt::format("scene {}: no ring turns (inner and outer ring at the same speed), so revolutions give no time", s.id));
  s.end_time = len.revolutions > 0 ? len.revolutions * period : len.end_time;
  s.overrides.push_back(fmt::format("scene.end_time={:.17g} s", s.end_time));
  if (len.samples_per_revolution > 0)
    s.overrides.push_back(fmt::format("scene.output_interval={:.17g} s", period / len.samples_per_revolution));
  scene = parsed(s.overrides);
  s.settling_time = len.settling_revolutions > 0 ? len.settling_revolutions * period : len.settling_time;
  if (s.settling_time >= s.end_time)
    r.fail(len.line, "campaign.settling_time",
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
                                              "steps",        "wall_time"};
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
  c.name = campaign->get("name") ? r.text_of(*campaign->get("name"), "campaign.name")
                                 : std::filesystem::path(path).stem().string();
  if (!campaign->get("scene")) r.fail(line_of(*campaign), "campaign.scene", "required: the base scene file");
  const auto scene = std::filesystem::path(r.text_of(*campaign->get("scene"), "campaign.scene"));
  c.scene_path = (scene.is_absolute() ? scene : std::filesystem::path(path).parent_path() / scene).lexically_normal().string();
  c.base_text = io::load_scene(c.scene_path).text;  // a SceneError names the scene file
  if (const toml::node* sweep = campaign->get("sweep")) {
    c.sweep = r.text_of(*sweep, "campaign.sweep");
    if (c.sweep != "product" && c.sweep != "zip") r.fail(line_of(*sweep), "campaign.sweep", "expected \"product\" or \"zip\"");
  }
  if (campaign->contains("ranks_per_scene"))
    c.ranks_per_scene = static_cast<int>(r.number(*campaign, "ranks_per_scene", "campaign", 0));
  c.metrics = known_campaign_metrics();
  if (const toml::node* m = campaign->get("metrics")) {
    c.metrics.clear();
    const toml::array* a = m->as_array();
    if (!a || a->empty()) r.fail(line_of(*m), "campaign.metrics", "expected a non-empty array of metric names");
    for (const toml::node& n : *a) {
      c.metrics.push_back(r.text_of(n, "campaign.metrics"));
      const auto& known = known_campaign_metrics();
      if (std::find(known.begin(), known.end(), c.metrics.back()) == known.end())
        r.fail(line_of(n), "campaign.metrics",
               fmt::format("unknown metric '{}'; known: {}", c.metrics.back(), fmt::join(known, ", ")));
    }
  }
  if (const toml::node* axes = root.get("axis")) {
    const toml::array* a = axes->as_array();
    if (!a || !a->is_array_of_tables()) r.fail(line_of(*axes), "axis", "expected [[axis]] tables");
    for (const toml::node& t : *a) c.axes.push_back(read_axis(r, *t.as_table(), static_cast<int>(c.axes.size())));
  }
  const RunLength len = read_run_length(r, *campaign);
  std::size_t index = 0;
  for (const auto& at : combinations(r, c, line_of(*campaign))) c.scenes.push_back(expand_scene(r, c, len, at, index++));
  return c;
}

io::Scene campaign_scene(const Campaign& campaign, const CampaignScene& scene) {
  return io::parse_scene(campaign.base_text, campaign.scene_path, scene.overrides);
}

}  // namespace raceway::driver
