// raceway scene parser: TOML (toml++) -> validated scene::Scene in SI units.
//
// One generic reader walks the schema table (scene_schema.cpp) section by section: it rejects keys
// the section does not know (with a suggestion) and keys of the other kind of bearing or contact
// before reading any value, so a misspelt key is reported as such and not as a missing one; then,
// row by row, it rejects a key that does not apply in this setting, reads the value (type, unit,
// bounds, default) and runs the row's rule. The rules across sections (scene_rules.cpp) close the
// parse.
#include "io/scene/scene_parser.hpp"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <type_traits>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "io/scene/scene_overrides.hpp"
#include "io/scene/catalogue_fill.hpp"
#include "io/scene/scene_rules.hpp"
#include "io/scene/scene_schema.hpp"
#include "io/scene/scene_section.hpp"

namespace raceway::scene {

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

using namespace schema;

const Material kBuiltinMaterials[] = {
    {"steel", 7850.0, 208e9, 0.3},
    {"brass", 8500.0, 100e9, 0.34},
    {"polyamide", 1140.0, 3e9, 0.4},
};

void read_section(std::string_view section, const Section& s, Bind& b);

/// Whether this bearing (and, in [contact.NAME], this contact) takes the row's key.
bool takes(const Row& row, const Bind& b) {
  const unsigned bearing = scene_bearing_bits(b);
  const bool contact_takes_it = b.contact_kind == 0 || row.contacts == 0 || (row.contacts & b.contact_kind);
  return (row.bearings & bearing) && contact_takes_it;
}

/// Why the row's key does not apply to this bearing, contact or setting; nullopt if it does.
std::optional<std::string> not_applicable(const Row& row, const Section& s, const Bind& b) {
  if (!takes(row, b)) return std::string(row.elsewhere);
  return row.when ? row.when(s, b) : std::nullopt;
}

/// The row's default as a number (numbers, integers, booleans, time functions); nullopt: required.
std::optional<double> number_default(const Row& row, const Bind& b) {
  switch (row.def.kind) {
    case Default::Kind::value: return row.def.number;
    case Default::Kind::derived: return row.def.derive(b);
    default: return std::nullopt;
  }
}

std::optional<std::string_view> word_default(const Row& row) {
  if (row.def.kind == Default::Kind::value) return row.def.word;
  return std::nullopt;
}

Names option_names(const Row& row) {
  Names names;
  for (const Option& o : row.options) names.push_back(o.name);
  return names;
}

/// Calls f(*p) with the field's target (nothing for a table without one).
template <class F>
void with_target(const Field& field, F&& f) {
  std::visit(
      [&](auto p) {
        if constexpr (std::is_pointer_v<decltype(p)>) f(*p);
      },
      field);
}

/// Stores a choice: an enum value, or yes (1) / no (0) in a bool.
void store_choice(const Field& field, int value) {
  with_target(field, [&](auto& target) {
    using T = std::remove_reference_t<decltype(target)>;
    if constexpr (std::is_enum_v<T>) target = static_cast<T>(value);
    if constexpr (std::is_same_v<T, bool>) target = value != 0;
  });
}

/// The value of a key that does not apply (`otherwise`), for numbers, yes/no choices and loads.
void store_otherwise(const Field& field, double v) {
  with_target(field, [&](auto& target) {
    using T = std::remove_reference_t<decltype(target)>;
    if constexpr (std::is_same_v<T, double>) target = v;
    if constexpr (std::is_same_v<T, bool>) target = v != 0;
    if constexpr (std::is_same_v<T, TimeFunction>) target = TimeFunction::constant(v);
  });
}

/// A contact law from the registry; an unknown one lists the laws this contact accepts.
void read_law(const Row& row, const Section& s, const Bind& b, const Field& field) {
  const contact::ContactKindBit kind = b.contact_kind;
  const std::string name = s.string(row.key, contact::default_law(row.role, kind).name);
  const contact::LawEntry* law = contact::find_law(row.role, name, kind);
  if (!law) {
    Names known;
    for (const contact::LawEntry& l : contact::registered_laws())
      if (l.role == row.role && (l.contacts & kind)) known.push_back(l.name);
    const contact::LawEntry* elsewhere = contact::find_law(row.role, name);
    const std::string hint =
        elsewhere ? fmt::format(" ('{}' is for {})", name, contact::contacts_description(elsewhere->contacts)) : "";
    s.fail(row.key, fmt::format("unknown {} law '{}'{}; known: {}{}", contact::role_name(row.role), name,
                                suggestion(name, known), contact::known_law_names(row.role, kind), hint));
  }
  with_target(field, [&](auto& target) {
    if constexpr (requires { target.id = law->id; }) target.id = law->id;
  });
}

/// grid = [nx, ny]: traction grid cells over the contact ellipse (rolling x transverse).
void read_grid(const Row& row, const Section& s, TractionLaw& t) {
  if (!s.has(row.key)) return;  // the TractionLaw default
  const toml::array& g = s.array(row.key);
  if (g.size() != 2)
    s.fail(row.key, fmt::format("expected [nx, ny], two cell counts (rolling, transverse), found {} values", g.size()));
  int* cells[] = {&t.grid_x, &t.grid_y};
  for (std::size_t i = 0; i < 2; ++i) {
    const toml::node& n = *g.get(i);
    const auto* v = n.as_integer();
    if (!v) s.fail_at(n, row.key, fmt::format("expected an integer, found {} ({})", type_name(n), shown(n)));
    if (v->get() < 1 || v->get() > 128)  // 128: a spinning contact's traction converged well below 0.1 %
      s.fail_at(n, row.key, fmt::format("grid cells must be between 1 and 128, found {}", v->get()));
    *cells[i] = static_cast<int>(v->get());
  }
}

void read_integer(const Row& row, const Section& s, const Bind& b, const Field& field) {
  const bool is_int = std::holds_alternative<int*>(field);
  const Bounds& bounds = row.bounds;
  const long type_max = is_int ? INT_MAX : LONG_MAX;
  const bool has_hi = bounds.hi_of || std::isfinite(bounds.hi);
  const long hi = bounds.hi_of ? bounds.hi_of(b) : has_hi ? static_cast<long>(bounds.hi) : type_max;
  const long lo = std::isfinite(bounds.lo) ? static_cast<long>(bounds.lo) : LONG_MIN;
  const std::optional<double> fallback = number_default(row, b);
  const long v = s.integer(row.key, lo, hi, has_hi,
                           fallback ? std::optional<long>(static_cast<long>(*fallback)) : std::nullopt);
  if (is_int)
    *std::get<int*>(field) = static_cast<int>(v);
  else
    *std::get<long*>(field) = v;
}

/// A nested table: its keys are the rows of row.sub; a [contact] table binds its contact.
void read_table(const Row& row, const Section& s, const Bind& b, const Field& field) {
  Bind inner = b;
  if (const auto* c = std::get_if<ContactSpec*>(&field)) {
    inner.contact = *c;
    inner.contact_kind = static_cast<contact::ContactKindBit>(row.contacts);
  }
  read_section(row.sub, s.sub(row.key), inner);
}

/// Whether the key's values must lie within the sane range of their quantity: unless the scene
/// names the key (or one of its parts, "inner_ring.speed.time") in [scene] allow_out_of_range.
bool sane_range_checked(const Row& row, const Section& s, const Bind& b) {
  const std::string key = s.dotted(row.key);
  for (const std::string& name : b.scene.scene.allow_out_of_range)
    if (name == key || (name.size() > key.size() && name.starts_with(key) && name[key.size()] == '.')) return false;
  return true;
}

/// An array of dotted keys, each a string.
void read_key_list(const Row& row, const Section& s, std::vector<std::string>& keys) {
  if (!s.has(row.key)) return;
  for (const toml::node& n : s.array(row.key)) {
    const auto* name = n.as_string();
    if (!name)
      s.fail_at(n, row.key, fmt::format("expected a string naming a key (e.g. \"inner_ring.speed\"), found {} ({})",
                                        type_name(n), shown(n)));
    keys.push_back(name->get());
  }
}

void read_value(const Row& row, const Section& s, Bind& b) {
  const Field field = row.field ? row.field(b) : Field();
  switch (row.kind) {
    case ValueKind::number:
      *std::get<double*>(field) = s.quantity(row.key, row.dim, row.bounds, number_default(row, b), row.example,
                                             sane_range_checked(row, s, b));
      break;
    case ValueKind::integer: read_integer(row, s, b, field); break;
    case ValueKind::boolean: *std::get<bool*>(field) = s.boolean(row.key, number_default(row, b).value_or(0) != 0); break;
    case ValueKind::text: *std::get<std::string*>(field) = s.string(row.key, word_default(row)); break;
    case ValueKind::key_list: read_key_list(row, s, *std::get<std::vector<std::string>*>(field)); break;
    case ValueKind::choice: {
      const std::size_t i = s.choice(row.key, option_names(row), word_default(row),
                                     row.noun.empty() ? row.key : row.noun);
      store_choice(field, row.options[i].value);
      break;
    }
    case ValueKind::material:
      *std::get<std::string*>(field) = s.material(row.key, word_default(row), b.scene.materials);
      break;
    case ValueKind::law: read_law(row, s, b, field); break;
    case ValueKind::time_function:
      *std::get<TimeFunction*>(field) = s.time_function(row.key, row.dim, row.bounds, number_default(row, b),
                                                        row.example, sane_range_checked(row, s, b));
      break;
    case ValueKind::cell_grid: read_grid(row, s, *std::get<TractionLaw*>(field)); break;
    case ValueKind::table: read_table(row, s, b, field); break;
    case ValueKind::number_list:
      if (s.has(row.key))
        *std::get<std::vector<double>*>(field) =
            s.quantity_list(row.key, row.dim, row.bounds, row.example, sane_range_checked(row, s, b));
      break;
    case ValueKind::integer_list:
      if (s.has(row.key))
        *std::get<std::vector<int>*>(field) =
            s.integer_list(row.key, static_cast<long>(row.bounds.lo), static_cast<long>(row.bounds.hi));
      break;
  }
}

/// Whether a key that does not apply under the scene's other settings (its row's `when`) is given at
/// the value it then takes (`otherwise`: a factor of 1, a switch off): that changes nothing, so it is
/// accepted, and a --set can take a scene back to the neutral setting (a shipped scene's factor of 3
/// to 1 with its frame). Keys of another kind of bearing or contact are refused whatever their value.
bool given_at_its_neutral_value(const Row& row, const Section& s, Bind& b) {
  if (!row.otherwise || !row.when || !takes(row, b) || !s.has(row.key)) return false;
  if (row.kind != ValueKind::number && row.kind != ValueKind::boolean) return false;
  read_value(row, s, b);
  bool neutral = false;
  with_target(row.field(b), [&](auto& target) {
    using T = std::remove_reference_t<decltype(target)>;
    if constexpr (std::is_same_v<T, double>) neutral = target == *row.otherwise;
    if constexpr (std::is_same_v<T, bool>) neutral = target == (*row.otherwise != 0);
  });
  return neutral;
}

void read_row(const Row& row, const Section& s, Bind& b) {
  if (const std::optional<std::string> why = not_applicable(row, s, b)) {
    if (!given_at_its_neutral_value(row, s, b)) s.reject(row.key, *why);
    if (row.otherwise) store_otherwise(row.field(b), *row.otherwise);
    return;
  }
  if (!s.has(row.key)) {
    if (row.def.kind == Default::Kind::absent) return;
    if (row.def.kind == Default::Kind::required || (row.def.kind == Default::Kind::derived && !row.def.derive(b)))
      (void)s.required(row.key, row.missing);
  }
  read_value(row, s, b);
  if (row.then) row.then(row, s, b);
}

Names keys_of(std::string_view section) {
  Names keys;
  for (const Row& row : rows_of(section)) keys.push_back(row.key);
  return keys;
}

void read_section(std::string_view section, const Section& s, Bind& b) {
  const std::span<const Row> rows = rows_of(section);
  s.allow(keys_of(section));
  // Keys of the other kind of bearing or contact are rejected before any value is read. [bearing]
  // decides the kind: its own rows are checked one by one (read_row), after `type`.
  if (b.bearing_known)
    for (const Row& row : rows)
      if (!takes(row, b)) s.reject(row.key, row.elsewhere);
  for (const Row& row : rows) read_row(row, s, b);
}

/// [materials.NAME] tables on top of the built-in materials.
void read_materials(const Section& s, Bind& b) {
  for (const auto& m : kBuiltinMaterials) b.scene.materials[m.name] = m;
  if (!s.present()) return;
  for (const auto& [k, v] : *s.table()) {
    const std::string name(k.str());
    if (!v.is_table())
      s.fail_at(v, name, fmt::format("expected a table [materials.{}] with {}", name, join(keys_of("materials.*"))));
    Material material{name, 0, 0, 0};
    Bind into = b;
    into.material = &material;
    read_section("materials.*", s.sub(name), into);
    b.scene.materials[name] = material;
  }
}

/// The line of every key and table of the scene text, by dotted path (arrays are not entered).
void record_key_lines(const toml::table& table, const std::string& prefix, Scene& scene) {
  for (const auto& [k, v] : table) {
    const std::string path = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    scene.key_lines[path] = std::max(line_of(v), 1);
    if (const auto* t = v.as_table()) record_key_lines(*t, path, scene);
  }
}

/// Rejects unknown top-level sections and keys outside any section.
void check_top_level(const std::string& file, const toml::table& root) {
  const Names sections(top_sections().begin(), top_sections().end());
  for (const auto& [k, v] : root) {
    if (std::find(sections.begin(), sections.end(), k.str()) != sections.end()) continue;
    throw SceneError(file, line_of(v), std::string(k.str()),
                     fmt::format("unknown {} '{}'{}{}; allowed sections: {}", v.is_table() ? "section" : "key",
                                 k.str(), v.is_table() ? "" : " outside any section", suggestion(k.str(), sections),
                                 join(sections)));
  }
}

/// The schema walk over the parsed (and overridden) TOML table.
Scene parse_table(toml::table& root, const std::string& source_name);
/// The text of a scene file; an unreadable one is a SceneError naming it.
std::string read_scene_text(const std::string& path);

}  // namespace

Scene parse_scene(std::string_view text, const std::string& source_name) { return parse_scene(text, source_name, {}); }

Scene parse_scene(std::string_view text, const std::string& source_name, std::span<const std::string> overrides) {
  toml::table root;
  try {
    root = toml::parse(text, std::string_view(source_name));
  } catch (const toml::parse_error& e) {
    throw SceneError(source_name, std::max(static_cast<int>(e.source().begin.line), 1), "",
                     fmt::format("invalid TOML: {}", e.description()));
  }
  apply_scene_overrides(root, overrides);
  try {
    Scene scene = parse_table(root, source_name);
    scene.text = std::string(text);
    scene.overrides.assign(overrides.begin(), overrides.end());
    return scene;
  } catch (const SceneError& e) {
    throw error_of_override(e, overrides);
  }
}

namespace {

Scene parse_table(toml::table& root, const std::string& source_name) {
  const std::string& file = source_name;
  check_top_level(file, root);

  Scene scene;
  scene.source = source_name;
  record_key_lines(root, "", scene);
  scene.catalogue = catalogue::fill(root, file);  // after the key lines: filled keys are not in the text
  const Section info = top(file, root, "scene", true);
  Bind b{scene, &info};
  read_section("scene", info, b);
  read_materials(top(file, root, "materials", false), b);
  const Section bearing = top(file, root, "bearing", true);
  read_section("bearing", bearing, b);
  b.bearing_known = true;
  const Section cage = top(file, root, "cage", true);
  read_section("cage", cage, b);
  const Section inner = top(file, root, "inner_ring", true);
  const Section outer = top(file, root, "outer_ring", true);
  for (const auto& [section, ring] : {std::pair{&inner, &scene.inner_ring}, std::pair{&outer, &scene.outer_ring}}) {
    Bind on_ring = b;
    on_ring.ring = ring;
    read_section("*_ring", *section, on_ring);
  }
  if (const Section element = top(file, root, "rolling_element", false); element.present())
    read_section("rolling_element", element, b);
  if (const Section housing = top(file, root, "housing", false); housing.present()) {
    read_section("housing", housing, b);
    scene.housing.present = true;
  }
  if (const Section carrier = top(file, root, "carrier", false); carrier.present()) {
    read_section("carrier", carrier, b);
    scene.carrier.present = true;
  }
  if (const Section lubricant = top(file, root, "lubricant", false); lubricant.present())
    read_section("lubricant", lubricant, b);
  if (const Section thermal = top(file, root, "thermal", false); thermal.present()) {
    read_section("thermal", thermal, b);
    scene.thermal.present = true;
  }
  if (const Section life = top(file, root, "life", false); life.present()) read_section("life", life, b);
  read_section("contact", top(file, root, "contact", false), b);
  read_section("solver", top(file, root, "solver", false), b);
  read_section("output", top(file, root, "output", false), b);
  rules::check_scene(bearing, outer, scene);
  rules::check_cage_held(cage, scene);
  return scene;
}

}  // namespace

Scene load_scene(const std::string& path, std::span<const std::string> overrides) {
  if (path.empty()) return parse_scene(default_scene_text(), "<built-in default>", overrides);
  return parse_scene(read_scene_text(path), path, overrides);
}

Scene load_scene(const std::string& path) { return parse_scene(read_scene_text(path), path); }

namespace {

std::string read_scene_text(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw SceneError(path, 0, "", "cannot read the scene file: it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path, 0, "", fmt::format("cannot read the scene file: {}", std::strerror(errno)));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError(path, 0, "", "cannot read the scene file: read error");
  return text.str();
}

}  // namespace

Scene default_scene() { return parse_scene(default_scene_text(), "<built-in default>"); }

std::string keys_with_lines(const Scene& scene, std::span<const std::string_view> keys) {
  const auto& lines = scene.key_lines;
  const auto under = [](std::string_view key, std::string_view prefix) {
    return key.starts_with(prefix) && key.size() > prefix.size() && key[prefix.size()] == '.';
  };
  std::vector<std::pair<int, std::string_view>> found;
  for (auto it = lines.begin(); it != lines.end(); ++it) {
    const std::string_view key = it->first;
    const auto next = std::next(it);
    if (next != lines.end() && under(next->first, key)) continue;  // a table: its keys are listed
    if (std::any_of(keys.begin(), keys.end(), [&](std::string_view k) { return key == k || under(key, k); }))
      found.emplace_back(it->second, key);
  }
  std::sort(found.begin(), found.end());
  std::string out;
  for (const auto& [line, key] : found) out += fmt::format("{}{} (line {})", out.empty() ? "" : ", ", key, line);
  return out;
}

}  // namespace raceway::scene
