// raceway scene parser: TOML (toml++) -> validated io::Scene in SI units.
//
// Structure: a small `Section` helper reads typed values from one TOML table (with units, bounds,
// defaults and the line of every value for errors); parse_scene() walks the schema section by
// section and finishes with the physical cross-checks. Unknown keys are rejected per section before
// any value is read, so a misspelt key is reported as such and not as a missing one.
#include "io/scene_parser.hpp"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "io/units.hpp"

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
const Names kSections = {"scene",      "bearing",    "materials", "cage",   "inner_ring",
                         "outer_ring", "lubricant",  "contact",   "solver", "output"};
const Names kContactSections = {"roller_race", "roller_cage", "cage_land"};
const Names kContactKeys = {"normal",  "slices",   "crown_drop",           "damping",
                            "damping_factor", "traction", "friction_coefficient", "slip_velocity_scale"};
const Names kRingKeys = {"motion", "speed", "translation", "load", "support", "mass", "inertia"};

// Contact law registries (names the contact/ library implements).
const Names kNormalLaws = {"palmgren"};
const Names kDampingLaws = {"hunt_crossley", "none"};
const Names kTractionLaws = {"tanh", "none"};

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

void parse_info(const Section& s, Scene& scene) {
  s.allow({"name", "model", "end_time", "output_interval", "gravity"});
  SceneInfo& info = scene.scene;
  info.name = s.string("name");
  if (s.choice("model", {"planar", "spatial"}, std::nullopt, "model") == "spatial")
    s.fail("model", "spatial model not available yet in this build");
  info.model = ModelKind::planar;
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

void parse_bearing(const Section& s, Scene& scene) {
  s.allow({"type", "rolling_elements", "roller_diameter", "roller_length", "pitch_diameter", "radial_clearance",
           "inner_bore_diameter", "outer_outside_diameter", "ring_width", "roller_material", "ring_material"});
  BearingGeometry& b = scene.bearing;
  s.choice("type", {"cylindrical_roller"}, std::nullopt, "bearing type");
  b.type = BearingType::cylindrical_roller;
  b.rolling_elements = static_cast<int>(s.integer("rolling_elements", 3, INT_MAX, std::nullopt));
  b.roller_diameter = s.quantity("roller_diameter", dim::length, Bound::positive, std::nullopt);
  b.roller_length = s.quantity("roller_length", dim::length, Bound::positive, std::nullopt);
  b.pitch_diameter = s.quantity("pitch_diameter", dim::length, Bound::positive, std::nullopt);
  b.radial_clearance = s.quantity("radial_clearance", dim::length, Bound::non_negative, 0.0);
  s.check(b.radial_clearance < b.roller_diameter, "radial_clearance", [&] {
    return fmt::format("clearance larger than a roller: {} clearance with {} rollers", mm(b.radial_clearance),
                       mm(b.roller_diameter));
  });
  const double inner_race = b.inner_race_diameter(), outer_race = b.outer_race_diameter();
  s.check(inner_race > 0, "roller_diameter", [&] {
    return fmt::format("{} rollers on a {} pitch diameter (clearance {}) leave no inner race: its diameter would be {}",
                       mm(b.roller_diameter), mm(b.pitch_diameter), mm(b.radial_clearance), mm(inner_race));
  });
  b.inner_bore_diameter =
      s.quantity("inner_bore_diameter", dim::length, Bound::positive, inner_race - b.roller_diameter);
  s.check(b.inner_bore_diameter > 0 && b.inner_bore_diameter < inner_race, "inner_bore_diameter", [&] {
    return fmt::format("inner bore of {}{} must be greater than zero and smaller than the inner race diameter ({})",
                       mm(b.inner_bore_diameter),
                       s.has("inner_bore_diameter") ? "" : " (default: inner race - roller diameter)",
                       mm(inner_race));
  });
  b.outer_outside_diameter =
      s.quantity("outer_outside_diameter", dim::length, Bound::positive, outer_race + b.roller_diameter);
  s.check(b.outer_outside_diameter > outer_race, "outer_outside_diameter", [&] {
    return fmt::format("outside diameter of {} must exceed the outer race diameter ({})", mm(b.outer_outside_diameter),
                       mm(outer_race));
  });
  b.ring_width = s.quantity("ring_width", dim::length, Bound::positive, b.roller_length);
  b.roller_material = material_ref(s, "roller_material", "steel", scene.materials);
  b.ring_material = material_ref(s, "ring_material", "steel", scene.materials);
}

void parse_cage(const Section& s, Scene& scene) {
  s.allow({"guidance", "pocket_clearance", "land_clearance", "bar_width", "land_width", "material", "mass", "inertia"});
  CageSpec& c = scene.cage;
  const double d = scene.bearing.roller_diameter, l = scene.bearing.roller_length;
  const std::string g = s.choice("guidance", {"inner_land", "outer_land", "rolling_element"}, std::nullopt, "guidance");
  c.guidance = g == "inner_land" ? CageGuidance::inner_land
             : g == "outer_land" ? CageGuidance::outer_land
                                 : CageGuidance::rolling_element;
  c.pocket_clearance = s.quantity("pocket_clearance", dim::length, Bound::positive, std::nullopt);
  if (c.guidance == CageGuidance::rolling_element) {
    if (s.has("land_clearance"))
      s.fail("land_clearance", "not allowed with guidance = \"rolling_element\": a roller-guided cage touches no land");
    c.land_clearance = 0;
  } else {
    c.land_clearance = s.quantity("land_clearance", dim::length, Bound::positive, std::nullopt);
    s.check(c.land_clearance < 0.5 * d, "land_clearance", [&] {
      return fmt::format("land clearance of {} must be smaller than half the roller diameter ({})",
                         mm(c.land_clearance), mm(0.5 * d));
    });
  }
  c.bar_width = s.quantity("bar_width", dim::length, Bound::positive, l);
  c.land_width = s.quantity("land_width", dim::length, Bound::positive, 0.5 * l);
  c.material = material_ref(s, "material", "brass", scene.materials);
  c.mass = s.quantity("mass", dim::mass, Bound::positive, 0.0);
  c.inertia = s.quantity("inertia", dim::inertia, Bound::positive, 0.0);
}

void parse_ring(const Section& s, RingSpec& r) {
  s.allow(kRingKeys);
  const std::string motion = s.choice("motion", {"fixed", "driven", "free"}, std::nullopt, "motion");
  r.motion = motion == "fixed" ? RingMotion::fixed : motion == "driven" ? RingMotion::driven : RingMotion::free;
  if (r.motion == RingMotion::driven) {
    if (!s.has("speed")) s.fail("speed", "required when motion = \"driven\"");
    r.speed = s.time_function("speed", dim::angular_speed, std::nullopt);
  } else if (s.has("speed")) {
    s.fail("speed", fmt::format("speed is only for motion = \"driven\"; this ring is \"{}\"", motion));
  }
  if (r.motion == RingMotion::fixed) {
    if (s.has("translation"))
      s.fail("translation", "not allowed with motion = \"fixed\": a fixed ring is held in every direction");
    r.translation_free = false;
  } else {
    r.translation_free = s.choice("translation", {"free", "fixed"}, "free", "translation") == "free";
  }
  const Section load = s.sub("load");
  load.allow({"fx", "fy", "mz"});
  for (const char* k : {"fx", "fy"})
    if (load.has(k) && !r.translation_free)
      load.fail(k, "this ring's centre is held (motion = \"fixed\" or translation = \"fixed\"): "
                   "a force on it has no effect");
  if (load.has("mz") && r.motion != RingMotion::free)
    load.fail("mz", fmt::format("a moment is only allowed for motion = \"free\"; this ring is \"{}\"", motion));
  r.load.fx = load.time_function("fx", dim::force, 0.0);
  r.load.fy = load.time_function("fy", dim::force, 0.0);
  r.load.mz = load.time_function("mz", dim::moment, 0.0);
  const Section support = s.sub("support");
  if (support.present() && !r.translation_free)
    s.fail("support", "a support is only for a ring with translation = \"free\"");
  support.allow({"stiffness", "damping"});
  if (support.present()) {
    r.support.stiffness = support.quantity("stiffness", dim::stiffness, Bound::positive, std::nullopt);
    r.support.damping = support.quantity("damping", dim::damping, Bound::non_negative, 0.0);
  }
  r.mass = s.quantity("mass", dim::mass, Bound::positive, 0.0);
  r.inertia = s.quantity("inertia", dim::inertia, Bound::positive, 0.0);
}

void parse_lubricant(const Section& s, Lubricant& lub) {
  if (!s.present()) return;
  s.allow({"name", "viscosity", "pressure_viscosity"});
  lub.name = s.string("name", "");
  lub.viscosity = s.quantity("viscosity", dim::viscosity, Bound::positive, std::nullopt);
  lub.pressure_viscosity = s.quantity("pressure_viscosity", dim::inverse_pressure, Bound::non_negative, 0.0);
}

ContactSpec parse_contact(const Section& s, double default_mu, double roller_diameter) {
  s.allow(kContactKeys);
  ContactSpec c;
  c.normal.name = s.choice("normal", kNormalLaws, "palmgren", "normal law");
  c.normal.slices = static_cast<int>(s.integer("slices", 1, 200, 1));
  c.normal.crown_drop = s.quantity("crown_drop", dim::length, Bound::non_negative, 0.0);
  s.check(c.normal.crown_drop < 0.25 * roller_diameter, "crown_drop", [&] {
    return fmt::format("crown drop of {} must be less than a quarter of the roller diameter ({})",
                       mm(c.normal.crown_drop), mm(0.25 * roller_diameter));
  });
  c.damping.name = s.choice("damping", kDampingLaws, "hunt_crossley", "damping law");
  if (c.damping.name == "none") {
    if (s.has("damping_factor")) s.fail("damping_factor", "has no effect with damping = \"none\"");
    c.damping.factor = 0;
  } else {
    c.damping.factor = s.quantity("damping_factor", dim::inverse_speed, Bound::non_negative, 0.5);
  }
  c.traction.name = s.choice("traction", kTractionLaws, "tanh", "traction law");
  c.traction.slip_velocity_scale = 0.05;
  if (c.traction.name == "none") {
    for (const char* k : {"friction_coefficient", "slip_velocity_scale"})
      if (s.has(k)) s.fail(k, "has no effect with traction = \"none\"");
    c.traction.friction_coefficient = 0;
  } else {
    c.traction.friction_coefficient = s.quantity("friction_coefficient", dim::none, Bound::any, default_mu);
    s.check(c.traction.friction_coefficient >= 0 && c.traction.friction_coefficient <= 1, "friction_coefficient",
            [&] { return fmt::format("must be between 0 and 1, found {}", c.traction.friction_coefficient); });
    c.traction.slip_velocity_scale = s.quantity("slip_velocity_scale", dim::speed, Bound::positive, 0.05);
  }
  return c;
}

void parse_solver(const Section& s, SolverSpec& sv) {
  s.allow({"method", "max_order", "rtol", "atol", "linear_solver", "max_step", "initial_step", "max_steps",
           "jacobian_perturbation"});
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
  sv.linear_solver = s.choice("linear_solver", {"bordered", "dense"}, "bordered", "linear solver") == "bordered"
                         ? LinearSolverKind::bordered
                         : LinearSolverKind::dense;
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
  const int n = b.rolling_elements;
  const double chord = b.pitch_diameter * std::sin(std::numbers::pi / n);
  const double need = b.roller_diameter + scene.cage.pocket_clearance;
  bearing.check(chord > need, "rolling_elements", [&] {
    return fmt::format("{} rollers of {} with {} pocket clearance need a pitch diameter of at least {} (found {})", n,
                       mm(b.roller_diameter), mm(scene.cage.pocket_clearance),
                       mm(need / std::sin(std::numbers::pi / n)), mm(b.pitch_diameter));
  });
  const auto held = [](const RingSpec& r) {
    return r.motion == RingMotion::fixed || !r.translation_free || r.support.stiffness > 0;
  };
  if (!held(scene.inner_ring) && !held(scene.outer_ring))
    outer.fail("motion",
               "both rings float: nothing holds the bearing (make one ring motion = \"fixed\", give it "
               "translation = \"fixed\", or a support)");
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

  parse_info(top(file, root, "scene", true), scene);
  parse_materials(top(file, root, "materials", false), scene.materials);
  const Section bearing = top(file, root, "bearing", true);
  parse_bearing(bearing, scene);
  parse_cage(top(file, root, "cage", true), scene);
  const Section inner = top(file, root, "inner_ring", true);
  const Section outer = top(file, root, "outer_ring", true);
  parse_ring(inner, scene.inner_ring);
  parse_ring(outer, scene.outer_ring);
  parse_lubricant(top(file, root, "lubricant", false), scene.lubricant);

  const Section contact = top(file, root, "contact", false);
  contact.allow(kContactSections);
  const double d = scene.bearing.roller_diameter;
  scene.roller_race = parse_contact(contact.sub("roller_race"), 0.1, d);
  scene.roller_cage = parse_contact(contact.sub("roller_cage"), 0.1, d);
  scene.cage_land = parse_contact(contact.sub("cage_land"), 0.05, d);

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
