// raceway scene parser: TOML (toml++) -> validated io::Scene in SI units.
//
// Structure: a small `Section` helper reads typed values from one TOML table (with units, bounds,
// defaults and the line of every value for errors); parse_scene() walks the schema section by
// section and finishes with the physical cross-checks. Unknown keys are rejected per section before
// any value is read, so a misspelt key is reported as such and not as a missing one.
#include "io/scene/scene_parser.hpp"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <span>
#include <sstream>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "io/scene/units.hpp"

namespace raceway::io {

namespace {

std::string compose(const std::string& file, int line, const std::string& key, const std::string& reason) {
  if (line <= 0)
    return key.empty() ? fmt::format("{}: {}", file, reason) : fmt::format("{}: key '{}': {}", file, key, reason);
  if (key.empty()) return fmt::format("{}:{}: {}", file, line, reason);
  return fmt::format("{}:{}: key '{}': {}", file, line, key, reason);
}

}  // namespace

SceneError::SceneError(std::string file, int line, std::string key, std::string reason)
    : std::runtime_error(compose(file, line, key, reason)),
      file_(std::move(file)),
      line_(line),
      key_(std::move(key)),
      reason_(std::move(reason)) {}

namespace {

using Names = std::vector<std::string_view>;

// ---- the schema: sections and keys -------------------------------------------------------------
// Each section first rejects keys it does not know at all (with a suggestion); keys that exist but
// belong to the other model (planar / spatial) or bearing type are then rejected with the reason.
const Names kSections = {"scene",      "bearing",    "materials", "cage",   "inner_ring",
                         "outer_ring", "lubricant",  "contact",   "solver", "output"};
const Names kBearingTypes = {"cylindrical_roller", "deep_groove_ball", "four_point_contact_ball"};
const Names kBearingKeys = {"type",           "rolling_elements",  "roller_diameter",        "roller_length",
                            "ball_diameter",  "inner_conformity",  "outer_conformity",       "arc_contact_angle",
                            "pitch_diameter", "radial_clearance",  "inner_bore_diameter",    "outer_outside_diameter",
                            "ring_width",     "roller_material",   "ball_material",          "ring_material"};
const Names kBallOnlyBearingKeys = {"ball_diameter", "inner_conformity", "outer_conformity", "arc_contact_angle",
                                    "ball_material"};
const Names kCageKeys = {"guidance",       "pocket_clearance", "land_clearance", "bar_width", "land_width",
                         "material",       "mass",             "inertia",        "pocket_shape",
                         "transverse_inertia", "inner_diameter", "outer_diameter", "width", "support"};
const Names kSpatialCageKeys = {"pocket_shape", "transverse_inertia", "inner_diameter", "outer_diameter", "width",
                                "support"};
const Names kCageSupportKeys = {"radial_stiffness", "radial_damping", "axial_stiffness",
                                "axial_damping",    "tilt_stiffness", "tilt_damping"};
const Names kRingKeys = {"motion", "speed",   "translation", "axial",   "tilt",   "misalignment",
                         "load",   "support", "mass",        "inertia", "transverse_inertia"};
const Names kSpatialRingKeys = {"axial", "tilt", "misalignment", "transverse_inertia"};
const Names kRingLoadKeys = {"fx", "fy", "fz", "mx", "my", "mz"};
const Names kRingSupportKeys = {"stiffness",     "damping",        "axial_stiffness",
                                "axial_damping", "tilt_stiffness", "tilt_damping"};
const Names kContactSections = {"roller_race", "roller_cage", "ball_race", "ball_cage", "cage_land"};
const Names kPlanarContactSections = {"roller_race", "roller_cage"};
const Names kSpatialContactSections = {"ball_race", "ball_cage"};
const Names kContactKeys = {"normal",   "slices",   "crown_drop",           "damping",             "damping_factor",
                            "traction", "friction_coefficient", "slip_velocity_scale", "grid", "rolling_resistance"};

// ---- contact law registries --------------------------------------------------------------------
// The one list of law names a scene may use, per law kind, with the contacts each law applies to.
// contact/ owns the implementations (line_contact.hpp: palmgren; point_contact.hpp: hertz, the
// tanh traction curve, limiting-shear traction; Hunt-Crossley damping in both): a name added here
// must exist there, and the model builder maps each name to its implementation.
enum ContactKind : unsigned { line_contact = 1u, ball_race_contact = 2u, ball_cage_contact = 4u };
constexpr unsigned kAllContacts = line_contact | ball_race_contact | ball_cage_contact;
constexpr unsigned kPointContacts = ball_race_contact | ball_cage_contact;
struct LawName {
  std::string_view name;
  unsigned contacts;  ///< ContactKind bits
};
constexpr LawName kNormalLaws[] = {{"palmgren", line_contact}, {"hertz", kPointContacts}};
constexpr LawName kDampingLaws[] = {{"hunt_crossley", kAllContacts}, {"none", kAllContacts}};
constexpr LawName kTractionLaws[] = {{"tanh", kAllContacts}, {"none", kAllContacts},
                                     {"limiting_shear", ball_race_contact}};

const char* contact_kind_name(unsigned kind) {
  switch (kind) {
    case line_contact: return "line contacts (roller_race, roller_cage, cage_land)";
    case ball_race_contact: return "ball_race contacts";
    case ball_cage_contact: return "ball_cage contacts";
    default: return "point contacts (ball_race, ball_cage)";
  }
}

const Material kBuiltinMaterials[] = {
    {"steel", 7850.0, 208e9, 0.3},
    {"brass", 8500.0, 100e9, 0.34},
    {"polyamide", 1140.0, 3e9, 0.4},
};

// ---- small helpers ----------------------------------------------------------------------------
std::string join(const Names& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

std::string mm(double metres) { return fmt::format("{:.6g} mm", metres * 1e3); }

int line_of(const toml::node& n) { return static_cast<int>(n.source().begin.line); }

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a floating-point number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    default: return "a date/time";
  }
}

/// The value as the user wrote it, for messages.
std::string shown(const toml::node& n) {
  if (const auto* s = n.as_string()) return s->get();
  if (const auto* i = n.as_integer()) return fmt::format("{}", i->get());
  if (const auto* f = n.as_floating_point()) return fmt::format("{}", f->get());
  if (const auto* b = n.as_boolean()) return b->get() ? "true" : "false";
  return type_name(n);
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0u : 1u)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string suggestion(std::string_view word, const Names& names) {
  std::string_view best;
  std::size_t best_d = 3;  // suggest only close matches
  for (const auto& n : names) {
    const std::size_t d = edit_distance(word, n);
    if (d < best_d) best_d = d, best = n;
  }
  return best.empty() ? std::string() : fmt::format(" (did you mean '{}'?)", best);
}

enum class Bound { any, positive, non_negative };

/// Typed access to one TOML table of the scene, with its dotted path and header line.
class Section {
 public:
  Section(const std::string& file, const toml::table* table, std::string path, int line)
      : file_(file), table_(table), path_(std::move(path)), line_(std::max(line, 1)) {}

  bool present() const { return table_ != nullptr; }
  const toml::table* table() const { return table_; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  int header_line() const { return line_; }
  const toml::node* node(std::string_view key) const { return table_ ? table_->get(key) : nullptr; }
  bool has(std::string_view key) const { return node(key) != nullptr; }
  std::string dotted(std::string_view key) const { return path_ + "." + std::string(key); }
  /// Line of the key's value, or of the section header when the key is absent.
  int line(std::string_view key) const {
    const toml::node* n = node(key);
    return n ? std::max(line_of(*n), 1) : line_;
  }

  [[noreturn]] void fail(std::string_view key, std::string reason) const {
    throw SceneError(file_, line(key), dotted(key), std::move(reason));
  }
  [[noreturn]] void fail_at(const toml::node& n, std::string_view key, std::string reason) const {
    throw SceneError(file_, std::max(line_of(n), 1), dotted(key), std::move(reason));
  }
  /// Fails at the key with reason() unless ok (the reason is only formatted on failure).
  template <class Reason>
  void check(bool ok, std::string_view key, Reason&& reason) const {
    if (!ok) fail(key, reason());
  }

  /// Rejects keys not in `allowed`, naming the key and listing the allowed ones.
  void allow(const Names& allowed) const {
    if (!table_) return;
    for (const auto& [k, v] : *table_) {
      if (std::find(allowed.begin(), allowed.end(), k.str()) != allowed.end()) continue;
      fail_at(v, k.str(),
              fmt::format("unknown key '{}' in [{}]{}; allowed keys: {}", k.str(), path_, suggestion(k.str(), allowed),
                          join(allowed)));
    }
  }

  /// Rejects any of `keys` that is present: keys that exist in the schema but not for this model,
  /// bearing type or setting; `reason` says why.
  void reject(const Names& keys, std::string_view reason) const {
    for (const auto& k : keys)
      if (const toml::node* n = node(k)) fail_at(*n, k, std::string(reason));
  }

  const toml::node& required(std::string_view key) const {
    if (const toml::node* n = node(key)) return *n;
    if (!table_)
      throw SceneError(file_, line_, dotted(key),
                       fmt::format("required key is missing (section [{}] is missing)", path_));
    fail(key, fmt::format("required key is missing in [{}]", path_));
  }

  std::string string(std::string_view key, std::optional<std::string_view> fallback = std::nullopt) const {
    const toml::node* n = fallback && !has(key) ? nullptr : &required(key);
    if (!n) return std::string(*fallback);
    if (const auto* s = n->as_string()) return s->get();
    fail_at(*n, key, fmt::format("expected a string, found {} ({})", type_name(*n), shown(*n)));
  }

  /// One of `options`; `noun` names what is chosen in the error ("unknown traction law 'x'").
  std::string choice(std::string_view key, const Names& options, std::optional<std::string_view> fallback,
                     std::string_view noun = "value") const {
    std::string v = string(key, fallback);
    if (std::find(options.begin(), options.end(), v) == options.end())
      fail(key, fmt::format("unknown {} '{}'{}; known: {}", noun, v, suggestion(v, options), join(options)));
    return v;
  }

  bool boolean(std::string_view key, bool fallback) const {
    const toml::node* n = node(key);
    if (!n) return fallback;
    if (const auto* b = n->as_boolean()) return b->get();
    fail_at(*n, key, fmt::format("expected true or false, found {} ({})", type_name(*n), shown(*n)));
  }

  long integer(std::string_view key, long lo, long hi, std::optional<long> fallback) const {
    const toml::node* n = fallback && !has(key) ? nullptr : &required(key);
    if (!n) return *fallback;
    const auto* i = n->as_integer();
    if (!i) fail_at(*n, key, fmt::format("expected an integer, found {} ({})", type_name(*n), shown(*n)));
    const auto v = i->get();
    if (v < lo || v > hi)
      fail_at(*n, key, hi == LONG_MAX ? fmt::format("must be at least {}, found {}", lo, v)
                                      : fmt::format("must be between {} and {}, found {}", lo, hi, v));
    return static_cast<long>(v);
  }

  /// A quantity converted to SI; absent -> fallback (not bound-checked), or an error when required.
  double quantity(std::string_view key, Dimension d, Bound bound, std::optional<double> fallback) const {
    const toml::node* n = fallback && !has(key) ? nullptr : &required(key);
    if (!n) return *fallback;
    const double v = to_si(*n, key, d);
    if (bound == Bound::positive && !(v > 0))
      fail_at(*n, key, fmt::format("must be greater than zero, found '{}'", shown(*n)));
    if (bound == Bound::non_negative && !(v >= 0))
      fail_at(*n, key, fmt::format("must not be negative, found '{}'", shown(*n)));
    return v;
  }

  /// A constant quantity or { time = [...], value = [...] } (piecewise linear, held outside).
  TimeFunction time_function(std::string_view key, Dimension d, std::optional<double> fallback) const {
    const toml::node* n = fallback && !has(key) ? nullptr : &required(key);
    if (!n) return TimeFunction::constant(*fallback);
    if (!n->is_table()) return TimeFunction::constant(to_si(*n, key, d));
    const Section t = sub(key);
    t.allow({"time", "value"});
    const toml::array& times = t.array("time");
    const toml::array& values = t.array("value");
    if (times.size() < 2) t.fail("time", fmt::format("a table needs at least 2 points, found {}", times.size()));
    if (values.size() != times.size())
      t.fail("value", fmt::format("{} values for {} times; the lengths must be equal", values.size(), times.size()));
    TimeFunction f;
    for (std::size_t i = 0; i < times.size(); ++i) {
      f.times.push_back(t.to_si(*times.get(i), "time", dim::time));
      f.values.push_back(t.to_si(*values.get(i), "value", d));
      if (i > 0 && !(f.times[i] > f.times[i - 1]))
        t.fail_at(*times.get(i), "time",
                  fmt::format("times must be strictly increasing: '{}' follows '{}'", shown(*times.get(i)),
                              shown(*times.get(i - 1))));
    }
    return f;
  }

  const toml::array& array(std::string_view key) const {
    const toml::node& n = required(key);
    if (const auto* a = n.as_array()) return *a;
    fail_at(n, key, fmt::format("expected an array, found {} ({})", type_name(n), shown(n)));
  }

  /// A nested table (inline or [a.b] header); an absent one is an empty Section at this header line.
  Section sub(std::string_view key) const {
    const toml::node* n = node(key);
    if (!n) return Section(file_, nullptr, dotted(key), line_);
    if (const auto* t = n->as_table()) return Section(file_, t, dotted(key), line_of(*n));
    fail_at(*n, key, fmt::format("expected a table, found {} ({})", type_name(*n), shown(*n)));
  }

  double to_si(const toml::node& n, std::string_view key, Dimension d) const {
    try {
      return parse_quantity(n, d);
    } catch (const UnitError& e) {
      fail_at(n, key, e.what());
    }
  }

 private:
  const std::string& file_;
  const toml::table* table_;
  std::string path_;
  int line_;
};

/// A top-level section; a missing required one is an error at line 1.
Section top(const std::string& file, const toml::table& root, std::string_view name, bool required) {
  const toml::node* n = root.get(name);
  if (!n) {
    if (required) throw SceneError(file, 1, std::string(name), fmt::format("required section [{}] is missing", name));
    return Section(file, nullptr, std::string(name), 1);
  }
  const auto* t = n->as_table();
  if (!t)
    throw SceneError(file, line_of(*n), std::string(name),
                     fmt::format("expected a section [{}], found {} ({})", name, type_name(*n), shown(*n)));
  return Section(file, t, std::string(name), line_of(*n));
}

// ---- sections ---------------------------------------------------------------------------------

constexpr double kPi = std::numbers::pi;
constexpr std::string_view kSpatialOnly = "only for spatial scenes (model = \"spatial\")";

void parse_info(const Section& s, Scene& scene) {
  s.allow({"name", "model", "end_time", "output_interval", "gravity"});
  SceneInfo& info = scene.scene;
  info.name = s.string("name");
  // planar: cylindrical roller bearings (x, y, rotation about z); spatial: ball bearings, all six
  // directions. parse_bearing checks that the model fits the bearing type.
  info.model = s.choice("model", {"planar", "spatial"}, std::nullopt, "model") == "spatial" ? ModelKind::spatial
                                                                                           : ModelKind::planar;
  info.end_time = s.quantity("end_time", dim::time, Bound::positive, std::nullopt);
  info.output_interval = s.quantity("output_interval", dim::time, Bound::positive, std::nullopt);
  s.check(info.output_interval <= info.end_time, "output_interval", [&] {
    return fmt::format("output interval of {:g} s is longer than end_time ({:g} s)", info.output_interval,
                       info.end_time);
  });
  scene.gravity = s.boolean("gravity", false);
}

void parse_materials(const Section& s, std::map<std::string, Material>& materials) {
  for (const auto& m : kBuiltinMaterials) materials[m.name] = m;
  if (!s.present()) return;
  for (const auto& [k, v] : *s.table()) {
    const std::string name(k.str());
    if (!v.is_table())
      s.fail_at(v, name,
                fmt::format("expected a table [materials.{}] with density, youngs_modulus, poisson_ratio", name));
    const Section m = s.sub(name);
    m.allow({"density", "youngs_modulus", "poisson_ratio"});
    Material mat{name, 0, 0, 0};
    mat.density = m.quantity("density", dim::density, Bound::positive, std::nullopt);
    mat.youngs_modulus = m.quantity("youngs_modulus", dim::pressure, Bound::positive, std::nullopt);
    mat.poisson_ratio = m.quantity("poisson_ratio", dim::none, Bound::any, std::nullopt);
    m.check(mat.poisson_ratio >= 0 && mat.poisson_ratio < 0.5, "poisson_ratio",
            [&] { return fmt::format("must be in [0, 0.5), found {}", mat.poisson_ratio); });
    materials[name] = mat;
  }
}

std::string material_ref(const Section& s, std::string_view key, std::string_view fallback,
                         const std::map<std::string, Material>& materials) {
  std::string name = s.string(key, fallback);
  if (!materials.count(name)) {
    Names known;
    for (const auto& [k, v] : materials) known.push_back(k);
    s.fail(key, fmt::format("unknown material '{}'; known: {} (define others in [materials.NAME])", name, join(known)));
  }
  return name;
}

/// Ball size and groove geometry (ball bearings). Conformities and the four-point arc angle have no
/// defaults: they set the contact stiffness and the contact angle, and every catalogue gives them.
void parse_ball_geometry(const Section& s, BearingGeometry& b) {
  BallGeometry& g = b.ball;
  g.ball_diameter = s.quantity("ball_diameter", dim::length, Bound::positive, std::nullopt);
  for (const std::string_view key : {"inner_conformity", "outer_conformity"}) {
    const double f = s.quantity(key, dim::none, Bound::any, std::nullopt);
    s.check(f > 0.5 && f <= 0.6, key, [&] {
      return fmt::format("conformity (groove radius / ball diameter) must be greater than 0.5 and at most 0.6, "
                         "found {}{}",
                         f, f <= 0.5 ? " (the groove radius must exceed the ball radius)"
                                     : " (ball bearing grooves are 0.505 to 0.58)");
    });
    (key == "inner_conformity" ? g.inner_conformity : g.outer_conformity) = f;
  }
  if (b.type == BearingType::four_point_contact_ball) {
    if (!s.has("arc_contact_angle"))
      s.fail("arc_contact_angle",
             "required for type = \"four_point_contact_ball\": the angle at which a centred ball touches each "
             "gothic arc, e.g. \"35 deg\"");
    g.arc_contact_angle = s.quantity("arc_contact_angle", dim::angle, Bound::any, std::nullopt);
    const toml::node& n = s.required("arc_contact_angle");
    s.check(g.arc_contact_angle > 0 && g.arc_contact_angle < kPi / 3, "arc_contact_angle", [&] {
      return fmt::format("must be greater than 0 and less than 60 deg, found '{}'{}", shown(n),
                         n.is_number() ? " (a bare number is in rad; write e.g. \"35 deg\")" : "");
    });
  } else {
    s.reject({"arc_contact_angle"},
             "only for type = \"four_point_contact_ball\": a deep groove ball bearing's contact angle comes out of "
             "its clearance, conformities and loads");
    g.arc_contact_angle = 0;
  }
}

void parse_bearing(const Section& s, const Section& info, Scene& scene) {
  s.allow(kBearingKeys);
  BearingGeometry& b = scene.bearing;
  const std::string type = s.choice("type", kBearingTypes, std::nullopt, "bearing type");
  b.type = type == "cylindrical_roller" ? BearingType::cylindrical_roller
         : type == "deep_groove_ball"   ? BearingType::deep_groove_ball
                                        : BearingType::four_point_contact_ball;
  const bool ball = b.is_ball_bearing();
  const bool spatial = scene.scene.model == ModelKind::spatial;
  if (spatial && !ball)
    info.fail("model", "spatial cylindrical roller bearings are not implemented; use model = \"planar\"");
  if (!spatial && ball)
    info.fail("model", fmt::format("a {} bearing needs model = \"spatial\": ball-groove contacts are three-"
                                   "dimensional (the planar model is for cylindrical roller bearings)",
                                   type));
  b.rolling_elements = static_cast<int>(s.integer("rolling_elements", 3, INT_MAX, std::nullopt));
  if (ball) {
    s.reject({"roller_diameter"}, "a ball bearing has no roller diameter: give ball_diameter");
    s.reject({"roller_length"}, "a ball bearing has no roller length: ring_width gives the width of the rings");
    parse_ball_geometry(s, b);
  } else {
    s.reject(kBallOnlyBearingKeys,
             "only for ball bearings (type = \"deep_groove_ball\" or \"four_point_contact_ball\")");
    b.roller_diameter = s.quantity("roller_diameter", dim::length, Bound::positive, std::nullopt);
    b.roller_length = s.quantity("roller_length", dim::length, Bound::positive, std::nullopt);
  }
  const double dw = b.element_diameter();
  const std::string_view element = ball ? "ball" : "roller";
  const std::string_view diameter_key = ball ? "ball_diameter" : "roller_diameter";
  b.pitch_diameter = s.quantity("pitch_diameter", dim::length, Bound::positive, std::nullopt);
  b.radial_clearance = s.quantity("radial_clearance", dim::length, Bound::non_negative, 0.0);
  s.check(b.radial_clearance < dw, "radial_clearance", [&] {
    return fmt::format("clearance larger than a {}: {} clearance with {} {}s", element, mm(b.radial_clearance),
                       mm(dw), element);
  });
  // Ball bearings: clearances are micrometres to a few tens of them; 5 % of the ball catches a unit slip.
  if (ball)
    s.check(b.radial_clearance <= 0.05 * dw, "radial_clearance", [&] {
      return fmt::format("a clearance of {} is more than 5 % of the ball diameter ({}); ball bearing clearances are "
                         "a few to a few tens of micrometres",
                         mm(b.radial_clearance), mm(dw));
    });
  const double inner_race = b.inner_race_diameter(), outer_race = b.outer_race_diameter();
  s.check(inner_race > 0, diameter_key, [&] {
    return fmt::format("{} {}s on a {} pitch diameter (clearance {}) leave no inner race: its diameter would be {}",
                       mm(dw), element, mm(b.pitch_diameter), mm(b.radial_clearance), mm(inner_race));
  });
  b.inner_bore_diameter = s.quantity("inner_bore_diameter", dim::length, Bound::positive, inner_race - dw);
  s.check(b.inner_bore_diameter > 0 && b.inner_bore_diameter < inner_race, "inner_bore_diameter", [&] {
    return fmt::format("inner bore of {}{} must be greater than zero and smaller than the inner race diameter ({})",
                       mm(b.inner_bore_diameter),
                       s.has("inner_bore_diameter") ? "" : fmt::format(" (default: inner race - {} diameter)", element),
                       mm(inner_race));
  });
  b.outer_outside_diameter = s.quantity("outer_outside_diameter", dim::length, Bound::positive, outer_race + dw);
  s.check(b.outer_outside_diameter > outer_race, "outer_outside_diameter", [&] {
    return fmt::format("outside diameter of {} must exceed the outer race diameter ({})", mm(b.outer_outside_diameter),
                       mm(outer_race));
  });
  // Ring width: a roller bearing's defaults to the roller length; a ball bearing's has no natural
  // default (it sets ring masses and the cage width) and is required.
  b.ring_width = s.quantity("ring_width", dim::length, Bound::positive,
                            ball ? std::nullopt : std::optional<double>(b.roller_length));
  if (ball)
    s.check(b.ring_width > dw, "ring_width", [&] {
      return fmt::format("ring width of {} must exceed the ball diameter ({}): the groove would open through the "
                         "ring's faces",
                         mm(b.ring_width), mm(dw));
    });
  if (ball && s.has("ball_material") && s.has("roller_material"))
    s.fail("roller_material", "give the ball material once: ball_material and roller_material name the same thing");
  b.roller_material = material_ref(s, ball && s.has("ball_material") ? "ball_material" : "roller_material", "steel",
                                   scene.materials);
  b.ring_material = material_ref(s, "ring_material", "steel", scene.materials);
}

/// Spindle-mounted cage (seed 000's aerostatic spindle): a spring and a damper per direction.
void parse_cage_support(const Section& s, CageSupport& sup) {
  s.allow(kCageSupportKeys);
  struct Direction {
    std::string_view stiffness, damping;
    Dimension stiffness_dim, damping_dim;
    double *k, *c;
  };
  const Direction directions[] = {
      {"radial_stiffness", "radial_damping", dim::stiffness, dim::damping, &sup.radial_stiffness, &sup.radial_damping},
      {"axial_stiffness", "axial_damping", dim::stiffness, dim::damping, &sup.axial_stiffness, &sup.axial_damping},
      {"tilt_stiffness", "tilt_damping", dim::angular_stiffness, dim::angular_damping, &sup.tilt_stiffness,
       &sup.tilt_damping}};
  for (const Direction& d : directions) {
    if (s.has(d.damping) && !s.has(d.stiffness))
      s.fail(d.damping, fmt::format("a damper needs its spring: give {} too", d.stiffness));
    *d.k = s.quantity(d.stiffness, d.stiffness_dim, Bound::positive, 0.0);
    *d.c = s.quantity(d.damping, d.damping_dim, Bound::non_negative, 0.0);
  }
}

void parse_cage(const Section& s, Scene& scene) {
  s.allow(kCageKeys);
  const BearingGeometry& b = scene.bearing;
  const bool ball = b.is_ball_bearing();
  const bool spatial = scene.scene.model == ModelKind::spatial;
  if (!spatial) s.reject(kSpatialCageKeys, fmt::format("{}: a planar cage moves in x, y and about z", kSpatialOnly));
  if (ball)
    s.reject({"bar_width"}, "bar_width is for roller cages; a ball pocket is set by pocket_clearance and pocket_shape");
  CageSpec& c = scene.cage;
  const double dw = b.element_diameter(), l = b.roller_length;
  const std::string_view element = ball ? "ball" : "roller";
  const std::string g = s.choice("guidance", {"inner_land", "outer_land", "rolling_element"}, std::nullopt, "guidance");
  c.guidance = g == "inner_land" ? CageGuidance::inner_land
             : g == "outer_land" ? CageGuidance::outer_land
                                 : CageGuidance::rolling_element;
  c.pocket_clearance = s.quantity("pocket_clearance", dim::length, Bound::positive, std::nullopt);
  // Ball pockets: typically 1 to 4 % of the ball diameter; a tenth catches unit slips.
  if (ball)
    s.check(c.pocket_clearance < 0.1 * dw, "pocket_clearance", [&] {
      return fmt::format("pocket clearance of {} must be smaller than a tenth of the ball diameter ({})",
                         mm(c.pocket_clearance), mm(0.1 * dw));
    });
  if (c.guidance == CageGuidance::rolling_element) {
    if (s.has("land_clearance"))
      s.fail("land_clearance",
             fmt::format("not allowed with guidance = \"rolling_element\": a {}-guided cage touches no land", element));
    c.land_clearance = 0;
  } else {
    c.land_clearance = s.quantity("land_clearance", dim::length, Bound::positive, std::nullopt);
    s.check(c.land_clearance < 0.5 * dw, "land_clearance", [&] {
      return fmt::format("land clearance of {} must be smaller than half the {} diameter ({})", mm(c.land_clearance),
                         element, mm(0.5 * dw));
    });
  }
  // Defaults: rollers: bars as long as the rollers, half of them on the land; balls: the land is
  // the two ring shoulders beside the groove, ring width - ball diameter in all.
  c.bar_width = ball ? 0.0 : s.quantity("bar_width", dim::length, Bound::positive, l);
  c.land_width = s.quantity("land_width", dim::length, Bound::positive, ball ? b.ring_width - dw : 0.5 * l);
  if (ball)
    s.check(c.land_width <= b.ring_width, "land_width", [&] {
      return fmt::format("land width of {} is wider than the rings ({})", mm(c.land_width), mm(b.ring_width));
    });
  c.material = material_ref(s, "material", "brass", scene.materials);
  c.mass = s.quantity("mass", dim::mass, Bound::positive, 0.0);
  c.inertia = s.quantity("inertia", dim::inertia, Bound::positive, 0.0);
  if (!spatial) return;

  // Pockets: "cylindrical" (drilled radially: machined cages) or "spherical" (pressed or snap cages).
  c.pocket_shape = s.choice("pocket_shape", {"cylindrical", "spherical"}, "cylindrical", "pocket shape") == "spherical"
                       ? PocketShape::spherical
                       : PocketShape::cylindrical;
  c.transverse_inertia = s.quantity("transverse_inertia", dim::inertia, Bound::positive, 0.0);
  // Cage ring: by default d_m -/+ 0.6 D across and 0.8 ring widths wide (a machined cage).
  const double dm = b.pitch_diameter;
  c.inner_diameter = s.quantity("inner_diameter", dim::length, Bound::positive, dm - 0.6 * dw);
  c.outer_diameter = s.quantity("outer_diameter", dim::length, Bound::positive, dm + 0.6 * dw);
  c.width = s.quantity("width", dim::length, Bound::positive, 0.8 * b.ring_width);
  const double inner_land = c.guidance == CageGuidance::inner_land ? 2 * c.land_clearance : 0.0;
  const double outer_land = c.guidance == CageGuidance::outer_land ? 2 * c.land_clearance : 0.0;
  const double lo = b.inner_race_diameter() + inner_land, hi = b.outer_race_diameter() - outer_land;
  s.check(c.inner_diameter > lo && c.inner_diameter < dm, "inner_diameter", [&] {
    return fmt::format("cage bore of {}{} must lie between the inner race diameter{} ({}) and the pitch diameter ({})",
                       mm(c.inner_diameter), s.has("inner_diameter") ? "" : " (default: d_m - 0.6 D)",
                       inner_land > 0 ? " plus twice the land clearance" : "", mm(lo), mm(dm));
  });
  s.check(c.outer_diameter < hi && c.outer_diameter > dm, "outer_diameter", [&] {
    return fmt::format("cage outside diameter of {}{} must lie between the pitch diameter ({}) and the outer race "
                       "diameter{} ({})",
                       mm(c.outer_diameter), s.has("outer_diameter") ? "" : " (default: d_m + 0.6 D)", mm(dm),
                       outer_land > 0 ? " minus twice the land clearance" : "", mm(hi));
  });
  s.check(c.width > 0.5 * dw, "width", [&] {
    return fmt::format("cage width of {} must exceed half the ball diameter ({}): narrower pockets cannot hold the "
                       "balls",
                       mm(c.width), mm(0.5 * dw));
  });
  if (s.has("support")) {
    parse_cage_support(s.sub("support"), c.support);
    if (!c.support.any())
      s.fail("support", "a cage support needs at least one of radial_stiffness, axial_stiffness, tilt_stiffness");
  }
}

const char* tilt_name(RingTilt t) {
  return t == RingTilt::fixed ? "fixed" : t == RingTilt::free ? "free" : "prescribed";
}

/// Misalignment as functions of time; a sanity limit catches "1.42" (rad) meant as mrad.
void parse_misalignment(const Section& ring, RingSpec& r) {
  constexpr double kLimit = 0.05;  // rad
  if (!ring.has("misalignment"))
    ring.fail("misalignment", "required with tilt = \"prescribed\": e.g. misalignment = { x = \"1.42 mrad\" } "
                              "(rotations about the x and y axes)");
  const Section m = ring.sub("misalignment");
  m.allow({"x", "y"});
  if (!m.has("x") && !m.has("y"))
    ring.fail("misalignment", "give x and/or y: rotations about the x and y axes, e.g. x = \"1.42 mrad\"");
  r.misalignment_x = m.time_function("x", dim::angle, 0.0);
  r.misalignment_y = m.time_function("y", dim::angle, 0.0);
  for (const auto& [key, f] : {std::pair<std::string_view, const TimeFunction*>{"x", &r.misalignment_x},
                               std::pair<std::string_view, const TimeFunction*>{"y", &r.misalignment_y}})
    for (const double v : f->values)
      m.check(std::abs(v) <= kLimit, key, [&] {
        return fmt::format("a misalignment of {:g} mrad is beyond the 50 mrad sanity limit (ball bearings run at a "
                           "few mrad; a bare number is in rad: write e.g. \"1.42 mrad\")",
                           v * 1e3);
      });
}

void parse_ring(const Section& s, RingSpec& r, bool spatial) {
  s.allow(kRingKeys);
  if (!spatial)
    s.reject(kSpatialRingKeys, fmt::format("{}: a planar ring moves in x, y and about z", kSpatialOnly));
  const std::string motion = s.choice("motion", {"fixed", "driven", "free"}, std::nullopt, "motion");
  r.motion = motion == "fixed" ? RingMotion::fixed : motion == "driven" ? RingMotion::driven : RingMotion::free;
  if (r.motion == RingMotion::driven) {
    if (!s.has("speed")) s.fail("speed", "required when motion = \"driven\"");
    r.speed = s.time_function("speed", dim::angular_speed, std::nullopt);
  } else if (s.has("speed")) {
    s.fail("speed", fmt::format("speed is only for motion = \"driven\"; this ring is \"{}\"", motion));
  }
  if (r.motion == RingMotion::fixed) {
    s.reject({"translation", "axial"}, "not allowed with motion = \"fixed\": a fixed ring is held in every direction");
    r.translation_free = false;
    r.axial_free = false;
  } else {
    r.translation_free = s.choice("translation", {"free", "fixed"}, "free", "translation") == "free";
    // Spatial driven and free rings move axially unless held (a planar scene has no axial direction).
    r.axial_free = spatial && s.choice("axial", {"free", "fixed"}, "free", "axial") == "free";
  }
  r.tilt = RingTilt::fixed;
  if (spatial) {
    // Tilt: "fixed" (aligned, the default), "free" (integrated), "prescribed" (misalignment).
    const std::string tilt = s.choice("tilt", {"fixed", "free", "prescribed"}, "fixed", "tilt");
    r.tilt = tilt == "fixed" ? RingTilt::fixed : tilt == "free" ? RingTilt::free : RingTilt::prescribed;
    if (r.motion == RingMotion::fixed && r.tilt == RingTilt::free)
      s.fail("tilt", "a ring with motion = \"fixed\" cannot tilt freely; a misaligned housing is tilt = \"prescribed\"");
    if (r.tilt == RingTilt::prescribed)
      parse_misalignment(s, r);
    else
      s.reject({"misalignment"}, fmt::format("only for tilt = \"prescribed\"; this ring's tilt is \"{}\"", tilt));
  }

  const Section load = s.sub("load");
  load.allow(kRingLoadKeys);
  if (!spatial)
    load.reject({"fz", "mx", "my"},
                fmt::format("{}: a planar model has no axial direction and no tilt", kSpatialOnly));
  for (const char* k : {"fx", "fy"})
    if (load.has(k) && !r.translation_free)
      load.fail(k, "this ring's centre is held (motion = \"fixed\" or translation = \"fixed\"): "
                   "a force on it has no effect");
  if (load.has("fz") && !r.axial_free)
    load.fail("fz", "this ring is held axially (motion = \"fixed\" or axial = \"fixed\"): an axial force on it has "
                    "no effect");
  for (const char* k : {"mx", "my"})
    if (load.has(k) && r.tilt != RingTilt::free)
      load.fail(k, fmt::format("a tilting moment needs tilt = \"free\"; this ring's tilt is \"{}\"", tilt_name(r.tilt)));
  if (load.has("mz") && r.motion != RingMotion::free)
    load.fail("mz", fmt::format("a moment is only allowed for motion = \"free\"; this ring is \"{}\"", motion));
  r.load.fx = load.time_function("fx", dim::force, 0.0);
  r.load.fy = load.time_function("fy", dim::force, 0.0);
  r.load.fz = load.time_function("fz", dim::force, 0.0);
  r.load.mx = load.time_function("mx", dim::moment, 0.0);
  r.load.my = load.time_function("my", dim::moment, 0.0);
  r.load.mz = load.time_function("mz", dim::moment, 0.0);

  const Section support = s.sub("support");
  support.allow(kRingSupportKeys);
  if (support.present() && !spatial) {
    support.reject({"axial_stiffness", "axial_damping", "tilt_stiffness", "tilt_damping"},
                   fmt::format("{}: a planar model has no axial direction and no tilt", kSpatialOnly));
    if (!r.translation_free) s.fail("support", "a support is only for a ring with translation = \"free\"");
    r.support.stiffness = support.quantity("stiffness", dim::stiffness, Bound::positive, std::nullopt);
    r.support.damping = support.quantity("damping", dim::damping, Bound::non_negative, 0.0);
  } else if (support.present()) {
    if (r.motion == RingMotion::fixed)
      s.fail("support", "a support is only for a ring that moves (motion = \"driven\" or \"free\")");
    struct Direction {
      std::string_view stiffness, damping;
      bool free;
      std::string held;  ///< why the direction is not free
      Dimension stiffness_dim, damping_dim;
      double *k, *c;
    };
    const Direction directions[] = {
        {"stiffness", "damping", r.translation_free, "translation is \"fixed\"", dim::stiffness, dim::damping,
         &r.support.stiffness, &r.support.damping},
        {"axial_stiffness", "axial_damping", r.axial_free, "axial position is \"fixed\"", dim::stiffness,
         dim::damping, &r.support.axial_stiffness, &r.support.axial_damping},
        {"tilt_stiffness", "tilt_damping", r.tilt == RingTilt::free,
         fmt::format("tilt is \"{}\" (not \"free\")", tilt_name(r.tilt)), dim::angular_stiffness,
         dim::angular_damping, &r.support.tilt_stiffness, &r.support.tilt_damping}};
    for (const Direction& d : directions) {
      if (!d.free)
        support.reject({d.stiffness, d.damping},
                       fmt::format("this ring's {}: a support in that direction has no effect", d.held));
      if (support.has(d.damping) && !support.has(d.stiffness))
        support.fail(d.damping, fmt::format("a damper needs its spring: give {} too", d.stiffness));
      *d.k = support.quantity(d.stiffness, d.stiffness_dim, Bound::positive, 0.0);
      *d.c = support.quantity(d.damping, d.damping_dim, Bound::non_negative, 0.0);
    }
    if (!(r.support.stiffness > 0 || r.support.axial_stiffness > 0 || r.support.tilt_stiffness > 0))
      s.fail("support", "a support needs at least one of stiffness, axial_stiffness, tilt_stiffness");
  }
  r.mass = s.quantity("mass", dim::mass, Bound::positive, 0.0);
  r.inertia = s.quantity("inertia", dim::inertia, Bound::positive, 0.0);
  r.transverse_inertia = s.quantity("transverse_inertia", dim::inertia, Bound::positive, 0.0);
}

void parse_lubricant(const Section& s, Lubricant& lub) {
  if (!s.present()) return;
  s.allow({"name", "viscosity", "pressure_viscosity", "limiting_shear_coefficient", "viscosity_exponent_cap"});
  lub.name = s.string("name", "");
  lub.viscosity = s.quantity("viscosity", dim::viscosity, Bound::positive, std::nullopt);
  lub.pressure_viscosity = s.quantity("pressure_viscosity", dim::inverse_pressure, Bound::non_negative, 0.0);
  // Limiting shear stress / pressure; 0 = none given (limiting_shear traction then refuses to run).
  lub.limiting_shear_coefficient = s.quantity("limiting_shear_coefficient", dim::none, Bound::any, 0.0);
  s.check(lub.limiting_shear_coefficient >= 0 && lub.limiting_shear_coefficient <= 0.5, "limiting_shear_coefficient",
          [&] {
            return fmt::format("must be between 0 and 0.5 (0.02 to 0.1 for mineral oils), found {}",
                               lub.limiting_shear_coefficient);
          });
  // Largest alpha p in the Barus law (contact/point_contact.hpp): default 12.
  lub.viscosity_exponent_cap = s.quantity("viscosity_exponent_cap", dim::none, Bound::positive, 12.0);
  s.check(lub.viscosity_exponent_cap <= 40, "viscosity_exponent_cap", [&] {
    return fmt::format("must be at most 40 (exp(40) times the viscosity is beyond any lubricant), found {}",
                       lub.viscosity_exponent_cap);
  });
}

/// A law name from a registry, for one kind of contact; names registered for other contacts get a hint.
std::string law_choice(const Section& s, std::string_view key, std::span<const LawName> registry, unsigned kind,
                       std::string_view fallback, std::string_view noun) {
  Names known;
  for (const LawName& law : registry)
    if (law.contacts & kind) known.push_back(law.name);
  std::string v = s.string(key, fallback);
  if (std::find(known.begin(), known.end(), v) != known.end()) return v;
  std::string hint;
  for (const LawName& law : registry)
    if (law.name == v) hint = fmt::format(" ('{}' is for {})", v, contact_kind_name(law.contacts));
  s.fail(key, fmt::format("unknown {} '{}'{}; known: {}{}", noun, v, suggestion(v, known), join(known), hint));
}

/// grid = [nx, ny]: traction grid cells over the contact ellipse (rolling x transverse).
void parse_grid(const Section& s, TractionLaw& t) {
  if (!s.has("grid")) return;  // default 5 x 5 (TractionLaw): traction within ~1 % of a fine grid
  const toml::array& g = s.array("grid");
  if (g.size() != 2)
    s.fail("grid", fmt::format("expected [nx, ny], two cell counts (rolling, transverse), found {} values", g.size()));
  int* cells[] = {&t.grid_x, &t.grid_y};
  for (std::size_t i = 0; i < 2; ++i) {
    const toml::node& n = *g.get(i);
    const auto* v = n.as_integer();
    if (!v) s.fail_at(n, "grid", fmt::format("expected an integer, found {} ({})", type_name(n), shown(n)));
    if (v->get() < 1 || v->get() > 50)
      s.fail_at(n, "grid", fmt::format("grid cells must be between 1 and 50, found {}", v->get()));
    *cells[i] = static_cast<int>(v->get());
  }
}

/// One [contact.NAME] section. kind: line_contact (roller_race, roller_cage, cage_land),
/// ball_race_contact or ball_cage_contact. Defaults (all contacts): Hunt-Crossley damping 0.5 s/m
/// (restitution ~0.93 at a 0.2 m/s impact), tanh traction with mu = default_mu and a 0.05 m/s slip
/// scale (70 % of mu at ~1 % slide-to-roll at a few m/s, where EHL traction curves rise).
ContactSpec parse_contact(const Section& s, unsigned kind, double default_mu, double element_diameter,
                          std::string_view element, const Lubricant& lub) {
  s.allow(kContactKeys);
  const bool point = kind != line_contact;
  if (point)
    s.reject({"slices", "crown_drop"},
             "slices and crown_drop are for line contacts (roller bearings); a ball contact is a Hertz point contact");
  if (kind != ball_race_contact)
    s.reject({"grid", "rolling_resistance"},
             kind == line_contact ? "only for ball-race point contacts ([contact.ball_race])"
                                  : "only for [contact.ball_race]: the pocket contact's friction is a traction curve "
                                    "at the contact centre");
  ContactSpec c;
  c.normal.name = law_choice(s, "normal", kNormalLaws, kind, point ? "hertz" : "palmgren", "normal law");
  if (!point) {
    c.normal.slices = static_cast<int>(s.integer("slices", 1, 200, 1));
    c.normal.crown_drop = s.quantity("crown_drop", dim::length, Bound::non_negative, 0.0);
    s.check(c.normal.crown_drop < 0.25 * element_diameter, "crown_drop", [&] {
      return fmt::format("crown drop of {} must be less than a quarter of the {} diameter ({})",
                         mm(c.normal.crown_drop), element, mm(0.25 * element_diameter));
    });
  }
  c.damping.name = law_choice(s, "damping", kDampingLaws, kind, "hunt_crossley", "damping law");
  if (c.damping.name == "none") {
    if (s.has("damping_factor")) s.fail("damping_factor", "has no effect with damping = \"none\"");
    c.damping.factor = 0;
  } else {
    c.damping.factor = s.quantity("damping_factor", dim::inverse_speed, Bound::non_negative, 0.5);
  }
  c.traction.name = law_choice(s, "traction", kTractionLaws, kind, "tanh", "traction law");
  c.traction.slip_velocity_scale = 0.05;
  if (c.traction.name == "none") {
    s.reject({"friction_coefficient", "slip_velocity_scale", "grid"}, "has no effect with traction = \"none\"");
    c.traction.friction_coefficient = 0;
  } else {
    // limiting_shear also uses the curve where there is no film (dry spots, film collapse).
    c.traction.friction_coefficient = s.quantity("friction_coefficient", dim::none, Bound::any, default_mu);
    s.check(c.traction.friction_coefficient >= 0 && c.traction.friction_coefficient <= 1, "friction_coefficient",
            [&] { return fmt::format("must be between 0 and 1, found {}", c.traction.friction_coefficient); });
    c.traction.slip_velocity_scale = s.quantity("slip_velocity_scale", dim::speed, Bound::positive, 0.05);
    if (kind == ball_race_contact) parse_grid(s, c.traction);
  }
  if (c.traction.name == "limiting_shear") {
    if (!(lub.viscosity > 0))
      s.fail("traction", "traction = \"limiting_shear\" needs a lubricant film: set lubricant.viscosity (there is no "
                         "[lubricant] section)");
    if (!(lub.limiting_shear_coefficient > 0))
      s.fail("traction", "traction = \"limiting_shear\" needs lubricant.limiting_shear_coefficient > 0 (limiting shear "
                         "stress = coefficient x pressure; 0.02 to 0.1 for mineral oils)");
  }
  if (kind == ball_race_contact) {
    // EHL rolling resistance: on by default wherever there is a lubricant (there is a film).
    const bool film = lub.viscosity > 0;
    c.traction.rolling_resistance = s.boolean("rolling_resistance", film);
    if (c.traction.rolling_resistance && !film)
      s.fail("rolling_resistance", "EHL rolling resistance needs a film: set lubricant.viscosity, or "
                                   "rolling_resistance = false");
  }
  return c;
}

void parse_solver(const Section& s, SolverSpec& sv) {
  s.allow({"method", "max_order", "rtol", "atol", "linear_solver", "petsc_options", "max_step", "initial_step",
           "max_steps", "jacobian_perturbation"});
  sv.method = s.choice("method", {"bdf", "adams"}, "bdf", "method") == "bdf" ? IntegrationMethod::bdf
                                                                            : IntegrationMethod::adams;
  const long max_order = sv.method == IntegrationMethod::bdf ? 5 : 12;
  sv.max_order = static_cast<int>(s.integer("max_order", 1, max_order, max_order));
  sv.rtol = s.quantity("rtol", dim::none, Bound::any, 1e-6);
  s.check(sv.rtol > 1e-14 && sv.rtol <= 1e-2, "rtol",
          [&] { return fmt::format("must be greater than 1e-14 and at most 1e-2, found {:g}", sv.rtol); });
  const Section atol = s.sub("atol");
  atol.allow({"position", "angle", "velocity", "angular_velocity"});
  sv.atol_position = atol.quantity("position", dim::length, Bound::positive, 0.0);
  sv.atol_angle = atol.quantity("angle", dim::angle, Bound::positive, 0.0);
  sv.atol_velocity = atol.quantity("velocity", dim::speed, Bound::positive, 0.0);
  sv.atol_angular_velocity = atol.quantity("angular_velocity", dim::angular_speed, Bound::positive, 0.0);
  // "bordered" and "dense" are the names of issue 2 (block elimination, SUNDIALS dense), still accepted.
  const std::string ls = s.choice(
      "linear_solver", {"auto", "petsc-bordered", "block-elimination", "sundials-dense", "bordered", "dense"}, "auto",
      "linear solver");
  sv.linear_solver = ls == "petsc-bordered"                         ? LinearSolverKind::petsc_bordered
                     : ls == "block-elimination" || ls == "bordered" ? LinearSolverKind::block_elimination
                     : ls == "sundials-dense" || ls == "dense"       ? LinearSolverKind::sundials_dense
                                                                     : LinearSolverKind::automatic;
  // PETSc options are checked when the solver is built (solver/newton_backends.hpp: a trial setup
  // needs PETSc); here only their place, for the error message.
  sv.petsc_options = s.string("petsc_options", "");
  sv.petsc_options_file = s.file();
  sv.petsc_options_line = s.line("petsc_options");
  sv.max_step = s.quantity("max_step", dim::time, Bound::non_negative, 0.0);
  sv.initial_step = s.quantity("initial_step", dim::time, Bound::non_negative, 0.0);
  sv.max_steps = s.integer("max_steps", 1, LONG_MAX, sv.max_steps);
  sv.jacobian_perturbation = s.quantity("jacobian_perturbation", dim::none, Bound::any, 1e-7);
  s.check(sv.jacobian_perturbation >= 1e-12 && sv.jacobian_perturbation <= 1e-2, "jacobian_perturbation",
          [&] { return fmt::format("must be between 1e-12 and 1e-2, found {:g}", sv.jacobian_perturbation); });
}

// ---- cross-section physical checks ------------------------------------------------------------

void check_physics(const Section& bearing, const Section& outer, const Scene& scene) {
  const BearingGeometry& b = scene.bearing;
  const bool ball = b.is_ball_bearing();
  const std::string_view elements = ball ? "balls" : "rollers";
  const int n = b.rolling_elements;
  const double dw = b.element_diameter(), pocket = scene.cage.pocket_clearance;
  const double chord = b.pitch_diameter * std::sin(kPi / n);
  const double need = dw + pocket;
  bearing.check(chord > need, "rolling_elements", [&] {
    return fmt::format("{} {} of {} with {} pocket clearance need a pitch diameter of at least {} (found {})", n,
                       elements, mm(dw), mm(pocket), mm(need / std::sin(kPi / n)), mm(b.pitch_diameter));
  });
  // Ball cages need bars between the pockets: the pockets may take at most 98 % of the pitch circle.
  if (ball) {
    const double circle = kPi * b.pitch_diameter;
    bearing.check(n * need <= 0.98 * circle, "rolling_elements", [&] {
      return fmt::format("{} balls of {} with {} pocket clearance take {:.1f} % of the pitch circle ({} around), "
                         "more than 98 %: no room for the cage bars",
                         n, mm(dw), mm(pocket), 100.0 * n * need / circle, mm(circle));
    });
  }
  const auto held = [](const RingSpec& r) {
    return r.motion == RingMotion::fixed || !r.translation_free || r.support.stiffness > 0;
  };
  if (!held(scene.inner_ring) && !held(scene.outer_ring))
    outer.fail("motion",
               "both rings float: nothing holds the bearing (make one ring motion = \"fixed\", give it "
               "translation = \"fixed\", or a support)");
  if (scene.scene.model != ModelKind::spatial) return;
  const auto held_axially = [](const RingSpec& r) {
    return r.motion == RingMotion::fixed || !r.axial_free || r.support.axial_stiffness > 0;
  };
  if (!held_axially(scene.inner_ring) && !held_axially(scene.outer_ring))
    outer.fail("axial",
               "both rings are free axially: nothing holds the bearing along its axis (make one ring motion = "
               "\"fixed\", give it axial = \"fixed\", or an axial_stiffness support)");
  const auto held_tilt = [](const RingSpec& r) { return r.tilt != RingTilt::free || r.support.tilt_stiffness > 0; };
  if (!held_tilt(scene.inner_ring) && !held_tilt(scene.outer_ring))
    outer.fail("tilt",
               "both rings tilt freely: nothing holds the bearing's orientation (give one ring tilt = \"fixed\" or "
               "\"prescribed\", or a tilt_stiffness support)");
}

}  // namespace

Scene parse_scene(std::string_view text, const std::string& source_name) {
  toml::table root;
  try {
    root = toml::parse(text, std::string_view(source_name));
  } catch (const toml::parse_error& e) {
    throw SceneError(source_name, std::max(static_cast<int>(e.source().begin.line), 1), "",
                     fmt::format("invalid TOML: {}", e.description()));
  }
  const std::string& file = source_name;
  for (const auto& [k, v] : root) {
    if (std::find(kSections.begin(), kSections.end(), k.str()) != kSections.end()) continue;
    throw SceneError(file, line_of(v), std::string(k.str()),
                     fmt::format("unknown {} '{}'{}{}; allowed sections: {}", v.is_table() ? "section" : "key",
                                 k.str(), v.is_table() ? "" : " outside any section", suggestion(k.str(), kSections),
                                 join(kSections)));
  }

  Scene scene;
  scene.source = source_name;
  scene.text = std::string(text);

  const Section info = top(file, root, "scene", true);
  parse_info(info, scene);
  const bool spatial = scene.scene.model == ModelKind::spatial;
  parse_materials(top(file, root, "materials", false), scene.materials);
  const Section bearing = top(file, root, "bearing", true);
  parse_bearing(bearing, info, scene);
  parse_cage(top(file, root, "cage", true), scene);
  const Section inner = top(file, root, "inner_ring", true);
  const Section outer = top(file, root, "outer_ring", true);
  parse_ring(inner, scene.inner_ring, spatial);
  parse_ring(outer, scene.outer_ring, spatial);
  parse_lubricant(top(file, root, "lubricant", false), scene.lubricant);

  const Section contact = top(file, root, "contact", false);
  contact.allow(kContactSections);
  if (spatial)
    contact.reject(kPlanarContactSections,
                   "roller-race and roller-cage contacts belong to planar roller bearings; a spatial ball bearing's "
                   "are [contact.ball_race] and [contact.ball_cage]");
  else
    contact.reject(kSpatialContactSections,
                   "ball-race and ball-cage contacts belong to spatial ball bearings; a planar roller bearing's are "
                   "[contact.roller_race] and [contact.roller_cage]");
  const double dw = scene.bearing.element_diameter();
  const std::string_view element = scene.bearing.is_ball_bearing() ? "ball" : "roller";
  // Friction defaults: 0.1 for rolling-element contacts (lubricated steel and brass), 0.05 on the land.
  if (spatial) {
    scene.ball_race = parse_contact(contact.sub("ball_race"), ball_race_contact, 0.1, dw, element, scene.lubricant);
    scene.ball_cage = parse_contact(contact.sub("ball_cage"), ball_cage_contact, 0.1, dw, element, scene.lubricant);
  } else {
    scene.roller_race = parse_contact(contact.sub("roller_race"), line_contact, 0.1, dw, element, scene.lubricant);
    scene.roller_cage = parse_contact(contact.sub("roller_cage"), line_contact, 0.1, dw, element, scene.lubricant);
  }
  scene.cage_land = parse_contact(contact.sub("cage_land"), line_contact, 0.05, dw, element, scene.lubricant);

  parse_solver(top(file, root, "solver", false), scene.solver);
  const Section output = top(file, root, "output", false);
  output.allow({"segments"});
  scene.output.segments = output.boolean("segments", true);

  check_physics(bearing, outer, scene);
  return scene;
}

Scene load_scene(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw SceneError(path, 0, "", "cannot read the scene file: it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path, 0, "", fmt::format("cannot read the scene file: {}", std::strerror(errno)));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError(path, 0, "", "cannot read the scene file: read error");
  return parse_scene(text.str(), path);
}

Scene default_scene() { return parse_scene(default_scene_text(), "<built-in default>"); }

}  // namespace raceway::io
